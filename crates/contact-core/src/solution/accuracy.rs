//! How far each reported zone end may lie from the edge of the contact zone
//! that mesh refinement converges to.
//!
//! A zone is reported from its first to its last node in contact, so its end
//! is off by up to the distance to the next, open node. Near a smooth edge
//! the pressure falls like a square root: p² is linear in the distance to the
//! edge, and exactly quadratic along the surface for Hertz (p² ∝ a² − x²).
//! A least-squares fit p² = c0 + c1 t + c2 t² over the nodes in contact in the
//! outer 30 % of the zone (at least its last four) finds the edge near the
//! last node in contact (between it and the next; for a mortar row, whose
//! last corner in contact can carry a multiplier past the edge, possibly
//! before it); its distance to the reported end is the
//! end's estimated error, at least a quarter of the spacing (the fit's own
//! scatter). Measured on the elastic disk on a flat against a 949k-DOF T6
//! solution (its own fitted edge, stable to 3e-5 of R over fit windows of
//! 10–30 % and against a mesh twice as coarse): effectivity 0.72–1.07 over
//! five T3 levels (h 0.0088 to 0.00055 R) and 0.83–0.95 over four T6 levels,
//! where the reported end itself was off by 2.6e-3 down to 1.3e-4 R.
//!
//! Where no root lies within 1.5 spacings (a sharp punch corner, where the
//! pressure rises to the end; too few nodes), the edge is only known to lie
//! before the next node: the estimate is that spacing. A zone that ends where
//! its edge set ends (a footing's whole base) ends there exactly: 0. A
//! foundation's zone ends at its last active panel, where the foundation
//! lifts off within half a spacing (`panel_end_error`).

use crate::solution::corners;
use crate::solution::report::{PairAccuracy, PairReport};

/// Outer fraction of a zone whose nodes the fit uses.
const WINDOW: f64 = 0.3;
/// Fewest nodes in contact the fit needs (three coefficients and one more).
const MIN_FIT: usize = 4;

/// A node along the pair's surface: arc length, pressure, in contact.
#[derive(Debug, Clone, Copy)]
pub struct Station {
    pub s: f64,
    pub pressure: f64,
    pub in_contact: bool,
}

/// The estimated error of a zone's end at `stations[last]` (the last node in
/// contact going in direction `dir`, ±1, from `stations[first]`): the
/// stations are one chain of the surface's candidates in order, and `beyond`
/// is the distance from their last one in direction `dir` to the next surface
/// node (0 where the surface ends there; the spacing to a pruned node past a
/// flat punch's corner, where the zone ends before it).
pub fn end_error(stations: &[Station], first: usize, last: usize, dir: isize, beyond: f64) -> f64 {
    let Some(next) = last.checked_add_signed(dir).filter(|&k| k < stations.len()) else {
        return beyond;
    };
    let end = stations[last].s;
    let spacing = (stations[next].s - end).abs();
    let length = (end - stations[first].s).abs();
    // From the end inward: the outer WINDOW of the zone, or MIN_FIT nodes.
    let (lo, hi) = (first.min(last), first.max(last));
    let mut inward: Vec<&Station> = stations[lo..=hi].iter().collect();
    if dir > 0 {
        inward.reverse();
    }
    let window: Vec<(f64, f64)> = inward
        .into_iter()
        .filter(|t| t.in_contact && t.pressure > 0.0)
        .enumerate()
        .take_while(|(n, t)| *n < MIN_FIT || (t.s - end).abs() <= WINDOW * length)
        .map(|(_, t)| ((t.s - end) / length.max(f64::MIN_POSITIVE), t.pressure * t.pressure))
        .collect();
    if window.len() < MIN_FIT || length <= 0.0 {
        return spacing;
    }
    match edge_root(&window, dir as f64) {
        Some(t) if t.abs() * length <= 1.5 * spacing => (t.abs() * length).max(0.25 * spacing),
        _ => spacing,
    }
}

