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
//! last node in contact can carry a multiplier past the edge, possibly
//! before it); its distance to the reported end is the
//! end's estimated error, at least a quarter of the spacing (the fit's own
//! scatter). Measured on the elastic disk on a flat against a 949k-DOF T6
//! solution (its own fitted edge, stable to 3e-5 of R over fit windows of
//! 10–30 % and against a mesh twice as coarse): effectivity 0.72–1.07 over
//! five T3 levels (h 0.0088 to 0.00055 R) and 0.83–0.95 over four T6 levels,
//! where the reported end itself was off by 2.6e-3 down to 1.3e-4 R (T6 with
//! its multipliers on the corners then; with one on every node, against the
//! disk's overkill table, 0.84–1.30 over three T6 levels, effectivity.csv).
//!
//! Where no root lies within 1.5 spacings (a sharp punch corner, where the
//! pressure rises to the end; too few nodes), the edge is only known to lie
//! before the next node: the estimate is that spacing. A zone that ends where
//! its edge set ends (a footing's whole base) ends there exactly: 0. A
//! foundation's zone ends at its last active panel, where the foundation
//! lifts off within half a spacing (`panel_end_error`).
//!
//! Length: about 600 lines, a fifth of them the tests; the fit that places
//! each zone end and the described field that ends there read the same
//! stations and must agree on where an edge lies.

use crate::outcome::EstimateBasis;
use crate::solution::corners;
use crate::solution::report::{PairAccuracy, PairReport, ZoneAlong};

/// Outer fraction of a zone whose nodes the fit uses.
const WINDOW: f64 = 0.3;
/// Fewest nodes in contact the fit needs (three coefficients and one more).
pub(crate) const MIN_FIT: usize = 4;
/// How far inward of the zone's last node in contact, as a fraction of the
/// facet to the node before, a fitted edge is kept (short of that node,
/// whose pressure is positive). A mortar row's last node can sit past the
/// edge with a small multiplier (the disk on a flat with T6 at h = 0.00125 R:
/// the node 0.24 spacings past the converged edge carried 0.85 % of its
/// neighbour's pressure); putting the edge at that node instead read the
/// described field 0.35 % off its overkill table (57.5k DOF) where it is
/// 0.16 % with the edge inside, and 0.43 % against 0.34 % with T3 at
/// h = 0.000625 R (49.8k DOF).
const INWARD_REACH: f64 = 0.999;

/// A node along the pair's surface: arc length, pressure, in contact.
#[derive(Debug, Clone, Copy)]
pub struct Station {
    pub s: f64,
    pub pressure: f64,
    pub in_contact: bool,
}

/// A zone end's estimate (`end_fit`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndFit {
    /// The estimated error of the end reported at its last node in contact.
    pub error: f64,
    /// Where the fit of p² places a smooth edge: its signed distance from
    /// that node along the surface, outward positive, within the spacing to
    /// the next node outward and (negative) almost the spacing to the node
    /// before inward; None where no smooth edge is found. A mortar row's last
    /// node in contact can lie past the edge: its multiplier is a weighted
    /// mean over the facets on both sides (`INWARD_REACH`).
    pub edge: Option<f64>,
    /// How far the fitted edge moves when the last node in contact is left
    /// out of the fit (`edge`'s own scatter).
    pub scatter: f64,
}

