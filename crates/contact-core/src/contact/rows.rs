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

/// Multiplier functions on an edge, (Φ, Ψ): the linear hats of the end nodes
/// (zero at a T6 midside) and their dual partners (see the module doc).
fn mult01(n_nodes: usize, xi: f64) -> ([f64; 3], [f64; 3]) {
    let (phi, psi) = ([1.0 - xi, xi], [2.0 - 3.0 * xi, 3.0 * xi - 1.0]);
    if n_nodes == 2 {
        ([phi[0], phi[1], 0.0], [psi[0], psi[1], 0.0])
    } else {
        ([phi[0], 0.0, phi[1]], [psi[0], 0.0, psi[1]])
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
pub fn mortar(surface: &Surface, see: &See, limit: f64, breaks: &dyn Fn(&[[f64; 2]]) -> Vec<f64>) -> Rows {
    let mut order: Vec<usize> = Vec::new();
    let mut acc: HashMap<usize, Acc> = HashMap::new();
    for e in surface.edges {
        let nodes: Vec<usize> = e.nodes().collect();
        let pts: Vec<[f64; 2]> = nodes.iter().map(|&i| surface.mesh.nodes[i]).collect();
        let dual = surface
            .axisymmetric()
            .then(|| weighted_dual(pts[0][0], pts[pts.len() - 1][0]));
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
                let (phi, mut psi) = mult01(nodes.len(), xi);
                if let Some(c) = dual {
                    let (a, b) = (0, nodes.len() - 1);
                    (psi[a], psi[b]) = (c[0][0] * phi[a] + c[0][1] * phi[b], c[1][0] * phi[a] + c[1][1] * phi[b]);
                }
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
    let corners = full.len() - surface.edges.iter().filter(|e| e.mid.is_some()).count();
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
