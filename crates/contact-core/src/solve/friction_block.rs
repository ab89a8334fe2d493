//! A frictional step's model, built once: the model, its tangential rows
//! and its block of free rigid motions (`methods::FreeBlock`, the motions
//! the friction cone admits: `FreeMotions::check_with_cone`), and the
//! block's answer completed after the solve.

use crate::contact::friction::Tangents;
use crate::error::{CoreError, InvalidKind};
use crate::mesh::Mesh2d;
use crate::methods::{self, friction::Friction, Solution};
use crate::model::Model;
use crate::scene::{Control, Scene, COMPONENTS};

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
        held_under_loaded_punch(s, &model, &tangents)?;
        let (block, keep) = punch_block(s, &mut model, &tangents)?.unzip();
        Ok(Self {
            model,
            tangents,
            block,
            keep: keep.unwrap_or_default(),
        })
    }
}

/// Refuses a frictional point that faces a load-controlled punch and whose
/// own motion along the surface the supports hold (a contact edge also held
/// along x): its slip is then the punch's motion alone (no tangential row:
/// `Tangents::held`), or that and what its closed gap fixes (`tied`), and its
/// friction force passes from the punch straight to the supports. The
/// friction block carries no such share: a flat punch over the held top of
/// the block, pressed by 10 and pushed by 1 at μ = 0.3, was refused as if it
/// had to slide ("the horizontal load must lie in [0, 0]"); a circular one
/// ran to the iteration cap with α1 = 5.7e14 and θ = 7.2e13 rad, pushed or
/// not. Not refused: a held point (no tangential row) under a punch whose
/// loaded components along its slip are all 0 (it sticks, α1 = 0, as
/// answered); a tied one is refused for any load there, 0 included.
fn held_under_loaded_punch(scene: &Scene, model: &Model, tangents: &Tangents) -> Result<(), CoreError> {
    let tied_rows = (0..tangents.len()).filter_map(|k| tangents.tied(k).map(|r| (tangents.of[k], Some(r))));
    let held = tangents.held.iter().map(|h| (h.candidate, None));
    for (i, tied) in held.chain(tied_rows) {
        let c = &model.cons.candidates[i];
        let (Some((o, ct)), Some((_, cn))) = (c.punch_tangent(), c.punch()) else {
            continue;
        };
        let Some(punch) = &scene.obstacles[o].punch else {
            continue;
        };
        // What a motion of the punch moves the slip by: along t, less (tied)
        // what it moves the gap by times r, which the closed gap fixes (a
        // circular punch's vertical motion, whose share is n_x both ways).
        let moves = |j: usize| tied.map_or(ct[j], |r| ct[j] - r * cn[j]);
        // A share below this (of the coefficients' size) is round-off.
        const ALONG: f64 = 1e-9;
        let scale = ct.iter().chain(&cn).fold(0.0f64, |m, v| m.max(v.abs()));
        let loaded = (0..3).find(|&j| {
            moves(j).abs() > ALONG * scale
                && matches!(punch.controls[j], Control::Load(v) if tied.is_some() || v != 0.0)
        });
        let Some(j) = loaded else {
            continue;
        };
        let body = &scene.bodies[c.body].name;
        let name = &scene.obstacles[o].name;
        return Err(CoreError::Invalid {
            kind: InvalidKind::Request,
            path: format!("/obstacles/{o}/punch/{}/load", COMPONENTS[j]),
            reason: format!(
                "the supports of body '{body}' hold its contact nodes against punch '{name}' along the surface \
                    (a support on the contact's own edge set), so their slip is the punch's own motion and their \
                    friction force passes from the punch straight to those supports: with the punch's {} motion \
                    load-controlled, this model cannot share that force between the punch and the supports and \
                    gives no answer (it reported the punch sliding, or motions without bound). Prescribe the \
                    punch's {} motion (a displacement, the reply then gives its load), or release the support \
                    along the surface on the contact's edge set",
                COMPONENTS[j], COMPONENTS[j]
            ),
            loads: Vec::new(),
        });
    }
    Ok(())
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
