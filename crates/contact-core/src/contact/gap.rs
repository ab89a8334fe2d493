//! Where a body point stands against a rigid obstacle.
//!
//! **Signed distance (default).** The exact non-penetration condition is
//! d(x + u) ≥ 0 with d the signed distance to the obstacle (positive outside).
//! Its first-order linearization at the reference point x is
//!
//! ```text
//! d(x) + ∇d(x) · u ≥ 0,     ∇d(x) = n_o(y),
//! ```
//!
//! with y the closest obstacle point and n_o the obstacle's outward normal
//! there: the gap is the distance to y and the row's direction is −n_o. For a
//! flat obstacle this is exact; on a curved body against a flat it differs from
//! the body-normal form by tan θ · u_t (θ the angle between the two normals),
//! which the body-normal form never recovers under refinement (measured: the
//! Hertz L2 pressure error of an elastic cylinder on a rigid flat stalls at 2.1 %).
//!
//! **Body normal (the seed's form, `settings.gap = body_normal`).** The gap is
//! measured along the body's outward normal n: the smallest t with x + t n on
//! the obstacle surface entering it; the row's direction is n.
//!
//! Either returns None when the point cannot meet the obstacle: the ray misses
//! it, or the closest point is an open end of a polyline or profile that the
//! point lies beyond (such obstacles extend no further than their ends).
//!
//! Length: about 420 lines of geometry (closest points on lines, circles,
//! polylines and smoothed punch profiles) and its tests.

use crate::scene::{Psi, Shape};

/// The obstacle as seen from a point: signed distance, the closest point y and
/// the obstacle's outward unit normal there (pointing toward the free side).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closest {
    pub distance: f64,
    pub point: [f64; 2],
    pub normal: [f64; 2],
}

/// One smooth piece of an obstacle boundary.
#[derive(Debug, Clone, Copy)]
enum Piece {
    /// Straight from a to b with the outward unit normal n (toward the free side).
    Segment { a: [f64; 2], b: [f64; 2], n: [f64; 2] },
    /// Circular arc, counter-clockwise from angle `from` to `to` (radians,
    /// to > from); the rigid side is inside the circle (a convex punch edge).
    Arc {
        center: [f64; 2],
        radius: f64,
        from: f64,
        to: f64,
    },
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// Where on a piece the closest point lies.
enum Foot {
    /// Strictly inside the piece, with the piece's outward normal there.
    Inside([f64; 2]),
    /// At the start (false) or the end (true) of the piece.
    End(bool),
}

impl Piece {
    fn ends(&self) -> ([f64; 2], [f64; 2]) {
        match *self {
            Piece::Segment { a, b, .. } => (a, b),
            Piece::Arc {
                center,
                radius,
                from,
                to,
            } => (
                [center[0] + radius * from.cos(), center[1] + radius * from.sin()],
                [center[0] + radius * to.cos(), center[1] + radius * to.sin()],
            ),
        }
    }

    /// Outward normal at the start (false) or end (true).
    fn end_normal(&self, end: bool) -> [f64; 2] {
        match *self {
            Piece::Segment { n, .. } => n,
            Piece::Arc { from, to, .. } => {
                let t = if end { to } else { from };
                [t.cos(), t.sin()]
            }
        }
    }

