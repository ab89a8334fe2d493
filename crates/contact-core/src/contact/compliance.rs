//! The compliance of tensionless deformable foundations under a body:
//! Winkler, Pasternak and the elastic half-plane (the rows that rest on them
//! are `targets::foundation`).
//!
//! A body node x on a pair's edge set with outward normal n (facing down) may
//! not pass the deflected foundation surface y0 − w:
//!
//! ```text
//! n · u − (−n_y) w ≤ s,   s = (y0 − y) / n_y  (the gap along n)
//! ```
//!
//! with n = (0, −1) and s = y − y0 under the default signed distance (the
//! height above the flat foundation surface: exact), n the body's outward
//! normal under `settings.gap = body_normal`.
//!
//! The foundation carries the row's force λ projected on the vertical,
//! (−n_y) λ, spread over the row's panel (its node's share of the edge set,
//! projected on x: the panels tile the body's footprint), so its deflection is
//! linear in λ and the condensed operator gains the foundation's compliance:
//! W = B K⁻¹ Bᵀ + D F D, D = diag(−n_y). Tension is impossible because λ ≥ 0.
//!
//! - Winkler: F = diag(1 / (k h_i)), h_i the panel length.
//! - Pasternak: a 1D finite-element layer along the whole foundation (the
//!   body's panels plus graded cells out to x_min and x_max, free ends):
//!   K_f = diag(k cell_i) + μ-stiffness of linear elements; F = K_f⁻¹ on the
//!   rows' nodes. μ = 0 is Winkler exactly.
//! - Half-plane: piecewise-constant pressure on the panels, the Flamant kernel
//!   (2/(π E*)) ln(d/|x − t|) integrated exactly over both panels (its
//!   singularity included) and divided by both lengths: the Galerkin (mean over
//!   the panel) deflection, which keeps F symmetric. It is positive definite when
//!   d exceeds a quarter of the loaded length (the logarithmic capacity).

use faer::Mat;

use super::constraints::ConstraintSet;
use crate::error::{CoreError, InvalidKind};
use crate::scene::{FoundationModel, Scene};

/// One foundation's discretization, built from the rows that rest on it.
struct Line {
    foundation: usize,
    /// Candidate indices on this foundation.
    rows: Vec<usize>,
    kind: LineKind,
}

enum LineKind {
    Winkler {
        k: f64,
    },
    /// Layer nodes, their cells' lengths, the rows' node indices, and K_f as a
    /// symmetric tridiagonal (diagonal, off-diagonal).
    Pasternak {
        x: Vec<f64>,
        node_of_row: Vec<usize>,
        diag: Vec<f64>,
        off: Vec<f64>,
    },
    HalfPlane {
        e_star: f64,
        d: f64,
    },
}

/// The foundations of a scene with rows on them.
pub struct Foundations {
    lines: Vec<Line>,
    /// Panels are annuli of a body of revolution (x = r).
    axisymmetric: bool,
}

impl Foundations {
    pub fn try_new(scene: &Scene, cons: &ConstraintSet) -> Result<Self, CoreError> {
        let mut lines = Vec::new();
        for (f, fnd) in scene.foundations.iter().enumerate() {
            let mut rows: Vec<usize> = (0..cons.len())
                .filter(|&i| cons.candidates[i].foundation().is_some_and(|r| r.foundation == f))
                .collect();
            if rows.is_empty() {
                continue;
            }
            let panel = |i: usize| cons.candidates[i].foundation().expect("foundation row").panel;
            rows.sort_by(|&a, &b| panel(a)[0].total_cmp(&panel(b)[0]));
            let kind = match fnd.model {
                FoundationModel::Winkler { k } => LineKind::Winkler { k },
                FoundationModel::Pasternak { k, mu } => {
                    let panels: Vec<[f64; 2]> = rows.iter().map(|&i| panel(i)).collect();
                    let centres: Vec<f64> = rows.iter().map(|&i| cons.candidates[i].x[0]).collect();
                    // In axisymmetry a row's springs act on its ring area (as for Winkler).
                    let ring_areas: Option<Vec<f64>> = (scene.analysis == crate::scene::Analysis::Axisymmetric)
                        .then(|| rows.iter().map(|&i| ring_area(cons, i)).collect());
                    layer(fnd.x_min, fnd.x_max, &panels, &centres, ring_areas.as_deref(), k, mu)
                }
                FoundationModel::HalfPlane { e_star, d } => {
                    let (lo, hi) = (
                        panel(rows[0])[0],
                        rows.iter().map(|&i| panel(i)[1]).fold(f64::MIN, f64::max),
                    );
                    if d <= 0.25 * (hi - lo) {
                        return Err(CoreError::invalid(
                            InvalidKind::Geometry,
                            format!("/foundations/{f}/model/half_plane/reference_distance"),
                            format!(
                                "the reference distance {:.6e} must exceed a quarter of the length the body can load \
                                    ({:.6e}); otherwise the half-plane's compliance is not positive definite",
                                scene.scales.length(d),
                                scene.scales.length(0.25 * (hi - lo))
                            ),
                        ));
                    }
                    LineKind::HalfPlane { e_star, d }
                }
            };
            lines.push(Line {
                foundation: f,
                rows,
                kind,
            });
        }
        Ok(Self {
            lines,
            axisymmetric: scene.analysis == crate::scene::Analysis::Axisymmetric,
        })
    }

