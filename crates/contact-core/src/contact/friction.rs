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
//! Against another body the normal row's terms on the other body's nodes are
//! −n times its shape functions at the facing point (`contact::rows`), so the
//! turned row reads t · u^a(x) − t · u^b(y): the relative tangential
//! displacement of the two surfaces, tested with the same multiplier
//! functions as the normal row, and its friction force acts on both bodies,
//! equal and opposite. There the coefficients are turned by 90° + δ, onto the
//! tangent of the bisector of the row's direction (the other surface's
//! normal at y) and the pair's own outward normal at the node: the two
//! surfaces are tilted by x/R1 and x/R2 against each other, and a tangent of
//! either one counts a pure approach of the bodies (relative motion along
//! their line of centres) as slip, g · x/R per step for a point that closes
//! the gap g. Measured on two identical cylinders (R = 8, T6, a = 0.42):
//! under the normal load alone the outer 8 % of the zone slipped, and under
//! Q the stick zone sat 0.07 a off centre (toward −x with the other
//! surface's tangent, +x with the own one). On the bisector the approach of
//! two surfaces of equal curvature has no tangential part, and for similar
//! materials it is the tangent of the deformed interface, which lies midway.
//! The normal rows keep their direction n (the frictionless problem is
//! unchanged), so the normal force λ n has a share λ n · t ≈ ∓ x/(2R) λ along
//! t, and the Coulomb law holds for the whole force's tangential component
//! τ + λ n · t (`along`): on τ alone the cone's two sides differed by
//! x/R λ, and the stick zone of two identical cylinders sat 0.012–0.034 a
//! off centre at every mesh (with the tangential traction reading 2–4 %
//! above Cattaneo–Mindlin's peak); on the whole force it sits on centre.
//!
//! Against a rigid punch the displacement is relative to the punch: the
//! punch moves the row's point by c_t · (α1, α2, θ) along t
//! (`Candidate::punch_tangent`), which the row subtracts; its prescribed
//! components go to the prescribed part, its load-controlled ones are
//! unknowns of the step (`punch` here, `methods::FreeBlock`).
//!
//! Only rows of pairs with μ > 0 get a tangential row, and only where some
//! free DOF moves along t (a node whose tangential motion is prescribed has
//! its friction force taken by the support; `held` lists it).

use std::collections::HashMap;

use super::constraints::{free_row, ConstraintSet};
use super::friction_law::{law_of, slip_line, Law};
use super::rows::Term;
use crate::fem::assembly::DofMap;
use crate::mesh::boundary::boundary_nodes;
use crate::mesh::Mesh2d;
use crate::scene::{Control, Scene, Target};

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
    /// The friction law of each row (its pair's).
    pub law: Vec<Law>,
    /// The punch of each row and its tangential motion coefficients c_t.
    pub punch: Vec<Option<(usize, [f64; 3])>>,
    /// The unit tangent t of each row (along which τ and the slip are
    /// measured): (−n_y, n_x) of the row's direction n, or against another
    /// body the bisector's tangent.
    pub tangent: Vec<[f64; 2]>,
    /// n · t of each row: the share of the normal force λ n along the
    /// tangent (0 unless t is the bisector's).
    pub lean: Vec<f64>,
    /// Of each row whose free part is r times its normal row's (`tied`), r:
    /// the supports leave the node one free direction, so closing the gap
    /// fixes the slip too (empty: none).
    pub tied: Vec<Option<f64>>,
    /// The frictional candidates left without a row (no free DOF moves
    /// along t: the supports take their friction force).
    pub held: Vec<HeldPoint>,
}

/// A frictional candidate without a tangential row: every DOF its slip
/// reads is prescribed, so its slip is a datum and the solve applies no
/// friction force there (the supports take it).
#[derive(Debug, Clone)]
pub struct HeldPoint {
    /// Its candidate (normal row).
    pub candidate: usize,
    /// The tangent its slip is measured along (as a row's `tangent`).
    pub tangent: [f64; 2],
    /// n · t: the normal force's share along the tangent (as a row's `lean`).
    pub lean: f64,
    /// Its tangential displacement relative to the other surface, all
    /// prescribed (nondimensional).
    pub prescribed: f64,
    /// The turned coefficients and the punch, to read the previous step's
    /// tangential displacement (`Tangents::held_slips`).
    terms: Vec<Term>,
    punch: Option<(usize, [f64; 3])>,
}

