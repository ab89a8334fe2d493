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
//! which on a stiff master reduces to the rigid obstacle's rows. With `body_normal`, y is where the slave normal
//! meets b
//! (y = x + g n_a) and n = n_a, the seed's form. On a flat interface the two
//! coincide, so both pass the contact patch test with mortar rows.
//!
//! The rows themselves (node-to-segment: one per slave node; mortar: weighted
//! by the slave multipliers and integrated, split at the projections of the
//! master nodes) are built by `contact::rows`.
//!
//! Length: about 520 lines, 125 of them the test that the tree's facing point
//! is the scan's on random surfaces, ties included; it needs the projection's
//! private scan and per-edge answer, so it lives beside them.

use std::collections::HashMap;

use super::edge_tree::{edge_box, Aabb, EdgeTree};
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

/// A master edge as the queries read it, gathered once: no allocation and
/// no hashing per query (the scan it replaces spent a third of the
/// two-cylinder run in `HashMap` lookups of the nodal normals and in
/// collecting each edge's nodes into a fresh `Vec`, measured with `perf`).
struct EdgeGeom {
    /// Nodes in edge order a, (mid), b; the first `len` slots are used.
    nodes: [usize; 3],
    pts: [[f64; 2]; 3],
    /// The continuous normal field's nodal values.
    normals: [[f64; 2]; 3],
    len: usize,
}

impl EdgeGeom {
    fn pts(&self) -> &[[f64; 2]] {
        &self.pts[..self.len]
    }

    /// Whether the edge faces a slave point of outward normal n: only a
    /// facing edge can be touched (outward normals opposed).
    fn faces(&self, n: [f64; 2]) -> bool {
        let (pa, pb) = (self.pts[0], self.pts[self.len - 1]);
        // Outward normal of the chord is (dy, −dx); facing means n · n_m < 0,
        // i.e. cross(chord, n) > 0.
        cross([pb[0] - pa[0], pb[1] - pa[1]], n) > 0.0
    }

    /// The master's nodes at ξ, as (body, node, N_k(ξ)).
    fn weights(&self, body: usize, xi: f64) -> Vec<(usize, usize, f64)> {
        let (m, _) = shape01(self.len, xi);
        (0..self.len).map(|k| (body, self.nodes[k], m[k])).collect()
    }
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
///
/// Which edge: of the facing edges with a converged foot on them, the one
/// with the least |g|, the first in edge order on a tie. The edges are found
/// through `EdgeTree` rather than by a scan of all of them (a scan made the
/// contact rows cost O(slave points × master edges): 0.50 s of the 1.0 s
/// two-cylinder run at 88k DOF); the tree's answer is the scan's, ties
/// included (`the_tree_sees_what_the_scan_sees`).
pub struct Projection<'a> {
    master: &'a Surface<'a>,
    edges: Vec<EdgeGeom>,
    tree: EdgeTree,
    /// Diagonal of the master surface's box: the scale of the search's slack.
    scale: f64,
}

/// Relative reach past the end of an edge that still counts as on it.
const END_SLACK: f64 = 1e-9;