    pub fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    /// What a Winkler row's springs spread its force over: its panel's
    /// length, or in axisymmetry its ring area ∫ N_i 2πr ds projected on the
    /// foundation (the row's own weight, so that a uniform pressure gives a
    /// uniform deflection also at the axis, where the panel's annulus
    /// π (h/2)² would miss the hat's π h²/3).
    fn spring_area(&self, cons: &ConstraintSet, i: usize) -> f64 {
        if self.axisymmetric {
            ring_area(cons, i)
        } else {
            let p = cons.candidates[i].foundation().expect("foundation row").panel;
            p[1] - p[0]
        }
    }

    /// D F D over all candidates (m × m), in the rows' force units.
    pub fn compliance(&self, cons: &ConstraintSet) -> Mat<f64> {
        let m = cons.len();
        let mut w = Mat::<f64>::zeros(m, m);
        let row = |i: usize| cons.candidates[i].foundation().expect("foundation row");
        for line in &self.lines {
            let r = &line.rows;
            match &line.kind {
                LineKind::Winkler { k } => {
                    for &i in r {
                        let fr = row(i);
                        w[(i, i)] += fr.proj * fr.proj / (k * self.spring_area(cons, i));
                    }
                }
                LineKind::Pasternak {
                    node_of_row, diag, off, ..
                } => {
                    for (a, &i) in r.iter().enumerate() {
                        let mut e = vec![0.0; diag.len()];
                        e[node_of_row[a]] = 1.0;
                        let col = tridiagonal_solve(diag, off, &e);
                        for (b, &j) in r.iter().enumerate() {
                            w[(j, i)] += row(j).proj * row(i).proj * col[node_of_row[b]];
                        }
                    }
                }
                LineKind::HalfPlane { e_star, d } => {
                    let c = 2.0 / (std::f64::consts::PI * e_star);
                    for &i in r {
                        for &j in r {
                            let (pi, pj) = (row(i).panel, row(j).panel);
                            let (hi, hj) = (pi[1] - pi[0], pj[1] - pj[0]);
                            let lnd = hi * hj * d.ln() - log_double_integral(pi, pj);
                            w[(i, j)] += row(i).proj * row(j).proj * c * lnd / (hi * hj);
                        }
                    }
                }
            }
        }
        w
    }

    /// Surface deflection (downward) of every foundation with rows, at points
    /// along its whole length: (foundation, x, w).
    pub fn deflections(&self, scene: &Scene, cons: &ConstraintSet, lambda: &[f64]) -> Vec<(usize, Vec<f64>, Vec<f64>)> {
        let row = |i: usize| cons.candidates[i].foundation().expect("foundation row");
        let load = |i: usize| row(i).proj * lambda[i];
        self.lines
            .iter()
            .map(|line| {
                let fnd = &scene.foundations[line.foundation];
                let (x, w) = match &line.kind {
                    LineKind::Winkler { k } => {
                        // Springs deflect only where loaded: the panels' values, and
                        // zero at the ends of the foundation beyond the body.
                        let mut pts: Vec<(f64, f64)> = line
                            .rows
                            .iter()
                            .map(|&i| (cons.candidates[i].x[0], load(i) / (k * self.spring_area(cons, i))))
                            .collect();
                        let first = row(line.rows[0]).panel[0];
                        let last = line.rows.iter().map(|&i| row(i).panel[1]).fold(f64::MIN, f64::max);
                        if first > fnd.x_min {
                            pts.insert(0, (fnd.x_min, 0.0));
                        }
                        if last < fnd.x_max {
                            pts.push((fnd.x_max, 0.0));
                        }
                        pts.into_iter().unzip()
                    }
                    LineKind::Pasternak {
                        x,
                        node_of_row,
                        diag,
                        off,
                    } => {
                        let mut f = vec![0.0; x.len()];
                        for (a, &i) in line.rows.iter().enumerate() {
                            f[node_of_row[a]] += load(i);
                        }
                        (x.clone(), tridiagonal_solve(diag, off, &f))
                    }
                    LineKind::HalfPlane { e_star, d } => {
                        let c = 2.0 / (std::f64::consts::PI * e_star);
                        let mut xs: Vec<f64> = line.rows.iter().map(|&i| cons.candidates[i].x[0]).collect();
                        let n = 200;
                        xs.extend((0..=n).map(|k| fnd.x_min + (fnd.x_max - fnd.x_min) * k as f64 / n as f64));
                        xs.sort_by(f64::total_cmp);
                        xs.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
                        let w = xs
                            .iter()
                            .map(|&x| {
                                line.rows
                                    .iter()
                                    .map(|&j| {
                                        let p = row(j).panel;
                                        let h = p[1] - p[0];
                                        // Pressure over the panel times ∫ ln(d/|x − t|) dt.
                                        load(j) / h * c * (h * d.ln() + big_f(x - p[1]) - big_f(x - p[0]))
                                    })
                                    .sum()
                            })
                            .collect();
                        (xs, w)
                    }
                };
                (line.foundation, x, w)
            })
            .collect()
    }
}

