//! What can only be judged after meshing: the one step that refuses a request
//! once its meshes and contact rows exist (sizes the estimates before meshing
//! could not settle, pairs that found nothing to touch, a formulation the
//! scene cannot run on), and the choice of route for the rest.
//!
//! Validation (`scene::validate`) refuses everything that can be known from
//! the request alone; two refusals stay with the computation that discovers
//! them, because the test is the computation: supports that leave a body
//! free (`fem::assembly::dof_map`, its rigid modes) and loads no
//! non-negative pressure can balance (`contact::free_motions`, an LP), and a
//! half-plane reference distance too short for the loaded length
//! (`contact::compliance`).

use crate::contact::{compliance::Foundations, free_motions::FreeMotions, ConstraintSet};
use crate::error::{CoreError, InvalidKind};
use crate::fem::{loads::Located, DofMap};
use crate::mesh::Mesh2d;
use crate::scene::scaling::shown;
use crate::scene::{Discretization, Formulation, Limits, Method, Scene, Target, Traction};

/// Where the contact problem is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Route {
    /// One factorization, the LCP on the contact rows (cacheable).
    Condensed,
    /// Exact methods on the whole system.
    Full,
}

/// The meshes against the deployment's size limit (the estimate before
/// meshing is within ±7 %; this is the exact count).
pub fn meshes(meshes: &[Mesh2d], limits: &Limits) -> Result<(), CoreError> {
    let n_dofs: usize = meshes.iter().map(|m| 2 * m.nodes.len()).sum();
    if n_dofs > limits.max_dofs {
        return Err(CoreError::TooLarge {
            path: "/bodies".into(),
            reason: format!(
                "{n_dofs} degrees of freedom; this service accepts at most {}",
                limits.max_dofs
            ),
        });
    }
    Ok(())
}

/// Ray casts a two-body pair may cost (each slave point against each master
/// edge, about 20 flops): a request is refused before the search rather than
/// tying a worker up for minutes on a pair of huge edge sets.
const MAX_SEARCH_CASTS: f64 = 4e8;

/// The contact search of every two-body pair against `MAX_SEARCH_CASTS`.
pub fn search_work(scene: &Scene, meshes: &[Mesh2d]) -> Result<(), CoreError> {
    for pair in &scene.pairs {
        let Target::Body {
            body,
            edges,
            discretization,
        } = &pair.target
        else {
            continue;
        };
        let slave = meshes[pair.body].edge_sets.get(&pair.edges).map_or(0, |e| e.len()) as f64;
        let master = meshes[*body].edge_sets.get(edges).map_or(0, |e| e.len()) as f64;
        // Mortar: 4 Gauss points on each of about two sub-segments per slave edge.
        let points = match discretization {
            Discretization::Mortar => 8.0 * slave,
            Discretization::NodeToSegment => slave + 1.0,
        };
        if points * master > MAX_SEARCH_CASTS {
            return Err(CoreError::TooLarge {
                path: format!("{}/edges", pair.path),
                reason: format!(
                    "the contact search of this two-body pair would cast {:.1e} rays ({} slave edges against {} master \
                        edges); this service accepts at most {MAX_SEARCH_CASTS:.0e}: restrict the edge sets to the \
                        faces that can touch",
                    points * master,
                    slave,
                    master
                ),
            });
        }
    }
    Ok(())
}

/// Where every point load falls on its edge set; a point off it is an
/// `invalid_geometry` at the load's `at`.
pub fn point_loads(scene: &Scene, meshes: &[Mesh2d]) -> Result<Vec<Vec<Located>>, CoreError> {
    if scene.analysis == crate::scene::Analysis::Axisymmetric {
        // A ring of radius 0 has no radial direction: the axis node's u_r is
        // held, so a radial force there would vanish into it unseen.
        for (body, mesh) in scene.bodies.iter().zip(meshes) {
            for pl in &body.point_loads {
                if pl.at[0] <= mesh.axis_tolerance() && pl.force[0] != 0.0 {
                    return Err(CoreError::invalid(
                        InvalidKind::Request,
                        format!("{}/force/0", pl.path),
                        "a point load on the axis of a body of revolution is axial: its radial component must be 0",
                    ));
                }
            }
        }
    }
    crate::fem::loads::locate_all(scene, meshes)
}

