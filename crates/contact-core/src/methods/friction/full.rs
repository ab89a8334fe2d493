//! One load step of Coulomb friction on the full (uncondensed) system: the
//! same semismooth Newton on the Alart–Curnier functions as `friction`, its
//! linear system K itself instead of the condensed compliance. It serves the
//! scenes whose rows the condensed operator W (dense, (m + m_t)²) cannot
//! hold, and `formulation: full`.
//!
//! The rows must be nodal (one node per row, T3 against a rigid obstacle or
//! a punch with prescribed motion), as for the frictionless full active set
//! (`full`): each candidate's DOFs are turned to its normal and tangent,
//! u = Q u', so that its normal row acts on one coordinate u'_n and its
//! tangential row on the other, u'_t (the turned coefficients are the
//! tangent's). With r = K'u' − f' the nodal reactions, λ = −r_n / c_n and
//! τ = −r_t / c_t, and the states of a step read
//!
//! ```text
//! open      r_n = 0, r_t = 0              (no force)
//! closed    u'_n = g / c_n                (the gap vanishes)
//! stick     u'_t = (u_t(before) − ū_t) / c_t   (no slip in the step)
//! slip ±    r_t − α r_n = 0,  α = c_t (± μ − n · t) / c_n   (τ + λ n·t = ± μ λ)
//! ```
//!
//! Closed and sticking coordinates are prescribed: K' with their rows and
//! columns replaced by the identity (`full::prescribed`) keeps K's pattern, so
//! the symbolic Cholesky is computed once per step and each Newton iteration
//! is one numeric factorization. A sliding point's equation takes α times its
//! normal row from its tangential one, which makes the system
//! K'_FF − C, C of rank the number of sliding points, unsymmetric. It is
//! solved by GMRES right-preconditioned by the factor of K'_FF, whose
//! operator I − C K'_FF⁻¹ is the identity plus that rank: exact in at most
//! rank + 1 steps, and in few when α times the normal reaction a unit
//! tangential force causes is small (measured: 10 to 13 steps for 18 to 104
//! sliding points). Without sliding points it is one solve. A factorization
//! that fails or a GMRES run that stops short of its tolerance is an error of
//! the linear algebra (`linear_algebra`), not a state set to leave: no
//! Newton iteration would mend it. The nonsmooth Gauss–Seidel fallback of the
//! condensed path (`gauss_seidel`) needs W and is not run here.
//!
//! The update's parameters are a tenth of the coordinates' stiffness
//! K'_nn / c_n² and K'_tt / c_t² (`PARAMETER_SCALE`), the frictionless full
//! active set's measure; the condensed path uses the global compliance W_ii
//! instead. Both are admissible
//! parameters of the Alart–Curnier functions: they change the path of the
//! iteration, not its answer.
//!
//! Load-controlled punches and bodies held only by contact (whose free
//! motions join the condensed Newton system) and mortar or two-body rows are
//! solved on the condensed formulation only.

use crate::outcome::MethodRan;
use std::time::Instant;

use super::newton::{finish, restarted, starting_states, Iterate, NewtonSystem};
use super::{Friction, History, State};
use crate::contact::friction::Tangents;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::assembly::DofMap;
use crate::linalg::cholesky::SymbolicFactor;
use crate::linalg::sparse::sym_lower_matvec;
use crate::linalg::{Cholesky, LinalgError};
use crate::methods::full::{apply_q, prescribed, rotate, Rotated};
use crate::methods::Solution;
use crate::scene::Settings;

/// The data of one step on the full system.
pub struct Step<'a> {
    /// K on the free DOFs, lower triangle.
    pub k: &'a faer::sparse::SparseColMat<usize, f64>,
    pub f: &'a [f64],
    pub cons: &'a ConstraintSet,
    pub tangents: &'a Tangents,
    pub dofs: &'a DofMap,
    pub settings: &'a Settings,
}

/// Why the rows of a step do not fit the full system (None when they do):
/// every row nodal on its own DOFs (`tangential_coordinates`).
pub fn unfit(cons: &ConstraintSet, tangents: &Tangents) -> Option<&'static str> {
    if !cons.rows_are_nodal() {
        return Some(
            "the full formulation needs nodal contact rows (one node per row, as T3 against a rigid obstacle gives); \
                mortar rows (the T6 default) and two-body rows are solved on the condensed formulation only",
        );
    }
    tangential_coordinates(cons, tangents)
        .is_none()
        .then_some("with friction the full formulation needs both DOFs of every contact node free")
}