impl Tangents {
    pub fn new(scene: &Scene, meshes: &[Mesh2d], cons: &ConstraintSet, dofs: &DofMap) -> Self {
        let mut t = Tangents {
            row_of: vec![None; cons.len()],
            ..Default::default()
        };
        // The outward normals of the frictional two-body pairs' own surfaces.
        let own: HashMap<usize, HashMap<usize, [f64; 2]>> = scene
            .pairs
            .iter()
            .enumerate()
            .filter(|(_, p)| p.friction > 0.0 && matches!(p.target, Target::Body { .. }))
            .map(|(k, p)| {
                let mesh = &meshes[p.body];
                let normals = boundary_nodes(mesh, &mesh.edge_sets[&p.edges], false)
                    .into_iter()
                    .map(|b| (b.node, b.normal))
                    .collect();
                (k, normals)
            })
            .collect();
        for (i, c) in cons.candidates.iter().enumerate() {
            if scene.pairs[c.pair].friction <= 0.0 {
                continue;
            }
            let n = c.normal;
            // The rotation taking n to the tangent, (cos φ, sin φ) = (n · t, n × t):
            // exactly 90° but against another body.
            let (tangent, cos, sin) = match own.get(&c.pair).and_then(|ns| ns.get(&c.node)) {
                Some(o) => {
                    let b = [n[0] + o[0], n[1] + o[1]];
                    let l = b[0].hypot(b[1]);
                    let t = [-b[1] / l, b[0] / l];
                    (t, n[0] * t[0] + n[1] * t[1], n[0] * t[1] - n[1] * t[0])
                }
                None => ([-n[1], n[0]], 0.0, 1.0),
            };
            let terms: Vec<Term> = c
                .terms
                .iter()
                .map(|k| Term {
                    coef: [cos * k.coef[0] - sin * k.coef[1], sin * k.coef[0] + cos * k.coef[1]],
                    ..*k
                })
                .collect();
            // free_row moves the prescribed part to the right-hand side of a
            // "≤ g" row: with g = 0 it returns −Σ coef · ū.
            let (row, minus_prescribed) = free_row(&terms, dofs, 0.0);
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
            if row.is_empty() {
                t.held.push(HeldPoint {
                    candidate: i,
                    tangent,
                    lean: cos,
                    prescribed: -minus_prescribed - moved,
                    terms,
                    punch,
                });
                continue;
            }
            t.row_of[i] = Some(t.of.len());
            t.of.push(i);
            t.rows.push(row);
            t.terms.push(terms);
            t.prescribed.push(-minus_prescribed - moved);
            t.law.push(law_of(&scene.pairs[c.pair]));
            t.punch.push(punch);
            t.tangent.push(tangent);
            t.lean.push(cos);
            // A foundation's deflection opens the gap but moves no slip.
            let tied_row = c
                .foundation()
                .is_none()
                .then(|| tied(&c.row, &t.rows[t.rows.len() - 1]));
            t.tied.push(tied_row.flatten());
        }
        t
    }

    /// The ratio r of row k's free part to its normal row's, if the one is
    /// r times the other (`tied`).
    pub fn tied(&self, k: usize) -> Option<f64> {
        self.tied.get(k).copied().flatten()
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
        self.terms
            .iter()
            .zip(&self.punch)
            .map(|(terms, punch)| tangential(terms, *punch, dofs, displacement, punches))
            .collect()
    }

    /// The slip in the step of each point of `held`: its prescribed
    /// tangential displacement less the one at the previous step's end
    /// (`displacement`, `punches` as for `of_nodal`; empty at the start).
    pub fn held_slips(&self, dofs: &DofMap, displacement: &[f64], punches: &HashMap<usize, [f64; 3]>) -> Vec<f64> {
        self.held
            .iter()
            .map(|h| h.prescribed - tangential(&h.terms, h.punch, dofs, displacement, punches))
            .collect()
    }

    /// The whole contact force's component along the tangent of row k,
    /// friction τ plus the normal force's share λ n · t (the Coulomb law
    /// holds for it).
    pub fn along(&self, k: usize, lambda: f64, tau: f64) -> f64 {
        tau + self.lean.get(k).copied().unwrap_or(0.0) * lambda
    }

    /// The cone's bound of row k for the normal force λ (μ λ for Coulomb).
    pub fn bound(&self, k: usize, lambda: f64) -> f64 {
        self.law[k].bound(lambda)
    }

