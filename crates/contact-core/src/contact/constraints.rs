//! The contact rows on the free DOFs: one row of B u ≤ g per candidate, what
//! the methods, the certificate and the post-processing read.
//!
//! Every row is first written as nodal terms Σ c_k · u_k over the nodes it
//! touches (`rows`), fixed components included; on the free DOFs it reads
//!
//! ```text
//! Σ c_k · u_k ≤ g − Σ c_k · ū_k     (ū: prescribed part of the displacement)
//! ```
//!
//! from which the free-DOF row, the prescribed part of the gap, the rigid-mode
//! coefficients and the nodal contact forces all follow.

use super::rows::{Row, Term};
use crate::fem::assembly::{DofMap, FIXED};
use crate::mesh::Mesh2d;
use crate::scene::{Control, Scene};

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
    /// What moves the far side of the row besides the bodies' DOFs.
    pub link: Link,
}

/// The far side of a row, where it is more than the bodies' DOFs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Link {
    /// A fixed obstacle or another body's surface.
    Fixed,
    /// A punch: its obstacle index and the row c of −C, so that the
    /// constraint reads n·u − c·(α1, α2, θ) ≤ s: c = (n_x, n_y, (x − x_r) n_y − (y − y_r) n_x).
    /// `lever_t`: the rotation's share along the tangent, (y − r) · n, for
    /// the tangential row of a frictional pair.
    Punch { obstacle: usize, c: [f64; 3], lever_t: f64 },
    /// A foundation whose deflection under the row's force opens the gap.
    Foundation(FoundationRow),
}

/// A candidate row's link to its foundation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoundationRow {
    pub foundation: usize,
    /// The row's panel [a, b] on the foundation line (x).
    pub panel: [f64; 2],
    /// −n_y: the share of the row's force that loads the foundation, and of
    /// the foundation's deflection that opens the gap.
    pub proj: f64,
}

impl Candidate {
    /// The punch (obstacle index) and coefficients c of a punch row.
    pub fn punch(&self) -> Option<(usize, [f64; 3])> {
        match self.link {
            Link::Punch { obstacle, c, .. } => Some((obstacle, c)),
            _ => None,
        }
    }

    /// The punch and its motion coefficients along the row's tangent
    /// t = (−n_y, n_x): the punch moves the point y by c_t · (α1, α2, θ)
    /// along t, c_t = (t_x, t_y, (y − r) · n).
    pub fn punch_tangent(&self) -> Option<(usize, [f64; 3])> {
        match self.link {
            Link::Punch { obstacle, c, lever_t } => Some((obstacle, [-c[1], c[0], lever_t])),
            _ => None,
        }
    }

    /// The foundation of a foundation row.
    pub fn foundation(&self) -> Option<FoundationRow> {
        match self.link {
            Link::Foundation(r) => Some(r),
            _ => None,
        }
    }

    /// The candidate of row `r` of pair `pair` on `body`, or None when the row
    /// constrains nothing (no free DOF and no rigid motion moves its nodes).
    pub fn try_new(pair: usize, body: usize, mesh: &Mesh2d, r: Row, dofs: &DofMap, link: Link) -> Option<Self> {
        let (row, g) = free_row(&r.terms, dofs, r.gap);
        if row.is_empty() && !moves_rigidly(&r.terms, dofs) {
            return None;
        }
        Some(Candidate {
            pair,
            body,
            node: r.node,
            x: mesh.nodes[r.node],
            normal: r.normal,
            weight: r.weight,
            terms: r.terms,
            row,
            g,
            link,
        })
    }
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
                if !self.candidates.iter().any(|c| c.punch().is_some_and(|p| p.0 == o)) {
                    continue;
                }
                for (k, ctl) in pu.controls.iter().enumerate() {
                    if let Control::Load(v) = ctl {
                        free.push((o, k, *v));
                    }
                }
            }
        }
        let c = faer::Mat::<f64>::from_fn(self.len(), free.len(), |i, j| match self.candidates[i].punch() {
            Some((o, row)) if o == free[j].0 => row[free[j].1],
            _ => 0.0,
        });
        (free, c)
    }
}
