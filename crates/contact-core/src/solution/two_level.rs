//! The two-level estimate of a pair's error (`adapt` solves the companion):
//! the answer against the same scene on meshes whose every element differs
//! by a factor 2 in size, Richardson-scaled, with the zone ends' own nodal
//! error beside it. One estimator in one file: a second one (an
//! equilibrated-flux bound, say) would sit beside it and fill the same
//! `PairAccuracy`.
//!
//! Length: about 625 lines, the two levels' differences and the answer's own
//! nodal terms each estimate keeps the largest of (zone ends, edge placement,
//! spacing steps, an axis peak, an end node standing off its neighbours
//! (`end_layer`), the resultant's floor), each with the
//! measurement that made it: one estimate read as a whole. Its
//! dimension-free sums (`relative_l2`, `peak_deviation`, `richardson`,
//! `resultant`) serve the 3D estimate too (`solid::two_level`).

use crate::outcome::EstimateBasis;
use crate::solution::accuracy;
use crate::solution::accuracy::{
    along, along_polyline, described, described_at, described_l2_of, field, field_with_reach, fit_quadratic, MIN_FIT,
};
use crate::solution::corners;
use crate::solution::end_layer;
use crate::solution::peak_fit;
use crate::solution::report::{PairAccuracy, PairReport, SingularEnd};

/// A node of a pair's surface: (x, y, pressure, tributary weight), in the
/// order of `accuracy::weighted_field`.
type Node = (f64, f64, f64, f64);

