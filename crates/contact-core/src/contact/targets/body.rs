//! Another deformable body as a contact target: what a point of one body's
//! surface sees of the other's, and the rows that follow.
//!
//! The non-mortar ("slave") side a carries the pressure; a point x of it faces
//! the point y of the other (mortar or "master") body b. Linearized about the
//! reference configuration, the two surfaces do not interpenetrate where
//!
//! ```text
//! n · u^a(x) − n · u^b(y) ≤ g(x)
//! ```
//!
//! (the theory's u^a·n^a + u^b·n^b ≤ gap with n^b = −n^a). With the default
//! signed distance (`settings.gap`), y is the point of b's surface facing x
//! along b's (continuous) normal field, g the signed distance to it and
//! n = −n_b(y): the first-order linearization of d_b(x + u^a − u^b(y)) ≥ 0,
//! which on a stiff master reduces to the rigid obstacle's rows. With `body_normal`, y is where the slave normal meets b
//! (y = x + g n_a) and n = n_a, the seed's form. On a flat interface the two
//! coincide, so both pass the contact patch test with mortar rows.
//!
//! The rows themselves (node-to-segment: one per slave node; mortar: weighted
//! by the slave multipliers and integrated, split at the projections of the
//! master nodes) are built by `contact::rows`.

use std::collections::HashMap;

use crate::contact::constraints::{Candidate, Link};
use crate::contact::rows::{self, edge_point, shape01, Seen, Surface, T6Multiplier};
use crate::fem::DofMap;
use crate::mesh::boundary::boundary_nodes;
use crate::scene::{Discretization, GapMeasure, Scene};

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The master's nodes at an edge point, as (body, node, N_k(ξ)).
fn master_nodes(master: &Surface, edge: usize, xi: f64) -> Vec<(usize, usize, f64)> {
    let nodes: Vec<usize> = master.edges[edge].nodes().collect();
    let (m, _) = shape01(nodes.len(), xi);
    nodes
        .iter()
        .enumerate()
        .map(|(k, &node)| (master.body, node, m[k]))
        .collect()
}

fn edge_points(master: &Surface, edge: usize) -> Vec<[f64; 2]> {
    master.edges[edge].nodes().map(|i| master.mesh.nodes[i]).collect()
}

/// Whether a master edge faces a slave point of outward normal n: only a
/// facing edge can be touched (outward normals opposed).
fn faces(pts: &[[f64; 2]], n: [f64; 2]) -> bool {
    let (pa, pb) = (pts[0], pts[pts.len() - 1]);
    // Outward normal of the chord is (dy, −dx); facing means n · n_m < 0,
    // i.e. cross(chord, n) > 0.
    cross([pb[0] - pa[0], pb[1] - pa[1]], n) > 0.0
}

/// The facing master point nearest along the ray x + t n (|t| ≤ limit): the
/// body-normal form.
pub fn along_normal(master: &Surface, x: [f64; 2], n: [f64; 2], limit: f64) -> Option<Seen> {
    let mut best: Option<(f64, usize, f64)> = None;
    for k in 0..master.edges.len() {
        let pts = edge_points(master, k);
        if !faces(&pts, n) {
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
            if t.abs() <= limit && best.is_none_or(|b| t.abs() < b.0.abs()) {
                best = Some((t, k, xi));
            }
        }
    }
    let (t, edge, xi) = best?;
    Some(Seen {
        gap: t,
        dir: n,
        other: master_nodes(master, edge, xi),
        punch: None,
    })
}

/// The master surface prepared for signed-distance queries, with a
/// continuous normal field: its nodal normals (`boundary_nodes`: exact on a
/// discretized circle or line) interpolated along each edge.
///
/// The faceted surface's own ∇d jumps by the facet angle h/R at every master
/// node; those jumps move a slave node's gap by u_t h/R and, through the
/// contact stiffness E*/h, its pressure by several percent (node-to-segment on
/// the two-cylinder example oscillated by ±5 % of the pressure). With the
/// continuous field the projection point y solves (x − y(ξ)) × n(ξ) = 0 and
/// g = (x − y) · n̂(ξ): on a flat master this is the closest point.
pub struct Projection<'a> {
    master: &'a Surface<'a>,
    normals: HashMap<usize, [f64; 2]>,
}

/// Relative reach past the end of an edge that still counts as on it.
const END_SLACK: f64 = 1e-9;

impl<'a> Projection<'a> {
    pub fn new(master: &'a Surface<'a>) -> Self {
        let normals = boundary_nodes(master.mesh, master.edges, master.axisymmetric())
            .into_iter()
            .map(|b| (b.node, b.normal))
            .collect();
        Self { master, normals }
    }

