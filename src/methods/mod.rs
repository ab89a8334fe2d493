//! Constraint treatments. Each takes the assembled problem
//!
//! ```text
//! minimize ½ uᵀK u − fᵀu   subject to   B u ≤ g
//! ```
//!
//! and returns (u, λ) with λ ≥ 0 the nodal contact forces. The exact methods
//! work on the condensed (dual) problem over the contact candidates:
//!
//! ```text
//! minimize ½ λᵀW λ + qᵀλ over λ ≥ 0,   W = B K⁻¹ Bᵀ,  q = g − B K⁻¹ f,
//! ```
//!
//! i.e. the LCP  λ ≥ 0,  w = Wλ + q ≥ 0,  λᵀw = 0  (w is the gap after deformation).

pub mod active_set;
pub mod condensed;
pub mod interior_point;

use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::proto::{MethodName, SolverSettings};
use faer::sparse::SparseColMat;

pub struct Problem<'a> {
    /// Lower triangle of K on the free DOFs.
    pub k: &'a SparseColMat<usize, f64>,
    pub f: &'a [f64],
    pub cons: &'a ConstraintSet,
    pub settings: &'a SolverSettings,
}

/// Result of the LCP stage.
pub struct LcpResult {
    pub lambda: Vec<f64>,
    pub iterations: usize,
    pub converged: bool,
}

pub struct Solution {
    pub u: Vec<f64>,
    pub lambda: Vec<f64>,
    pub iterations: usize,
    pub converged: bool,
    /// Name of the method that ran.
    pub method: &'static str,
    pub t_factorization: f64,
    pub t_condensation: f64,
    pub t_contact: f64,
}

/// A solver of the condensed LCP (W, q).
pub type LcpSolver = fn(&faer::Mat<f64>, &[f64], &SolverSettings) -> LcpResult;

/// Runs the requested method (`auto` → condensed active set, the fastest exact
/// method measured so far).
pub fn solve(problem: &Problem, method: MethodName) -> Result<Solution, CoreError> {
    let (name, lcp): (&'static str, LcpSolver) = match method {
        MethodName::Auto | MethodName::ActiveSet => ("active_set", active_set::solve_lcp),
        MethodName::InteriorPoint => ("interior_point", interior_point::solve_lcp),
    };
    condensed::solve_condensed(problem, name, lcp)
}
