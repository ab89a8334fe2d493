//! What a converged, certified 3D answer can still get wrong that the user
//! must be told: a contact patch narrower than the mesh resolves (2D's
//! `coarse_contact_zone`, `solution::validity`), and a body moved further
//! than the small-displacement theory holds (2D's `large_displacement`, the
//! same limit `MAX_DISPLACEMENT`: 5 % of the body's largest side).
//!
//! Both are what a unit slip gives, as in 2D: loads 10⁻⁶ of what was meant
//! (a modulus in Pa with lengths in mm) press one node; loads 10⁶ too large
//! move the body by many times its size (the ball example's ×10⁹ is
//! worked out in `tests/solid.rs`, `loads_far_too_large_for_the_modulus_are_warned_or_refused`).
//!
//! A patch's width is read from its rows' tributary area A as the diameter
//! of a disk of that area, D = 2 √(A/π), or for a strip (a line contact)
//! twice its area over its length (`width`), counted in the spacing h of
//! the candidate faces at its rows. 2D asks for 8 element edges across a zone
//! (`MIN_ZONE_EDGES`), 4 across Hertz's half-width a. On the quarter models
//! a 3D scene is usually posed as, a patch of radius a reads D = a, so the
//! limit here is 4 edges across D: it holds the same on a quarter model as
//! 2D's, and on a whole model asks 2 across a. Measured on the Hertz ball
//! (`contact-bench --solid`, a quarter): T10 at h = 0.4 mm (a/h = 2.5) has a
//! 1.4 % and p0 6.5 % off Hertz and is warned, at 0.2 mm (a/h = 5) 0.6 %
//! and 1.6 % and is not. A patch of one pressed node, the answer a modulus
//! in Pa with lengths in mm gives (the load 10⁻⁶ of what was meant), reads
//! D/h below 1.

use std::collections::HashSet;

use super::obstacle::ObstacleRows;
use super::report::SolidContactReport;
use super::SolidBody;
use crate::mesh3d::{area_normal, dot, sub};
use crate::outcome::WarningCode;
use crate::scene::scaling::shown;
use crate::solution::report::Warning;
use crate::solution::validity::MAX_DISPLACEMENT;

/// Face edges a patch must span across its width (module doc).
pub const MIN_PATCH_EDGES: f64 = 4.0;

/// One `coarse_contact_zone` warning for the narrowest patch when it spans
/// fewer than `MIN_PATCH_EDGES` face spacings, counting the others that do
/// (a height field may press thousands of patches: one message, as 2D
/// gives one per pair for its narrowest zone); `report` is nondimensional,
/// `length` the scene's length scale, for the message.
pub fn coarse_patches(body: &SolidBody, rows: &ObstacleRows, report: &SolidContactReport, length: f64) -> Vec<Warning> {
    let Ok(set) = body.face_set(&rows.faces, "contact/faces") else {
        return Vec::new();
    };
    let nodes = &body.mesh.nodes;
    let pressed: HashSet<usize> = report.points.iter().filter(|q| q.in_contact).map(|q| q.node).collect();
    // (patch, its width, the spacing there)
    let mut narrow: Vec<(usize, f64, f64)> = Vec::new();
    for (k, patch) in report.patches.iter().enumerate() {
        let at: HashSet<usize> = patch.rows.iter().map(|&i| report.points[i].node).collect();
        let (mut sum, mut count, mut open_beside) = (0.0, 0usize, false);
        for f in set.iter().filter(|f| f.corners.iter().any(|c| at.contains(c))) {
            let [p, q, r] = f.corners.map(|n| nodes[n]);
            sum += area_normal(p, q, r).0;
            count += 1;
            open_beside |= f.corners.iter().any(|c| !pressed.contains(c));
        }
        // A patch with no open row beside it fills its face set: its edge is
        // the body's, with nothing inside the set to resolve (a block
        // pressed flat on a plane, whose pressure is exact on any mesh).
        if count == 0 || !open_beside {
            continue;
        }
        // √(2 × the mean corner-triangle area): a grid's spacing on the
        // right triangles a box's faces are, 0.93 of the side of an
        // equilateral one.
        let h = (2.0 * sum / count as f64).sqrt();
        let points: Vec<[f64; 3]> = patch.rows.iter().map(|&i| report.points[i].position).collect();
        let width = width(patch.tributary_area, &points, h);
        if width / h < MIN_PATCH_EDGES {
            narrow.push((k, width, h));
        }
    }
    let Some(&(k, width, h)) = narrow.iter().min_by(|a, b| (a.1 / a.2).total_cmp(&(b.1 / b.2))) else {
        return Vec::new();
    };
    let patch = &report.patches[k];
    let across = width / h;
    // Round-off off a symmetry plane reads 0.
    let c = patch
        .centre_of_pressure
        .map(|x| shown(if x.abs() < 1e-12 { 0.0 } else { x * length }));
    let others = match narrow.len() - 1 {
        0 => String::new(),
        n => format!(" ({n} other patch(es) span fewer than {MIN_PATCH_EDGES} too)"),
    };
    vec![Warning {
        code: WarningCode::CoarseContactZone,
        value: across,
        limit: MIN_PATCH_EDGES,
        location: "/solid/contact".into(),
        message: format!(
            "contact patch {k} (centre of pressure ({}, {}, {}), {} row(s) in contact) spans {across:.2} face \
                spacings across: its width {} over the spacing {} of the faces at its rows, fewer than \
                {MIN_PATCH_EDGES}{others}; its pressure and area are resolved only to about a face. Refine near it \
                to an edge of at most {} (a box's grading: h_min about that, extent a little beyond the patch). A \
                patch this small is also what a unit slip gives (a modulus in Pa with lengths in mm)",
            c[0],
            c[1],
            c[2],
            patch.rows.len(),
            shown(width * length),
            shown(h * length),
            shown(width * length / 8.0),
        ),
    }]
}

