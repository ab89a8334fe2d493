//! Primal-dual active set (semismooth Newton on min(λ, c·w) = 0) for the LCP
//!
//! ```text
//! λ ≥ 0,  w = Wλ + q ≥ 0,  λᵀw = 0.
//! ```
//!
//! Each step solves W_AA λ_A = −q_A with λ = 0 off A, then takes
//! A ← {i : λ_i − c w_i > 0}. It converges superlinearly and stops when A
//! repeats. W from elasticity is not an M-matrix, so PDAS may cycle; after
//! `max_iterations / 2` steps without convergence it falls back to a monotone
//! primal active-set method (Lawson–Hanson type), finite by construction.

use faer::Mat;

use super::LcpResult;
use crate::linalg::dense::{matvec, solve_principal};
use crate::proto::SolverSettings;

pub fn solve_lcp(w: &Mat<f64>, q: &[f64], s: &SolverSettings) -> LcpResult {
    // Start from the candidates that penetrate without contact forces.
    solve_lcp_from(w, q, s, q.iter().map(|&qi| qi < 0.0).collect())
}

/// PDAS from a given initial active set (warm start).
pub fn solve_lcp_from(w: &Mat<f64>, q: &[f64], s: &SolverSettings, mut active: Vec<bool>) -> LcpResult {
    let m = q.len();
    if m == 0 {
        return LcpResult {
            lambda: vec![],
            iterations: 0,
            converged: true,
        };
    }
    let diag_mean = (0..m).map(|i| w[(i, i)]).sum::<f64>() / m as f64;
    let c = 1.0 / diag_mean;
    let mut lambda = vec![0.0; m];
    let pdas_cap = (s.max_iterations / 2).max(1);
    let mut seen: Vec<Vec<bool>> = Vec::new();
    for it in 1..=pdas_cap {
        let idx: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
        let rhs: Vec<f64> = idx.iter().map(|&i| -q[i]).collect();
        let Some(la) = solve_principal(w, &idx, &rhs) else {
            break;
        };
        lambda.iter_mut().for_each(|l| *l = 0.0);
        for (k, &i) in idx.iter().enumerate() {
            lambda[i] = la[k];
        }
        let wv: Vec<f64> = matvec(w, &lambda).iter().zip(q).map(|(a, b)| a + b).collect();
        let next: Vec<bool> = (0..m).map(|i| lambda[i] - c * wv[i] > 0.0).collect();
        if next == active {
            return LcpResult {
                lambda,
                iterations: it,
                converged: true,
            };
        }
        if seen.contains(&next) {
            break; // cycling
        }
        seen.push(active.clone());
        active = next;
    }
    let mut r = lawson_hanson(w, q, s.max_iterations);
    r.iterations += pdas_cap;
    r
}

/// Monotone active-set method for min ½λᵀWλ + qᵀλ, λ ≥ 0 (W SPD).
fn lawson_hanson(w: &Mat<f64>, q: &[f64], max_outer: usize) -> LcpResult {
    let m = q.len();
    let mut lambda = vec![0.0; m];
    let mut passive = vec![false; m];
    let scale = q.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(f64::MIN_POSITIVE);
    let tol = 1e-14 * scale;
    let mut iterations = 0;
    loop {
        let grad: Vec<f64> = matvec(w, &lambda).iter().zip(q).map(|(a, b)| a + b).collect();
        let entering = (0..m)
            .filter(|&i| !passive[i] && grad[i] < -tol)
            .min_by(|&a, &b| grad[a].total_cmp(&grad[b]));
        let Some(j) = entering else {
            return LcpResult {
                lambda,
                iterations,
                converged: true,
            };
        };
        if iterations >= max_outer * m.max(1) {
            return LcpResult {
                lambda,
                iterations,
                converged: false,
            };
        }
        passive[j] = true;
        loop {
            iterations += 1;
            let idx: Vec<usize> = (0..m).filter(|&i| passive[i]).collect();
            let rhs: Vec<f64> = idx.iter().map(|&i| -q[i]).collect();
            let Some(z) = solve_principal(w, &idx, &rhs) else {
                return LcpResult {
                    lambda,
                    iterations,
                    converged: false,
                };
            };
            if z.iter().all(|&v| v > 0.0) {
                for (k, &i) in idx.iter().enumerate() {
                    lambda[i] = z[k];
                }
                break;
            }
            // Step toward z until the first passive variable hits zero; that one leaves.
            let mut alpha: f64 = 1.0;
            let mut leaving = usize::MAX;
            for (k, &i) in idx.iter().enumerate() {
                if z[k] <= 0.0 {
                    let a = lambda[i] / (lambda[i] - z[k]);
                    if a < alpha {
                        alpha = a;
                        leaving = i;
                    }
                }
            }
            for (k, &i) in idx.iter().enumerate() {
                lambda[i] += alpha * (z[k] - lambda[i]);
                if i == leaving || lambda[i] <= 0.0 {
                    lambda[i] = 0.0;
                    passive[i] = false;
                }
            }
        }
    }
}
