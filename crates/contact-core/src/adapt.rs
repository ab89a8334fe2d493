//! The error bar of an answer, and refinement until it meets a requested
//! accuracy.
//!
//! **Estimate.** After the solve, the same scene is solved again with every
//! generated element twice as large (`h_min`, the grading's `ratio − 1` and
//! `size` × 2, the graded window unchanged), and each pair's nodal pressure,
//! peak and resultant are compared (`solution::accuracy::two_level`). The
//! coarser solve has about a quarter of the unknowns: its cost is measured in
//! `timings.estimate` (14–16 % of the solve on the Hertz example at 30k–391k
//! DOF). A scene with an inline or Gmsh mesh cannot be coarsened; its pairs
//! carry only the zone ends' uncertainty (`basis: zone_edges`).
//!
//! **Refinement** (`settings.accuracy`). Round after round the generated
//! meshes' smallest element `h_min` is halved, the grading's growth
//! `ratio − 1` and the far-field `size` shrink by √2 (`ROUND_FIELD`; with
//! `h_min` alone the T3 disk's resultant stayed 0.22 % stiff at every level),
//! and the graded window is widened to cover every zone the last round found
//! (with a quarter of margin). A given (inline or Gmsh) mesh is bisected
//! around its zones instead (`mesh::bisect`: conforming, its edge sets kept);
//! its far field keeps the user's elements, so its rounds' estimates see the
//! zones' error, not the far field's. Each round's estimate compares it with
//! the round before (ratio 2 in the zones' element size); the first round's
//! with its coarser companion. The rounds stop when every estimate meets its
//! target, or at `max_rounds`, at `max_dofs` (predicted from the growth of the
//! last round), at the service's size or time limit, when two rounds in a row
//! do not improve the estimate, or when a round fails (its mesh, its
//! numerics): the answer is then the last round that solved, `solved` with a
//! `tolerance_not_reached` warning.

use std::time::Instant;

use crate::error::CoreError;
use crate::mesh::generate::Grading;
use crate::scene::{AccuracyTarget, MeshSource, Scene};
use crate::solution::accuracy;
use crate::solution::report::{PairAccuracy, Refinement, Report, Round, Status, Warning};

/// Element size ratio of the estimate's coarser companion and of one round
/// in the zones.
const RATIO: f64 = 2.0;
/// A round's factor on the grading's growth (ratio − 1) and the far-field
/// size: the error sits at the zones, and halving these too made each round
/// 4× larger (the T3 disk from h_min = 0.02 R met 0.5 % at 27.6k DOF in
/// 0.11 s; by 1/√2, at 9.9k DOF in 0.04 s; the T6 one, with its multipliers
/// on the corners then, stopped at 110k DOF short of it, and by 1/√2 met it
/// at 118k DOF; with one on every node it meets it at 13.7k DOF).
const ROUND_FIELD: f64 = std::f64::consts::FRAC_1_SQRT_2;
/// Growth of the graded window over the farthest zone end it must cover.
const MARGIN: f64 = 1.25;
/// A round that does not bring the estimate below this fraction of the
/// previous one is not converging (the answer sits at a floor the sizing
/// does not move).
const PROGRESS: f64 = 0.9;

/// A solve of a whole scene (its load factors included).
pub type Solver<'a> = dyn Fn(&Scene) -> Result<Report, CoreError> + 'a;

/// Fills every pair's `accuracy` of a solved report: the two-level estimate
/// when the meshes can be coarsened and the coarser solve succeeds, else the
/// zone ends alone (with a note saying why).
pub fn estimate(scene: &Scene, report: &mut Report, solve: &Solver) {
    let t = Instant::now();
    let coarse = (report.status == Status::Solved)
        .then(|| resized(scene, [RATIO; 3], None))
        .flatten()
        .map(|c| {
            // The companion's progress would restart the caller's bar.
            let _mute = crate::progress::Sink::install(|_| {});
            solve(&c)
        });
    match coarse {
        Some(Ok(c)) if c.status == Status::Solved && c.pairs.len() == report.pairs.len() => {
            for (f, cp) in report.pairs.iter_mut().zip(&c.pairs) {
                f.accuracy = Some(accuracy::two_level(f, cp, RATIO));
            }
        }
        other => {
            if let Some(why) = match other {
                Some(Ok(c)) => Some(format!(
                    "the error estimate's coarser solve (elements twice as large) ended {:?}; only the zone ends' uncertainty is estimated",
                    c.status
                )),
                Some(Err(e)) => Some(format!(
                    "the error estimate's coarser solve (elements twice as large) failed: {e}; only the zone ends' uncertainty is estimated"
                )),
                None => None,
            } {
                report.notes.push(why);
            }
            for p in report.pairs.iter_mut() {
                p.accuracy = Some(accuracy::zone_edges_only(p));
            }
        }
    }
    let dt = t.elapsed().as_secs_f64();
    report.timings.estimate += dt;
    report.timings.total += dt;
}

