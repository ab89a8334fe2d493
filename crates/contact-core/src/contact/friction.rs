//! The tangential rows of frictional pairs, beside the normal ones.
//!
//! A normal row reads n · u ≤ g over the nodal terms Σ coef_k · u_k, every
//! coefficient a multiple of the row's direction n (nodal rows: n itself;
//! mortar rows: n times the test function's integral). Turning every
//! coefficient by 90° counter-clockwise gives the same test functions on the
//! tangent t = (−n_y, n_x): the row's tangential displacement u_t = Σ R coef_k · u_k,
//! relative to the fixed obstacle. Its multiplier τ puts −τ · R coef_k on
//! the nodes, as λ puts −λ · coef_k: the friction force along t is −τ.
//!
//! Against a rigid punch the displacement is relative to the punch: the
//! punch moves the row's point by c_t · (α1, α2, θ) along t
//! (`Candidate::punch_tangent`), which the row subtracts; its prescribed
//! components go to the prescribed part, its load-controlled ones are
//! unknowns of the step (`punch` here, `methods::friction::Block`).
//!
//! Only rows of pairs with μ > 0 get a tangential row, and only where some
//! free DOF moves along t (a node whose tangential motion is prescribed has
//! its friction force taken by the support).

use std::collections::HashMap;

use super::constraints::{free_row, ConstraintSet};
use super::rows::Term;
use crate::fem::assembly::DofMap;
use crate::scene::{Control, Scene};

/// The tangential rows of the frictional candidates.
#[derive(Debug, Clone, Default)]
pub struct Tangents {
    /// Candidate (normal row) of each tangential row.
    pub of: Vec<usize>,
    /// Tangential row of each candidate, if any.
    pub row_of: Vec<Option<usize>>,
    /// The row on the free DOFs.
    pub rows: Vec<Vec<(usize, f64)>>,
    /// The row over nodes (the coefficients turned by 90°).
    pub terms: Vec<Vec<Term>>,
    /// The prescribed part Σ R coef · ū of each tangential displacement.
    pub prescribed: Vec<f64>,
    /// μ of each row.
    pub mu: Vec<f64>,
    /// The punch of each row and its tangential motion coefficients c_t.
    pub punch: Vec<Option<(usize, [f64; 3])>>,
}

impl Tangents {
    pub fn new(scene: &Scene, cons: &ConstraintSet, dofs: &DofMap) -> Self {
        let mut t = Tangents {
            row_of: vec![None; cons.len()],
            ..Default::default()
        };
        for (i, c) in cons.candidates.iter().enumerate() {
            let mu = scene.pairs[c.pair].friction;
            if mu <= 0.0 {
                continue;
            }
            let terms: Vec<Term> = c
                .terms
                .iter()
                .map(|k| Term {
                    coef: [-k.coef[1], k.coef[0]],
                    ..*k
                })
                .collect();
            // free_row moves the prescribed part to the right-hand side of a
            // "≤ g" row: with g = 0 it returns −Σ coef · ū.
            let (row, minus_prescribed) = free_row(&terms, dofs, 0.0);
            if row.is_empty() {
                continue;
            }
            // A prescribed punch motion moves the obstacle along t by c_t · ᾱ.
            let punch = c.punch_tangent();
            let moved: f64 = punch.map_or(0.0, |(o, ct)| {
                let controls = scene.obstacles[o].punch.as_ref().map(|p| p.controls);
                controls.map_or(0.0, |cs| {
                    (0..3)
                        .map(|k| match cs[k] {
                            Control::Displacement(v) => ct[k] * v,
                            _ => 0.0,
                        })
                        .sum()
                })
            });
            t.row_of[i] = Some(t.of.len());
            t.of.push(i);
            t.rows.push(row);
            t.terms.push(terms);
            t.prescribed.push(-minus_prescribed - moved);
            t.mu.push(mu);
            t.punch.push(punch);
        }
        t
    }

    pub fn len(&self) -> usize {
        self.of.len()
    }

    pub fn is_empty(&self) -> bool {
        self.of.is_empty()
    }

    /// Tangential displacements B_T u + prescribed part.
    pub fn displacements(&self, u: &[f64]) -> Vec<f64> {
        self.rows
            .iter()
            .zip(&self.prescribed)
            .map(|(r, p)| p + r.iter().map(|&(d, v)| v * u[d]).sum::<f64>())
            .collect()
    }

    /// The tangential displacements of the rows, relative to their punches,
    /// for a displacement of every DOF (free and prescribed: `DofMap::dof`
    /// indexing) and the punches' motions (α1, α2, θ) by obstacle; zero for
    /// an empty displacement (the undeformed start).
    pub fn of_nodal(&self, dofs: &DofMap, displacement: &[f64], punches: &HashMap<usize, [f64; 3]>) -> Vec<f64> {
        if displacement.is_empty() {
            return vec![0.0; self.len()];
        }
        self.terms
            .iter()
            .zip(&self.punch)
            .map(|(terms, punch)| {
                let body: f64 = terms
                    .iter()
                    .map(|t| {
                        let d = |c: usize| displacement[dofs.dof(t.body, t.node, c)];
                        t.coef[0] * d(0) + t.coef[1] * d(1)
                    })
                    .sum();
                let moved = punch.map_or(0.0, |(o, ct)| {
                    punches.get(&o).map_or(0.0, |a| (0..3).map(|k| ct[k] * a[k]).sum())
                });
                body - moved
            })
            .collect()
    }

    /// Accumulates B_Tᵀ τ into y.
    pub fn apply_transpose_into(&self, tau: &[f64], y: &mut [f64]) {
        for (r, &t) in self.rows.iter().zip(tau) {
            for &(d, v) in r {
                y[d] += v * t;
            }
        }
    }
}
