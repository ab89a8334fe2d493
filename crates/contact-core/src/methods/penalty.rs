//! Exterior penalty and its augmented Lagrangian, on the condensed operator.
//!
//! Penalty: the contact pressure is p = (u·n − s)⁺ / ζ, i.e. tensionless Winkler
//! springs of stiffness 1/ζ per unit length, so the nodal force is
//! λ_i = D_i · max(0, −gap_i), D = diag(w_i/ζ), w_i the tributary length and
//! gap = Wλ + q (+ Cβ with load-controlled punches). Where λ_i > 0,
//! gap_i + λ_i/D_i = 0; elsewhere gap_i ≥ 0: the penalty problem is exactly the
//! LCP with W + D⁻¹ in place of W, solved by the active set (`active_set`). This
//! is the discrete penalty solution of the full system (same K, same springs),
//! found without refactoring K.
//!
//! Augmented Lagrangian (Uzawa on the penalty): with multiplier estimate μ,
//! λ = max(0, μ − D·gap) is the same LCP with q − D⁻¹μ; then μ ← λ. It
//! converges to the exact contact solution for any fixed ζ > 0, the penetration
//! falling geometrically per outer step.

use faer::Mat;

use super::LcpResult;
use crate::scene::Settings;

/// Spring constants D_i = w_i / ζ of the candidates.
pub fn springs(weights: &[f64], zeta: f64) -> Vec<f64> {
    weights.iter().map(|w| w / zeta).collect()
}

pub fn solve_penalty(w: &Mat<f64>, q: &[f64], d: &[f64], s: &Settings) -> LcpResult {
    super::active_set::solve_lcp(&with_springs(w, d), q, s)
}

pub fn solve_augmented_lagrangian(w: &Mat<f64>, q: &[f64], d: &[f64], s: &Settings) -> LcpResult {
    let wd = with_springs(w, d);
    augmented_lagrangian(q, d, s, &|qs| (super::active_set::solve_lcp(&wd, qs, s), Vec::new())).0
}

/// W + D⁻¹: with springs of stiffness D the penalty problem is the LCP
/// λ ≥ 0, (W + D⁻¹)λ + q + Cβ ≥ 0, complementary, since λ_i = −D_i gap_i where
/// λ_i > 0.
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
    s: &Settings,
) -> (LcpResult, Vec<f64>) {
    super::active_set::solve_mlcp(&with_springs(w, d), q, c, r, s)
}

pub fn solve_augmented_lagrangian_mixed(
    w: &Mat<f64>,
    q: &[f64],
    c: &Mat<f64>,
    r: &[f64],
    d: &[f64],
    s: &Settings,
) -> (LcpResult, Vec<f64>) {
    let wd = with_springs(w, d);
    augmented_lagrangian(q, d, s, &|qs| super::active_set::solve_mlcp(&wd, qs, c, r, s))
}

/// One penalty solve for a shifted q: (λ, punch motions).
type PenaltyStep<'a> = &'a dyn Fn(&[f64]) -> (LcpResult, Vec<f64>);

/// The Uzawa loop: `inner(q − D⁻¹μ)` solves one penalty step (returns λ and the
/// punch motions, if any); stops when the multiplier update is within the
/// tolerance of the largest contact force, i.e. the pressures have settled.
fn augmented_lagrangian(q: &[f64], d: &[f64], s: &Settings, inner: PenaltyStep) -> (LcpResult, Vec<f64>) {
    let m = q.len();
    let mut mu = vec![0.0; m];
    let mut total = 0;
    let mut beta = Vec::new();
    for _ in (0..s.max_iterations).take_while(|_| !crate::cancel::expired()) {
        let qs: Vec<f64> = (0..m).map(|i| q[i] - mu[i] / d[i]).collect();
        let (res, b) = inner(&qs);
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
                    breakdown: false,
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
            breakdown: false,
        },
        beta,
    )
}
