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
use crate::scene::Settings;

pub fn solve_lcp(w: &Mat<f64>, q: &[f64], s: &Settings) -> LcpResult {
    // Start from the candidates that penetrate without contact forces.
    solve_lcp_from(w, q, s, q.iter().map(|&qi| qi < 0.0).collect())
}

/// PDAS from a given initial active set (warm start).
pub fn solve_lcp_from(w: &Mat<f64>, q: &[f64], s: &Settings, mut active: Vec<bool>) -> LcpResult {
    let m = q.len();
    if m == 0 {
        return LcpResult::at_rest(0);
    }
    let diag_mean = (0..m).map(|i| w[(i, i)]).sum::<f64>() / m as f64;
    let c = 1.0 / diag_mean;
    let mut lambda = vec![0.0; m];
    let pdas_cap = (s.max_iterations / 2).max(1);
    let mut seen: Vec<Vec<bool>> = Vec::new();
    for it in (1..=pdas_cap).take_while(|_| !crate::cancel::expired()) {
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
        crate::progress::iteration(it, (0..m).map(|i| lambda[i].min(c * wv[i]).abs()).fold(0.0, f64::max));
        if next == active {
            return LcpResult {
                lambda,
                iterations: it,
                converged: true,
                breakdown: false,
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
                breakdown: false,
            };
        };
        if iterations >= max_outer * m.max(1) || crate::cancel::expired() {
            return LcpResult {
                lambda,
                iterations,
                converged: false,
                breakdown: false,
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
                    breakdown: false,
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

/// Mixed LCP of a scene with load-controlled punches:
///
/// ```text
/// λ ≥ 0,   w = Wλ + q + Cβ ≥ 0,   λᵀw = 0,   Cᵀλ = r   (β free: the punch motions)
/// ```
///
/// PDAS again: on the active set A, [W_AA C_A; C_Aᵀ 0][λ_A; β] = [−q_A; r], solved
/// through the Schur complement C_Aᵀ W_AA⁻¹ C_A (size = number of free motions).
/// Starts from the candidates that penetrate with the motions at rest, and
/// every active set is completed to one that can carry the motions'
/// equilibrium (`carrying`): without that, a set whose rows do not span the
/// motions makes the saddle singular and the iteration stop. (Starting from
/// every row the motions touch, as for a flat punch, failed where all rows
/// touch a motion: a half-disk held sideways only by tilted body-normal rows
/// solved gap = 0 on the whole arc, in tension everywhere, then found no row
/// to keep: max_iterations after one step, every force negative.)
pub fn solve_mlcp(w: &Mat<f64>, q: &[f64], c: &Mat<f64>, r: &[f64], s: &Settings) -> (LcpResult, Vec<f64>) {
    let start = carrying((0..q.len()).map(|i| q[i] < 0.0).collect(), q, c);
    solve_mlcp_from(w, q, c, r, s, start)
}

/// The active set completed, if its rows of C do not span the motions, by the
/// rows of smallest gap that add a direction: the nearest contacts are the
/// ones that carry a motion's load first.
fn carrying(mut active: Vec<bool>, gap: &[f64], c: &Mat<f64>) -> Vec<bool> {
    let k = c.ncols();
    if k == 0 {
        return active;
    }
    let row = |i: usize| -> Vec<f64> { (0..k).map(|j| c[(i, j)]).collect() };
    let scale = (0..gap.len())
        .flat_map(|i| (0..k).map(move |j| (i, j)))
        .fold(0.0f64, |a, (i, j)| a.max(c[(i, j)].abs()));
    if scale == 0.0 {
        return active;
    }
    // Orthonormal basis of the span of the active rows (Gram–Schmidt).
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let adds = |v: Vec<f64>, basis: &mut Vec<Vec<f64>>| -> bool {
        let mut v = v;
        for b in basis.iter() {
            let d: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
            v.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
        }
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > 1e-8 * scale && basis.len() < k {
            basis.push(v.into_iter().map(|x| x / n).collect());
            true
        } else {
            false
        }
    };
    for i in (0..gap.len()).filter(|&i| active[i]) {
        adds(row(i), &mut basis);
    }
    if basis.len() == k {
        return active;
    }
    let mut order: Vec<usize> = (0..gap.len()).filter(|&i| !active[i]).collect();
    order.sort_by(|&a, &b| gap[a].total_cmp(&gap[b]));
    for i in order {
        if adds(row(i), &mut basis) {
            active[i] = true;
            if basis.len() == k {
                break;
            }
        }
    }
    active
}

/// `solve_mlcp` from a given initial active set (warm start, crossover).
pub fn solve_mlcp_from(
    w: &Mat<f64>,
    q: &[f64],
    c: &Mat<f64>,
    r: &[f64],
    s: &Settings,
    mut active: Vec<bool>,
) -> (LcpResult, Vec<f64>) {
    let m = q.len();
    let k = c.ncols();
    let diag_mean = (0..m).map(|i| w[(i, i)]).sum::<f64>() / m.max(1) as f64;
    let cpar = 1.0 / diag_mean;
    let mut lambda = vec![0.0; m];
    let mut beta = vec![0.0; k];
    let mut seen: Vec<Vec<bool>> = Vec::new();
    for it in (1..=s.max_iterations).take_while(|_| !crate::cancel::expired()) {
        let idx: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
        let Some((la, b)) = saddle(w, q, c, r, &idx) else {
            break;
        };
        lambda.iter_mut().for_each(|l| *l = 0.0);
        for (t, &i) in idx.iter().enumerate() {
            lambda[i] = la[t];
        }
        beta = b;
        let wl = matvec(w, &lambda);
        let gap: Vec<f64> = (0..m)
            .map(|i| wl[i] + q[i] + (0..k).map(|j| c[(i, j)] * beta[j]).sum::<f64>())
            .collect();
        let next = carrying((0..m).map(|i| lambda[i] - cpar * gap[i] > 0.0).collect(), &gap, c);
        if next == active {
            return (
                LcpResult {
                    lambda,
                    iterations: it,
                    converged: true,
                    breakdown: false,
                },
                beta,
            );
        }
        if seen.contains(&next) {
            break;
        }
        seen.push(active.clone());
        active = next;
    }
    (
        LcpResult {
            lambda,
            iterations: s.max_iterations,
            converged: false,
            breakdown: false,
        },
        beta,
    )
}

/// [W_AA C_A; C_Aᵀ 0][λ_A; β] = [−q_A; r]; None if singular.
pub fn saddle(w: &Mat<f64>, q: &[f64], c: &Mat<f64>, r: &[f64], idx: &[usize]) -> Option<(Vec<f64>, Vec<f64>)> {
    let (a, k) = (idx.len(), c.ncols());
    if a == 0 {
        return None;
    }
    let waa = Mat::<f64>::from_fn(a, a, |i, j| w[(idx[i], idx[j])]);
    let llt = waa.llt(faer::Side::Lower).ok()?;
    // Columns: −q_A, then C_A.
    let rhs = Mat::<f64>::from_fn(a, 1 + k, |i, j| if j == 0 { -q[idx[i]] } else { c[(idx[i], j - 1)] });
    let sol = faer::linalg::solvers::Solve::solve(&llt, &rhs);
    // S β = C_Aᵀ y − r with S = C_Aᵀ X.
    let s = Mat::<f64>::from_fn(k, k, |p, t| (0..a).map(|i| c[(idx[i], p)] * sol[(i, 1 + t)]).sum());
    let bvec = Mat::<f64>::from_fn(k, 1, |p, _| {
        (0..a).map(|i| c[(idx[i], p)] * sol[(i, 0)]).sum::<f64>() - r[p]
    });
    let beta: Vec<f64> = if k == 0 {
        Vec::new()
    } else {
        let lu = s.partial_piv_lu();
        let b = faer::linalg::solvers::Solve::solve(&lu, &bvec);
        (0..k).map(|p| b[(p, 0)]).collect()
    };
    let la: Vec<f64> = (0..a)
        .map(|i| sol[(i, 0)] - (0..k).map(|t| sol[(i, 1 + t)] * beta[t]).sum::<f64>())
        .collect();
    (la.iter().chain(&beta).all(|v| v.is_finite())).then_some((la, beta))
}
