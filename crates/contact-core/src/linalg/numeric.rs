//! The numeric supernodal Cholesky factorization, supernode by supernode, with
//! the clock checked between the updates (`cancel`): a factorization past its
//! deadline stops there and its partial factor is dropped.
//!
//! faer 0.24 does this in one call (`factorize_supernodal_numeric_llt`) with no
//! way to stop it: the one stage of a solve that did not poll, so a time limit
//! was overrun by up to a whole factorization (16 s at 2M DOF). This is the
//! same left-looking algorithm, step for step — each supernode gathers its
//! columns of P A Pᵀ, takes the update of every descendant through faer's own
//! gather–scatter product kernel (`private-gemm-x86`, the one faer calls for
//! f64 on AVX2/AVX-512), then factors its diagonal block and solves its
//! off-diagonal rows with faer's dense kernels — in the same order, so the
//! factor is bit for bit faer's (test `the_factor_is_faers_to_the_bit`). Without
//! AVX2 (no such kernel) faer's own call runs, unstoppable as before.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch, LltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::SparseColMatRef;
use faer::{MatMut, MatRef, Par, Side};

/// For each supernode s, the supernodes d < s whose row pattern meets s's
/// columns (they update s), in increasing order: faer keeps this as a private
/// row-major structure.
pub(crate) struct Descendants {
    ptr: Vec<usize>,
    idx: Vec<usize>,
}

impl Descendants {
    pub(crate) fn of(sym: &SymbolicSupernodalCholesky<usize>) -> Self {
        let ns = sym.n_supernodes();
        let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
        let mut owner = vec![0usize; sym.nrows()];
        for s in 0..ns {
            owner[begin[s]..end[s]].fill(s);
        }
        let mut ptr = vec![0usize; ns + 1];
        let each = |visit: &mut dyn FnMut(usize, usize)| {
            for d in 0..ns {
                let mut last = usize::MAX;
                for &row in pattern(sym, d) {
                    let s = owner[row];
                    if s != last {
                        visit(d, s);
                        last = s;
                    }
                }
            }
        };
        each(&mut |_, s| ptr[s + 1] += 1);
        for s in 0..ns {
            ptr[s + 1] += ptr[s];
        }
        let mut next = ptr.clone();
        let mut idx = vec![0usize; ptr[ns]];
        each(&mut |d, s| {
            idx[next[s]] = d;
            next[s] += 1;
        });
        Self { ptr, idx }
    }

    fn of_supernode(&self, s: usize) -> &[usize] {
        &self.idx[self.ptr[s]..self.ptr[s + 1]]
    }
}

/// The rows of supernode s below its diagonal block.
fn pattern(sym: &SymbolicSupernodalCholesky<usize>, s: usize) -> &[usize] {
    &sym.row_idx()[sym.col_ptr_for_row_idx()[s]..][..sym.nnz_per_super()[s]]
}

/// Why the factorization did not finish.
#[derive(Debug)]
pub(crate) enum Stop {
    NotPositiveDefinite,
    OutOfMemory,
    Deadline(crate::cancel::Timeout),
}

/// Multiply–adds between two looks at the clock: about 0.1 ms of work, so
/// the checks cost nothing measurable and the overshoot is one update or one
/// diagonal block (T3 grids of 0.5M–2M DOF stopped 5–27 ms past deadlines at
/// 25–75 % of their factorization: `examples/factor_rate.rs --stop`).
const WORK_BETWEEN_CHECKS: f64 = 1e6;