    /// The whole tangential force of row k projected onto its cone at λ.
    pub fn project(&self, k: usize, lambda: f64, z: f64) -> f64 {
        self.law[k].project(lambda, z)
    }

    /// A sliding point's friction force τ = γ λ + c on row k, sliding along
    /// `sign`, the law linearized at the normal force `at`
    /// (`friction_law::slip_line`).
    pub fn slip_line(&self, k: usize, sign: i8, at: f64) -> (f64, f64) {
        slip_line(self.law[k].as_ref(), sign, self.along(k, 1.0, 0.0), at)
    }

    /// The slip of row k once its point is closed, if its normal row fixes
    /// it (`tied`): with the free parts T = r N, the slip t·u − ū_t equals
    /// r (g − w) plus the prescribed part, so at w = 0 it is r g + the
    /// prescribed part, less `before` (the row's tangential displacement at
    /// the start of the step). None where the free motions `moves` (C_N, C_T
    /// rows of the point, if any) break the proportion.
    pub fn closed_slip(&self, k: usize, g: f64, before: f64, moves: Option<(&[f64], &[f64])>) -> Option<f64> {
        let r = self.tied(k)?;
        if let Some((cn, ct)) = moves {
            let scale = cn.iter().chain(ct).fold(0.0f64, |m, v| m.max(v.abs()));
            if cn.iter().zip(ct).any(|(n, t)| (t - r * n).abs() > TIED * scale) {
                return None;
            }
        }
        let (a, b) = (r * g, self.prescribed[k]);
        let slip = a + b - before;
        // Zero within the round-off of the sum (both sides held still), or of
        // a ratio r that is round-off of the turned coefficients.
        let scale = a.abs() + g.abs() + b.abs() + before.abs();
        Some(if slip.abs() <= SAME * scale { 0.0 } else { slip })
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

/// The tangential displacement Σ coef · u of turned `terms`, relative to
/// the punch, for a displacement of every DOF and the punches' motions;
/// zero for an empty displacement (the undeformed start).
fn tangential(
    terms: &[Term],
    punch: Option<(usize, [f64; 3])>,
    dofs: &DofMap,
    displacement: &[f64],
    punches: &HashMap<usize, [f64; 3]>,
) -> f64 {
    if displacement.is_empty() {
        return 0.0;
    }
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
}

/// A free-DOF coefficient this small against the row's largest is round-off
/// of the turned coefficients, not a direction the node moves in (the
/// tangent's components are exact to 1e-16; 1e-9 leaves room for the sums
/// of a mortar row's terms).
const TIED: f64 = 1e-9;

/// A slip within this share of the displacements it is the difference of
/// is 0 (round-off).
const SAME: f64 = 1e-12;

/// The ratio r if the tangential row's free part is r times the normal
/// row's (within `TIED`): a node held along one axis whose other DOF the
/// normal row moves, as a contact edge with u_x prescribed against a curved
/// obstacle. Closing the gap (N u = g) then fixes the slip (T u = r g): a
/// stick state's two equations are one, and its system is singular.
fn tied(normal: &[(usize, f64)], tangential: &[(usize, f64)]) -> Option<f64> {
    let dot = |a: &[(usize, f64)], d: usize| a.iter().filter(|e| e.0 == d).map(|e| e.1).sum::<f64>();
    let nn: f64 = normal.iter().map(|e| e.1 * e.1).sum();
    if nn == 0.0 {
        return None;
    }
    let largest = |row: &[(usize, f64)]| row.iter().fold(0.0f64, |m, e| m.max(e.1.abs()));
    let scale = largest(normal).max(largest(tangential));
    // A row of round-off alone (the press fit's bottom node, held along the
    // axis on both sides: 7e-17 of the normal row's 1) moves no free DOF
    // along t; its slip is the supports' (`solution::prescribed_slip`).
    if largest(tangential) <= TIED * scale {
        return None;
    }
    let r = tangential.iter().map(|&(d, v)| v * dot(normal, d)).sum::<f64>() / nn;
    let off = |row: &[(usize, f64)]| {
        row.iter()
            .any(|&(d, _)| (dot(tangential, d) - r * dot(normal, d)).abs() > TIED * scale)
    };
    (!off(normal) && !off(tangential)).then_some(r)
}
