//! How the obstacle's normal runs along a candidate side, and so which
//! contact pressure p* can follow it with a traction −p* ν linear along the
//! side (what `airy` carries exactly).
//!
//! ν(x) is the gap's (`contact::gap::closest`): the normal at the closest
//! obstacle point of the undeformed x. Wherever ν = m(x)/|m(x)| with m
//! affine along the side, p* = q |m(x)| (one q on the side) gives
//! −p* ν = −q m(x), linear. Three shapes of the obstacle give that:
//!
//! - a straight piece: ν constant (m constant), p* linear between the ends
//!   (`Straight`);
//! - a circular piece centred at c: m = ±(x − c) (`Arc`);
//! - a straight piece of a finely tabulated curve (a polyline's or a
//!   profile's segment with a gentle joint at an end, turn < 30°): the gap
//!   interpolates the joints' normals linearly along the segment
//!   (`gap::smoothed`), so m is affine in the closest point, which is affine
//!   in x while it stays inside the segment (`Fan`). The V-shaped floor of
//!   `signorini_inline_block_on_vee` is of this kind: its two segments meet
//!   at a joint of 11.4°, and their normals turn along each.
//!
//! The complementary energy asks exactly that traction: the Prager–Synge
//! inequality holds for any pointwise condition v · ν ≤ g as long as τ n =
//! −p* ν with p* ≥ 0 for the same ν(x) (`super` module doc). A side whose ν
//! is of none of these forms (it straddles a sharp vertex, or two facets'
//! regions) is `Kinked`, and is out of reach when in contact.
//!
//! The form is read from the normals at `SAMPLES` points of the side, fitted
//! to round-off (1e-9): the normal of each shape above is analytic between
//! them. Along with it goes a bound of the curvature the admissibility
//! check's margin needs: 0 on a flat, where v · ν − g is affine on a linear
//! side and its samples' largest exact; the turn's bound on an arc or a fan;
//! and 1/ρ where two samples share a vertex as their closest point (g =
//! ±|x − c| there: over a convex gentle joint's wedge the normal is constant
//! and the side counts as straight, but g is not affine).

use super::SAMPLES;
use crate::contact::gap::closest;
use crate::scene::Shape;

/// How the obstacle's normal runs along a side: the traction −p*(x) ν(x)
/// is linear in x for the first three.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Form {
    /// ν constant (a straight piece): p* linear between the ends.
    Straight,
    /// ν = ±(x − c)/|x − c| (a circular piece centred at c): p* = q |x − c|
    /// with one q on the side, so −p* ν = ∓q (x − c).
    Arc { center: [f64; 2] },
    /// ν = m/|m| with m affine along the side, m[0] at its first end and
    /// m[1] at its second, along the rows' direction −n (unit at the first
    /// end): p* = q |m| with one q, so −p* ν = −q m, linear.
    Fan { m: [[f64; 2]; 2] },
    /// ν turns otherwise (a sharp vertex of a polyline or profile within the
    /// side, two facets' regions, a spline): no linear traction follows it,
    /// so a side in contact there is out of the bound's reach.
    Kinked,
}

impl Form {
    /// p*(t) / p*(0) for a form with one q on the side (None for the others,
    /// whose p* is linear through its nodal values).
    pub(super) fn scale(&self, a: [f64; 2], b: [f64; 2], t: f64) -> Option<f64> {
        match *self {
            Form::Arc { center } => {
                let x = [(1.0 - t) * a[0] + t * b[0], (1.0 - t) * a[1] + t * b[1]];
                let ra = (a[0] - center[0]).hypot(a[1] - center[1]);
                Some((x[0] - center[0]).hypot(x[1] - center[1]) / ra)
            }
            Form::Fan { m } => {
                let mt = [0, 1].map(|c| (1.0 - t) * m[0][c] + t * m[1][c]);
                Some(mt[0].hypot(mt[1]) / m[0][0].hypot(m[0][1]))
            }
            Form::Straight | Form::Kinked => None,
        }
    }
}

