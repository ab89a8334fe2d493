//! Frictionless Signorini contact of a body of tetrahedra with a rigid obstacle,
//! on the condensed path the 2D solve takes:
//!
//! ```text
//! minimize ½ uᵀK u − fᵀu   subject to   B u ≤ g     (rows: `obstacle`)
//! ```
//!
//! K is factored once (`methods::condensed::prepare_on`: supernodal, in the
//! nested-dissection order of `ordering`; the numeric factorization is
//! started only if its predicted time, `FactorCost::predicted_secs`, fits
//! in the time left, as in 2D. That model was fitted on 2D factors: on the
//! 47k-DOF T4 and 49k-DOF T10 boxes of the `solid3d_timing` example a 3D
//! factor took 1.14–1.33 times what a 2D grid factored just after said the
//! machine's scale was (six runs at a load average of 3.5; up to 1.5, and
//! 2.4 once, at 4.2), about the fit's own −15…+23 %; the scale learns from
//! each factorization, 3D ones included),
//! W = B K⁻¹ Bᵀ is formed on the reach of the rows (`linalg::schur`), and the
//! LCP λ ≥ 0, w = Wλ + q ≥ 0, λᵀw = 0 with q = g − B K⁻¹ f is solved by the
//! primal-dual active set (`methods::active_set`); u = K⁻¹ (f − Bᵀλ) costs
//! one forward and one backward sweep. Rigid motions the supports leave free
//! (a box on the plane held sideways by rollers is free to move along the
//! plane's normal) are the free motions β of `dofs`: u = ũ + Rβ, the rows
//! gain D β with D = B R, and the motions' equilibrium Dᵀλ = Rᵀ f closes
//! the mixed LCP (`active_set::solve_mlcp`, with C = −D).
//!
//! Load factors (`Operator`): scaling every load and prescribed motion by k
//! scales f, the prescribed part of g and Rᵀ f, while K, B, W and D stay; so
//! the operator is prepared once and each factor is one LCP on it. A load
//! path's step (`path`) is one LCP on it too: its loads and prescribed
//! values are another right-hand side (frictionless contact of a linear
//! body keeps no history, so each step is solved from nothing).
//!
//! The answer carries the KKT certificate of the full system, each entry
//! relative and dimensionless: primal (penetration max(0, −gap) over
//! ‖u‖∞), dual (max(0, −λ) over ‖λ‖∞), complementarity (max |λ_i gap_i|
//! over ‖λ‖∞ ‖u‖∞) and equilibrium (‖K u − f + Bᵀλ‖∞ off the supports over
//! the size of its terms, max(‖f‖∞, ‖|K||u|‖∞, ‖λ‖∞): the normwise
//! backward error). Not converging is an answer (`converged = false` with
//! the certificate), not an error.

use std::sync::Arc;

use faer::Mat;

use super::dofs::{dof_map, SolidDofs};
use super::linear::inf_norm;
use super::obstacle::ObstacleRows;
use super::{loads, ordering, stiffness, SolidBody};
use crate::cache::Prepared;
use crate::contact::fichera;
use crate::error::{CoreError, InvalidKind};
use crate::fem::pattern::FIXED;
use crate::linalg::dense;
use crate::methods::{active_set, condensed};
use crate::outcome::ProgressStage;
use crate::scene::Settings;

/// The relative KKT residuals of a contact solution (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Certificate {
    pub primal: f64,
    pub dual: f64,
    pub complementarity: f64,
    pub equilibrium: f64,
}

impl Certificate {
    /// The largest entry.
    pub fn worst(&self) -> f64 {
        self.primal
            .max(self.dual)
            .max(self.complementarity)
            .max(self.equilibrium)
    }
}

/// A contact solution.
#[derive(Debug, Clone)]
pub struct Contact {
    /// u on every DOF (3·node + c).
    pub u: Vec<f64>,
    /// Contact force of each row (+λ n on the body).
    pub lambda: Vec<f64>,
    /// λ_i / a_i.
    pub pressure: Vec<f64>,
    /// The rows' gaps after deformation (`ObstacleRows::gaps_after`).
    pub gap: Vec<f64>,
    /// Support reactions on every DOF (0 off the supports).
    pub reactions: Vec<f64>,
    /// Amplitudes of the free rigid motions (`dofs.modes`).
    pub beta: Vec<f64>,
    pub certificate: Certificate,
    pub iterations: usize,
    pub converged: bool,
    /// Contact-force refinement steps taken on the final active set.
    pub refinements: usize,
    pub dofs: SolidDofs,
    /// Seconds of assembly, factorization with condensation, and the
    /// contact solve with the displacements.
    pub seconds: [f64; 3],
}