/// The estimate of a zone's end at `stations[last]` (the last node in
/// contact going in direction `dir`, ±1, from `stations[first]`): the
/// stations are one chain of the surface's candidates in order, and `beyond`
/// is the distance from their last one in direction `dir` to the next surface
/// node (0 where the surface ends there; the spacing to a pruned node past a
/// flat punch's corner, where the zone ends before it).
pub fn end_fit(stations: &[Station], first: usize, last: usize, dir: isize, beyond: f64) -> EndFit {
    let plain = |error: f64| EndFit {
        error,
        edge: None,
        scatter: error,
    };
    let Some(next) = last.checked_add_signed(dir).filter(|&k| k < stations.len()) else {
        return plain(beyond);
    };
    let end = stations[last].s;
    let spacing = (stations[next].s - end).abs();
    // The facet inward of the end, which a mortar row's edge may lie on.
    let inner = last
        .checked_add_signed(-dir)
        .filter(|&k| k < stations.len() && stations[k].in_contact)
        .map_or(0.0, |k| (stations[k].s - end).abs());
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
        return plain(spacing);
    }
    match edge_root(&window, dir as f64) {
        Some(t) if t.abs() * length <= 1.5 * spacing => {
            let without_last = (window.len() > MIN_FIT)
                .then(|| edge_root(&window[1..], dir as f64))
                .flatten();
            let error = (t.abs() * length).max(0.25 * spacing);
            EndFit {
                error,
                edge: Some((t * length).clamp(-INWARD_REACH * inner, spacing)),
                // Too few nodes to leave one out: the end's own estimate.
                scatter: without_last.map_or(error, |u| ((u - t).abs() * length).min(error)),
            }
        }
        _ => plain(spacing),
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
/// outward, or None. It may lie inside the zone: a mortar row's last node
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
        energy: None,
        basis: EstimateBasis::ZoneEdges,
        pressure_l2: None,
        peak: None,
        resultant: None,
        zone_edges: pair.zones_along.iter().map(|z| z.uncertainty).collect(),
        fitted_edges: pair
            .zones_along
            .iter()
            .map(|z| [0, 1].map(|k| z.fitted[k].map(|f| f.scatter)))
            .collect(),
        singular_ends: corners::singular_ends(pair),
    }
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
    weighted_field(pair).into_iter().map(|(x, y, p, _)| (x, y, p)).collect()
}

/// `field` with each node's tributary weight: (x, y, p, w), in the same order.
pub(crate) fn weighted_field(pair: &PairReport) -> Vec<(f64, f64, f64, f64)> {
    let mut v: Vec<(f64, f64, f64, f64)> = pair.points.iter().map(|q| (q.x, q.y, q.pressure, q.weight)).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    v
}

/// `field`, with each point's distance to its zone's estimated edge where it
/// ends a zone (`zones_along`'s uncertainty), else 0.
pub(crate) fn field_with_reach(pair: &PairReport) -> (Vec<(f64, f64, f64)>, Vec<f64>) {
    field_with(pair, |z, k, _| Some(z.uncertainty[k]))
}

/// `field`, with `reach(zone, k, end)` at each point that is a zone's end
/// `k` (0: start, 1: end), else 0.
fn field_with(
    pair: &PairReport,
    reach: impl Fn(&ZoneAlong, usize, [f64; 2]) -> Option<f64>,
) -> (Vec<(f64, f64, f64)>, Vec<f64>) {
    let pts = field(pair);
    let r = pts
        .iter()
        .map(|p| {
            pair.zones_along
                .iter()
                .flat_map(|z| [(z, 0, z.start), (z, 1, z.end)])
                .find(|(_, _, e)| e[0] == p.0 && e[1] == p.1)
                .and_then(|(z, k, e)| reach(z, k, e))
                .unwrap_or(0.0)
        })
        .collect();
    (pts, r)
}

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
/// (`end_fit`), not linearly to the open point (which puts pressure where
/// the zone has ended).
pub fn along(pts: &[(f64, f64, f64)], reach: Option<&[f64]>, x: f64, y: f64) -> f64 {
    along_with(pts, reach, x, y, false)
}

/// The described field (`described`'s points and reach) at (x, y).
pub fn described_at(pts: &[(f64, f64, f64)], reach: &[f64], x: f64, y: f64) -> f64 {
    along_with(pts, Some(reach), x, y, true)
}

fn along_with(pts: &[(f64, f64, f64)], reach: Option<&[f64]>, x: f64, y: f64, squared: bool) -> f64 {
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
            let r = reach.map(|r| [r[i], r[i + 1]]);
            best = (d, on_segment(a.2, b.2, r, t, len2.sqrt(), squared));
        }
    }
    best.1
}