fn cross(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

/// The form of the obstacle's normal along the segment a–b, from its normals
/// at `SAMPLES` points (None where the obstacle does not face every one),
/// with a bound of the normal's turn per unit length (0 on a straight
/// piece; for the margin of the admissibility check between samples).
pub(super) fn form_of(shape: &Shape, a: [f64; 2], b: [f64; 2]) -> Option<(Form, f64)> {
    let mut normals = Vec::with_capacity(SAMPLES);
    let mut points = Vec::with_capacity(SAMPLES);
    let mut feet = Vec::with_capacity(SAMPLES);
    for q in 0..SAMPLES {
        let t = q as f64 / (SAMPLES - 1) as f64;
        let x = [(1.0 - t) * a[0] + t * b[0], (1.0 - t) * a[1] + t * b[1]];
        let c = closest(shape, x)?;
        normals.push(c.normal);
        points.push(x);
        feet.push(c.point);
    }
    let l = (b[0] - a[0]).hypot(b[1] - a[1]);
    // A vertex that is the closest point of two neighbouring samples: there
    // g = ±|x − c|, not affine along the side whatever the normal does (a
    // gentle joint's normal is constant over its wedge, `gap::gentle_joint`),
    // and |g''| ≤ 1/ρ with ρ the vertex's distance from the side.
    let vertex = feet
        .windows(2)
        .filter(|w| (w[0][0] - w[1][0]).hypot(w[0][1] - w[1][1]) <= 1e-12 * (1.0 + w[0][0].hypot(w[0][1])))
        .map(|w| 1.0 / distance_to_segment(w[0], a, b))
        .fold(0.0, f64::max);
    let turn = normals.iter().map(|n| cross(normals[0], *n).abs()).fold(0.0, f64::max);
    if turn <= 1e-12 {
        // ν constant: a linear p* follows it; the vertex's curvature goes to
        // the admissibility check's margin.
        return Some((Form::Straight, vertex));
    }
    // The normals' lines at the two ends meet at the centre of a circular
    // piece; every normal must then point along x − c.
    let (n0, n1) = (normals[0], normals[SAMPLES - 1]);
    let den = cross(n0, n1);
    if den.abs() > 1e-300 {
        let d = [b[0] - a[0], b[1] - a[1]];
        let s0 = cross(d, n1) / den;
        let center = [a[0] + s0 * n0[0], a[1] + s0 * n0[1]];
        let fits = points.iter().zip(&normals).all(|(x, n)| {
            let r = [x[0] - center[0], x[1] - center[1]];
            cross(r, *n).abs() <= 1e-9 * (r[0].hypot(r[1]) + l)
        });
        if fits {
            let rho = points
                .iter()
                .map(|x| (x[0] - center[0]).hypot(x[1] - center[1]))
                .fold(f64::INFINITY, f64::min);
            return Some((Form::Arc { center }, 1.0 / rho));
        }
    }
    if let Some(fan) = fan(&normals) {
        return Some(fan_with_turn(fan, l));
    }
    // The samples' turn over their spacing stands for the curvature of a
    // side out of contact whose normal turns at a vertex.
    Some((Form::Kinked, (turn / l * (SAMPLES - 1) as f64).max(vertex)))
}

/// The distance from p to the segment a–b.
fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let s = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
    (a[0] + s * d[0] - p[0]).hypot(a[1] + s * d[1] - p[1])
}

/// Whether the obstacle faces each of the side's samples.
fn seen_by(shape: &Shape, a: [f64; 2], b: [f64; 2]) -> Vec<bool> {
    (0..SAMPLES)
        .map(|q| {
            let t = q as f64 / (SAMPLES - 1) as f64;
            closest(shape, [(1.0 - t) * a[0] + t * b[0], (1.0 - t) * a[1] + t * b[1]]).is_some()
        })
        .collect()
}

/// Whether the obstacle faces the side's samples in more than one run (a
/// gap between two of its pieces within the side), which `facing_part`
/// leaves to the caller: no part of it may be dropped unchecked.
pub(super) fn faced_in_pieces(shape: &Shape, a: [f64; 2], b: [f64; 2]) -> bool {
    let seen = seen_by(shape, a, b);
    match (seen.iter().position(|&x| x), seen.iter().rposition(|&x| x)) {
        (Some(first), Some(last)) => seen[first..=last].iter().any(|x| !x),
        _ => false,
    }
}