/// The rows on the free DOFs and D = B R (rows × free motions): what the
/// loads do not change.
struct FreeRows {
    rows: Vec<Vec<(usize, f64)>>,
    d: Mat<f64>,
}

fn free_rows(body: &SolidBody, rows: &ObstacleRows, dofs: &SolidDofs) -> FreeRows {
    let k = dofs.modes.len();
    let mut out = FreeRows {
        rows: Vec::with_capacity(rows.len()),
        d: Mat::zeros(rows.len(), k),
    };
    for (i, terms) in rows.terms.iter().enumerate() {
        let mut row = Vec::with_capacity(3 * terms.len());
        let n = rows.normal[i];
        for &(node, cn) in terms {
            for (c, nc) in n.iter().enumerate() {
                let (dof, coef) = (3 * node + c, -nc * cn);
                if coef == 0.0 {
                    continue;
                }
                if dofs.free[dof] != FIXED {
                    row.push((dofs.free[dof], coef));
                }
                for j in 0..k {
                    out.d[(i, j)] += coef * dofs.modes.at(j, body.mesh.nodes[node], c);
                }
            }
        }
        out.rows.push(row);
    }
    out
}

/// The rows' gaps less the prescribed motion (`dofs.prescribed`, already
/// scaled by the load factor).
fn free_gaps(rows: &ObstacleRows, dofs: &SolidDofs) -> Vec<f64> {
    let mut out = Vec::with_capacity(rows.len());
    for (i, terms) in rows.terms.iter().enumerate() {
        let (mut g, n) = (rows.gap[i], rows.normal[i]);
        for &(node, cn) in terms {
            for (c, nc) in n.iter().enumerate() {
                let (dof, coef) = (3 * node + c, -nc * cn);
                if coef != 0.0 && dofs.free[dof] == FIXED {
                    g -= coef * dofs.prescribed[dof];
                }
            }
        }
        out.push(g);
    }
    out
}

/// Solves the contact of `body` with the obstacle of `rows`.
pub fn solve(body: &SolidBody, rows: &ObstacleRows, settings: &Settings) -> Result<Contact, CoreError> {
    solve_within(body, rows, settings, f64::INFINITY)
}

/// `solve`, refused (`too_large` at the body's mesh) when the factor of K
/// would hold more than `max_bytes` (`prepare_within`).
pub fn solve_within(
    body: &SolidBody,
    rows: &ObstacleRows,
    settings: &Settings,
    max_bytes: f64,
) -> Result<Contact, CoreError> {
    let op = prepare_within(body, rows, &[1.0], max_bytes)?;
    let mut contact = op.solve(body, rows, settings, 1.0)?;
    contact.seconds[..2].copy_from_slice(&op.seconds);
    Ok(contact)
}

/// What every load factor of a frictionless solve shares: K assembled and
/// factored, the rows condensed into W, the free motions' rows D. The loads
/// and prescribed motions enter the LCP only through q = g − B K⁻¹ f and the
/// motions' loads Rᵀ f, linear in the factor, and the rows are those of the
/// undeformed body (small strain): so each factor is one more LCP on the same
/// W, one forward and one backward sweep.
pub struct Operator {
    dofs: SolidDofs,
    prepared: Prepared,
    rows: FreeRows,
    /// The free motions on every DOF.
    fields: Vec<Vec<f64>>,
    /// The external forces at factor 1 on every DOF.
    f_ext: Vec<f64>,
    /// Seconds of assembly, and of the factorization with condensation.
    pub seconds: [f64; 2],
    /// Bytes of the factor of K (8 per stored value): what a refinement
    /// round's next factor is predicted from (`adapt::solid`).
    pub factor_bytes: f64,
}