impl<'a> Projection<'a> {
    pub fn new(master: &'a Surface<'a>) -> Self {
        let normals: HashMap<usize, [f64; 2]> = boundary_nodes(master.mesh, master.edges, master.axisymmetric())
            .into_iter()
            .map(|b| (b.node, b.normal))
            .collect();
        let edges: Vec<EdgeGeom> = master
            .edges
            .iter()
            .map(|e| {
                let mut g = EdgeGeom {
                    nodes: [0; 3],
                    pts: [[0.0; 2]; 3],
                    normals: [[0.0; 2]; 3],
                    len: 0,
                };
                for node in e.nodes() {
                    g.nodes[g.len] = node;
                    g.pts[g.len] = master.mesh.nodes[node];
                    g.normals[g.len] = normals[&node];
                    g.len += 1;
                }
                g
            })
            .collect();
        let boxes: Vec<Aabb> = edges.iter().map(|g| edge_box(g.pts())).collect();
        let whole = boxes.iter().fold(
            [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
            |a, b| [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])],
        );
        let scale = if edges.is_empty() {
            0.0
        } else {
            (whole[2] - whole[0]).hypot(whole[3] - whole[1])
        };
        Self {
            master,
            tree: EdgeTree::new(&boxes),
            edges,
            scale,
        }
    }

    /// Point, tangent, normal field and its derivative along edge k at ξ.
    fn at(&self, k: usize, xi: f64) -> ([f64; 2], [f64; 2], [f64; 2], [f64; 2]) {
        let g = &self.edges[k];
        let (sn, dn) = shape01(g.len, xi);
        let (mut p, mut t, mut n, mut dnv) = ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
        for j in 0..g.len {
            let (x, nn) = (g.pts[j], g.normals[j]);
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
        let g = &self.edges[k];
        let (pa, pb) = (g.pts[0], g.pts[g.len - 1]);
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

    /// What edge k answers for x: the signed distance along the normal field,
    /// ξ and the unit normal there, if the edge faces x and its foot is a
    /// converged point of it.
    fn project(&self, k: usize, x: [f64; 2], n_slave: [f64; 2]) -> Option<(f64, f64, [f64; 2])> {
        if !self.edges[k].faces(n_slave) {
            return None;
        }
        let xi = self.foot(k, x);
        if !(-END_SLACK..=1.0 + END_SLACK).contains(&xi) {
            return None;
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
            return None;
        }
        Some((dot(r, n), xi, n))
    }

    fn seen(&self, best: Option<(f64, usize, f64, [f64; 2])>) -> Option<Seen> {
        let (gap, k, xi, n) = best?;
        Some(Seen {
            gap,
            dir: [-n[0], -n[1]],
            other: self.edges[k].weights(self.master.body, xi),
            punch: None,
        })
    }

    /// The facing master point along the normal field and the signed distance
    /// to it: the signed-distance form.
    ///
    /// An answer of edge k lies on k's curve, within |r| of x, and the foot
    /// test bounds |r| ≤ |g| (1 + 2e-8) + 2e-8 |y'(ξ)| with |y'| ≤ 2 `scale`:
    /// so the slack 1e-6 (|g| + `scale`) on the reach keeps every edge that
    /// could attain or tie the least |g| in the search.
    pub fn see(&self, x: [f64; 2], n_slave: [f64; 2], limit: f64) -> Option<Seen> {
        let slack = |g: f64| 1e-6 * (g + self.scale);
        let reach = limit + slack(limit);
        let mut best: Option<(f64, usize, f64, [f64; 2])> = None;
        self.tree.near(x, reach, |k| {
            if let Some((gap, xi, n)) = self.project(k, x, n_slave) {
                // Least |g|, then the first edge: the scan's order.
                if gap.abs() <= limit && best.is_none_or(|b| (gap.abs(), k) < (b.0.abs(), b.1)) {
                    best = Some((gap, k, xi, n));
                }
            }
            best.map_or(reach, |b| b.0.abs() + slack(b.0.abs()))
        });
        self.seen(best)
    }

    /// `see` by a scan of every edge, the reference the tree is tested
    /// against.
    #[cfg(test)]
    fn see_scan(&self, x: [f64; 2], n_slave: [f64; 2], limit: f64) -> Option<Seen> {
        let mut best: Option<(f64, usize, f64, [f64; 2])> = None;
        for k in 0..self.edges.len() {
            if let Some((gap, xi, n)) = self.project(k, x, n_slave) {
                if gap.abs() <= limit && best.is_none_or(|b| gap.abs() < b.0.abs()) {
                    best = Some((gap, k, xi, n));
                }
            }
        }
        self.seen(best)
    }

    /// The facing master point nearest along the ray x + t n (|t| ≤ limit):
    /// the body-normal form. A scan of every edge: a chord hit refined by
    /// Newton need not lie within |t| of x, so the tree's distance bound does
    /// not hold here (a setting, not the default).
    pub fn along_normal(&self, x: [f64; 2], n: [f64; 2], limit: f64) -> Option<Seen> {
        let mut best: Option<(f64, usize, f64)> = None;
        for (k, g) in self.edges.iter().enumerate() {
            if !g.faces(n) {
                continue;
            }
            let pts = g.pts();
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
                        let (p, tan) = edge_point(pts, xi);
                        let f = cross([p[0] - x[0], p[1] - x[1]], n);
                        let df = cross(tan, n);
                        if df.abs() < 1e-300 {
                            break;
                        }
                        xi = (xi - f / df).clamp(0.0, 1.0);
                    }
                }
                let (p, _) = edge_point(pts, xi);
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
            other: self.edges[edge].weights(self.master.body, xi),
            punch: None,
        })
    }

    /// Break points of a slave edge for mortar integration: where the master
    /// nodes project onto its chord, so that each sub-interval sees one smooth
    /// piece of the master interpolation. Only the master edges in the slab
    /// across the chord are read (`EdgeTree::across`); a node shared by two
    /// of them gives the same ξ twice, which the dedup removes as it removed
    /// nothing else.
    pub fn breaks(&self, pts: &[[f64; 2]]) -> Vec<f64> {
        let (pa, pb) = (pts[0], pts[pts.len() - 1]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let mut breaks = if pts.len() == 3 {
            vec![0.0, 0.5, 1.0]
        } else {
            vec![0.0, 1.0]
        };
        self.tree.across(pa, d, |k| {
            for y in self.edges[k].pts() {
                let xi = ((y[0] - pa[0]) * d[0] + (y[1] - pa[1]) * d[1]) / len2;
                if xi > 0.0 && xi < 1.0 {
                    breaks.push(xi);
                }
            }
        });
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
            projection.along_normal(x, n, limit)
        }
    };
    let rows = match discretization {
        Discretization::NodeToSegment => rows::nodal(slave, &see, limit),
        Discretization::Mortar => rows::mortar(
            slave,
            T6Multiplier::of(scene.settings.t6_multipliers),
            &see,
            limit,
            &|pts: &[[f64; 2]]| projection.breaks(pts),
        ),
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

#[cfg(test)]
mod tests {
    use super::super::edge_tree::tests::Rng;
    use super::*;
    use crate::mesh::{Edge, Mesh2d, Order};
    use crate::scene::Analysis;

    /// A wavy graded curve (edges 50× apart in length) followed by a flat run
    /// on binary fractions, whose shared nodes are exact ties between two
    /// edges; T3 or T6 (midsides on the curve), its edges in shuffled order.
    fn surface(rng: &mut Rng, t6: bool) -> Mesh2d {
        let mut xs: Vec<f64> = Vec::new();
        let mut x = 0.0;
        while x < 6.0 {
            xs.push(x);
            x += 0.004 + 0.2 * (x / 6.0).powi(2) * (0.5 + rng.uniform());
        }
        xs.extend((0..=8).map(|i| 6.0 + 0.25 * i as f64));
        let y = |x: f64| {
            if x < 6.0 {
                0.3 * (2.0 * x).sin() * (6.0 - x) / 6.0
            } else {
                0.0
            }
        };
        let mut nodes: Vec<[f64; 2]> = xs.iter().map(|&x| [x, y(x)]).collect();
        let mut edges: Vec<Edge> = (0..xs.len() - 1)
            .map(|i| {
                let mid = t6.then(|| {
                    let xm = 0.5 * (xs[i] + xs[i + 1]);
                    nodes.push([xm, y(xm)]);
                    nodes.len() - 1
                });
                Edge { a: i, b: i + 1, mid }
            })
            .collect();
        for i in (1..edges.len()).rev() {
            let j = (rng.uniform() * (i + 1) as f64) as usize;
            edges.swap(i, j.min(i));
        }
        Mesh2d {
            order: if t6 { Order::T6 } else { Order::T3 },
            nodes,
            elems: Vec::new(),
            edge_sets: [("s".to_string(), edges)].into_iter().collect(),
        }
    }

    fn same(a: &Option<Seen>, b: &Option<Seen>) -> bool {
        match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => a.gap.to_bits() == b.gap.to_bits() && a.dir == b.dir && a.other == b.other,
            _ => false,
        }
    }

    /// The tree's facing point is the scan's, bit for bit, ties between
    /// equidistant edges broken alike (the first edge in edge order): random
    /// points and slave normals around random graded surfaces, and points
    /// straight below the nodes of the flat run. The mortar breaks read from
    /// the slab are those of every master node.
    #[test]
    fn the_tree_sees_what_the_scan_sees() {
        let mut rng = Rng::new(3);
        let (mut found, mut ties) = (0, 0);
        for trial in 0..8 {
            let mesh = surface(&mut rng, trial % 2 == 1);
            let master = Surface {
                body: 1,
                mesh: &mesh,
                edges: &mesh.edge_sets["s"],
                analysis: Analysis::PlaneStrain,
            };
            let projection = Projection::new(&master);
            for q in 0..600 {
                let (x, n) = if q < 9 {
                    ([6.0 + 0.25 * q as f64, -0.01 * (1.0 + rng.uniform())], [0.0, 1.0])
                } else {
                    let a = std::f64::consts::PI * (0.1 + 0.8 * rng.uniform());
                    (
                        [10.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.5],
                        [a.cos(), a.sin()],
                    )
                };
                let limit = [0.05, 0.5, 10.0][q % 3];
                let (tree, scan) = (projection.see(x, n, limit), projection.see_scan(x, n, limit));
                assert!(same(&tree, &scan), "{x:?} {n:?}: tree {tree:?}, scan {scan:?}");
                found += usize::from(scan.is_some());
                if let Some(seen) = &scan {
                    let attaining = (0..projection.edges.len())
                        .filter_map(|k| projection.project(k, x, n))
                        .filter(|p| p.0.abs() == seen.gap.abs())
                        .count();
                    ties += usize::from(attaining > 1);
                }
            }
            let all: Vec<[f64; 2]> = {
                let mut seen = vec![false; mesh.nodes.len()];
                master
                    .edges
                    .iter()
                    .flat_map(|e| e.nodes())
                    .filter(|&i| !std::mem::replace(&mut seen[i], true))
                    .map(|i| mesh.nodes[i])
                    .collect()
            };
            for _ in 0..200 {
                let pa = [10.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.5];
                let pb = [pa[0] + 0.3 * rng.uniform() - 0.15, pa[1] + 0.3 * rng.uniform() - 0.15];
                let d = [pb[0] - pa[0], pb[1] - pa[1]];
                let len2 = d[0] * d[0] + d[1] * d[1];
                let mut want = vec![0.0, 1.0];
                want.extend(
                    all.iter()
                        .map(|y| ((y[0] - pa[0]) * d[0] + (y[1] - pa[1]) * d[1]) / len2)
                        .filter(|&xi| xi > 0.0 && xi < 1.0),
                );
                want.sort_by(f64::total_cmp);
                want.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
                assert_eq!(projection.breaks(&[pa, pb]), want, "chord {pa:?} → {pb:?}");
            }
        }
        // The comparison bites: most points see the surface, and the nodes of
        // the flat run are ties.
        assert!(found > 8 * 200 && ties >= 8 * 6, "{found} found, {ties} ties");
    }
}
