//! Sparse Cholesky of the (free-DOF) stiffness K in a fill-reducing (AMD)
//! order: P K Pᵀ = L Lᵀ, supernodal. The contact operator is formed on this
//! factor by `linalg::schur` from the reach of the contact rows, so the
//! factor is the same as for K alone (the floor of any direct method).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky},
    SymbolicCholesky, SymbolicCholeskyRaw,
};
use faer::sparse::SparseColMat;
use faer::{Conj, Mat, MatMut};
use std::hash::{Hash, Hasher};
use std::sync::Arc;

pub use super::cost::{FactorCost, LinalgError};

impl FactorCost {
    /// The cost of factorizing `a` (lower triangle) in a fill-reducing order,
    /// from a symbolic analysis alone (for factorizations that faer orders
    /// itself: the full formulation's).
    pub fn predict(a: &SparseColMat<usize, f64>) -> Result<Self, LinalgError> {
        Ok(Self::of(&super::symbolic::symbolic(a)?))
    }
}

/// The ordering and supernodal symbolic factorization of a sparsity
/// pattern: everything of a factorization that does not depend on the
/// values, so a matrix with the same pattern (a change of E or ν, of the
/// loads, of the prescribed values or of the contact rows) factors without
/// redoing it.
pub struct SymbolicFactor {
    symbolic: SymbolicCholesky<usize>,
    /// Which supernodes update which: the numeric factorization's schedule.
    descendants: super::numeric::Descendants,
    n: usize,
    cost: FactorCost,
    /// `pattern_key` of the matrix it was made for.
    key: u64,
}

impl SymbolicFactor {
    /// Orders `a` (lower triangle) and analyzes the factor's structure.
    pub fn try_new(a: &SparseColMat<usize, f64>) -> Result<Self, LinalgError> {
        Self::try_new_keyed(a, pattern_key(a))
    }

    /// `try_new` for a pattern whose `pattern_key` the caller already has
    /// (the operator cache's lookup): hashing the pattern costs a pass over
    /// its indices, which the lookup and the analysis made twice.
    pub fn try_new_keyed(a: &SparseColMat<usize, f64>, key: u64) -> Result<Self, LinalgError> {
        debug_assert_eq!(key, pattern_key(a));
        Ok(Self::of(a, super::symbolic::symbolic(a)?, key))
    }

    /// Analyzes `a` (lower triangle) in the caller's fill-reducing order
    /// (`fwd[i]`: the unknown at position i; `inv` its inverse), for
    /// matrices whose geometry knows a better order than AMD (a 3D mesh's
    /// nested dissection, `solid::ordering`).
    pub fn try_new_ordered(a: &SparseColMat<usize, f64>, fwd: &[usize], inv: &[usize]) -> Result<Self, LinalgError> {
        Ok(Self::of(a, super::symbolic::in_order(a, fwd, inv)?, pattern_key(a)))
    }

    fn of(a: &SparseColMat<usize, f64>, symbolic: SymbolicCholesky<usize>, key: u64) -> Self {
        let SymbolicCholeskyRaw::Supernodal(sym) = symbolic.raw() else {
            unreachable!("factorization is forced supernodal")
        };
        Self {
            descendants: super::numeric::Descendants::of(sym),
            cost: FactorCost::of(&symbolic),
            symbolic,
            n: a.nrows(),
            key,
        }
    }

    /// The key of the pattern this analysis is for.
    pub fn key(&self) -> u64 {
        self.key
    }

    /// The supernodal structure (supernodes, their row patterns).
    pub(crate) fn supernodal(&self) -> &SymbolicSupernodalCholesky<usize> {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("factorization is forced supernodal")
        };
        sym
    }

    /// faer's symbolic factorization (ordering included).
    #[cfg(test)]
    pub(crate) fn symbolic(&self) -> &SymbolicCholesky<usize> {
        &self.symbolic
    }

    /// Which supernodes update which.
    pub(crate) fn descendants(&self) -> &super::numeric::Descendants {
        &self.descendants
    }

    /// Factor position of every DOF (the inverse of the fill-reducing order).
    pub(crate) fn positions(&self) -> &[usize] {
        self.symbolic.perm().expect("the ordering is always given").arrays().1
    }

    /// The numeric factorization's predicted cost.
    pub fn cost(&self) -> FactorCost {
        self.cost
    }
}

/// Identity of a sparsity pattern (lower triangle): equal keys share one
/// `SymbolicFactor`.
pub fn pattern_key(a: &SparseColMat<usize, f64>) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    let sym = a.symbolic();
    (sym.nrows(), sym.ncols()).hash(&mut h);
    sym.col_ptr().hash(&mut h);
    sym.row_idx().hash(&mut h);
    sym.col_nnz().hash(&mut h);
    h.finish()
}

