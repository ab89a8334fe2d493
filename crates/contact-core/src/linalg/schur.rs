//! The condensed contact operator W = B K⁻¹ Bᵀ on the plain fill-reducing
//! factor of K, from the reach of the contact rows.
//!
//! With P K Pᵀ = L Lᵀ, W = Xᵀ X for X = L⁻¹ P Bᵀ. A row of B touches the DOFs
//! of one node (or of one element, or of two bodies); L⁻¹ of it is nonzero
//! only on the supernodes from those DOFs up to the root of the elimination
//! tree (Gilbert's reach), so X is formed supernode by supernode on the union
//! of those paths. Numbering the rows by the postorder of their first
//! supernode makes the rows reaching a supernode one contiguous range, so
//! each supernode holds one dense block of X: one triangular solve with its
//! diagonal block, one product with its off-diagonal block scattered into
//! its ancestors, and its share of the Gram product. The same blocks give
//! B K⁻¹ f = Xᵀ (L⁻¹ P f) and u = Pᵀ L⁻ᵀ (L⁻¹ P f − X λ): one forward and one
//! backward sweep per solve.
//!
//! Ordering the contact DOFs last instead (the trailing block of L is then
//! the Schur complement's factor) costs more: measured on the Hertz block at
//! 1.2M DOF with 1371 rows, 1.70e11 more multiply–adds in the factorization
//! and 7.7e9 in the condensation, against 3.6e10 here.

use faer::linalg::matmul::triangular::{matmul as triangular_matmul, BlockStructure};
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Accum, Mat};

use super::cholesky::{Cholesky, SymbolicFactor};
use crate::cancel::Timeout;

const NONE: usize = usize::MAX;

/// A row's DOFs on one path of the elimination tree: (row, first supernode,
/// (factor position, coefficient) entries).
type Part = (usize, usize, Vec<(usize, f64)>);

/// Where the contact rows reach in the factor: the structure of X, known from
/// the symbolic analysis alone.
pub struct Reach {
    /// Supernode of every factor position.
    supernode_of: Vec<usize>,
    /// Per part (a row's DOFs on one path of the tree, in postorder of their
    /// first supernode): the row it belongs to and its (factor position,
    /// value) entries.
    owner: Vec<usize>,
    entries: Vec<Vec<(usize, f64)>>,
    /// Per supernode: the first part reaching it and how many do.
    lo: Vec<usize>,
    k: Vec<usize>,
    rows: usize,
    flops: f64,
}

impl Reach {
    /// The reach of `rows` (each a list of (DOF, coefficient)) in `analysis`.
    pub fn new(analysis: &SymbolicFactor, rows: &[&[(usize, f64)]]) -> Self {
        let sym = analysis.supernodal();
        let pos = analysis.positions();
        let ns = sym.n_supernodes();
        let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
        let ptr = sym.col_ptr_for_row_idx();
        let row_idx = sym.row_idx();
        let mut supernode_of = vec![0; pos.len()];
        for s in 0..ns {
            supernode_of[begin[s]..end[s]].fill(s);
        }
        // A supernode's parent holds the first row of its pattern.
        let parent: Vec<usize> = (0..ns)
            .map(|s| {
                if ptr[s + 1] > ptr[s] {
                    supernode_of[row_idx[ptr[s]]]
                } else {
                    NONE
                }
            })
            .collect();
        let (rank, first) = postorder(&parent);
        let is_ancestor_or_self = |a: usize, s: usize| first[a] <= rank[s] && rank[s] <= rank[a];

        // Split each row into parts that lie on one path: entries in
        // increasing position, each joining the first part below it.
        let mut parts: Vec<Part> = Vec::with_capacity(rows.len());
        for (i, row) in rows.iter().enumerate() {
            let mut ents: Vec<(usize, f64)> = row.iter().map(|&(d, v)| (pos[d], v)).collect();
            ents.sort_by_key(|e| e.0);
            let start = parts.len();
            for (p, v) in ents {
                let s = supernode_of[p];
                match parts[start..]
                    .iter_mut()
                    .find(|(_, home, _)| is_ancestor_or_self(s, *home))
                {
                    Some(part) => part.2.push((p, v)),
                    None => parts.push((i, s, vec![(p, v)])),
                }
            }
        }
        parts.sort_by_key(|(_, home, _)| rank[*home]);
        // below[r]: parts whose first supernode ranks below r.
        let mut below = vec![0usize; ns + 1];
        for (_, home, _) in &parts {
            below[rank[*home] + 1] += 1;
        }
        for r in 0..ns {
            below[r + 1] += below[r];
        }
        let lo: Vec<usize> = (0..ns).map(|s| below[first[s]]).collect();
        let k: Vec<usize> = (0..ns).map(|s| below[rank[s] + 1] - lo[s]).collect();
        let mut flops = 0.0;
        for s in 0..ns {
            let (w, r, kf) = ((end[s] - begin[s]) as f64, (ptr[s + 1] - ptr[s]) as f64, k[s] as f64);
            flops += kf * (0.5 * w * (w + 1.0) + w * r) + 0.5 * w * kf * (kf + 1.0);
        }
        let (owner, entries) = parts.into_iter().map(|(i, _, e)| (i, e)).unzip();
        Self {
            supernode_of,
            owner,
            entries,
            lo,
            k,
            rows: rows.len(),
            flops,
        }
    }