/// The value at `t` ∈ [0, 1] along a segment of length `len` from a point of
/// value `a` to one of value `b`: linear, or, where one is a zone end
/// (positive, with `reach` > 0) and the other open, falling like a square
/// root from the end to zero at `reach` from it.
/// `squared`: p² linear between the points instead of p (`described`).
fn on_segment(a: f64, b: f64, reach: Option<[f64; 2]>, t: f64, len: f64, squared: bool) -> f64 {
    let linear = if squared {
        (a * a + t * (b * b - a * a)).max(0.0).sqrt()
    } else {
        a + t * (b - a)
    };
    match reach {
        Some(r) if (a > 0.0) != (b > 0.0) && len > 0.0 => {
            let (p, from_end, to_edge) = if a > 0.0 { (a, t, r[0]) } else { (b, 1.0 - t, r[1]) };
            let e = (to_edge / len).min(1.0);
            if e > 0.0 {
                p * (1.0 - from_end / e).max(0.0).sqrt()
            } else {
                linear
            }
        }
        _ => linear,
    }
}

/// The pressure the reply describes (`ZoneAlong::fitted`): p² linear
/// between consecutive points (a square-root edge's p² is linear in the
/// distance to it, Hertz's p² quadratic along the zone: p itself drawn linear
/// on the facets before the edge reads 0.43–0.60 % off the disk's overkill
/// table where the nodes are 0.23–0.43 % off), and on a zone end's facet
/// falling to 0 at its fitted edge; `field`, with
/// each zone end's distance to its fitted edge (`field_with_reach`'s
/// convention: 0 where none is fitted, the segment then linear; an edge
/// fitted at the node itself, a vanishing reach, 0 past the node). An edge
/// fitted inward of the end's node (`EndFit::edge`) ends the field on the
/// facet from the node before, and the end's node reads 0 in it.
pub fn described(pair: &PairReport) -> (Vec<(f64, f64, f64)>, Vec<f64>) {
    let (mut pts, mut reach) = field_with(pair, |z, k, e| {
        z.fitted[k]
            .filter(|_| !inward(z, k))
            .map(|f| (f.at[0] - e[0]).hypot(f.at[1] - e[1]).max(f64::MIN_POSITIVE))
    });
    for z in &pair.zones_along {
        for (k, e) in [(0, z.start), (1, z.end)] {
            if let Some(f) = z.fitted[k].filter(|_| inward(z, k)) {
                end_inside(&mut pts, &mut reach, e, f.at);
            }
        }
    }
    (pts, reach)
}

/// Whether zone `z`'s end `k` (0: start, 1: end) has its edge fitted inward
/// of its last node in contact (`EndFit::edge`).
pub(crate) fn inward(z: &ZoneAlong, k: usize) -> bool {
    z.fitted[k].is_some_and(|f| if k == 0 { f.s > z.s[0] } else { f.s < z.s[1] })
}

/// Ends the described field at `edge`, fitted inward of the zone end at
/// `end`: that node's multiplier is a weighted mean reaching past the edge,
/// so the pressure falls to 0 at the edge on the facet from the node before,
/// and the end's node reads 0.
/// The indices next to `i` along the sorted points of a field (`field`).
pub(crate) fn beside(i: usize, len: usize) -> impl Iterator<Item = usize> {
    [i.checked_sub(1), (i + 1 < len).then_some(i + 1)].into_iter().flatten()
}

fn end_inside(pts: &mut [(f64, f64, f64)], reach: &mut [f64], end: [f64; 2], edge: [f64; 2]) {
    let Some(i) = pts.iter().position(|p| p.0 == end[0] && p.1 == end[1]) else {
        return;
    };
    let before = beside(i, pts.len()).filter(|&j| pts[j].2 > 0.0).min_by(|&a, &b| {
        let d = |j: usize| (pts[j].0 - edge[0]).hypot(pts[j].1 - edge[1]);
        d(a).total_cmp(&d(b))
    });
    if let Some(j) = before {
        pts[i].2 = 0.0;
        reach[i] = 0.0;
        reach[j] = (edge[0] - pts[j].0).hypot(edge[1] - pts[j].1).max(f64::MIN_POSITIVE);
    }
}

/// Samples per segment of the described field's L2 integral: its square-root
/// facet's squared error converges like n^(−2) in the midpoint rule; 16
/// samples put the quadrature's share below 1e-3 of the facet's own.
const SAMPLES: usize = 16;

/// ∫ (p − f)² ds, ∫ max(p, f)² ds and ∫ f² ds along `pair`'s described
/// pressure p (`described`), by the midpoint rule on each segment between
/// consecutive points, over the samples where `counted`.
pub fn described_l2(
    pair: &PairReport,
    f: &dyn Fn(f64, f64) -> f64,
    counted: &dyn Fn(f64, f64) -> bool,
) -> (f64, f64, f64) {
    let (pts, reach) = described(pair);
    described_l2_of(&pts, &reach, f, counted)
}

