//! Zone ends where the pressure is unbounded: a rigid punch's sharp corner
//! (or any edge of the contact zone fixed by a kink of a surface), where the
//! pressure rises like d^(−1/2) in the distance d to the corner (Sadowsky's
//! flat punch, Johnson §2.8; Boussinesq's in axisymmetry).
//!
//! There p is not square-integrable (∫ p² dd diverges like ln d), so the
//! relative L2 error of the nodal pressure over the whole zone has no limit:
//! measured on the flat punch of revolution and the flat punch under a moment
//! against the same scenes solved 4× finer, it stayed at 20–80 % over three
//! levels while the estimate of the same quantity said 8–27 %. The estimate
//! (`two_level::two_level`) and its check (`contact-verify`'s effectivity) both
//! leave out a band at each such end, `BAND` of the zone's length, which the
//! reply names, so that what is estimated converges; the corner's own
//! pressure is the singular solution's and is not estimated.
//!
//! An end is singular when the pressure at its last node in contact exceeds
//! that of both nodes next inward (a smooth edge's pressure falls to it) and
//! the surface goes on past it (where the edge set itself ends, a footing's
//! whole base, the end is that of the body and its zone end is exact), or
//! where the edge set ends on a target that goes on past it and carries
//! load there (a Pasternak layer, an elastic half-plane).

use crate::solution::report::{PairReport, SingularEnd};

/// Fraction of a zone's length (along the surface) left out at each singular
/// end.
pub const BAND: f64 = 0.05;

/// The singular zone ends of a pair, each with the band left out around it.
pub fn singular_ends(pair: &PairReport) -> Vec<SingularEnd> {
    let touching: Vec<(f64, f64, f64)> = pair
        .points
        .iter()
        .filter(|q| q.pressure > 0.0)
        .map(|q| (q.x, q.y, q.pressure))
        .collect();
    // The point in contact nearest to `from`, other than those in `not`: the
    // neighbours along the surface, whatever its shape (not by x).
    let nearest = |from: (f64, f64, f64), not: &[(f64, f64, f64)]| {
        touching
            .iter()
            .filter(|q| !not.iter().any(|n| n.0 == q.0 && n.1 == q.1))
            .min_by(|a, b| {
                let d = |q: &&(f64, f64, f64)| (q.0 - from.0).hypot(q.1 - from.1);
                d(a).total_cmp(&d(b))
            })
            .copied()
    };
    let mut out = Vec::new();
    for z in &pair.zones_along {
        let length = (z.s[1] - z.s[0]).abs();
        for (end, uncertainty) in [(z.start, z.uncertainty[0]), (z.end, z.uncertainty[1])] {
            // An end of the edge set (its place exact) is a corner too where
            // the target goes on past it: a footing's edge on a Pasternak
            // layer carries a concentrated line load √(kμ) w there, and on a
            // half-plane the edge of a stiffer body is a punch's corner (the
            // end nodes measured: docs/verification/accuracy.md, "A
            // footing's edge on a Pasternak layer").
            if length <= 0.0 || (uncertainty <= 0.0 && !pair.goes_on) {
                continue;
            }
            let Some(&last) = touching.iter().find(|q| q.0 == end[0] && q.1 == end[1]) else {
                continue;
            };
            // The end above both its inward neighbours (three nodes at
            // least): one interval alone is a zone two nodes wide; T6 corner
            // and midside values may alternate next to the end.
            let Some(first) = nearest(last, &[last]) else { continue };
            let Some(second) = nearest(first, &[last, first]) else {
                continue;
            };
            if last.2 > first.2 && last.2 > second.2 {
                out.push(SingularEnd {
                    at: end,
                    band: BAND * length,
                });
            }
        }
    }
    out
}

/// Whether (x, y) lies in the band of one of `ends`.
pub fn in_band(ends: &[SingularEnd], x: f64, y: f64) -> bool {
    ends.iter().any(|e| (x - e.at[0]).hypot(y - e.at[1]) < e.band)
}
