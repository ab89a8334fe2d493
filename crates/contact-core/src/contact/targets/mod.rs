//! What a pair's edge set can touch, one file per kind: a rigid obstacle or
//! punch (`obstacle`), another deformable body (`body`), a tensionless
//! foundation (`foundation`). Each answers what a point of the pair's surface
//! sees (`rows::Seen`) and turns the rows into candidates on the free DOFs
//! (`constraints::Candidate`, with its `Link`); [`build`] is the one place
//! that dispatches on the kind. A new kind is a file here, a variant of
//! `scene::Target` and one arm below.
//!
//! Candidates whose gap cannot close (no intersection, or a gap beyond
//! `prune_gap_ratio` of the body size) are dropped and counted per pair.

pub mod body;
mod edge_tree;
pub mod foundation;
pub mod obstacle;

use super::constraints::ConstraintSet;
use super::rows::Surface;
use crate::fem::DofMap;
use crate::mesh::Mesh2d;
use crate::scene::{Scene, Target};

/// The contact rows of every pair of the scene.
pub fn build(scene: &Scene, meshes: &[Mesh2d], dofs: &DofMap) -> ConstraintSet {
    let mut set = ConstraintSet::default();
    for (p, pair) in scene.pairs.iter().enumerate() {
        // Relative to the pair's own bodies, not to the scene's length scale, so
        // that an unrelated body elsewhere changes nothing.
        let limit = scene.settings.prune_gap_ratio
            * match &pair.target {
                Target::Obstacle(_) | Target::Foundation(_) => meshes[pair.body].size(),
                Target::Body { body, .. } => meshes[pair.body].size().max(meshes[*body].size()),
            };
        let slave = Surface {
            body: pair.body,
            mesh: &meshes[pair.body],
            edges: &meshes[pair.body].edge_sets[&pair.edges],
            analysis: scene.analysis,
        };
        let out = &mut set.candidates;
        let pruned = match &pair.target {
            Target::Obstacle(o) => obstacle::rows(scene, p, *o, &slave, limit, dofs, out),
            Target::Foundation(f) => foundation::rows(scene, p, *f, meshes, dofs, out),
            Target::Body {
                body,
                edges,
                discretization,
            } => {
                let master = Surface {
                    body: *body,
                    mesh: &meshes[*body],
                    edges: &meshes[*body].edge_sets[edges],
                    analysis: scene.analysis,
                };
                body::rows(scene, p, &slave, &master, *discretization, limit, dofs, out)
            }
        };
        set.pruned.push(pruned);
    }
    set
}
