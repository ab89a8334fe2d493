//! The frictional route: load step after load step, each from the state the
//! previous one left, on one factorization (`admit::frictional_route`).

use super::friction_block::{add_rigid_motions, punch_block};
use super::notes::{friction_shortfall, sliding_punches, unsettled_bodies};
use super::step_scenes;
use crate::admit::{self, Route};
use crate::cache::OperatorCache;
use crate::error::CoreError;
use crate::fem::assembly::{assemble_loads, assemble_stiffness};
use crate::methods;
use crate::model::Model;
use crate::observer::{Observer, Stage};
use crate::scene::{Limits, Scene};
use crate::solution::compose::{self, Solved};
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
    // A punch pushed, or a body held only by contact loaded, beyond what
    // friction holds in some step is refused before the first step is
    // solved (Fichera's condition with friction).
    let loaded_punch = scene.obstacles.iter().any(|o| {
        o.punch
            .as_ref()
            .is_some_and(|p| p.controls.iter().any(|c| matches!(c, crate::scene::Control::Load(_))))
    });
    let free_body = !crate::fem::assembly::dof_map(scene, &meshes)?.rigid.is_empty();
    if stepped && (loaded_punch || free_body) {
        for (s, _, _) in step_scenes(scene) {
            let mut model = Model::build(&s, meshes.clone())?;
            let tangents = crate::contact::friction::Tangents::new(&s, &model.meshes, &model.cons, &model.dofs);
            punch_block(&s, &mut model, &tangents)?;
        }
    }
    let steps_in = if stepped {
        step_scenes(scene)
    } else {
        Box::new(std::iter::once((scene.clone(), 1.0, None)))
    };
    // K is the same in every step (the loads and prescribed values change,
    // not the mesh or the materials): assembled once, and on the condensed
    // route factored and condensed once for every step.
    let mut op: Option<Arc<crate::cache::Prepared>> = None;
    let mut k_once: Option<Arc<crate::fem::assembly::Stiffness>> = None;
    let mut history = methods::friction::History::default();
    let (mut steps, mut timings, mut last) = (Vec::new(), Timings::default(), None);
    for (s, k, loads) in steps_in {
        obs.enter(Stage::Assembly);
        let mut model = Model::build(&s, meshes.clone())?;
        let tangents = crate::contact::friction::Tangents::new(&s, &model.meshes, &model.cons, &model.dofs);
        // Load-controlled punch motions and the rigid modes of bodies held
        // only by contact join the step's unknowns, once Fichera's condition
        // with the friction cone admits their loads.
        let block = punch_block(&s, &mut model, &tangents)?;
        let (route, why_full) =
            admit::frictional_route(&s, &model.cons, &tangents, model.dofs.n_free, block.is_some(), limits)?;
        let stiffness = match &k_once {
            Some(k) => k.clone(),
            None => k_once
                .insert(Arc::new(assemble_stiffness(&s, &model.meshes, &model.dofs)?))
                .clone(),
        };
        obs.leave(Stage::Assembly)?;
        let f = assemble_loads(&model.external, &model.dofs, &stiffness);
        let (mut sol, mut friction, factor) = match route {
            Route::Condensed => {
                let prepared = match &op {
                    Some(p) => p.clone(),
                    None => {
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
                        op = Some(p.clone());
                        p
                    }
                };
                obs.check(Stage::Factorization)?;
                obs.enter(Stage::ContactSolve);
                let step = methods::friction::Step {
                    op: &prepared,
                    f: &f,
                    cons: &model.cons,
                    tangents: &tangents,
                    dofs: &model.dofs,
                    settings: &s.settings,
                    block: block.as_ref(),
                };
                let (sol, friction) = methods::friction::solve_step(&step, &history);
                let factor = (prepared.pivot_ratio, prepared.chol.cost().predicted_secs());
                (sol, friction, Some(factor))
            }
            Route::Full => {
                // No factorization stage of its own: every Newton iteration
                // factors K with its state's prescribed coordinates.
                obs.enter(Stage::ContactSolve);
                let step = methods::friction_full::Step {
                    k: &stiffness.k,
                    f: &f,
                    cons: &model.cons,
                    tangents: &tangents,
                    dofs: &model.dofs,
                    settings: &s.settings,
                };
                let (mut sol, friction) = methods::friction_full::solve_step(&step, &history)?;
                sol.fallback = why_full;
                (sol, friction, None)
            }
        };
        // Every free motion's amplitude, 0 for those not determined.
        if let Some(b) = &block {
            let mut beta = vec![0.0; model.free.motions.len()];
            for (j, &m) in b.keep.iter().enumerate() {
                beta[m] = sol.beta[j];
            }
            sol.beta = beta.clone();
            // The next step's slip is measured from the whole displacement,
            // the bodies' rigid motions R β included.
            add_rigid_motions(&model, &beta, &mut friction.history.displacement);
            friction.beta = beta;
        }
        obs.leave(Stage::ContactSolve)?;
        obs.timings.contact_solve = sol.t_contact;
        // The friction forces join the loads: the certificate's equilibrium is
        // then K u = f − B_Nᵀ λ − B_Tᵀ τ.
        let mut f_eff = f.clone();
        let minus_tau: Vec<f64> = friction.tau.iter().map(|t| -t).collect();
        tangents.apply_transpose_into(&minus_tau, &mut f_eff);
        // Likewise the punches' equilibrium: C_Nᵀλ + C_Tᵀτ = −P.
        if let Some(b) = &block {
            let mut shares = vec![(0.0, 0.0); model.free.motions.len()];
            for (j, &m) in b.keep.iter().enumerate() {
                let terms = (0..tangents.len()).map(|k| b.ct[(k, j)] * friction.tau[k]);
                // A body's slide that only friction resists carries no load
                // at Q = 0, and its friction terms are ~μ λ: judged against
                // them alone the LU's round-off on λ read 1.2e-7 at μ = 1e-9
                // (measured), so the size of the body's loads is a scale too.
                let largest = terms.clone().fold(0.0, |a: f64, v| a.max(v.abs()));
                let loads = model.free.load_scale.get(m).copied().unwrap_or(0.0);
                shares[m] = (terms.sum(), largest.max(loads));
            }
            model.free.friction = shares;
        }
        for o in 0..s.obstacles.len() {
            if s.obstacles[o].punch.is_some() {
                let a = crate::contact::free_motions::punch_motion(&s, &model.free, &friction.beta, o);
                friction.history.punches.insert(o, a);
            }
        }
        let composed = Solved {
            model: &model,
            k: &stiffness.k,
            f: &f_eff,
            pivot_ratio: factor.map(|f| f.0),
            predicted: factor.map(|f| f.1),
            compliance: None,
        };
        let sol_iterations = sol.iterations;
        let mut r = compose::report(&s, &composed, sol, obs, CacheState::Off);
        crate::solution::friction::attach(&mut r, &s, &model, &tangents, &friction);
        if r.status == Status::MaxIterations {
            r.notes.extend(sliding_punches(&s));
            let short = block
                .as_ref()
                .map(|b| friction_shortfall(&s, &model, b, &tangents, &friction.lambda))
                .unwrap_or_default();
            r.notes.extend(unsettled_bodies(&s, &model, sol_iterations, &short));
        }
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