/// The operator of `body` against the rows, for the load `factors` the
/// caller will solve; refused (`too_large` at the body's mesh) when the
/// factor of K would hold more than `max_bytes`: a 3D factor fills far more
/// per unknown than a 2D one (the T10 ball example, 35k DOF, took 344 MB where
/// 2D solves take 1.3–1.5 kB per DOF), so a DOF limit set from the memory at
/// 2D rates does not bound it. Judged from the symbolic analysis, before the
/// factor's memory is taken; and loads that no contact force balances are
/// refused before it too, for every sign of the factors (Fichera's condition
/// holds alike for every positive multiple of a load).
pub fn prepare_within(
    body: &SolidBody,
    rows: &ObstacleRows,
    factors: &[f64],
    max_bytes: f64,
) -> Result<Operator, CoreError> {
    prepare_checked(body, rows, max_bytes, |c, fields, f_ext| {
        let mut signs: Vec<f64> = factors
            .iter()
            .map(|k| if *k == 0.0 { 0.0 } else { k.signum() })
            .collect();
        signs.dedup();
        for s in signs {
            compatible(c, &motion_loads(fields, f_ext, s))?;
        }
        Ok(())
    })
}

/// The loads of one solve on an `Operator`: external forces and prescribed
/// values on every DOF (`dofs::dof_map`'s; its supports hold the same
/// components as the operator's).
#[derive(Debug, Clone)]
pub struct StepLoads {
    pub f_ext: Vec<f64>,
    pub prescribed: Vec<f64>,
}

/// `prepare_within` with the loads' balance judged by `check(C, R, f_ext)`
/// (C = −D, R the free motions on every DOF, f_ext the body's loads).
pub(super) fn prepare_checked(
    body: &SolidBody,
    rows: &ObstacleRows,
    max_bytes: f64,
    check: impl FnOnce(&Mat<f64>, &[Vec<f64>], &[f64]) -> Result<(), CoreError>,
) -> Result<Operator, CoreError> {
    let t0 = std::time::Instant::now();
    let touching: Vec<usize> = rows.terms.iter().flatten().map(|t| t.0).collect();
    let dofs = dof_map(body, Some(&touching))?;
    let k = Arc::new(stiffness::assemble(body, &dofs)?);
    let f_ext = loads::external(body)?;
    let fr = free_rows(body, rows, &dofs);
    let nm = dofs.modes.len();
    let fields: Vec<Vec<f64>> = (0..nm).map(|j| dofs.modes.field(j, &body.mesh.nodes)).collect();
    if let Some(b) = unresisted(&fr.d, &dofs.modes.basis) {
        return Err(CoreError::invalid(
            InvalidKind::NoSupport,
            "supports",
            format!(
                "the supports leave the {} free, which the obstacle cannot resist (a frictionless obstacle pushes \
                    only along its normals)",
                super::dofs::describe(&b)
            ),
        ));
    }
    check(&-&fr.d, &fields, &f_ext)?;
    let t1 = std::time::Instant::now();
    crate::progress::stage(crate::progress::ProgressStage::Factorization);
    let refs: Vec<&[(usize, f64)]> = fr.rows.iter().map(|r| r.as_slice()).collect();
    let symbolic = Arc::new(ordering::analysed(body.mesh, &dofs, &k.k)?);
    let factor_bytes = 8.0 * symbolic.cost().nnz as f64;
    if factor_bytes > max_bytes {
        return Err(CoreError::TooLarge {
            path: "/solid/body/mesh".into(),
            reason: format!(
                "the factor of the stiffness would hold {:.2} GB, past the {:.2} GB this service gives a request: \
                 coarsen the mesh (size or grading/h_min)",
                factor_bytes / 1e9,
                max_bytes / 1e9
            ),
        });
    }
    let prepared = condensed::prepare_on(k, &refs, symbolic, t1)?;
    Ok(Operator {
        dofs,
        prepared,
        rows: fr,
        fields,
        f_ext,
        seconds: [t1 - t0, t1.elapsed()].map(|d| d.as_secs_f64()),
        factor_bytes,
    })
}

/// r = −Rᵀ f at load factor `k`, the right-hand side of the motions'
/// equilibrium Cᵀλ = r (R on every DOF: a virtual support's share too).
pub(super) fn motion_loads(fields: &[Vec<f64>], f_ext: &[f64], k: f64) -> Vec<f64> {
    fields.iter().map(|r| -k * dense::dot(r, f_ext)).collect()
}

