//! The algorithm, stage by stage:
//!
//! ```text
//! request ─validate→ Scene ─mesh→ meshes ─admit→ ─assemble→ Model ─admit→ Route
//!   Condensed: K ─factor+condense→ Prepared (cacheable) ─LCP→ Solution
//!   Full:      K ─active set / interior point on the whole system→ Solution
//!   Friction:  K ─factor+condense normal and tangential rows→ per load step
//!              ─frictional active set from the previous step's state→ Solution
//! Solution ─certify, post-process→ Report
//! ```
//!
//! Each stage is a typed value in and out; the [`Observer`] announces, times
//! and deadline-checks them.
//!
//! Length: about 500 lines, the routes side by side (load steps, friction
//! with its block of punch and free-body motions, condensed, full), so that
//! the stages read in order in one place.

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::admit::{self, Route};
use crate::cache::{self, OperatorCache};
use crate::error::CoreError;
use crate::fem::assembly::{assemble_loads, assemble_stiffness};
use crate::methods::{self, full, Problem, PunchBlock};
use crate::model::Model;
use crate::observer::{self, Observer, Stage};
use crate::scene::{Limits, Method, Scene};
use crate::solution::compose::{self, Solved};
use crate::solution::report::{with_steps, CacheState, LoadStep, Report, Status, Timings};

/// Solves the scene, once per load factor or load path step (one
/// factorization serves them all); with friction, step after step from the
/// state the previous one left (`solve_frictional`). Within the scene's own
/// time limit, if it has one. With `settings.accuracy`, round after round on
/// finer meshes; with `settings.estimate`, every pair's error estimated
/// (`adapt`).
pub fn solve(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
    let _deadline = scene
        .time_limit
        .map(|s| crate::cancel::Deadline::install(std::time::Duration::from_secs_f64(s.min(1e9))));
    // The estimate's coarser companion and the refinement rounds are meshes
    // of their own: they bypass the service's operator cache (which would
    // keep operators no later request asks for).
    let uncached = |s: &Scene| solve_steps(s, limits, None);
    if scene.settings.estimate || scene.settings.accuracy.is_some() {
        crate::progress::expect_estimate(crate::adapt::estimate_share(scene));
    }
    if let Some(target) = scene.settings.accuracy {
        return crate::adapt::refine(scene, target, &uncached, limits.max_dofs);
    }
    let mut report = solve_steps(scene, limits, cache)?;
    if scene.settings.estimate {
        crate::adapt::estimate(scene, &mut report, &uncached, limits.max_dofs);
    }
    Ok(report)
}

/// The scene once per load factor or load path step.
fn solve_steps(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
    if scene.has_friction() {
        return solve_frictional(scene, limits, cache);
    }
    if scene.load_factors.is_empty() && scene.load_path.is_empty() {
        return solve_once(scene, limits, cache);
    }
    // Later factors find the operator the first one prepared.
    let local = OperatorCache::new(usize::MAX);
    let mut steps = Vec::with_capacity(scene.load_factors.len());
    let (mut timings, mut first_cache, mut last) = (Timings::default(), None, None);
    for (step, k, loads) in step_scenes(scene) {
        let r = solve_once(&step, limits, cache.or(Some(&local)))?;
        steps.push(LoadStep::of(k, loads, &r));
        timings.add(&r.timings);
        first_cache.get_or_insert(r.cache);
        last = Some(r);
    }
    let mut last = with_steps(last.expect("at least one factor"), steps, timings);
    last.cache = match (local.is_empty(), first_cache) {
        (true, Some(c)) => c,
        _ => CacheState::Off,
    };
    Ok(last)
}

/// A load step's scene, its factor, and a load path step's factors.
type StepScene = (Scene, f64, Option<BTreeMap<String, f64>>);

