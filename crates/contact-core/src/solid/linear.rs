//! The linear solve of a supported body: K_ff u_f = f_f − K_fd u_d with the
//! sparse Cholesky of `linalg::cholesky` (supernodal, in the nested-dissection
//! order of `ordering`), and the
//! reactions r = K u − f on the supported DOFs.

use super::dofs::{dof_map, SolidDofs};
use super::{loads, ordering, stiffness, SolidBody};
use crate::error::CoreError;
use crate::linalg::cholesky::SymbolicFactor;
use crate::linalg::Cholesky;
use crate::outcome::ProgressStage;
use std::sync::Arc;

/// Displacements and reactions of a body its supports hold.
#[derive(Debug, Clone)]
pub struct Static {
    /// u on every DOF (3·node + c).
    pub u: Vec<f64>,
    /// Support reactions on every DOF (0 off the supports).
    pub reactions: Vec<f64>,
    /// ‖K u − f‖∞ on the free DOFs over max(‖f‖∞, ‖|K||u|‖∞): the normwise
    /// backward error of the solve.
    pub residual: f64,
    pub dofs: SolidDofs,
    /// Seconds of assembly, factorization (symbolic and numeric) and solve.
    pub seconds: [f64; 3],
}

/// Solves the body under its loads; supports that leave a rigid motion free
/// are refused (`no_support`, see `dofs`).
pub fn solve(body: &SolidBody) -> Result<Static, CoreError> {
    let t0 = std::time::Instant::now();
    let dofs = dof_map(body, None)?;
    let k = stiffness::assemble(body, &dofs)?;
    let f_ext = loads::external(body)?;
    let f = loads::free_rhs(&f_ext, &dofs, &k);
    let t1 = std::time::Instant::now();
    let (fwd, inv) = ordering::nested_dissection(body.mesh, &dofs)?;
    let chol = Cholesky::with_symbolic(Arc::new(SymbolicFactor::try_new_ordered(&k.k, &fwd, &inv)?), &k.k)?;
    let t2 = std::time::Instant::now();
    let u = loads::full_field(&dofs, &chol.solve(&f));
    let t3 = std::time::Instant::now();
    let (ku, abs) = stiffness::internal_forces(body, &u, ProgressStage::Post)?;
    let mut reactions = vec![0.0; u.len()];
    let mut worst: f64 = 0.0;
    for d in 0..u.len() {
        let r = ku[d] - f_ext[d];
        if dofs.supported[d] {
            reactions[d] = r;
        } else {
            worst = worst.max(r.abs());
        }
    }
    let size = inf_norm(&f_ext).max(inf_norm(&abs)).max(f64::MIN_POSITIVE);
    Ok(Static {
        u,
        reactions,
        residual: worst / size,
        dofs,
        seconds: [t1 - t0, t2 - t1, t3 - t2].map(|d| d.as_secs_f64()),
    })
}

pub(crate) fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |a, x| a.max(x.abs()))
}
