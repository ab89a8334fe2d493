//! Interior point (Clarabel) on the condensed QP
//!
//! ```text
//! minimize ½ λ̂ᵀW λ̂ + (q/σ)ᵀλ̂   subject to  λ̂ ≥ 0,   λ = σ λ̂,
//! ```
//!
//! with σ = ‖q‖∞ / max diag W so that λ̂ = O(1) whatever the load level.
//! Clarabel's status maps onto ours: anything but (Almost)Solved is not converged.
//!
//! An interior point stops at a small but positive barrier parameter μ, which
//! leaves λ_i ≈ μ / w_i > 0 on open candidates next to the contact edge. As is
//! usual for IPMs (crossover / polishing), the converged iterate's active set
//! A = {i : λ_i W_ii > w_i} is then solved exactly, W_AA λ_A = −q_A; the polished
//! point is kept only if it satisfies the KKT conditions (λ_A ≥ 0, w ≥ 0 off A),
//! otherwise the active-set iteration finishes from that set (a crossover).

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus};
use faer::Mat;

use super::LcpResult;
use crate::linalg::dense::{matvec, solve_principal};
use crate::scene::Settings;

pub fn solve_lcp(w: &Mat<f64>, q: &[f64], s: &Settings) -> LcpResult {
    let m = q.len();
    let dmax = (0..m).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
    let qmax = q.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    // No rows, or q = 0: λ = 0 (and no scale to normalize by).
    if qmax == 0.0 {
        return LcpResult::at_rest(m);
    }
    let sigma = qmax / dmax;
    let p = upper_triangle(w);
    let qs: Vec<f64> = q.iter().map(|v| v / sigma).collect();
    let a = CscMatrix::new(m, m, (0..=m).collect(), (0..m).collect(), vec![-1.0; m]);
    let b = vec![0.0; m];
    let mut settings = clarabel_settings(s);
    settings.tol_ktratio = 1e-8;
    let cones = [NonnegativeConeT(m)];
    let Ok(mut solver) = DefaultSolver::new(&p, &qs, &a, &b, &cones, settings) else {
        return LcpResult::broke_down(m);
    };
    solver.solve();
    let sol = &solver.solution;
    let converged = matches!(sol.status, SolverStatus::Solved | SolverStatus::AlmostSolved);
    let lambda: Vec<f64> = sol.x.iter().map(|v| (v * sigma).max(0.0)).collect();
    let iterations = sol.iterations as usize;
    if converged {
        if let Some(polished) = polish(w, q, &lambda) {
            return LcpResult {
                lambda: polished,
                iterations: iterations + 1,
                converged,
                breakdown: false,
            };
        }
        // The estimate missed a borderline candidate: let the active-set
        // iteration finish from the IPM's active set (it needs a step or two).
        let start: Vec<bool> = active_estimate(w, q, &lambda);
        let mut r = super::active_set::solve_lcp_from(w, q, s, start);
        r.iterations += iterations;
        return r;
    }
    LcpResult {
        lambda,
        iterations,
        converged,
        breakdown: breakdown(sol.status),
    }
}

/// Whether Clarabel stopped on a numerical breakdown rather than its
/// iteration or time cap (see `LcpResult::breakdown`).
fn breakdown(status: SolverStatus) -> bool {
    !matches!(
        status,
        SolverStatus::Solved | SolverStatus::AlmostSolved | SolverStatus::MaxIterations | SolverStatus::MaxTime
    )
}

/// Candidates whose force outweighs their gap (in the units of W's diagonal).
fn active_estimate(w: &Mat<f64>, q: &[f64], lambda: &[f64]) -> Vec<bool> {
    let gap: Vec<f64> = matvec(w, lambda).iter().zip(q).map(|(a, b)| a + b).collect();
    (0..q.len()).map(|i| lambda[i] * w[(i, i)] > gap[i]).collect()
}

/// Exact solve on the IPM's active set; None unless the result is KKT-feasible.
fn polish(w: &Mat<f64>, q: &[f64], lambda: &[f64]) -> Option<Vec<f64>> {
    let m = q.len();
    let est = active_estimate(w, q, lambda);
    let idx: Vec<usize> = (0..m).filter(|&i| est[i]).collect();
    let rhs: Vec<f64> = idx.iter().map(|&i| -q[i]).collect();
    let la = solve_principal(w, &idx, &rhs)?;
    let mut out = vec![0.0; m];
    for (k, &i) in idx.iter().enumerate() {
        out[i] = la[k];
    }
    let gap: Vec<f64> = matvec(w, &out).iter().zip(q).map(|(a, b)| a + b).collect();
    let qmax = q.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let feasible = la.iter().all(|&l| l >= 0.0) && (0..m).all(|i| out[i] > 0.0 || gap[i] >= -1e-12 * qmax);
    feasible.then_some(out)
}