/// Every surface load with an `x_range` loads some part of its edge set: a
/// range that misses the set would load nothing, and the solve would answer
/// a different question without a word.
pub fn traction_ranges(scene: &Scene, meshes: &[Mesh2d]) -> Result<(), CoreError> {
    for (body, mesh) in scene.bodies.iter().zip(meshes) {
        for (k, t) in body.tractions.iter().enumerate() {
            let (edges, range) = match t {
                Traction::Vector { edges, x_range, .. } | Traction::Pressure { edges, x_range, .. } => (edges, x_range),
            };
            let (Some(range), Some(set)) = (range, mesh.edge_sets.get(edges)) else {
                continue;
            };
            if set
                .iter()
                .any(|e| crate::fem::loads::clip(mesh, e, Some(*range)).is_some())
            {
                continue;
            }
            let xs = set.iter().flat_map(|e| [mesh.nodes[e.a][0], mesh.nodes[e.b][0]]);
            let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| (l.min(x), h.max(x)));
            let l = |x: f64| scene.scales.length(x);
            return Err(CoreError::invalid(
                InvalidKind::Request,
                format!("{}/tractions/{k}/x_range", body.path),
                format!(
                    "x_range [{}, {}] meets no edge of set '{edges}', whose x spans [{}, {}]: the load would act \
                        nowhere",
                    shown(l(range[0])),
                    shown(l(range[1])),
                    shown(l(lo)),
                    shown(l(hi))
                ),
            ));
        }
    }
    Ok(())
}

/// Every pair has at least one contact row.
pub fn candidates(scene: &Scene, cons: &ConstraintSet) -> Result<(), CoreError> {
    for (p, pair) in scene.pairs.iter().enumerate() {
        if !cons.candidates.iter().any(|c| c.pair == p) {
            return Err(CoreError::invalid(
                InvalidKind::NoContactCandidates,
                format!("{}/edges", pair.path),
                format!(
                    "no node of edge set '{}' can reach {} along its outward normal ({} pruned: the ray misses the \
                        obstacle or the gap exceeds prune_gap_ratio × body size)",
                    pair.edges,
                    target_name(scene, &pair.target),
                    cons.pruned[p]
                ),
            ));
        }
    }
    Ok(())
}

/// Largest problem the full-system interior point accepts: Clarabel on the
/// full QP needs about 4 GB and a minute at 1M DOF.
const FULL_IPM_MAX_DOFS: usize = 200_000;

/// The discrete model's parts the route depends on (`model::Model` holds them).
pub struct Parts<'a> {
    pub dofs: &'a DofMap,
    pub cons: &'a ConstraintSet,
    pub free: &'a FreeMotions,
    pub foundations: &'a Foundations,
}

/// The route of the solve, refusing a formulation the scene cannot run on
/// and a condensed operator over the candidate limit.
pub fn route(scene: &Scene, model: Parts, limits: &Limits) -> Result<Route, CoreError> {
    let (free, cons) = (model.free, model.cons);
    if scene.settings.formulation == Formulation::Full {
        if !free.motions.is_empty() || !model.foundations.is_empty() {
            return Err(CoreError::invalid(
                InvalidKind::Request,
                "/settings/formulation",
                "load-controlled punches, bodies held only by contact and foundations are solved on the condensed \
                    formulation only",
            ));
        }
        if !cons.rows_are_nodal() {
            return Err(CoreError::invalid(
                InvalidKind::Request,
                "/settings/formulation",
                "the full formulation needs nodal contact rows (one node per row, as T3 and discretization 'nodal' \
                    give); mortar rows (the T6 default) and two-body rows are solved on the condensed formulation only",
            ));
        }
        return full_method(scene, model.dofs.n_free).map(|()| Route::Full);
    }
    if scene.method == Method::Auto
        && free.motions.is_empty()
        && model.dofs.rigid.is_empty()
        && model.foundations.is_empty()
        && cons.rows_are_nodal()
        && full_is_cheaper(model.dofs.n_free, cons.len())
    {
        return Ok(Route::Full);
    }
    // The condensed operator is dense in the candidates: bounded by the limit.
    if cons.len() > limits.max_candidates {
        return Err(CoreError::TooLarge {
            path: "/contacts".into(),
            reason: format!(
                "{} contact candidates; this service accepts at most {} on the condensed formulation",
                cons.len(),
                limits.max_candidates
            ),
        });
    }
    Ok(Route::Condensed)
}

/// The full formulation runs the exact methods only, the interior point up to
/// `FULL_IPM_MAX_DOFS`.
fn full_method(scene: &Scene, n_free: usize) -> Result<(), CoreError> {
    match scene.method {
        Method::Auto | Method::ActiveSet => Ok(()),
        Method::InteriorPoint if n_free > FULL_IPM_MAX_DOFS => Err(CoreError::TooLarge {
            path: "/settings/formulation".into(),
            reason: format!(
                "interior_point on the full formulation is limited to {FULL_IPM_MAX_DOFS} DOFs ({} requested); use the \
                    condensed formulation",
                n_free
            ),
        }),
        Method::InteriorPoint => Ok(()),
        other => Err(CoreError::invalid(
            InvalidKind::Request,
            "/settings/formulation",
            format!(
                "the full formulation is offered for the exact methods active_set and interior_point, not {other:?}"
            ),
        )),
    }
}