/// F(s) = s ln|s| − s, with F(0) = 0: −∫ ln|x − t| dt = F(x − b) − F(x − a) over [a, b].
fn big_f(s: f64) -> f64 {
    if s == 0.0 {
        0.0
    } else {
        s * s.abs().ln() - s
    }
}

/// G(s) = s²/2 ln|s| − 3s²/4, G(0) = 0: G' = F.
fn big_g(s: f64) -> f64 {
    if s == 0.0 {
        0.0
    } else {
        0.5 * s * s * s.abs().ln() - 0.75 * s * s
    }
}

/// ∫_{p} ∫_{q} ln|x − t| dt dx, exact (the log singularity is integrable).
fn log_double_integral(p: [f64; 2], q: [f64; 2]) -> f64 {
    // ∫ ln|x − t| dt over q = F(x − q0) − F(x − q1); then ∫ F(x − c) dx = G(x − c).
    (big_g(p[1] - q[0]) - big_g(p[0] - q[0])) - (big_g(p[1] - q[1]) - big_g(p[0] - q[1]))
}

/// A foundation row's ring area on the foundation: ∫ N_i 2πr ds projected
/// on it (`spring_area`).
fn ring_area(cons: &ConstraintSet, i: usize) -> f64 {
    let c = &cons.candidates[i];
    c.weight * c.foundation().expect("foundation row").proj.abs()
}

