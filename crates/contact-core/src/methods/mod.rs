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
//! Load-controlled punch motions β add −Cβ to the rows and their equilibrium
//! Cᵀλ = −P as equalities: a mixed LCP, w = Wλ + q + Cβ (`FreeBlock`).
//! Coulomb friction adds tangential rows and is solved per load step by
//! `friction`. `settings.formulation = full` runs the exact methods on the uncondensed system
//! instead (`full`), for comparison.

pub mod active_set;
pub mod barrier;
pub mod condensed;
pub mod friction;
pub mod full;
pub mod interior_point;
pub mod penalty;

use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::outcome::MethodRan;
use crate::scene::{Method, Settings};

pub struct Problem<'a> {
    /// K (factored, with the condensed operator W), possibly from the cache.
    pub op: &'a crate::cache::Prepared,
    pub f: &'a [f64],
    pub cons: &'a ConstraintSet,
    pub settings: &'a Settings,
    /// Free rigid motions (punches, bodies held by contact): rows −C β and
    /// their equilibrium Cᵀλ = rhs.
    pub punch: Option<FreeBlock>,
    /// Compliance added to W (foundations), m × m.
    pub compliance: Option<&'a faer::Mat<f64>>,
}

/// A solver of the mixed LCP (W, q) with the punch block bound in: returns (λ, β).
pub type MixedSolver<'a> = &'a dyn Fn(&faer::Mat<f64>, &[f64]) -> (LcpResult, Vec<f64>);

/// The free rigid motions β of a solve (load-controlled punches, bodies
/// held only by contact), one block of the mixed problem: the gaps gain
/// C_N β (w = W λ + q + C_N β) and, with friction, the slips −C_T β, and the
/// motions bring their equilibrium C_Nᵀλ + C_Tᵀτ = rhs (−P, P their loads).
pub struct FreeBlock {
    /// C_N: candidates × motions.
    pub cn: faer::Mat<f64>,
    /// C_T: tangential rows × motions (no rows without friction).
    pub ct: faer::Mat<f64>,
    pub rhs: Vec<f64>,
    /// The bodies held only by contact whose rigid modes are among the
    /// motions: with friction their points start closed (they rest on their
    /// contacts at the start).
    pub bodies: Vec<usize>,
}

impl FreeBlock {
    /// The frictionless block of the free motions contact determines (the
    /// combinations γ of `FreeMotions::v`).
    pub fn frictionless(fm: &crate::contact::free_motions::FreeMotions) -> Self {
        Self {
            cn: fm.c.clone(),
            ct: faer::Mat::zeros(0, fm.c.ncols()),
            rhs: fm.rhs.clone(),
            bodies: Vec::new(),
        }
    }

    /// The number of free motions.
    pub fn len(&self) -> usize {
        self.rhs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rhs.is_empty()
    }
}

/// Result of the LCP stage.
pub struct LcpResult {
    pub lambda: Vec<f64>,
    pub iterations: usize,
    pub converged: bool,
    /// Not converged because the method broke down numerically (Clarabel's
    /// numerical error, insufficient progress, or a certificate of
    /// infeasibility, which an LCP with W positive definite cannot have), not
    /// because it ran out of iterations.
    pub breakdown: bool,
}

impl LcpResult {
    /// λ = 0, converged at once: the answer of an LCP with q ≥ 0 (nothing
    /// pressed, or no rows at all).
    pub fn at_rest(m: usize) -> Self {
        Self {
            lambda: vec![0.0; m],
            iterations: 0,
            converged: true,
            breakdown: false,
        }
    }

    /// The solver broke down before an answer (λ = 0, not converged).
    pub fn broke_down(m: usize) -> Self {
        Self {
            lambda: vec![0.0; m],
            iterations: 0,
            converged: false,
            breakdown: true,
        }
    }
}

