//! Contact candidates: one row of B u ≤ g per candidate node.
//!
//! Against a rigid obstacle (one row per boundary node of the pair)
//!
//! ```text
//! n_i · u_i ≤ s_i − n_i · ū_i     (ū: prescribed part of the displacement)
//! ```
//!
//! on the free DOFs; against another body, the rows of `two_body`. Every row is
//! first written as nodal terms Σ c_k · u_k over the nodes it touches (fixed
//! components included), from which the free-DOF row, the prescribed part of
//! the gap, the rigid-mode coefficients and the nodal contact forces all follow.
//! Candidates whose gap cannot close (no intersection, or a gap beyond
//! `prune_gap_ratio` of the body size) are dropped and counted.

use super::foundation::{self, FoundationRow};
use super::gap::gap_along_normal;
use super::two_body::{self, Surface};
use crate::fem::assembly::{DofMap, FIXED};
use crate::mesh::{boundary::boundary_nodes, Mesh2d};
use crate::proto::Discretization;
use crate::scene::{Scene, Target};

#[derive(Debug, Clone)]
pub struct Candidate {
    pub pair: usize,
    pub body: usize,
    pub node: usize,
    pub x: [f64; 2],
    pub normal: [f64; 2],
    /// Tributary length ∫ N_i ds.
    pub weight: f64,
    /// The row over nodes: Σ coef · u_node (fixed components included).
    pub terms: Vec<Term>,
    /// Free DOFs and their coefficients in the row.
    pub row: Vec<(usize, f64)>,
    /// Right-hand side of the row (gap less the prescribed motion of the body,
    /// plus the prescribed motion of a punch).
    pub g: f64,
    /// For a punch: its obstacle index and the row c of −C, so that the
    /// constraint reads n·u − c·(α1, α2, θ) ≤ s: c = (n_x, n_y, (x − x_r) n_y − (y − y_r) n_x).
    pub punch: Option<(usize, [f64; 3])>,
    /// For a row on a foundation: which one, the row's panel and projection.
    pub foundation: Option<FoundationRow>,
}

/// One node's share of a candidate row; the contact force the row's
/// multiplier λ puts on that node is −λ · coef.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Term {
    pub body: usize,
    pub node: usize,
    pub coef: [f64; 2],
}

/// Splits nodal terms into the free-DOF row and the prescribed part, which
/// moves to the right-hand side: returns (row, s − Σ coef · ū).
/// Whether a row with no free DOF still constrains something: its node is held
/// by a virtual support of a body whose rigid modes are free (they move it). A
/// node held by real supports does not move at all: its row is pruned.
pub fn moves_rigidly(terms: &[Term], dofs: &DofMap) -> bool {
    terms.iter().any(|t| {
        let (x, y) = (dofs.dof(t.body, t.node, 0), dofs.dof(t.body, t.node, 1));
        dofs.rigid
            .iter()
            .any(|r| r.body == t.body && (r.virtual_dofs.contains(&x) || r.virtual_dofs.contains(&y)))
    })
}

/// Nodal terms, free-DOF row and right-hand side of a row.
pub type NodeRow = (Vec<Term>, Vec<(usize, f64)>, f64);

/// The one-node row n · u_node ≤ s against something that does not move with
/// the body's DOFs (an obstacle, a foundation); None when the gap cannot close
/// (beyond `limit`) or the node is fully prescribed.
pub fn node_row(body: usize, node: usize, normal: [f64; 2], s: f64, limit: f64, dofs: &DofMap) -> Option<NodeRow> {
    if s > limit {
        return None;
    }
    let terms = vec![Term {
        body,
        node,
        coef: normal,
    }];
    let (row, g) = free_row(&terms, dofs, s);
    (!row.is_empty() || moves_rigidly(&terms, dofs)).then_some((terms, row, g))
}

pub fn free_row(terms: &[Term], dofs: &DofMap, s: f64) -> (Vec<(usize, f64)>, f64) {
    let mut row: Vec<(usize, f64)> = Vec::with_capacity(2 * terms.len());
    let mut g = s;
    for t in terms {
        for c in 0..2 {
            let d = dofs.dof(t.body, t.node, c);
            let coef = t.coef[c];
            if dofs.free[d] == FIXED {
                g -= coef * dofs.prescribed[d];
            } else if coef != 0.0 {
                match row.iter_mut().find(|e| e.0 == dofs.free[d]) {
                    Some(e) => e.1 += coef,
                    None => row.push((dofs.free[d], coef)),
                }
            }
        }
    }
    (row, g)
}

#[derive(Debug, Clone, Default)]
pub struct ConstraintSet {
    pub candidates: Vec<Candidate>,
    /// Pruned candidates per pair.
    pub pruned: Vec<usize>,
}