/// The Pasternak layer on [x_min, x_max]: the rows' panels as cells (their nodes
/// at the rows' x), and graded cells filling the rest so that the decay length
/// √(μ/k) is resolved (cells no longer than a fifth of it).
/// `ring_areas`: the rows' ring areas of a body of revolution (x = r ≥ 0);
/// the layer is then the annular plate ∫ (μ w′ v′ + k w v) 2πr dr.
fn layer(
    x_min: f64,
    x_max: f64,
    panels: &[[f64; 2]],
    centres: &[f64],
    ring_areas: Option<&[f64]>,
    k: f64,
    mu: f64,
) -> LineKind {
    let decay = if mu > 0.0 { (mu / k).sqrt() } else { f64::INFINITY };
    // Cells resolve the decay length, but never finer than 1e-4 of the layer:
    // a shear layer thinner than that acts as Winkler springs anyway, and an
    // unbounded cell count would let one request exhaust the memory.
    let cap = (0.2 * decay).min(0.05 * (x_max - x_min)).max(1e-4 * (x_max - x_min));
    // (cell, node x, row index or none), in order along x.
    let mut cells: Vec<([f64; 2], f64, Option<usize>)> = Vec::new();
    let fill = |from: f64, to: f64, h0: f64, grow_right: bool, cells: &mut Vec<([f64; 2], f64, Option<usize>)>| {
        if to - from <= 1e-12 * (x_max - x_min) {
            return;
        }
        // Sizes growing away from the body side of the gap.
        let mut sizes = Vec::new();
        let (mut h, mut total) = (h0.min(cap).max(1e-9 * (x_max - x_min)), 0.0);
        while total + h < to - from {
            sizes.push(h);
            total += h;
            h = (h * 1.2).min(cap);
        }
        sizes.push(to - from - total);
        if !grow_right {
            sizes.reverse();
        }
        let mut a = from;
        for s in sizes {
            cells.push(([a, a + s], a + 0.5 * s, None));
            a += s;
        }
    };
    let h_first = panels[0][1] - panels[0][0];
    fill(x_min, panels[0][0], h_first, false, &mut cells);
    for (r, p) in panels.iter().enumerate() {
        if r > 0 {
            let prev = panels[r - 1][1];
            let h = p[1] - p[0];
            fill(prev, p[0], h, true, &mut cells);
        }
        cells.push((*p, centres[r], Some(r)));
    }
    let last = panels[panels.len() - 1];
    fill(last[1], x_max, last[1] - last[0], true, &mut cells);
    // Free ends: the outer cells' nodes sit on the ends of the foundation.
    let n = cells.len();
    if cells[0].2.is_none() {
        cells[0].1 = x_min;
    }
    if cells[n - 1].2.is_none() {
        cells[n - 1].1 = x_max;
    }
    let x: Vec<f64> = cells.iter().map(|c| c.1).collect();
    let mut diag: Vec<f64> = cells
        .iter()
        .map(|c| match (ring_areas, c.2) {
            (None, _) => k * (c.0[1] - c.0[0]),
            (Some(areas), Some(r)) => k * areas[r],
            (Some(_), None) => k * std::f64::consts::PI * (c.0[1] * c.0[1] - c.0[0] * c.0[0]),
        })
        .collect();
    let mut off = vec![0.0; n.saturating_sub(1)];
    for i in 0..n.saturating_sub(1) {
        let h = x[i + 1] - x[i];
        if h > 0.0 && mu > 0.0 {
            // Linear elements: μ/h, or μ 2π r̄ / h with r̄ the element's mid-radius.
            let s = match ring_areas {
                None => mu / h,
                Some(_) => mu * std::f64::consts::PI * (x[i] + x[i + 1]) / h,
            };
            diag[i] += s;
            diag[i + 1] += s;
            off[i] = -s;
        }
    }
    let mut node_of_row = vec![0; panels.len()];
    for (i, c) in cells.iter().enumerate() {
        if let Some(r) = c.2 {
            node_of_row[r] = i;
        }
    }
    LineKind::Pasternak {
        x,
        node_of_row,
        diag,
        off,
    }
}

/// Solves the symmetric tridiagonal system (diag, off) y = f (Thomas algorithm;
/// K_f is diagonally dominant, so no pivoting is needed).
fn tridiagonal_solve(diag: &[f64], off: &[f64], f: &[f64]) -> Vec<f64> {
    let n = diag.len();
    let mut c = vec![0.0; n];
    let mut y = vec![0.0; n];
    let mut denom = diag[0];
    y[0] = f[0] / denom;
    for i in 1..n {
        c[i - 1] = off[i - 1] / denom;
        denom = diag[i] - off[i - 1] * c[i - 1];
        y[i] = (f[i] - off[i - 1] * y[i - 1]) / denom;
    }
    for i in (0..n - 1).rev() {
        y[i] -= c[i] * y[i + 1];
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_log_integral_matches_quadrature() {
        let (p, q) = ([0.0, 0.3], [0.5, 1.2]);
        let n = 2000;
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                let x = p[0] + (i as f64 + 0.5) * (p[1] - p[0]) / n as f64;
                let t = q[0] + (j as f64 + 0.5) * (q[1] - q[0]) / n as f64;
                s += (x - t).abs().ln();
            }
        }
        s *= (p[1] - p[0]) * (q[1] - q[0]) / (n * n) as f64;
        assert!(
            (s - log_double_integral(p, q)).abs() < 1e-6,
            "{s} vs {}",
            log_double_integral(p, q)
        );
        // The self term: ∫∫ over [0,h]² of ln|x − t| = h² (ln h − 3/2).
        let h: f64 = 0.2;
        assert!((log_double_integral([0.0, h], [0.0, h]) - h * h * (h.ln() - 1.5)).abs() < 1e-15);
    }

    #[test]
    fn tridiagonal_solve_inverts() {
        let (d, o) = (vec![4.0, 5.0, 6.0, 3.0], vec![-1.0, -2.0, -0.5]);
        let f = vec![1.0, 2.0, 3.0, 4.0];
        let y = tridiagonal_solve(&d, &o, &f);
        for i in 0..4 {
            let mut r = d[i] * y[i];
            if i > 0 {
                r += o[i - 1] * y[i - 1];
            }
            if i < 3 {
                r += o[i] * y[i + 1];
            }
            assert!((r - f[i]).abs() < 1e-14);
        }
    }
}