    /// Closest point to x, its squared distance, and where it lies; `slack`
    /// (a fraction of the piece) lets a foot just past an end count as inside,
    /// so that a mesh node placed on an end up to round-off still sees it.
    fn foot(&self, x: [f64; 2], slack: f64) -> ([f64; 2], f64, Foot) {
        match *self {
            Piece::Segment { a, b, n } => {
                let s = sub(b, a);
                let t = dot(sub(x, a), s) / dot(s, s);
                let (t_in, foot) = if t <= 0.0 {
                    (0.0, if t >= -slack { Foot::Inside(n) } else { Foot::End(false) })
                } else if t >= 1.0 {
                    (
                        1.0,
                        if t <= 1.0 + slack {
                            Foot::Inside(n)
                        } else {
                            Foot::End(true)
                        },
                    )
                } else {
                    (t, Foot::Inside(n))
                };
                let y = [a[0] + t_in * s[0], a[1] + t_in * s[1]];
                let d = sub(x, y);
                (y, dot(d, d), foot)
            }
            Piece::Arc {
                center,
                radius,
                from,
                to,
            } => {
                let v = sub(x, center);
                let r = norm(v);
                let span = to - from;
                // Angle of x measured from `from`, in [0, 2π).
                let mut phi = v[1].atan2(v[0]) - from;
                phi = phi.rem_euclid(std::f64::consts::TAU);
                let inside = r > 0.0 && (phi <= span * (1.0 + slack) || phi >= std::f64::consts::TAU - span * slack);
                if inside {
                    let n = [v[0] / r, v[1] / r];
                    let y = [center[0] + radius * n[0], center[1] + radius * n[1]];
                    (y, (r - radius).powi(2), Foot::Inside(n))
                } else {
                    let (p, q) = self.ends();
                    let (dp, dq) = (sub(x, p), sub(x, q));
                    if dot(dp, dp) <= dot(dq, dq) {
                        (p, dot(dp, dp), Foot::End(false))
                    } else {
                        (q, dot(dq, dq), Foot::End(true))
                    }
                }
            }
        }
    }
}

/// Relative reach of a foot past a piece's end that still counts as on it.
const END_SLACK: f64 = 1e-9;

/// Closest point of an open chain of pieces (consecutive pieces share ends).
fn closest_on_chain(pieces: &[Piece], x: [f64; 2]) -> Option<Closest> {
    let mut best: Option<(f64, usize, [f64; 2], Foot)> = None;
    for (k, p) in pieces.iter().enumerate() {
        let (y, d2, foot) = p.foot(x, END_SLACK);
        if best.as_ref().is_none_or(|b| d2 < b.0) {
            best = Some((d2, k, y, foot));
        }
    }
    let (d2, k, y, foot) = best?;
    let dist = d2.sqrt();
    let r = sub(x, y);
    match foot {
        Foot::Inside(n) => Some(Closest {
            distance: dot(r, n),
            point: y,
            normal: smoothed(pieces, k, y).unwrap_or(n),
        }),
        Foot::End(end) => {
            // An open end of the chain: the obstacle does not continue there.
            let neighbour = if end { k + 1 } else { k.wrapping_sub(1) };
            let other = pieces.get(neighbour)?;
            if let Some(vn) = gentle_joint(pieces, if end { k } else { neighbour }) {
                let sign = if dot(r, vn) >= 0.0 { 1.0 } else { -1.0 };
                return Some(Closest {
                    distance: sign * dist,
                    point: y,
                    normal: vn,
                });
            }
            // A joint: the pseudo-normal (mean of both pieces' normals) tells
            // the side; the direction is that of x − y (∇d at a corner).
            let (n1, n2) = (pieces[k].end_normal(end), other.end_normal(!end));
            let pn = [n1[0] + n2[0], n1[1] + n2[1]];
            let l = norm(pn);
            let pn = if l > 0.0 { [pn[0] / l, pn[1] / l] } else { n1 };
            let sign = if dot(r, pn) >= 0.0 { 1.0 } else { -1.0 };
            let normal = if dist > 1e-14 * norm(x).max(1.0) {
                [sign * r[0] / dist, sign * r[1] / dist]
            } else {
                pn
            };
            Some(Closest {
                distance: sign * dist,
                point: y,
                normal,
            })
        }
    }
}

/// A segment from a to b whose free side is to the left of travel (`left`)
/// or to the right.
fn segment(a: [f64; 2], b: [f64; 2], left: bool) -> Piece {
    let s = sub(b, a);
    let l = norm(s);
    let n = if left {
        [-s[1] / l, s[0] / l]
    } else {
        [s[1] / l, -s[0] / l]
    };
    Piece::Segment { a, b, n }
}

/// Largest turn between consecutive segments that counts as a sampled smooth
/// curve rather than a corner (30°, as for the bodies' own boundary normals).
const GENTLE_COS: f64 = 0.866;

/// The normal at the joint after segment k, when both neighbours are segments
/// meeting at a gentle turn: the mean of their normals.
fn gentle_joint(pieces: &[Piece], k: usize) -> Option<[f64; 2]> {
    match (pieces.get(k)?, pieces.get(k + 1)?) {
        (Piece::Segment { n: a, .. }, Piece::Segment { n: b, .. }) if dot(*a, *b) >= GENTLE_COS => {
            let m = [a[0] + b[0], a[1] + b[1]];
            let l = norm(m);
            Some([m[0] / l, m[1] / l])
        }
        _ => None,
    }
}

/// Along a segment whose ends are gentle joints, the normal interpolated
/// between the joints' normals: a finely tabulated smooth profile then gets
/// the smooth curve's normal instead of its facets' (whose jumps of one facet
/// angle move the gap by u_t times that angle, measured 4e-3 of the peak
/// pressure near a Hertz zone edge with 2001 samples of R = 8). Real corners
/// (turns over 30°) keep the polyline's own ∇d.
fn smoothed(pieces: &[Piece], k: usize, y: [f64; 2]) -> Option<[f64; 2]> {
    let Piece::Segment { a, b, n } = pieces[k] else {
        return None;
    };
    let start = k.checked_sub(1).and_then(|j| gentle_joint(pieces, j));
    let end = gentle_joint(pieces, k);
    if start.is_none() && end.is_none() {
        return None;
    }
    let s = sub(b, a);
    let t = (dot(sub(y, a), s) / dot(s, s)).clamp(0.0, 1.0);
    let (p, q) = (start.unwrap_or(n), end.unwrap_or(n));
    let m = [(1.0 - t) * p[0] + t * q[0], (1.0 - t) * p[1] + t * q[1]];
    let l = norm(m);
    Some([m[0] / l, m[1] / l])
}

/// The pieces of a punch profile y = y_r + ψ(x − x_r), rigid above, in
/// increasing t (the lower arcs run counter-clockwise, i.e. left to right),
/// consecutive pieces sharing their ends.
fn profile_pieces(reference: [f64; 2], psi: &Psi) -> Vec<Piece> {
    let at = |t: f64, v: f64| [reference[0] + t, reference[1] + v];
    let pi = std::f64::consts::PI;
    match psi {
        Psi::Circle { radius } => vec![Piece::Arc {
            center: at(0.0, *radius),
            radius: *radius,
            from: pi,
            to: 2.0 * pi,
        }],
        Psi::Flat {
            half_width,
            corner_radius,
        } => {
            let (hw, rc) = (*half_width, *corner_radius);
            let flat = hw - rc;
            let mut out = Vec::new();
            if rc > 0.0 {
                out.push(Piece::Arc {
                    center: at(-flat, rc),
                    radius: rc,
                    from: pi,
                    to: 1.5 * pi,
                });
            }
            if flat > 0.0 {
                out.push(segment(at(-flat, 0.0), at(flat, 0.0), false));
            }
            if rc > 0.0 {
                out.push(Piece::Arc {
                    center: at(flat, rc),
                    radius: rc,
                    from: 1.5 * pi,
                    to: 2.0 * pi,
                });
            }
            out
        }
        // Rigid above, travelling left to right: the free side is on the right.
        Psi::Points(p) => p
            .windows(2)
            .map(|w| segment(at(w[0][0], w[0][1]), at(w[1][0], w[1][1]), false))
            .collect(),
    }
}

/// The chain of a profile or polyline.
fn chain(shape: &Shape) -> Vec<Piece> {
    match shape {
        // Rigid to the right of travel: the free side is on the left.
        Shape::Polyline { points } => points.windows(2).map(|w| segment(w[0], w[1], true)).collect(),
        Shape::Profile { reference, psi } => profile_pieces(*reference, psi),
        Shape::Line { .. } | Shape::Circle { .. } => Vec::new(),
    }
}

/// Signed distance from x to the obstacle, the closest point and the outward
/// normal there; None if x lies beyond an open end of the obstacle.
pub fn closest(shape: &Shape, x: [f64; 2]) -> Option<Closest> {
    match shape {
        Shape::Line { point, normal } => {
            let d = dot(sub(x, *point), *normal);
            Some(Closest {
                distance: d,
                point: [x[0] - d * normal[0], x[1] - d * normal[1]],
                normal: *normal,
            })
        }
        Shape::Circle { center, radius } => {
            let v = sub(x, *center);
            let r = norm(v);
            (r > 0.0).then(|| {
                let n = [v[0] / r, v[1] / r];
                Closest {
                    distance: r - radius,
                    point: [center[0] + radius * n[0], center[1] + radius * n[1]],
                    normal: n,
                }
            })
        }
        Shape::Polyline { .. } | Shape::Profile { .. } => closest_on_chain(&chain(shape), x),
    }
}

pub fn gap_along_normal(shape: &Shape, x: [f64; 2], n: [f64; 2]) -> Option<f64> {
    match shape {
        Shape::Line { point, normal } => {
            let dn = n[0] * normal[0] + n[1] * normal[1];
            if dn >= 0.0 {
                return None;
            }
            let h = (x[0] - point[0]) * normal[0] + (x[1] - point[1]) * normal[1];
            Some(-h / dn)
        }
        Shape::Circle { center, radius } => {
            let (dx, dy) = (x[0] - center[0], x[1] - center[1]);
            let b = n[0] * dx + n[1] * dy;
            let c = dx * dx + dy * dy - radius * radius;
            let disc = b * b - c;
            if disc < 0.0 {
                return None;
            }
            // Entry point of the line x + t n into the disk.
            let t = -b - disc.sqrt();
            // Outside and moving away: the entry lies behind the point.
            if c > 0.0 && t < 0.0 {
                return None;
            }
            Some(t)
        }
        Shape::Profile { reference, psi } => {
            // Vertical normal: the graph gives the gap exactly.
            if n[0].abs() <= 1e-12 * n[1].abs() && n[1] > 0.0 {
                let psi_x = psi.eval(x[0] - reference[0])?;
                return Some((reference[1] + psi_x - x[1]) / n[1]);
            }
            // Otherwise intersect with the profile sampled finely, traversed right
            // to left so that the rigid side (above) is to the right of travel.
            let (t0, t1) = psi.extent();
            let k = 4096;
            let points: Vec<[f64; 2]> = (0..=k)
                .rev()
                .filter_map(|i| {
                    let t = t0 + (t1 - t0) * i as f64 / k as f64;
                    psi.eval(t).map(|v| [reference[0] + t, reference[1] + v])
                })
                .collect();
            gap_along_normal(&Shape::Polyline { points }, x, n)
        }
        Shape::Polyline { points } => {
            let mut best: Option<f64> = None;
            for w in points.windows(2) {
                let (a, b) = (w[0], w[1]);
                let (sx, sy) = (b[0] - a[0], b[1] - a[1]);
                // Outward (free-side) normal of the segment: left of travel.
                let (ox, oy) = (-sy, sx);
                let dn = n[0] * ox + n[1] * oy;
                if dn >= 0.0 {
                    continue; // not entering the rigid side through this segment
                }
                // Solve x + t n = a + s (b − a).
                let det = n[0] * (-sy) - n[1] * (-sx);
                if det == 0.0 {
                    continue;
                }
                let (rx, ry) = (a[0] - x[0], a[1] - x[1]);
                let t = (rx * (-sy) - ry * (-sx)) / det;
                let s = (n[0] * ry - n[1] * rx) / det;
                if (-1e-12..=1.0 + 1e-12).contains(&s) && best.is_none_or(|bt: f64| t.abs() < bt.abs()) {
                    best = Some(t);
                }
            }
            best
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12
    }

    #[test]
    fn circle_and_line_are_exact() {
        let c = closest(
            &Shape::Circle {
                center: [0.0, 2.0],
                radius: 1.0,
            },
            [0.6, 0.0],
        )
        .unwrap();
        let r = 0.6f64.hypot(2.0);
        assert!(close(c.distance, r - 1.0));
        assert!(close(c.normal[0], 0.6 / r) && close(c.normal[1], -2.0 / r));
        let l = closest(
            &Shape::Line {
                point: [0.0, -1.0],
                normal: [0.0, 1.0],
            },
            [3.0, 0.5],
        )
        .unwrap();
        assert!(close(l.distance, 1.5) && l.normal == [0.0, 1.0]);
    }

    #[test]
    fn circle_profile_matches_the_circle_obstacle() {
        // ψ = R − sqrt(R² − t²) about (1, 0.5) is the lower half of the circle
        // of centre (1, 0.5 + R): both obstacles give one distance field below it.
        let (r, x) = (2.0, [1.7, 0.2]);
        let p = closest(
            &Shape::Profile {
                reference: [1.0, 0.5],
                psi: Psi::Circle { radius: r },
            },
            x,
        )
        .unwrap();
        let c = closest(
            &Shape::Circle {
                center: [1.0, 0.5 + r],
                radius: r,
            },
            x,
        )
        .unwrap();
        assert!(close(p.distance, c.distance) && close(p.normal[0], c.normal[0]));
        // Above the centre the profile has ended.
        assert!(closest(
            &Shape::Profile {
                reference: [1.0, 0.5],
                psi: Psi::Circle { radius: r },
            },
            [4.0, 3.0]
        )
        .is_none());
    }

    #[test]
    fn rounded_flat_punch_corner_and_base() {
        let shape = Shape::Profile {
            reference: [0.0, 0.0],
            psi: Psi::Flat {
                half_width: 1.0,
                corner_radius: 0.25,
            },
        };
        // Under the flat base: vertical, distance below the base.
        let base = closest(&shape, [0.3, -0.1]).unwrap();
        assert!(close(base.distance, 0.1) && close(base.normal[1], -1.0));
        // Under the right corner's arc: radial from its centre (0.75, 0.25).
        let x = [0.95, -0.05];
        let c = closest(&shape, x).unwrap();
        let v = [x[0] - 0.75, x[1] - 0.25];
        let r = v[0].hypot(v[1]);
        assert!(close(c.distance, r - 0.25));
        assert!(close(c.normal[0], v[0] / r) && close(c.normal[1], v[1] / r));
        // Beside the punch, below its corner's centre: the arc is nearest.
        let side = closest(&shape, [1.5, 0.1]).unwrap();
        assert!(close(side.distance, (0.75f64).hypot(0.15) - 0.25));
        // Above the corner's centre the punch's side (not modelled) is nearest.
        assert!(closest(&shape, [1.5, 0.4]).is_none());
        // Sharp corners: the base alone, ends open.
        let sharp = Shape::Profile {
            reference: [0.0, 0.0],
            psi: Psi::Flat {
                half_width: 1.0,
                corner_radius: 0.0,
            },
        };
        assert!(close(closest(&sharp, [1.0, -0.2]).unwrap().distance, 0.2));
        assert!(closest(&sharp, [1.2, -0.2]).is_none());
    }

    #[test]
    fn polyline_vertex_gives_the_direction_to_the_corner() {
        // A roof (rigid below): peak at the origin, convex corner.
        let shape = Shape::Polyline {
            points: vec![[-1.0, -1.0], [0.0, 0.0], [1.0, -1.0]],
        };
        let c = closest(&shape, [0.0, 0.5]).unwrap();
        assert!(close(c.distance, 0.5) && close(c.normal[1], 1.0));
        // A point inside the rigid side, under the left slope.
        let inside = closest(&shape, [-0.5, -0.7]).unwrap();
        assert!(inside.distance < 0.0);
        // Tabulated profiles walk right to left: the rigid side is above.
        let table = Shape::Profile {
            reference: [0.0, 0.0],
            psi: Psi::Points(vec![[-1.0, 0.5], [0.0, 0.0], [1.0, 0.5]]),
        };
        let v = closest(&table, [0.0, -0.3]).unwrap();
        assert!(close(v.distance, 0.3) && close(v.normal[1], -1.0));
    }
}
