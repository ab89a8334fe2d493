//! Compatibility of the loads on load-controlled punches (Fichera's condition).
//!
//! A punch whose motion β_F is free is held only by contact: a solution exists
//! only if some non-negative contact force on the candidates balances its loads,
//! i.e. the LP {λ ≥ 0 : C_Fᵀλ = −P_F} is feasible. When it is not, each load
//! component's admissible range (with the other components as given) tells the
//! user what to change: [min, max] of −(C_Fᵀλ)_j over λ ≥ 0 meeting the others.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT};
use faer::Mat;

/// Outcome of one LP over λ ≥ 0 with C_Fᵀλ = rhs on the rows in `keep`.
enum Lp {
    Optimal(f64),
    Infeasible,
    Unbounded,
    /// Clarabel could not decide (set-up failure, iteration cap, numerical
    /// trouble): nothing is known of feasibility.
    Failed,
}

/// Clarabel run to a gap of 1e-13: the ranges are reported to the user, and
/// its default gap tolerance (1e-8, and 5e-5 when it settles for "almost
/// solved") printed 9.999926 for a moment bound of exactly 10.
fn tight_settings() -> clarabel::solver::DefaultSettings<f64> {
    DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-13)
        .tol_gap_rel(1e-13)
        .tol_feas(1e-12)
        .tol_ktratio(1e-10)
        .max_iter(400)
        .build()
        .expect("static settings")
}

fn lp(c: &Mat<f64>, rhs: &[f64], keep: &[usize], objective: Option<(usize, f64)>) -> Lp {
    let m = c.nrows();
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for (r, &j) in keep.iter().enumerate() {
        for i in 0..m {
            if c[(i, j)] != 0.0 {
                rows.push(r);
                cols.push(i);
                vals.push(c[(i, j)]);
            }
        }
    }
    let ne = keep.len();
    for i in 0..m {
        rows.push(ne + i);
        cols.push(i);
        vals.push(-1.0);
    }
    let a = CscMatrix::new_from_triplets(ne + m, m, rows, cols, vals);
    let mut b: Vec<f64> = keep.iter().map(|&j| rhs[j]).collect();
    b.extend(std::iter::repeat_n(0.0, m));
    let q: Vec<f64> = match objective {
        Some((j, sign)) => (0..m).map(|i| sign * c[(i, j)]).collect(),
        None => vec![0.0; m],
    };
    let p = CscMatrix::zeros((m, m));
    let settings = tight_settings();
    let cones = [ZeroConeT(ne), NonnegativeConeT(m)];
    let Ok(mut solver) = DefaultSolver::new(&p, &q, &a, &b, &cones, settings) else {
        return Lp::Failed;
    };
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Lp::Optimal(solver.solution.obj_val),
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => Lp::Infeasible,
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => Lp::Unbounded,
        _ => Lp::Failed,
    }
}

/// Ok if a non-negative λ with C_Fᵀλ = rhs exists; otherwise, per component
/// whose value cannot be met with the others as given, its admissible range of
/// loads (−(C_Fᵀλ)_j; None = unbounded on that side).
/// A free load component that cannot be met, with its admissible range
/// (None: unbounded on that side), both in the units of the load.
#[derive(Debug, Clone, Copy)]
pub struct LoadRange {
    pub component: usize,
    pub min: Option<f64>,
    pub max: Option<f64>,
}

