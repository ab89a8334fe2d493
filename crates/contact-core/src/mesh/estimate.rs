//! Node counts of the generated meshes, predicted from their parameters
//! without meshing, for the size limit (a request must be refused before its
//! mesh is built, however small its `h_min`).
//!
//! A graded mesh has about one node per area (√3/2)·h² of an equilateral
//! triangle of the local size h(x), plus a share of its boundary nodes, one per
//! length h: V ≈ ∫ dA / (C_AREA h²) + C_BOUNDARY ∫ ds / h, both integrals
//! taken numerically about the focus. The constants are fitted to the
//! generators' real counts (see the test: within ±10 % from 2k to 600k nodes).

use super::generate::{size_at, Grading};

/// Area per node in units of h², where the seeded rings set the spacing;
/// fitted (least squares on the test's 25 T3 meshes: 1.000).
const C_AREA: f64 = 1.0;
/// Area per node where the size is the nominal one, in units of size²: there
/// refinement alone places the nodes, under its area bound; fitted (0.578,
/// i.e. 1/√3: twice the density of an equilateral lattice at that size).
const C_UNIFORM: f64 = 0.577;
/// Boundary nodes counted on top of the area term; fitted (0.926).
const C_BOUNDARY: f64 = 0.93;

/// A generated mesh's shape, in coordinates local to it.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// [0, w] × [0, h]; graded toward `focus` (relative to the corner) if any.
    Rectangle { w: f64, h: f64 },
    /// Half-disk of radius r (or its quarter), graded toward the apex.
    Disk { r: f64, quarter: bool },
}

/// Predicted node count (corner and midside nodes for T6).
pub fn nodes(shape: Shape, size: f64, grading: Option<([f64; 2], Grading)>, t6: bool) -> f64 {
    let corners = match (shape, grading) {
        (Shape::Rectangle { w, h }, None) => {
            // The structured grid: exact.
            let (nx, ny) = ((w / size).ceil().max(1.0), (h / size).ceil().max(1.0));
            return if t6 {
                (2.0 * nx + 1.0) * (2.0 * ny + 1.0)
            } else {
                (nx + 1.0) * (ny + 1.0)
            };
        }
        _ => graded(shape, size, grading),
    };
    if t6 {
        // A triangulation with V vertices, B of them on the boundary, has
        // 3V − B − 3 edges, each with a midside node.
        let (v, b) = corners;
        4.0 * v - b - 3.0
    } else {
        corners.0
    }
}

/// (vertices, boundary vertices) of a graded Delaunay mesh.
fn graded(shape: Shape, size: f64, grading: Option<([f64; 2], Grading)>) -> (f64, f64) {
    let (focus, g) = match (shape, grading) {
        (_, Some(fg)) => fg,
        (Shape::Disk { r, .. }, None) => (
            [0.0, -r],
            Grading {
                h_min: size,
                ratio: 1.0,
                extent: 0.0,
            },
        ),
        (Shape::Rectangle { .. }, None) => unreachable!("uniform rectangles are counted exactly"),
    };
    let h = |p: [f64; 2]| size_at(((p[0] - focus[0]).powi(2) + (p[1] - focus[1]).powi(2)).sqrt(), g, size);
    // Boundary sides as (start, end, is_arc) in local coordinates.
    type Inside = Box<dyn Fn([f64; 2]) -> bool>;
    let (inside, sides, reach): (Inside, Vec<Side>, f64) = match shape {
        Shape::Rectangle { w, h: ht } => {
            let c = [[0.0, 0.0], [w, 0.0], [w, ht], [0.0, ht]];
            let reach = c
                .iter()
                .map(|q| ((q[0] - focus[0]).powi(2) + (q[1] - focus[1]).powi(2)).sqrt())
                .fold(0.0, f64::max);
            (
                Box::new(move |p| p[0] >= 0.0 && p[0] <= w && p[1] >= 0.0 && p[1] <= ht),
                (0..4).map(|k| Side::Line(c[k], c[(k + 1) % 4])).collect(),
                reach,
            )
        }
        Shape::Disk { r, quarter } => {
            let lo = if quarter { 0.0 } else { -r };
            let mut sides = vec![
                Side::Arc {
                    r,
                    from: if quarter { -0.5 } else { -1.0 },
                    to: 0.0,
                },
                Side::Line([lo, 0.0], [r, 0.0]),
            ];
            if quarter {
                sides.push(Side::Line([0.0, -r], [0.0, 0.0]));
            }
            (
                Box::new(move |p| p[1] <= 0.0 && p[0] >= lo && p[0] * p[0] + p[1] * p[1] <= r * r),
                sides,
                2.0 * r,
            )
        }
    };
    let boundary: f64 = sides.iter().map(|s| s.count(&h)).sum();
    let area = area_count(
        &*inside,
        focus,
        &|d| size_at(d, g, size),
        reach,
        g.extent,
        g.ratio - 1.0,
    );
    (area[0] / C_AREA + area[1] / C_UNIFORM + C_BOUNDARY * boundary, boundary)
}

enum Side {
    Line([f64; 2], [f64; 2]),
    /// Arc of the circle of radius r about the origin, angles from·π to to·π.
    Arc {
        r: f64,
        from: f64,
        to: f64,
    },
}