/// The two-level estimate of the error of a pair's answer: the same pair
/// solved on meshes whose every element is `ratio` times as large (`other`;
/// `ratio` = 2: a coarser companion of a generated mesh, ½: a given mesh
/// bisected twice over, far field included) differs from the answer by about
/// |ratio^q − 1| times the answer's error, for an error of order q in the
/// element size (`order`: the pressure's error is dominated by where the zone
/// edge falls between nodes and by the graded field's stiffness, both O(h²)
/// for T3; for T6, whose multipliers sit on every surface node, the estimate
/// with q = 2 kept its effectivity within 0.67–1.64 on the disk, ball, block
/// and two cylinders at three levels each, measured against the overkill
/// tables or the scene solved 4× finer). Against a finer companion the
/// answer's error is the difference over 1 − 2^(−q) (¾ for q = 2), against a
/// coarser one over 2^q − 1 (3).
///
/// Against a coarser companion the nodal L2 difference is taken both ways
/// and the larger kept: at the answer's candidates (the other pressure
/// interpolated along its surface, weighed by the answer's tributary
/// weights) and at the other's. Against a finer one, only at the answer's
/// candidates: the finer nodes read against the answer's polyline measure
/// the polyline's interpolation error, not the answer's nodal error (the
/// inline disk and block read 1.1–5.5 times their true error both ways,
/// 0.93–1.71 at the answer's nodes, `contact-verify`'s effectivity). Where the
/// edge's placement dominates, the two levels' errors are not in Richardson's
/// ratio and either comparison alone can miss it: on the T6 disk
/// (multipliers on the corners then) at h = 0.0088 R the coarse-node
/// comparison gave 0.15 % for a true 1.08 %, the fine-node one 0.57 %; at
/// h = 0.0044 R the fine-node comparison gave 1.54 % for a true 0.20 % (a
/// linear segment across the coarse zone's square-root edge), the coarse-node
/// one 0.29 %. Keeping the larger errs on the safe side.
///
/// The pressure's estimate is that of the field the reply describes
/// (`accuracy::described`: p² linear between nodes, the square-root facet to
/// each fitted edge), integrated along the answer's surface against the
/// other level's described field; the nodal difference above is its fallback
/// where no pressure is described. Its effectivity against the overkill
/// tables and 4× finer solves is `contact-verify`'s effectivity example
/// (`err_curve`, the table in docs/verification/accuracy.md); why the field
/// is described so is `accuracy::described`.
///
/// The zone ends' own error (`edge_deviation`) is a second, direct
/// estimate, the edge's placement (`edge_placement`) a third and the nodes'
/// offset where the spacing changes (`grading_deviation`) a fourth; the
/// largest is the pressure's (effectivities: the table cited above). Without
/// the nodal term the finer levels' last-node error went unseen (measured
/// with T6 multipliers on the corners only: 0.19 at worst on the
/// smooth-edged scenes, against 0.56 with it). Zone ends where the
/// pressure is unbounded are left out with a band around them (`corners`).
///
/// The peak's error is that of the largest nodal value (outside the
/// singular ends' bands), what the reply's `peak` estimates. It is the nodal
/// difference between the levels where the answer is within `PEAK_REGION` of
/// its peak, not the difference of the two maxima: the two maxima alone can
/// agree while the field around them does not (that estimate read 0.03–0.4
/// of the true peak error on balls and two-body scenes). Where both levels'
/// peaks are smooth maxima, the smaller of that and the fitted peaks'
/// estimate (`peak_fit::fitted_peak_error`) is kept: each errs high where
/// the other does not (the nodal difference where the other level's nodes
/// scatter near the peak, the fitted one where the answer's own do), and
/// neither read below 0.5 of the true error where it is read, on the
/// effectivity scenes (docs/verification/accuracy.md, "Peak").
pub fn two_level(answer: &PairReport, other: &PairReport, ratio: f64) -> PairAccuracy {
    let singular = corners::singular_ends(answer);
    let counted = |x: f64, y: f64| !corners::in_band(&singular, x, y);
    let d = differences(answer, other, &counted, ratio > 1.0);
    let scale = richardson(ratio, order(&singular));
    // The zone ends' own nodal error, which the two levels' steps hide.
    let den: f64 = answer
        .points
        .iter()
        .filter(|q| counted(q.x, q.y))
        .map(|q| q.weight * q.pressure * q.pressure)
        .sum();
    // The answer's nodes in surface order, read by its own nodal terms.
    let nodes = accuracy::weighted_field(answer);
    // Where neighbouring spacings differ, each node's own error (which the
    // two levels, graded alike, do not see).
    let grading = if den > 0.0 {
        grading_deviation(&nodes, &counted) / den
    } else {
        0.0
    };
    // An end of the edge set whose node stands off its oscillating
    // neighbours: its own error, the same at every level (`end_layer`).
    let standing = end_layer::standing_ends(answer, &counted);
    let layer = if den > 0.0 {
        end_layer::l2_share(&standing) / den
    } else {
        0.0
    };
    let top = nodes
        .iter()
        .filter(|q| counted(q.0, q.1))
        .map(|q| q.2)
        .fold(0.0, f64::max);
    // The described field's difference (the square-root facets to the
    // fitted edges included), along the answer's surface.
    let (pa, ra) = described(answer);
    let (po, ro) = described(other);
    let (num, of_curve, _) = described_l2_of(&pa, &ra, &|x, y| described_at(&po, &ro, x, y), &counted);
    let curve = (of_curve > 0.0).then(|| (num / of_curve).sqrt());
    let edge = if of_curve > 0.0 {
        edge_deviation(answer, &nodes, &pa, &ra) / of_curve
    } else {
        0.0
    };
    // A zone of a few nodes has no fitted edges and its described facets are
    // guesses: there the nodal difference counts too (the Hertz example at
    // E × 1000, three nodes in contact: 2.7 % from the described field
    // alone, 6.4 % with the nodes).
    let few = answer.points.iter().filter(|q| q.pressure > 0.0).count() < FEW_IN_CONTACT;
    let l2 = match (curve, d.l2) {
        (Some(c), Some(n)) if few => Some(c.max(n)),
        (c, n) => c.or(n),
    };
    // Where the described edge may lie, which both levels can miss alike.
    let placement = if of_curve > 0.0 {
        (edge_placement(&pa, &ra) / of_curve).sqrt()
    } else {
        0.0
    };
    PairAccuracy {
        energy: None,
        basis: if ratio < 1.0 {
            EstimateBasis::TwoLevelFiner
        } else {
            EstimateBasis::TwoLevel
        },
        pressure_l2: l2.map(|v| {
            (v / scale)
                .max(edge.sqrt())
                .max(placement)
                .max(grading.sqrt())
                .max(layer.sqrt())
        }),
        peak: d.peak.map(|v| {
            let theirs = accuracy::weighted_field(other);
            peak_fit::fitted_peak_error(&nodes, &theirs, &counted, PEAK_REGION, scale)
                .map_or(v / scale, |f| f.min(v / scale))
                .max(peak_spike(&nodes, &counted))
                .max(end_layer::peak_error(&standing, top))
        }),
        resultant: d.resultant.map(|v| resultant(v, scale)),
        zone_edges: answer.zones_along.iter().map(|z| z.uncertainty).collect(),
        fitted_edges: fitted_edges(answer, other, scale),
        singular_ends: singular,
    }
}

