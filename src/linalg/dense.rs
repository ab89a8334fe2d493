//! Small dense kernels for the condensed contact operator W (m × m, m = candidates).

use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Accum, Mat, Par, Side};

/// W = Yᵀ Y with Y = L⁻¹ Bᵀ, where `l` is lower triangular (k × k) and `bt` is k × m.
pub fn gram_of_lower_solve(l: &Mat<f64>, mut bt: Mat<f64>) -> Mat<f64> {
    solve_lower_triangular_in_place(l.as_ref(), bt.as_mut(), Par::Seq);
    let m = bt.ncols();
    let mut w = Mat::<f64>::zeros(m, m);
    faer::linalg::matmul::matmul(w.as_mut(), Accum::Replace, bt.transpose(), bt.as_ref(), 1.0, Par::Seq);
    // Symmetrize exactly: rounding in the product is not symmetric to the last bit.
    for j in 0..m {
        for i in j + 1..m {
            let v = 0.5 * (w[(i, j)] + w[(j, i)]);
            w[(i, j)] = v;
            w[(j, i)] = v;
        }
    }
    w
}

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
