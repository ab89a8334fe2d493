//! The 3D route: a `SolidScene` (`analysis: "solid"`) solved stage by stage
//! as the 2D routes are, with the same deadline, cancellation and progress:
//!
//! ```text
//! SolidScene ─mesh→ Mesh3d ─admit→ ─rows→ ObstacleRows
//!   ─assemble, factor (nested dissection, admitted by predicted time),
//!    condense→ Operator ─LCP per load factor or load path step→ Contact
//!    (`solid::signorini`, `solid::path`)
//!   ─report→ SolidAnswer
//!   ─estimate (a coarser companion, `adapt::solid`)→ SolidAnswer.accuracy
//! ```
//!
//! With `settings.accuracy`, `adapt::solid` runs these stages round by
//! round.
//!
//! The dimension lives in the `mesh3d` and `solid` rooms; this file only
//! orders their stages and times them.

use crate::error::CoreError;
use crate::mesh3d::generate::box_mesh;
use crate::mesh3d::Order;
use crate::observer::{self, Observer, Stage};
use crate::outcome::ProgressStage;
use crate::outcome::Status;
use crate::scene::solid::SolidMesh;
use crate::scene::solid::SolidScene;
use crate::scene::Limits;
use crate::solid::answer::{dimensional, status, BodyFields, SolidAnswer, SolidStep};
use crate::solid::door::SolidProblem;
use crate::solid::obstacle::rows_with;
use crate::solid::path as solid_path;
use crate::solid::report::report;
use crate::solid::signorini::Contact;
use crate::solid::two_level::Surface;
use crate::solid::validity::{coarse_patches, large_displacement};
use crate::solid::{fields, signorini, SolidBody};
use crate::solution::report::{worst_of_steps, Warning};

/// Solves the 3D problem within its time limit, if it has one, with its
/// error estimate, or refined round by round to `settings.accuracy`
/// (`adapt::solid`).
pub fn solve_solid(problem: &SolidProblem, limits: &Limits) -> Result<SolidAnswer, CoreError> {
    let _deadline = problem
        .scene
        .time_limit
        .map(|s| crate::cancel::Deadline::install(std::time::Duration::from_secs_f64(s.min(1e9))));
    // A core this solve keeps busy is not free for a 2D estimate's companion.
    let _busy = crate::adapt::overlap::busy();
    let once = |p: &SolidProblem| solve_solid_once(p, limits);
    match problem.scene.settings.accuracy {
        Some(target) => crate::adapt::solid::refine(problem, target, &once, limits),
        None => {
            if problem.scene.settings.estimate {
                crate::progress::expect_estimate(crate::adapt::solid::COMPANION_SHARE);
            }
            let (mut answer, surface) = once(problem)?;
            crate::adapt::solid::estimate(problem, &mut answer, &surface, &once);
            Ok(answer)
        }
    }
}