/// The scenes of the load steps, one at a time (a scene holds its inline
/// meshes: a hundred steps' copies at once could hold gigabytes).
fn step_scenes(scene: &Scene) -> Box<dyn Iterator<Item = StepScene> + '_> {
    if !scene.load_path.is_empty() {
        return Box::new(
            scene
                .load_path
                .iter()
                .map(|st| (scene.at_step(st), 1.0, Some(st.given.clone()))),
        );
    }
    Box::new(scene.load_factors.iter().map(|&k| (scene.scaled(k), k, None)))
}

/// Coulomb friction: the load steps in order (one step, the loads as given,
/// without `load_factors` or `load_path`), each starting from the state the
/// previous one left, on one factorization of K condensed onto the normal
/// and tangential rows together, or on K itself (`admit::frictional_route`).
fn solve_frictional(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
    let t6 = scene.bodies.iter().any(|b| b.is_t6());
    crate::progress::plan(observer::predicted(scene.estimated_nodes, t6));
    let mut obs = Observer::new();
    obs.enter(Stage::Mesh);
    let meshes = crate::meshing::meshes(scene)?;
    obs.leave(Stage::Mesh)?;
    admit::meshes(&meshes, limits)?;
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

/// The load-controlled punch motions and the free rigid modes of bodies
/// held only by contact of a frictional step (None without any): their
/// columns in the normal and tangential rows and their loads, refused with
/// `incompatible_loads` when no contact force inside the friction cone
/// balances them (the punch or body would slide). A motion nothing
/// resists and nothing loads is left out, at 0, and marked not determined.
fn punch_block(
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

fn solve_once(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
    let t6 = scene.bodies.iter().any(|b| b.is_t6());
    crate::progress::plan(observer::predicted(scene.estimated_nodes, t6));
    let mut obs = Observer::new();
    obs.enter(Stage::Mesh);
    let meshes = crate::meshing::meshes(scene)?;
    obs.leave(Stage::Mesh)?;
    admit::meshes(&meshes, limits)?;
    let nodes: usize = meshes.iter().map(|m| m.nodes.len()).sum();
    let mut plan = observer::predicted(nodes as f64, t6);
    plan[0] = obs.timings.mesh;
    crate::progress::plan(plan);

    obs.enter(Stage::Assembly);
    let model = Model::build(scene, meshes)?;
    match admit::route(scene, model.parts(), limits)? {
        Route::Full => solve_full(scene, &model, obs),
        Route::Condensed => solve_condensed(scene, &model, cache, obs),
    }
}

/// One factorization (or the cache's), the LCP on the contact rows.
fn solve_condensed(
    scene: &Scene,
    model: &Model,
    cache: Option<&OperatorCache>,
    mut obs: Observer,
) -> Result<Report, CoreError> {
    let key = cache::key(scene, &model.meshes, &model.dofs, &model.cons);
    let (op, cache_state) = match cache.and_then(|c| c.get(key)) {
        Some(op) => {
            crate::progress::revise("factorization", 0.0);
            crate::progress::revise("condensation", 0.0);
            (op, CacheState::Hit)
        }
        None => {
            let stiffness = Arc::new(assemble_stiffness(scene, &model.meshes, &model.dofs)?);
            obs.leave(Stage::Assembly)?;
            obs.enter(Stage::Factorization);
            let op = Arc::new(methods::condensed::prepare(stiffness, &model.cons, cache)?);
            obs.timings.factorization = op.t_factorization;
            obs.timings.condensation = op.t_condensation;
            if let Some(c) = cache {
                c.insert(key, op.clone());
            }
            (op, cache.map_or(CacheState::Off, |_| CacheState::Miss))
        }
    };
    obs.check(Stage::Factorization)?;
    let f = assemble_loads(&model.external, &model.dofs, &op.stiffness);
    let compliance = (!model.foundations.is_empty()).then(|| model.foundations.compliance(&model.cons));
    let problem = Problem {
        op: &op,
        f: &f,
        cons: &model.cons,
        settings: &scene.settings,
        punch: (!model.free.is_empty()).then_some(PunchBlock {
            c: &model.free.c,
            rhs: &model.free.rhs,
        }),
        compliance: compliance.as_ref(),
    };
    obs.enter(Stage::ContactSolve);
    let sol = methods::solve(&problem, scene.method)?;
    obs.leave(Stage::ContactSolve)?;
    obs.timings.contact_solve = sol.t_contact;
    let solved = Solved {
        model,
        k: &op.stiffness.k,
        f: &f,
        pivot_ratio: Some(op.pivot_ratio),
        predicted: Some(op.chol.cost().predicted_secs()),
        compliance: compliance.as_ref(),
    };
    Ok(compose::report(scene, &solved, sol, obs, cache_state))
}

/// Exact methods on the whole system: no condensation, no cache (they are
/// the comparison, and `auto`'s choice for many rows on few DOFs).
fn solve_full(scene: &Scene, model: &Model, mut obs: Observer) -> Result<Report, CoreError> {
    // No factorization stage of its own: the active set refactors a few times
    // inside the contact solve.
    let factor = observer::predicted(model.dofs.n_free as f64 / 2.0, false)[2];
    crate::progress::revise("factorization", 0.0);
    crate::progress::revise("condensation", 0.0);
    crate::progress::revise("contact_solve", 3.0 * factor);
    let stiffness = assemble_stiffness(scene, &model.meshes, &model.dofs)?;
    let f = assemble_loads(&model.external, &model.dofs, &stiffness);
    obs.leave(Stage::Assembly)?;
    let g = model.cons.g();
    obs.enter(Stage::ContactSolve);
    let sol = match scene.method {
        Method::InteriorPoint => full::solve_interior_point(&stiffness.k, &f, &model.cons, &g, &scene.settings)?,
        // `admit::route` lets only the exact methods through.
        _ => full::solve_active_set(&stiffness.k, &f, &model.cons, &g, &scene.settings)?,
    };
    obs.leave(Stage::ContactSolve)?;
    obs.timings.contact_solve = sol.t_contact;
    let solved = Solved {
        model,
        k: &stiffness.k,
        f: &f,
        pivot_ratio: None,
        predicted: None,
        compliance: None,
    };
    Ok(compose::report(scene, &solved, sol, obs, CacheState::Off))
}

/// What a frictional step that ran out of iterations says of the bodies
/// held only by contact. Their loads passed the check with the friction
/// cone before the solve, but that check sees loads, not the normal forces
/// a prescribed displacement makes (the LP may take any λ ≥ 0): a block
/// pressed down by a prescribed uy and pushed by Q = 1.46 μ P ran out of
/// iterations with a note that an equilibrium exists. So the step's own
/// normal forces are checked (`friction_shortfall`): where friction cannot
/// carry the load with them the body most likely slides; otherwise the
/// iteration, not the loads, fell short, and the remedies are more
/// iterations or smaller steps (each starts from the previous one's states,
/// so fewer points change state at once).
fn unsettled_bodies(scene: &Scene, model: &Model, iterations: usize, short: &[(usize, f64, String)]) -> Vec<String> {
    let mut bodies: Vec<usize> = model.dofs.rigid.iter().map(|rm| rm.body).collect();
    bodies.sort_unstable();
    bodies.dedup();
    bodies
        .into_iter()
        .map(|b| {
            let name = &scene.bodies[b].name;
            let worst = short
                .iter()
                .filter(|s| s.0 == b)
                .max_by(|x, y| x.1.total_cmp(&y.1))
                .filter(|s| s.1 > 1.0 + SHORTFALL_SLACK);
            match worst {
                Some((_, ratio, motion)) => format!(
                    "body '{name}' is held only by contact and most likely slides: the frictional iteration did not \
                        settle \
                     in {iterations} iterations, and with the normal forces of its last iterate the load along the \
                         {motion} \
                     is {ratio:.4} times the most friction can carry (μ times those normal forces); the check of the \
                         loads \
                     with the friction cone before the solve sees loads only, not normal forces made by prescribed \
                     displacements: keep the load along that motion below μ times the normal force, or press harder"
                ),
                None => format!(
                    "body '{name}' is held only by contact: the frictional iteration did not settle its points' stick \
                        and \
                     slip states in {iterations} iterations; its loads pass the check with the friction cone, and the \
                     normal forces of the last iterate leave friction enough to carry them: raise \
                         settings.max_iterations \
                     ({}), or apply the loads in more steps (load_path)",
                    scene.settings.max_iterations
                ),
            }
        })
        .collect()
}

/// Round-off allowance of `friction_shortfall`'s ratio: the sums it compares
/// are of the step's forces, exact to a few ε of the largest.
const SHORTFALL_SLACK: f64 = 1e-9;

/// Per free rigid motion of a body held only by contact in the block:
/// (body, ratio, motion in words), the ratio of what friction must carry
/// along the motion once the normal forces λ have taken their share,
/// |rhs − C_Nᵀλ − C_Tᵀτ₀|, to the most the cone allows, Σ |C_T| μ λ, with τ₀
/// the centre of each point's cone (−λ n · t, 0 but against another body).
/// Above 1 no friction force in the cones balances the motion at these λ.
fn friction_shortfall(
    scene: &Scene,
    model: &Model,
    block: &methods::friction::Block,
    t: &crate::contact::friction::Tangents,
    lambda: &[f64],
) -> Vec<(usize, f64, String)> {
    use crate::contact::free_motions::Motion;
    let mut out = Vec::new();
    for (j, &m) in block.keep.iter().enumerate() {
        let Motion::Body { set, dir } = model.free.motions[m].0 else {
            continue;
        };
        let normal: f64 = (0..block.cn.nrows()).map(|i| block.cn[(i, j)] * lambda[i]).sum();
        let (mut centre, mut reach) = (0.0, 0.0);
        for k in 0..t.len() {
            let l = lambda[t.of[k]].max(0.0);
            centre -= block.ct[(k, j)] * t.along(k, l, 0.0);
            reach += block.ct[(k, j)].abs() * t.bound(k, l);
        }
        let need = (block.rhs[j] - normal - centre).abs();
        // What the normal forces balance exactly (a translation normal to a
        // flat floor, which no cone reaches) leaves round-off, not a load.
        let scale = block.rhs[j].abs() + normal.abs() + reach;
        let ratio = if need <= SHORTFALL_SLACK * scale {
            0.0
        } else {
            need / reach
        };
        let rm = &model.dofs.rigid[set];
        out.push((rm.body, ratio, rm.describe(dir, scene.scales.length(1.0))));
    }
    out
}

/// Why a frictional step with a load-controlled punch may not converge: a
/// horizontal load beyond μ times the vertical one. The frictional
/// compatibility check refuses it on a flat face and on a curved punch over
/// a flat block (each candidate's cone is taken about both normals,
/// `FreeMotions::check_with_friction`); where the punch's and the body's
/// normals are inclined together (a face and a surface both sloping) it can
/// admit it, and a step that then does not converge gets this note.
fn sliding_punches(scene: &Scene) -> Vec<String> {
    use crate::scene::{Control, Target};
    scene
        .obstacles
        .iter()
        .enumerate()
        .filter_map(|(o, ob)| {
            let punch = ob.punch.as_ref()?;
            let (Control::Load(q), Control::Load(p)) = (punch.controls[0], punch.controls[1]) else {
                return None;
            };
            let mu = scene
                .pairs
                .iter()
                .filter(|pr| matches!(pr.target, Target::Obstacle(t) if t == o))
                .map(|pr| pr.friction)
                .fold(0.0, f64::max);
            (mu > 0.0 && q.abs() > mu * p.abs()).then(|| {
                format!(
                    "punch '{}': its horizontal load is {:.4} times its vertical load, more than the friction \
                        coefficient {mu}: \
                     on a flat face it would slide; on this profile the compatibility check admitted it (inclined \
                         normals), \
                     and the frictional iteration did not converge; the punch most likely slides (keep |Q| below μ|P|)",
                    ob.name,
                    q.abs() / p.abs().max(f64::MIN_POSITIVE)
                )
            })
        })
        .collect()
}