    /// Multiply–adds of `condense`: the triangular solves, the updates of the
    /// ancestors and the Gram product (its lower half).
    pub fn flops(&self) -> f64 {
        self.flops
    }

    /// X = L⁻¹ P Bᵀ on its reach, and W = Xᵀ X.
    pub fn condense(self, chol: &Cholesky) -> Result<Condensed, Timeout> {
        let llt = chol.supernodes();
        let sym = chol.analysis().supernodal();
        let begin = sym.supernode_begin();
        let ns = self.k.len();
        let par = super::par();
        let mut x: Vec<Mat<f64>> = (0..ns)
            .map(|s| {
                Mat::zeros(
                    if self.k[s] > 0 {
                        sym.supernode_end()[s] - begin[s]
                    } else {
                        0
                    },
                    self.k[s],
                )
            })
            .collect();
        for (j, part) in self.entries.iter().enumerate() {
            for &(p, v) in part {
                let s = self.supernode_of[p];
                x[s][(p - begin[s], j - self.lo[s])] += v;
            }
        }
        for s in 0..ns {
            let k = self.k[s];
            if k == 0 {
                continue;
            }
            let node = llt.supernode(s);
            let val = node.val();
            let w = val.ncols();
            let (diag, below) = val.split_at_row(w);
            solve_lower_triangular_in_place(diag, x[s].as_mut(), par);
            let pattern = node.pattern();
            if pattern.is_empty() {
                continue;
            }
            let mut t = Mat::<f64>::zeros(pattern.len(), k);
            faer::linalg::matmul::matmul(t.as_mut(), Accum::Replace, below, x[s].as_ref(), 1.0, par);
            for (row, &p) in pattern.iter().enumerate() {
                let a = self.supernode_of[p];
                let (r, off) = (p - begin[a], self.lo[s] - self.lo[a]);
                let xa = &mut x[a];
                for c in 0..k {
                    xa[(r, off + c)] -= t[(row, c)];
                }
            }
            // Every supernode with work (a look at the clock is ~25 ns beside
            // its dense products): one in 256 let a deadline at 0.5M DOF be
            // seen 0.20 s late, the top supernodes holding most of the work.
            crate::cancel::check(crate::outcome::ProgressStage::Condensation)?;
        }
        let np = self.owner.len();
        let mut g = Mat::<f64>::zeros(np, np);
        for (s, xs) in x.iter().enumerate() {
            let (lo, k) = (self.lo[s], self.k[s]);
            if k == 0 {
                continue;
            }
            triangular_matmul(
                g.as_mut().submatrix_mut(lo, lo, k, k),
                BlockStructure::TriangularLower,
                Accum::Add,
                xs.transpose(),
                BlockStructure::Rectangular,
                xs.as_ref(),
                BlockStructure::Rectangular,
                1.0,
                par,
            );
        }
        // W = Eᵀ G E (E: parts to rows) from G's lower half: every term goes
        // to both W_ij and W_ji in the same order, so W is exactly symmetric.
        let mut w = Mat::<f64>::zeros(self.rows, self.rows);
        for b in 0..np {
            for a in b..np {
                let (i, j) = (self.owner[a], self.owner[b]);
                let v = g[(a, b)];
                w[(i, j)] += v;
                if a != b {
                    w[(j, i)] += v;
                }
            }
        }
        let blocks = x
            .into_iter()
            .enumerate()
            .filter(|(s, _)| self.k[*s] > 0)
            .map(|(s, xs)| (begin[s], self.lo[s], xs))
            .collect();
        Ok(Condensed {
            w,
            blocks,
            owner: self.owner,
        })
    }
}

