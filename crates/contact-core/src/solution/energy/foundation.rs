//! A body's sides on a tensionless Winkler bed in the bound: the bed's
//! pressure p*, its balance of a body the bed alone holds, and the bed's
//! term of the bound.
//!
//! The continuous model bounded: springs of modulus k (pressure per length
//! of the foundation line, x) act vertically on every side of the pair's
//! edge set that faces down (n_y < 0), over the foundation's extent; the
//! indentation of a point of the deformed side is w(v) = −v_y − (y − y0)
//! (the row's n · v − g with the signed distance's n = (0, −1) and
//! g = y − y0), and the bed stores ½ k (w⁺)² per length. With J(v) the
//! body's potential plus ∫ ½ k (w(v)⁺)² dx, J is the body's quadratic
//! energy plus a convex term, so J(v) − J(u) ≥ ½ ‖u − v‖²_E for every v (u
//! the minimizer): no admissibility correction, v is free on a bed. Young's
//! inequality ½ k (w⁺)² ≥ p* w − p*²/(2k) (p* ≥ 0) and the Green formula
//! for a stress τ in equilibrium with the loads and with the traction
//! p* dx/ds upward on those sides (zero elsewhere off the loads and
//! supports) give J(v) ≥ −J*(τ, p*),
//! J*(τ, p*) = ½ (τ, C⁻¹ τ) + ∫ p*²/(2k) dx + ∫ p* g dx (less the supports'
//! work, which cancels below), with equality at (σ, k w(u)⁺). Hence
//!
//! ```text
//! ‖u − v‖²_E ≤ 2 (J(v) + J*(τ, p*))
//!            = ‖C ε(v) − τ‖²_C⁻¹ + 2 ∫ [½ k (w⁺)² + p*²/(2k) − p* w] dx,
//! ```
//!
//! every integrand ≥ 0 (it is (k w − p*)²/(2k) where w ≥ 0 and
//! p*²/(2k) + p* |w| where w < 0), zero at v = u, τ = σ, p* = k w(u)⁺ (the
//! Prager–Synge hypercircle with the contact term of Weiss & Wohlmuth,
//! Math. Comp. 78, 2009, whose obstacle is the limit k → ∞).
//!
//! The lumped springs of the finite element model (`contact::compliance`:
//! a row's force λ over its panel h, deflection λ / (k h)) make the nodal
//! pressure λ / h equal to k times the row's indentation wherever the row
//! is active: p* linear through those nodal values on each side is k w(u_h)
//! on every side in full contact, so the bed's term is the lift-off sides'
//! share alone. On quadratic triangles the rows are the corners' (dual
//! mortar rows, `contact::targets::foundation`): p* is linear along each
//! side through them while w is quadratic, so the term is not zero in full
//! contact, and is integrated on the pieces between w's roots. A side that
//! runs past an end of the bed gets p* = 0 (p* may be discontinuous between
//! sides; a pressure beyond the bed is not admissible).

use std::collections::HashMap;

use super::punch::{least_norm, GAUSS4};
use crate::fem::rigid_modes::RigidModes;
use crate::mesh::{boundary::edge_normal, Mesh2d};
use crate::model::Model;
use crate::scene::{FoundationModel, Scene, Target};

/// A side facing down over a Winkler bed.
pub(super) struct BedSide {
    pub body: usize,
    pub ends: [usize; 2],
    /// A quadratic side's midside node (p* stays linear along the side: its
    /// rows are the corners', `contact::targets::foundation`).
    pub mid: Option<usize>,
    /// p* at the ends, per length of the foundation line.
    pub pressure: [f64; 2],
    /// |dx/ds| = −n_y: the traction per length of the side is p* |dx/ds|
    /// upward, linear along it.
    pub slope: f64,
    /// The side's parameters over the bed, t0 ≤ t ≤ t1.
    pub over: [f64; 2],
    pub k: f64,
    /// The bed's surface.
    pub y0: f64,
}

impl BedSide {
    /// The upward traction (per side length) at the ends.
    pub fn traction(&self) -> [[f64; 2]; 2] {
        self.pressure.map(|p| [0.0, p * self.slope])
    }

    fn pressure_at(&self, t: f64) -> f64 {
        (1.0 - t) * self.pressure[0] + t * self.pressure[1]
    }
}

