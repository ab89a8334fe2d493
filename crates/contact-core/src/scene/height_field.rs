//! A rigid obstacle given as a table of heights: the surface s = h(ξ, η)
//! over a regular grid in a frame (origin o, unit normal n toward the body,
//! unit e₁ ⊥ n along the grid's rows, e₂ = n × e₁), with
//! (ξ, η, s) = ((x − o)·e₁, (x − o)·e₂, (x − o)·n): a worn or measured
//! surface, a roller's crowned profile, a groove that is no body of
//! revolution. The obstacle lies on the side s < h.
//!
//! h is the tensor product of cubic Hermite pieces whose slopes are the
//! grid's central differences, three-point one-sided at the grid's edges
//! (Catmull–Rom): C¹, so the normal turns continuously and the rows'
//! linearization along it holds, and exact on every quadratic of ξ and of
//! η (both differences are exact on quadratics), so a field sampled from
//! Hertz's paraboloid is that paraboloid to round-off. The distance is the
//! paraboloid's construction: φ = s − h(ξ, η) over the length of
//! ∇φ = n − h_ξ e₁ − h_η e₂, with the same zero set as the distance and, on
//! it, the exact normal (`solid_obstacle`). A point outside the grid's
//! extent has no height: it has no distance either (`closest` gives None).

/// The table and its frame, in the scene's nondimensional lengths.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightField {
    pub origin: [f64; 3],
    /// Unit, out of the obstacle toward the body.
    pub normal: [f64; 3],
    /// Unit, orthogonal to `normal`: the direction of a row of the table.
    pub e1: [f64; 3],
    /// Grid spacing along e₁ and e₂.
    pub spacing: [f64; 2],
    /// Points along e₁ (a row's length) and along e₂ (the rows), each ≥ 2.
    pub counts: [usize; 2],
    /// Row by row: the height at (ξ, η) = (i d₁, j d₂) is `heights[j * counts[0] + i]`.
    pub heights: Vec<f64>,
}

/// The weights of the grid values in a 1D Catmull–Rom piece and in its
/// derivative per spacing: (index, weight, derivative weight), at most six.
type Weights = [(usize, f64, f64); 6];

/// The slope at grid index k (per spacing) as weights of the values: the
/// central difference, or the three-point one-sided one at an end (two
/// points: their difference).
fn slope(k: usize, n: usize) -> [(usize, f64); 3] {
    match (k, n) {
        (_, 2) => [(0, -1.0), (1, 1.0), (1, 0.0)],
        (0, _) => [(0, -1.5), (1, 2.0), (2, -0.5)],
        (k, n) if k == n - 1 => [(k, 1.5), (k - 1, -2.0), (k - 2, 0.5)],
        (k, _) => [(k - 1, -0.5), (k + 1, 0.5), (k, 0.0)],
    }
}

/// The piece holding t = position / spacing and its weights; None outside
/// [0, n − 1] beyond round-off.
fn weights(t: f64, n: usize) -> Option<Weights> {
    let last = (n - 1) as f64;
    if !(t >= -1e-9 && t <= last + 1e-9 * last.max(1.0)) {
        return None;
    }
    let t = t.clamp(0.0, last);
    let i = (t.floor() as usize).min(n - 2);
    let u = t - i as f64;
    // The Hermite basis (value i, slope i, value i+1, slope i+1) and its derivative.
    let (u2, u3) = (u * u, u * u * u);
    let h = [
        2.0 * u3 - 3.0 * u2 + 1.0,
        u3 - 2.0 * u2 + u,
        -2.0 * u3 + 3.0 * u2,
        u3 - u2,
    ];
    let dh = [
        6.0 * u2 - 6.0 * u,
        3.0 * u2 - 4.0 * u + 1.0,
        -6.0 * u2 + 6.0 * u,
        3.0 * u2 - 2.0 * u,
    ];
    let mut out: Weights = [(0, 0.0, 0.0); 6];
    let mut len = 0;
    let mut add = |idx: usize, w: f64, dw: f64| match out[..len].iter_mut().find(|e| e.0 == idx) {
        Some(e) => {
            e.1 += w;
            e.2 += dw;
        }
        None => {
            out[len] = (idx, w, dw);
            len += 1;
        }
    };
    add(i, h[0], dh[0]);
    add(i + 1, h[2], dh[2]);
    for (k, b) in [(i, 1), (i + 1, 3)] {
        for (idx, c) in slope(k, n) {
            add(idx, h[b] * c, dh[b] * c);
        }
    }
    Some(out)
}

