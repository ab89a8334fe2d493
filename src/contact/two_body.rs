//! Rows of the linearized non-penetration condition between two deformable
//! bodies on non-matching meshes.
//!
//! The non-mortar ("slave") side a carries the pressure; a point x of it looks
//! along its outward normal n for the facing surface of body b (the mortar or
//! "master" side) and finds it at y = x + s n. Linearized about the reference
//! configuration, the two surfaces do not interpenetrate where
//!
//! ```text
//! n · u^a(x) − n · u^b(y) ≤ s(x)
//! ```
//!
//! (the condition u^a·n^a + u^b·n^b ≤ gap of the theory, with n^b = −n^a).
//!
//! - **Node-to-segment**: one row per slave node, x the node, n its nodal normal.
//! - **Mortar** (segment-to-segment): the condition weighted by each slave
//!   multiplier function (the shape functions on T3 edges, piecewise-linear hats
//!   on the halves of T6 edges) and integrated over the part of the slave surface that sees the
//!   master, split at the projections of the master nodes so that Gauss
//!   quadrature integrates the piecewise polynomial products exactly on straight
//!   edges. Row i is ∫ Φ_i (·) ds / ∫ Φ_i ds, so its multiplier is the force
//!   λ_i = p_i w_i with p_i the nodal value of the pressure field Σ p_i Φ_i and
//!   w_i = ∫ Φ_i ds; since Σ Φ_i = 1, the forces
//!   on both sides are the consistent nodal loads of that pressure field: this is
//!   what makes the contact patch test pass.

use std::collections::HashMap;

use super::candidates::Term;
use crate::mesh::{boundary::boundary_nodes, Edge, Mesh2d};

/// An edge set of one body.
pub struct Surface<'a> {
    pub body: usize,
    pub mesh: &'a Mesh2d,
    pub edges: &'a [Edge],
}

/// A slave node's row before the DOF map: Σ terms · u ≤ gap.
pub struct Row {
    pub node: usize,
    pub normal: [f64; 2],
    /// Tributary length of the row: ∫ Φ_i ds over the part that sees the master.
    pub weight: f64,
    pub terms: Vec<Term>,
    pub gap: f64,
}

