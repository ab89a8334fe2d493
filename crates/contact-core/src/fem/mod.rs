//! Finite elements of 2D linear elasticity: materials, element kernels, assembly.

pub mod assembly;
pub mod axisymmetric;
pub mod element;
pub mod loads;
pub mod material;
pub mod rigid_modes;

pub use assembly::DofMap;
pub use loads::{assemble, Assembled};