impl Side {
    /// ∫ ds / h along the side, marched at half the local h (at most 10⁴
    /// steps: where h is finer than that, the area term dominates the count).
    fn count(&self, h: &dyn Fn([f64; 2]) -> f64) -> f64 {
        let (at, len): (Box<dyn Fn(f64) -> [f64; 2]>, f64) = match *self {
            Side::Line(a, b) => (
                Box::new(move |t| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]),
                ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt(),
            ),
            Side::Arc { r, from, to } => {
                let pi = std::f64::consts::PI;
                (
                    Box::new(move |t| {
                        let th = pi * (from + t * (to - from));
                        [r * th.cos(), r * th.sin()]
                    }),
                    r * pi * (to - from),
                )
            }
        };
        let (mut s, mut n) = (0.0, 0.0);
        while s < len {
            let step = (0.5 * h(at(s / len))).max(1e-4 * len).min(len - s);
            n += step / h(at((s + 0.5 * step) / len));
            s += step;
        }
        n
    }
}

/// ∫ dA / h² over the region, in polar coordinates about the focus: the
/// angular measure of each circle inside the region, sampled, times ρ / h(ρ)².
fn area_count(
    inside: &dyn Fn([f64; 2]) -> bool,
    focus: [f64; 2],
    h: &dyn Fn(f64) -> f64,
    reach: f64,
    extent: f64,
    growth: f64,
) -> [f64; 2] {
    const ANGLES: usize = 360;
    const STEPS: usize = 200;
    let arc = |rho: f64| {
        let hits = (0..ANGLES)
            .filter(|&j| {
                let t = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / ANGLES as f64;
                inside([focus[0] + rho * t.cos(), focus[1] + rho * t.sin()])
            })
            .count();
        2.0 * std::f64::consts::PI * hits as f64 / ANGLES as f64
    };
    // The uniform core (h = h_min), the graded ring where h grows linearly
    // (integrated in ln h, so that a tiny h_min is resolved), and the rest at
    // the nominal size.
    let mut total = [0.0; 2];
    let h_max = h(f64::INFINITY) * (1.0 - 1e-12);
    let midpoints = |a: f64, b: f64, total: &mut [f64; 2]| {
        let b = b.min(reach);
        if b > a {
            let d = (b - a) / STEPS as f64;
            for i in 0..STEPS {
                let rho = a + (i as f64 + 0.5) * d;
                let hr = h(rho);
                total[usize::from(hr >= h_max)] += arc(rho) * rho / hr.powi(2) * d;
            }
        }
    };
    let (h0, h1) = (h(0.0), h(reach));
    let core = extent.min(reach);
    midpoints(0.0, core, &mut total);
    let slope = growth;
    if slope > 0.0 && h1 > h0 * (1.0 + 1e-12) {
        let (u0, u1) = (h0.ln(), h(f64::INFINITY).ln());
        let du = (u1 - u0) / STEPS as f64;
        let mut end = core;
        for i in 0..STEPS {
            let hu = (u0 + (i as f64 + 0.5) * du).exp();
            let rho = core + (hu - h0) / slope;
            if rho > reach {
                break;
            }
            // dρ = h du / slope.
            total[usize::from(hu >= h_max)] += arc(rho) * rho / (hu * slope) * du;
            end = core + ((u0 + (i as f64 + 1.0) * du).exp() - h0) / slope;
        }
        midpoints(end, reach, &mut total);
    } else {
        midpoints(core, reach, &mut total);
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{disk, rectangle, DiskPart};
    use crate::mesh::Order;

    fn g(h_min: f64, ratio: f64, extent: f64) -> Grading {
        Grading { h_min, ratio, extent }
    }

    /// The estimate against the generators' real counts, T3 and T6, on the
    /// shapes and gradings of the benches and examples.
    #[test]
    fn estimates_are_within_ten_percent_of_the_real_counts() {
        let mut worst: f64 = 0.0;
        let mut rows = Vec::new();
        for (order, t6) in [(Order::T3, false), (Order::T6, true)] {
            for &(h_min, ratio, extent, size) in &[
                (0.004, 1.1, 0.1, 0.1),
                (0.002, 1.05, 0.1, 0.1),
                (0.01, 1.2, 0.05, 0.2),
                (0.001, 1.1, 0.105, 0.05),
                (0.05, 1.0, 0.0, 0.05),
            ] {
                let gr = g(h_min, ratio, extent);
                for quarter in [false, true] {
                    let part = if quarter { DiskPart::Quarter } else { DiskPart::Half };
                    let real = disk([0.0, 1.0], 1.0, true, part, size, Some(gr), order)
                        .unwrap()
                        .nodes
                        .len() as f64;
                    let est = nodes(Shape::Disk { r: 1.0, quarter }, size, Some(([0.0, -1.0], gr)), t6);
                    rows.push(format!(
                        "disk q={quarter} t6={t6} {h_min} {ratio}: real {real} est {est:.0}"
                    ));
                    worst = worst.max((est / real - 1.0).abs());
                }
                for (w, h, f) in [(2.0, 1.0, [1.0, 1.0]), (2.0, 1.0, [0.5, 1.0]), (1.0, 0.5, [0.5, 0.25])] {
                    let real = rectangle([0.0, 0.0], w, h, size, Some((f, gr)), order)
                        .unwrap()
                        .nodes
                        .len() as f64;
                    let est = nodes(Shape::Rectangle { w, h }, size, Some((f, gr)), t6);
                    rows.push(format!(
                        "rect {w}x{h} f={f:?} t6={t6} {h_min} {ratio}: real {real} est {est:.0}"
                    ));
                    worst = worst.max((est / real - 1.0).abs());
                }
            }
            let real = rectangle([0.0, 0.0], 2.0, 1.0, 0.03, None, order).unwrap().nodes.len() as f64;
            let est = nodes(Shape::Rectangle { w: 2.0, h: 1.0 }, 0.03, None, t6);
            assert_eq!(real, est, "a uniform rectangle is counted exactly");
        }
        eprintln!("{}", rows.join("\n"));
        eprintln!("worst {worst:.3}");
        assert!(worst <= 0.10, "worst relative error {worst:.3}");
    }
}