/// The factor between two levels' difference and the answer's error, for a
/// companion whose elements are `ratio` times the answer's and an error of
/// order q in the element size: |ratio^q − 1| (3 against a coarser companion
/// for q = 2, ¾ against a finer one). Dimension-free: the 3D estimate
/// (`solid::two_level`) divides by it too.
pub(crate) fn richardson(ratio: f64, q: f64) -> f64 {
    (ratio.powf(q) - 1.0).abs()
}

/// The relative L2 difference √(Σ w (p − p̃)² / Σ w max(p, p̃)²) over the
/// samples (w, p, p̃) of one level's points (weight, own pressure, the other
/// level's there) where either presses; None without pressure. Dimension-free:
/// the samples are points along a 2D surface or on a 3D face set.
pub(crate) fn relative_l2(samples: impl Iterator<Item = (f64, f64, f64)>) -> Option<f64> {
    let (mut num, mut den) = (0.0, 0.0);
    for (w, p, po) in samples {
        if p > 0.0 || po > 0.0 {
            num += w * (p - po).powi(2);
            den += w * p.max(po).powi(2);
        }
    }
    (den > 0.0).then(|| (num / den).sqrt())
}

/// Whether a point's pressure `p` lies within `PEAK_REGION` of the level's
/// `peak`: the points whose difference estimates the peak's error.
pub(crate) fn near_peak(p: f64, peak: f64) -> bool {
    p >= PEAK_REGION * peak
}

/// The root mean square of |p − p̃| over samples (w, p, p̃) near the peak
/// (`near_peak`), or the difference at the peak itself where that is larger
/// (`peak_difference` says why both). Dimension-free, as `relative_l2`.
pub(crate) fn peak_deviation(samples: impl Iterator<Item = (f64, f64, f64)>, peak: f64) -> f64 {
    let (mut num, mut den, mut at_peak) = (0.0, 0.0, 0.0);
    for (w, p, po) in samples {
        let d = (p - po).abs();
        num += w * d * d;
        den += w;
        if p == peak {
            at_peak = d;
        }
    }
    if den > 0.0 {
        (num / den).sqrt().max(at_peak)
    } else {
        at_peak
    }
}

/// Below this the two levels cannot tell a resultant's error (relative).
/// T6 resultants converge fast and their error changes sign from level to
/// level, so two levels can agree by chance (the two-level difference read
/// 0.02–0.34 of the true error on the finest T6 levels); 1e-4 is above the
/// errors measured there. The measurements: docs/verification/accuracy.md,
/// "Resultant".
pub(crate) const RESULTANT_FLOOR: f64 = 1e-4;

/// Two levels whose resultants agree to round-off carry a resultant the loads
/// prescribe (a punch, a footing under a force): exact, not estimated.
const RESULTANT_PRESCRIBED: f64 = 1e-12;

/// The resultant's estimate from its relative two-level difference `diff`:
/// Richardson-scaled, and not below what two levels can resolve.
pub(crate) fn resultant(diff: f64, scale: f64) -> f64 {
    if diff <= RESULTANT_PRESCRIBED {
        diff / scale
    } else {
        (diff / scale).max(RESULTANT_FLOOR)
    }
}

