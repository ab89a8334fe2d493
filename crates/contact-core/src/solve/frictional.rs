//! The frictional route: load step after load step, each from the state the
//! previous one left, on one factorization (`admit::frictional_route`).

use super::friction_block::{settle_block, StepModel};
use super::notes::{friction_shortfall, sliding_punches, unsettled_bodies};
use super::step_scenes;
use crate::admit::{self, Route};
use crate::cache::{OperatorCache, Prepared};
use crate::contact::friction::Tangents;
use crate::error::CoreError;
use crate::fem::assembly::{assemble_loads, assemble_stiffness, Stiffness};
use crate::mesh::Mesh2d;
use crate::methods::{self, friction::History, Solution};
use crate::model::Model;
use crate::observer::{Observer, Stage};
use crate::outcome::{Note, NoteKind};
use crate::scene::{Control, Limits, Scene};
use crate::solution::compose::{self, Solved};
use crate::solution::prescribed_slip;
use crate::solution::report::{with_steps, CacheState, LoadStep, Report, Status, Timings};
use std::sync::Arc;

/// Coulomb friction: the load steps in order (one step, the loads as given,
/// without `load_factors` or `load_path`), each starting from the state the
/// previous one left, on one factorization of K condensed onto the normal
/// and tangential rows together, or on K itself (`admit::frictional_route`).
pub(super) fn solve_frictional(
    scene: &Scene,
    limits: &Limits,
    cache: Option<&OperatorCache>,
) -> Result<Report, CoreError> {
    let (meshes, mut obs) = super::meshed(scene, limits)?;
    let stepped = !scene.load_factors.is_empty() || !scene.load_path.is_empty();
    let mut prebuilt = checked_models(scene, &meshes, stepped)?.into_iter();
    let steps_in = if stepped {
        step_scenes(scene)
    } else {
        Box::new(std::iter::once((scene.clone(), 1.0, None)))
    };
    // K is the same in every step (the loads and prescribed values change,
    // not the mesh or the materials): assembled once, and on the condensed
    // route factored and condensed once for every step.
    let (mut op, mut k_once): (Option<Arc<Prepared>>, Option<Arc<Stiffness>>) = (None, None);
    let mut history = History::default();
    let (mut steps, mut timings, mut last) = (Vec::new(), Timings::default(), None);
    for (s, k, loads) in steps_in {
        obs.enter(Stage::Assembly);
        let sm = match prebuilt.next() {
            Some(sm) => sm,
            None => StepModel::build(&s, meshes.clone())?,
        };
        let (model, tangents) = (&sm.model, &sm.tangents);
        let (route, why_full) =
            admit::frictional_route(&s, &model.cons, tangents, model.dofs.n_free, sm.block.is_some(), limits)?;
        let stiffness = match &k_once {
            Some(k) => k.clone(),
            None => k_once
                .insert(Arc::new(assemble_stiffness(&s, &model.meshes, &model.dofs)?))
                .clone(),
        };
        obs.leave(Stage::Assembly)?;
        let f = assemble_loads(&model.external, &model.dofs, &stiffness);
        // Before the solve: points whose slip the supports prescribe.
        let prescribed = prescribed_slip::find(&s, model, tangents);
        let (mut sol, mut friction, factor) = match route {
            Route::Condensed => {
                let prepared = match &op {
                    Some(p) => p.clone(),
                    None => op
                        .insert(prepare(&mut obs, &stiffness, model, tangents, cache)?)
                        .clone(),
                };
                obs.check(Stage::Factorization)?;
                obs.enter(Stage::ContactSolve);
                let step = methods::friction::condensed::Step {
                    op: &prepared,
                    f: &f,
                    cons: &model.cons,
                    tangents,
                    dofs: &model.dofs,
                    settings: &s.settings,
                    block: sm.block.as_ref(),
                };
                let (sol, friction) = methods::friction::condensed::solve_step(&step, &history);
                (
                    sol,
                    friction,
                    Some((prepared.pivot_ratio, prepared.chol.cost().predicted_secs())),
                )
            }
            Route::Full => {
                // No factorization stage of its own: every Newton iteration
                // factors K with its state's prescribed coordinates.
                obs.enter(Stage::ContactSolve);
                let step = methods::friction::full::Step {
                    k: &stiffness.k,
                    f: &f,
                    cons: &model.cons,
                    tangents,
                    dofs: &model.dofs,
                    settings: &s.settings,
                };
                let (mut sol, friction) = methods::friction::full::solve_step(&step, &history)?;
                sol.fallback = why_full.map(|t| Note::new(NoteKind::FullSystem, t));
                (sol, friction, None)
            }
        };
        let shares = settle_block(&sm, &mut sol, &mut friction);
        // The points without a tangential row slide by what the supports
        // prescribe, from where the previous step left them.
        friction.held_slip = tangents.held_slips(&model.dofs, &history.displacement, &history.punches);
        obs.leave(Stage::ContactSolve)?;
        obs.timings.contact_solve = sol.t_contact;
        // The friction forces join the loads: the certificate's equilibrium is
        // then K u = f − B_Nᵀ λ − B_Tᵀ τ.
        let mut f_eff = f.clone();
        let minus_tau: Vec<f64> = friction.tau.iter().map(|t| -t).collect();
        sm.tangents.apply_transpose_into(&minus_tau, &mut f_eff);
        for o in (0..s.obstacles.len()).filter(|&o| s.obstacles[o].punch.is_some()) {
            let a = crate::contact::free_motions::punch_motion(&s, &sm.model.free, &friction.beta, o);
            friction.history.punches.insert(o, a);
        }
        let composed = Solved {
            model: &sm.model,
            k: &stiffness.k,
            f: &f_eff,
            loads: Some(&f),
            pivot_ratio: factor.map(|f| f.0),
            predicted: factor.map(|f| f.1),
            compliance: None,
            friction: &shares,
            operator: None,
        };
        let mut r = report(&s, &composed, &sm, sol, &friction, obs);
        let settled = r.status == Status::Solved;
        r.warnings
            .extend(prescribed_slip::warnings(&s, &prescribed, &friction.lambda, settled));
        history = friction.history;
        obs = Observer::new();
        steps.push(LoadStep::of(k, loads, &r));
        timings.add(&r.timings);
        last = Some(r);
    }
    let mut last = with_steps(last.expect("at least one step"), steps, timings);
    if !stepped {
        last.steps = None;
    }
    Ok(last)
}