/// One solve of the problem on its mesh, without its estimate or rounds
/// (and without installing its time limit): the answer, and its candidate
/// surface for the estimate (`adapt::solid`) or a verification's own.
pub fn solve_solid_once(problem: &SolidProblem, limits: &Limits) -> Result<(SolidAnswer, Surface), CoreError> {
    let scene = &problem.scene;
    // The 2D plan counts 2 DOFs per node: 3D's are 1.5 times as many per
    // node. Its factorization is revised from the symbolic analysis.
    let t10 = problem.t10();
    crate::progress::plan(observer::predicted(1.5 * scene.estimated_nodes, t10));
    let mut obs = Observer::new();
    obs.enter(Stage::Mesh);
    let generated;
    let mesh = match (&problem.mesh, &scene.mesh) {
        (Some(m), _) => m,
        (
            None,
            SolidMesh::Box {
                lo,
                hi,
                size,
                grading,
                t10,
            },
        ) => {
            let order = if *t10 { Order::T10 } else { Order::T4 };
            generated = box_mesh(*lo, *hi, *size, *grading, order);
            &generated
        }
        (None, _) => unreachable!("`solid::door::admit` builds every given mesh"),
    };
    obs.leave(Stage::Mesh)?;
    if 3 * mesh.nodes.len() > limits.max_dofs {
        return Err(CoreError::TooLarge {
            path: "/solid/body/mesh".into(),
            reason: format!(
                "the mesh has {} degrees of freedom; this service solves at most {}",
                3 * mesh.nodes.len(),
                limits.max_dofs
            ),
        });
    }
    obs.enter(Stage::Assembly);
    let body = SolidBody {
        mesh,
        youngs_modulus: 1.0,
        poisson_ratio: scene.poisson_ratio,
        supports: scene.supports.clone(),
        loads: scene.loads.clone(),
        body_force: scene.body_force,
    };
    let t_rows = std::time::Instant::now();
    let rows = rows_with(&body, &scene.faces, scene.shape.clone(), &|x| scene.extra_gap(x)).map_err(located)?;
    if rows.len() > limits.max_candidates {
        // The condensed operator is dense in the rows (`Limits::max_candidates`).
        return Err(CoreError::TooLarge {
            path: "/solid/contact/faces".into(),
            reason: format!(
                "face set '{}' has {} contact rows; this service condenses at most {} (coarsen the mesh there)",
                scene.faces,
                rows.len(),
                limits.max_candidates
            ),
        });
    }
    let rows_secs = t_rows.elapsed().as_secs_f64();
    let path: Vec<_> = scene.load_path.iter().map(|s| scene.at_step(s)).collect();
    let stepped = !scene.load_factors.is_empty() || !path.is_empty();
    let factors = if scene.load_factors.is_empty() {
        vec![1.0]
    } else {
        scene.load_factors.clone()
    };
    // One operator for every factor or step: only q and the motions' loads change.
    let mem = limits.memory_bytes();
    let op = if path.is_empty() {
        signorini::prepare_within(&body, &rows, &factors, mem)
    } else {
        solid_path::prepare_path(&body, &rows, &path, mem)
    }
    .map_err(located)?;
    obs.timings.assembly = rows_secs + op.seconds[0];
    obs.timings.factorization = op.seconds[1];
    let tol = scene.settings.tolerance;
    let (mut steps, mut last) = (Vec::new(), None);
    // Every step's warnings, not the last step's alone: a path may pass
    // through a load far larger than the one it ends on, or a patch far
    // narrower (merged as 2D's `report::with_steps`).
    let mut warned: Vec<(String, Vec<Warning>)> = Vec::new();
    // (factor, load path step): a path's steps answer with factor 1 (2D's).
    let runs: Vec<(f64, Option<usize>)> = if path.is_empty() {
        factors.iter().map(|&k| (k, None)).collect()
    } else {
        (0..path.len()).map(|i| (1.0, Some(i))).collect()
    };
    for (factor, at) in runs {
        let (contact, loads) = match at {
            None => (op.solve(&body, &rows, &scene.settings, factor), None),
            Some(i) => {
                // A load path step's answer echoes its loads.
                let b = solid_path::step_body(&body, &path[i]);
                let l = solid_path::step_loads(&b, &rows).map_err(|e| solid_path::at_step(e, i))?;
                let given = scene.load_path[i].given.clone();
                (op.solve_loads(&b, &rows, &scene.settings, &l), Some(given))
            }
        };
        let contact = contact.map_err(located)?;
        obs.timings.contact_solve += contact.seconds[2];
        obs.check(Stage::ContactSolve)?;
        let rep = report(&body, &rows, &contact).map_err(located)?;
        let mut w = large_displacement(&body, &contact.u, &scene.body);
        w.extend(coarse_patches(&body, &rows, &rep, scene.length));
        let label = match at {
            Some(i) => format!("load path step {i}"),
            None => format!("load factor {factor}"),
        };
        warned.push((label, w));
        if stepped {
            steps.push(SolidStep {
                factor,
                loads,
                status: status(&rep, tol),
                report: dimensional(rep.clone(), scene),
                max_penetration: max_penetration(&contact, scene),
            });
        }
        last = Some((contact, rep));
    }
    let (contact, rep) = last.expect("at least one factor");
    obs.enter(Stage::Post);
    let surface = Surface::of(&body, &rows, &contact, rep.resultant.force).map_err(located)?;
    let o = scene.outputs;
    let fields = (o.mesh || o.displacement || o.stress || o.vtu).then(|| {
        let s = if o.stress || o.vtu {
            fields::stress(&body, &contact.u)
        } else {
            Vec::new()
        };
        BodyFields::dimensional(&mesh.nodes, &mesh.elems, &fields::displacement(&contact.u), &s, scene)
    });
    obs.leave(Stage::Post)?;
    let max_penetration = max_penetration(&contact, scene);
    let active = contact.lambda.iter().filter(|&&l| l > 0.0).count();
    // Only as good as its worst step, as 2D's `with_steps`.
    let status = steps
        .iter()
        .map(|s| s.status)
        .find(|s| *s != Status::Solved)
        .unwrap_or_else(|| status(&rep, tol));
    crate::progress::stage(ProgressStage::Post);
    let last_warnings = warned.pop().map(|(_, w)| w).unwrap_or_default();
    let warnings = worst_of_steps(last_warnings, warned.iter().map(|(l, w)| (l.clone(), w.as_slice())));
    let answer = SolidAnswer {
        body: scene.body.clone(),
        obstacle: scene.obstacle.clone(),
        faces: scene.faces.clone(),
        order: mesh.order,
        status,
        report: dimensional(rep, scene),
        max_penetration,
        dofs: contact.dofs.n_free,
        candidates: rows.len(),
        active,
        refinements: contact.refinements,
        factor_bytes: op.factor_bytes,
        timings: obs.finish(),
        client_id: scene.client_id.clone(),
        outputs: o,
        fields,
        steps: stepped.then_some(steps),
        accuracy: None,
        refinement: None,
        notes: Vec::new(),
        warnings,
    };
    Ok((answer, surface))
}

/// The largest penetration of a row, in the request's length.
fn max_penetration(contact: &Contact, scene: &SolidScene) -> f64 {
    contact.gap.iter().fold(0.0f64, |a, g| a.max(-g)) * scene.length
}

/// A refusal of the `solid` room, whose paths name the body's fields
/// (`supports`, `loads`, `contact/faces`), at its place in the request.
fn located(e: CoreError) -> CoreError {
    match e {
        CoreError::Invalid {
            kind,
            path,
            reason,
            loads,
        } if !path.starts_with('/') => {
            let path = match path.as_str() {
                "loads" => "/solid/body/tractions".to_string(),
                "contact/faces" => "/solid/contact/faces".to_string(),
                "obstacle" => "/solid/obstacle".to_string(),
                p => format!("/solid/body/{p}"),
            };
            CoreError::Invalid {
                kind,
                path,
                reason,
                loads,
            }
        }
        other => other,
    }
}