/// The Winkler sides of every pair on a foundation, with p* through the
/// rows' nodal pressures λ (−n_y) / h (h the row's panel: the springs'
/// own spread). Err for a bed the bound does not cover.
pub(super) fn sides(scene: &Scene, model: &Model, lambda: &[f64]) -> Result<Vec<BedSide>, &'static str> {
    let mut nodal: HashMap<(usize, usize), f64> = HashMap::new();
    for (c, l) in model.cons.candidates.iter().zip(lambda) {
        if let Some(r) = c.foundation() {
            let h = r.panel[1] - r.panel[0];
            nodal.insert((c.pair, c.node), if h > 0.0 { l.max(0.0) * r.proj / h } else { 0.0 });
        }
    }
    let mut out = Vec::new();
    for (p, pair) in scene.pairs.iter().enumerate() {
        let Target::Foundation(f) = pair.target else {
            continue;
        };
        let fnd = &scene.foundations[f];
        let FoundationModel::Winkler { k } = fnd.model else {
            return Err(super::BED_MODELS);
        };
        let mesh = &model.meshes[pair.body];
        for e in mesh.edge_sets.get(&pair.edges).map(|v| v.as_slice()).unwrap_or(&[]) {
            let (n, _) = edge_normal(mesh, e);
            let (xa, xb) = (mesh.nodes[e.a][0], mesh.nodes[e.b][0]);
            if n[1] >= -1e-12 || xa == xb {
                continue;
            }
            let t_of = |x: f64| ((x - xa) / (xb - xa)).clamp(0.0, 1.0);
            let (t0, t1) = (t_of(fnd.x_min), t_of(fnd.x_max));
            let over = [t0.min(t1), t0.max(t1)];
            if over[1] <= over[0] {
                continue;
            }
            let whole = over == [0.0, 1.0];
            let at = |node: usize| {
                if whole {
                    nodal.get(&(p, node)).copied().unwrap_or(0.0)
                } else {
                    0.0
                }
            };
            out.push(BedSide {
                body: pair.body,
                ends: [e.a, e.b],
                mid: e.mid,
                pressure: [at(e.a), at(e.b)],
                slope: -n[1],
                over,
                k,
                y0: fnd.y,
            });
        }
    }
    Ok(out)
}

/// Scales p* on the sides of a body the bed alone holds (free rigid modes,
/// `fem::rigid_modes`) so that it balances the body's loads on every free
/// mode: the equilibrated stress needs loads in equilibrium, and p* through
/// the nodal pressures matches the rows' force but not their moment.
/// Nodal pressures × (1 + Σ_j a_j (x − c_x)^j), one term per mode the bed
/// pushes, as a punch's (`punch::balance`). Err where no such scaling keeps
/// p* ≥ 0 or a mode the bed cannot push is loaded.
pub(super) fn balance(model: &Model, set: &RigidModes, sides: &mut [BedSide]) -> Result<(), &'static str> {
    let mesh = &model.meshes[set.body];
    let dofs = &model.dofs;
    let n = set.basis.len();
    let basis = |x: f64, j: usize| (x - set.center[0]).powi(j as i32);
    // The loads' work on each mode, which p* must cancel.
    let target: Vec<f64> = (0..n)
        .map(|k| {
            -(0..mesh.nodes.len())
                .map(|node| {
                    let r = set.at(k, mesh.nodes[node]);
                    (0..2)
                        .map(|c| model.external[dofs.dof(set.body, node, c)] * r[c])
                        .sum::<f64>()
                })
                .sum::<f64>()
        })
        .collect();
    // a[k][j]: p*'s work on mode k when its nodal pressures are scaled by
    // basis j (j = n: unscaled); p* pushes up, so only the modes' vertical
    // motion works, exactly integrated (both linear along the side).
    let mut a = [[0.0; 4]; 3];
    let mut scale = 0.0_f64;
    for s in sides.iter().filter(|s| s.body == set.body && s.pressure != [0.0, 0.0]) {
        let (pa, pb) = (mesh.nodes[s.ends[0]], mesh.nodes[s.ends[1]]);
        let dx = (pb[0] - pa[0]).abs();
        for (t, w) in GAUSS4 {
            let x = [(1.0 - t) * pa[0] + t * pb[0], (1.0 - t) * pa[1] + t * pb[1]];
            for j in 0..=n {
                let factor = |xe: f64| if j < n { basis(xe, j) } else { 1.0 };
                let p = (1.0 - t) * s.pressure[0] * factor(pa[0]) + t * s.pressure[1] * factor(pb[0]);
                for (k, row) in a.iter_mut().enumerate().take(n) {
                    row[j] += w * dx * p * set.at(k, x)[1];
                }
            }
        }
        scale = scale.max(s.pressure[0]).max(s.pressure[1]);
    }
    let big = a
        .iter()
        .flat_map(|r| r[..=n].iter())
        .chain(&target)
        .fold(0.0_f64, |x, y| x.max(y.abs()));
    let (pushed, idle): (Vec<usize>, Vec<usize>) =
        (0..n).partition(|&k| a[k][..n].iter().any(|v| v.abs() > 1e-12 * big));
    const REFUSED: &str = "the bed's pressure cannot balance the loads of a body it alone holds with one sign";
    // A mode the bed cannot push (a horizontal slide) must be unloaded: the
    // solve held it at rest only because nothing loads it.
    if idle
        .iter()
        .any(|&k| (target[k] - a[k][n]).abs() > 1e-9 * big.max(f64::MIN_POSITIVE))
    {
        return Err(REFUSED);
    }
    if pushed.is_empty() {
        return Ok(());
    }
    let rows: Vec<[f64; 4]> = pushed.iter().map(|&k| a[k]).collect();
    let r: Vec<f64> = pushed.iter().map(|&k| target[k] - a[k][n]).collect();
    let coef = least_norm(&rows, &r, big).ok_or(REFUSED)?;
    for s in sides.iter_mut().filter(|s| s.body == set.body) {
        for (end, &node) in s.ends.iter().enumerate() {
            let x = mesh.nodes[node][0];
            let f: f64 = coef.iter().enumerate().map(|(j, c)| c * basis(x, j)).sum();
            s.pressure[end] *= 1.0 + f;
            if s.pressure[end] < -1e-12 * scale {
                return Err(REFUSED);
            }
            s.pressure[end] = s.pressure[end].max(0.0);
        }
    }
    Ok(())
}