/// Each fitted edge's estimated error: its distance to the nearest fitted
/// edge of the other level, over `scale`, or its zone end's uncertainty
/// where the other level fits none.
fn fitted_edges(answer: &PairReport, other: &PairReport, scale: f64) -> Vec<[Option<f64>; 2]> {
    let theirs: Vec<[f64; 2]> = other
        .zones_along
        .iter()
        .flat_map(|z| z.fitted.into_iter().flatten())
        .map(|f| f.at)
        .collect();
    answer
        .zones_along
        .iter()
        .map(|z| {
            [0, 1].map(|k| {
                z.fitted[k].map(|f| {
                    theirs
                        .iter()
                        .map(|o| (o[0] - f.at[0]).hypot(o[1] - f.at[1]))
                        .min_by(f64::total_cmp)
                        .filter(|&d| d <= 2.0 * z.uncertainty[k].max(f64::MIN_POSITIVE))
                        .map_or(z.uncertainty[k], |d| (d / scale).max(f.scatter))
                })
            })
        })
        .collect()
}

/// Relative differences between two levels of a pair: the nodal pressure's
/// L2, the peak's (`peak_difference`) and the resultant's.
struct Differences {
    l2: Option<f64>,
    peak: Option<f64>,
    resultant: Option<f64>,
}

/// `both`: the L2 difference taken at the other's candidates too (`two_level`).
fn differences(answer: &PairReport, other: &PairReport, counted: &dyn Fn(f64, f64) -> bool, both: bool) -> Differences {
    // Relative L2 difference of `at`'s nodal pressure from `other`'s
    // field, weighed at `at`'s candidates; None without pressure.
    let relative = |at: &PairReport, other: &PairReport| {
        let (pts, reach) = field_with_reach(other);
        relative_l2(
            at.points
                .iter()
                .filter(|q| counted(q.x, q.y))
                .map(|q| (q.weight, q.pressure, along(&pts, Some(&reach), q.x, q.y))),
        )
    };
    let l2 = match (relative(answer, other), both.then(|| relative(other, answer)).flatten()) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    };
    let norm = |r: &crate::solution::report::Resultant| r.fx.hypot(r.fy);
    let (ra, ro) = (norm(&answer.resultant), norm(&other.resultant));
    let dr = (answer.resultant.fx - other.resultant.fx).hypot(answer.resultant.fy - other.resultant.fy);
    Differences {
        l2,
        peak: peak_difference(answer, other, counted),
        resultant: (ra > 0.0 && ro.is_finite()).then(|| dr / ra),
    }
}

/// The order q of the pressure's error in the element size. Next to a sharp
/// corner (outside its band) the local error is polluted by the d^(−1/2)
/// singularity and falls like h¹–h^1.3 (measured on two punch scenes), so
/// q = 2 under-estimates it by 2.5–4× (punch L2 effectivities 0.22–0.39):
/// q = 1 there errs on the safe side (1.04–2.96 on the two punch scenes of
/// the convergence suite at three levels, T3 and T6). Orders measured from a
/// third, coarser level were tried and dropped: at these levels the
/// differences do not fall regularly, and the measured orders put smooth
/// scenes' effectivities at up to 8.6 and a punch's at 0.35.
fn order(singular: &[SingularEnd]) -> f64 {
    if singular.is_empty() {
        2.0
    } else {
        1.0
    }
}

/// Σ w_i e_i² over the answer's nodes in contact between two nodes in
/// contact, e_i = |p′| |h₊ − h₋| / 3: a node's value λ_i / w_i is the mean of
/// the pressure weighed by its hat over the spacings h₋ and h₊ to its
/// neighbours, whose centroid lies (h₊ − h₋)/3 from the node, so where the
/// spacing changes the value is the pressure a third of the change away
/// (first order in h, where the rest of the error is second order). Two
/// levels whose spacings change at the same ratio see it only in part:
/// against the coarser companion of a given mesh with two-to-one steps in
/// its surface spacing the estimate read 0.46–0.83 of the true error (the
/// Hertz block, T6, 23k–62k DOF), and this term 0.92–0.97 of the nodal error
/// (the spikes at the steps: 0.3–1.0 % of p0, each within 0.8–1.2 of
/// |p′| |h₊ − h₋| / 3). p′ is the central difference of the neighbours.
fn grading_deviation(pts: &[Node], counted: &dyn Fn(f64, f64) -> bool) -> f64 {
    let dist = |a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    pts.windows(3)
        .filter(|w| w.iter().all(|q| q.2 > 0.0) && counted(w[1].0, w[1].1))
        .map(|w| {
            let (h0, h1) = (dist(w[0], w[1]), dist(w[1], w[2]));
            let slope = (w[2].2 - w[0].2) / (h0 + h1);
            let e = slope * (h1 - h0) / 3.0;
            w[1].3 * e * e
        })
        .sum()
}

