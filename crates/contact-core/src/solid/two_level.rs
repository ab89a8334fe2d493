//! The two-level estimate of a solid's contact answer: the same scene
//! solved on a companion whose every element is `ratio` times as large (a
//! generated box with its grading's `h_min`, growth and far-field size
//! doubled), compared with the answer on the candidate face set and
//! Richardson-scaled, as the 2D estimate is (`solution::two_level`, whose
//! dimension-free parts it calls: `relative_l2`, `peak_deviation`,
//! `richardson`, `resultant`).
//!
//! **Transfer.** Both meshes mesh the same box, so their candidate surfaces
//! are the same faces of it: each level's pressure is read at the other's
//! points by interpolating its corner pressures linearly over the face that
//! holds the point (the field the rows describe, Σ p_i Φ_i with Φ_i the
//! corner hats, `report`'s module doc; on T10 too, whose rows sit on the
//! corners). Faces are found through a uniform grid of their bounding
//! boxes.
//!
//! **Orders.** The pressure's L2 difference is scaled for q = 1
//! (2^q − 1 = 1 against the coarser companion): it sits at the patch's
//! edge, where a row's pressure is a mean over faces the edge crosses, not
//! the square root's value there, a ring of width h whose error does not
//! fall with h, so its L2 norm falls like h, not h². On Hertz's ball the
//! rounds of `settings.accuracy` measured their two-level differences
//! falling like h^0.70, h^0.83, h^1.06 (T4, h_min 0.17 to 0.066 a), the
//! effectivity table's T4 levels h^0.78 and h^1.30: scaled for q = 2, an
//! error falling like h would be read a third of itself once asymptotic.
//! 2D keeps q = 2 with its own terms for the zone ends' nodes
//! (`solution::two_level`), which a 3D patch's ring has not. The peak,
//! at the patch's smooth interior maximum, keeps q = 2 (2^q − 1 = 3), as the
//! resultant does. The contact area, counted from the rows' tributary
//! areas, is off by the width of that ring too (q = 1), and is given at
//! least half of it. `contact-verify`'s `solid_effectivity` example
//! measures what these give against Hertz and a finer solve
//! (docs/verification/accuracy.md, "A solid in 3D").
//!
//! Pure: the answer's and the companion's `Surface`s in, the estimate out
//! (nondimensional and relative, so the scales do not enter).

use super::obstacle::ObstacleRows;
use super::signorini::Contact;
use super::SolidBody;
use crate::error::CoreError;
use crate::solution::two_level::{near_peak, peak_deviation, relative_l2, resultant, richardson};

/// The order of the pressure's L2 error (module doc); the rounds size
/// their steps by it (`adapt::solid`).
pub const PRESSURE_ORDER: f64 = 1.0;
/// The order of the peak's and the resultant's error (module doc).
const PEAK_ORDER: f64 = 2.0;
/// The order of the contact area's error (module doc).
const AREA_ORDER: f64 = 1.0;
/// How far outside a face (in barycentric terms) a point may lie and still
/// read that face: round-off between two meshes of the same box face.
const INSIDE: f64 = 1e-9;

/// One level's candidate surface as the estimate reads it.
#[derive(Debug, Clone)]
pub struct Surface {
    /// Each row's node position.
    pub points: Vec<[f64; 3]>,
    /// Each row's pressure λ_i / a_i.
    pub pressure: Vec<f64>,
    /// Each row's area a_i.
    pub weight: Vec<f64>,
    /// The face set's faces, by the rows of their corners.
    pub faces: Vec<[usize; 3]>,
    /// The contact force on the body.
    pub force: [f64; 3],
}

impl Surface {
    /// The surface of `contact`, solved on `rows` for `body`.
    pub fn of(body: &SolidBody, rows: &ObstacleRows, contact: &Contact, force: [f64; 3]) -> Result<Self, CoreError> {
        let set = body.face_set(&rows.faces, "contact/faces")?;
        let row_of: std::collections::HashMap<usize, usize> =
            rows.nodes.iter().enumerate().map(|(i, &v)| (v, i)).collect();
        Ok(Surface {
            points: rows.nodes.iter().map(|&v| body.mesh.nodes[v]).collect(),
            pressure: contact.pressure.clone(),
            weight: rows.area.clone(),
            faces: set.iter().map(|f| f.corners.map(|v| row_of[&v])).collect(),
            force,
        })
    }

