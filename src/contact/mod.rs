//! Contact constraints: candidate rows B u ≤ g on the free DOFs.

pub mod candidates;
pub mod gap;
pub mod rigid;

pub use candidates::{build, Candidate, ConstraintSet};
