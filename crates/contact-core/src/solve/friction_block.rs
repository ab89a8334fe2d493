//! The block of free rigid motions in a frictional solve: the punches' and
//! the contact-held bodies' motions as columns over the normal and
//! tangential rows (`methods::friction::Block`), and their rigid
//! displacement added back to the answer.

use crate::error::CoreError;
use crate::methods;
use crate::model::Model;
use crate::scene::Scene;

/// The load-controlled punch motions and the free rigid modes of bodies
/// held only by contact of a frictional step (None without any): their
/// columns in the normal and tangential rows and their loads, refused with
/// `incompatible_loads` when no contact force inside the friction cone
/// balances them (the punch or body would slide). A motion nothing
/// resists and nothing loads is left out, at 0, and marked not determined.
pub(crate) fn punch_block(
    scene: &Scene,
    model: &mut Model,
    tangents: &crate::contact::friction::Tangents,
) -> Result<Option<methods::friction::Block>, CoreError> {
    let fm = &model.free;
    if fm.is_empty() {
        return Ok(None);
    }
    use crate::contact::free_motions::Motion;
    let k = fm.motions.len();
    // A punch's motion moves the row's target by c_t · α along t (the row
    // subtracts it); a body's rigid motion R moves the row's own points, so
    // its slip gains B_T R β and its column is −B_T R (as C_N = −B_N R).
    let ct = faer::Mat::<f64>::from_fn(tangents.len(), k, |r, j| match fm.motions[j].0 {
        Motion::Punch { obstacle, component } => match tangents.punch[r] {
            Some((o, c)) if o == obstacle => c[component],
            _ => 0.0,
        },
        Motion::Body { set, dir } => {
            let rm = &model.dofs.rigid[set];
            tangents.terms[r]
                .iter()
                .filter(|t| t.body == rm.body)
                .map(|t| {
                    let d = rm.at_dir(dir, model.meshes[rm.body].nodes[t.node]);
                    -(t.coef[0] * d[0] + t.coef[1] * d[1])
                })
                .sum()
        }
    });
    let n = model.cons.len();
    let ct_by_candidate = faer::Mat::<f64>::from_fn(n, k, |i, j| tangents.row_of[i].map_or(0.0, |r| ct[(r, j)]));
    let mu: Vec<f64> = (0..n)
        .map(|i| tangents.row_of[i].map_or(0.0, |r| tangents.mu[r]))
        .collect();
    let tilt = body_normal_tilts(scene, model, &mu);
    let loose = fm.check_with_friction(scene, &model.dofs, &ct_by_candidate, &mu, &tilt)?;
    let keep: Vec<usize> = (0..k).filter(|j| !loose.contains(j)).collect();
    let block = methods::friction::Block {
        cn: faer::Mat::<f64>::from_fn(n, keep.len(), |i, j| fm.c[(i, keep[j])]),
        ct: faer::Mat::<f64>::from_fn(tangents.len(), keep.len(), |r, j| ct[(r, keep[j])]),
        rhs: keep.iter().map(|&j| fm.rhs[j]).collect(),
        bodies: model.dofs.rigid.iter().map(|rm| rm.body).collect(),
        keep,
    };
    for j in loose {
        model
            .free
            .undetermined
            .push((0..k).map(|i| f64::from(u8::from(i == j))).collect());
    }
    Ok(Some(block))
}

/// Adds the rigid motions R β of the bodies held only by contact (β every
/// free motion's amplitude) to a displacement of every DOF.
pub(crate) fn add_rigid_motions(model: &Model, beta: &[f64], displacement: &mut [f64]) {
    use crate::contact::free_motions::Motion;
    for ((mo, _), &a) in model.free.motions.iter().zip(beta) {
        if let Motion::Body { set, dir } = *mo {
            let rm = &model.dofs.rigid[set];
            for (n, &x) in model.meshes[rm.body].nodes.iter().enumerate() {
                let d = rm.at_dir(dir, x);
                displacement[model.dofs.dof(rm.body, n, 0)] += a * d[0];
                displacement[model.dofs.dof(rm.body, n, 1)] += a * d[1];
            }
        }
    }
}

/// The signed angle from each candidate's row direction (the punch's normal
/// at the point it faces) to the body's outward normal at the candidate's
/// node, counter-clockwise (toward the row's tangent t = (−n_y, n_x)); 0 on
/// rows without friction (`mu` 0), which keep the row direction alone in the
/// compatibility check.
fn body_normal_tilts(scene: &Scene, model: &Model, mu: &[f64]) -> Vec<f64> {
    use crate::mesh::boundary::boundary_nodes;
    let mut normal: std::collections::HashMap<(usize, usize), [f64; 2]> = std::collections::HashMap::new();
    for pair in scene.pairs.iter().filter(|p| p.friction > 0.0) {
        let mesh = &model.meshes[pair.body];
        if let Some(edges) = mesh.edge_sets.get(&pair.edges) {
            // Only the normals are read: the plane weights do.
            for bn in boundary_nodes(mesh, edges, false) {
                normal.insert((pair.body, bn.node), bn.normal);
            }
        }
    }
    model
        .cons
        .candidates
        .iter()
        .zip(mu)
        .map(|(c, &m)| {
            let Some(nb) = normal.get(&(c.body, c.node)).filter(|_| m > 0.0) else {
                return 0.0;
            };
            let n = c.normal;
            (n[0] * nb[1] - n[1] * nb[0]).atan2(n[0] * nb[0] + n[1] * nb[1])
        })
        .collect()
}
