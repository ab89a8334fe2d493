//! The free motions with friction: their columns over the tangential rows,
//! the friction cone each candidate's force must lie in for Fichera's test
//! (`check_with_friction`), and the bodies' rigid displacement R β.

use std::collections::HashMap;

use faer::Mat;

use super::columns::rigid_column;
use super::{FreeMotions, Motion};
use crate::contact::friction::Tangents;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::DofMap;
use crate::mesh::boundary::boundary_nodes;
use crate::mesh::Mesh2d;
use crate::scene::Scene;

impl FreeMotions {
    /// C_T, each free motion's column over the tangential rows. A punch's
    /// motion moves the row's target by c_t · α along t (the row subtracts
    /// it); a body's rigid motion R moves the row's own points, so its slip
    /// gains B_T R β and its column is −B_T R (as C_N = −B_N R).
    pub fn tangential_columns(&self, t: &Tangents, dofs: &DofMap, meshes: &[Mesh2d]) -> Mat<f64> {
        let bodies: Vec<Option<Vec<f64>>> = (self.motions.iter())
            .map(|(mo, _)| match *mo {
                Motion::Body { set, dir } => {
                    let rm = &dofs.rigid[set];
                    let rows = t.terms.iter().map(Vec::as_slice);
                    Some(rigid_column(rows, rm, &meshes[rm.body], dir).col)
                }
                Motion::Punch { .. } => None,
            })
            .collect();
        Mat::<f64>::from_fn(t.len(), self.motions.len(), |r, j| match self.motions[j].0 {
            Motion::Punch { obstacle, component } => match t.punch[r] {
                Some((o, c)) if o == obstacle => c[component],
                _ => 0.0,
            },
            Motion::Body { .. } => bodies[j].as_ref().map_or(0.0, |col| col[r]),
        })
    }

    /// Fichera's condition with each candidate's friction cone
    /// (`check_with_friction`) for the tangential columns `ct`: the cone's
    /// slope from the row's law, taken about both the row direction and the
    /// body's normal. Returns the motions not determined.
    pub fn check_with_cone(
        &self,
        scene: &Scene,
        (dofs, meshes, cons): (&DofMap, &[Mesh2d], &ConstraintSet),
        t: &Tangents,
        ct: &Mat<f64>,
    ) -> Result<Vec<usize>, CoreError> {
        let n = cons.len();
        let ct_by_candidate = Mat::<f64>::from_fn(n, ct.ncols(), |i, j| t.row_of[i].map_or(0.0, |r| ct[(r, j)]));
        // The slope of each candidate's cone rays (0 without a tangential row).
        let slope: Vec<f64> = (0..n)
            .map(|i| t.row_of[i].map_or(0.0, |r| t.law[r].ray_slope()))
            .collect();
        let tilt = body_normal_tilts(scene, meshes, cons, &slope);
        self.check_with_friction(scene, dofs, &ct_by_candidate, &slope, &tilt)
    }

    /// Adds the rigid motions R β of the bodies held only by contact (β every
    /// free motion's amplitude) to a displacement of every DOF.
    pub fn add_rigid_motions(&self, dofs: &DofMap, meshes: &[Mesh2d], beta: &[f64], displacement: &mut [f64]) {
        for ((mo, _), &a) in self.motions.iter().zip(beta) {
            if let Motion::Body { set, dir } = *mo {
                let rm = &dofs.rigid[set];
                for (n, &x) in meshes[rm.body].nodes.iter().enumerate() {
                    let d = rm.at_dir(dir, x);
                    displacement[dofs.dof(rm.body, n, 0)] += a * d[0];
                    displacement[dofs.dof(rm.body, n, 1)] += a * d[1];
                }
            }
        }
    }
}

/// The signed angle from each candidate's row direction (the punch's normal
/// at the point it faces) to the body's outward normal at the candidate's
/// node, counter-clockwise (toward the row's tangent t = (−n_y, n_x)); 0 on
/// rows without friction (`slope` 0), which keep the row direction alone in
/// the compatibility check.
fn body_normal_tilts(scene: &Scene, meshes: &[Mesh2d], cons: &ConstraintSet, slope: &[f64]) -> Vec<f64> {
    let mut normal: HashMap<(usize, usize), [f64; 2]> = HashMap::new();
    for pair in scene.pairs.iter().filter(|p| p.friction > 0.0) {
        let mesh = &meshes[pair.body];
        if let Some(edges) = mesh.edge_sets.get(&pair.edges) {
            // Only the normals are read: the plane weights do.
            for bn in boundary_nodes(mesh, edges, false) {
                normal.insert((pair.body, bn.node), bn.normal);
            }
        }
    }
    cons.candidates
        .iter()
        .zip(slope)
        .map(|(c, &m)| {
            let Some(nb) = normal.get(&(c.body, c.node)).filter(|_| m > 0.0) else {
                return 0.0;
            };
            let n = c.normal;
            (n[0] * nb[1] - n[1] * nb[0]).atan2(n[0] * nb[0] + n[1] * nb[1])
        })
        .collect()
}