/// The error of a foundation zone's end at `stations[last]` (its active node
/// on the side `dir`): the zone is reported to the outer end of that node's
/// panel, halfway to the next node, and the foundation lifts off somewhere
/// between the two nodes: half the spacing, or 0 where the surface ends.
pub fn panel_end_error(stations: &[Station], last: usize, dir: isize, beyond: f64) -> f64 {
    last.checked_add_signed(dir)
        .filter(|&k| k < stations.len())
        .map_or(beyond, |next| 0.5 * (stations[next].s - stations[last].s).abs())
}

/// The root nearest the end (t = 0; t > 0 outward in direction `dir`) where
/// the least-squares quadratic through (t_i, y_i) falls through zero going
/// outward, or None. It may lie inside the zone: a mortar row's last corner
/// in contact can carry a positive multiplier past the edge.
fn edge_root(points: &[(f64, f64)], dir: f64) -> Option<f64> {
    // y = c0 + c1 t + c2 t², in the outward coordinate.
    let outward: Vec<(f64, f64)> = points.iter().map(|&(t, y)| (dir * t, y)).collect();
    let c = fit_quadratic(&outward)?;
    let (c0, c1, c2) = (c[0], c[1], c[2]);
    let roots: Vec<f64> = if c2.abs() <= 1e-12 * (c1.abs() + c0.abs()) {
        if c1 != 0.0 {
            vec![-c0 / c1]
        } else {
            Vec::new()
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return None;
        }
        // The numerically stable pair of roots.
        let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
        let mut r = vec![q / c2];
        if q != 0.0 {
            r.push(c0 / q);
        }
        r
    };
    // p² falls through zero going outward there.
    roots
        .into_iter()
        .filter(|&t| c1 + 2.0 * c2 * t < 0.0)
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
}

/// A pair's estimate from its zone ends alone (no second solve).
pub fn zone_edges_only(pair: &PairReport) -> PairAccuracy {
    PairAccuracy {
        basis: "zone_edges",
        pressure_l2: None,
        peak: None,
        resultant: None,
        zone_edges: pair.zones_along.iter().map(|z| z.uncertainty).collect(),
        singular_ends: corners::singular_ends(pair),
    }
}