/// Ranks in a postorder of the forest `parent` (children before parents,
/// every subtree a contiguous range) and the first rank of every subtree.
fn postorder(parent: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let n = parent.len();
    let (mut head, mut next) = (vec![NONE; n], vec![NONE; n]);
    for s in (0..n).rev() {
        if parent[s] != NONE {
            next[s] = head[parent[s]];
            head[parent[s]] = s;
        }
    }
    let (mut rank, mut first) = (vec![0; n], vec![0; n]);
    let mut r = 0;
    let mut stack = Vec::new();
    for root in (0..n).filter(|&s| parent[s] == NONE) {
        stack.push((root, r));
        while let Some(&(s, _)) = stack.last() {
            let child = head[s];
            if child != NONE {
                head[s] = next[child];
                stack.push((child, r));
            } else {
                let (s, start) = stack.pop().expect("nonempty");
                rank[s] = r;
                first[s] = start;
                r += 1;
            }
        }
    }
    (rank, first)
}

/// X on its reach and W = Xᵀ X, for the sweeps of every later solve.
pub struct Condensed {
    pub w: Mat<f64>,
    /// (first factor position, first part, block of X) per supernode reached.
    blocks: Vec<(usize, usize, Mat<f64>)>,
    owner: Vec<usize>,
}

impl Condensed {
    /// Xᵀ y summed per row: B K⁻¹ f for the forward sweep y = L⁻¹ P f.
    pub fn rows_of(&self, y: &[f64]) -> Vec<f64> {
        let mut parts = vec![0.0; self.owner.len()];
        for (b, lo, x) in &self.blocks {
            for c in 0..x.ncols() {
                let col = x.col(c);
                parts[lo + c] += (0..x.nrows()).map(|i| col[i] * y[b + i]).sum::<f64>();
            }
        }
        let mut out = vec![0.0; self.w.nrows()];
        for (j, v) in parts.into_iter().enumerate() {
            out[self.owner[j]] += v;
        }
        out
    }

    /// y − X λ: the forward sweep of f − Bᵀ λ from that of f.
    pub fn subtract(&self, lambda: &[f64], y: &mut [f64]) {
        for (b, lo, x) in &self.blocks {
            for c in 0..x.ncols() {
                let l = lambda[self.owner[lo + c]];
                if l != 0.0 {
                    let col = x.col(c);
                    for i in 0..x.nrows() {
                        y[b + i] -= col[i] * l;
                    }
                }
            }
        }
    }

    /// Values held (X's blocks and W), for the cache's bound.
    pub fn stored_values(&self) -> usize {
        self.w.nrows() * self.w.ncols() + self.blocks.iter().map(|(_, _, x)| x.nrows() * x.ncols()).sum::<usize>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};