/// Solves, estimates and refines until `target` is met or a limit stops the
/// rounds (module doc).
pub fn refine(scene: &Scene, target: AccuracyTarget, solve: &Solver) -> Result<Report, CoreError> {
    let started = Instant::now();
    crate::progress::round(1);
    let mut report = solve(scene)?;
    estimate(scene, &mut report, solve);
    let mut current = scene.clone();
    let mut rounds = vec![round(&current, &report, started.elapsed().as_secs_f64())];
    let mut growth = None::<f64>;
    let mut stalled = 0;
    let mut failure = None::<String>;
    let stopped = loop {
        if met(&report, &target) {
            break "reached";
        }
        if report.status != Status::Solved {
            break "not_solved";
        }
        if rounds.len() >= target.max_rounds {
            break "max_rounds";
        }
        let next = resized(&current, [1.0 / RATIO, ROUND_FIELD, ROUND_FIELD], Some(&report))
            .expect("refining always succeeds");
        // Unknowns grow by about the last round's factor (4 before the first).
        if report.size.dofs as f64 * growth.unwrap_or(4.0) > target.max_dofs as f64 {
            break "max_dofs";
        }
        let t = Instant::now();
        crate::progress::round(rounds.len() + 1);
        let mut fine = match solve(&next) {
            Ok(r) => r,
            Err(CoreError::Timeout { .. }) => break "time_limit",
            Err(CoreError::TooLarge { .. }) => break "size_limit",
            // A later round that cannot be solved (its mesh, its numerics)
            // leaves the last round's answer standing.
            Err(e) => {
                failure = Some(e.to_string());
                break "round_failed";
            }
        };
        if fine.pairs.len() == report.pairs.len() {
            for (f, c) in fine.pairs.iter_mut().zip(&report.pairs) {
                f.accuracy = Some(accuracy::two_level(f, c, RATIO));
            }
        }
        growth = Some(fine.size.dofs as f64 / report.size.dofs.max(1) as f64);
        let r = round(&next, &fine, t.elapsed().as_secs_f64());
        let last = *rounds.last().expect("one round ran");
        rounds.push(r);
        let better = |now: f64, before: f64| now <= PROGRESS * before;
        let improving = match (r.pressure_l2, last.pressure_l2) {
            (Some(a), Some(b)) if target.pressure_l2.is_some() => better(a, b),
            _ => target.zone_edge.is_none() || better(r.zone_edge, last.zone_edge) || r.zone_edge == 0.0,
        };
        report = fine;
        current = next;
        // Where the zone edge falls between nodes makes single rounds step
        // up as well as down (measured on the disk: 1.03, 1.08, 0.20, 0.21,
        // 0.10 % over five T6 levels with corner multipliers, T3 0.43, 0.24,
        // 0.26, 0.24 %): only two rounds without progress stop.
        stalled = if improving { 0 } else { stalled + 1 };
        if stalled >= 2 && !met(&report, &target) {
            break "not_converging";
        }
    };
    let total = started.elapsed().as_secs_f64();
    // The earlier rounds' time counts as the estimate's.
    report.timings.estimate += (total - report.timings.total).max(0.0);
    report.timings.total = total;
    let reached = stopped == "reached";
    if !reached {
        report
            .warnings
            .push(not_reached(&report, &target, stopped, failure.as_deref()));
    }
    report.refinement = Some(Refinement {
        reached,
        stopped,
        rounds,
    });
    Ok(report)
}

/// Whether every pair's estimate meets the target.
fn met(report: &Report, target: &AccuracyTarget) -> bool {
    let (p, z) = worst(report);
    target.pressure_l2.is_none_or(|t| p.is_some_and(|p| p <= t)) && target.zone_edge.is_none_or(|t| z <= t)
}

/// The largest estimates over the pairs: pressure (None if no pair has a
/// two-level estimate), zone end.
fn worst(report: &Report) -> (Option<f64>, f64) {
    let acc: Vec<&PairAccuracy> = report.pairs.iter().filter_map(|p| p.accuracy.as_ref()).collect();
    let p = acc
        .iter()
        .filter_map(|a| a.pressure_l2)
        .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
    let z = acc
        .iter()
        .flat_map(|a| a.zone_edges.iter().flatten())
        .fold(0.0, |m: f64, &v| m.max(v));
    (p, z)
}