/// A patch's width: the diameter of a disk of its area A, 2 √(A/π), or,
/// where it is a strip, twice its area over its length L (its points'
/// extent along their principal axis, plus a spacing h for the rows' own
/// share): a disk of radius r reads 2r either way (2A/L = πr ≥ 2r), a line
/// of single nodes m spacings long about 2h whatever m, where the disk's
/// diameter alone grew as 2h √(m/π).
fn width(area: f64, points: &[[f64; 3]], h: f64) -> f64 {
    let disk = 2.0 * (area / std::f64::consts::PI).sqrt();
    let n = points.len() as f64;
    let c = points.iter().fold([0.0; 3], |a, p| [0, 1, 2].map(|i| a[i] + p[i] / n));
    let mut m = [[0.0; 3]; 3];
    for p in points {
        let d = sub(*p, c);
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += d[i] * d[j];
            }
        }
    }
    // The principal axis by power iteration from the most spread coordinate
    // (a 3×3 moment matrix: 30 steps settle it to far below a spacing).
    let start = (0..3).max_by(|&a, &b| m[a][a].total_cmp(&m[b][b])).unwrap_or(0);
    let mut v = [0.0; 3];
    v[start] = 1.0;
    for _ in 0..30 {
        let w = [0, 1, 2].map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2]);
        let l = dot(w, w).sqrt();
        if l <= 0.0 {
            break;
        }
        v = w.map(|x| x / l);
    }
    let along = points.iter().map(|p| dot(sub(*p, c), v));
    let (lo, hi) = along.fold((f64::MAX, f64::MIN), |(lo, hi), s| (lo.min(s), hi.max(s)));
    let length = (hi - lo).max(0.0) + h;
    disk.min(2.0 * area / length)
}

/// A `large_displacement` warning when some node of `body` moves by more
/// than `MAX_DISPLACEMENT` of the body's largest side (rigid motions the
/// supports leave free included, as 2D counts them): `u` on every DOF,
/// nondimensional as the mesh.
pub fn large_displacement(body: &SolidBody, u: &[f64], name: &str) -> Vec<Warning> {
    let size = crate::mesh::extent(&body.mesh.nodes);
    let biggest = u
        .chunks_exact(3)
        .map(|d| dot([d[0], d[1], d[2]], [d[0], d[1], d[2]]).sqrt())
        .fold(0.0, f64::max);
    let moved = biggest / size;
    if moved.is_nan() || moved <= MAX_DISPLACEMENT {
        return Vec::new();
    }
    vec![Warning {
        code: WarningCode::LargeDisplacement,
        value: moved,
        limit: MAX_DISPLACEMENT,
        location: "/solid/body".into(),
        message: format!(
            "body '{name}' moves by {moved:.3e} of its size, beyond the {MAX_DISPLACEMENT} up to which equilibrium \
                written on the undeformed shape holds: the answer is that of the linear model, not of the real body. \
                A displacement this large is also what a unit slip gives (loads far larger than meant for the \
                modulus: a modulus in MPa with stresses in Pa, say)"
        ),
    }]
}
