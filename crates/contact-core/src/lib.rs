//! # contact — 2D elastic contact, frictionless or with Coulomb friction
//!
//! Every scene is one quadratic program after discretization:
//!
//! ```text
//! minimize  ½ uᵀK u − fᵀu     subject to   B u ≤ g
//! ```
//!
//! K: linear elastic stiffness (T3/T6, plane strain or stress) on the free DOFs,
//! B: one row per contact candidate (the outward normal at a boundary node),
//! g: the initial gap along that normal. The multipliers λ ≥ 0 are the nodal
//! contact forces; pressure = λ / tributary length.
//!
//! The default (exact) path condenses onto the candidates with one sparse
//! Cholesky factorization (`linalg::cholesky`) and solves the small LCP there
//! (`methods`). [`solve`] runs the stages in order (`solve.rs` reads as the
//! algorithm); `scene::Scene::try_new` is the boundary where a wire request
//! becomes a validated, nondimensional scene, and `solution::report::Report`
//! is what comes out. No I/O, no serialization: the `contact` crate turns
//! bytes into requests and reports into replies.

pub mod adapt;
pub mod admit;
pub mod cache;
pub mod cancel;
pub mod contact;
pub mod error;
pub mod fem;
pub mod linalg;
pub mod mesh;
pub mod mesh3d;
pub mod meshing;
pub mod methods;
pub mod model;
pub mod observer;
pub mod outcome;
pub mod progress;
pub mod scene;
pub mod solid;
pub mod solution;
pub mod solve;

pub use error::CoreError;
pub use scene::{Limits, Scene};
pub use solve::{solve, solve_solid, solve_solid_once};
