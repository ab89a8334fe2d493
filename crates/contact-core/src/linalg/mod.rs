//! Linear algebra kernels: sparse Cholesky with a trailing Schur block, small dense kernels.

pub mod cholesky;
pub mod dense;
pub mod sparse;

pub use cholesky::{Cholesky, LinalgError};
