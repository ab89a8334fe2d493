//! Checks of the model's own assumptions on a solution.
//!
//! The theory is small strain and small rotation, with the non-penetration
//! condition linearized about the reference configuration. A solution can
//! satisfy the discrete equations exactly and still lie outside that model (a
//! punch tipped by 37°, a cylinder pushed in to a/R = 0.67): these checks say
//! so with the measured value and the limit.
//!
//! Limits, each where a neglected term reaches about 1 % of what is kept (a
//! Hertz contact at a/R = 0.085 has 3 % strain and 0.08 rad of local surface
//! rotation at the zone edge and is well inside the theory's validity):
//! - strain 5e-2: Green's strain adds ½ε² ≈ 2.5 % of the linear strain;
//! - rotation 0.15 rad: a linearized rotation misplaces points by θ²/2 ≈ 1.1 %
//!   of their distance to the centre of rotation;
//! - displacement 5e-2 of the body's size: equilibrium is written on the
//!   undeformed shape;
//! - contact half-width 0.3 of a curved obstacle's radius: the obstacle's
//!   surface there has turned by 17°, and the body's pressed onto it as much
//!   (the gap itself is the distance to the true surface, linearized);
//! - contact motion across the obstacle, relative to it (a punch carries its
//!   surface along), 5e-2 of its local radius of curvature: the linearized
//!   distance d + ∇d·u errs by |u_t|²/2R, 2.5 % of u_t.
//!
//! Strain and rotation are judged on the mean gradient over patches a tenth
//! of the body's narrowest contact zone wide (and no wider than a tenth of
//! the body's smaller extent, so that a thin footing's bending is not
//! averaged away), not element by element: at a sharp punch corner the
//! linear theory's strain grows like r^(−1/2), so an element-wise maximum
//! grows without bound under refinement (measured 0.17 and 0.84 on the two
//! flat punch examples) while the deformation the answer rests on does not.
//! On patches the Sadowsky example stays below the limit; the punch of
//! revolution still reads 0.18, a real strain (its mean pressure is 0.16 E).
//!
//! One more check is of the discretization, not the model: a contact zone
//! spanning fewer than `MIN_ZONE_EDGES` element edges resolves its pressure
//! poorly (its error is of the order of one element over the zone's width),
//! the usual sign of a unit slip or of a mesh too coarse near the contact.

use crate::outcome::WarningCode;
use std::collections::HashMap;
use std::collections::HashSet;

use crate::contact::ConstraintSet;
use crate::fem::element;
use crate::mesh::{signed_area, Mesh2d};
use crate::scene::scaling::shown;
use crate::scene::{Psi, Scene, Shape, Target};
use crate::solution::report::{PairReport, Warning};

pub const MAX_STRAIN: f64 = 5e-2;
pub const MAX_ROTATION: f64 = 0.15;
pub const MAX_DISPLACEMENT: f64 = 5e-2;
pub const MAX_ZONE_OVER_RADIUS: f64 = 0.3;
pub const MAX_CONTACT_MOTION_OVER_RADIUS: f64 = 5e-2;
/// Largest roll of a curved surface over its zone's half-width a: a body of
/// radius of curvature ρ at the contact that turns by θ brings material
/// points θ ρ away into contact, while the linear model keeps every contact
/// force's lever about the body on the undeformed shape: the moment of the
/// pressure is misplaced by its normal force times θ ρ, against the P a the
/// zone can carry at most.
pub const MAX_ROLL: f64 = 5e-2;
/// Below this curvature times the zone's half-width (radius of curvature over
/// 10⁴ half-widths), the surface at the zone is flat: a turning flat face
/// tilts, as its linearized rotation says.
const FLAT: f64 = 1e-4;
/// Fewest element edges across a contact zone: the pressure's L2 error on
/// Hertz measured 4.4 % with about 5 edges across the zone and 1.2 % with 10
/// (generated half disk, T3), so below 8 an answer needs the user's eye.
pub const MIN_ZONE_EDGES: f64 = 8.0;
/// Patch width over the narrowest contact zone for the strain and rotation.
const PATCH_OVER_ZONE: f64 = 0.1;

