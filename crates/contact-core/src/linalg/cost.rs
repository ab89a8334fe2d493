//! What a numeric factorization will cost (`FactorCost`, known from the
//! symbolic analysis) and how the linear algebra fails (`LinalgError`): read
//! by the symbolic analysis, the factorization and the solvers alike, so they
//! live apart from each (`FactorCost::predict`, which runs an analysis, is in
//! `cholesky`).

use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};

#[derive(Debug, thiserror::Error)]
pub enum LinalgError {
    #[error("stiffness matrix is not positive definite (a body is not fully supported, or the mesh is degenerate)")]
    NotPositiveDefinite,
    #[error("sparse factorization failed: {0}")]
    Faer(String),
    /// Clarabel refused to set the problem up (its own message).
    #[error("the interior point solver could not set the problem up: {0}")]
    Clarabel(String),
    /// The numeric factorization would not end within the time left.
    #[error(
        "the factorization was predicted to take {:.1} s (nnz(L) = {:.2e}, {:.2e} multiply-adds), more than the {:.1} \
            s left of the time limit: refused before starting it",
        cost.predicted_secs(),
        cost.nnz as f64,
        cost.flops,
        left_s
    )]
    Overrun { cost: FactorCost, left_s: f64 },
    /// An iterative solve stopped short of its tolerance.
    #[error(
        "{what}: GMRES reached a relative residual of {residual:.1e} in {steps} steps, not the {tolerance:.0e} asked"
    )]
    Iterative {
        what: &'static str,
        steps: usize,
        residual: f64,
        tolerance: f64,
    },
    /// The numeric factorization was stopped at the deadline (a `timeout`).
    #[error("the factorization was stopped at the time limit of {} s", .0.limit_s)]
    Deadline(crate::cancel::Timeout),
}

/// What a numeric factorization will cost, known from the symbolic analysis.
#[derive(Debug, Clone, Copy)]
pub struct FactorCost {
    /// Values stored for L (a supernode keeps its diagonal block in full).
    pub nnz: usize,
    /// Σ_j c_j² over the columns of L, c_j the column's entries (diagonal
    /// included): the multiply–adds of a column Cholesky.
    pub flops: f64,
}

impl FactorCost {
    pub fn of(symbolic: &SymbolicCholesky<usize>) -> Self {
        let SymbolicCholeskyRaw::Supernodal(sym) = symbolic.raw() else {
            unreachable!("factorization is forced supernodal")
        };
        let ptr = sym.col_ptr_for_row_idx();
        let mut flops = 0.0;
        for s in 0..sym.n_supernodes() {
            let w = (sym.supernode_end()[s] - sym.supernode_begin()[s]) as f64;
            let r = (ptr[s + 1] - ptr[s]) as f64;
            // Σ_{k=1..w} (k + r)², the supernode's columns from the last to the first.
            flops += w * (w + 1.0) * (2.0 * w + 1.0) / 6.0 + r * w * (w + 1.0) + r * r * w;
        }
        Self {
            nnz: symbolic.len_val(),
            flops,
        }
    }

    /// A numeric factorization does not poll the clock: start it only if it
    /// can end within the time left.
    pub fn fits_in_time_left(self) -> Result<(), LinalgError> {
        let left = crate::cancel::remaining_secs();
        if self.predicted_secs() > left {
            return Err(LinalgError::Overrun {
                cost: self,
                left_s: left,
            });
        }
        Ok(())
    }

    /// Seconds the numeric factorization is predicted to take on this
    /// machine: the reference machine's time times the scale learned here
    /// (`linalg::rate`).
    pub fn predicted_secs(&self) -> f64 {
        self.reference_secs() * super::rate::scale()
    }

    /// Seconds the numeric factorization takes on the reference machine (2
    /// cores, faer sequential supernodal), t = a·flops + b·nnz + c·flops·nnz:
    /// the last term is the loss of cache reuse once L outgrows memory
    /// bandwidth (measured 42 GFlop/s at nnz(L) = 4.9e8 against 56 at 1e8).
    /// Least-squares fit over 22 factorizations (T3 and T6; graded and uniform
    /// rectangles, half-disks; 12k to 2.1M DOF, 0.014 to 27 s): relative error
    /// within −15 %…+23 % (−13 % on the two 2M-DOF factors).
    pub fn reference_secs(&self) -> f64 {
        const PER_FLOP: f64 = 6.68e-12;
        const PER_ENTRY: f64 = 9.92e-9;
        const PER_FLOP_ENTRY: f64 = 1.72e-20;
        let nnz = self.nnz as f64;
        PER_FLOP * self.flops + PER_ENTRY * nnz + PER_FLOP_ENTRY * self.flops * nnz
    }
}
