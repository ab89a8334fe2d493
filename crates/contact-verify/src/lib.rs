//! # contact-verify — what the contact solver is checked against
//!
//! Analytic references (`reference`: Hertz), overkill references of the
//! convergence scenes (`overkill`, tables in `data/`), typed request builders (`build`),
//! the time-against-error benchmark (`bench`; its 3D rows `solid_bench`),
//! convergence under refinement (`convergence`; with friction: `friction`,
//! the Cattaneo–Mindlin stick zone), the error estimate against
//! the true error (`effectivity`), time to a tolerance with and
//! without refinement (`tolerance`), the 3D Hertz ball the solid's error
//! bar is checked against (`solid_ball`) and the numerical stress suite
//! (`stability`). Used by the tests, the CI smoke run and `contact-bench`.

pub mod bench;
pub mod build;
pub mod convergence;
pub mod effectivity;
pub mod friction;
pub mod overkill;
pub mod reference;
pub mod run;
pub mod solid_ball;
pub mod solid_bench;
pub mod stability;
pub mod tolerance;
