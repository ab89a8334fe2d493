//! Contact candidates: one row of B u ≤ g per candidate node.
//!
//! Each pair's target (rigid obstacle: `gap`; another body: `two_body`) says
//! what a surface point sees, and `rows` turns that into nodal or mortar rows
//! Σ c_k · u_k ≤ g. On the free DOFs a row reads
//!
//! ```text
//! Σ c_k · u_k ≤ g − Σ c_k · ū_k     (ū: prescribed part of the displacement)
//! ```
//!
//! Every row is
//! first written as nodal terms Σ c_k · u_k over the nodes it touches (fixed
//! components included), from which the free-DOF row, the prescribed part of
//! the gap, the rigid-mode coefficients and the nodal contact forces all follow.
//! Candidates whose gap cannot close (no intersection, or a gap beyond
//! `prune_gap_ratio` of the body size) are dropped and counted.

use super::foundation::{self, FoundationRow};
use super::gap::{closest, gap_along_normal};
use super::rows::{self, punch_coefficients, Rows, Seen, Surface};
use super::two_body;
use crate::fem::assembly::{DofMap, FIXED};
use crate::mesh::{Mesh2d, Order};
use crate::scene::{Discretization, GapMeasure};
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

/// Splits nodal terms into the free-DOF row and the prescribed part, which
/// moves to the right-hand side: returns (row, s − Σ coef · ū).
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
    /// Whether every row acts on one node along a unit direction and no two rows
    /// share a DOF: what the full-system active set needs to turn each row into
    /// one rotated coordinate. Mortar rows (T6) and two-body rows are not.
    pub fn rows_are_nodal(&self) -> bool {
        let mut seen = std::collections::HashSet::new();
        self.candidates.iter().all(|c| {
            let unit = match *c.row.as_slice() {
                [(_, v)] => v != 0.0,
                [(a, nx), (b, ny)] => a != b && ((nx * nx + ny * ny) - 1.0).abs() < 1e-12,
                _ => false,
            };
            unit && c.terms.len() == 1 && c.row.iter().all(|&(d, _)| seen.insert(d))
        })
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
    /// Accumulates |B|ᵀ |λ| into y: the size of the terms Bᵀλ sums.
    pub fn apply_abs_transpose_into(&self, lambda: &[f64], y: &mut [f64]) {
        for (c, &l) in self.candidates.iter().zip(lambda) {
            for &(d, v) in &c.row {
                y[d] += (v * l).abs();
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
                    if let crate::scene::Control::Load(v) = ctl {
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
    let signed = scene.settings.gap == GapMeasure::SignedDistance;
    for (p, pair) in scene.pairs.iter().enumerate() {
        // Relative to the pair's own bodies, not to the scene's length scale, so
        // that an unrelated body elsewhere changes nothing.
        let limit = scene.settings.prune_gap_ratio
            * match &pair.target {
                Target::Obstacle(_) | Target::Foundation(_) => meshes[pair.body].size(),
                Target::Body { body, .. } => meshes[pair.body].size().max(meshes[*body].size()),
            };
        let slave = Surface {
            body: pair.body,
            mesh: &meshes[pair.body],
            edges: &meshes[pair.body].edge_sets[&pair.edges],
        };
        let rows = match &pair.target {
            Target::Foundation(f) => {
                set.pruned
                    .push(foundation::rows(scene, p, *f, meshes, dofs, &mut set.candidates));
                continue;
            }
            Target::Obstacle(o) => {
                let obstacle = &scene.obstacles[*o];
                let see = |x: [f64; 2], n_body: [f64; 2]| -> Option<Seen> {
                    let (gap, dir, y) = if signed {
                        let c = closest(&obstacle.shape, x)?;
                        (c.distance, [-c.normal[0], -c.normal[1]], c.point)
                    } else {
                        (gap_along_normal(&obstacle.shape, x, n_body)?, n_body, x)
                    };
                    Some(Seen {
                        gap,
                        dir,
                        other: Vec::new(),
                        punch: obstacle
                            .punch
                            .as_ref()
                            .map(|pu| punch_coefficients(y, pu.reference, dir)),
                    })
                };
                if slave.mesh.order == Order::T6 {
                    // Nodal rows on quadratic faces let the pressure alternate
                    // between corners and midsides; the corners' dual mortar
                    // rows do not (see `rows`). Gauss points on each half of an
                    // edge: the normals turn along the quadratic edge.
                    rows::mortar(&slave, &see, limit, &|_| vec![0.0, 0.5, 1.0])
                } else {
                    rows::nodal(&slave, &see, limit)
                }
            }
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
                let projection = two_body::Projection::new(&master);
                let see = |x: [f64; 2], n: [f64; 2]| {
                    if signed {
                        projection.see(x, n, limit)
                    } else {
                        two_body::along_normal(&master, x, n, limit)
                    }
                };
                match discretization {
                    Discretization::NodeToSegment => rows::nodal(&slave, &see, limit),
                    Discretization::Mortar => rows::mortar(&slave, &see, limit, &two_body::mortar_breaks(&master)),
                }
            }
        };
        let obstacle = match pair.target {
            Target::Obstacle(o) => Some(o),
            _ => None,
        };
        set.pruned.push(push_rows(
            p,
            pair.body,
            obstacle,
            rows,
            scene,
            meshes,
            dofs,
            &mut set.candidates,
        ));
    }
    set
}

/// Turns rows into candidates on the free DOFs; returns how many were pruned
/// (rows' own prunes, and rows whose nodes cannot move).
#[allow(clippy::too_many_arguments)]
fn push_rows(
    p: usize,
    body: usize,
    obstacle: Option<usize>,
    rows: Rows,
    scene: &Scene,
    meshes: &[Mesh2d],
    dofs: &DofMap,
    out: &mut Vec<Candidate>,
) -> usize {
    let mut pruned = rows.pruned;
    for r in rows.rows {
        let (row, mut g) = free_row(&r.terms, dofs, r.gap);
        if row.is_empty() && !moves_rigidly(&r.terms, dofs) {
            pruned += 1;
            continue;
        }
        // A prescribed punch motion moves the obstacle: it opens the gap by c · β.
        let punch = match (obstacle, r.punch) {
            (Some(o), Some(c)) => {
                if let Some(pu) = &scene.obstacles[o].punch {
                    for (k, ctl) in pu.controls.iter().enumerate() {
                        if let crate::scene::Control::Displacement(v) = ctl {
                            g += c[k] * v;
                        }
                    }
                }
                Some((o, c))
            }
            _ => None,
        };
        out.push(Candidate {
            pair: p,
            body,
            node: r.node,
            x: meshes[body].nodes[r.node],
            normal: r.normal,
            weight: r.weight,
            terms: r.terms,
            row,
            g,
            punch,
            foundation: None,
        });
    }
    pruned
}