/// The coordinate and coefficient c_t of every tangential row (None if one
/// has none). A normal row on both DOFs (dx, dy) of its node is turned to
/// (u'_n, u'_t) at (dx, dy), so its tangential row must act on the same two
/// DOFs along the tangent, on u'_t alone. A normal row on one DOF (its
/// normal along an axis) is not turned, so its tangential row must act on
/// the node's other DOF alone, which no other row may use.
fn tangential_coordinates(cons: &ConstraintSet, tangents: &Tangents) -> Option<Vec<(usize, f64)>> {
    let mut used: std::collections::HashSet<usize> = cons
        .candidates
        .iter()
        .flat_map(|c| c.row.iter().map(|&(d, _)| d))
        .collect();
    (0..tangents.len())
        .map(|k| {
            match (
                cons.candidates[tangents.of[k]].row.as_slice(),
                tangents.rows[k].as_slice(),
            ) {
                (&[(dx, nx), (dy, ny)], row) => {
                    let (mut a, mut b) = (0.0, 0.0);
                    for &(d, v) in row {
                        match d {
                            _ if d == dx => a += v,
                            _ if d == dy => b += v,
                            _ => return None,
                        }
                    }
                    // a u_x + b u_y = (a nx + b ny) u'_n + (b nx − a ny) u'_t.
                    let (normal, tangential) = (a * nx + b * ny, b * nx - a * ny);
                    (normal.abs() <= 1e-12 * tangential.abs() && tangential != 0.0).then_some((dy, tangential))
                }
                (&[_], &[(d, v)]) => used.insert(d).then_some((d, v)),
                _ => None,
            }
        })
        .collect()
}

/// The update's parameters as a fraction of the coordinates' stiffness.
/// Measured on three T3 load paths (roller ν = 0.3, flat punch moved
/// sideways, block sheared under a fixed cylinder): at 1 the second step
/// cycled and restarted (21, 15 and 10 iterations, against the condensed
/// path's 7, 6 and 4); at 0.1, 0.03 and 0.01 every step took what the
/// condensed path takes, ±1.
const PARAMETER_SCALE: f64 = 0.1;

/// Solves one step from the state `previous` left.
pub fn solve_step(p: &Step, previous: &History) -> Result<(Solution, Friction), CoreError> {
    let t0 = Instant::now();
    let ut_before = p.tangents.of_nodal(p.dofs, &previous.displacement, &previous.punches);
    let mut sys = Rows::new(p, &ut_before)?;
    // New points start open: the first iteration without them is the
    // unconstrained solve, whose penetrations close them.
    let state = starting_states(p.cons, previous, |_| State::Open);
    let stiffness = |&(d, c): &(usize, f64)| PARAMETER_SCALE * sys.rot.diag[d] / (c * c);
    let c: Vec<f64> = sys.rot.coord.iter().map(stiffness).collect();
    let ct: Vec<f64> = sys.tangential.iter().map(stiffness).collect();
    let run = restarted(&mut sys, p.tangents, state, (&c, &ct), p.settings.max_iterations)?;
    let u = match sys.last_u.take() {
        Some(u) => u,
        // No iteration ran (no candidates, no iterations allowed, or the
        // deadline): the displacement of the states as they are.
        None => {
            sys.solve(&run.state, &run.lambda)?;
            sys.last_u.take().unwrap_or_else(|| vec![0.0; p.f.len()])
        }
    };
    let slip: Vec<f64> = p
        .tangents
        .displacements(&u)
        .iter()
        .zip(&ut_before)
        .map(|(a, b)| a - b)
        .collect();
    Ok(finish(p.cons, p.dofs, u, slip, run, (MethodRan::ActiveSetFull, t0)))
}

/// The rotated system of a step and what its iterations read back.
struct Rows<'a> {
    p: &'a Step<'a>,
    rot: Rotated,
    /// f' = Qᵀ f.
    fp: Vec<f64>,
    /// Tangential coordinate and c_t of each tangential row.
    tangential: Vec<(usize, f64)>,
    /// The analysis of K''s pattern, which prescribing coordinates keeps:
    /// one per step, its factorizations' cost checked against the time left.
    analysis: std::sync::Arc<SymbolicFactor>,
    /// u_t(before) − ū_t of each tangential row: c_t u'_t where it sticks.
    stick_rhs: Vec<f64>,
    g: Vec<f64>,
    /// u of the last iterate.
    last_u: Option<Vec<f64>>,
}

impl<'a> Rows<'a> {
    fn new(p: &'a Step<'a>, ut_before: &[f64]) -> Result<Self, CoreError> {
        let rot = rotate(p.k, p.cons);
        let tangential = tangential_coordinates(p.cons, p.tangents).expect("`unfit` admitted the rows");
        let analysis = std::sync::Arc::new(SymbolicFactor::try_new(&rot.k)?);
        Ok(Rows {
            fp: apply_q(&rot, p.f, true),
            rot,
            tangential,
            analysis,
            stick_rhs: (0..p.tangents.len())
                .map(|k| ut_before[k] - p.tangents.prescribed[k])
                .collect(),
            g: p.cons.g(),
            last_u: None,
            p,
        })
    }
}