/// Fewer nodes in contact than this (the element edges across a zone that
/// `coarse_contact_zone` asks for) make the pressure's estimate the larger of
/// the described field's and the nodes'.
const FEW_IN_CONTACT: usize = 8;

/// Nodes within this fraction of the answer's peak pressure make the region
/// whose largest difference between levels estimates the peak's error (for
/// Hertz, |x| ≤ 0.44 a).
const PEAK_REGION: f64 = 0.9;

/// The difference |p − p̃| over the answer's nodes within `PEAK_REGION` of
/// its peak and over the other's nodes within it of theirs (each against the
/// other's field), the larger of the two, relative to the answer's peak;
/// None without pressure.
fn peak_difference(answer: &PairReport, other: &PairReport, counted: &dyn Fn(f64, f64) -> bool) -> Option<f64> {
    let top = |pair: &PairReport| {
        pair.points
            .iter()
            .filter(|q| counted(q.x, q.y))
            .map(|q| q.pressure)
            .fold(0.0, f64::max)
    };
    let (pa, po) = (top(answer), top(other));
    if pa <= 0.0 || po <= 0.0 {
        return None;
    }
    // Root mean square over the region (weighed by the tributary weights),
    // or the difference at the maximum itself where that is larger: the
    // largest difference anywhere picked up the nodal ripple of mortar rows
    // on two cylinders (the peak estimated 5–26× its true error), the mean
    // alone missed a user mesh's spike at its symmetry axis node (+2.5 % of
    // p0 over its neighbour, halving with h).
    let largest = |at: &PairReport, peak: f64, from: &PairReport| {
        let pts = field(from);
        peak_deviation(
            at.points
                .iter()
                .filter(|q| counted(q.x, q.y) && near_peak(q.pressure, peak))
                .map(|q| (q.weight, q.pressure, along_polyline(&pts, q.x, q.y))),
            peak,
        )
    };
    Some(largest(answer, pa, other).max(largest(other, po, answer)) / pa)
}

/// Where the answer's peak is the first or last of its candidates in their
/// order along x (a symmetry axis at the surface's end), that node's own
/// deviation from the trend of its next `SPIKE_FIT` nodes, relative to the
/// peak; 0 elsewhere. An axis node that stands off its neighbours carries an
/// error the two levels share and Richardson's scaling divides away (a user's
/// quarter disk, estimated at a third of its true peak error without this).
/// The trend is the even quadratic p0 − c s² (s along the surface) or the
/// full quadratic, whichever the node is nearer (an axis peak has zero
/// slope), and only where the neighbours follow the even one to `SPIKE_EVEN`
/// of their spread: a pressure that rises toward an end (a Pasternak
/// footing's edge) is the physics there, not a node's error, and an end
/// node standing off oscillating neighbours (a press fit's flush ends) is
/// `end_layer`'s. Interior peaks are left to the two levels: there a T6 surface's
/// corner and midside values alternate (the two cylinders), which a
/// neighbours' fit reads as a spike at every level. The measurements:
/// docs/verification/accuracy.md, "A peak node standing off its neighbours".
fn peak_spike(pts: &[Node], counted: &dyn Fn(f64, f64) -> bool) -> f64 {
    let Some(m) = (0..pts.len())
        .filter(|&i| counted(pts[i].0, pts[i].1))
        .max_by(|&a, &b| pts[a].2.total_cmp(&pts[b].2))
    else {
        return 0.0;
    };
    let peak = pts[m].2;
    let near: Vec<usize> = if m == 0 {
        (1..=SPIKE_FIT).collect()
    } else if m + 1 == pts.len() {
        (m.saturating_sub(SPIKE_FIT)..m).collect()
    } else {
        return 0.0;
    };
    let usable = |i: usize| i < pts.len() && pts[i].2 > 0.0 && counted(pts[i].0, pts[i].1);
    if peak <= 0.0 || near.len() < SPIKE_FIT || !near.iter().all(|&i| usable(i)) {
        return 0.0;
    }
    let s = |i: usize| (pts[i].0 - pts[m].0).hypot(pts[i].1 - pts[m].1);
    // p ≈ p0 − c s²: least squares in t = s².
    let (mut st, mut stt, mut sp, mut stp) = (0.0, 0.0, 0.0, 0.0);
    for &i in &near {
        let t = s(i) * s(i);
        st += t;
        stt += t * t;
        sp += pts[i].2;
        stp += t * pts[i].2;
    }
    let n = near.len() as f64;
    let det = n * stt - st * st;
    if det <= 0.0 {
        return 0.0;
    }
    let (p0, c) = ((stt * sp - st * stp) / det, (n * stp - st * sp) / det);
    let spread = near.iter().map(|&i| pts[i].2).fold(f64::NEG_INFINITY, f64::max)
        - near.iter().map(|&i| pts[i].2).fold(f64::INFINITY, f64::min);
    let off = near
        .iter()
        .map(|&i| (pts[i].2 - p0 - c * s(i) * s(i)).abs())
        .fold(0.0, f64::max);
    if off > SPIKE_EVEN * spread {
        return 0.0;
    }
    let even = Some(p0);
    let full = fit_quadratic(&near.iter().map(|&i| (s(i), pts[i].2)).collect::<Vec<_>>()).map(|c| c[0]);
    [even, full]
        .into_iter()
        .flatten()
        .map(|p0| (peak - p0).abs() / peak)
        .min_by(f64::total_cmp)
        .unwrap_or(0.0)
}