/// `disp[b][n]`: nodal displacements of body b (rigid motions included);
/// `punch_motions`: (obstacle, (α1, α2, θ)) of every punch; `turns`: (body,
/// θ) of every body held only by contact; `pairs`: the pairs' reports (zones
/// and points in the request's units).
pub fn check(
    scene: &Scene,
    meshes: &[Mesh2d],
    disp: &[Vec<[f64; 2]>],
    cons: &ConstraintSet,
    punch_motions: &[(usize, [f64; 3])],
    turns: &[(usize, f64)],
    pairs: &[PairReport],
) -> Vec<Warning> {
    let to_scene = 1.0 / scene.scales.length;
    let zones: Vec<Vec<[f64; 2]>> = pairs
        .iter()
        .map(|pr| pr.zones.iter().map(|z| [z[0] * to_scene, z[1] * to_scene]).collect())
        .collect();
    let (mut out, mut coarse) = (Vec::new(), Vec::new());
    let mut warn = |code: WarningCode, value: f64, limit: f64, location: String, message: String| {
        if value > limit {
            out.push(Warning {
                code,
                value,
                limit,
                location,
                message,
            });
        }
    };
    for (b, (mesh, u)) in meshes.iter().zip(disp).enumerate() {
        // The narrowest zone this body touches sets the patch.
        let narrowest = scene
            .pairs
            .iter()
            .enumerate()
            .filter(|(_, p)| p.body == b || matches!(p.target, Target::Body { body, .. } if body == b))
            .flat_map(|(k, _)| pairs[k].zones_along.iter().map(|z| (z.s[1] - z.s[0]) * to_scene))
            .filter(|w| *w > 0.0)
            .fold(f64::INFINITY, f64::min);
        // No wider than a tenth of the body's smaller extent either: a patch
        // across a thin footing's whole thickness would average its bending
        // strain (tension above, compression below) to nothing.
        let (lo, hi) = mesh
            .nodes
            .iter()
            .fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(l, h), p| {
                ([l[0].min(p[0]), l[1].min(p[1])], [h[0].max(p[0]), h[1].max(p[1])])
            });
        let thinnest = (hi[0] - lo[0]).min(hi[1] - lo[1]);
        let patch = if narrowest.is_finite() {
            PATCH_OVER_ZONE * narrowest.min(thinnest)
        } else {
            0.0
        };
        let (strain, rotation) = patch_extremes(mesh, u, patch);
        let biggest = u.iter().map(|d| d[0].hypot(d[1])).fold(0.0, f64::max);
        let path = scene.bodies[b].path.clone();
        let name = &scene.bodies[b].name;
        warn(
            WarningCode::LargeStrain,
            strain,
            MAX_STRAIN,
            path.clone(),
            format!(
                "body '{name}' strains by {strain:.3} (principal strain, mean over patches a tenth of its \
                narrowest contact zone wide), beyond the {MAX_STRAIN} up to which small-strain elasticity holds to \
                about 2.5 %: the answer is that of the linear model, not of the real body"
            ),
        );
        warn(
            WarningCode::LargeRotation,
            rotation,
            MAX_ROTATION,
            path.clone(),
            format!(
                "part of body '{name}' turns by {rotation:.3} rad, beyond the {MAX_ROTATION} rad up to which a \
                linearized rotation misplaces points by under 1.1 %"
            ),
        );
        let moved = biggest / mesh.size();
        warn(
            WarningCode::LargeDisplacement,
            moved,
            MAX_DISPLACEMENT,
            path,
            format!(
                "body '{name}' moves by {moved:.3} of its size, beyond the {MAX_DISPLACEMENT} up to which \
                equilibrium written on the undeformed shape holds"
            ),
        );
    }
    for &(o, [_, _, theta]) in punch_motions {
        warn(
            WarningCode::LargeRotation,
            theta.abs(),
            MAX_ROTATION,
            format!("/obstacles/{o}"),
            format!(
                "punch '{}' turns by {:.3} rad, beyond the {MAX_ROTATION} rad up to which its linearized rotation \
                    misplaces points by under 1.1 %",
                scene.obstacles[o].name,
                theta.abs()
            ),
        );
    }
    for &(b, theta) in turns {
        for (p, pair) in scene.pairs.iter().enumerate() {
            let Some((roll, half)) = rolled(pair, &pairs[p], b, theta, to_scene) else {
                continue;
            };
            let length = scene.scales.length;
            let name = &scene.bodies[b].name;
            // A body turned by a free coupling rotation: the place to hold it.
            let (location, hold) = match scene.bodies[b].couplings.first() {
                Some(cp) if matches!(cp.controls[2], crate::scene::Control::Load(_)) => (
                    format!("{}/rotation", cp.path),
                    "Hold the axle's rotation (the coupling's rotation as a displacement, e.g. 0)",
                ),
                _ => (
                    scene.bodies[b].path.clone(),
                    "Hold the body's rotation (a support on it)",
                ),
            };
            warn(
                WarningCode::Rolling,
                roll / half,
                MAX_ROLL,
                location,
                format!(
                    "body '{name}', held only by contact, turns by {:.3e} rad under its loads: its curved surface has \
                        rolled its contact by {} along itself, {:.2}× the zone's half-width {}, beyond the {MAX_ROLL} \
                        of it up to which the linear model, which takes the contact forces' levers on the undeformed \
                        shape, misplaces their moment by under 5 % of what the zone can carry. The loads' moment about \
                        the contact exceeds what a zone this wide can carry (its normal force times its half-width): \
                        the body rolls, and the zone, pressure and friction of this answer are those of the linearized \
                        roll, not of the scene. {hold} or apply the load through the contact's line of action",
                    theta.abs(),
                    shown(roll * length),
                    roll / half,
                    shown(half * length)
                ),
            );
        }
    }
    for (p, pair) in scene.pairs.iter().enumerate() {
        let midsides: HashSet<usize> = meshes[pair.body]
            .edge_sets
            .get(&pair.edges)
            .map(|set| set.iter().filter_map(|e| e.mid).collect())
            .unwrap_or_default();
        let edges = zone_edges(&pairs[p], &midsides);
        if let Some((k, n)) = edges.iter().copied().enumerate().min_by(|a, b| a.1.total_cmp(&b.1)) {
            let z = &pairs[p].zones_along[k];
            let width = z.s[1] - z.s[0];
            let hint = if width > 0.0 {
                format!(
                    "refine near the zone to an element size of at most {} (a rectangle's or disk's grading: h_min \
                        about the zone's width / 16, extent a little beyond the zone)",
                    shown(width / 16.0)
                )
            } else {
                "refine near the contact point (a grading with a smaller h_min)".to_string()
            };
            // Fires below its limit, unlike the model's checks.
            if n < MIN_ZONE_EDGES {
                coarse.push(Warning {
                    code: WarningCode::CoarseContactZone,
                    value: n,
                    limit: MIN_ZONE_EDGES,
                    location: pair.path.clone(),
                    message: format!(
                        "the contact zone from ({}, {}) to ({}, {}) spans {n} element edge(s), fewer than \
                            {MIN_ZONE_EDGES}: its pressure and extent are resolved only to about an element; {hint}. A \
                            zone this narrow is also what a unit slip gives (a modulus in Pa with lengths in mm)",
                        shown(z.start[0]),
                        shown(z.start[1]),
                        shown(z.end[0]),
                        shown(z.end[1])
                    ),
                });
            }
        }
        let Target::Obstacle(o) = pair.target else {
            continue;
        };
        let shape = &scene.obstacles[o].shape;
        let Some(radius) = curvature_radius(shape) else {
            continue;
        };
        let onto = curved_reach(shape, &zones[p]);
        warn(
            WarningCode::LargeContactZone,
            onto / radius,
            MAX_ZONE_OVER_RADIUS,
            pair.path.clone(),
            format!(
                "the contact zone reaches {:.3} of the obstacle's radius of curvature onto its curved part, where the \
                    obstacle's surface has turned by {:.1}°, beyond the {MAX_ZONE_OVER_RADIUS} ({:.1}°) the model is \
                    meant for: the gap is the distance to the obstacle's true surface, linearized in the displacement, \
                    but the body's surface pressed onto it turns as much, a rotation the small-rotation theory follows \
                    only approximately, and half-space closed forms (Hertz) no longer describe the scene",
                onto / radius,
                (onto / radius).min(1.0).asin().to_degrees(),
                MAX_ZONE_OVER_RADIUS.asin().to_degrees()
            ),
        );
        // The linearized distance errs by u_t²/2R, u_t the point's motion
        // relative to the obstacle across the row's normal, R the radius of
        // curvature where it touches: a punch carries the surface with it, and
        // a rounded punch's flat has no curvature to err by.
        let punch = punch_motions.iter().find(|(q, _)| *q == o).map(|(_, b)| *b);
        let reference = scene.obstacles[o].punch.as_ref().map_or([0.0; 2], |pu| pu.reference);
        // Only where it touches: an open point's gap is not linearized about it.
        let touching: std::collections::HashSet<usize> = pairs[p]
            .points
            .iter()
            .filter(|q| q.pressure > 0.0)
            .map(|q| q.node)
            .collect();
        let slid = cons
            .candidates
            .iter()
            .filter(|c| c.pair == p && touching.contains(&c.node))
            .filter_map(|c| {
                let r = local_radius(shape, c.x)?;
                let mut u = disp[c.body][c.node];
                if let Some([a1, a2, th]) = punch {
                    u[0] -= a1 - th * (c.x[1] - reference[1]);
                    u[1] -= a2 + th * (c.x[0] - reference[0]);
                }
                let along = u[0] * c.normal[0] + u[1] * c.normal[1];
                let across = (u[0] - along * c.normal[0]).hypot(u[1] - along * c.normal[1]);
                Some(across / r)
            })
            .fold(0.0, f64::max);
        warn(
            WarningCode::GapLinearization,
            slid,
            MAX_CONTACT_MOTION_OVER_RADIUS,
            pair.path.clone(),
            format!(
                "contact points slide across the obstacle by {slid:.3} of its radius of curvature, beyond the \
                    {MAX_CONTACT_MOTION_OVER_RADIUS} up to which the linearized distance errs by under 2.5 % of that \
                    motion"
            ),
        );
    }
    out.extend(coarse);
    out
}

