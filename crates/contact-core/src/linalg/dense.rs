//! Small dense kernels for the condensed contact operator W (m × m, m = candidates).

use faer::{Mat, Side};

/// Solves W[idx, idx] x = rhs by dense Cholesky; None if that block is not positive definite.
pub fn solve_principal(w: &Mat<f64>, idx: &[usize], rhs: &[f64]) -> Option<Vec<f64>> {
    let k = idx.len();
    if k == 0 {
        return Some(Vec::new());
    }
    let sub = Mat::<f64>::from_fn(k, k, |i, j| w[(idx[i], idx[j])]);
    let llt = sub.llt(Side::Lower).ok()?;
    let b = Mat::<f64>::from_fn(k, 1, |i, _| rhs[i]);
    let x = faer::linalg::solvers::Solve::solve(&llt, &b);
    let out: Vec<f64> = (0..k).map(|i| x[(i, 0)]).collect();
    out.iter().all(|v| v.is_finite()).then_some(out)
}

/// x · y.
pub fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// y = W x.
pub fn matvec(w: &Mat<f64>, x: &[f64]) -> Vec<f64> {
    let m = w.nrows();
    let mut y = vec![0.0; m];
    for (j, &xj) in x.iter().enumerate() {
        if xj != 0.0 {
            let col = w.col(j);
            for i in 0..m {
                y[i] += col[i] * xj;
            }
        }
    }
    y
}

/// Eigenvalues (ascending) and orthonormal eigenvectors (columns) of a small
/// symmetric matrix by cyclic Jacobi rotations: robust and exact enough for the
/// few-by-few Gram matrices of rigid modes, where a library call would cost more
/// set-up than work.
pub fn sym_eigen_small(a: &Mat<f64>) -> (Vec<f64>, Mat<f64>) {
    let n = a.nrows();
    let mut a = a.clone();
    let mut v = Mat::<f64>::identity(n, n);
    for _sweep in 0..64 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[(i, j)] * a[(i, j)])
            .sum();
        let diag: f64 = (0..n).map(|i| a[(i, i)] * a[(i, i)]).sum();
        if off <= 1e-30 * diag || off == 0.0 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[(p, q)] == 0.0 {
                    continue;
                }
                let theta = 0.5 * (a[(q, q)] - a[(p, p)]) / a[(p, q)];
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[(k, p)], a[(k, q)]);
                    a[(k, p)] = c * akp - s * akq;
                    a[(k, q)] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[(p, k)], a[(q, k)]);
                    a[(p, k)] = c * apk - s * aqk;
                    a[(q, k)] = s * apk + c * aqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[(k, p)], v[(k, q)]);
                    v[(k, p)] = c * vkp - s * vkq;
                    v[(k, q)] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut idx: Vec<usize> = (0..n).collect();
    idx.sort_by(|&i, &j| a[(i, i)].total_cmp(&a[(j, j)]));
    let vals = idx.iter().map(|&i| a[(i, i)]).collect();
    let vecs = Mat::<f64>::from_fn(n, n, |r, c| v[(r, idx[c])]);
    (vals, vecs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_diagonalizes_a_symmetric_matrix() {
        let a = Mat::<f64>::from_fn(3, 3, |i, j| [[4.0, 1.0, 2.0], [1.0, 3.0, 0.5], [2.0, 0.5, 1.0]][i][j]);
        let (vals, v) = sym_eigen_small(&a);
        for k in 0..3 {
            for i in 0..3 {
                let av: f64 = (0..3).map(|j| a[(i, j)] * v[(j, k)]).sum();
                assert!((av - vals[k] * v[(i, k)]).abs() < 1e-12, "A v = λ v");
            }
        }
        assert!(vals[0] <= vals[1] && vals[1] <= vals[2]);
        let trace: f64 = vals.iter().sum();
        assert!((trace - 8.0).abs() < 1e-12);
    }
}
