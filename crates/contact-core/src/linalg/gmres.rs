//! GMRES (Saad and Schultz 1986) without restarts, for a system whose
//! operator is the identity plus a perturbation of low rank or small norm,
//! as a preconditioned system is: the caller passes the preconditioned
//! operator v ↦ A M⁻¹ v and maps the answer z back, x = M⁻¹ z.
//!
//! Arnoldi by modified Gram–Schmidt with one reorthogonalization (the basis
//! stays orthogonal to round-off, so the residual the Givens rotations
//! predict is the true one), the least-squares problem by Givens rotations.

use super::dense::dot;

/// The answer of a GMRES run.
pub struct Gmres {
    pub x: Vec<f64>,
    /// Operator applications made.
    pub iterations: usize,
    /// Whether ‖b − A x‖ ≤ tol ‖b‖ (as the rotations compute it).
    pub converged: bool,
    /// ‖b − A x‖ / ‖b‖ as the rotations compute it.
    pub residual: f64,
}

/// Solves A x = b from `x0`, `apply` computing A v.
pub fn gmres(
    mut apply: impl FnMut(&[f64]) -> Vec<f64>,
    b: &[f64],
    x0: Vec<f64>,
    tol: f64,
    max_iterations: usize,
) -> Gmres {
    let norm = |v: &[f64]| dot(v, v).sqrt();
    let target = tol * norm(b);
    let ax0 = apply(&x0);
    let r0: Vec<f64> = b.iter().zip(&ax0).map(|(b, a)| b - a).collect();
    let beta = norm(&r0);
    let b_norm = norm(b).max(f64::MIN_POSITIVE);
    if beta <= target || !beta.is_finite() {
        return Gmres {
            x: x0,
            iterations: 1,
            converged: beta <= target,
            residual: beta / b_norm,
        };
    }
    let mut basis = vec![r0.iter().map(|v| v / beta).collect::<Vec<f64>>()];
    // Columns of the Hessenberg matrix, rotated to upper triangular.
    let mut h: Vec<Vec<f64>> = Vec::new();
    let mut rotations: Vec<(f64, f64)> = Vec::new();
    let mut g = vec![beta];
    let mut converged = false;
    for j in 0..max_iterations {
        let mut w = apply(&basis[j]);
        let mut col = vec![0.0; j + 2];
        for _ in 0..2 {
            for (i, v) in basis.iter().enumerate() {
                let c = dot(&w, v);
                col[i] += c;
                w.iter_mut().zip(v).for_each(|(a, b)| *a -= c * b);
            }
        }
        let next = norm(&w);
        col[j + 1] = next;
        for (i, &(c, s)) in rotations.iter().enumerate() {
            let (a, b) = (col[i], col[i + 1]);
            col[i] = c * a + s * b;
            col[i + 1] = -s * a + c * b;
        }
        let (a, b) = (col[j], col[j + 1]);
        let r = a.hypot(b);
        let (c, s) = if r == 0.0 { (1.0, 0.0) } else { (a / r, b / r) };
        col[j] = r;
        col[j + 1] = 0.0;
        rotations.push((c, s));
        let gj = g[j];
        g[j] = c * gj;
        g.push(-s * gj);
        h.push(col);
        // A breakdown (next = 0) ends the Krylov space: exact when the
        // rotated diagonal is not 0, and then g[j + 1] = 0 already.
        if g[j + 1].abs() <= target || next == 0.0 || !next.is_finite() {
            converged = g[j + 1].abs() <= target && r != 0.0;
            break;
        }
        basis.push(w.iter().map(|v| v / next).collect());
    }
    // Back substitution of the triangular system H y = g (a zero on its
    // diagonal: the operator is singular on the Krylov space; not converged).
    let k = h.len();
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        if h[i][i] == 0.0 {
            converged = false;
            break;
        }
        let s: f64 = (i + 1..k).map(|l| h[l][i] * y[l]).sum();
        y[i] = (g[i] - s) / h[i][i];
    }
    let mut x = x0;
    for (v, &yi) in basis.iter().zip(&y) {
        x.iter_mut().zip(v).for_each(|(a, b)| *a += yi * b);
    }
    Gmres {
        x,
        iterations: k + 1,
        converged,
        residual: g[k].abs() / b_norm,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On I + E with E of rank 3 (and norm up to 2), GMRES is exact after at
    /// most 4 applications (the Krylov space of I + E from any start has
    /// dimension ≤ rank + 1); the answer solves the system to 1e-12 relative.
    #[test]
    fn identity_plus_low_rank_in_rank_plus_one_steps() {
        let n = 50;
        let u: Vec<Vec<f64>> = (0..3)
            .map(|k| (0..n).map(|i| ((i * (k + 2)) as f64 * 0.37).sin()).collect())
            .collect();
        let v: Vec<Vec<f64>> = (0..3)
            .map(|k| (0..n).map(|i| 0.1 * ((i + 3 * k) as f64 * 0.11).cos()).collect())
            .collect();
        let apply = |x: &[f64]| -> Vec<f64> {
            let mut y = x.to_vec();
            for (uk, vk) in u.iter().zip(&v) {
                let c = dot(vk, x);
                y.iter_mut().zip(uk).for_each(|(a, b)| *a += c * b);
            }
            y
        };
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sqrt() - 3.0).collect();
        let r = gmres(apply, &b, vec![0.0; n], 1e-14, 20);
        assert!(r.converged && r.iterations <= 5, "{} iterations", r.iterations);
        let ax = apply(&r.x);
        let err = ax.iter().zip(&b).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        let size = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(err <= 1e-12 * size, "residual {err}");
    }
}
