//! What the energy bound needs of a solved answer, kept with its report until
//! the answer is known to be the one returned: with `settings.accuracy` a
//! round is final only once its own estimate is read, after its solve, and a
//! bound made with every round (12–32 % of each round's solve, two measurements at load 5–7) was thrown
//! away with every round but the last. `adapt` makes the bound from this
//! (`Estimator::energy`) for the answer it returns, and for no other.

use std::sync::Arc;

use faer::sparse::SparseColMat;

use super::{bound, EnergyBound};
use crate::linalg::Cholesky;
use crate::model::Model;
use crate::scene::Scene;

/// The stiffness and its factor of a solve (the condensed route's operator).
pub trait Operator: Send + Sync {
    fn stiffness(&self) -> &SparseColMat<usize, f64>;
    fn factor(&self) -> &Cholesky;
}

/// A solved answer the bound covers, with the model, the operator and the
/// fields it is made from. It holds the answer's factor while it is kept: a
/// refinement round's factor stays beside its coarser companion's while that
/// solves (about a quarter of the round's unknowns), and is released before
/// the next round solves (`adapt::refine_by`; a finer companion, which is
/// the next round, solves within the last round's estimate, beside it).
pub struct Pending {
    pub model: Arc<Model>,
    pub operator: Arc<dyn Operator>,
    /// Nodal displacements of every body (`compose`).
    pub disp: Vec<Vec<[f64; 2]>>,
    pub lambda: Vec<f64>,
    /// Every punch's motion (obstacle, [α₁, α₂, θ]).
    pub punches: Vec<(usize, [f64; 3])>,
}

impl Pending {
    /// The bound of the answer (`energy::bound`), or why there is none.
    pub fn bound(&self, scene: &Scene) -> Result<EnergyBound, &'static str> {
        let op = &*self.operator;
        bound(
            scene,
            &self.model,
            op.stiffness(),
            op.factor(),
            &self.disp,
            &self.lambda,
            &self.punches,
        )
    }
}

impl std::fmt::Debug for Pending {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Pending {{ dofs: {} }}", self.model.dofs.n_free)
    }
}
