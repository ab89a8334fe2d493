//! From "what a point of the contact surface sees" to rows of B u ≤ g.
//!
//! Every contact target (rigid obstacle, another body) answers one question
//! for a point x of the pair's own surface (the slave side): `Seen`, the gap
//! g(x) and the row direction n(x) of the linearized condition
//!
//! ```text
//! n · u(x) − n · u_t(y) − c · β ≤ g,
//! ```
//!
//! with u_t(y) the target's displacement at the point y facing x (nodal
//! weights of the other body's nodes) and c · β a punch's rigid motion. The
//! rows are then
//!
//! - **nodal**: one row per surface node, at the node, with its tributary
//!   length w_i = ∫ N_i ds as weight (pressure p_i = λ_i / w_i);
//! - **mortar**: row i is ∫ Ψ_i (·) ds / ∫ Ψ_i ds over the part of the surface
//!   that sees the target (∫ Ψ_i = ∫ Φ_i over a whole support). Φ_i are the linear hats of the multiplier nodes (the
//!   nodes of T3 edges, the corners of T6 edges: quadratic nodal multipliers let
//!   the pressure alternate between corner and midside nodes); Ψ_i are their
//!   dual (biorthogonal) partners, ∫ Ψ_i Φ_j ds = δ_ij ∫ Φ_j ds, which on an
//!   edge are 2 − 3ξ and 3ξ − 1 (Wohlmuth, SIAM J. Numer. Anal. 38, 2000).
//!   Testing with Ψ makes the discrete pressure a local quantity: with the
//!   standard Φ the pressure is an L2-type projection and rings next to the
//!   zone edge, where it drops like a square root (measured on the elastic disk
//!   on a flat, T6, corners a/29 apart: the error alternating in sign over the
//!   last five corners and growing to +4.4 % and −7.7 % of p0; with Ψ it keeps
//!   one sign and stays within 1.2 %).
//!   The multiplier is the force λ_i = p_i w_i with w_i = ∫ Φ_i ds; since
//!   Σ Ψ_i = 1 a uniform pressure is still transmitted exactly.
//!
//! Length: about 500 lines, half of them the T6 multiplier schemes with their
//! measured comparison and the test that each is biorthogonal; the rows and
//! their schemes belong together.

use std::collections::HashMap;

use crate::mesh::{boundary::boundary_nodes, Edge, Mesh2d};
use crate::scene::Analysis;

/// One node's share of a candidate row; the contact force the row's
/// multiplier λ puts on that node is −λ · coef.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Term {
    pub body: usize,
    pub node: usize,
    pub coef: [f64; 2],
}

/// An edge set of one body.
pub struct Surface<'a> {
    pub body: usize,
    pub mesh: &'a Mesh2d,
    pub edges: &'a [Edge],
    /// Its kinematics: on the section of a body of revolution the weights
    /// are areas 2πr ds (`Analysis::measure`).
    pub analysis: Analysis,
}

impl Surface<'_> {
    pub fn axisymmetric(&self) -> bool {
        self.analysis == Analysis::Axisymmetric
    }
}

/// What a surface point sees of its target.
#[derive(Debug, Clone)]
pub struct Seen {
    pub gap: f64,
    /// Unit row direction n (from the surface toward the target).
    pub dir: [f64; 2],
    /// (body, node, N_k(y)): the target's nodes whose motion at y closes the gap.
    pub other: Vec<(usize, usize, f64)>,
    /// A rigid punch's motion coefficients c (β = α1, α2, θ) and the lever
    /// (y − r) · n of its rotation along the tangent (`punch_coefficients`).
    pub punch: Option<[f64; 4]>,
}

/// Answers `Seen` for a point x with the surface's outward normal there, or
/// None when the point cannot meet the target (pruned).
pub type See<'a> = dyn Fn([f64; 2], [f64; 2]) -> Option<Seen> + 'a;

/// A surface node's row before the DOF map: Σ terms · u − punch · β ≤ gap.
pub struct Row {
    pub node: usize,
    /// The row's direction (weighted mean over a mortar row's support).
    pub normal: [f64; 2],
    /// Tributary length: ∫ N_i ds (nodal) or ∫ Φ_i ds over the part that sees
    /// the target (areas, with 2πr ds, in axisymmetry).
    pub weight: f64,
    pub terms: Vec<Term>,
    pub gap: f64,
    pub punch: Option<[f64; 4]>,
}

pub struct Rows {
    pub rows: Vec<Row>,
    pub pruned: usize,
}

