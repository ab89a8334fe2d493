//! Contact constraints: candidate rows B u ≤ g on the free DOFs, and the rigid
//! motions (punches, bodies held only by contact) that enter them.

pub mod candidates;
pub mod foundation;
pub mod free_motions;
pub mod gap;
pub mod rigid;
pub mod rows;
pub mod two_body;

pub use candidates::{build, Candidate, ConstraintSet, Term};