/// `described_l2` of the points and reach of `described`.
pub(crate) fn described_l2_of(
    pts: &[(f64, f64, f64)],
    reach: &[f64],
    f: &dyn Fn(f64, f64) -> f64,
    counted: &dyn Fn(f64, f64) -> bool,
) -> (f64, f64, f64) {
    let (mut num, mut den, mut of_f) = (0.0, 0.0, 0.0);
    for i in 0..pts.len().saturating_sub(1) {
        let (a, b) = (pts[i], pts[i + 1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        if len == 0.0 {
            continue;
        }
        for k in 0..SAMPLES {
            let t = (k as f64 + 0.5) / SAMPLES as f64;
            let (x, y) = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            if !counted(x, y) {
                continue;
            }
            let p = on_segment(a.2, b.2, Some([reach[i], reach[i + 1]]), t, len, true);
            let q = f(x, y);
            if p > 0.0 || q > 0.0 {
                let ds = len / SAMPLES as f64;
                num += ds * (p - q).powi(2);
                den += ds * p.max(q).powi(2);
                of_f += ds * q * q;
            }
        }
    }
    (num, den, of_f)
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

    /// Hertz's p = √(a² − x²) at nodes 0.1 apart (a = 0.93), described with
    /// p² linear between nodes and the square-root facet to the fitted edge
    /// at 0.93: its L2 error along the surface is a small fraction of the
    /// polyline's that runs linearly to the open node at 1.0 (the field a
    /// user draws through the nodal values).
    #[test]
    fn the_described_field_follows_a_square_root_edge() {
        let a: f64 = 0.93;
        let exact = |x: f64, _: f64| (a * a - x * x).max(0.0).sqrt();
        let pts: Vec<(f64, f64, f64)> = (0..13)
            .map(|k| (0.1 * k as f64, 0.0, exact(0.1 * k as f64, 0.0)))
            .collect();
        let mut reach = vec![0.0; pts.len()];
        reach[9] = 0.03;
        let all = |_: f64, _: f64| true;
        let (num, _, den) = described_l2_of(&pts, &reach, &exact, &all);
        let described = (num / den).sqrt();
        // The polyline: p linear between the points, no fitted edge.
        let (mut n, mut d) = (0.0, 0.0);
        for k in 0..120_000 {
            let x = 1.2 * (k as f64 + 0.5) / 120_000.0;
            let line = along_polyline(&pts, x, 0.0);
            n += (line - exact(x, 0.0)).powi(2);
            d += exact(x, 0.0).powi(2);
        }
        let polyline = (n / d).sqrt();
        assert!(
            described < 0.004 && described < polyline / 5.0,
            "{described} against {polyline}"
        );
        // At the nodes and past the edge it is the nodal values and 0.
        assert!((described_at(&pts, &reach, 0.5, 0.0) - exact(0.5, 0.0)).abs() < 1e-12);
        assert_eq!(described_at(&pts, &reach, 0.95, 0.0), 0.0);
        assert!((described_at(&pts, &reach, 0.915, 0.0) - exact(0.9, 0.0) * 0.5f64.sqrt()).abs() < 1e-12);
    }

    /// Hertz's edge at a = 0.975, between the nodes at 0.9 and 1.0, where the
    /// node at 1.0 carries a small multiplier (a weighted mean over its
    /// facets): with the edge fitted inward of that node the described field
    /// falls to 0 at the edge, and its error is a small fraction of the field
    /// that ends at the node (the edge put there).
    #[test]
    fn an_edge_inside_the_last_facet_ends_the_field_there() {
        let a: f64 = 0.975;
        let exact = |x: f64, _: f64| (a * a - x * x).max(0.0).sqrt();
        let mut pts: Vec<(f64, f64, f64)> = (0..13)
            .map(|k| (0.1 * k as f64, 0.0, exact(0.1 * k as f64, 0.0)))
            .collect();
        pts[10].2 = 0.01 * pts[9].2;
        let all = |_: f64, _: f64| true;
        let error = |pts: &[(f64, f64, f64)], reach: &[f64]| {
            let (num, _, den) = described_l2_of(pts, reach, &exact, &all);
            (num / den).sqrt()
        };
        // The edge at the node itself: a vanishing reach there.
        let mut at_node = vec![0.0; pts.len()];
        at_node[10] = f64::MIN_POSITIVE;
        let before = error(&pts, &at_node);
        let mut reach = vec![0.0; pts.len()];
        end_inside(&mut pts, &mut reach, [1.0, 0.0], [a, 0.0]);
        let inside = error(&pts, &reach);
        // Ended at the edge, the field is Hertz's p² interpolated at spacing
        // 0.1 with its edge exact, as in the test above (< 0.004; 0.0017
        // measured). Ended at the node, it carries p₉² (1 − x)/0.1 on
        // [a, 1], where the pressure is 0: that span alone is
        // √(p₉² 0.025² / 0.2 / (2a³/3)) = 0.0267 of the zone's norm.
        let on_the_open_span = ((a * a - 0.81) * 0.025f64.powi(2) / 0.2 / (2.0 * a.powi(3) / 3.0)).sqrt();
        assert!(inside < 0.004, "{inside}");
        assert!(before >= on_the_open_span, "{before} against {on_the_open_span}");
        assert_eq!(described_at(&pts, &reach, 0.99, 0.0), 0.0);
        assert_eq!(described_at(&pts, &reach, 1.0, 0.0), 0.0);
        let p9 = exact(0.9, 0.0);
        let half = 0.9 + 0.5 * (a - 0.9);
        assert!((described_at(&pts, &reach, half, 0.0) - p9 * 0.5f64.sqrt()).abs() < 1e-12);
    }

    /// Hertz's p = √(a² − x²) sampled at nodes 0.1 apart with a = 0.93: the
    /// last node in contact is 0.9, the fit finds the edge 0.03 beyond it;
    /// a sharp corner (p rising to the end) is known only to the spacing; a
    /// zone at the end of its surface ends there.
    #[test]
    fn the_fit_finds_a_square_root_edge_between_nodes() {
        let hertz = |spacing: f64, n: usize| -> Vec<Station> {
            (0..n)
                .map(|k| {
                    let s = spacing * k as f64;
                    let p = (0.93f64 * 0.93 - s * s).max(0.0).sqrt();
                    Station {
                        s,
                        pressure: p,
                        in_contact: p > 0.0,
                    }
                })
                .collect()
        };
        let stations = hertz(0.1, 15);
        let e = end_fit(&stations, 0, 9, 1, 0.0).error;
        assert!((e - 0.03).abs() < 1e-9, "{e}");
        // p² is exactly quadratic: the edge is found where it is, and
        // leaving the last node out of the fit does not move it.
        let fit = end_fit(&stations, 0, 9, 1, 0.0);
        assert!((fit.edge.expect("a smooth edge") - 0.03).abs() < 1e-9, "{fit:?}");
        // Four nodes only, none to leave out: the end's own estimate.
        assert_eq!(fit.scatter, fit.error);
        let fine = hertz(0.02, 60);
        let fit = end_fit(&fine, 0, 46, 1, 0.0);
        assert!((fit.edge.expect("a smooth edge") - 0.01).abs() < 1e-9, "{fit:?}");
        assert!(fit.scatter < 1e-9, "{fit:?}");
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
        assert!((end_fit(&corner, 0, 9, 1, 0.0).error - 0.1).abs() < 1e-12);
        // A mortar row's last node just past the edge, its multiplier a
        // weighted mean reaching over the edge: the edge is fitted inward
        // of it, on the facet from the node before.
        let mut mortar = hertz(0.1, 15);
        mortar[10].pressure = 0.01 * mortar[9].pressure;
        mortar[10].in_contact = true;
        let fit = end_fit(&mortar, 0, 10, 1, 0.0);
        let edge = fit.edge.expect("a smooth edge");
        assert!(edge < 0.0 && edge > -0.1, "{fit:?}");
        assert_eq!(end_fit(&stations[..10], 0, 9, 1, 0.0).error, 0.0);
        // Past the last candidate the surface may go on (pruned nodes).
        assert_eq!(end_fit(&stations[..10], 0, 9, 1, 0.07).error, 0.07);
    }
}
