//! The block of free rigid motions in a frictional solve: the punches' and
//! the contact-held bodies' motions as columns over the normal and
//! tangential rows (`methods::FreeBlock`), and their rigid
//! displacement added back to the answer.

use crate::contact::friction::Tangents;
use crate::error::CoreError;
use crate::mesh::Mesh2d;
use crate::methods::{self, friction::Friction, Solution};
use crate::model::Model;
use crate::scene::Scene;

/// The load-controlled punch motions and the free rigid modes of bodies
/// held only by contact of a frictional step (None without any): their
/// columns in the normal and tangential rows and their loads, refused with
/// `incompatible_loads` when no contact force inside the friction cone
/// balances them (the punch or body would slide). A motion nothing
/// resists and nothing loads is left out, at 0, and marked not determined.
fn punch_block(
    scene: &Scene,
    model: &mut Model,
    tangents: &Tangents,
) -> Result<Option<(methods::FreeBlock, Vec<usize>)>, CoreError> {
    let fm = &model.free;
    if fm.is_empty() {
        return Ok(None);
    }
    use crate::contact::free_motions::{rigid_column, Motion};
    let k = fm.motions.len();
    // A punch's motion moves the row's target by c_t · α along t (the row
    // subtracts it); a body's rigid motion R moves the row's own points, so
    // its slip gains B_T R β and its column is −B_T R (as C_N = −B_N R).
    let bodies: Vec<Option<Vec<f64>>> = (fm.motions.iter())
        .map(|(mo, _)| match *mo {
            Motion::Body { set, dir } => {
                let rm = &model.dofs.rigid[set];
                let rows = tangents.terms.iter().map(Vec::as_slice);
                Some(rigid_column(rows, rm, &model.meshes[rm.body], dir).col)
            }
            Motion::Punch { .. } => None,
        })
        .collect();
    let ct = faer::Mat::<f64>::from_fn(tangents.len(), k, |r, j| match fm.motions[j].0 {
        Motion::Punch { obstacle, component } => match tangents.punch[r] {
            Some((o, c)) if o == obstacle => c[component],
            _ => 0.0,
        },
        Motion::Body { .. } => bodies[j].as_ref().map_or(0.0, |col| col[r]),
    });
    let n = model.cons.len();
    let ct_by_candidate = faer::Mat::<f64>::from_fn(n, k, |i, j| tangents.row_of[i].map_or(0.0, |r| ct[(r, j)]));
    // The slope of each candidate's cone rays (0 without a tangential row).
    let slope: Vec<f64> = (0..n)
        .map(|i| tangents.row_of[i].map_or(0.0, |r| tangents.law[r].ray_slope()))
        .collect();
    let tilt = body_normal_tilts(scene, model, &slope);
    let loose = fm.check_with_friction(scene, &model.dofs, &ct_by_candidate, &slope, &tilt)?;
    let keep: Vec<usize> = (0..k).filter(|j| !loose.contains(j)).collect();
    let block = methods::FreeBlock {
        cn: faer::Mat::<f64>::from_fn(n, keep.len(), |i, j| fm.c[(i, keep[j])]),
        ct: faer::Mat::<f64>::from_fn(tangents.len(), keep.len(), |r, j| ct[(r, keep[j])]),
        rhs: keep.iter().map(|&j| fm.rhs[j]).collect(),
        bodies: model.dofs.rigid.iter().map(|rm| rm.body).collect(),
    };
    for j in loose {
        model
            .free
            .undetermined
            .push((0..k).map(|i| f64::from(u8::from(i == j))).collect());
    }
    Ok(Some((block, keep)))
}

/// A step's model with its tangential rows and its block of free motions,
/// built once per step.
pub(crate) struct StepModel {
    pub model: Model,
    pub tangents: Tangents,
    pub block: Option<methods::FreeBlock>,
    /// The free motions (`FreeMotions::motions`) the block holds; the
    /// others are not determined and stay at 0.
    pub keep: Vec<usize>,
}

impl StepModel {
    /// The model of the step's scene `s`; its free motions join the step's
    /// unknowns once Fichera's condition with the friction cone admits
    /// their loads (`punch_block`).
    pub fn build(s: &Scene, meshes: Vec<Mesh2d>) -> Result<Self, CoreError> {
        let mut model = Model::build(s, meshes)?;
        let tangents = Tangents::new(s, &model.meshes, &model.cons, &model.dofs);
        let (block, keep) = punch_block(s, &mut model, &tangents)?.unzip();
        Ok(Self {
            model,
            tangents,
            block,
            keep: keep.unwrap_or_default(),
        })
    }
}

/// Completes the free motions of a solved step: every motion's amplitude
/// (0 for those not determined) in the solution and the friction, the
/// bodies' rigid motions R β in the displacement the next step's slip is
/// measured from; returns the friction forces' share of each motion's
/// equilibrium C_Nᵀλ + C_Tᵀτ = −P with its scale (`FreeMotions::equilibrium`).
pub(crate) fn settle_block(sm: &StepModel, sol: &mut Solution, friction: &mut Friction) -> Vec<(f64, f64)> {
    let (Some(b), model) = (&sm.block, &sm.model) else {
        return Vec::new();
    };
    let mut beta = vec![0.0; model.free.motions.len()];
    for (j, &m) in sm.keep.iter().enumerate() {
        beta[m] = sol.beta[j];
    }
    sol.beta = beta.clone();
    add_rigid_motions(model, &beta, &mut friction.history.displacement);
    friction.beta = beta;
    let mut shares = vec![(0.0, 0.0); model.free.motions.len()];
    for (j, &m) in sm.keep.iter().enumerate() {
        let terms = (0..sm.tangents.len()).map(|k| b.ct[(k, j)] * friction.tau[k]);
        // A body's slide that only friction resists carries no load at
        // Q = 0, and its friction terms are ~μ λ: judged against them alone
        // the LU's round-off on λ read 1.2e-7 at μ = 1e-9 (measured), so the
        // size of the body's loads is a scale too.
        let largest = terms.clone().fold(0.0, |a: f64, v| a.max(v.abs()));
        let loads = model.free.load_scale.get(m).copied().unwrap_or(0.0);
        shares[m] = (terms.sum(), largest.max(loads));
    }
    shares
}

/// Adds the rigid motions R β of the bodies held only by contact (β every
/// free motion's amplitude) to a displacement of every DOF.
fn add_rigid_motions(model: &Model, beta: &[f64], displacement: &mut [f64]) {
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
/// rows without friction (`slope` 0), which keep the row direction alone in
/// the compatibility check.
fn body_normal_tilts(scene: &Scene, model: &Model, slope: &[f64]) -> Vec<f64> {
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