impl Operator {
    /// The contact at load factor `k`: every load and prescribed motion
    /// times k, the gaps as given. `body` and `rows` are those the operator
    /// was prepared for. Its `seconds` hold the contact solve alone.
    pub fn solve(
        &self,
        body: &SolidBody,
        rows: &ObstacleRows,
        settings: &Settings,
        k: f64,
    ) -> Result<Contact, CoreError> {
        let step = StepLoads {
            f_ext: self.f_ext.iter().map(|f| k * f).collect(),
            prescribed: self.dofs.prescribed.iter().map(|p| k * p).collect(),
        };
        self.solve_loads(body, rows, settings, &step)
    }

    /// The contact under `step`'s loads and prescribed values (a load path
    /// step's), the gaps as given: the LCP on the same W with
    /// q = g − B K⁻¹ f of this step, one forward sweep for its free
    /// solution (the backward sweep for u is needed anyway, so solving each
    /// named load once and combining would save nothing but a forward sweep
    /// per step, at the cost of one stored field per load).
    pub fn solve_loads(
        &self,
        body: &SolidBody,
        rows: &ObstacleRows,
        settings: &Settings,
        step: &StepLoads,
    ) -> Result<Contact, CoreError> {
        let t2 = std::time::Instant::now();
        crate::progress::stage(crate::progress::ProgressStage::ContactSolve);
        let op = &self.prepared;
        let mut dofs = self.dofs.clone();
        dofs.prescribed.clone_from(&step.prescribed);
        let f_ext = &step.f_ext;
        let f = loads::free_rhs(f_ext, &dofs, &op.stiffness);
        let g = free_gaps(rows, &dofs);
        let (c, r) = (-&self.rows.d, motion_loads(&self.fields, f_ext, 1.0));
        let nm = dofs.modes.len();
        let y = op.chol.forward(&f);
        let q: Vec<f64> = g.iter().zip(op.condensed.rows_of(&y)).map(|(g, b)| g - b).collect();
        let (res, mut beta) = if nm == 0 {
            (active_set::solve_lcp(&op.condensed.w, &q, settings), Vec::new())
        } else {
            active_set::solve_mlcp(&op.condensed.w, &q, &c, &r, settings)
        };
        let mut lambda = res.lambda;
        let displacements = |lambda: &[f64], beta: &[f64]| {
            let mut yz = y.clone();
            op.condensed.subtract(lambda, &mut yz);
            let mut u = loads::full_field(&dofs, &op.chol.backward(&yz));
            for (field, b) in self.fields.iter().zip(beta) {
                u.iter_mut().zip(field).for_each(|(u, r)| *u += b * r);
            }
            u
        };
        let gaps = |u: &[f64]| rows.gaps_after(u);
        let mut u = displacements(&lambda, &beta);
        let mut gap = gaps(&u);
        // Refinement on the final active set: the dense W carries the round-off
        // of the compliance it was formed from, the sparse u does not; solving
        // [W_AA C_A; C_Aᵀ 0] δ = −(gap_A, Dᵀλ − Rᵀf) moves the active gaps to 0.
        let mut refinements = 0;
        if res.converged {
            let idx: Vec<usize> = (0..lambda.len()).filter(|&i| lambda[i] > 0.0).collect();
            let worst = |g: &[f64]| idx.iter().fold(0.0f64, |a, &i| a.max(g[i].abs()));
            for _ in 0..REFINE_STEPS {
                let now = worst(&gap);
                if idx.is_empty() || now <= 1e-3 * settings.tolerance * inf_norm(&u) {
                    break;
                }
                let eq: Vec<f64> = (0..nm)
                    .map(|j| r[j] - idx.iter().map(|&i| c[(i, j)] * lambda[i]).sum::<f64>())
                    .collect();
                let Some((dl, db)) = active_set::saddle(&op.condensed.w, &gap, &c, &eq, &idx) else {
                    break;
                };
                let mut l2 = lambda.clone();
                idx.iter().zip(&dl).for_each(|(&i, d)| l2[i] += d);
                let b2: Vec<f64> = beta.iter().zip(&db).map(|(b, d)| b + d).collect();
                let u2 = displacements(&l2, &b2);
                let g2 = gaps(&u2);
                if idx.iter().any(|&i| l2[i] < 0.0) || worst(&g2) > 0.5 * now {
                    break;
                }
                (lambda, beta, u, gap) = (l2, b2, u2, g2);
                refinements += 1;
            }
        }
        let t3 = std::time::Instant::now();
        let (ku, abs) = stiffness::internal_forces(body, &u, ProgressStage::ContactSolve)?;
        let mut residual = ku;
        residual.iter_mut().zip(f_ext).for_each(|(r, f)| *r -= f);
        for ((terms, l), n) in rows.terms.iter().zip(&lambda).zip(&rows.normal) {
            for &(node, cn) in terms {
                for cc in 0..3 {
                    residual[3 * node + cc] -= l * cn * n[cc];
                }
            }
        }
        let mut reactions = vec![0.0; u.len()];
        let mut off_supports: f64 = 0.0;
        for (d, &rd) in residual.iter().enumerate() {
            if dofs.supported[d] {
                reactions[d] = rd;
            } else {
                off_supports = off_supports.max(rd.abs());
            }
        }
        let (lmax, umax) = (
            inf_norm(&lambda).max(f64::MIN_POSITIVE),
            inf_norm(&u).max(f64::MIN_POSITIVE),
        );
        let certificate = Certificate {
            primal: gap.iter().fold(0.0f64, |a, g| a.max(-g)) / umax,
            dual: lambda.iter().fold(0.0f64, |a, l| a.max(-l)) / lmax,
            complementarity: lambda.iter().zip(&gap).fold(0.0f64, |a, (l, g)| a.max((l * g).abs())) / (lmax * umax),
            equilibrium: off_supports / inf_norm(f_ext).max(inf_norm(&abs)).max(lmax),
        };
        let pressure = lambda.iter().zip(&rows.area).map(|(l, a)| l / a).collect();
        Ok(Contact {
            u,
            lambda,
            pressure,
            gap,
            reactions,
            beta,
            certificate,
            iterations: res.iterations,
            converged: res.converged,
            refinements,
            dofs,
            seconds: [0.0, 0.0, (t3 - t2).as_secs_f64()],
        })
    }
}

