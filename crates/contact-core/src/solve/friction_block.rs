//! A frictional step's model, built once: the model, its tangential rows
//! and its block of free rigid motions (`methods::FreeBlock`, the motions
//! the friction cone admits: `FreeMotions::check_with_cone`), and the
//! block's answer completed after the solve.

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
    let k = fm.motions.len();
    let ct = fm.tangential_columns(tangents, &model.dofs, &model.meshes);
    let loose = fm.check_with_cone(scene, (&model.dofs, &model.meshes, &model.cons), tangents, &ct)?;
    let keep: Vec<usize> = (0..k).filter(|j| !loose.contains(j)).collect();
    let block = methods::FreeBlock {
        cn: faer::Mat::<f64>::from_fn(fm.c.nrows(), keep.len(), |i, j| fm.c[(i, keep[j])]),
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
    model
        .free
        .add_rigid_motions(&model.dofs, &model.meshes, &beta, &mut friction.history.displacement);
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