fn round(scene: &Scene, report: &Report, seconds: f64) -> Round {
    let (pressure_l2, zone_edge) = worst(report);
    Round {
        dofs: report.size.dofs,
        h_min: smallest_size(scene),
        pressure_l2,
        zone_edge,
        seconds,
    }
}

fn not_reached(report: &Report, target: &AccuracyTarget, stopped: &str, failure: Option<&str>) -> Warning {
    let (p, z) = worst(report);
    let why = match stopped {
        "max_rounds" => format!("after {} rounds (max_rounds)", target.max_rounds),
        "max_dofs" => format!("the next round would exceed max_dofs = {}", target.max_dofs),
        "size_limit" => "the next round exceeds the service's size limit".into(),
        "time_limit" => "the next round ran past the time limit".into(),
        "not_solved" => "a round did not solve".into(),
        "round_failed" => format!("the next round failed: {}", failure.unwrap_or("unknown")),
        _ => "a round no longer reduced the estimate (a floor the element sizes do not move)".into(),
    };
    let (value, limit, what) = match (target.pressure_l2, p) {
        (Some(t), Some(p)) if p > t => (p, t, format!("the pressure's estimated relative L2 error is {p:.3e}")),
        (Some(t), None) => (
            f64::INFINITY,
            t,
            "the pressure's error could not be estimated".to_string(),
        ),
        _ => {
            let t = target.zone_edge.unwrap_or(0.0);
            (z, t, format!("the zone ends' estimated error is {z:.3e}"))
        }
    };
    Warning {
        code: "tolerance_not_reached",
        value: if value.is_finite() { value } else { f64::MAX },
        limit,
        location: "/settings/accuracy".into(),
        message: format!("{what}, above the target {limit:.3e}: refinement stopped because {why}"),
    }
}

/// The shortest element side of a given mesh (its own, nondimensional units).
fn shortest_edge(m: &crate::mesh::Mesh2d) -> f64 {
    let k = m.order.nodes_per_element();
    m.elems
        .chunks(k)
        .flat_map(|e| (0..3).map(move |i| (e[i], e[(i + 1) % 3])))
        .map(|(a, b)| (m.nodes[a][0] - m.nodes[b][0]).hypot(m.nodes[a][1] - m.nodes[b][1]))
        .fold(f64::INFINITY, f64::min)
}

/// The smallest element size of the round (request units): asked of the
/// generators, or the shortest side of a given mesh.
fn smallest_size(scene: &Scene) -> f64 {
    scene
        .bodies
        .iter()
        .map(|b| match &b.mesh {
            MeshSource::Rectangle { size, grading, .. } => grading.map_or(*size, |(_, g)| g.h_min.min(*size)),
            MeshSource::Disk { size, grading, .. } => grading.map_or(*size, |g| g.h_min.min(*size)),
            MeshSource::Inline(m) => shortest_edge(m) * scene.scales.length,
        })
        .fold(f64::INFINITY, f64::min)
}