/// The two-level estimate of a pair's error: the same pair solved on meshes
/// whose elements are `ratio` times as large (`coarse`) differs from the
/// finer solution (`fine`) by about (ratio^q − 1) times the finer one's
/// error, for an error of order q in the element size (`ORDER`: the
/// pressure's error is dominated by where the zone edge falls between nodes
/// and by the graded field's stiffness, both O(h²) for T3; for T6, whose
/// multipliers sit on every surface node, the estimate with q = 2 kept its
/// effectivity within 0.83–1.64 on the disk, ball, block and two cylinders
/// at three levels each, measured against their overkill references).
///
/// The nodal L2 difference is taken both ways and the larger kept: at the
/// fine candidates (the coarse pressure interpolated along its surface,
/// weighed by the fine tributary weights) and at the coarse ones (the fine
/// interpolated). Where the edge's placement dominates, the two levels'
/// errors are not in Richardson's ratio and either comparison alone can miss
/// it: on the T6 disk at h = 0.0088 R the coarse-node comparison gave 0.15 %
/// for a true 1.08 %, the fine-node one 0.57 %; at h = 0.0044 R the fine-node
/// comparison gave 1.54 % for a true 0.20 % (a linear segment across the
/// coarse zone's square-root edge), the coarse-node one 0.29 %. Keeping the
/// larger errs on the safe side.
///
/// The zone ends' own nodal error (`edge_deviation`) is a second, direct
/// estimate; the larger of the two is the pressure's. Over seven scenes at
/// three levels each, T3 and T6 (`contact bench --convergence`,
/// effectivity.csv), the pressure's effectivity is 0.35–2.86, 39 of 42 rows
/// within [0.5, 2]; without this term the finer levels' last-node error went
/// unseen (measured with T6 multipliers on the corners only: 0.19 at worst
/// on the smooth-edged scenes, against 0.56 with it). Zone ends where the
/// pressure is unbounded are left out with a band around them (`corners`).
pub fn two_level(fine: &PairReport, coarse: &PairReport, ratio: f64) -> PairAccuracy {
    let singular = corners::singular_ends(fine);
    // The same order next to a corner (outside its band): on the two punch
    // scenes at three levels each, T3 and T6, q = 2 gave effectivities
    // 0.35–1.64 (11 of 12 within [0.5, 2]), q = 1, which the pollution of
    // the local error by a d^(−1/2) singularity would suggest, 1.04–4.9.
    let scale = ratio.powf(ORDER) - 1.0;
    let counted = |x: f64, y: f64| !corners::in_band(&singular, x, y);
    // Relative L2 difference of `at`'s nodal pressure from `other`'s
    // field, weighed at `at`'s candidates; None without pressure.
    let relative = |at: &PairReport, other: &PairReport| {
        let (pts, reach) = field_with_reach(other);
        let (mut num, mut den) = (0.0, 0.0);
        for q in at.points.iter().filter(|q| counted(q.x, q.y)) {
            let po = along(&pts, Some(&reach), q.x, q.y);
            if q.pressure > 0.0 || po > 0.0 {
                num += q.weight * (q.pressure - po).powi(2);
                den += q.weight * q.pressure.max(po).powi(2);
            }
        }
        (den > 0.0).then(|| (num / den).sqrt())
    };
    let l2 = match (relative(fine, coarse), relative(coarse, fine)) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    };
    let peak = |pts: &[crate::solution::report::ContactPoint]| {
        pts.iter()
            .filter(|q| counted(q.x, q.y))
            .map(|q| q.pressure)
            .fold(0.0, f64::max)
    };
    let (pf, pc) = (peak(&fine.points), peak(&coarse.points));
    let norm = |r: &crate::solution::report::Resultant| r.fx.hypot(r.fy);
    let (rf, rc) = (norm(&fine.resultant), norm(&coarse.resultant));
    let dr = (fine.resultant.fx - coarse.resultant.fx).hypot(fine.resultant.fy - coarse.resultant.fy);
    // The zone ends' own nodal error, which the two levels' steps hide.
    let den: f64 = fine
        .points
        .iter()
        .filter(|q| counted(q.x, q.y))
        .map(|q| q.weight * q.pressure * q.pressure)
        .sum();
    let edge = if den > 0.0 { edge_deviation(fine) / den } else { 0.0 };
    PairAccuracy {
        basis: "two_level",
        pressure_l2: l2.map(|v| (v / scale).max(edge.sqrt())),
        peak: (pf > 0.0).then(|| (pf - pc).abs() / pf / scale),
        resultant: (rf > 0.0 && rc.is_finite()).then(|| dr / rf / scale),
        zone_edges: fine.zones_along.iter().map(|z| z.uncertainty).collect(),
        singular_ends: singular,
    }
}