    /// Point, tangent, normal field and its derivative along edge k at ξ.
    fn at(&self, k: usize, xi: f64) -> ([f64; 2], [f64; 2], [f64; 2], [f64; 2]) {
        let e = &self.master.edges[k];
        let nodes: Vec<usize> = e.nodes().collect();
        let (sn, dn) = shape01(nodes.len(), xi);
        let (mut p, mut t, mut n, mut dnv) = ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
        for (j, &node) in nodes.iter().enumerate() {
            let (x, nn) = (self.master.mesh.nodes[node], self.normals[&node]);
            for c in 0..2 {
                p[c] += sn[j] * x[c];
                t[c] += dn[j] * x[c];
                n[c] += sn[j] * nn[c];
                dnv[c] += dn[j] * nn[c];
            }
        }
        (p, t, n, dnv)
    }

    /// ξ on edge k where the normal field through x meets it (unclamped, so
    /// that a foot beyond the edge's ends is recognised), by Newton on
    /// f(ξ) = (x − y(ξ)) × n(ξ) from the chord's projection.
    fn foot(&self, k: usize, x: [f64; 2]) -> f64 {
        let pts = edge_points(self.master, k);
        let (pa, pb) = (pts[0], pts[pts.len() - 1]);
        let c = [pb[0] - pa[0], pb[1] - pa[1]];
        let mut xi = dot([x[0] - pa[0], x[1] - pa[1]], c) / dot(c, c);
        for _ in 0..8 {
            let (p, t, n, dn) = self.at(k, xi);
            let r = [x[0] - p[0], x[1] - p[1]];
            let f = cross(r, n);
            let df = cross([-t[0], -t[1]], n) + cross(r, dn);
            if df.abs() < 1e-300 {
                break;
            }
            let step = f / df;
            xi -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        xi
    }

    /// The facing master point along the normal field and the signed distance
    /// to it: the signed-distance form.
    pub fn see(&self, x: [f64; 2], n_slave: [f64; 2], limit: f64) -> Option<Seen> {
        let mut best: Option<(f64, usize, f64, [f64; 2])> = None;
        for k in 0..self.master.edges.len() {
            if !faces(&edge_points(self.master, k), n_slave) {
                continue;
            }
            let xi = self.foot(k, x);
            if !(-END_SLACK..=1.0 + END_SLACK).contains(&xi) {
                continue;
            }
            let xi = xi.clamp(0.0, 1.0);
            let (p, t, n, _) = self.at(k, xi);
            let l = n[0].hypot(n[1]);
            let n = [n[0] / l, n[1] / l];
            let r = [x[0] - p[0], x[1] - p[1]];
            // Newton may stop on an edge whose normal line does not pass
            // through x (a far edge that merely faces the same way): only a
            // converged foot is a projection.
            if cross(r, n).abs() > 1e-8 * r[0].hypot(r[1]).max(t[0].hypot(t[1])) {
                continue;
            }
            let gap = dot(r, n);
            if gap.abs() <= limit && best.is_none_or(|b| gap.abs() < b.0.abs()) {
                best = Some((gap, k, xi, n));
            }
        }
        let (gap, k, xi, n) = best?;
        Some(Seen {
            gap,
            dir: [-n[0], -n[1]],
            other: master_nodes(self.master, k, xi),
            punch: None,
        })
    }
}

/// Break points of a slave edge for mortar integration: where the master
/// nodes project onto its chord, so that each sub-interval sees one smooth
/// piece of the master interpolation.
pub fn mortar_breaks(master: &Surface) -> impl Fn(&[[f64; 2]]) -> Vec<f64> {
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
    move |pts: &[[f64; 2]]| {
        let (pa, pb) = (pts[0], pts[pts.len() - 1]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let mut breaks = if pts.len() == 3 {
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
        breaks
    }
}

/// Rows of the slave surface against the master edge set `edges` of `body`
/// into `out`; returns how many were pruned.
#[allow(clippy::too_many_arguments)]
pub fn rows(
    scene: &Scene,
    p: usize,
    slave: &Surface,
    master: &Surface,
    discretization: Discretization,
    limit: f64,
    dofs: &DofMap,
    out: &mut Vec<Candidate>,
) -> usize {
    let signed = scene.settings.gap == GapMeasure::SignedDistance;
    let projection = Projection::new(master);
    let see = |x: [f64; 2], n: [f64; 2]| {
        if signed {
            projection.see(x, n, limit)
        } else {
            along_normal(master, x, n, limit)
        }
    };
    let rows = match discretization {
        Discretization::NodeToSegment => rows::nodal(slave, &see, limit),
        Discretization::Mortar => rows::mortar(slave, T6Multiplier::Halves, &see, limit, &mortar_breaks(master)),
    };
    let mut pruned = rows.pruned;
    for r in rows.rows {
        match Candidate::try_new(p, slave.body, slave.mesh, r, dofs, Link::Fixed) {
            Some(c) => out.push(c),
            None => pruned += 1,
        }
    }
    pruned
}