/// Numeric Cholesky factor of an SPD matrix given by its lower triangle.
pub struct Cholesky {
    analysis: Arc<SymbolicFactor>,
    values: Vec<f64>,
}

/// Factors of more values than this are freed on a thread of their own.
const FREED_BESIDE: usize = 1 << 23;

impl Drop for Cholesky {
    /// Giving a large factor's pages back takes time (0.26–0.41 s measured
    /// for the 2.4 GB of a 2M-DOF factor) that a reply, a `timeout` above
    /// all, need not wait for.
    fn drop(&mut self) {
        if self.values.len() >= FREED_BESIDE {
            free_beside(std::mem::take(&mut self.values));
        }
    }
}

impl Cholesky {
    /// Factorizes `a` (lower triangle, n×n).
    pub fn try_new(a: &SparseColMat<usize, f64>) -> Result<Self, LinalgError> {
        Self::with_symbolic(Arc::new(SymbolicFactor::try_new(a)?), a)
    }

    /// The numeric factorization of `a` on an analysis of its pattern (the
    /// caller matched `analysis.key()` with `pattern_key`).
    pub fn with_symbolic(analysis: Arc<SymbolicFactor>, a: &SparseColMat<usize, f64>) -> Result<Self, LinalgError> {
        debug_assert_eq!(a.nrows(), analysis.n);
        let symbolic = &analysis.symbolic;
        analysis.cost.fits_in_time_left()?;
        // Timed from here: the prediction is for the whole numeric stage,
        // the factor's memory included (zeroed lazily, then filled).
        let started = std::time::Instant::now();
        let mut values = vec![0.0; symbolic.len_val()];
        let done = super::numeric::factorize(
            &mut values,
            a.as_ref(),
            symbolic.perm().expect("the ordering is always given"),
            analysis.supernodal(),
            analysis.descendants(),
            super::par(),
        );
        if let Err(stop) = done {
            use super::numeric::Stop;
            return Err(match stop {
                Stop::NotPositiveDefinite => LinalgError::NotPositiveDefinite,
                Stop::OutOfMemory => LinalgError::Faer("out of memory".into()),
                Stop::Deadline(t) => {
                    // As a finished factor (`Drop for Cholesky`): beside the reply.
                    if values.len() >= FREED_BESIDE {
                        free_beside(values);
                    }
                    LinalgError::Deadline(t)
                }
            });
        }
        super::rate::learn(analysis.cost.reference_secs(), started.elapsed().as_secs_f64());
        Ok(Self { analysis, values })
    }

    /// The numeric factorization's cost as predicted before it ran.
    pub fn cost(&self) -> FactorCost {
        self.analysis.cost
    }

    /// L's values, supernode by supernode (faer's layout).
    #[cfg(test)]
    pub(crate) fn values(&self) -> &[f64] {
        &self.values
    }

    /// Entries in the factor L (a memory and cost measure).
    pub fn nnz_factor(&self) -> usize {
        self.values.len()
    }

