//! Zone ends at the end of the edge set whose node stands off its
//! neighbours (a press fit's bore where shaft and ring end flush): the end
//! node's own error, which no level resolves.
//!
//! The press fit pushed out (proto/examples/friction_press_fit_pushed_out.json,
//! the whole bore sliding) is bounded there: at fixed distances from the end
//! the pressure converges and runs flat into it, yet the nodes next to the
//! end read the same at every level, a layer a few nodes wide whatever h.
//! So the end node is off by the same amount at every level and the two
//! levels agree on it (Richardson's scaling divides it away). The end
//! node's step above its inward neighbour measures that error: as the
//! peak's and, times its tributary weight, as its share of the squared L2
//! error. The measurements (levels, effectivities, the reading of the
//! corner) and the command: docs/verification/accuracy.md, "A zone's end
//! at the edge set's end".

use crate::solution::report::PairReport;

/// An end node of a zone at the edge set's end standing above its nodes
/// next inward, which oscillate: (x, y, pressure, its step above the first
/// inward neighbour, tributary weight).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandingEnd {
    pub x: f64,
    pub y: f64,
    pub pressure: f64,
    pub step: f64,
    pub weight: f64,
}

/// The pair's zone ends at the end of the edge set (their position exact:
/// zero uncertainty) whose pressure exceeds the next node inward and the one
/// after, which itself exceeds the first (an oscillation, not a rise), not on
/// a symmetry axis about y; only
/// where `counted` (outside the singular ends' bands, `corners`).
pub fn standing_ends(pair: &PairReport, counted: &dyn Fn(f64, f64) -> bool) -> Vec<StandingEnd> {
    let candidates: Vec<(f64, f64, f64, f64)> = pair.points.iter().map(|q| (q.x, q.y, q.pressure, q.weight)).collect();
    // The candidate nearest to `from`, other than those in `not`: the
    // neighbours along the surface, whatever its shape, as `corners` finds
    // them. Open ones included: the two inward must both be in contact, in
    // the end's zone (a 16-element block on a vee, two zones of two nodes
    // each, read the other zone's node as the second and its estimate
    // 0.40 for 0.079).
    let nearest = |from: (f64, f64), not: &[(f64, f64)]| {
        candidates
            .iter()
            .filter(|q| !not.iter().any(|n| n.0 == q.0 && n.1 == q.1))
            .min_by(|a, b| {
                let d = |q: &&(f64, f64, f64, f64)| (q.0 - from.0).hypot(q.1 - from.1);
                d(a).total_cmp(&d(b))
            })
            .copied()
    };
    let at = |q: (f64, f64, f64, f64)| (q.0, q.1);
    let mut out = Vec::new();
    for z in &pair.zones_along {
        for (end, uncertainty) in [(z.start, z.uncertainty[0]), (z.end, z.uncertainty[1])] {
            if uncertainty > 0.0 || !counted(end[0], end[1]) {
                continue;
            }
            let Some(&last) = candidates.iter().find(|q| q.0 == end[0] && q.1 == end[1] && q.2 > 0.0) else {
                continue;
            };
            let Some(first) = nearest(at(last), &[at(last)]).filter(|q| q.2 > 0.0) else {
                continue;
            };
            let Some(second) = nearest(at(first), &[at(last), at(first)]).filter(|q| q.2 > 0.0) else {
                continue;
            };
            // Above both, the first dipping below the second: a node-scale
            // oscillation. A resolved rise into the end (a Winkler footing's
            // edge) falls monotonically inward over these three nodes:
            // without this the step read the footing's peak at 7.6–12.7
            // times its true error.
            if !(second.2 < last.2 && first.2 < second.2) {
                continue;
            }
            // A symmetry axis about y (an axisymmetric section's r = 0, a
            // symmetric half's x = 0), which the surface leaves: its node's
            // ripple is `two_level::peak_spike`'s (0.4 % of p on the ball on
            // a flat, T3 at 5.8k DOF, read here as 4.0 times the peak's true
            // error). On the axis to round-off of the facet (the ball's axis
            // node sits at x = 6e-17 for a facet of 0.0022).
            let facet = (first.0 - last.0).hypot(first.1 - last.1);
            if last.0.abs() <= AXIS * facet && first.0.abs() > AXIS * facet {
                continue;
            }
            out.push(StandingEnd {
                x: last.0,
                y: last.1,
                pressure: last.2,
                step: last.2 - first.2,
                weight: last.3,
            });
        }
    }
    out
}

/// A node within this fraction of its facet of x = 0 lies on the y axis.
const AXIS: f64 = 1e-9;

/// Σ w step² over the standing ends: their nodes' share of the squared L2
/// error, to be divided by the zone's Σ w p².
pub fn l2_share(ends: &[StandingEnd]) -> f64 {
    ends.iter().map(|e| e.weight * e.step * e.step).sum()
}

/// The peak's error where a standing end's node is the peak `peak` (the
/// largest counted nodal pressure): its step over the peak; 0 elsewhere.
pub fn peak_error(ends: &[StandingEnd], peak: f64) -> f64 {
    ends.iter()
        .filter(|e| peak > 0.0 && e.pressure >= peak)
        .map(|e| e.step / peak)
        .fold(0.0, f64::max)
}
