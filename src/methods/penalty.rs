//! Exterior penalty and its augmented Lagrangian, on the condensed operator.
//!
//! Penalty: the contact pressure is p = (u·n − s)⁺ / ζ, i.e. tensionless Winkler
//! springs of stiffness 1/ζ per unit length, so the nodal force is
//! λ_i = (w_i / ζ) · max(0, −gap_i) with gap = Wλ + q and w_i the tributary length.
//! Semismooth Newton on λ = D max(0, −(Wλ + q)), D = diag(w_i/ζ): on the set A
//! of penetrating candidates (D_A⁻¹ + W_AA) λ_A = −q_A, λ = 0 elsewhere; stop
//! when A repeats. This is exactly the discrete penalty solution of the full
//! system (same K, same springs), found without refactoring K.
//!
//! Augmented Lagrangian (Uzawa on the penalty): with multiplier estimate μ,
//! λ = max(0, μ − D (Wλ + q)) (same Newton, shifted right-hand side
//! D_A⁻¹ μ_A − q_A), then μ ← λ; converges to the exact contact solution for
//! any fixed ζ > 0, the penetration falling geometrically per outer step.

use faer::Mat;

use super::LcpResult;
use crate::linalg::dense::{matvec, solve_principal};

use crate::proto::SolverSettings;

/// Newton solve of λ = max(0, μ − D(Wλ + q)); returns (λ, iterations, converged).
fn shifted_penalty(w: &Mat<f64>, q: &[f64], d: &[f64], mu: &[f64], cap: usize) -> (Vec<f64>, usize, bool) {
    let m = q.len();
    let mut lambda = mu.to_vec();
    let mut active: Vec<bool> = vec![false; m];
    for it in 1..=cap {
        let gap: Vec<f64> = matvec(w, &lambda).iter().zip(q).map(|(a, b)| a + b).collect();
        let next: Vec<bool> = (0..m).map(|i| mu[i] - d[i] * gap[i] > 0.0).collect();
        if it > 1 && next == active {
            return (lambda, it - 1, true);
        }
        active = next;
        let idx: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
        let rhs: Vec<f64> = idx.iter().map(|&i| mu[i] / d[i] - q[i]).collect();
        // (D_A⁻¹ + W_AA) is W_AA with the spring compliances added to its diagonal.
        let mut wd = w.clone();
        for &i in &idx {
            wd[(i, i)] += 1.0 / d[i];
        }
        let Some(la) = solve_principal(&wd, &idx, &rhs) else {
            return (lambda, it, false);
        };
        lambda.iter_mut().for_each(|l| *l = 0.0);
        for (k, &i) in idx.iter().enumerate() {
            lambda[i] = la[k];
        }
    }
    (lambda, cap, false)
}

/// Spring constants D_i = w_i / ζ of the candidates.
pub fn springs(weights: &[f64], zeta: f64) -> Vec<f64> {
    weights.iter().map(|w| w / zeta).collect()
}

pub fn solve_penalty(w: &Mat<f64>, q: &[f64], d: &[f64], s: &SolverSettings) -> LcpResult {
    let zero = vec![0.0; q.len()];
    let (lambda, iterations, converged) = shifted_penalty(w, q, d, &zero, s.max_iterations);
    LcpResult {
        lambda,
        iterations,
        converged,
    }
}

pub fn solve_augmented_lagrangian(w: &Mat<f64>, q: &[f64], d: &[f64], s: &SolverSettings) -> LcpResult {
    let m = q.len();
    let mut mu = vec![0.0; m];
    let mut total = 0;
    for _ in 0..s.max_iterations {
        let (lambda, it, ok) = shifted_penalty(w, q, d, &mu, s.max_iterations);
        total += it;
        if !ok {
            return LcpResult {
                lambda,
                iterations: total,
                converged: false,
            };
        }
        // Stop when the multiplier update (= D × remaining penetration) is within
        // the tolerance of the largest contact force: the pressures have settled.
        let change = lambda.iter().zip(&mu).fold(0.0f64, |a, (l, m)| a.max((l - m).abs()));
        let scale = lambda.iter().fold(0.0f64, |a, l| a.max(l.abs()));
        mu = lambda;
        if change <= 1e-2 * s.tolerance * scale {
            return LcpResult {
                lambda: mu,
                iterations: total,
                converged: true,
            };
        }
    }
    LcpResult {
        lambda: mu,
        iterations: total,
        converged: false,
    }
}

/// W + D⁻¹: with springs of stiffness D the penalty problem is the LCP
/// λ ≥ 0, (W + D⁻¹)λ + q + Cβ ≥ 0, complementary, since λ_i = −D_i gap_i where
/// λ_i > 0. Used for scenes with load-controlled punches.
fn with_springs(w: &Mat<f64>, d: &[f64]) -> Mat<f64> {
    let mut wd = w.clone();
    for (i, di) in d.iter().enumerate() {
        wd[(i, i)] += 1.0 / di;
    }
    wd
}

pub fn solve_penalty_mixed(
    w: &Mat<f64>,
    q: &[f64],
    c: &Mat<f64>,
    r: &[f64],
    d: &[f64],
    s: &SolverSettings,
) -> (LcpResult, Vec<f64>) {
    super::active_set::solve_mlcp(&with_springs(w, d), q, c, r, s)
}

/// ALM step: λ = max(0, μ − D·gap) is the LCP with W + D⁻¹ and q − D⁻¹μ.
pub fn solve_augmented_lagrangian_mixed(
    w: &Mat<f64>,
    q: &[f64],
    c: &Mat<f64>,
    r: &[f64],
    d: &[f64],
    s: &SolverSettings,
) -> (LcpResult, Vec<f64>) {
    let wd = with_springs(w, d);
    let m = q.len();
    let mut mu = vec![0.0; m];
    let mut total = 0;
    let mut beta = vec![0.0; c.ncols()];
    for _ in 0..s.max_iterations {
        let qs: Vec<f64> = (0..m).map(|i| q[i] - mu[i] / d[i]).collect();
        let (res, b) = super::active_set::solve_mlcp(&wd, &qs, c, r, s);
        total += res.iterations;
        beta = b;
        if !res.converged {
            return (
                LcpResult {
                    iterations: total,
                    ..res
                },
                beta,
            );
        }
        let change = res
            .lambda
            .iter()
            .zip(&mu)
            .fold(0.0f64, |a, (l, m)| a.max((l - m).abs()));
        let scale = res.lambda.iter().fold(0.0f64, |a, l| a.max(l.abs()));
        mu = res.lambda;
        if change <= 1e-2 * s.tolerance * scale {
            return (
                LcpResult {
                    lambda: mu,
                    iterations: total,
                    converged: true,
                },
                beta,
            );
        }
    }
    (
        LcpResult {
            lambda: mu,
            iterations: total,
            converged: false,
        },
        beta,
    )
}