/// A free motion (in (t, Lω) coordinates) that moves no row: D γ = 0 for
/// some γ ≠ 0 (DᵀD's eigenvalues at 1e-12 of its largest, or D = 0), which
/// would leave the mixed LCP's saddle point singular.
fn unresisted(d: &Mat<f64>, basis: &[[f64; 6]]) -> Option<[f64; 6]> {
    let k = d.ncols();
    if k == 0 {
        return None;
    }
    let dtd = Mat::<f64>::from_fn(k, k, |a, b| (0..d.nrows()).map(|i| d[(i, a)] * d[(i, b)]).sum());
    let (vals, vecs) = dense::sym_eigen_small(&dtd);
    let scale = vals[k - 1];
    let j = (0..k).find(|&j| scale == 0.0 || vals[j] <= 1e-12 * scale)?;
    let b: [f64; 6] = std::array::from_fn(|c| (0..k).map(|m| vecs[(m, j)] * basis[m][c]).sum());
    let lead = b
        .iter()
        .copied()
        .fold(0.0f64, |a, v| if v.abs() > a.abs() { v } else { a });
    Some(b.map(|v| if (v / lead).abs() < 1e-12 { 0.0 } else { v / lead }))
}

/// Fichera's condition on the free motions (rows B u − C β ≤ g, equilibrium
/// Cᵀλ = r): some λ ≥ 0 must balance the loads (`contact::fichera::check`,
/// an LP), and no motion may open every row while the loads do no work on it
/// (`fichera::escape`: nothing would decide where the body rests).
pub(super) fn compatible(c: &Mat<f64>, r: &[f64]) -> Result<(), CoreError> {
    if c.ncols() == 0 {
        return Ok(());
    }
    if fichera::check(c, r).is_err() {
        return Err(CoreError::invalid(
            InvalidKind::IncompatibleLoads,
            "loads",
            "no contact pressure on the obstacle (λ ≥ 0) balances the loads along the rigid motions the supports \
                leave free: the loads pull the body off the obstacle or push it along it",
        ));
    }
    if fichera::escape(c, r).is_some() {
        return Err(CoreError::invalid(
            InvalidKind::NoSupport,
            "supports",
            "a rigid motion the supports leave free lifts the body off the obstacle without work against the loads: \
                nothing decides where it rests (a support is missing, or the loads do not press it on the obstacle)",
        ));
    }
    Ok(())
}

/// Refinement steps of the contact forces at most (each one dense solve on
/// the active set and one forward and backward sweep).
const REFINE_STEPS: usize = 2;