    /// Σ a_i over the rows that press: the patches' tributary area.
    pub fn contact_area(&self) -> f64 {
        self.weight
            .iter()
            .zip(&self.pressure)
            .filter(|(_, &p)| p > 0.0)
            .map(|(w, _)| w)
            .sum()
    }

    /// Σ of the areas of the faces whose corners all press: the patches'
    /// inner bound (`report`'s `area`, with flat faces: a box's are).
    fn pressed_faces_area(&self) -> f64 {
        self.faces
            .iter()
            .filter(|f| f.iter().all(|&r| self.pressure[r] > 0.0))
            .map(|f| {
                let [a, b, c] = f.map(|r| self.points[r]);
                let (u, v) = (sub(b, a), sub(c, a));
                let n = crate::mesh3d::cross(u, v);
                0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
            })
            .sum()
    }

    /// The largest point pressure.
    pub fn peak(&self) -> f64 {
        self.pressure.iter().copied().fold(0.0, f64::max)
    }

    /// The pressure this surface describes, as a function of a point on the
    /// same geometric surface (module doc, "Transfer").
    pub fn reader(&self) -> impl Fn([f64; 3]) -> f64 + '_ {
        let loc = Locator::new(self);
        move |x| loc.pressure(self, x)
    }

    /// The relative L2 difference of this surface's pressure from
    /// `reference` over its points, weighed as the estimate weighs them
    /// (`solution::two_level::relative_l2`): what a verification compares the
    /// estimate with.
    pub fn relative_l2_against(&self, reference: impl Fn([f64; 3]) -> f64) -> Option<f64> {
        relative_l2((0..self.points.len()).map(|i| (self.weight[i], self.pressure[i], reference(self.points[i]))))
    }
}

/// The estimated relative errors of a solid's answer (None: not estimated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Of the pressure, in the L2 norm over the candidate face set.
    pub pressure_l2: Option<f64>,
    /// Of the largest point pressure.
    pub peak: Option<f64>,
    /// Of the contact force's magnitude.
    pub resultant: Option<f64>,
    /// Of the contact area (Σ of the patches' tributary areas).
    pub contact_area: Option<f64>,
}

/// The estimate of `answer`'s error from `other`, the same scene with every
/// element `ratio` times as large (module doc). As in 2D against a coarser
/// companion, the L2 and peak differences are taken both ways (at each
/// level's points, the other read there) and the larger kept.
pub fn two_level(answer: &Surface, other: &Surface, ratio: f64) -> Estimate {
    let scale = richardson(ratio, PEAK_ORDER);
    let (to_other, to_answer) = (Locator::new(other), Locator::new(answer));
    let at = |s: &Surface, loc: &Locator, from: &Surface| -> Vec<f64> {
        s.points.iter().map(|x| loc.pressure(from, *x)).collect()
    };
    let (o_at_a, a_at_o) = (at(answer, &to_other, other), at(other, &to_answer, answer));
    let samples = |s: &Surface, read: &[f64]| -> Vec<(f64, f64, f64)> {
        (0..s.points.len())
            .map(|i| (s.weight[i], s.pressure[i], read[i]))
            .collect()
    };
    let (sa, so) = (samples(answer, &o_at_a), samples(other, &a_at_o));
    let l2 = match (relative_l2(sa.iter().copied()), relative_l2(so.iter().copied())) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    };
    let (pa, po) = (answer.peak(), other.peak());
    let peak = (pa > 0.0 && po > 0.0).then(|| {
        let near =
            |v: &[(f64, f64, f64)], top: f64| peak_deviation(v.iter().copied().filter(|s| near_peak(s.1, top)), top);
        near(&sa, pa).max(near(&so, po)) / pa / scale
    });
    let norm = |f: [f64; 3]| f.iter().map(|c| c * c).sum::<f64>().sqrt();
    let fa = norm(answer.force);
    let df = norm(std::array::from_fn(|c| answer.force[c] - other.force[c]));
    let (aa, ao) = (answer.contact_area(), other.contact_area());
    // The edge lies somewhere in the ring of faces between the inner bound
    // (faces whose corners all press) and the outer one (the rows' shares):
    // two levels whose pressed rows cover the same squares agree to 0 while
    // both are off by part of that ring (`solid_effectivity`: 0 estimated,
    // 8.6 % off Hertz's area, on T4 at h_min = 0.4 a). Half the ring is the
    // least error the area may be given.
    let ring = 0.5 * (aa - answer.pressed_faces_area()).max(0.0);
    Estimate {
        pressure_l2: l2.map(|v| v / richardson(ratio, PRESSURE_ORDER)),
        peak,
        resultant: (fa > 0.0 && df.is_finite()).then(|| resultant(df / fa, scale)),
        contact_area: (aa > 0.0).then(|| ((aa - ao).abs() / richardson(ratio, AREA_ORDER)).max(ring) / aa),
    }
}