/// How far body `b`'s contact in `pair` rolls under its rotation `theta`
/// (nondimensional): (θ times the surface's radius of curvature across the
/// zone, the zone's half-width), where that surface is curved (`FLAT`); None
/// without three points in contact.
fn rolled(pair: &crate::scene::Pair, report: &PairReport, b: usize, theta: f64, to_scene: f64) -> Option<(f64, f64)> {
    let mut pts: Vec<[f64; 2]> = if pair.body == b {
        report
            .points
            .iter()
            .filter(|q| q.pressure > 0.0)
            .map(|q| [q.x, q.y])
            .collect()
    } else if matches!(pair.target, Target::Body { body, .. } if body == b) {
        report
            .other_points
            .iter()
            .flatten()
            .filter(|q| q.pressure > 0.0)
            .map(|q| [q.x, q.y])
            .collect()
    } else {
        return None;
    };
    if pts.len() < 3 {
        return None;
    }
    for p in pts.iter_mut() {
        *p = [p[0] * to_scene, p[1] * to_scene];
    }
    // Along a surface that is a graph over x, or a vertical face.
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let (first, middle, last) = (pts[0], pts[pts.len() / 2], pts[pts.len() - 1]);
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let half = 0.5 * dist(first, last);
    // The circle through the three points: κ = 4 area / (product of sides).
    let area =
        0.5 * ((middle[0] - first[0]) * (last[1] - first[1]) - (last[0] - first[0]) * (middle[1] - first[1])).abs();
    let sides = dist(first, middle) * dist(middle, last) * dist(first, last);
    if half <= 0.0 || sides <= 0.0 || 4.0 * area / sides * half < FLAT {
        return None;
    }
    Some((theta.abs() * sides / (4.0 * area), half))
}