    /// Two disconnected 2D grid Laplacians (plus a shift), n×n each, lower
    /// triangle: a forest of two trees.
    fn two_grids(n: usize) -> SparseColMat<usize, f64> {
        let mut t = Vec::new();
        for g in 0..2 {
            let o = g * n * n;
            for i in 0..n {
                for j in 0..n {
                    let d = o + i * n + j;
                    t.push(Triplet::new(d, d, 4.1));
                    if j + 1 < n {
                        t.push(Triplet::new(d + 1, d, -1.0));
                    }
                    if i + 1 < n {
                        t.push(Triplet::new(d + n, d, -1.0));
                    }
                }
            }
        }
        SparseColMat::try_new_from_triplets(2 * n * n, 2 * n * n, &t).unwrap()
    }

    /// W, B K⁻¹ f and the solve after subtracting X λ equal what plain solves
    /// give, for rows on one DOF, on two neighbours and across the two
    /// disconnected grids (rows split into parts).
    #[test]
    fn condensed_operator_equals_plain_solves() {
        let n = 9;
        let k = two_grids(n);
        let dim = k.nrows();
        let chol = Cholesky::try_new(&k).unwrap();
        let rows: Vec<Vec<(usize, f64)>> = vec![
            vec![(4, 1.0)],
            vec![(40, 0.6), (41, -0.8)],
            vec![(8, 0.5), (n * n + 3, -0.5)],
            vec![(n * n + 70, 1.0), (60, 0.3), (n * n + 71, 0.2)],
            vec![(17, -1.0)],
        ];
        let refs: Vec<&[(usize, f64)]> = rows.iter().map(|r| r.as_slice()).collect();
        let reach = Reach::new(chol.analysis(), &refs);
        assert!(reach.flops() > 0.0);
        let cond = reach.condense(&chol).unwrap();
        let bt = |i: usize| {
            let mut v = vec![0.0; dim];
            for &(d, c) in &rows[i] {
                v[d] += c;
            }
            v
        };
        let apply = |i: usize, u: &[f64]| rows[i].iter().map(|&(d, c)| c * u[d]).sum::<f64>();
        for i in 0..rows.len() {
            let x = chol.solve(&bt(i));
            for j in 0..rows.len() {
                let expect = apply(j, &x);
                assert!(
                    (cond.w[(j, i)] - expect).abs() < 1e-14,
                    "W[{j},{i}] {} vs {expect}",
                    cond.w[(j, i)]
                );
            }
        }
        let f: Vec<f64> = (0..dim).map(|i| (0.37 * i as f64).sin()).collect();
        let y = chol.forward(&f);
        let u0 = chol.solve(&f);
        let bu0 = cond.rows_of(&y);
        for (i, v) in bu0.iter().enumerate() {
            assert!((v - apply(i, &u0)).abs() < 1e-14, "row {i}: {v} vs {}", apply(i, &u0));
        }
        let lambda = [0.3, 0.0, 1.2, -0.4, 2.0];
        let mut y2 = y.clone();
        cond.subtract(&lambda, &mut y2);
        let u = chol.backward(&y2);
        let mut rhs = f.clone();
        for (i, l) in lambda.iter().enumerate() {
            for &(d, c) in &rows[i] {
                rhs[d] -= l * c;
            }
        }
        let expect = chol.solve(&rhs);
        for (a, b) in u.iter().zip(&expect) {
            assert!((a - b).abs() < 1e-13, "{a} vs {b}");
        }
    }

    /// Subtrees are contiguous ranges of a postorder.
    #[test]
    fn postorder_ranks_subtrees_contiguously() {
        //      4       6
        //    /   \     |
        //   1     3    5
        //   |    / \
        //   0   2   7
        let parent = [1, 4, 3, 4, NONE, 6, NONE, 3];
        let (rank, first) = postorder(&parent);
        for s in 0..parent.len() {
            let mut size = 1;
            let mut stack: Vec<usize> = (0..parent.len()).filter(|&c| parent[c] == s).collect();
            while let Some(c) = stack.pop() {
                size += 1;
                assert!(first[s] <= rank[c] && rank[c] < rank[s], "{c} in subtree of {s}");
                stack.extend((0..parent.len()).filter(|&d| parent[d] == c));
            }
            assert_eq!(rank[s] + 1 - first[s], size, "subtree of {s}");
        }
    }
}
