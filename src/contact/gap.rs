//! Initial gap s(x) from a body point to a rigid obstacle, measured along the
//! body's outward normal n: the smallest t with x + t n on the obstacle surface
//! entering the obstacle. Negative t means the point starts inside (initial
//! penetration). `None`: the ray never meets the obstacle, so under the
//! linearized (small displacement) condition the point cannot touch it.

use crate::scene::Shape;

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