/// Element edges across each zone of a pair (`zones_along`): its points in
/// contact (positive pressure) at element corners (`midsides`: T6 rows may
/// sit on midsides too, half an edge apart) from the point at the zone's
/// start to the one at its end, less one; the points are ordered by (x, y),
/// which runs along a surface that is a graph over x and along a vertical
/// face.
fn zone_edges(pair: &PairReport, midsides: &HashSet<usize>) -> Vec<f64> {
    let nearest = |p: [f64; 2]| {
        (0..pair.points.len()).min_by(|&a, &b| {
            let d = |k: usize| (pair.points[k].x - p[0]).hypot(pair.points[k].y - p[1]);
            d(a).total_cmp(&d(b))
        })
    };
    pair.zones_along
        .iter()
        .map(|z| {
            let (Some(a), Some(b)) = (nearest(z.start), nearest(z.end)) else {
                return 0.0;
            };
            let n = pair.points[a.min(b)..=a.max(b)]
                .iter()
                .filter(|q| q.pressure > 0.0 && !midsides.contains(&q.node))
                .count();
            n.saturating_sub(1) as f64
        })
        .collect()
}

/// How far the zones reach onto the obstacle's curved part: the half-width
/// for a circle; for a flat punch with rounded corners, the distance beyond
/// the flat (from the punch's reference point) reached by the farthest zone
/// end, which is 0 while the zone stays on the flat.
fn curved_reach(shape: &Shape, zones: &[[f64; 2]]) -> f64 {
    match rounded_flat(shape) {
        Some((x_r, flat, _)) => zones
            .iter()
            .flat_map(|z| [z[0], z[1]])
            .map(|x| ((x - x_r).abs() - flat).max(0.0))
            .fold(0.0, f64::max),
        None => zones.iter().map(|z| 0.5 * (z[1] - z[0])).fold(0.0, f64::max),
    }
}

