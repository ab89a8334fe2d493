//! Interior penalty (log barrier) on the condensed operator.
//!
//! The barrier problem min ½uᵀKu − fᵀu − ζ Σ w_i log(s_i − (Bu)_i) has the
//! contact pressure p_i = ζ / gap_i, i.e. nodal forces λ_i = ζ w_i / gap_i, with
//! gap = Wλ + q > 0 in condensed form. Newton on F(λ) = λ ∘ (Wλ + q) − ζ w,
//! symmetrized by diag(λ)⁻¹: (diag(gap/λ) + W) Δλ = −F / λ (SPD, dense
//! Cholesky), with a fraction-to-boundary step keeping λ > 0 and gap > 0.
//! Continuation drives ζ from a start value, where the feasible start λ = t·1
//! is well centred, down to the requested ζ by factors of 10. Every iterate is
//! strictly feasible: the answer never penetrates; its pressure error and the
//! spurious pressure ζ/gap on open candidates fall with ζ.

use faer::Mat;

use super::LcpResult;
use crate::linalg::dense::{matvec, solve_principal};
use crate::proto::SolverSettings;

pub fn solve_barrier(w: &Mat<f64>, q: &[f64], weights: &[f64], zeta: f64, s: &SolverSettings) -> LcpResult {
    let m = q.len();
    let fail = |lambda: Vec<f64>, iterations| LcpResult {
        lambda,
        iterations,
        converged: false,
    };
    // Strictly feasible start: λ = t·1 with W·1 > 0 and t large enough that gap > 0.
    let ones = vec![1.0; m];
    let w1 = matvec(w, &ones);
    if w1.iter().any(|&v| v <= 0.0) {
        return fail(vec![0.0; m], 0);
    }
    let t = (0..m).map(|i| (-q[i] / w1[i]).max(0.0)).fold(0.0f64, f64::max);
    let qmax = q.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let dmax = (0..m).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
    let mut lambda = vec![2.0 * t + qmax / dmax; m];
    let gap_of = |l: &[f64]| -> Vec<f64> { matvec(w, l).iter().zip(q).map(|(a, b)| a + b).collect() };
    // Start ζ at the average centring of the start point, never below the target.
    let g0 = gap_of(&lambda);
    let mut z = ((0..m).map(|i| lambda[i] * g0[i] / weights[i]).sum::<f64>() / m as f64).max(zeta);
    let all: Vec<usize> = (0..m).collect();
    let mut iterations = 0;
    loop {
        // Newton on the current ζ.
        let mut converged = false;
        for _ in 0..s.max_iterations {
            let gap = gap_of(&lambda);
            let f: Vec<f64> = (0..m).map(|i| lambda[i] * gap[i] - z * weights[i]).collect();
            let fnorm = (0..m).map(|i| (f[i] / (z * weights[i])).abs()).fold(0.0f64, f64::max);
            // Loose centring on the way down; at the requested ζ, 1e-6 relative
            // (round-off in gap = Wλ + q limits it near contact, and the barrier's
            // own error in the pressure is far larger).
            let target = if z <= zeta { s.tolerance.max(1e-6) } else { 1e-3 };
            if fnorm <= target {
                converged = true;
                break;
            }
            iterations += 1;
            let mut j = w.clone();
            for i in 0..m {
                j[(i, i)] += gap[i] / lambda[i];
            }
            let rhs: Vec<f64> = (0..m).map(|i| -f[i] / lambda[i]).collect();
            let Some(dl) = solve_principal(&j, &all, &rhs) else {
                return fail(lambda, iterations);
            };
            let dg = matvec(w, &dl);
            let mut alpha: f64 = 1.0;
            for i in 0..m {
                if dl[i] < 0.0 {
                    alpha = alpha.min(-0.99 * lambda[i] / dl[i]);
                }
                if dg[i] < 0.0 {
                    alpha = alpha.min(-0.99 * gap[i] / dg[i]);
                }
            }
            for i in 0..m {
                lambda[i] += alpha * dl[i];
            }
        }
        if !converged {
            return fail(lambda, iterations);
        }
        if z <= zeta {
            return LcpResult {
                lambda,
                iterations,
                converged: true,
            };
        }
        z = (0.1 * z).max(zeta);
    }
}