    /// Solves K X = B in place for every column of `rhs`.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let symbolic = &self.analysis.symbolic;
        let llt = faer::sparse::linalg::cholesky::LltRef::new(symbolic, &self.values);
        let par = super::par();
        let req = symbolic.solve_in_place_scratch::<f64>(rhs.ncols(), par);
        let mut mem = MemBuffer::new(req);
        llt.solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
    }

    /// The analysis this factor was made on.
    pub fn analysis(&self) -> &SymbolicFactor {
        &self.analysis
    }

    /// The numeric factor, supernode by supernode.
    pub(crate) fn supernodes(&self) -> SupernodalLltRef<'_, usize, f64> {
        SupernodalLltRef::new(self.analysis.supernodal(), &self.values)
    }

    /// The forward sweep y = L⁻¹ P b, in factor order.
    pub fn forward(&self, b: &[f64]) -> Vec<f64> {
        let (fwd, _) = self.perm();
        let mut y = Mat::<f64>::from_fn(b.len(), 1, |i, _| b[fwd[i]]);
        let SymbolicCholeskyRaw::Supernodal(sym) = self.analysis.symbolic.raw() else {
            unreachable!("factorization is forced supernodal")
        };
        let llt = SupernodalLltRef::new(sym, &self.values);
        let mut mem = MemBuffer::new(sym.solve_in_place_scratch::<f64>(1, super::par()));
        llt.l_solve_with_conj(Conj::No, y.as_mut(), super::par(), MemStack::new(&mut mem));
        (0..b.len()).map(|i| y[(i, 0)]).collect()
    }

    /// The forward sweep of a `b` that is zero on most DOFs (loads on a few
    /// nodes), as `forward` but on the supernodes that b's nonzeros reach
    /// alone: a supernode whose part of the sweep is still zero when its turn
    /// comes contributes nothing and is skipped (Gilbert's reach; the same
    /// sweep to round-off).
    pub fn forward_sparse(&self, b: &[f64]) -> Vec<f64> {
        let (fwd, _) = self.perm();
        let mut y: Vec<f64> = fwd.iter().map(|&f| b[f]).collect();
        let llt = self.supernodes();
        let sym = self.analysis.supernodal();
        let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
        let mut t: Vec<f64> = Vec::new();
        for s in 0..sym.n_supernodes() {
            let ys = &mut y[begin[s]..end[s]];
            if ys.iter().all(|&v| v == 0.0) {
                continue;
            }
            let node = llt.supernode(s);
            let val = node.val();
            let w = val.ncols();
            let (diag, below) = val.split_at_row(w);
            let mut xs = MatMut::from_column_major_slice_mut(ys, w, 1);
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(diag, xs.as_mut(), faer::Par::Seq);
            let pattern = node.pattern();
            if pattern.is_empty() {
                continue;
            }
            t.clear();
            t.resize(pattern.len(), 0.0);
            let tm = MatMut::from_column_major_slice_mut(&mut t, pattern.len(), 1);
            faer::linalg::matmul::matmul(tm, faer::Accum::Replace, below, xs.as_ref(), 1.0, faer::Par::Seq);
            for (&p, v) in pattern.iter().zip(&t) {
                y[p] -= v;
            }
        }
        y
    }

    /// The backward sweep x = Pᵀ L⁻ᵀ y of a factor-order `y`: with `forward`,
    /// one solve with K.
    pub fn backward(&self, y: &[f64]) -> Vec<f64> {
        let (fwd, _) = self.perm();
        let mut x = Mat::<f64>::from_fn(y.len(), 1, |i, _| y[i]);
        let SymbolicCholeskyRaw::Supernodal(sym) = self.analysis.symbolic.raw() else {
            unreachable!("factorization is forced supernodal")
        };
        let llt = SupernodalLltRef::new(sym, &self.values);
        let mut mem = MemBuffer::new(sym.solve_in_place_scratch::<f64>(1, super::par()));
        llt.l_transpose_solve_with_conj(Conj::No, x.as_mut(), super::par(), MemStack::new(&mut mem));
        let mut out = vec![0.0; y.len()];
        for (i, &f) in fwd.iter().enumerate() {
            out[f] = x[(i, 0)];
        }
        out
    }

    /// The fill-reducing order (forward, inverse): factor position i holds DOF fwd[i].
    fn perm(&self) -> (&[usize], &[usize]) {
        self.analysis
            .symbolic
            .perm()
            .expect("the ordering is always given")
            .arrays()
    }

    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut x = Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
        self.solve_in_place(x.as_mut());
        (0..b.len()).map(|i| x[(i, 0)]).collect()
    }

    /// (max L_ii / min L_ii)²: a cheap lower bound of the 2-norm condition number
    /// of K (the ratio of the factor's pivots), reported with every solve so
    /// that ill-conditioned scenes are visible.
    pub fn pivot_ratio(&self) -> f64 {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.analysis.symbolic.raw() else {
            unreachable!("factorization is forced supernodal")
        };
        let llt = SupernodalLltRef::new(sym, &self.values);
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for s in 0..sym.n_supernodes() {
            let val = llt.supernode(s).val();
            for j in 0..sym.supernode_end()[s] - sym.supernode_begin()[s] {
                let d = val[(j, j)].abs();
                lo = lo.min(d);
                hi = hi.max(d);
            }
        }
        if lo > 0.0 {
            (hi / lo).powi(2)
        } else {
            f64::INFINITY
        }
    }
}

