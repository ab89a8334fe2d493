//! Contact constraints: the rows B u ≤ g on the free DOFs, and the rigid
//! motions (punches, bodies held only by contact) that enter them.
//!
//! Layers, each using only those above it (a test checks there is no cycle):
//!
//! - `gap`: geometry of rigid obstacles (closest point, signed distance);
//! - `rows`: from what a surface point sees (`Seen`) to nodal or mortar rows;
//! - `constraints`: the rows on the free DOFs (`Candidate`, `ConstraintSet`);
//! - `targets`: one file per kind of contact target, and `build`;
//! - `compliance`: the foundations' compliance, which joins the condensed operator;
//! - `friction_law`: the bound of the tangential force (Coulomb's μ λ);
//! - `friction`: the tangential rows of frictional pairs, beside the normal ones;
//! - `free_motions` and `fichera`: rigid motions left to contact and the
//!   compatibility of their loads.

pub mod compliance;
pub mod constraints;
pub mod fichera;
pub mod free_motions;
pub mod friction;
pub mod friction_law;
pub mod gap;
pub mod rows;
pub mod targets;

pub use constraints::{Candidate, ConstraintSet};
pub use rows::Term;
pub use targets::build;
