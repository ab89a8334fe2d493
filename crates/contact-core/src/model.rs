//! The assembly stage's product: the discrete model of a scene on its meshes,
//! everything but the stiffness (which the condensed path may take from the
//! cache): degrees of freedom, contact rows, external loads, the rigid motions
//! left to contact, and the foundations.

use crate::admit;
use crate::contact::{self, compliance::Foundations, free_motions::FreeMotions, ConstraintSet};
use crate::error::CoreError;
use crate::fem::{self, DofMap};
use crate::mesh::Mesh2d;
use crate::scene::Scene;

pub struct Model {
    pub meshes: Vec<Mesh2d>,
    pub dofs: DofMap,
    pub cons: ConstraintSet,
    /// Nodal external loads on all DOFs (tractions, body forces).
    pub external: Vec<f64>,
    /// Rigid motions held only by contact (load-controlled punches, bodies
    /// without enough supports) and their equilibrium rows.
    pub free: FreeMotions,
    pub foundations: Foundations,
}

impl Model {
    /// What `admit::route` judges.
    pub fn parts(&self) -> admit::Parts<'_> {
        admit::Parts {
            dofs: &self.dofs,
            cons: &self.cons,
            free: &self.free,
            foundations: &self.foundations,
        }
    }

    pub fn build(scene: &Scene, meshes: Vec<Mesh2d>) -> Result<Model, CoreError> {
        let dofs = fem::assembly::dof_map(scene, &meshes)?;
        admit::search_work(scene, &meshes)?;
        let cons = contact::build(scene, &meshes, &dofs);
        admit::candidates(scene, &cons)?;
        let points = admit::point_loads(scene, &meshes)?;
        admit::traction_ranges(scene, &meshes)?;
        let external = fem::loads::external(scene, &meshes, &dofs, &points);
        let free = FreeMotions::try_new(scene, &cons, &dofs, &meshes, &points, &external)?;
        let foundations = Foundations::try_new(scene, &cons)?;
        Ok(Model {
            meshes,
            dofs,
            cons,
            external,
            free,
            foundations,
        })
    }
}