/// Largest GMRES steps per Newton iteration, and its relative residual: the
/// iterate must solve its state's system to round-off for the certificate.
const GMRES_STEPS: usize = 200;
const GMRES_TOL: f64 = 1e-14;

impl NewtonSystem for Rows<'_> {
    fn solve(&mut self, state: &[State], at: &[f64]) -> Result<Option<Iterate>, CoreError> {
        crate::cancel::check(crate::outcome::ProgressStage::ContactSolve)?;
        let (rot, t) = (&self.rot, self.p.tangents);
        let n = rot.k.nrows();
        let m = rot.coord.len();
        let mut fixed = vec![f64::NAN; n];
        // (tangential coordinate, normal coordinate, α, c_t c) of each sliding point.
        let mut sliding = Vec::new();
        for (i, &st) in state.iter().enumerate() {
            if st == State::Open {
                continue;
            }
            let (dn, cn) = rot.coord[i];
            fixed[dn] = self.g[i] / cn;
            let Some(k) = t.row_of[i] else { continue };
            let (dt, ct) = self.tangential[k];
            match st {
                State::Slip(sign) => {
                    // τ = γ λ + c: r_t − α r_n = −c_t c (c = 0 for Coulomb).
                    let (gamma, c) = t.slip_line(k, sign, at[i]);
                    sliding.push((dt, dn, ct * gamma / cn, ct * c));
                }
                _ => fixed[dt] = self.stick_rhs[k] / ct,
            }
        }
        // K with coordinates prescribed stays positive definite: a failure is
        // the linear algebra's, not the states', and no iteration mends it
        // (the factorization checks the time left and polls the deadline).
        let (kk, rhs) = prescribed(&rot.k, &fixed, &self.fp);
        let chol = Cholesky::with_symbolic(self.analysis.clone(), &kk)?;
        let solve = |z: &[f64]| chol.solve(z);
        // u' = x_P + y, y zero on the prescribed coordinates: the free rows
        // read (K'y)_j = f'_j − (K'x_P)_j (`prescribed`'s right-hand side), a
        // sliding one less α times its normal row, r_t − α r_n = 0.
        let x_p: Vec<f64> = fixed.iter().map(|v| if v.is_finite() { *v } else { 0.0 }).collect();
        let mut b: Vec<f64> = (0..n)
            .map(|j| if fixed[j].is_finite() { 0.0 } else { rhs[j] })
            .collect();
        if !sliding.is_empty() {
            let kx = sym_lower_matvec(&rot.k, &x_p);
            for &(dt, dn, alpha, shift) in &sliding {
                b[dt] -= alpha * (self.fp[dn] - kx[dn]);
                if shift != 0.0 {
                    b[dt] -= shift;
                }
            }
        }
        let y = if sliding.is_empty() {
            solve(&b)
        } else {
            // The operator z ↦ z − C K'_FF⁻¹ z, (C y)_t = α (K'y)_n.
            let apply = |z: &[f64]| -> Vec<f64> {
                let ky = sym_lower_matvec(&rot.k, &solve(z));
                let mut out = z.to_vec();
                for &(dt, dn, alpha, _) in &sliding {
                    out[dt] -= alpha * ky[dn];
                }
                out
            };
            let run = crate::linalg::gmres::gmres(apply, &b, b.clone(), GMRES_TOL, GMRES_STEPS);
            if !run.converged {
                return Err(LinalgError::Iterative {
                    what: "the full system's sliding points",
                    steps: run.iterations,
                    residual: run.residual,
                    tolerance: GMRES_TOL,
                }
                .into());
            }
            solve(&run.x)
        };
        let up: Vec<f64> = (0..n).map(|j| x_p[j] + y[j]).collect();
        if !up.iter().all(|v| v.is_finite()) {
            return Err(LinalgError::Faer("the full system's solve gave non-finite displacements".into()).into());
        }
        let r: Vec<f64> = sym_lower_matvec(&rot.k, &up)
            .iter()
            .zip(&self.fp)
            .map(|(a, b)| a - b)
            .collect();
        let mut lambda = vec![0.0; m];
        let mut gap = vec![0.0; m];
        for i in 0..m {
            let (dn, cn) = rot.coord[i];
            gap[i] = self.g[i] - cn * up[dn];
            if state[i] != State::Open {
                lambda[i] = -r[dn] / cn;
            }
        }
        let mut tau = vec![0.0; t.len()];
        let mut slip = vec![0.0; t.len()];
        for (k, &(dt, ct)) in self.tangential.iter().enumerate() {
            slip[k] = ct * up[dt] - self.stick_rhs[k];
            if state[t.of[k]] != State::Open {
                tau[k] = -r[dt] / ct;
            }
        }
        self.last_u = Some(apply_q(rot, &up, false));
        Ok(Some(Iterate {
            lambda,
            tau,
            beta: Vec::new(),
            gap,
            slip,
        }))
    }

    fn free_motions(&self) -> usize {
        0
    }
}