/// A flat punch with rounded corners: its reference x, the flat's half-width
/// and the corners' radius.
fn rounded_flat(shape: &Shape) -> Option<(f64, f64, f64)> {
    match shape {
        Shape::Profile {
            reference,
            psi: Psi::Flat {
                half_width,
                corner_radius,
            },
        } if *corner_radius > 0.0 => Some((reference[0], half_width - corner_radius, *corner_radius)),
        _ => None,
    }
}

/// Largest principal strain and rotation of the displacement gradient
/// averaged (area-weighted) over square patches of side `patch` (0: element
/// by element).
fn patch_extremes(mesh: &Mesh2d, u: &[[f64; 2]], patch: f64) -> (f64, f64) {
    let mut cells: HashMap<(i64, i64), ([f64; 4], f64)> = HashMap::new();
    let (mut x, mut ue) = (Vec::with_capacity(6), Vec::with_capacity(12));
    for e in 0..mesh.n_elems() {
        x.clear();
        ue.clear();
        for &n in mesh.elem(e) {
            x.push(mesh.nodes[n]);
            ue.extend_from_slice(&u[n]);
        }
        let g = element::centroid_gradient(mesh.order, &x, &ue);
        let area = signed_area(x[0], x[1], x[2]).abs();
        let key = if patch > 0.0 {
            let c = [(x[0][0] + x[1][0] + x[2][0]) / 3.0, (x[0][1] + x[1][1] + x[2][1]) / 3.0];
            ((c[0] / patch).floor() as i64, (c[1] / patch).floor() as i64)
        } else {
            (e as i64, 0)
        };
        let cell = cells.entry(key).or_insert(([0.0; 4], 0.0));
        for (s, v) in cell.0.iter_mut().zip(g) {
            *s += area * v;
        }
        cell.1 += area;
    }
    let (mut strain, mut rotation) = (0.0f64, 0.0f64);
    for (sum, area) in cells.values() {
        let g: Vec<f64> = sum.iter().map(|v| v / area.max(f64::MIN_POSITIVE)).collect();
        // Principal strains of the symmetric part; the rotation is the skew part.
        let (exx, eyy, exy) = (g[0], g[3], 0.5 * (g[1] + g[2]));
        let (mean, radius) = (0.5 * (exx + eyy), (0.25 * (exx - eyy).powi(2) + exy * exy).sqrt());
        strain = strain.max((mean + radius).abs()).max((mean - radius).abs());
        rotation = rotation.max((0.5 * (g[2] - g[1])).abs());
    }
    (strain, rotation)
}

/// The obstacle's radius of curvature where the point at `x` touches it
/// (None: straight there).
fn local_radius(shape: &Shape, x: [f64; 2]) -> Option<f64> {
    match rounded_flat(shape) {
        Some((x_r, flat, radius)) => ((x[0] - x_r).abs() > flat).then_some(radius),
        None => curvature_radius(shape),
    }
}

/// The smallest radius of curvature of a curved obstacle (None: straight).
fn curvature_radius(shape: &Shape) -> Option<f64> {
    match shape {
        Shape::Circle { radius, .. } => Some(*radius),
        Shape::Profile { psi, .. } => match psi {
            Psi::Circle { radius } => Some(*radius),
            Psi::Flat { corner_radius, .. } if *corner_radius > 0.0 => Some(*corner_radius),
            _ => None,
        },
        Shape::Line { .. } | Shape::Polyline { .. } => None,
    }
}
