//! Finite elements of linear elasticity: the constitutive seam (`constitutive`),
//! the element seam (`reference`), the one stiffness kernel over both
//! (`kernel`), and the 2D assembly, loads and post-processing kernels.

pub mod assembly;
pub mod axisymmetric;
pub mod constitutive;
pub mod coupling;
pub mod element;
pub mod kernel;
pub mod loads;
pub mod pattern;
pub mod reference;
pub mod rigid_modes;

pub use assembly::DofMap;
pub use loads::{assemble, Assembled};