/// The rigid motion coefficients c of a punch point y for the row direction n:
/// the punch moves y by (α1 − θ (y_y − r_y), α2 + θ (y_x − r_x)), which closes
/// the gap by −n · that motion. The fourth coefficient is the rotation's
/// share along the tangent t = (−n_y, n_x), −t_x (y_y − r_y) + t_y (y_x − r_x)
/// = (y − r) · n: a frictional row's tangential coefficients are then
/// (t_x, t_y, (y − r) · n).
pub fn punch_coefficients(y: [f64; 2], reference: [f64; 2], n: [f64; 2]) -> [f64; 4] {
    let (dx, dy) = (y[0] - reference[0], y[1] - reference[1]);
    [n[0], n[1], dx * n[1] - dy * n[0], dx * n[0] + dy * n[1]]
}

/// Adds c · v to the coefficient of `node` of `body` in `terms`.
pub fn add(terms: &mut Vec<Term>, body: usize, node: usize, v: [f64; 2], c: f64) {
    let coef = [c * v[0], c * v[1]];
    match terms.iter_mut().find(|t| t.body == body && t.node == node) {
        Some(t) => {
            t.coef[0] += coef[0];
            t.coef[1] += coef[1];
        }
        None => terms.push(Term { body, node, coef }),
    }
}

fn add_other(terms: &mut Vec<Term>, seen: &Seen, scale: f64) {
    for &(body, node, m) in &seen.other {
        if m != 0.0 {
            add(terms, body, node, seen.dir, -scale * m);
        }
    }
}

/// One row per surface node (node-to-target).
pub fn nodal(surface: &Surface, see: &See, limit: f64) -> Rows {
    let mut out = Rows {
        rows: Vec::new(),
        pruned: 0,
    };
    for bn in boundary_nodes(surface.mesh, surface.edges, surface.axisymmetric()) {
        let x = surface.mesh.nodes[bn.node];
        let Some(seen) = see(x, bn.normal).filter(|s| s.gap <= limit) else {
            out.pruned += 1;
            continue;
        };
        let mut terms = vec![Term {
            body: surface.body,
            node: bn.node,
            coef: seen.dir,
        }];
        add_other(&mut terms, &seen, 1.0);
        out.rows.push(Row {
            node: bn.node,
            normal: seen.dir,
            weight: bn.weight,
            terms,
            gap: seen.gap,
            punch: seen.punch,
        });
    }
    out
}

/// Shape functions and their derivatives on an edge, ξ ∈ [0, 1], nodes in
/// edge order a, (mid), b.
pub fn shape01(n_nodes: usize, xi: f64) -> ([f64; 3], [f64; 3]) {
    if n_nodes == 2 {
        ([1.0 - xi, xi, 0.0], [-1.0, 1.0, 0.0])
    } else {
        (
            [
                (1.0 - xi) * (1.0 - 2.0 * xi),
                4.0 * xi * (1.0 - xi),
                xi * (2.0 * xi - 1.0),
            ],
            [4.0 * xi - 3.0, 4.0 - 8.0 * xi, 4.0 * xi - 1.0],
        )
    }
}

/// How the multipliers of a T6 edge are placed (a T3 edge has one way).
///
/// Measured on the elastic disk on a flat (nodal L2 error against its overkill
/// table, T6 at h_min 0.0088 … 0.00055 R, 4k–252k DOF; T3 at half the h_min,
/// the same surface spacing, 2k–237k DOF):
///
/// - `Corners` keeps the edge's pressure on its two corners, so the zone edge
///   is resolved no better than by T3 with the corner spacing, and the error
///   falls in steps as the edge moves between corners: 1.08, 0.20, 0.21,
///   0.11, 0.16 % (T3: 0.51, 0.43, 0.24, 0.26, 0.24 %).
/// - `Halves` (linear hats on each half of the edge, corners and midside, and
///   their duals) places a multiplier at every surface node: 0.375, 0.231,
///   0.121, 0.080, 0.022 %, better per DOF than T3 and than `Corners` at every
///   level; the ball and the flat block improve alike. It needs the midside on
///   the curved surface: on a straight chord the midside row sees the chord's
///   sagitta h²/8R as a gap bump, and the pressure alternates between corners
///   and midsides by O(h) (disk: 4.6, 2.4, 1.2, 0.62, 0.31 %), which is why the
///   generators place the midsides of curved edges on the curve. Next to the
///   zone edge corner and midside errors keep opposite signs, by up to 2–3e-3
///   of p0 (measured), within the largest nodal error of T3 (1e-2 of p0).
/// - The quadratic Lagrange functions with their dual partners D M⁻¹ N were
///   non-monotone on the same disk (0.33, 0.57, 0.14, 0.14, 0.070 %) and
///   cannot carry an axis node of a body of revolution (∫ N ρ = 0 there).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum T6Multiplier {
    /// Linear hats on the corners and their duals: the foundations' rows,
    /// which load the foundation over each corner's panel.
    Corners,
    /// Linear hats on the two halves of the edge and their duals per half:
    /// rigid obstacles, punches and two bodies.
    Halves,
}