/// The mixed problem with load-controlled punches: min ½λᵀWλ + qᵀλ over λ ≥ 0
/// with C_Fᵀλ = r (Clarabel's zero cone; its multipliers are the punch motions
/// β), then the active-set iteration from Clarabel's active set.
pub fn solve_mlcp(w: &Mat<f64>, q: &[f64], c: &Mat<f64>, r: &[f64], s: &Settings) -> (LcpResult, Vec<f64>) {
    use clarabel::solver::ZeroConeT;
    let (m, k) = (q.len(), c.ncols());
    let dmax = (0..m).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
    let scale = q
        .iter()
        .chain(r)
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let sigma = scale / dmax.max(f64::MIN_POSITIVE);
    let p = upper_triangle(w);
    let qs: Vec<f64> = q.iter().map(|v| v / sigma).collect();
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..k {
        for i in 0..m {
            if c[(i, j)] != 0.0 {
                rows.push(j);
                cols.push(i);
                vals.push(c[(i, j)]);
            }
        }
    }
    for i in 0..m {
        rows.push(k + i);
        cols.push(i);
        vals.push(-1.0);
    }
    let a = CscMatrix::new_from_triplets(k + m, m, rows, cols, vals);
    let mut b: Vec<f64> = r.iter().map(|v| v / sigma).collect();
    b.extend(std::iter::repeat_n(0.0, m));
    let settings = clarabel_settings(s);
    let cones = [ZeroConeT(k), NonnegativeConeT(m)];
    // Clarabel refusing to set up, or stopping early (the status decides).
    let failed = || (LcpResult::broke_down(m), vec![0.0; k]);
    let Ok(mut solver) = DefaultSolver::new(&p, &qs, &a, &b, &cones, settings) else {
        return failed();
    };
    solver.solve();
    let sol = &solver.solution;
    if !matches!(sol.status, SolverStatus::Solved | SolverStatus::AlmostSolved) {
        let mut f = failed();
        f.0.iterations = sol.iterations as usize;
        f.0.breakdown = breakdown(sol.status);
        return f;
    }
    let lambda: Vec<f64> = sol.x.iter().map(|v| (v * sigma).max(0.0)).collect();
    // The gap is the multiplier of λ ≥ 0 (scaled by σ like q).
    let start: Vec<bool> = (0..m).map(|i| lambda[i] * w[(i, i)] > sol.z[k + i] * sigma).collect();
    let (mut res, beta) = super::active_set::solve_mlcp_from(w, q, c, r, s, start);
    res.iterations += sol.iterations as usize;
    (res, beta)
}

/// The upper triangle of the dense W as Clarabel's P (column by column, rows sorted).
fn upper_triangle(w: &Mat<f64>) -> CscMatrix<f64> {
    let m = w.nrows();
    let mut colptr = Vec::with_capacity(m + 1);
    let mut rowval = Vec::with_capacity(m * (m + 1) / 2);
    let mut nzval = Vec::with_capacity(m * (m + 1) / 2);
    colptr.push(0);
    for j in 0..m {
        for i in 0..=j {
            rowval.push(i);
            nzval.push(w[(i, j)]);
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(m, m, colptr, rowval, nzval)
}

/// Clarabel with tolerances two orders below ours (the crossover then makes the
/// answer exact), capped at round-off.
fn clarabel_settings(s: &Settings) -> clarabel::solver::DefaultSettings<f64> {
    let tol = (1e-2 * s.tolerance).max(1e-13);
    DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(s.max_iterations as u32)
        .time_limit(crate::cancel::remaining_secs())
        .tol_gap_abs(tol)
        .tol_gap_rel(tol)
        .tol_feas(tol)
        .build()
        .expect("static clarabel settings are valid")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clarabel's statuses keep their meaning: its caps are caps
    /// (max_iterations; the deadline is answered by the solve as timeout),
    /// everything else that is not a solution is a numerical breakdown (the
    /// LCP of a positive definite W always has one).
    #[test]
    fn clarabel_statuses_map_to_their_meaning() {
        for s in [SolverStatus::MaxIterations, SolverStatus::MaxTime, SolverStatus::Solved] {
            assert!(!breakdown(s), "{s:?}");
        }
        for s in [
            SolverStatus::NumericalError,
            SolverStatus::InsufficientProgress,
            SolverStatus::PrimalInfeasible,
            SolverStatus::DualInfeasible,
            SolverStatus::AlmostPrimalInfeasible,
        ] {
            assert!(breakdown(s), "{s:?}");
        }
    }
}