/// The faces of a surface binned by their bounding boxes on a uniform grid,
/// for reading its pressure at a point of the same surface.
struct Locator {
    lo: [f64; 3],
    cell: f64,
    dims: [usize; 3],
    bins: Vec<Vec<usize>>,
}

/// Cells along the grid's longest axis at most: the bins of a graded face
/// set stay few where its faces are small (a box face with h_min = 0.02 of
/// its side would ask for 50 × 50 of its mean size and far more of its
/// smallest).
const MAX_CELLS: f64 = 64.0;

impl Locator {
    fn new(s: &Surface) -> Self {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in &s.points {
            for c in 0..3 {
                lo[c] = lo[c].min(x[c]);
                hi[c] = hi[c].max(x[c]);
            }
        }
        let span = (0..3).map(|c| hi[c] - lo[c]).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        // About √(faces) cells along the longest side: a face set is a
        // surface, so that many cells hold a few faces each when uniform.
        let cell = span / (s.faces.len() as f64).sqrt().clamp(1.0, MAX_CELLS);
        let dims: [usize; 3] = std::array::from_fn(|c| ((hi[c] - lo[c]) / cell).floor() as usize + 1);
        let mut bins = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let index = |x: [f64; 3]| -> [usize; 3] {
            std::array::from_fn(|c| (((x[c] - lo[c]) / cell).max(0.0) as usize).min(dims[c] - 1))
        };
        for (f, corners) in s.faces.iter().enumerate() {
            let (mut a, mut b) = ([usize::MAX; 3], [0; 3]);
            for &r in corners {
                let k = index(s.points[r]);
                for c in 0..3 {
                    a[c] = a[c].min(k[c]);
                    b[c] = b[c].max(k[c]);
                }
            }
            for i in a[0]..=b[0] {
                for j in a[1]..=b[1] {
                    for k in a[2]..=b[2] {
                        bins[(i * dims[1] + j) * dims[2] + k].push(f);
                    }
                }
            }
        }
        Locator { lo, cell, dims, bins }
    }