/// The multiplier functions of one edge: Φ and Ψ at ξ.
enum EdgeMult {
    /// Two multiplier nodes (slots 0 and `b`), Ψ = C Φ (None: the plain
    /// duals 2 − 3ξ, 3ξ − 1).
    Linear { b: usize, c: Option<[[f64; 2]; 2]> },
    /// Linear per half (a–m, m–b), each with its own C.
    Halves { c: [Option<[[f64; 2]; 2]>; 2] },
}

impl EdgeMult {
    fn new(scheme: T6Multiplier, n_nodes: usize, radii: Option<[f64; 3]>) -> Self {
        let lin = |ra: f64, rb: f64| radii.map(|_| weighted_dual(ra, rb));
        let r = radii.unwrap_or([1.0; 3]);
        if n_nodes == 2 {
            return EdgeMult::Linear {
                b: 1,
                c: lin(r[0], r[2]),
            };
        }
        match scheme {
            T6Multiplier::Corners => EdgeMult::Linear {
                b: 2,
                c: lin(r[0], r[2]),
            },
            T6Multiplier::Halves => EdgeMult::Halves {
                c: [lin(r[0], r[1]), lin(r[1], r[2])],
            },
        }
    }

    fn at(&self, xi: f64) -> ([f64; 3], [f64; 3]) {
        let mut phi = [0.0; 3];
        let mut psi = [0.0; 3];
        match self {
            EdgeMult::Linear { b, c } => {
                phi[0] = 1.0 - xi;
                phi[*b] = xi;
                [psi[0], psi[*b]] = linear_dual(c, xi);
            }
            EdgeMult::Halves { c } => {
                let (k, s) = if xi < 0.5 { (0, 2.0 * xi) } else { (1, 2.0 * xi - 1.0) };
                phi[k] = 1.0 - s;
                phi[k + 1] = s;
                [psi[k], psi[k + 1]] = linear_dual(&c[k], s);
            }
        }
        (phi, psi)
    }
}

/// The dual partners of the hats 1 − ξ, ξ at ξ: C Φ, or 2 − 3ξ, 3ξ − 1.
fn linear_dual(c: &Option<[[f64; 2]; 2]>, xi: f64) -> [f64; 2] {
    match c {
        Some(c) => [c[0][0] * (1.0 - xi) + c[0][1] * xi, c[1][0] * (1.0 - xi) + c[1][1] * xi],
        None => [2.0 - 3.0 * xi, 3.0 * xi - 1.0],
    }
}

/// The dual partners Ψ = C Φ of the hats Φ on an edge whose measure is
/// linear in ξ, ρ = r_a (1 − ξ) + r_b ξ (the 2πr of a body of revolution):
/// C = D M⁻¹ with M_ij = ∫ Φ_i Φ_j ρ and D = diag(∫ Φ_i ρ), so that
/// ∫ Ψ_i Φ_j ρ = δ_ij ∫ Φ_j ρ. The plain Ψ (2 − 3ξ, 3ξ − 1) is the case
/// r_a = r_b; on an edge touching the axis (r_a = 0) Ψ_a = 3 − 4ξ, whose
/// plain counterpart would integrate to 0 there.
fn weighted_dual(ra: f64, rb: f64) -> [[f64; 2]; 2] {
    let (m11, m12, m22) = (ra / 4.0 + rb / 12.0, (ra + rb) / 12.0, ra / 12.0 + rb / 4.0);
    let (d1, d2) = (m11 + m12, m12 + m22);
    let det = m11 * m22 - m12 * m12;
    [[d1 * m22 / det, -d1 * m12 / det], [-d2 * m12 / det, d2 * m11 / det]]
}

/// Point and tangent of an edge at ξ.
pub fn edge_point(pts: &[[f64; 2]], xi: f64) -> ([f64; 2], [f64; 2]) {
    let (n, dn) = shape01(pts.len(), xi);
    let mut x = [0.0; 2];
    let mut t = [0.0; 2];
    for (k, p) in pts.iter().enumerate() {
        for c in 0..2 {
            x[c] += n[k] * p[c];
            t[c] += dn[k] * p[c];
        }
    }
    (x, t)
}

