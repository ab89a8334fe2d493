//! The values-independent start of a sparse Cholesky: the fill-reducing
//! AMD ordering and faer's supernodal symbolic factorization in it, each
//! predicted against the deadline before it starts (neither polls).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::{amd, SupernodalThreshold};
use faer::sparse::SparseColMat;
use faer::Side;

use super::cost::LinalgError;

/// Seconds per unknown of the AMD ordering and of faer's symbolic
/// factorization after it, on the machine the factorization's cost was
/// fitted on (T3 grids: 0.55 s then 0.47 s at 1M DOF, 1.07 s then 0.92 s at
/// 2M); times `rate::scale()` on this one.
const ORDERING_PER_DOF: f64 = 0.55e-6;
const SYMBOLIC_PER_DOF: f64 = 0.47e-6;

/// Supernodal symbolic factorization of `a` in AMD order.
pub(super) fn symbolic(a: &SparseColMat<usize, f64>) -> Result<SymbolicCholesky<usize>, LinalgError> {
    // Neither stage polls: one predicted past the deadline is not started (a
    // 1.5 s limit on a graded block was answered after 2.9–3.3 s, 1.7 s of
    // it in the ordering).
    let predicted = (ORDERING_PER_DOF + SYMBOLIC_PER_DOF) * a.nrows() as f64 * super::rate::scale();
    crate::cancel::check_room(crate::outcome::ProgressStage::Factorization, predicted)
        .map_err(LinalgError::Deadline)?;
    let started = std::time::Instant::now();
    let (fwd, inv) = ordering(a)?;
    // Neither the ordering nor faer's symbolic factorization after it polls
    // (measured on T3 grids: 0.55 s then 0.47 s at 1M DOF, 1.07 s then 0.92 s
    // at 2M): a deadline passed during the ordering stops the solve here, and
    // so does one the symbolic factorization, about as long, would pass.
    let took = started.elapsed().as_secs_f64();
    crate::cancel::check(crate::outcome::ProgressStage::Factorization).map_err(LinalgError::Deadline)?;
    crate::cancel::check_room(crate::outcome::ProgressStage::Factorization, took).map_err(LinalgError::Deadline)?;
    in_order(a, &fwd, &inv)
}

/// Supernodal symbolic factorization of `a` in a given fill-reducing order
/// (`fwd[i]`: the unknown at position i, `inv` its inverse).
pub(super) fn in_order(
    a: &SparseColMat<usize, f64>,
    fwd: &[usize],
    inv: &[usize],
) -> Result<SymbolicCholesky<usize>, LinalgError> {
    let perm = PermRef::new_checked(fwd, inv, a.nrows());
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    factorize_symbolic_cholesky(a.symbolic(), Side::Lower, SymmetricOrdering::Custom(perm), params)
        .map_err(|e| LinalgError::Faer(format!("{e:?}")))
}

fn ordering(a: &SparseColMat<usize, f64>) -> Result<(Vec<usize>, Vec<usize>), LinalgError> {
    let n = a.nrows();
    let sym = a.symbolic();
    let nnz = sym.compute_nnz();
    let req = amd::order_maybe_unsorted_scratch::<usize>(n, nnz);
    let mut mem = MemBuffer::try_new(req).map_err(|_| LinalgError::Faer("out of memory".into()))?;
    let (mut fwd, mut inv) = (vec![0usize; n], vec![0usize; n]);
    amd::order_maybe_unsorted(
        &mut fwd,
        &mut inv,
        sym,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| LinalgError::Faer(format!("{e:?}")))?;
    Ok((fwd, inv))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ordering predicted past the deadline is not started: a 400 × 400
    /// node grid (320k DOF, about 0.33 s of ordering and symbolic analysis
    /// predicted) with 1 ms left is refused at once, long before the
    /// ordering alone could have ended.
    #[test]
    fn an_ordering_that_cannot_end_in_time_is_not_started() {
        let a = super::super::rate::grid_stiffness(400, 400);
        let _deadline = crate::cancel::Deadline::install(std::time::Duration::from_millis(1));
        let t = std::time::Instant::now();
        let r = symbolic(&a);
        assert!(matches!(r, Err(LinalgError::Deadline(_))), "{:?}", r.err());
        let predicted_ordering = ORDERING_PER_DOF * a.nrows() as f64;
        assert!(t.elapsed().as_secs_f64() < 0.1 * predicted_ordering);
    }
}