/// The scene with every generated mesh's smallest element size times `h` and
/// its far-field size times `size`; with a `report`, each graded window
/// widened (or, ungraded, created) to cover the body's zones, and each given
/// (inline or Gmsh) mesh bisected around them. None when coarsening (`h` ≥ 1)
/// a given mesh.
fn resized(scene: &Scene, [h, growth, size]: [f64; 3], report: Option<&Report>) -> Option<Scene> {
    let mut out = scene.clone();
    for (b, body) in out.bodies.iter_mut().enumerate() {
        let ends = report.map(|r| zone_ends(scene, r, b)).unwrap_or_default();
        body.mesh = match &body.mesh {
            // A given mesh cannot be coarsened; it is refined by bisection
            // around its zones (nondimensional, like the mesh).
            MeshSource::Inline(_) if h >= 1.0 => return None,
            MeshSource::Inline(m) => {
                let ends: Vec<[f64; 2]> = ends.iter().map(|p| p.map(|v| v / scene.scales.length)).collect();
                MeshSource::Inline(around_zones(m, &ends))
            }
            MeshSource::Disk {
                center,
                radius,
                down,
                part,
                size: s,
                grading,
                order,
            } => {
                let apex = [center[0], center[1] + if *down { -radius } else { *radius }];
                let new_size = s * size;
                let g = grading.unwrap_or(Grading {
                    h_min: *s,
                    ratio: 1.1,
                    extent: 0.0,
                });
                MeshSource::Disk {
                    center: *center,
                    radius: *radius,
                    down: *down,
                    part: *part,
                    size: new_size,
                    grading: Some(Grading {
                        extent: g.extent.max(MARGIN * reach(apex, &ends)),
                        ..scaled(g, [h, growth], new_size)
                    }),
                    order: *order,
                }
            }
            MeshSource::Rectangle {
                corner,
                width,
                height,
                size: s,
                grading,
                order,
            } => {
                let new_size = s * size;
                let grading = match (grading, ends.is_empty()) {
                    (Some((focus, g)), true) => Some((*focus, scaled(*g, [h, growth], new_size))),
                    (None, true) => None,
                    (g, false) => {
                        // Keep the focus if it already covers the zones; else
                        // centre the window on them.
                        let centre = midpoint(&ends);
                        let (focus, g0) = match g {
                            Some((f, g0)) if reach(*f, &ends) <= g0.extent => (*f, *g0),
                            Some((_, g0)) => (centre, *g0),
                            None => (
                                centre,
                                Grading {
                                    h_min: *s,
                                    ratio: 1.1,
                                    extent: 0.0,
                                },
                            ),
                        };
                        let mut g1 = scaled(g0, [h, growth], new_size);
                        g1.extent = g1.extent.max(MARGIN * reach(focus, &ends));
                        Some((focus, g1))
                    }
                };
                MeshSource::Rectangle {
                    corner: *corner,
                    width: *width,
                    height: *height,
                    size: new_size,
                    grading,
                    order: *order,
                }
            }
        };
    }
    // The node count grows with the refinement; the mesh stage recounts it.
    out.estimated_nodes = scene.estimated_nodes / (h * size);
    Some(out)
}

/// The grading with every element `h` times as large: the element size at a
/// distance d from the focus is about h_min + (ratio − 1) d, so both terms
/// scale (scaling h_min alone leaves the graded region's error: on the T3
/// disk the resultant stayed 0.22 % stiff at every h_min with ratio 1.1).
fn scaled(g: Grading, [h, growth]: [f64; 2], size: f64) -> Grading {
    Grading {
        h_min: (g.h_min * h).min(size),
        ratio: (1.0 + (g.ratio - 1.0) * growth).clamp(1.0, 2.0),
        extent: g.extent,
    }
}

/// A given mesh with its elements near the zones (`ends`) halved: two
/// passes of bisection over the triangles with a corner in the zones'
/// bounding box, widened by a quarter of its diagonal and two of the local
/// elements (so that the zone ends move within refined ground).
fn around_zones(mesh: &crate::mesh::Mesh2d, ends: &[[f64; 2]]) -> crate::mesh::Mesh2d {
    if ends.is_empty() {
        return mesh.clone();
    }
    let (lo, hi) = bounding_box(ends);
    let inside = |p: [f64; 2], pad: f64| (0..2).all(|k| p[k] >= lo[k] - pad && p[k] <= hi[k] + pad);
    let k = mesh.order.nodes_per_element();
    let local = mesh
        .elems
        .chunks(k)
        .filter(|e| e[..3].iter().any(|&n| inside(mesh.nodes[n], 0.0)))
        .flat_map(|e| (0..3).map(move |i| (e[i], e[(i + 1) % 3])))
        .map(|(a, b)| {
            let (p, q) = (mesh.nodes[a], mesh.nodes[b]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(0.0, f64::max);
    let pad = 0.25 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]) + 2.0 * local;
    crate::mesh::bisect::refine_where(mesh, |p| inside(p, pad), 2)
}

/// The ends of every zone on body `b`'s surface: of the pairs it is the body
/// of, and of the two-body pairs it is the other body of (the same interface).
fn zone_ends(scene: &Scene, report: &Report, b: usize) -> Vec<[f64; 2]> {
    scene
        .pairs
        .iter()
        .zip(&report.pairs)
        .filter(|(p, _)| p.body == b || matches!(p.target, crate::scene::Target::Body { body, .. } if body == b))
        .flat_map(|(_, r)| r.zones_along.iter().flat_map(|z| [z.start, z.end]))
        .collect()
}

/// The farthest of `points` from `from`.
fn reach(from: [f64; 2], points: &[[f64; 2]]) -> f64 {
    points
        .iter()
        .map(|p| (p[0] - from[0]).hypot(p[1] - from[1]))
        .fold(0.0, f64::max)
}

/// The centre of the points' bounding box.
fn midpoint(points: &[[f64; 2]]) -> [f64; 2] {
    let (lo, hi) = bounding_box(points);
    [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]
}

fn bounding_box(points: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}
