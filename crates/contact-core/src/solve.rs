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
//! A 3D solid (`analysis: "solid"`) takes its own route, `solve::solid`
//! (`solve_solid`): one body, one plane, the same stages.
//!
//! The frictional route's step loop is `solve/frictional.rs`; its block of
//! punch and free-body motions `solve::friction_block`, its notes on a
//! step that fell short `solve::notes`.

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::admit::{self, Route};
use crate::cache::{self, OperatorCache};
use crate::error::CoreError;
use crate::fem::assembly::{assemble_loads, assemble_stiffness};
use crate::mesh::Mesh2d;
use crate::methods::{self, full};
use crate::model::Model;
use crate::observer::{self, Observer, Stage};
use crate::scene::{Limits, Method, Scene};
use crate::solution::compose::{self, Solved};
use crate::solution::report::{with_steps, CacheState, LoadStep, Report, Timings};

mod friction_block;
mod frictional;
mod notes;
mod screen;
mod solid;
use frictional::solve_frictional;
pub use solid::{solve_solid, solve_solid_once};

/// Solves the scene, once per load factor or load path step (one
/// factorization serves them all); with friction, step after step from the
/// state the previous one left (`solve_frictional`). Within the scene's own
/// time limit, if it has one. With `settings.accuracy`, round after round on
/// finer meshes; with `settings.estimate`, every pair's error estimated
/// (`adapt`), its companion solved beside the answer when a core is free
/// (`adapt::overlap`).
pub fn solve(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
    let _deadline = scene
        .time_limit
        .map(|s| crate::cancel::Deadline::install(std::time::Duration::from_secs_f64(s.min(1e9))));
    // The estimate's coarser companion and the refinement rounds are meshes
    // of their own: they bypass the service's operator cache (which would
    // keep operators no later request asks for).
    let uncached = |s: &Scene| solve_steps(s, limits, None);
    let _busy = crate::adapt::overlap::busy();
    if scene.settings.estimate || scene.settings.accuracy.is_some() {
        crate::progress::expect_estimate(crate::adapt::estimate_share(scene));
    }
    if let Some(target) = scene.settings.accuracy {
        return crate::adapt::refine(scene, target, &uncached, limits);
    }
    if !scene.settings.estimate {
        return solve_steps(scene, limits, cache);
    }
    let answer = || solve_steps(scene, limits, cache);
    crate::adapt::overlap::solve_estimated(scene, limits, answer, &uncached)
}