/// The part [t0, t1] of the segment a–b that the obstacle faces, where it
/// faces some of its samples but not all (an open end of a polyline or a
/// profile within the side): each end found by bisection between the last
/// facing and the first other sample, to 2⁻⁶⁰ of the side, on the facing
/// side. None where no sample faces it, where the facing samples are not one
/// run, or where the obstacle faces a single point (a node on its end: the
/// node's own sides check it).
pub(super) fn facing_part(shape: &Shape, a: [f64; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let faces = |t: f64| closest(shape, [(1.0 - t) * a[0] + t * b[0], (1.0 - t) * a[1] + t * b[1]]).is_some();
    let ts: Vec<f64> = (0..SAMPLES).map(|q| q as f64 / (SAMPLES - 1) as f64).collect();
    let seen = seen_by(shape, a, b);
    let first = seen.iter().position(|&x| x)?;
    let last = seen.iter().rposition(|&x| x)?;
    if seen[first..=last].iter().any(|x| !x) {
        return None;
    }
    let edge = |mut inside: f64, mut outside: f64| {
        for _ in 0..60 {
            let m = 0.5 * (inside + outside);
            if faces(m) {
                inside = m;
            } else {
                outside = m;
            }
        }
        inside
    };
    let t0 = if first == 0 {
        0.0
    } else {
        edge(ts[first], ts[first - 1])
    };
    let t1 = if last == SAMPLES - 1 {
        1.0
    } else {
        edge(ts[last], ts[last + 1])
    };
    // A foot within 1e-9 of the piece past its end still counts as on it
    // (`gap::END_SLACK`): a part that short is the end node's alone.
    (t1 - t0 > 1e-6).then_some([t0, t1])
}

/// m(t) = (1 − t) d0 + t ρ d1 (d = −n, the rows' direction) parallel to
/// every sampled normal, ρ > 0 read from the middle sample; None where no ρ
/// fits them all to 1e-9.
fn fan(normals: &[[f64; 2]]) -> Option<Form> {
    let k = normals.len();
    let (n0, n1) = (normals[0], normals[k - 1]);
    let mid = k / 2;
    let tm = mid as f64 / (k - 1) as f64;
    // (1 − t) n0 × n + t ρ n1 × n = 0 at the middle sample.
    let den = tm * cross(n1, normals[mid]);
    if den.abs() <= 1e-300 {
        return None;
    }
    let rho = -(1.0 - tm) * cross(n0, normals[mid]) / den;
    if !(rho.is_finite() && rho > 0.0) {
        return None;
    }
    let m = [[-n0[0], -n0[1]], [-rho * n1[0], -rho * n1[1]]];
    let fits = normals.iter().enumerate().all(|(q, n)| {
        let t = q as f64 / (k - 1) as f64;
        let mt = [0, 1].map(|c| (1.0 - t) * m[0][c] + t * m[1][c]);
        let len = mt[0].hypot(mt[1]);
        // m along −n: the cross product vanishes and the dot is negative.
        len > 0.0 && cross(mt, *n).abs() <= 1e-9 * len && mt[0] * n[0] + mt[1] * n[1] < 0.0
    });
    fits.then_some(Form::Fan { m })
}

/// A fan with the bound of its normal's turn per unit length along a side
/// of length l: |ν'| ≤ |m'| / |m| per unit t, |m| at least the distance from
/// 0 to the segment m0–m1 (m is affine in t).
fn fan_with_turn(form: Form, l: f64) -> (Form, f64) {
    let Form::Fan { m } = form else {
        return (form, 0.0);
    };
    let dm = [m[1][0] - m[0][0], m[1][1] - m[0][1]];
    let len2 = dm[0] * dm[0] + dm[1] * dm[1];
    let s = (-(m[0][0] * dm[0] + m[0][1] * dm[1]) / len2).clamp(0.0, 1.0);
    let nearest = [m[0][0] + s * dm[0], m[0][1] + s * dm[1]];
    let least = nearest[0].hypot(nearest[1]);
    (form, len2.sqrt() / least / l)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Psi;

    /// The example's V-shaped floor: each segment's normal is interpolated
    /// from its own (at the open end) to the joint's mean (at the apex) by
    /// the gap, so a side under one segment is a fan, whose m is parallel to
    /// the gap's normal at every point (checked at points other than the
    /// samples); a side across the apex has two segments' regions and is
    /// kinked.
    #[test]
    fn a_gently_jointed_polyline_gives_a_fan_and_a_kink_across_its_joint() {
        let vee = Shape::Polyline {
            points: vec![[-2.0, 0.2], [0.0, 0.0], [2.0, 0.2]],
        };
        let (a, b) = ([-0.5, 0.0], [0.0, 0.0]);
        let (form, turn) = form_of(&vee, a, b).expect("the vee faces the side");
        let Form::Fan { m } = form else {
            panic!("{form:?}");
        };
        for t in [0.1, 0.37, 0.71, 0.93] {
            let x = [(1.0 - t) * a[0] + t * b[0], 0.0];
            let n = closest(&vee, x).expect("faced").normal;
            let mt = [0, 1].map(|c| (1.0 - t) * m[0][c] + t * m[1][c]);
            assert!(cross(mt, n).abs() < 1e-12, "t {t}: m {mt:?} against n {n:?}");
        }
        // The normal turns by atan 0.1 = 0.0997 rad (chord 0.0996) along
        // the segment, whose foot moves 2/4.04 = 0.495 of it per unit x:
        // 0.0493 per unit, over the least |m| on the side (0.9991, where the
        // foot is at 0.752 of the segment), 0.04936.
        assert!((turn - 0.04936).abs() < 2e-5, "turn {turn}");
        let (across, _) = form_of(&vee, [-0.25, 0.0], [0.25, 0.0]).expect("faced");
        assert_eq!(across, Form::Kinked);
    }

    /// Over a convex gentle joint (a roof of 11.4°, whose joint normal the gap
    /// gives to the whole wedge above it) the normal is constant, so a linear
    /// p* follows it, but the gap is the distance to the apex, not affine:
    /// the admissibility check's margin takes |g''| ≤ 1/ρ, ρ = 0.5 the apex's
    /// distance from the side (0 on a flat).
    #[test]
    fn a_gentle_joints_wedge_is_straight_with_the_vertexs_curvature() {
        let roof = Shape::Polyline {
            points: vec![[-1.0, -0.1], [0.0, 0.0], [1.0, -0.1]],
        };
        let (form, curvature) = form_of(&roof, [-0.04, 0.5], [0.04, 0.5]).expect("faced");
        assert_eq!(form, Form::Straight);
        assert!((curvature - 2.0).abs() < 1e-12, "curvature {curvature}");
        let flat = Shape::Line {
            point: [0.0, 0.0],
            normal: [0.0, 1.0],
        };
        assert_eq!(form_of(&flat, [-0.04, 0.5], [0.04, 0.5]), Some((Form::Straight, 0.0)));
    }

    /// A circle stays an arc (its p* = q |x − c| as before), a flat punch's
    /// face is straight, a side wholly in a sharp roof's vertex region is an
    /// arc about the vertex (ν = (x − c)/|x − c| there), and one reaching
    /// from a facet's region into the vertex's is a kink.
    #[test]
    fn circles_flats_and_sharp_vertices_keep_their_forms() {
        let circle = Shape::Circle {
            center: [0.0, 2.0],
            radius: 1.5,
        };
        let (form, _) = form_of(&circle, [-0.2, 0.0], [0.1, 0.05]).expect("faced");
        assert!(matches!(form, Form::Arc { .. }), "{form:?}");
        let flat = Shape::Profile {
            reference: [0.0, 0.0],
            psi: Psi::Flat {
                half_width: 1.0,
                corner_radius: 0.0,
            },
        };
        assert_eq!(
            form_of(&flat, [0.5, 0.0], [1.0, 0.0]).map(|f| f.0),
            Some(Form::Straight)
        );
        // Across the punch's open end the obstacle faces the side up to the
        // corner, to round-off; a side from the corner outward, only its
        // first end.
        assert!(form_of(&flat, [0.99, 0.0], [1.01, 0.0]).is_none());
        let part = facing_part(&flat, [0.97, 0.0], [1.01, 0.0]).expect("faced in part");
        assert!(part[0] == 0.0 && (part[1] - 0.75).abs() < 1e-7, "{part:?}");
        assert!(facing_part(&flat, [1.0, 0.0], [1.01, 0.0]).is_none());
        let roof = Shape::Polyline {
            points: vec![[-1.0, -1.0], [0.0, 0.0], [1.0, -1.0]],
        };
        let (form, _) = form_of(&roof, [-0.1, 0.1], [0.1, 0.1]).expect("faced");
        assert!(
            matches!(form, Form::Arc { center } if center[0].hypot(center[1]) < 1e-12),
            "{form:?}"
        );
        let (form, _) = form_of(&roof, [-0.3, 0.1], [0.05, 0.1]).expect("faced");
        assert_eq!(form, Form::Kinked);
    }
}