/// Nodes next to an axis peak that its even fit (`peak_spike`) runs through.
const SPIKE_FIT: usize = 4;

/// How closely those nodes must follow the even fit, as a share of their
/// spread, for the end to read as an axis; the readings that place it
/// (a user's axis against press-fit and footing edges) are with
/// `peak_spike`'s measurements.
const SPIKE_EVEN: f64 = 0.1;

/// ∫ (f_D − f_D')² ds over each described square-root facet (`described`):
/// f_D = p √(1 − d/D) falls from the facet's node to the fitted edge at D,
/// and D' = D ± `PLACEMENT` × the facet's length, the larger of the two. The
/// last nodes' values and the fitted edge are off by amounts that depend on
/// where the edge falls between nodes, and two levels can agree on them by
/// chance: on the T3 disk at h_min = 0.00202 R (6.6k DOF) the described
/// field was 0.68 % off its overkill table, 82 % of its square on the edge's
/// facet, where the two levels' estimate read 0.36 %; with this term 0.51 %.
fn edge_placement(pts: &[(f64, f64, f64)], reach: &[f64]) -> f64 {
    let mut sum = 0.0;
    for i in 0..pts.len() {
        if reach[i] <= 0.0 || pts[i].2 <= 0.0 {
            continue;
        }
        // The facet the edge lies on: to the open neighbour.
        let Some(facet) = accuracy::beside(i, pts.len())
            .filter(|&n| pts[n].2 <= 0.0)
            .map(|n| (pts[n].0 - pts[i].0).hypot(pts[n].1 - pts[i].1))
            .min_by(f64::total_cmp)
        else {
            continue;
        };
        let d0 = reach[i].min(facet);
        let u = PLACEMENT * facet;
        let fall = |d: f64, e: f64| if e > 0.0 { (1.0 - d / e).max(0.0).sqrt() } else { 0.0 };
        let worst = [d0 + u, (d0 - u).max(0.0)]
            .map(|e| {
                let to = e.max(d0);
                (0..PLACEMENT_SAMPLES)
                    .map(|j| {
                        let d = (j as f64 + 0.5) / PLACEMENT_SAMPLES as f64 * to;
                        (fall(d, d0) - fall(d, e)).powi(2)
                    })
                    .sum::<f64>()
                    * to
                    / PLACEMENT_SAMPLES as f64
            })
            .into_iter()
            .fold(0.0, f64::max);
        sum += pts[i].2 * pts[i].2 * worst;
    }
    sum
}