/// The scene once per load factor or load path step, without the error
/// estimate and the refinement (whose companions and rounds it solves).
pub fn solve_steps(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
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

/// The first stage of every route: the progress plan from the predicted
/// size, the meshes, and their admission against the limits.
fn meshed(scene: &Scene, limits: &Limits) -> Result<(Vec<Mesh2d>, Observer), CoreError> {
    let t6 = scene.bodies.iter().any(|b| b.is_t6());
    crate::progress::plan(observer::predicted(scene.estimated_nodes, t6));
    let mut obs = Observer::new();
    obs.enter(Stage::Mesh);
    let meshes = crate::meshing::meshes(scene)?;
    obs.leave(Stage::Mesh)?;
    admit::meshes(&meshes, limits)?;
    Ok((meshes, obs))
}

fn solve_once(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<Report, CoreError> {
    let t6 = scene.bodies.iter().any(|b| b.is_t6());
    let (meshes, mut obs) = meshed(scene, limits)?;
    let nodes: usize = meshes.iter().map(|m| m.nodes.len()).sum();
    let mut plan = observer::predicted(nodes as f64, t6);
    plan[0] = obs.timings.mesh;
    crate::progress::plan(plan);

    obs.enter(Stage::Assembly);
    let model = Arc::new(Model::build(scene, meshes)?);
    match admit::route(scene, model.parts(), limits)? {
        Route::Full => solve_full(scene, &model, obs),
        Route::Condensed => solve_condensed(scene, model, cache, obs),
    }
}

/// One factorization (or the cache's), the LCP on the contact rows.
fn solve_condensed(
    scene: &Scene,
    model: Arc<Model>,
    cache: Option<&OperatorCache>,
    mut obs: Observer,
) -> Result<Report, CoreError> {
    let key = cache::key(scene, &model.meshes, &model.dofs, &model.cons);
    let model_ref: &Model = &model;
    let screened = screen::applies(scene, model_ref);
    let (op, cache_state) = match cache.and_then(|c| c.get(key)) {
        Some(op) => {
            crate::progress::revise(crate::outcome::ProgressStage::Factorization, 0.0);
            crate::progress::revise(crate::outcome::ProgressStage::Condensation, 0.0);
            (op, CacheState::Hit)
        }
        None => {
            let stiffness = Arc::new(assemble_stiffness(scene, &model.meshes, &model.dofs)?);
            obs.leave(Stage::Assembly)?;
            obs.enter(Stage::Factorization);
            let op = match screened {
                true => methods::condensed::prepare_factor(stiffness, cache)?,
                false => methods::condensed::prepare(stiffness, &model.cons, cache)?,
            };
            obs.timings.factorization = op.t_factorization;
            obs.timings.condensation = op.t_condensation;
            (Arc::new(op), cache.map_or(CacheState::Off, |_| CacheState::Miss))
        }
    };
    obs.check(Stage::Factorization)?;
    let f = assemble_loads(&model.external, &model.dofs, &op.stiffness);
    let compliance = (!model.foundations.is_empty()).then(|| model.foundations.compliance(&model.cons));
    obs.enter(Stage::ContactSolve);
    let fresh = op.clone();
    let s = screen::solve_rows(scene, model_ref, op, &f, compliance.as_ref(), screened)?;
    obs.leave(Stage::ContactSolve)?;
    let (op, sol) = (s.op, s.sol);
    obs.timings.contact_solve = sol.t_contact;
    obs.timings.condensation += s.t_condensation;
    if let Some(c) = cache.filter(|_| cache_state != CacheState::Hit || !Arc::ptr_eq(&op, &fresh)) {
        c.insert(key, op.clone());
    }
    let solved = Solved {
        model: model_ref,
        k: &op.stiffness.k,
        f: &f,
        loads: None,
        pivot_ratio: Some(op.pivot_ratio),
        predicted: Some(op.chol.cost().predicted_secs()),
        compliance: compliance.as_ref(),
        friction: &[],
        operator: Some((model.clone(), op.clone())),
    };
    let mut report = compose::report(scene, &solved, sol, obs, cache_state);
    report.diagnostics.condensed_rows = op.rows.as_ref().map(Vec::len);
    Ok(report)
}

/// The energy bound solves with the condensed route's operator
/// (`energy::Pending`).
impl crate::solution::energy::Operator for cache::Prepared {
    fn stiffness(&self) -> &faer::sparse::SparseColMat<usize, f64> {
        &self.stiffness.k
    }
    fn factor(&self) -> &crate::linalg::Cholesky {
        &self.chol
    }
}

/// Exact methods on the whole system: no condensation, no cache (they are
/// the comparison, and `auto`'s choice for many rows on few DOFs).
fn solve_full(scene: &Scene, model: &Model, mut obs: Observer) -> Result<Report, CoreError> {
    // No factorization stage of its own: the active set refactors a few times
    // inside the contact solve.
    let factor = observer::predicted(model.dofs.n_free as f64 / 2.0, false)[2];
    crate::progress::revise(crate::outcome::ProgressStage::Factorization, 0.0);
    crate::progress::revise(crate::outcome::ProgressStage::Condensation, 0.0);
    crate::progress::revise(crate::outcome::ProgressStage::ContactSolve, 3.0 * factor);
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
        loads: None,
        pivot_ratio: None,
        predicted: None,
        compliance: None,
        friction: &[],
        operator: None,
    };
    Ok(compose::report(scene, &solved, sol, obs, CacheState::Off))
}