impl HeightField {
    /// h, ∂h/∂ξ and ∂h/∂η at (ξ, η); None outside the grid.
    pub fn height(&self, xi: f64, eta: f64) -> Option<(f64, f64, f64)> {
        let [n1, n2] = self.counts;
        let a = weights(xi / self.spacing[0], n1)?;
        let b = weights(eta / self.spacing[1], n2)?;
        let (mut h, mut hx, mut hy) = (0.0, 0.0, 0.0);
        for &(j, wb, dwb) in &b {
            let row = &self.heights[j * n1..(j + 1) * n1];
            let (mut v, mut dv) = (0.0, 0.0);
            for &(i, wa, dwa) in &a {
                v += wa * row[i];
                dv += dwa * row[i];
            }
            h += wb * v;
            hx += wb * dv;
            hy += dwb * v;
        }
        Some((h, hx / self.spacing[0], hy / self.spacing[1]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(counts: [usize; 2], spacing: [f64; 2], f: impl Fn(f64, f64) -> f64) -> HeightField {
        let mut heights = Vec::new();
        for j in 0..counts[1] {
            for i in 0..counts[0] {
                heights.push(f(i as f64 * spacing[0], j as f64 * spacing[1]));
            }
        }
        HeightField {
            origin: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
            e1: [1.0, 0.0, 0.0],
            spacing,
            counts,
            heights,
        }
    }

    /// A quadratic in ξ and η (Hertz's paraboloid, shifted and tilted) is
    /// reproduced with its slopes to round-off everywhere on the grid, the
    /// edge pieces included: both differences are exact on quadratics. On
    /// a grid of 2 points a line is.
    #[test]
    fn quadratics_are_reproduced_exactly() {
        let q = |x: f64, y: f64| 0.3 - 0.1 * x + 0.05 * y - x * x / 16.0 - (y - 1.0) * (y - 1.0) / 8.0;
        let f = table([7, 5], [0.5, 0.75], q);
        for &(x, y) in &[
            (0.0, 0.0),
            (0.1, 0.2),
            (1.3, 2.9),
            (2.999, 0.01),
            (3.0, 3.0),
            (1.75, 1.5),
        ] {
            let (h, hx, hy) = f.height(x, y).expect("on the grid");
            let (dx, dy) = (-0.1 - x / 8.0, 0.05 - (y - 1.0) / 4.0);
            assert!((h - q(x, y)).abs() < 1e-14, "h at ({x}, {y})");
            assert!(
                (hx - dx).abs() < 1e-13 && (hy - dy).abs() < 1e-13,
                "slopes at ({x}, {y})"
            );
        }
        let line = table([2, 2], [1.0, 2.0], |x, y| 1.0 + 2.0 * x - y);
        let (h, hx, hy) = line.height(0.25, 1.5).unwrap();
        assert!((h - (1.0 + 0.5 - 1.5)).abs() < 1e-15 && (hx - 2.0).abs() < 1e-15 && (hy + 1.0).abs() < 1e-15);
    }

    /// The slopes are continuous across the pieces' edges (C¹: the normal
    /// turns continuously), on a table that is no polynomial; off the grid
    /// there is no height.
    #[test]
    fn slopes_are_continuous_and_the_grid_bounds_the_field() {
        let f = table([6, 6], [1.0, 1.0], |x, y| {
            (1.3 * x).sin() * (0.7 * y).cos() + 0.1 * x * y
        });
        for (x, y) in [(2.0, 1.3), (1.4, 3.0), (4.0, 4.0)] {
            let e = 1e-9;
            let (a, b) = (f.height(x - e, y - e).unwrap(), f.height(x + e, y + e).unwrap());
            assert!(
                (a.1 - b.1).abs() < 1e-7 && (a.2 - b.2).abs() < 1e-7,
                "at ({x}, {y}): {a:?} {b:?}"
            );
        }
        assert!(f.height(-0.01, 1.0).is_none() && f.height(1.0, 5.01).is_none());
        assert!(f.height(5.0, 0.0).is_some());
    }
}