    /// The pressure of `s` at `x`: linear over the face that holds x's
    /// projection best (its smallest barycentric coordinate the largest),
    /// searched in x's cell and its neighbours, then over every face should
    /// none hold it (a point off the surface reads its nearest face's
    /// extrapolation, clamped at 0).
    fn pressure(&self, s: &Surface, x: [f64; 3]) -> f64 {
        let k: [usize; 3] =
            std::array::from_fn(|c| (((x[c] - self.lo[c]) / self.cell).max(0.0) as usize).min(self.dims[c] - 1));
        let mut best: Option<(f64, [f64; 3], usize)> = None;
        let consider = |best: &mut Option<(f64, [f64; 3], usize)>, f: usize| {
            if let Some(l) = barycentric(s, f, x) {
                let m = l[0].min(l[1]).min(l[2]);
                if best.is_none_or(|b| m > b.0) {
                    *best = Some((m, l, f));
                }
            }
        };
        let near = |c: usize| k[c].saturating_sub(1)..=(k[c] + 1).min(self.dims[c] - 1);
        for i in near(0) {
            for j in near(1) {
                for l in near(2) {
                    self.bins[(i * self.dims[1] + j) * self.dims[2] + l]
                        .iter()
                        .for_each(|&f| consider(&mut best, f));
                }
            }
        }
        if best.is_none_or(|b| b.0 < -INSIDE) {
            (0..s.faces.len()).for_each(|f| consider(&mut best, f));
        }
        let Some((_, l, f)) = best else { return 0.0 };
        let r = s.faces[f];
        (0..3).map(|c| l[c] * s.pressure[r[c]]).sum::<f64>().max(0.0)
    }
}

fn sub(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| p[k] - q[k])
}

/// The barycentric coordinates of x's projection on face `f`'s plane, or
/// None for a degenerate face.
fn barycentric(s: &Surface, f: usize, x: [f64; 3]) -> Option<[f64; 3]> {
    let [a, b, c] = s.faces[f].map(|r| s.points[r]);
    let dot = |p: [f64; 3], q: [f64; 3]| (0..3).map(|k| p[k] * q[k]).sum::<f64>();
    let (e0, e1, d) = (sub(b, a), sub(c, a), sub(x, a));
    let (d00, d01, d11) = (dot(e0, e0), dot(e0, e1), dot(e1, e1));
    let det = d00 * d11 - d01 * d01;
    if det <= 0.0 {
        return None;
    }
    let (d20, d21) = (dot(d, e0), dot(d, e1));
    let v = (d11 * d20 - d01 * d21) / det;
    let w = (d00 * d21 - d01 * d20) / det;
    Some([1.0 - v - w, v, w])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square of two triangles at z = 0, its corners' pressures
    /// given.
    fn square(p: [f64; 4], force: f64) -> Surface {
        Surface {
            points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            pressure: p.to_vec(),
            weight: vec![0.25; 4],
            faces: vec![[0, 1, 2], [0, 2, 3]],
            force: [0.0, 0.0, force],
        }
    }

    #[test]
    fn a_linear_field_is_read_exactly_between_meshes() {
        // p = 1 + x + 2y at the corners of the square; read at an inner point
        // of either triangle it is the plane's value (to round-off).
        let s = square([1.0, 2.0, 4.0, 3.0], 1.0);
        let loc = Locator::new(&s);
        for x in [[0.3, 0.1, 0.0], [0.2, 0.7, 0.0], [1.0, 1.0, 0.0]] {
            let want = 1.0 + x[0] + 2.0 * x[1];
            assert!((loc.pressure(&s, x) - want).abs() < 1e-14, "{x:?}");
        }
    }

    #[test]
    fn equal_levels_estimate_nothing_and_a_scaled_one_its_richardson_share() {
        let a = square([1.0, 2.0, 4.0, 3.0], 1.0);
        let e = two_level(&a, &a, 2.0);
        assert_eq!(e.pressure_l2, Some(0.0));
        assert_eq!(e.peak, Some(0.0));
        assert_eq!(e.contact_area, Some(0.0));
        // A companion 3 % higher everywhere: the relative difference is
        // 0.03 / 1.03 both ways (of the larger), over 2¹ − 1 = 1.
        let b = square([1.03, 2.06, 4.12, 3.09], 1.03);
        let e = two_level(&a, &b, 2.0);
        let want = 0.03 / 1.03;
        assert!((e.pressure_l2.unwrap() - want).abs() < 1e-12, "{e:?}");
        // The resultant's: 0.03 of the answer's, over 3.
        assert!((e.resultant.unwrap() - 0.01).abs() < 1e-12, "{e:?}");
        // The peak: at the peak point, |4.12 − 4| of 4, over 3.
        assert!((e.peak.unwrap() - 0.12 / 4.0 / 3.0).abs() < 1e-12, "{e:?}");
    }
}