/// Whether every pair of `body` rests on a Winkler bed (a body such a bed
/// alone may hold is in the bound; one held by obstacles is not yet).
pub(super) fn only_on_beds(scene: &Scene, body: usize) -> bool {
    scene.pairs.iter().filter(|p| p.body == body).all(|p| match p.target {
        Target::Foundation(f) => matches!(scene.foundations[f].model, FoundationModel::Winkler { .. }),
        _ => false,
    })
}

/// The sides' terms along a displacement `v` (per body): the bound's
/// 2 ∫ [½ k (w⁺)² + p*²/(2k) − p* w] dx and the bed's energy
/// ∫ ½ k (w⁺)² dx, exactly: the side is cut at the roots of w (one on a
/// linear side, up to two on a quadratic one), where each integrand is a
/// polynomial in t of degree at most 4, which 4 Gauss points integrate
/// exactly.
pub(super) fn terms(meshes: &[Mesh2d], sides: &[BedSide], v: &[Vec<[f64; 2]>]) -> (f64, f64) {
    let (mut bound, mut energy) = (0.0, 0.0);
    for s in sides {
        let mesh = &meshes[s.body];
        let (a, b) = (s.ends[0], s.ends[1]);
        let (pa, pb) = (mesh.nodes[a], mesh.nodes[b]);
        let w_of = |node: usize| -v[s.body][node][1] - (mesh.nodes[node][1] - s.y0);
        let (wa, wb) = (w_of(a), w_of(b));
        // w along the side: linear, or on a straight quadratic side the P2
        // interpolant through its midside value (y is linear along it). The
        // linear side keeps its own formula and its round-off (the centred
        // footing's bound, 1.7e-8 of its norm, is that round-off).
        let wm = s.mid.map(w_of);
        let w_at = |t: f64| match wm {
            Some(wm) => {
                let f = super::quadratic::along_side(t);
                f[0] * wa + f[1] * wm + f[2] * wb
            }
            None => (1.0 - t) * wa + t * wb,
        };
        let dx = (pb[0] - pa[0]).abs();
        let mut cuts = vec![s.over[0], s.over[1]];
        let inner = match wm {
            Some(wm) => roots(wa, wm, wb),
            None if wa != wb => vec![wa / (wa - wb)],
            None => vec![],
        };
        cuts.extend(inner.into_iter().filter(|&r| r > s.over[0] && r < s.over[1]));
        cuts.sort_by(f64::total_cmp);
        // Each piece's integrand is a polynomial of degree 4 at most (w
        // quadratic, p* linear), which 4 Gauss points integrate exactly.
        for piece in cuts.windows(2) {
            let len = piece[1] - piece[0];
            for (q, wq) in GAUSS4 {
                let t = piece[0] + q * len;
                let (w, p) = (w_at(t), s.pressure_at(t));
                let wp = w.max(0.0);
                bound += 2.0 * wq * len * dx * (0.5 * s.k * wp * wp + p * p / (2.0 * s.k) - p * w).max(0.0);
                energy += wq * len * dx * 0.5 * s.k * wp * wp;
            }
        }
    }
    (bound, energy)
}

