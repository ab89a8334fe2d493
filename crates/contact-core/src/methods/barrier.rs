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
use crate::scene::Settings;

pub fn solve_barrier(w: &Mat<f64>, q: &[f64], weights: &[f64], zeta: f64, s: &Settings) -> LcpResult {
    solve_barrier_mixed(w, q, &Mat::<f64>::zeros(q.len(), 0), &[], weights, zeta, s).0
}

/// With load-controlled punches: unknowns (λ, β), F = (λ∘(Wλ + q + Cβ) − ζw,
/// Cᵀλ − r), the Newton system [diag(gap/λ) + W, C; Cᵀ, 0] solved as a saddle point.
pub fn solve_barrier_mixed(
    w: &Mat<f64>,
    q: &[f64],
    c: &Mat<f64>,
    r: &[f64],
    weights: &[f64],
    zeta: f64,
    s: &Settings,
) -> (LcpResult, Vec<f64>) {
    let k = c.ncols();
    let mut beta = vec![0.0; k];
    let m = q.len();
    let fail = |lambda: Vec<f64>, iterations, beta: Vec<f64>| {
        (
            LcpResult {
                lambda,
                iterations,
                converged: false,
                breakdown: false,
            },
            beta,
        )
    };
    // Strictly feasible start: λ = t·1 with W·1 > 0 and t large enough that gap > 0.
    let ones = vec![1.0; m];
    let w1 = matvec(w, &ones);
    if w1.iter().any(|&v| v <= 0.0) {
        return fail(vec![0.0; m], 0, beta);
    }
    let t = (0..m).map(|i| (-q[i] / w1[i]).max(0.0)).fold(0.0f64, f64::max);
    let qmax = q.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let dmax = (0..m).map(|i| w[(i, i)]).fold(0.0f64, f64::max);
    // Scale of the start: the gaps' (q/W) or, when every gap is zero (a flat punch
    // resting on the surface), the punch loads shared by the candidates.
    let rmax = r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let base = (qmax / dmax).max(rmax / m as f64).max(f64::MIN_POSITIVE);
    let mut lambda = vec![2.0 * t + base; m];
    let gap_of = |l: &[f64], b: &[f64]| -> Vec<f64> {
        let wl = matvec(w, l);
        (0..m)
            .map(|i| wl[i] + q[i] + (0..k).map(|j| c[(i, j)] * b[j]).sum::<f64>())
            .collect()
    };
    // Start ζ at the average centring of the start point, never below the target.
    let g0 = gap_of(&lambda, &beta);
    let mut z = ((0..m).map(|i| lambda[i] * g0[i] / weights[i]).sum::<f64>() / m as f64).max(zeta);
    let all: Vec<usize> = (0..m).collect();
    let mut iterations = 0;
    loop {
        // Newton on the current ζ.
        let mut converged = false;
        for _ in (0..s.max_iterations).take_while(|_| !crate::cancel::expired()) {
            let gap = gap_of(&lambda, &beta);
            let f: Vec<f64> = (0..m).map(|i| lambda[i] * gap[i] - z * weights[i]).collect();
            let f2: Vec<f64> = (0..k)
                .map(|j| (0..m).map(|i| c[(i, j)] * lambda[i]).sum::<f64>() - r[j])
                .collect();
            let f2_scale = r.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(f64::MIN_POSITIVE);
            let fnorm = (0..m)
                .map(|i| (f[i] / (z * weights[i])).abs())
                .chain(f2.iter().map(|v| v.abs() / f2_scale))
                .fold(0.0f64, f64::max);
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
            let (dl, db) = if k == 0 {
                let rhs: Vec<f64> = (0..m).map(|i| -f[i] / lambda[i]).collect();
                let Some(dl) = solve_principal(&j, &all, &rhs) else {
                    return fail(lambda, iterations, beta);
                };
                (dl, Vec::new())
            } else {
                // [J C; Cᵀ 0][Δλ; Δβ] = [−F/λ; −F2]
                let fq: Vec<f64> = (0..m).map(|i| f[i] / lambda[i]).collect();
                let fr: Vec<f64> = f2.iter().map(|v| -v).collect();
                let Some(step) = crate::methods::active_set::saddle(&j, &fq, c, &fr, &all) else {
                    return fail(lambda, iterations, beta);
                };
                step
            };
            let dwl = matvec(w, &dl);
            let dg: Vec<f64> = (0..m)
                .map(|i| dwl[i] + (0..k).map(|t| c[(i, t)] * db[t]).sum::<f64>())
                .collect();
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
            for t in 0..k {
                beta[t] += alpha * db[t];
            }
        }
        if !converged {
            return fail(lambda, iterations, beta);
        }
        if z <= zeta {
            return (
                LcpResult {
                    lambda,
                    iterations,
                    converged: true,
                    breakdown: false,
                },
                beta,
            );
        }
        z = (0.1 * z).max(zeta);
    }
}