impl ConstraintSet {
    pub fn len(&self) -> usize {
        self.candidates.len()
    }
    pub fn is_empty(&self) -> bool {
        self.candidates.is_empty()
    }
    /// Distinct free DOFs touched by any row, in first-use order.
    pub fn dofs(&self) -> Vec<usize> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for c in &self.candidates {
            for &(d, _) in &c.row {
                if seen.insert(d) {
                    out.push(d);
                }
            }
        }
        out
    }
    /// B x for x on the free DOFs.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        self.candidates
            .iter()
            .map(|c| c.row.iter().map(|&(d, v)| v * x[d]).sum())
            .collect()
    }
    /// Accumulates Bᵀ λ into y.
    pub fn apply_transpose_into(&self, lambda: &[f64], y: &mut [f64]) {
        for (c, &l) in self.candidates.iter().zip(lambda) {
            for &(d, v) in &c.row {
                y[d] += v * l;
            }
        }
    }
    pub fn g(&self) -> Vec<f64> {
        self.candidates.iter().map(|c| c.g).collect()
    }

    /// The load-controlled punch motions (obstacle, component, load) present in
    /// the rows, and the matrix C_F (m × their number) with C_Fᵀλ = −P_F their
    /// equilibrium and −C_F β_F their share of the rows.
    pub fn punch_block(&self, scene: &Scene) -> (Vec<(usize, usize, f64)>, faer::Mat<f64>) {
        let mut free = Vec::new();
        for (o, ob) in scene.obstacles.iter().enumerate() {
            if let Some(pu) = &ob.punch {
                if !self.candidates.iter().any(|c| c.punch.is_some_and(|p| p.0 == o)) {
                    continue;
                }
                for (k, ctl) in pu.controls.iter().enumerate() {
                    if let crate::proto::Control::Load(v) = ctl {
                        free.push((o, k, *v));
                    }
                }
            }
        }
        let c = faer::Mat::<f64>::from_fn(self.len(), free.len(), |i, j| match self.candidates[i].punch {
            Some((o, row)) if o == free[j].0 => row[free[j].1],
            _ => 0.0,
        });
        (free, c)
    }
}

pub fn build(scene: &Scene, meshes: &[Mesh2d], dofs: &DofMap) -> ConstraintSet {
    let mut set = ConstraintSet::default();
    for (p, pair) in scene.pairs.iter().enumerate() {
        // Relative to the pair's own bodies, not to the scene's length scale, so
        // that an unrelated body elsewhere changes nothing.
        let limit = scene.settings.prune_gap_ratio
            * match &pair.target {
                Target::Obstacle(_) | Target::Foundation(_) => meshes[pair.body].size(),
                Target::Body { body, .. } => meshes[pair.body].size().max(meshes[*body].size()),
            };
        let pruned = match &pair.target {
            Target::Obstacle(o) => against_obstacle(scene, p, *o, meshes, dofs, limit, &mut set.candidates),
            Target::Foundation(f) => foundation::rows(scene, p, *f, meshes, dofs, &mut set.candidates),
            Target::Body {
                body,
                edges,
                discretization,
            } => {
                let master = Surface {
                    body: *body,
                    mesh: &meshes[*body],
                    edges: &meshes[*body].edge_sets[edges],
                };
                let slave = Surface {
                    body: pair.body,
                    mesh: &meshes[pair.body],
                    edges: &meshes[pair.body].edge_sets[&pair.edges],
                };
                let rows = match discretization {
                    Discretization::NodeToSegment => two_body::node_to_segment(&slave, &master, limit),
                    Discretization::Mortar => two_body::mortar(&slave, &master, limit),
                };
                let mut pruned = rows.pruned;
                for r in rows.rows {
                    let (row, g) = free_row(&r.terms, dofs, r.gap);
                    if row.is_empty() && !moves_rigidly(&r.terms, dofs) {
                        pruned += 1;
                        continue;
                    }
                    set.candidates.push(Candidate {
                        pair: p,
                        body: pair.body,
                        node: r.node,
                        x: meshes[pair.body].nodes[r.node],
                        normal: r.normal,
                        weight: r.weight,
                        terms: r.terms,
                        row,
                        g,
                        punch: None,
                        foundation: None,
                    });
                }
                pruned
            }
        };
        set.pruned.push(pruned);
    }
    set
}

/// Node-to-rigid-obstacle rows of pair `p`; returns the number pruned.
fn against_obstacle(
    scene: &Scene,
    p: usize,
    obstacle: usize,
    meshes: &[Mesh2d],
    dofs: &DofMap,
    limit: f64,
    out: &mut Vec<Candidate>,
) -> usize {
    let pair = &scene.pairs[p];
    let mesh = &meshes[pair.body];
    let shape = &scene.obstacles[obstacle].shape;
    let mut pruned = 0;
    for bn in boundary_nodes(mesh, &mesh.edge_sets[&pair.edges]) {
        let x = mesh.nodes[bn.node];
        let row =
            gap_along_normal(shape, x, bn.normal).and_then(|s| node_row(pair.body, bn.node, bn.normal, s, limit, dofs));
        let Some((terms, row, mut g)) = row else {
            pruned += 1;
            continue;
        };
        let punch = scene.obstacles[obstacle].punch.as_ref().map(|pu| {
            let (dx, dy) = (x[0] - pu.reference[0], x[1] - pu.reference[1]);
            let c = [bn.normal[0], bn.normal[1], dx * bn.normal[1] - dy * bn.normal[0]];
            for (k, ctl) in pu.controls.iter().enumerate() {
                if let crate::proto::Control::Displacement(v) = ctl {
                    g += c[k] * v;
                }
            }
            (obstacle, c)
        });
        out.push(Candidate {
            punch,
            pair: p,
            body: pair.body,
            node: bn.node,
            x,
            normal: bn.normal,
            weight: bn.weight,
            terms,
            row,
            g,
            foundation: None,
        });
    }
    pruned
}