/// Σ w (p − p_fit)² over the last node in contact at each smooth zone end
/// and the open node beyond it, where p_fit is the square-root profile
/// fitted (p² quadratic in the distance to the end) on the nodes inward of
/// the end alone. The last node's value depends on where the edge falls
/// between it and the next (a node 0.37 spacings inside the edge read 15 %
/// below the profile on the T3 disk at h_min = 0.00125 R, 97 % of that
/// solution's squared L2 error), which neither level of `two_level` sees when
/// both ends fall alike; the nodes further in are off by 20× less.
fn edge_deviation(pair: &PairReport) -> f64 {
    let mut pts: Vec<(f64, f64, f64, f64)> = pair.points.iter().map(|q| (q.x, q.y, q.pressure, q.weight)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let dist = |a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let mut sum = 0.0;
    for z in &pair.zones_along {
        for end in [z.start, z.end] {
            let Some(i) = pts.iter().position(|p| p.0 == end[0] && p.1 == end[1] && p.2 > 0.0) else {
                continue;
            };
            // Inward: the neighbour in contact; outward: the open one.
            let inside = |k: Option<usize>| k.filter(|&k| k < pts.len() && pts[k].2 > 0.0);
            let (dir, open) = match (inside(i.checked_sub(1)), inside(i.checked_add(1))) {
                (Some(_), None) => (-1isize, (i + 1 < pts.len()).then_some(i + 1)),
                (None, Some(_)) => (1isize, i.checked_sub(1)),
                _ => continue,
            };
            // The nodes inward, after the end: distance along the surface, p².
            let mut window = Vec::new();
            let (mut k, mut t) = (i, 0.0);
            while let Some(next) = k.checked_add_signed(dir).filter(|&n| n < pts.len() && pts[n].2 > 0.0) {
                t += dist(pts[k], pts[next]);
                window.push((t, pts[next].2 * pts[next].2));
                k = next;
            }
            let n = window.len().clamp(MIN_FIT, 12);
            if window.len() < MIN_FIT + 1 {
                continue;
            }
            let Some(c) = fit_quadratic(&window[..n]) else { continue };
            // p² must grow inward at the end: a smooth edge, not a corner.
            if c[1] <= 0.0 {
                continue;
            }
            let profile = |t: f64| (c[0] + c[1] * t + c[2] * t * t).max(0.0).sqrt();
            sum += pts[i].3 * (pts[i].2 - profile(0.0)).powi(2);
            if let Some(o) = open {
                sum += pts[o].3 * profile(-dist(pts[i], pts[o])).powi(2);
            }
        }
    }
    sum
}

/// Least-squares y = c0 + c1 x + c2 x² through the points, centred and
/// scaled for conditioning; None if they do not determine it.
pub fn fit_quadratic(pts: &[(f64, f64)]) -> Option<[f64; 3]> {
    let n = pts.len() as f64;
    let m = pts.iter().map(|q| q.0).sum::<f64>() / n;
    let s = pts
        .iter()
        .map(|q| (q.0 - m).abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut a = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for &(x, y) in pts {
        let t = (x - m) / s;
        let phi = [1.0, t, t * t];
        for i in 0..3 {
            b[i] += phi[i] * y;
            for j in 0..3 {
                a[i][j] += phi[i] * phi[j];
            }
        }
    }
    let d = solve3(a, b)?;
    // Back to x: y = d0 + d1 (x − m)/s + d2 (x − m)²/s².
    let (d1, d2) = (d[1] / s, d[2] / (s * s));
    Some([d[0] - d1 * m + d2 * m * m, d1 - 2.0 * d2 * m, d2])
}

/// A pair's nodal pressure as (x, y, p), sorted for `along_polyline`.
pub fn field(pair: &PairReport) -> Vec<(f64, f64, f64)> {
    let mut v: Vec<(f64, f64, f64)> = pair.points.iter().map(|q| (q.x, q.y, q.pressure)).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    v
}

/// `field`, with each point's distance to its zone's estimated edge where it
/// ends a zone (`zones_along`'s uncertainty), else 0.
fn field_with_reach(pair: &PairReport) -> (Vec<(f64, f64, f64)>, Vec<f64>) {
    let pts = field(pair);
    let reach = pts
        .iter()
        .map(|p| {
            pair.zones_along
                .iter()
                .flat_map(|z| [(z.start, z.uncertainty[0]), (z.end, z.uncertainty[1])])
                .find(|(e, _)| e[0] == p.0 && e[1] == p.1)
                .map_or(0.0, |(_, u)| u)
        })
        .collect();
    (pts, reach)
}

/// Observed order of the nodal pressure error in the element size (see
/// `two_level`).
const ORDER: f64 = 2.0;

/// The value at (x, y) of the piecewise-linear field through `pts` (x, y,
/// value; sorted by x, then y, which is their order along a surface that is
/// a graph over x or a vertical face): on the segment nearest the point among
/// those around its place in the order; 0 beyond the ends.
pub fn along_polyline(pts: &[(f64, f64, f64)], x: f64, y: f64) -> f64 {
    along(pts, None, x, y)
}

/// As `along_polyline`, but on a segment from a zone end (a point with
/// positive value and `reach[i]` > 0) to an open point, the value falls like
/// a square root to zero at `reach[i]` from the end: the estimated edge
/// (`end_error`), not linearly to the open point (which puts pressure where
/// the zone has ended).
fn along(pts: &[(f64, f64, f64)], reach: Option<&[f64]>, x: f64, y: f64) -> f64 {
    if pts.len() < 2 {
        return pts
            .first()
            .map_or(0.0, |p| if (p.0 - x).hypot(p.1 - y) == 0.0 { p.2 } else { 0.0 });
    }
    let k = pts.partition_point(|p| p.0 < x || (p.0 == x && p.1 < y));
    let lo = k.saturating_sub(4);
    let hi = (k + 4).min(pts.len() - 1);
    let mut best = (f64::INFINITY, 0.0);
    for i in lo..hi {
        let (a, b) = (pts[i], pts[i + 1]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((x - a.0) * dx + (y - a.1) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (px, py) = (a.0 + t * dx, a.1 + t * dy);
        let d = (x - px).hypot(y - py);
        if d < best.0 {
            let linear = a.2 + t * (b.2 - a.2);
            let value = match reach {
                Some(r) if (a.2 > 0.0) != (b.2 > 0.0) && len2 > 0.0 => {
                    let (p, from_end, to_edge) = if a.2 > 0.0 {
                        (a.2, t, r[i])
                    } else {
                        (b.2, 1.0 - t, r[i + 1])
                    };
                    let e = (to_edge / len2.sqrt()).min(1.0);
                    if e > 0.0 {
                        p * (1.0 - from_end / e).max(0.0).sqrt()
                    } else {
                        linear
                    }
                }
                _ => linear,
            };
            best = (d, value);
        }
    }
    best.1
}

/// Gaussian elimination with partial pivoting on a 3 × 3 system.
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    for col in 0..3 {
        let piv = (col..3).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() <= 1e-300 {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        let pivot = a[col];
        for row in col + 1..3 {
            let f = a[row][col] / pivot[col];
            for (x, p) in a[row].iter_mut().zip(pivot).skip(col) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 3];
    for row in (0..3).rev() {
        let s: f64 = (row + 1..3).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hertz's p = √(a² − x²) sampled at nodes 0.1 apart with a = 0.93: the
    /// last node in contact is 0.9, the fit finds the edge 0.03 beyond it;
    /// a sharp corner (p rising to the end) is known only to the spacing; a
    /// zone at the end of its surface ends there.
    #[test]
    fn the_fit_finds_a_square_root_edge_between_nodes() {
        let a: f64 = 0.93;
        let stations: Vec<Station> = (0..15)
            .map(|k| {
                let s = 0.1 * k as f64;
                let p = (a * a - s * s).max(0.0).sqrt();
                Station {
                    s,
                    pressure: p,
                    in_contact: p > 0.0,
                }
            })
            .collect();
        let e = end_error(&stations, 0, 9, 1, 0.0);
        assert!((e - 0.03).abs() < 1e-9, "{e}");
        let corner: Vec<Station> = (0..15)
            .map(|k| {
                let s = 0.1 * k as f64;
                let p = if s <= 0.9 { 1.0 / (1.0 - s / 0.95).sqrt() } else { 0.0 };
                Station {
                    s,
                    pressure: p,
                    in_contact: p > 0.0,
                }
            })
            .collect();
        assert!((end_error(&corner, 0, 9, 1, 0.0) - 0.1).abs() < 1e-12);
        assert_eq!(end_error(&stations[..10], 0, 9, 1, 0.0), 0.0);
        // Past the last candidate the surface may go on (pruned nodes).
        assert_eq!(end_error(&stations[..10], 0, 9, 1, 0.07), 0.07);
    }
}