pub struct Rows {
    pub rows: Vec<Row>,
    pub pruned: usize,
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Shape functions and their derivatives on an edge, ξ ∈ [0, 1], nodes in
/// edge order a, (mid), b.
fn shape01(n_nodes: usize, xi: f64) -> ([f64; 3], [f64; 3]) {
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

/// Multiplier (test) functions on a slave edge: the shape functions for a T3
/// edge; for a T6 edge, hat functions on its two halves. Quadratic multipliers
/// with nodal sign conditions let the pressure oscillate from node to node (the
/// corner functions change sign along the edge); the piecewise-linear ones keep
/// Σ Φ_i = 1, so a uniform pressure is still transmitted exactly.
fn mult01(n_nodes: usize, xi: f64) -> [f64; 3] {
    if n_nodes == 2 {
        [1.0 - xi, xi, 0.0]
    } else {
        [1.0 - xi, 0.0, xi]
    }
}

/// Point and tangent of an edge at ξ.
fn edge_point(pts: &[[f64; 2]], xi: f64) -> ([f64; 2], [f64; 2]) {
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

/// Where the ray x + t n meets the master surface.
struct Hit {
    t: f64,
    edge: usize,
    xi: f64,
}

/// The facing master point nearest along the ray (|t| ≤ limit), if any.
fn cast(master: &Surface, x: [f64; 2], n: [f64; 2], limit: f64) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (k, e) in master.edges.iter().enumerate() {
        let pts: Vec<[f64; 2]> = e.nodes().map(|i| master.mesh.nodes[i]).collect();
        let (pa, pb) = (pts[0], pts[pts.len() - 1]);
        // Only a master edge that faces the slave point can be touched by it.
        let chord = [pb[0] - pa[0], pb[1] - pa[1]];
        if cross(chord, n) <= 0.0 {
            // Outward normal of the chord is (dy, −dx); facing means n · n_m < 0,
            // i.e. n_x dy − n_y dx < 0, i.e. cross(chord, n) > 0.
            continue;
        }
        // The chord pieces (two for a T6 edge) locate the hit; Newton on the
        // isoparametric curve refines it.
        let pieces: &[(usize, usize, f64, f64)] = if pts.len() == 2 {
            &[(0, 1, 0.0, 1.0)]
        } else {
            &[(0, 1, 0.0, 0.5), (1, 2, 0.5, 1.0)]
        };
        for &(i, j, xa, xb) in pieces {
            let d = [pts[j][0] - pts[i][0], pts[j][1] - pts[i][1]];
            let den = cross(n, d);
            if den.abs() <= 1e-14 * (d[0].abs() + d[1].abs()) {
                continue;
            }
            let r = [pts[i][0] - x[0], pts[i][1] - x[1]];
            let s = cross(r, n) / den;
            const SLACK: f64 = 1e-10;
            if !(-SLACK..=1.0 + SLACK).contains(&s) {
                continue;
            }
            let mut xi = (xa + s.clamp(0.0, 1.0) * (xb - xa)).clamp(0.0, 1.0);
            if pts.len() == 3 {
                for _ in 0..4 {
                    let (p, tan) = edge_point(&pts, xi);
                    let f = cross([p[0] - x[0], p[1] - x[1]], n);
                    let df = cross(tan, n);
                    if df.abs() < 1e-300 {
                        break;
                    }
                    xi = (xi - f / df).clamp(0.0, 1.0);
                }
            }
            let (p, _) = edge_point(&pts, xi);
            let t = (p[0] - x[0]) * n[0] + (p[1] - x[1]) * n[1];
            if t.abs() <= limit && best.as_ref().is_none_or(|b| t.abs() < b.t.abs()) {
                best = Some(Hit { t, edge: k, xi });
            }
        }
    }
    best
}

/// Adds c · v to the coefficient of `node` of `body` in `terms`.
fn add(terms: &mut Vec<Term>, body: usize, node: usize, v: [f64; 2], c: f64) {
    let coef = [c * v[0], c * v[1]];
    match terms.iter_mut().find(|t| t.body == body && t.node == node) {
        Some(t) => {
            t.coef[0] += coef[0];
            t.coef[1] += coef[1];
        }
        None => terms.push(Term { body, node, coef }),
    }
}

/// The master side of a hit: − Σ M_k(ξ) n · u^b_k, times `scale`.
fn add_master(terms: &mut Vec<Term>, master: &Surface, hit: &Hit, n: [f64; 2], scale: f64) {
    let e = &master.edges[hit.edge];
    let nodes: Vec<usize> = e.nodes().collect();
    let (m, _) = shape01(nodes.len(), hit.xi);
    for (k, &node) in nodes.iter().enumerate() {
        if m[k] != 0.0 {
            add(terms, master.body, node, n, -scale * m[k]);
        }
    }
}

pub fn node_to_segment(slave: &Surface, master: &Surface, limit: f64) -> Rows {
    let mut out = Rows {
        rows: Vec::new(),
        pruned: 0,
    };
    for bn in boundary_nodes(slave.mesh, slave.edges) {
        let x = slave.mesh.nodes[bn.node];
        let Some(hit) = cast(master, x, bn.normal, limit) else {
            out.pruned += 1;
            continue;
        };
        let mut terms = vec![Term {
            body: slave.body,
            node: bn.node,
            coef: bn.normal,
        }];
        add_master(&mut terms, master, &hit, bn.normal, 1.0);
        out.rows.push(Row {
            node: bn.node,
            normal: bn.normal,
            weight: bn.weight,
            terms,
            gap: hit.t,
        });
    }
    out
}

/// 4-point Gauss–Legendre on [−1, 1] (exact to degree 7).
const GAUSS4: [[f64; 2]; 4] = [
    [-0.861_136_311_594_052_6, 0.347_854_845_137_453_85],
    [-0.339_981_043_584_856_26, 0.652_145_154_862_546_2],
    [0.339_981_043_584_856_26, 0.652_145_154_862_546_2],
    [0.861_136_311_594_052_6, 0.347_854_845_137_453_85],
];

#[derive(Default)]
struct Acc {
    weight: f64,
    gap: f64,
    normal: [f64; 2],
    terms: Vec<Term>,
}

pub fn mortar(slave: &Surface, master: &Surface, limit: f64) -> Rows {
    let master_nodes: Vec<[f64; 2]> = {
        let mut seen = std::collections::HashSet::new();
        master
            .edges
            .iter()
            .flat_map(|e| e.nodes())
            .filter(|&i| seen.insert(i))
            .map(|i| master.mesh.nodes[i])
            .collect()
    };
    let mut order: Vec<usize> = Vec::new();
    let mut acc: HashMap<usize, Acc> = HashMap::new();
    for e in slave.edges {
        let nodes: Vec<usize> = e.nodes().collect();
        let pts: Vec<[f64; 2]> = nodes.iter().map(|&i| slave.mesh.nodes[i]).collect();
        let (pa, pb) = (pts[0], pts[pts.len() - 1]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        // Break points: where master nodes project onto the slave edge, so that
        // each sub-interval sees one smooth piece of the master interpolation.
        let mut breaks = if nodes.len() == 3 {
            vec![0.0, 0.5, 1.0]
        } else {
            vec![0.0, 1.0]
        };
        for y in &master_nodes {
            let xi = ((y[0] - pa[0]) * d[0] + (y[1] - pa[1]) * d[1]) / len2;
            if xi > 0.0 && xi < 1.0 {
                breaks.push(xi);
            }
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
        for w in breaks.windows(2) {
            let (x0, x1) = (w[0], w[1]);
            for g in &GAUSS4 {
                let xi = x0 + 0.5 * (g[0] + 1.0) * (x1 - x0);
                let (x, tan) = edge_point(&pts, xi);
                let jac = (tan[0] * tan[0] + tan[1] * tan[1]).sqrt();
                let n = [tan[1] / jac, -tan[0] / jac];
                let Some(hit) = cast(master, x, n, limit) else {
                    continue;
                };
                let omega = 0.5 * g[1] * (x1 - x0) * jac;
                let (sn, _) = shape01(nodes.len(), xi);
                let phi = mult01(nodes.len(), xi);
                for (i, &node) in nodes.iter().enumerate() {
                    let wi = omega * phi[i];
                    if wi == 0.0 {
                        continue;
                    }
                    let a = acc.entry(node).or_insert_with(|| {
                        order.push(node);
                        Acc::default()
                    });
                    a.weight += wi;
                    a.gap += wi * hit.t;
                    a.normal[0] += wi * n[0];
                    a.normal[1] += wi * n[1];
                    for (j, &nj) in nodes.iter().enumerate() {
                        if sn[j] != 0.0 {
                            add(&mut a.terms, slave.body, nj, n, wi * sn[j]);
                        }
                    }
                    add_master(&mut a.terms, master, &hit, n, wi);
                }
            }
        }
    }
    let full: HashMap<usize, f64> = boundary_nodes(slave.mesh, slave.edges)
        .into_iter()
        .map(|b| (b.node, b.weight))
        .collect();
    let mut out = Rows {
        rows: Vec::new(),
        pruned: full.len() - order.len(),
    };
    for node in order {
        let a = acc.remove(&node).expect("accumulated");
        // A node whose shape function barely overlaps the master (or whose
        // quadratic shape weight cancels there) has no well-defined pressure.
        if a.weight <= 1e-9 * full[&node] {
            out.pruned += 1;
            continue;
        }
        let gap = a.gap / a.weight;
        if gap > limit {
            out.pruned += 1;
            continue;
        }
        let nl = (a.normal[0] * a.normal[0] + a.normal[1] * a.normal[1]).sqrt();
        let inv = 1.0 / a.weight;
        out.rows.push(Row {
            node,
            normal: [a.normal[0] / nl, a.normal[1] / nl],
            weight: a.weight,
            terms: a
                .terms
                .into_iter()
                .map(|t| Term {
                    coef: [t.coef[0] * inv, t.coef[1] * inv],
                    ..t
                })
                .collect(),
            gap,
        });
    }
    out
}