/// 4-point Gauss–Legendre on [−1, 1] (exact to degree 7).
const GAUSS4: [[f64; 2]; 4] = [
    [-0.861_136_311_594_052_6, 0.347_854_845_137_453_85],
    [-0.339_981_043_584_856_26, 0.652_145_154_862_546_2],
    [0.339_981_043_584_856_26, 0.652_145_154_862_546_2],
    [0.861_136_311_594_052_6, 0.347_854_845_137_453_85],
];

/// A row tested with one family of functions: Σ ∫ f (·) ds.
#[derive(Default)]
struct Tested {
    weight: f64,
    gap: f64,
    terms: Vec<Term>,
    punch: Option<[f64; 4]>,
}

impl Tested {
    fn add(&mut self, f: f64, seen: &Seen, body: usize, nodes: &[usize], sn: &[f64; 3]) {
        self.weight += f;
        self.gap += f * seen.gap;
        if let Some(c) = seen.punch {
            let p = self.punch.get_or_insert([0.0; 4]);
            for k in 0..4 {
                p[k] += f * c[k];
            }
        }
        for (j, &nj) in nodes.iter().enumerate() {
            if sn[j] != 0.0 {
                add(&mut self.terms, body, nj, seen.dir, f * sn[j]);
            }
        }
        add_other(&mut self.terms, seen, f);
    }
}

/// A multiplier node's integrals: its Φ-weighted normal and the row tested
/// with Ψ and with Φ (whose weight is the node's tributary length ∫ Φ_i ds).
#[derive(Default)]
struct Acc {
    normal: [f64; 2],
    dual: Tested,
    standard: Tested,
}