/// The fitted edge's typical error as a fraction of its facet: over ten
/// levels of the disk on a flat (T3 and T6, h_min 0.01 to 0.000625 R) its
/// distance to the overkill table's edge was 0.00–0.24 facets, root mean
/// square 0.13. What it does to the pressure's effectivity over the
/// convergence scenes is the table in docs/verification/accuracy.md.
const PLACEMENT: f64 = 0.1;
/// Midpoint samples of a placement integral (its square-root end converges
/// like n^(−2)).
const PLACEMENT_SAMPLES: usize = 64;

/// ∫ (p_D − p_fit)² ds, p_D the described field (`described`), over each
/// smooth zone end's facet to the open node and the facets of the nodes
/// inward of it that p_fit, the square-root profile (p² quadratic in the
/// distance to the end), is fitted on (up to 12; the end's node itself is
/// not in the fit), times n/(n − 3) for the n fitted nodes. The last node's
/// value depends on where the edge falls between it and the next (a node
/// 0.37 spacings inside the edge read 15 % below the profile on the T3 disk
/// at h_min = 0.00125 R, 97 % of that solution's squared L2 error), which
/// neither level of `two_level` sees when both ends fall alike. Near a
/// smooth edge the exact p² is c₁ d + c₂ d² + O(d³) (Hertz: exactly
/// quadratic), so the described field's misfit to that profile is an error
/// the two levels share, read in the norm the estimate is of.
///
/// It was the nodal misfit Σ w (p − p_fit)² at the end's node and the open
/// one, which the described field does not carry: with p² linear on the
/// end's facet, a small end value moves the field there by much less than
/// itself (the two cylinders T3 at 328k DOF: the end node 0.013 p0 for a
/// true 0.057 p0, the fit 0.12 p0, where the described field's error was
/// 0.48 %). On two bodies the mortar rows' last nodes are off by a few % of
/// p0 at every level (±4.4 % at the last two there), so that term did not
/// fall with h: it alone made the estimate, 1.19, 1.07, 1.35 % over the
/// rounds to 0.5 % at 39k, 152k and 328k DOF. Read over the fitted nodes
/// too, the misfit sees the ripple near the end both levels share (T6's
/// corner and midside values alternating by ±1.4 % of p0 on the two
/// cylinders at 39k DOF, effectivity 0.92 → 1.06). The measurements:
/// docs/verification/accuracy.md, "Zone ends' own error".
fn edge_deviation(pair: &PairReport, pts: &[Node], dp: &[(f64, f64, f64)], dr: &[f64]) -> f64 {
    let dist = |a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let mut sum = 0.0;
    for z in &pair.zones_along {
        for (k, end) in [(0, z.start), (1, z.end)] {
            // An end node past its fitted edge reads 0 in the described
            // field: its multiplier is a weighted mean reaching over the
            // edge, not the pressure there, and `edge_placement` counts the
            // facet before it.
            if accuracy::inward(z, k) {
                continue;
            }
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
            // The facets (from, t, to, t) the described field is read on:
            // the end's to the open node (t < 0), then inward over the n
            // fitted nodes.
            let mut facets: Vec<(usize, f64, usize, f64)> =
                open.map(|o| (i, 0.0, o, -dist(pts[i], pts[o]))).into_iter().collect();
            let mut from = (i, 0.0);
            for &(t, _) in &window[..n] {
                let Some(to) = from.0.checked_add_signed(dir) else {
                    break;
                };
                facets.push((from.0, from.1, to, t));
                from = (to, t);
            }
            // The fit's three coefficients absorb three of the n nodes'
            // errors (its hat matrix has trace 3), so the misfit reads
            // (n − 3)/n of their square: scaled back by n/(n − 3).
            let dof = n as f64 / (n - 3) as f64;
            for (a, ta, b, tb) in facets {
                let ds = (tb - ta).abs() / PLACEMENT_SAMPLES as f64;
                for k in 0..PLACEMENT_SAMPLES {
                    let u = (k as f64 + 0.5) / PLACEMENT_SAMPLES as f64;
                    let (x, y) = (
                        pts[a].0 + u * (pts[b].0 - pts[a].0),
                        pts[a].1 + u * (pts[b].1 - pts[a].1),
                    );
                    sum += dof * ds * (described_at(dp, dr, x, y) - profile(ta + u * (tb - ta))).powi(2);
                }
            }
        }
    }
    sum
}