/// Whether `auto` should solve on the full system: the condensed path costs
/// about 1.2e-10 m³ s of dense work on this machine (W and the LCP, measured
/// 0.18 s at m = 1000 and 6.8 s at m = 4000), the full active set a few
/// factorizations of about 1.8e-7 n^1.2 s each (0.126 s at 75k DOF, 1.74 s at
/// 612k); the full path wins when the first exceeds about ten of the second
/// (strip of 1000 candidates on 5k DOF: 0.18 s condensed, 0.02 s full; the
/// Hertz scenes stay condensed).
fn full_is_cheaper(n_free: usize, m: usize) -> bool {
    (m as f64).powi(3) > 1.5e4 * (n_free as f64).powf(1.2)
}

/// The route of a frictional step over its rows: the full system
/// (`methods::friction::full`) when the request asks for it, when `auto`
/// finds it cheaper, or when the rows exceed what the condensed operator
/// (dense in them) may hold, with a note saying so; the free motions of a
/// block (load-controlled punches, bodies held only by contact) only
/// condensed, and the full system only on nodal rows.
pub fn frictional_route(
    scene: &Scene,
    cons: &ConstraintSet,
    tangents: &crate::contact::friction::Tangents,
    n_free: usize,
    block: bool,
    limits: &Limits,
) -> Result<(Route, Option<String>), CoreError> {
    const CONDENSED_ONLY: &str =
        "load-controlled punches and bodies held only by contact are solved with friction on the condensed formulation \
            only";
    // Why the full system cannot take the step; asked only where it might.
    let unfit = || {
        if block {
            Some(CONDENSED_ONLY)
        } else {
            crate::methods::friction::full::unfit(cons, tangents)
        }
    };
    let (normal, tangential) = (cons.len(), tangents.len());
    let rows = normal + tangential;
    if scene.settings.formulation == Formulation::Full {
        return match unfit() {
            Some(why) => Err(CoreError::invalid(InvalidKind::Request, "/settings/formulation", why)),
            None => Ok((Route::Full, None)),
        };
    }
    if rows <= limits.max_candidates {
        let cheaper = scene.method == Method::Auto && frictional_full_is_cheaper(n_free, rows) && unfit().is_none();
        return Ok((if cheaper { Route::Full } else { Route::Condensed }, None));
    }
    if let Some(why) = unfit() {
        return Err(CoreError::TooLarge {
            path: "/contacts".into(),
            reason: format!(
                "{rows} contact rows ({normal} normal and {tangential} tangential); this service accepts at most {} on \
                    the condensed formulation, and {why}",
                limits.max_candidates
            ),
        });
    }
    let note = format!(
        "solved on the full system (active_set_full): {rows} contact rows ({normal} normal and {tangential} \
            tangential) exceed the {} the condensed formulation holds",
        limits.max_candidates
    );
    Ok((Route::Full, Some(note)))
}

/// Whether a frictional step is cheaper on the full system. A condensed
/// Newton iteration factors the dense system of the points in contact (up
/// to all r rows: about 1.85e-11 r³ s here), a full one K and runs GMRES
/// (about twice a factorization, 3.6e-7 n^1.2 s), both about as many times:
/// equal at r³ = 2e4 n^1.2. Measured on a T3 strip on a rigid floor, three
/// steps of pressing and shearing with every bottom node in contact
/// (condensed against full): 20k DOF, 1002 rows, 0.75 s against 0.59 s;
/// 40k, 2002 rows, 3.4 against 1.3 s; 80k, 3998 rows, 24 against 2.8 s (the
/// condensed W alone 1 GB). The full system wins earlier than the model
/// says (the condensed path also builds W), so the constant is set to 1e4,
/// between the first two strips (r³/n^1.2 = 0.69e4 and 2.4e4); the Hertz and
/// roller scenes (a few hundred rows, r³/n^1.2 < 1e3) stay condensed.
fn frictional_full_is_cheaper(n_free: usize, rows: usize) -> bool {
    (rows as f64).powi(3) > 1e4 * (n_free as f64).powf(1.2)
}

/// How a pair's target is named in messages.
fn target_name(scene: &Scene, target: &Target) -> String {
    match target {
        Target::Obstacle(o) => format!("obstacle '{}'", scene.obstacles[*o].name),
        Target::Body { body, edges, .. } => {
            format!("edge set '{edges}' of body '{}'", scene.bodies[*body].name)
        }
        Target::Foundation(f) => format!("foundation '{}'", scene.foundations[*f].name),
    }
}