/// Mortar rows: each edge is integrated by 4-point Gauss on the sub-intervals
/// between `breaks(edge)` (sorted, from 0 to 1), where the caller puts the
/// kinks of what the points see (the projections of the other body's nodes), so
/// that the products are integrated exactly on straight edges.
pub fn mortar(
    surface: &Surface,
    scheme: T6Multiplier,
    see: &See,
    limit: f64,
    breaks: &dyn Fn(&[[f64; 2]]) -> Vec<f64>,
) -> Rows {
    let mut order: Vec<usize> = Vec::new();
    let mut acc: HashMap<usize, Acc> = HashMap::new();
    for e in surface.edges {
        let nodes: Vec<usize> = e.nodes().collect();
        let pts: Vec<[f64; 2]> = nodes.iter().map(|&i| surface.mesh.nodes[i]).collect();
        let radii = surface
            .axisymmetric()
            .then(|| [pts[0][0], pts[pts.len() / 2][0], pts[pts.len() - 1][0]]);
        let mult = EdgeMult::new(scheme, nodes.len(), radii);
        for w in breaks(&pts).windows(2) {
            let (x0, x1) = (w[0], w[1]);
            for g in &GAUSS4 {
                let xi = x0 + 0.5 * (g[0] + 1.0) * (x1 - x0);
                let (x, tan) = edge_point(&pts, xi);
                let jac = (tan[0] * tan[0] + tan[1] * tan[1]).sqrt();
                let n = [tan[1] / jac, -tan[0] / jac];
                let Some(seen) = see(x, n).filter(|s| s.gap <= limit) else {
                    continue;
                };
                let omega = 0.5 * g[1] * (x1 - x0) * jac * surface.analysis.measure(x);
                let (sn, _) = shape01(nodes.len(), xi);
                let (phi, psi) = mult.at(xi);
                for (i, &node) in nodes.iter().enumerate() {
                    let (wi, ti) = (omega * phi[i], omega * psi[i]);
                    if wi == 0.0 {
                        continue;
                    }
                    let a = acc.entry(node).or_insert_with(|| {
                        order.push(node);
                        Acc::default()
                    });
                    a.normal[0] += wi * seen.dir[0];
                    a.normal[1] += wi * seen.dir[1];
                    a.dual.add(ti, &seen, surface.body, &nodes, &sn);
                    a.standard.add(wi, &seen, surface.body, &nodes, &sn);
                }
            }
        }
    }
    let full: HashMap<usize, f64> = boundary_nodes(surface.mesh, surface.edges, surface.axisymmetric())
        .into_iter()
        .map(|b| (b.node, b.weight))
        .collect();
    // Midside nodes carry no multiplier: they are not candidates.
    let corners = if scheme == T6Multiplier::Corners {
        full.len() - surface.edges.iter().filter(|e| e.mid.is_some()).count()
    } else {
        full.len()
    };
    let mut out = Rows {
        rows: Vec::new(),
        pruned: corners - order.len(),
    };
    for node in order {
        let a = acc.remove(&node).expect("accumulated");
        // A node whose multiplier barely overlaps the target has no
        // well-defined pressure.
        let weight = a.standard.weight;
        if weight <= 1e-9 * full[&node] {
            out.pruned += 1;
            continue;
        }
        // Ψ integrates to ∫ Φ over a whole support; where the target sees only
        // part of it (an end of the target or of the pruned region) ∫ Ψ can
        // vanish or turn negative, and the node keeps the standard row.
        let t = if a.dual.weight >= 0.5 * weight {
            a.dual
        } else {
            a.standard
        };
        let gap = t.gap / t.weight;
        if gap > limit {
            out.pruned += 1;
            continue;
        }
        let nl = (a.normal[0] * a.normal[0] + a.normal[1] * a.normal[1]).sqrt();
        // Normalized by the tested weight, the multiplier is the row's force.
        let inv = 1.0 / t.weight;
        out.rows.push(Row {
            node,
            normal: [a.normal[0] / nl, a.normal[1] / nl],
            weight,
            terms: t
                .terms
                .into_iter()
                .map(|t| Term {
                    coef: [t.coef[0] * inv, t.coef[1] * inv],
                    ..t
                })
                .collect(),
            gap,
            punch: t.punch.map(|p| p.map(|v| v * inv)),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every multiplier scheme of a T6 edge is biorthogonal for the measure
    /// ρ dξ: ∫ Ψ_i Φ_j ρ = δ_ij ∫ Φ_j ρ (so a node's row is its own), and its
    /// dual functions sum to 1 (a uniform pressure is transmitted exactly) and
    /// integrate to ∫ Φ_i ρ > 0 (a row over a whole support has a positive
    /// weight). ρ linear: 1, a ring away from the axis, and one touching it.
    /// The integrands are polynomials of degree ≤ 5 on each half, which
    /// 4-point Gauss integrates exactly: the tolerance is rounding.
    #[test]
    fn t6_multiplier_schemes_are_biorthogonal_and_sum_to_one() {
        for scheme in [T6Multiplier::Corners, T6Multiplier::Halves] {
            for radii in [None, Some([0.3, 0.35, 0.4]), Some([0.0, 0.05, 0.1])] {
                let mult = EdgeMult::new(scheme, 3, radii);
                let rho = |xi: f64| radii.map_or(1.0, |r| r[0] * (1.0 - xi) + r[2] * xi);
                let (mut m, mut d, mut dpsi) = ([[0.0; 3]; 3], [0.0; 3], [0.0; 3]);
                for (x0, x1) in [(0.0, 0.5), (0.5, 1.0)] {
                    for g in &GAUSS4 {
                        let xi = x0 + 0.5 * (g[0] + 1.0) * (x1 - x0);
                        let w = 0.5 * g[1] * (x1 - x0) * rho(xi);
                        let (phi, psi) = mult.at(xi);
                        let sum: f64 = psi.iter().sum();
                        assert!((sum - 1.0).abs() < 1e-12, "{scheme:?} {radii:?}: Σ Ψ = {sum} at {xi}");
                        for i in 0..3 {
                            d[i] += w * phi[i];
                            dpsi[i] += w * psi[i];
                            for j in 0..3 {
                                m[i][j] += w * psi[i] * phi[j];
                            }
                        }
                    }
                }
                let scale = d.iter().fold(0.0f64, |a, &b| a.max(b));
                for i in 0..3 {
                    if scheme == T6Multiplier::Corners && i == 1 {
                        assert_eq!(d[i], 0.0, "the midside of `Corners` carries no multiplier");
                        continue;
                    }
                    assert!(d[i] > 0.05 * scale, "{scheme:?} {radii:?} node {i}: ∫Φρ = {}", d[i]);
                    assert!(
                        (dpsi[i] - d[i]).abs() < 1e-12 * scale,
                        "{scheme:?} {radii:?} node {i}: ∫Ψρ = {}",
                        dpsi[i]
                    );
                    for j in 0..3 {
                        let want = if i == j { d[j] } else { 0.0 };
                        assert!(
                            (m[i][j] - want).abs() < 1e-12 * scale,
                            "{scheme:?} {radii:?}: ∫Ψ{i}Φ{j} = {}",
                            m[i][j]
                        );
                    }
                }
            }
        }
    }
}