pub struct Solution {
    pub u: Vec<f64>,
    pub lambda: Vec<f64>,
    /// Free punch motions β_F (empty without load-controlled punches).
    pub beta: Vec<f64>,
    /// Candidates in contact: λ_i > 0 and λ_i W_ii > gap_i (the force's own
    /// displacement exceeds what is left of the gap). For exact methods this is
    /// λ_i > 0; for the penalty, penetration; for the barrier, gap_i² < ζ w_i W_ii.
    pub in_contact: Vec<bool>,
    pub iterations: usize,
    pub converged: bool,
    /// Not converged on a numerical breakdown (`LcpResult::breakdown`).
    pub breakdown: bool,
    /// Name of the method that ran.
    pub method: MethodRan,
    /// Whether the method solves the exact contact conditions (penalty does not:
    /// its penetration and complementarity gap are inherent, not a failure).
    pub exact: bool,
    /// LCP and the two solves.
    pub t_contact: f64,
    /// Iterative-refinement steps the solves with K needed.
    pub refinements: usize,
    /// Why another method ran instead of the first choice of `auto`.
    pub fallback: Option<crate::outcome::Note>,
}

/// Runs the requested method (`auto` → condensed active set, the fastest exact
/// method measured so far; see `contact-bench`).
pub fn solve(problem: &Problem, method: Method) -> Result<Solution, CoreError> {
    let first = solve_with(problem, method)?;
    if method != Method::Auto || first.converged || crate::cancel::expired() {
        return Ok(first);
    }
    // `auto` must not fail where another exact method succeeds: the active set
    // can cycle on a mixed LCP whose free motions are weakly resisted (a
    // half-disk held sideways only by contact with body-normal rows: 200
    // iterations, max_iterations; interior point: 15).
    let mut second = solve_with(problem, Method::InteriorPoint)?;
    if !second.converged {
        return Ok(first);
    }
    second.fallback = Some(crate::outcome::Note::new(
        crate::outcome::NoteKind::MethodFallback,
        format!(
            "auto: the active set did not converge ({} iterations); the interior point method ran instead",
            first.iterations
        ),
    ));
    second.iterations += first.iterations;
    second.t_contact += first.t_contact;
    Ok(second)
}

fn solve_with(problem: &Problem, method: Method) -> Result<Solution, CoreError> {
    let weights: Vec<f64> = problem.cons.candidates.iter().map(|c| c.weight).collect();
    let d = penalty::springs(&weights, problem.settings.penalty);
    let run = |name: MethodRan, exact: bool, lcp: &dyn Fn(&faer::Mat<f64>, &[f64]) -> LcpResult| {
        condensed::solve_condensed(problem, name, exact, lcp)
    };
    let s = problem.settings;
    if let Some(pb) = &problem.punch {
        let (c, r) = (&pb.cn, pb.rhs.as_slice());
        let run = |name: MethodRan, exact: bool, mlcp: MixedSolver| {
            condensed::solve_condensed_mixed(problem, pb, name, exact, mlcp)
        };
        return match method {
            Method::Auto | Method::ActiveSet => run(MethodRan::ActiveSet, true, &|w, q| {
                active_set::solve_mlcp(w, q, c, r, s)
            }),
            Method::InteriorPoint => run(MethodRan::InteriorPoint, true, &|w, q| {
                interior_point::solve_mlcp(w, q, c, r, s)
            }),
            Method::Penalty => run(MethodRan::Penalty, false, &|w, q| {
                penalty::solve_penalty_mixed(w, q, c, r, &d, s)
            }),
            Method::AugmentedLagrangian => run(MethodRan::AugmentedLagrangian, true, &|w, q| {
                penalty::solve_augmented_lagrangian_mixed(w, q, c, r, &d, s)
            }),
            Method::Barrier => run(MethodRan::Barrier, false, &|w, q| {
                barrier::solve_barrier_mixed(w, q, c, r, &weights, problem.settings.barrier, s)
            }),
        };
    }
    match method {
        Method::Auto | Method::ActiveSet => run(MethodRan::ActiveSet, true, &|w, q| active_set::solve_lcp(w, q, s)),
        Method::InteriorPoint => run(MethodRan::InteriorPoint, true, &|w, q| {
            interior_point::solve_lcp(w, q, s)
        }),
        Method::Penalty => run(MethodRan::Penalty, false, &|w, q| penalty::solve_penalty(w, q, &d, s)),
        Method::Barrier => run(MethodRan::Barrier, false, &|w, q| {
            barrier::solve_barrier(w, q, &weights, problem.settings.barrier, s)
        }),
        Method::AugmentedLagrangian => run(MethodRan::AugmentedLagrangian, true, &|w, q| {
            penalty::solve_augmented_lagrangian(w, q, &d, s)
        }),
    }
}