/// An LP that Clarabel cannot decide does not refuse the request: the loads
/// are then left to the contact solve, whose certificate judges the answer.
pub fn check(c: &Mat<f64>, rhs: &[f64]) -> Result<(), Vec<LoadRange>> {
    let k = c.ncols();
    let all: Vec<usize> = (0..k).collect();
    if !matches!(lp(c, rhs, &all, None), Lp::Infeasible) {
        return Ok(());
    }
    let mut bad = Vec::new();
    for j in 0..k {
        let others: Vec<usize> = (0..k).filter(|&t| t != j).collect();
        // (C_Fᵀλ)_j ranges over [lo, hi]; the load is its negative.
        let lo = match lp(c, rhs, &others, Some((j, 1.0))) {
            Lp::Optimal(v) => Some(v),
            // An undecided bound is reported as open rather than guessed.
            Lp::Unbounded | Lp::Failed => None,
            Lp::Infeasible => continue, // the others alone are infeasible: not this component's fault
        };
        let hi = match lp(c, rhs, &others, Some((j, -1.0))) {
            Lp::Optimal(v) => Some(-v),
            _ => None,
        };
        let inside = lo.is_none_or(|l| rhs[j] >= l - 1e-12 * l.abs().max(1e-300))
            && hi.is_none_or(|h| rhs[j] <= h + 1e-12 * h.abs().max(1e-300));
        if !inside {
            bad.push(LoadRange {
                component: j,
                min: hi.map(|h| -h),
                max: lo.map(|l| -l),
            });
        }
    }
    if bad.is_empty() {
        // Jointly infeasible although each alone fits: report every component with its range.
        bad = (0..k)
            .map(|j| LoadRange {
                component: j,
                min: None,
                max: None,
            })
            .collect();
    }
    Err(bad)
}

/// Fraction of the largest possible opening below which a motion is taken
/// to close as much as it opens: the LP runs to 1e-12, and a real escape
/// opens its candidates by O(1) of the normalized motion.
const ESCAPE: f64 = 1e-7;

/// A free motion that moves every candidate away from its target (or along
/// it) while the loads do no work against it, if there is one: then nothing
/// decides where the bodies rest, and contact, which only pushes, carries
/// nothing. Fichera's condition holds (λ = 0 balances zero work), but the
/// solution is not determined: the commonest cause is a forgotten support.
///
/// The rows read B u − C β ≤ g, so a motion β opens row i by (Cβ)_i and the
/// loads' work on it is −rhsᵀβ (rhs = −VᵀP). The LP is
/// max 1ᵀCβ s.t. Cβ ≥ 0, rhsᵀβ ≤ 0 (the loads do not resist it),
/// 1ᵀCβ ≤ 1, β free; a value near 1 is an escape.
pub fn escape(c: &Mat<f64>, rhs: &[f64]) -> Option<Vec<f64>> {
    let (m, k) = (c.nrows(), c.ncols());
    if k == 0 || m == 0 {
        return None;
    }
    let big = rhs.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    // −Cβ ≤ 0 (rows 0..m), rhsᵀβ ≤ 0 (row m), 1ᵀCβ ≤ 1 (row m + 1).
    for j in 0..k {
        let mut sum = 0.0;
        for i in 0..m {
            let v = c[(i, j)];
            if v != 0.0 {
                rows.push(i);
                cols.push(j);
                vals.push(-v);
                sum += v;
            }
        }
        // Load components at round-off of the largest are no load at all.
        // The row is homogeneous, so it is scaled to the largest load: as
        // given, a load of 1e-10 of E (P = 500 N on a roller in mm with E
        // in Pa) put coefficients of 1e-10 in it, inside the LP's
        // feasibility tolerance, and the escape it forbids was found: the
        // roller was told `no_support`.
        if rhs[j].abs() > 1e-12 * big {
            rows.push(m);
            cols.push(j);
            vals.push(rhs[j] / big);
        }
        if sum != 0.0 {
            rows.push(m + 1);
            cols.push(j);
            vals.push(sum);
        }
    }
    let a = CscMatrix::new_from_triplets(m + 2, k, rows, cols, vals);
    let mut b = vec![0.0; m + 2];
    b[m + 1] = 1.0;
    let q: Vec<f64> = (0..k).map(|j| -(0..m).map(|i| c[(i, j)]).sum::<f64>()).collect();
    let p = CscMatrix::zeros((k, k));
    let mut solver = DefaultSolver::new(&p, &q, &a, &b, &[NonnegativeConeT(m + 2)], tight_settings()).ok()?;
    solver.solve();
    // Undecided: leave it to the solve, whose certificate judges the answer.
    if !matches!(
        solver.solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    ) {
        return None;
    }
    (-solver.solution.obj_val > ESCAPE).then(|| solver.solution.x.clone())
}