/// Drops `values` on a thread of its own (inline when no thread can be
/// started: the closure that holds them is dropped then).
fn free_beside(values: Vec<f64>) {
    let _ = std::thread::Builder::new()
        .name("free-factor".into())
        .spawn(move || drop(values));
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::Triplet;

    /// A dense n×n SPD matrix (all couplings −1/n, diagonal 2) as a lower triangle.
    fn dense_spd(n: usize) -> SparseColMat<usize, f64> {
        let mut t = Vec::new();
        for j in 0..n {
            t.push(Triplet::new(j, j, 2.0));
            for i in j + 1..n {
                t.push(Triplet::new(i, j, -1.0 / n as f64));
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    /// The cost of a dense factor is known exactly: Σ_j c_j² = Σ_k k² =
    /// n(n+1)(2n+1)/6 however faer groups the supernodes, and the stored
    /// values lie between the triangle n(n+1)/2 and the square n² (a supernode
    /// keeps its diagonal block in full).
    #[test]
    fn the_predicted_cost_of_a_dense_factor_is_exact() {
        let n = 60;
        let chol = Cholesky::try_new(&dense_spd(n)).unwrap();
        let c = chol.cost();
        assert!(c.nnz >= n * (n + 1) / 2 && c.nnz <= n * n, "{}", c.nnz);
        let nf = n as f64;
        assert_eq!(c.flops, nf * (nf + 1.0) * (2.0 * nf + 1.0) / 6.0);
        assert!(c.predicted_secs() > 0.0);
    }

    /// With no time left the numeric factorization is not started: the refusal
    /// carries the prediction.
    #[test]
    fn a_factorization_that_cannot_end_in_time_is_not_started() {
        let k = dense_spd(60);
        let analysis = Arc::new(SymbolicFactor::try_new(&k).unwrap());
        let _d = crate::cancel::Deadline::install(std::time::Duration::ZERO);
        match Cholesky::with_symbolic(analysis, &k) {
            Err(LinalgError::Overrun { cost, left_s }) => {
                assert_eq!(left_s, 0.0);
                assert!(cost.flops > 0.0);
            }
            Err(e) => panic!("expected an overrun, got {e}"),
            Ok(_) => panic!("expected an overrun, got a factor"),
        }
    }

    #[test]
    fn indefinite_matrix_is_reported() {
        let t = [
            Triplet::new(0, 0, 1.0),
            Triplet::new(1, 0, 2.0),
            Triplet::new(1, 1, 1.0),
        ];
        let k = SparseColMat::<usize, f64>::try_new_from_triplets(2, 2, &t).unwrap();
        assert!(matches!(Cholesky::try_new(&k), Err(LinalgError::NotPositiveDefinite)));
    }

    /// One forward and one backward sweep are one solve, in the original
    /// order of the unknowns.
    #[test]
    fn forward_then_backward_is_a_solve() {
        let k = dense_spd(30);
        let chol = Cholesky::try_new(&k).unwrap();
        let b: Vec<f64> = (0..30).map(|i| (i as f64 * 0.7).sin()).collect();
        let x = chol.backward(&chol.forward(&b));
        let y = chol.solve(&b);
        for (a, c) in x.iter().zip(&y) {
            assert!((a - c).abs() < 1e-13, "{a} vs {c}");
        }
    }

    /// Two disconnected m×m grid Laplacians (plus a unit shift), lower
    /// triangle: a forest of two trees, many supernodes.
    fn two_grids(m: usize) -> SparseColMat<usize, f64> {
        let mut t = Vec::new();
        for g in 0..2 {
            let at = |i: usize, j: usize| g * m * m + i * m + j;
            for i in 0..m {
                for j in 0..m {
                    t.push(Triplet::new(at(i, j), at(i, j), 5.0));
                    if i + 1 < m {
                        t.push(Triplet::new(at(i + 1, j), at(i, j), -1.0));
                    }
                    if j + 1 < m {
                        t.push(Triplet::new(at(i, j + 1), at(i, j), -1.0));
                    }
                }
            }
        }
        SparseColMat::try_new_from_triplets(2 * m * m, 2 * m * m, &t).unwrap()
    }

    /// The sweep of a b with a few nonzeros in the first grid is the full
    /// sweep's (the same factor, additions in another order: round-off, far
    /// below 1e-13 of its largest entry for a factor this well conditioned),
    /// and exactly zero on the second grid, whose supernodes it never reaches.
    #[test]
    fn the_sparse_forward_sweep_is_the_full_one() {
        let m = 20;
        let chol = Cholesky::try_new(&two_grids(m)).unwrap();
        let mut b = vec![0.0; 2 * m * m];
        for (i, v) in [(3, 1.0), (m * 7 + 11, -2.5), (m * m - 1, 0.75)] {
            b[i] = v;
        }
        let (full, sparse) = (chol.forward(&b), chol.forward_sparse(&b));
        let scale = full.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (a, c) in full.iter().zip(&sparse) {
            assert!((a - c).abs() <= 1e-13 * scale, "{a} vs {c}");
        }
        let (_, inv) = chol.perm();
        for dof in m * m..2 * m * m {
            assert_eq!(sparse[inv[dof]], 0.0, "DOF {dof} of the second grid");
        }
    }
}