/// The models of every step, built before the first step is solved when a
/// punch pushed, or a body held only by contact loaded, beyond what friction
/// holds in some step must be refused up front (Fichera's condition with
/// friction, in `punch_block`); each serves its step's solve. Empty
/// otherwise: each step builds its model when it comes.
fn checked_models(scene: &Scene, meshes: &[Mesh2d], stepped: bool) -> Result<Vec<StepModel>, CoreError> {
    let loaded_punch = scene.obstacles.iter().any(|o| {
        o.punch
            .as_ref()
            .is_some_and(|p| p.controls.iter().any(|c| matches!(c, Control::Load(_))))
    });
    let free_body = !crate::fem::assembly::dof_map(scene, meshes)?.rigid.is_empty();
    if !stepped || !(loaded_punch || free_body) {
        return Ok(Vec::new());
    }
    // Every step is built for the check; the first ones are kept for the
    // solves, up to `KEEP_BYTES`, and the later ones built again there.
    let (mut kept, mut bytes) = (Vec::new(), 0usize);
    for (s, _, _) in step_scenes(scene) {
        let sm = StepModel::build(&s, meshes.to_vec())?;
        bytes = bytes.saturating_add(model_bytes(&sm.model));
        if bytes <= KEEP_BYTES {
            kept.push(sm);
        }
    }
    Ok(kept)
}

/// The step models kept from the up-front check, at most (their meshes,
/// loads and rows): each holds a copy of the meshes, so keeping a long load
/// path's every step on a large mesh would hold them all at once, where a
/// step built in turn holds one.
const KEEP_BYTES: usize = 256 << 20;

/// A model's heap, roughly: its meshes, its load vector and its rows.
fn model_bytes(model: &crate::model::Model) -> usize {
    let meshes: usize = model
        .meshes
        .iter()
        .map(|m| m.nodes.len() * std::mem::size_of::<[f64; 2]>() + m.elems.len() * std::mem::size_of::<usize>())
        .sum();
    let rows: usize = model.cons.candidates.iter().map(|c| c.row.len()).sum();
    meshes + model.external.len() * std::mem::size_of::<f64>() + rows * std::mem::size_of::<(usize, f64)>()
}

/// Factors K and condenses it onto the normal and tangential rows together.
fn prepare(
    obs: &mut Observer,
    stiffness: &Arc<Stiffness>,
    model: &Model,
    tangents: &Tangents,
    cache: Option<&OperatorCache>,
) -> Result<Arc<Prepared>, CoreError> {
    obs.enter(Stage::Factorization);
    let rows: Vec<&[(usize, f64)]> = model
        .cons
        .candidates
        .iter()
        .map(|c| c.row.as_slice())
        .chain(tangents.rows.iter().map(|r| r.as_slice()))
        .collect();
    let p = Arc::new(methods::condensed::prepare_rows(stiffness.clone(), &rows, cache)?);
    obs.timings.factorization = p.t_factorization;
    obs.timings.condensation = p.t_condensation;
    Ok(p)
}

/// The step's report with its friction, and the notes of a step that ran
/// out of iterations.
fn report(
    s: &Scene,
    composed: &Solved,
    sm: &StepModel,
    sol: Solution,
    friction: &methods::friction::Friction,
    obs: Observer,
) -> Report {
    let sol_iterations = sol.iterations;
    let mut r = compose::report(s, composed, sol, obs, CacheState::Off);
    crate::solution::friction::attach(&mut r, s, &sm.model, &sm.tangents, friction);
    if r.status == Status::MaxIterations {
        r.notes.extend(
            sliding_punches(s)
                .into_iter()
                .map(|t| Note::new(NoteKind::SlidingPunch, t)),
        );
        let short = sm
            .block
            .as_ref()
            .map(|b| friction_shortfall(s, &sm.model, (b, &sm.keep), &sm.tangents, &friction.lambda))
            .unwrap_or_default();
        let unsettled = unsettled_bodies(s, &sm.model, sol_iterations, &short);
        r.notes
            .extend(unsettled.into_iter().map(|t| Note::new(NoteKind::UnsettledBody, t)));
    }
    r
}