/// L's values (faer's supernodal layout) of P A Pᵀ, `a` the lower triangle
/// of A and `perm` the fill-reducing order, stopping at this thread's deadline.
pub(crate) fn factorize(
    values: &mut [f64],
    a: SparseColMatRef<'_, usize, f64>,
    perm: PermRef<'_, usize>,
    sym: &SymbolicSupernodalCholesky<usize>,
    descendants: &Descendants,
    par: Par,
) -> Result<(), Stop> {
    let n = a.nrows();
    let a_nnz = a.compute_nnz();
    let ns = sym.n_supernodes();
    let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
    let mut chol = StackReq::EMPTY;
    for s in 0..ns {
        chol = chol.or(cholesky_in_place_scratch::<f64>(
            end[s] - begin[s],
            par,
            Default::default(),
        ));
    }
    // P A Pᵀ first, in memory left uninitialized until written, as faer's
    // own call keeps it: zeroed first (two more passes over it), the 1M-DOF
    // grid's factorization took 2.6–4.6 % more CPU time than faer's, against
    // 0.7–0.9 % less without.
    let req = StackReq::new::<f64>(a_nnz)
        .and(StackReq::new::<usize>(n + 1))
        .and(StackReq::new::<usize>(a_nnz))
        .and(chol.or(faer::sparse::utils::permute_self_adjoint_scratch::<usize>(n)));
    let mut mem = MemBuffer::try_new(req).map_err(|_| Stop::OutOfMemory)?;
    let stack = MemStack::new(&mut mem);
    // SAFETY: f64 and usize are plain data, valid whatever their bits, and
    // the permutation writes every entry of the matrix it returns.
    let (pval, stack) = unsafe { stack.make_raw::<f64>(a_nnz) };
    let (pcol, stack) = unsafe { stack.make_raw::<usize>(n + 1) };
    let (prow, stack) = unsafe { stack.make_raw::<usize>(a_nnz) };
    // P A Pᵀ, lower triangle, exactly as faer's own numeric factorization makes it.
    let pa_mut = faer::sparse::utils::permute_self_adjoint_to_unsorted(
        pval,
        pcol,
        prow,
        a,
        perm,
        Side::Lower,
        Side::Lower,
        stack,
    );
    let pa = faer::reborrow::IntoConst::into_const(pa_mut);
    let Some(gemm) = Gemm::detect() else {
        use faer::sparse::linalg::cholesky::supernodal as faer_supernodal;
        // faer's product without the gather–scatter kernel needs scratch of its own.
        let req = faer_supernodal::factorize_supernodal_numeric_llt_scratch::<usize, f64>(sym, par, Default::default());
        let mut mem = MemBuffer::try_new(req).map_err(|_| Stop::OutOfMemory)?;
        return faer_supernodal::factorize_supernodal_numeric_llt(
            values,
            pa,
            LltRegularization::default(),
            sym,
            par,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .map(|_| ())
        .map_err(|_| Stop::NotPositiveDefinite);
    };
    crate::cancel::check(crate::outcome::ProgressStage::Factorization).map_err(Stop::Deadline)?;
    let col_ptr_val = sym.col_ptr_for_val();
    const NONE: usize = usize::MAX;
    let mut global_to_local = vec![NONE; n];
    let (mut row_idx, mut col_idx) = (Vec::<usize>::new(), Vec::<usize>::new());
    // The factorization's multiply–adds in all (`FactorCost`'s count): the
    // share done moves the progress bar through the stage that is most of a
    // large solve (it sat at one value for 6 s at 1M DOF).
    let total: f64 = (0..ns)
        .map(|s| {
            let (w, r) = ((end[s] - begin[s]) as f64, pattern(sym, s).len() as f64);
            w * (w + 1.0) * (2.0 * w + 1.0) / 6.0 + r * w * (w + 1.0) + r * r * w
        })
        .sum();
    let (mut work, mut done) = (0.0, 0.0);
    let mut check = |w: f64| -> Result<(), Stop> {
        work += w;
        if work >= WORK_BETWEEN_CHECKS {
            done += work;
            work = 0.0;
            crate::cancel::check(crate::outcome::ProgressStage::Factorization).map_err(Stop::Deadline)?;
            crate::progress::within(done / total.max(1.0));
        }
        Ok(())
    };
    for s in 0..ns {
        let (s_start, s_end) = (begin[s], end[s]);
        let s_pattern = pattern(sym, s);
        let s_ncols = s_end - s_start;
        let s_nrows = s_pattern.len() + s_ncols;
        for (i, &row) in s_pattern.iter().enumerate() {
            global_to_local[row] = i + s_ncols;
        }
        let (head, tail) = values.split_at_mut(col_ptr_val[s]);
        let head: &[f64] = head;
        // Zeroed here rather than all at once before the loop as faer does
        // (the same zeros under the same sums): the first touch of a 2.4 GB
        // factor's pages takes a large part of a second, which the clock sees here.
        let block = &mut tail[..col_ptr_val[s + 1] - col_ptr_val[s]];
        block.fill(0.0);
        let mut ls = MatMut::from_column_major_slice_mut(block, s_nrows, s_ncols);
        for j in s_start..s_end {
            let j_shifted = j - s_start;
            for (&i, &val) in pa.row_idx_of_col_raw(j).iter().zip(pa.val_of_col(j)) {
                if i < j {
                    continue;
                }
                let ix = if i >= s_end { global_to_local[i] } else { i - s_start };
                ls[(ix, j_shifted)] += val;
            }
        }
        for &d in descendants.of_supernode(s) {
            let (d_start, d_end) = (begin[d], end[d]);
            let d_pattern = pattern(sym, d);
            let d_ncols = d_end - d_start;
            let d_nrows = d_pattern.len() + d_ncols;
            let ld = MatRef::from_column_major_slice(&head[col_ptr_val[d]..col_ptr_val[d + 1]], d_nrows, d_ncols);
            let d_pattern_start = d_pattern.partition_point(|&i| i < s_start);
            let d_pattern_mid_len = d_pattern[d_pattern_start..].partition_point(|&i| i < s_end);
            let (_, ld_mid_bot) = ld.split_at_row(d_ncols);
            let (_, ld_mid_bot) = ld_mid_bot.split_at_row(d_pattern_start);
            let (ld_mid, _) = ld_mid_bot.split_at_row(d_pattern_mid_len);
            row_idx.clear();
            row_idx.extend(d_pattern[d_pattern_start..].iter().enumerate().map(|(i, &row)| {
                if i < d_pattern_mid_len {
                    row - s_start
                } else {
                    global_to_local[row]
                }
            }));
            col_idx.clear();
            col_idx.extend(
                d_pattern[d_pattern_start..][..d_pattern_mid_len]
                    .iter()
                    .map(|&c| c - s_start),
            );
            gemm.lower_update(ls.as_mut(), &row_idx, &col_idx, ld_mid_bot, ld_mid.transpose(), par);
            check((row_idx.len() * col_idx.len() * d_ncols) as f64)?;
        }
        let (mut ls_top, mut ls_bot) = ls.as_mut().split_at_row_mut(s_ncols);
        cholesky_in_place(
            ls_top.as_mut(),
            LltRegularization::default(),
            par,
            stack,
            Default::default(),
        )
        .map_err(|_| Stop::NotPositiveDefinite)?;
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            ls_top.as_ref().conjugate(),
            ls_bot.as_mut().transpose_mut(),
            par,
        );
        for &row in s_pattern {
            global_to_local[row] = NONE;
        }
        let (w, r) = (s_ncols as f64, s_pattern.len() as f64);
        // The block's own factorization and solve, and its first touch.
        check(w * w * (w / 3.0 + r) + w * (w + r))?;
    }
    Ok(())
}