/// The roots in (0, 1) of the quadratic through w(0) = a, w(½) = m,
/// w(1) = b (of the line when m is their mean, as on a linear side).
fn roots(a: f64, m: f64, b: f64) -> Vec<f64> {
    // w = a + c1 t + c2 t².
    let c2 = 2.0 * (a - 2.0 * m + b);
    let c1 = b - a - c2;
    let scale = a.abs().max(m.abs()).max(b.abs());
    let inside = |t: &f64| *t > 0.0 && *t < 1.0;
    if c2.abs() <= 1e-12 * scale {
        return if c1 != 0.0 { vec![-a / c1] } else { vec![] }
            .into_iter()
            .filter(inside)
            .collect();
    }
    let disc = c1 * c1 - 4.0 * c2 * a;
    if disc < 0.0 {
        return vec![];
    }
    // The cancellation-free pair: q = −(c1 + sign(c1) √disc) / 2, t = q / c2
    // and a / q.
    let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
    let mut out = vec![q / c2];
    if q != 0.0 {
        out.push(a / q);
    }
    out.into_iter().filter(inside).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Order;

    /// One side along y = 0 from x = 0 to 1 on a bed at y0 = 0 with k = 100.
    fn side(pressure: [f64; 2]) -> (Vec<Mesh2d>, BedSide) {
        let mesh = Mesh2d {
            order: Order::T3,
            nodes: vec![[0.0, 0.0], [1.0, 0.0]],
            elems: Vec::new(),
            edge_sets: Default::default(),
        };
        let s = BedSide {
            body: 0,
            ends: [0, 1],
            mid: None,
            pressure,
            slope: 1.0,
            over: [0.0, 1.0],
            k: 100.0,
            y0: 0.0,
        };
        (vec![mesh], s)
    }

    /// The bed's term vanishes where p* = k w (a uniform indentation 0.01
    /// under p* = 1), and the bed stores ½ k w² per length.
    #[test]
    fn the_term_vanishes_where_the_pressure_is_the_springs() {
        let (meshes, s) = side([1.0, 1.0]);
        let v = vec![vec![[0.0, -0.01], [0.0, -0.01]]];
        let (bound, energy) = terms(&meshes, &[s], &v);
        // Round-off of products of order 1 and 1e-4.
        assert!(bound.abs() < 1e-15, "{bound}");
        assert!((energy - 0.5 * 100.0 * 1e-4).abs() < 1e-15, "{energy}");
    }

    /// Lifting off in the middle of the side (w from 0.01 to −0.01, p* from
    /// 1 to 0): 2 ∫ [½ k (w⁺)² + p*²/(2k) − p* w] = 2 (1/4800 + 1/4800 +
    /// 1/2400) = 1/600 and ∫ ½ k (w⁺)² = 1/1200 by hand, on either side of
    /// the root; the pieces' Gauss points make both exact to round-off.
    #[test]
    fn the_term_is_integrated_exactly_across_a_lift_off() {
        let (meshes, s) = side([1.0, 0.0]);
        let v = vec![vec![[0.0, -0.01], [0.0, 0.01]]];
        let (bound, energy) = terms(&meshes, &[s], &v);
        assert!((bound - 1.0 / 600.0).abs() < 1e-15, "{bound}");
        assert!((energy - 1.0 / 1200.0).abs() < 1e-15, "{energy}");
    }

    /// A quadratic side (midside node at x = ½) lifting off between its
    /// ends and its middle: w = 0.01 at the ends and −0.01 at the middle, a
    /// parabola with two roots, under p* linear from 1 to 0.5. Its term,
    /// integrated on the pieces the roots cut, matches a midpoint sum of
    /// 200,000 cells (whose error is of order 1e-11 of the term, the kinks'
    /// cells included).
    #[test]
    fn a_quadratic_side_is_integrated_across_its_two_roots() {
        let (mut meshes, mut s) = side([1.0, 0.5]);
        meshes[0].nodes.push([0.5, 0.0]);
        s.mid = Some(2);
        let v = vec![vec![[0.0, -0.01], [0.0, -0.01], [0.0, 0.01]]];
        let (bound, energy) = terms(&meshes, &[s], &v);
        let n = 200_000;
        let (mut b, mut e) = (0.0, 0.0);
        for i in 0..n {
            let t = (i as f64 + 0.5) / n as f64;
            let w = 0.01 * ((1.0 - t) * (1.0 - 2.0 * t) - 4.0 * t * (1.0 - t) + t * (2.0 * t - 1.0));
            let p = 1.0 - 0.5 * t;
            let wp = w.max(0.0);
            b += 2.0 * (0.5 * 100.0 * wp * wp + p * p / 200.0 - p * w) / n as f64;
            e += 0.5 * 100.0 * wp * wp / n as f64;
        }
        assert!((bound - b).abs() < 1e-9 * b, "{bound} against {b}");
        assert!((energy - e).abs() < 1e-9 * e, "{energy} against {e}");
        assert_eq!(roots(0.01, -0.01, 0.01).len(), 2);
    }
}
