//! Sparse helpers on matrices stored by their lower triangle.

use faer::sparse::SparseColMat;

/// y = A x for symmetric A given by its lower triangle (diagonal included once).
pub fn sym_lower_matvec(a: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    sym_lower_map_matvec(a, x, |v| v)
}

/// |A| |x| for A symmetric stored as its lower triangle: the size of the terms
/// that A x sums, against which its round-off is judged.
pub fn sym_lower_abs_matvec(a: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let ax: Vec<f64> = x.iter().map(|v| v.abs()).collect();
    sym_lower_map_matvec(a, &ax, f64::abs)
}

fn sym_lower_map_matvec(a: &SparseColMat<usize, f64>, x: &[f64], map: impl Fn(f64) -> f64) -> Vec<f64> {
    let n = a.nrows();
    let mut y = vec![0.0; n];
    let sym = a.symbolic();
    let vals = a.val();
    let col_ptr = sym.col_ptr();
    let row_idx = sym.row_idx();
    for j in 0..n {
        let xj = x[j];
        let mut acc = 0.0;
        for k in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[k];
            let v = map(vals[k]);
            if i == j {
                acc += v * xj;
            } else {
                y[i] += v * xj;
                acc += v * x[i];
            }
        }
        y[j] += acc;
    }
    y
}