/// faer's gather–scatter product C[row_idx, col_idx] −= A B (lower part of
/// C), on the instruction set faer itself would pick.
#[derive(Clone, Copy)]
struct Gemm {
    #[cfg(target_arch = "x86_64")]
    instr: private_gemm_x86::InstrSet,
}

impl Gemm {
    #[cfg(target_arch = "x86_64")]
    fn detect() -> Option<Self> {
        use private_gemm_x86::InstrSet;
        let instr = if std::arch::is_x86_feature_detected!("avx512f") {
            InstrSet::Avx512
        } else if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
            InstrSet::Avx256
        } else {
            return None;
        };
        Some(Self { instr })
    }

    #[cfg(not(target_arch = "x86_64"))]
    fn detect() -> Option<Self> {
        None
    }

    #[cfg(target_arch = "x86_64")]
    fn lower_update(
        self,
        c: MatMut<'_, f64>,
        row_idx: &[usize],
        col_idx: &[usize],
        a: MatRef<'_, f64>,
        b: MatRef<'_, f64>,
        par: Par,
    ) {
        let (nrows, ncols, depth) = (a.nrows(), b.ncols(), a.ncols());
        assert!(b.nrows() == depth && row_idx.len() == nrows && col_idx.len() == ncols);
        if nrows == 0 || ncols == 0 {
            return;
        }
        // The kernel writes through raw indices: they must lie in C.
        assert!(row_idx.iter().all(|&i| i < c.nrows()) && col_idx.iter().all(|&j| j < c.ncols()));
        // faer's threshold for threading a product (`spicy_matmul`).
        let par = if (nrows * ncols).saturating_mul(depth) > 32 * 32 * 32 {
            par
        } else {
            Par::Seq
        };
        let alpha = -1.0f64;
        // SAFETY: the dimensions and strides are those of the views, every
        // index is inside C (checked above), and the kernel reads and writes
        // nothing else: the call faer's `spicy_matmul` makes for f64.
        unsafe {
            private_gemm_x86::gemm(
                private_gemm_x86::DType::F64,
                private_gemm_x86::IType::U64,
                self.instr,
                nrows,
                ncols,
                depth,
                c.as_ptr_mut() as _,
                c.row_stride(),
                c.col_stride(),
                row_idx.as_ptr() as _,
                col_idx.as_ptr() as _,
                private_gemm_x86::DstKind::Lower,
                private_gemm_x86::Accum::Add,
                a.as_ptr() as _,
                a.row_stride(),
                a.col_stride(),
                false,
                core::ptr::null(),
                0,
                b.as_ptr() as _,
                b.row_stride(),
                b.col_stride(),
                true,
                &raw const alpha as _,
                par.degree(),
            );
        }
    }

    #[cfg(not(target_arch = "x86_64"))]
    fn lower_update(
        self,
        _: MatMut<'_, f64>,
        _: &[usize],
        _: &[usize],
        _: MatRef<'_, f64>,
        _: MatRef<'_, f64>,
        _: Par,
    ) {
        unreachable!("no kernel: detect() gave None")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::cholesky::{Cholesky, SymbolicFactor};

    /// The factorization runs faer's supernodal loop itself (to look at the
    /// clock between updates) with faer's kernels in faer's order: the factor
    /// is faer's one-call factor to the last bit (a 6000-DOF T3 grid, whose
    /// supernodes take updates from many descendants).
    #[test]
    fn the_factor_is_faers_to_the_bit() {
        let k = crate::linalg::rate::grid_stiffness(60, 50);
        let chol = Cholesky::try_new(&k).unwrap();
        let symbolic = chol.analysis().symbolic();
        let mut theirs = vec![0.0; symbolic.len_val()];
        let par = faer::Par::Seq;
        let mut mem = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        symbolic
            .factorize_numeric_llt(
                &mut theirs,
                k.as_ref(),
                Side::Lower,
                faer::linalg::cholesky::llt::factor::LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .unwrap();
        assert_eq!(chol.values().len(), theirs.len());
        let differ = chol
            .values()
            .iter()
            .zip(&theirs)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert_eq!(differ, 0, "entries of L differing from faer's");
    }

    /// A factorization under way when the deadline passes stops at the next
    /// look at the clock (here the first: the deadline has passed already)
    /// and is the solve's `timeout` in the factorization stage.
    #[test]
    fn a_factorization_past_its_deadline_is_stopped() {
        let k = crate::linalg::rate::grid_stiffness(60, 50);
        let analysis = SymbolicFactor::try_new(&k).unwrap();
        let mut values = vec![0.0; analysis.symbolic().len_val()];
        let _d = crate::cancel::Deadline::install(std::time::Duration::ZERO);
        // Called below the prediction check, which would refuse to start.
        let r = factorize(
            &mut values,
            k.as_ref(),
            analysis.symbolic().perm().unwrap(),
            analysis.supernodal(),
            analysis.descendants(),
            faer::Par::Seq,
        );
        let Err(Stop::Deadline(t)) = r else {
            panic!("expected a stop at the deadline, got {r:?}")
        };
        let e = crate::error::CoreError::from(crate::linalg::LinalgError::Deadline(t));
        assert_eq!(
            (e.code(), t.stage),
            ("timeout", crate::outcome::ProgressStage::Factorization)
        );
    }
}
