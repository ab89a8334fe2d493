//! One load step of Coulomb friction on the condensed rows: a primal–dual
//! active set (semismooth Newton) on the Alart–Curnier complementarity
//! functions.
//!
//! The normal rows N and the tangential rows T (`contact::friction`) are
//! condensed together from one factorization, W = [B_N; B_T] K⁻¹ [B_N; B_T]ᵀ,
//! so that for the normal forces λ and the tangential multipliers τ (friction
//! force −τ along the tangent)
//!
//! ```text
//! gap   w  = W_NN λ + W_NT τ + q,    q = g − B_N K⁻¹ f
//! slip  Δs = e − W_TN λ − W_TT τ,    e = B_T K⁻¹ f + ū_t − u_t(previous step)
//! ```
//!
//! and the step's conditions are λ ≥ 0, w ≥ 0, λ w = 0 and, in contact,
//! |τ| ≤ μ λ with Δs = 0 where |τ| < μ λ and τ = μ λ sign(Δs) where Δs ≠ 0
//! (the friction force opposes the slip: −τ Δs ≤ 0). Against another body
//! the law holds for τ + λ n · t instead of τ (`Tangents::along`: the normal
//! rows' direction is not quite normal to the tangent there). The slip is the
//! increment over the step (incremental, small-slip Coulomb law), measured
//! from the tangential displacement the previous step ended with.
//!
//! A load-controlled punch adds its free motions β (`Block`): the rows read
//! the motion relative to the punch, w += C_N β and Δs −= C_T β, and the
//! punch is in equilibrium with its loads P under the normal and the
//! friction forces, C_Nᵀλ + C_Tᵀτ = −P. The Newton system gains β and these
//! equations; with |Q| > μ|P| on a sliding punch it has no solution, which
//! Fichera's test with the friction cone refuses before (`solve`). The rigid
//! modes R of a body held only by contact are motions of the same block,
//! C_N = −B_N R and C_T = −B_T R (they move the rows' own points), with the
//! equilibrium Rᵀ(f − B_Nᵀλ − B_Tᵀτ) = 0, i.e. P = Rᵀf.
//!
//! Why this method: in 2D the cone is an interval, so the Alart–Curnier
//! functions min(λ, c w) = 0 and τ = proj_[−μλ̃, μλ̃](τ + c_t Δs), λ̃ = λ − c w,
//! are piecewise linear with four pieces per point (open, stick, slip + and
//! slip −). Their semismooth Newton step is the linear system of the current
//! pieces, and Newton's update of the pieces is the active-set update, as in
//! the frictionless `active_set` (Hüeber, Stadler and Wohlmuth, SIAM J. Sci.
//! Comput. 30, 2008). It reuses the warm start of the previous step's states
//! (a load path changes a few points per step) and stops when the states
//! repeat, with the answer exact up to the linear algebra. A Tresca fixed
//! point on p would solve a QP per outer iteration and converge only
//! linearly in its outer loop. The system of a state set is not symmetric
//! (the slip rows tie τ to λ), so it is solved by LU; its size is the number
//! of points in contact plus those among them with a tangential row.
//!
//! Length: about 700 lines. The iteration on the states is written once
//! for both linear algebras (`NewtonSystem`: the dense one here, the full
//! system's in `friction_full`), with its restarts and the Alart–Curnier
//! residual that ends it; the condensed path's hand-over to the Gauss–Seidel
//! fallback, and the test of the discrete Coulomb law on random
//! compliances, which needs the private run and residual functions.

use crate::outcome::MethodRan;
use std::collections::HashMap;
use std::time::Instant;

use faer::Mat;

use super::Solution;
use crate::cache::Prepared;
use crate::contact::friction::Tangents;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::assembly::{DofMap, FIXED};
use crate::scene::Settings;

/// A point's state in a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    Open,
    Stick,
    /// Sliding with τ = sign · μ λ (the slip along +t for sign +1).
    Slip(i8),
}

/// What a step leaves to the next one, by node rather than by row index
/// (the candidates of a step depend on its loads through the pruning of
/// distant nodes, so the rows of two steps need not be the same).
#[derive(Debug, Clone, Default)]
pub struct History {
    /// Displacement of every DOF (free and prescribed) at the end of the
    /// step; empty at the undeformed start.
    pub displacement: Vec<f64>,
    /// State of each candidate, by (pair, node): the warm start of the next step.
    pub state: HashMap<(usize, usize), State>,
    /// Motion (α1, α2, θ) of every punch at the end of the step, by obstacle.
    pub punches: HashMap<usize, [f64; 3]>,
}

/// The free motions β of load-controlled punches and of bodies held only by
/// contact in a step: their
/// coefficients in the normal rows (C_N, candidates × motions) and in the
/// tangential rows (C_T, tangential rows × motions), and the right-hand side
/// −P of their equilibrium.
pub struct Block {
    /// The free motions (`FreeMotions::motions`) the block holds; the others
    /// are not determined and stay at 0.
    pub keep: Vec<usize>,
    pub cn: Mat<f64>,
    pub ct: Mat<f64>,
    pub rhs: Vec<f64>,
    /// The bodies held only by contact whose rigid modes are among the
    /// motions: they rest on their contacts at the start.
    pub bodies: Vec<usize>,
}

impl Block {
    fn len(&self) -> usize {
        self.rhs.len()
    }
}

/// The data of one step.
pub struct Step<'a> {
    /// The factor with W over the rows [N; T].
    pub op: &'a Prepared,
    pub f: &'a [f64],
    pub cons: &'a ConstraintSet,
    pub tangents: &'a Tangents,
    pub dofs: &'a DofMap,
    pub settings: &'a Settings,
    /// Load-controlled punch motions, if any.
    pub block: Option<&'a Block>,
}

/// The friction of a solved step: the tangential multipliers, the slip of
/// the step per tangential row, the states, and what the report reads of the
/// normal solution (forces, contact, displacement scale ‖u‖∞).
pub struct Friction {
    pub tau: Vec<f64>,
    pub slip: Vec<f64>,
    pub history: History,
    pub lambda: Vec<f64>,
    pub in_contact: Vec<bool>,
    pub u_scale: f64,
    /// The free motions β of the step (empty without a block).
    pub beta: Vec<f64>,
}

/// Solves one step from the state `previous` left.
pub fn solve_step(p: &Step, previous: &History) -> (Solution, Friction) {
    let t0 = Instant::now();
    let (n, nt) = (p.cons.len(), p.tangents.len());
    let w = &p.op.condensed.w;
    let y = p.op.chol.forward(p.f);
    let bk = p.op.condensed.rows_of(&y);
    let q: Vec<f64> = (0..n).map(|i| p.cons.candidates[i].g - bk[i]).collect();
    let ut_before = p.tangents.of_nodal(p.dofs, &previous.displacement, &previous.punches);
    let e: Vec<f64> = (0..nt)
        .map(|k| bk[n + k] + p.tangents.prescribed[k] - ut_before[k])
        .collect();
    // Points known from the previous step start in their state; new ones in
    // contact where they penetrate without forces.
    let state = starting_states(p.cons, previous, |i| {
        let c = &p.cons.candidates[i];
        // A load-controlled punch, or a body held only by contact, rests at
        // its reference position, where its candidates touch or almost: all
        // start closed and the first Newton step opens those the loads do
        // not press.
        if q[i] < 0.0
            || p.block
                .is_some_and(|b| c.punch().is_some() || b.bodies.contains(&c.body))
        {
            State::Stick
        } else {
            State::Open
        }
    });
    let run = solve_states(w, &q, &e, p.tangents, p.block, state, p.settings.max_iterations);
    // u = K⁻¹ (f − B_Nᵀ λ − B_Tᵀ τ): the condensed blocks hold both row sets.
    let multipliers: Vec<f64> = run.lambda.iter().chain(&run.tau).copied().collect();
    let mut yz = y;
    p.op.condensed.subtract(&multipliers, &mut yz);
    let u = p.op.chol.backward(&yz);
    let mut ut = p.tangents.displacements(&u);
    if let Some(b) = p.block {
        for (k, v) in ut.iter_mut().enumerate() {
            *v -= (0..b.len()).map(|j| b.ct[(k, j)] * run.beta[j]).sum::<f64>();
        }
    }
    let slip: Vec<f64> = ut.iter().zip(&ut_before).map(|(a, b)| a - b).collect();
    finish(p.cons, p.dofs, u, slip, run, (MethodRan::ActiveSet, t0))
}

/// The states a step starts from: a point known from the previous step in
/// its state, a new one in `new(i)`.
pub(super) fn starting_states(cons: &ConstraintSet, previous: &History, new: impl Fn(usize) -> State) -> Vec<State> {
    (0..cons.len())
        .map(|i| {
            let c = &cons.candidates[i];
            previous.state.get(&(c.pair, c.node)).copied().unwrap_or_else(|| new(i))
        })
        .collect()
}

/// The step's answer from the displacement `u` of the free DOFs, the slip of
/// the step per tangential row and the run's last iterate; `method` names
/// what ran and when it started.
pub(super) fn finish(
    cons: &ConstraintSet,
    dofs: &DofMap,
    u: Vec<f64>,
    slip: Vec<f64>,
    run: Run,
    (method, t0): (MethodRan, Instant),
) -> (Solution, Friction) {
    let n = cons.len();
    let Run {
        lambda,
        tau,
        beta,
        state,
        converged,
        iterations,
    } = run;
    let displacement: Vec<f64> = (0..dofs.free.len())
        .map(|d| match dofs.free[d] {
            FIXED => dofs.prescribed[d],
            k => u[k],
        })
        .collect();
    let by_node = (0..n)
        .map(|i| ((cons.candidates[i].pair, cons.candidates[i].node), state[i]))
        .collect();
    let in_contact: Vec<bool> = (0..n).map(|i| state[i] != State::Open && lambda[i] > 0.0).collect();
    let friction = Friction {
        tau,
        slip,
        history: History {
            displacement,
            state: by_node,
            // The caller knows the punches' prescribed components.
            punches: HashMap::new(),
        },
        lambda: lambda.clone(),
        in_contact: in_contact.clone(),
        u_scale: u.iter().fold(0.0f64, |a, x| a.max(x.abs())),
        beta: beta.clone(),
    };
    let sol = Solution {
        u,
        lambda,
        beta,
        in_contact,
        iterations,
        converged,
        breakdown: false,
        method,
        exact: true,
        t_contact: t0.elapsed().as_secs_f64(),
        refinements: 0,
        fallback: None,
    };
    (sol, friction)
}

/// The step's problem for (W, q, e) from the states `state`, on the
/// condensed rows.
fn solve_states(
    w: &Mat<f64>,
    q: &[f64],
    e: &[f64],
    t: &Tangents,
    block: Option<&Block>,
    state: Vec<State>,
    max_iterations: usize,
) -> Run {
    let (n, nt) = (q.len(), e.len());
    let mean = |r: std::ops::Range<usize>| {
        let len = r.len().max(1) as f64;
        r.map(|i| w[(i, i)]).sum::<f64>() / len
    };
    let (c, ct) = (1.0 / mean(0..n), 1.0 / mean(n..n + nt).max(f64::MIN_POSITIVE));
    let (c, ct) = (vec![c; n], vec![ct; nt]);
    let mut dense = Dense { w, q, e, t, block };
    let run = restarted(&mut dense, t, state, (&c, &ct), max_iterations).expect("the dense Newton step does not fail");
    // Out of iterations is the caller's limit: no more work past it.
    if run.converged || run.iterations >= max_iterations || block.is_some() || crate::cancel::expired() {
        return run;
    }
    // The Newton iteration cycled from these states under every rescaling:
    // nonsmooth Gauss–Seidel finds states near the answer, from which it
    // converges.
    let sweeps = super::friction_gauss_seidel::sweep(w, q, e, t, GAUSS_SEIDEL_SWEEPS, GAUSS_SEIDEL_TOL);
    let budget = max_iterations - run.iterations;
    let mut again =
        restarted(&mut dense, t, sweeps.state, (&c, &ct), budget).expect("the dense Newton step does not fail");
    again.iterations += run.iterations;
    again
}

/// The fallback's sweeps at most, and the change of the forces (relative to
/// the largest) at which its states are taken: they only need to be near
/// the answer's, which the Newton iteration then finds exactly.
const GAUSS_SEIDEL_SWEEPS: usize = 2000;
const GAUSS_SEIDEL_TOL: f64 = 1e-8;

/// The linear algebra of one Newton step: the multipliers, free motions,
/// gaps and slips of the system of a state set (None when singular).
pub(super) trait NewtonSystem {
    /// `at`: the normal forces of the last iterate, where a sliding point's
    /// bound is linearized.
    fn solve(&mut self, state: &[State], at: &[f64]) -> Result<Option<Iterate>, CoreError>;
    /// The number of free motions β among the unknowns.
    fn free_motions(&self) -> usize;
}

/// One Newton iterate: λ, τ, β and the gaps w and slips Δs they give.
pub(super) struct Iterate {
    pub lambda: Vec<f64>,
    pub tau: Vec<f64>,
    pub beta: Vec<f64>,
    pub gap: Vec<f64>,
    pub slip: Vec<f64>,
}

/// The active set from the states `state`, restarted with rescaled
/// parameters after a cycle; the iterations of all its runs. (c, c_t) are
/// per point and per tangential row: they weigh gap against force and slip
/// against friction force in the update.
pub(super) fn restarted(
    sys: &mut dyn NewtonSystem,
    t: &Tangents,
    state: Vec<State>,
    (c, ct): (&[f64], &[f64]),
    max_iterations: usize,
) -> Result<Run, CoreError> {
    // Semismooth Newton on a piecewise linear function may cycle between
    // state sets when a step changes many points at once (measured at ν = 0.3,
    // where the normal load alone makes points slip: two steps out of four
    // cycled with the parameters below). The parameters c, c_t weigh the
    // forces against the gaps in the update; a cycle for one choice is
    // usually none for another, so the run restarts with them scaled.
    let mut iterations = 0;
    let mut run = None;
    for scale in C_SCALES {
        let budget = max_iterations.saturating_sub(iterations);
        if budget == 0 || crate::cancel::expired() {
            break;
        }
        let scaled = |v: &[f64]| v.iter().map(|x| scale * x).collect::<Vec<f64>>();
        let r = pdas(sys, t, state.clone(), (&scaled(c), &scaled(ct)), budget)?;
        iterations += r.iterations;
        let done = r.converged;
        run = Some(r);
        if done {
            break;
        }
    }
    let mut run = run.unwrap_or_else(|| Run {
        lambda: vec![0.0; c.len()],
        tau: vec![0.0; ct.len()],
        beta: vec![0.0; sys.free_motions()],
        state,
        iterations: 0,
        converged: c.is_empty(),
    });
    run.iterations = iterations;
    Ok(run)
}

/// Scalings of the update's parameters tried in turn after a cycle.
const C_SCALES: [f64; 5] = [1.0, 0.1, 10.0, 0.01, 100.0];

/// One run of the active set: its last iterate and states.
pub(super) struct Run {
    pub lambda: Vec<f64>,
    pub tau: Vec<f64>,
    pub beta: Vec<f64>,
    pub state: Vec<State>,
    pub iterations: usize,
    pub converged: bool,
}

/// Newton steps from the states `state` until they repeat (converged), cycle
/// or exhaust `budget`.
fn pdas(
    sys: &mut dyn NewtonSystem,
    t: &Tangents,
    mut state: Vec<State>,
    (c, ct): (&[f64], &[f64]),
    budget: usize,
) -> Result<Run, CoreError> {
    let (n, nt) = (c.len(), ct.len());
    let nb = sys.free_motions();
    let mut run = Run {
        lambda: vec![0.0; n],
        tau: vec![0.0; nt],
        beta: vec![0.0; nb],
        state: state.clone(),
        iterations: 0,
        converged: n == 0,
    };
    let mut seen: Vec<Vec<State>> = Vec::new();
    // How far each point's trial force |z| lies beyond its cone's bound in
    // the last update (∞ before the first and off the tangential rows).
    let mut beyond = vec![f64::INFINITY; n];
    // The sign of the tangential force of each point that stuck in tension
    // (0: none): closed again, it slides that way instead of sticking.
    let mut pulled = vec![0i8; n];
    while !run.converged && run.iterations < budget && !crate::cancel::expired() {
        run.iterations += 1;
        let mut attempt = sys.solve(&state, &run.lambda)?;
        // A free motion that only friction resists (a block's slide along a
        // flat floor) has no equation left when every point slips: the
        // system is singular. Some point must stick at a solution with
        // |Q| < μP (where the slip changes sign), so the sliding point
        // nearest its cone sticks instead, until the system is regular
        // (measured: on the free block at μ ≤ 1e-3 the first update slid
        // every point and the run stopped there).
        while attempt.is_none() && nb > 0 {
            let Some(i) = (0..n)
                .filter(|&i| matches!(state[i], State::Slip(_)))
                .min_by(|&a, &b| beyond[a].total_cmp(&beyond[b]))
            else {
                break;
            };
            state[i] = State::Stick;
            attempt = sys.solve(&state, &run.lambda)?;
        }
        let Some(Iterate {
            lambda,
            tau,
            beta,
            gap,
            slip,
        }) = attempt
        else {
            break;
        };
        let next: Vec<State> = (0..n)
            .map(|i| {
                let lt = lambda[i] - c[i] * gap[i];
                if lt <= 0.0 {
                    beyond[i] = f64::INFINITY;
                    if let (State::Stick, Some(k)) = (state[i], t.row_of[i]) {
                        let along = t.along(k, lambda[i], tau[k]);
                        pulled[i] = if along > 0.0 { 1 } else { -1 };
                    }
                    return State::Open;
                }
                match t.row_of[i] {
                    None => State::Stick,
                    Some(k) => {
                        let z = t.along(k, lambda[i], tau[k]) + ct[k] * slip[k];
                        beyond[i] = z.abs() / t.bound(k, lt);
                        // Stuck, it pulled; open, it penetrates: a point at
                        // the edge of its zone where the friction force needs
                        // a normal force the stick state cannot give. Neither
                        // state holds it, and with a large μ the cone's test
                        // from open never proposes the slip that does (the
                        // T3 roller at μ = 1e3: one edge node alternated
                        // open–stick under every rescaling until the cap;
                        // sliding it, 3 iterations up to μ = 1e6).
                        if state[i] == State::Open && pulled[i] != 0 {
                            State::Slip(pulled[i])
                        } else if z.abs() <= t.bound(k, lt) {
                            State::Stick
                        } else {
                            State::Slip(if z > 0.0 { 1 } else { -1 })
                        }
                    }
                }
            })
            .collect();
        let residual = alart_curnier_residual(t, (&lambda, &tau), (&gap, &slip), (c, ct));
        crate::progress::iteration(run.iterations, residual);
        // A point exactly on its cone's edge with no slip (|τ| = μλ, Δs = 0)
        // is both sticking and sliding: round-off picks its next state, and
        // the states can alternate between sets with the same answer
        // (measured on a press fit closing through its interference with
        // friction). The iterate is the answer when it solves the
        // Alart–Curnier equations, whatever the labels.
        let solved = residual <= AC_TOLERANCE * lambda.iter().chain(&tau).fold(0.0f64, |m, v| m.max(v.abs()));
        // The run answers with this iterate and the states it solved.
        (run.lambda, run.tau, run.beta, run.state) = (lambda, tau, beta, state.clone());
        if next == state || solved {
            run.converged = true;
            break;
        }
        if seen.contains(&next) {
            break; // cycling
        }
        seen.push(std::mem::replace(&mut state, next));
    }
    Ok(run)
}

/// Relative size of the Alart–Curnier residual at which an iterate is the
/// answer: round-off of the state's linear system (measured 1e-16 to 1e-14
/// of the largest force on the test scenes), well inside the certificate's
/// 1e-8.
const AC_TOLERANCE: f64 = 1e-12;

/// The largest residual of the Alart–Curnier equations, in force units:
/// min(λ, c w) = 0 and τ_a = proj_[−μλ̃, μλ̃](τ_a + c_t Δs) with λ̃ = max(0, λ − c w)
/// and τ_a the whole tangential force (`Tangents::along`); zero exactly on the
/// discrete Coulomb law.
fn alart_curnier_residual(
    t: &Tangents,
    (lambda, tau): (&[f64], &[f64]),
    (gap, slip): (&[f64], &[f64]),
    (c, ct): (&[f64], &[f64]),
) -> f64 {
    (0..lambda.len())
        .map(|i| {
            let normal = lambda[i].min(c[i] * gap[i]).abs();
            let tangential = t.row_of[i].map_or(0.0, |k| {
                let bound_at = (lambda[i] - c[i] * gap[i]).max(0.0);
                let along = t.along(k, lambda[i], tau[k]);
                (along - t.project(k, bound_at, along + ct[k] * slip[k])).abs()
            });
            normal.max(tangential)
        })
        .fold(0.0, f64::max)
}

/// The Newton system on the condensed rows: W over [N; T], the right-hand
/// sides q and e, and the free motions' block.
struct Dense<'a> {
    w: &'a Mat<f64>,
    q: &'a [f64],
    e: &'a [f64],
    t: &'a Tangents,
    block: Option<&'a Block>,
}

impl NewtonSystem for Dense<'_> {
    fn solve(&mut self, state: &[State], at: &[f64]) -> Result<Option<Iterate>, CoreError> {
        let Some((lambda, tau, beta)) = newton_step(self.w, self.q, self.e, self.t, self.block, (state, at)) else {
            return Ok(None);
        };
        let (gap, slip) = gap_and_slip(self.w, self.q, self.e, self.block, &lambda, &tau, &beta);
        Ok(Some(Iterate {
            lambda,
            tau,
            beta,
            gap,
            slip,
        }))
    }

    fn free_motions(&self) -> usize {
        self.block.map_or(0, Block::len)
    }
}

/// The gaps w and slips Δs of (λ, τ) and the free motions β.
fn gap_and_slip(
    w: &Mat<f64>,
    q: &[f64],
    e: &[f64],
    block: Option<&Block>,
    lambda: &[f64],
    tau: &[f64],
    beta: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let (n, nt) = (q.len(), e.len());
    let x: Vec<f64> = lambda.iter().chain(tau).copied().collect();
    let wx = crate::linalg::dense::matvec(w, &x);
    let mut gap: Vec<f64> = (0..n).map(|i| wx[i] + q[i]).collect();
    let mut slip: Vec<f64> = (0..nt).map(|k| e[k] - wx[n + k]).collect();
    if let Some(b) = block {
        for (j, &bj) in beta.iter().enumerate() {
            (0..n).for_each(|i| gap[i] += b.cn[(i, j)] * bj);
            (0..nt).for_each(|k| slip[k] -= b.ct[(k, j)] * bj);
        }
    }
    (gap, slip)
}

/// The linear system of the states: for every point in contact its gap is
/// closed (w_i = 0); a sticking point's slip vanishes (Δs_k = 0); a sliding
/// point's τ_k = ± μ_k λ_i. λ and τ vanish off contact. With a block, the
/// free motions β join the unknowns and their equilibrium the equations.
/// None when singular.
fn newton_step(
    w: &Mat<f64>,
    q: &[f64],
    e: &[f64],
    t: &Tangents,
    block: Option<&Block>,
    (state, at): (&[State], &[f64]),
) -> Option<NewtonStep> {
    let n = q.len();
    let on: Vec<usize> = (0..n).filter(|&i| state[i] != State::Open).collect();
    let on_t: Vec<usize> = on.iter().filter_map(|&i| t.row_of[i]).collect();
    let (a, b) = (on.len(), on_t.len());
    let nb = block.map_or(0, Block::len);
    if a == 0 {
        // Nothing holds a free motion off contact.
        return (nb == 0).then(|| (vec![0.0; n], vec![0.0; e.len()], Vec::new()));
    }
    // Unknowns: λ of `on`, then τ of `on_t`, then β; W's columns n + k for τ_k.
    let col = |j: usize| if j < a { on[j] } else { n + on_t[j - a] };
    let size = a + b + nb;
    let mut m = Mat::<f64>::zeros(size, size);
    let mut rhs = Mat::<f64>::zeros(size, 1);
    for (r, &i) in on.iter().enumerate() {
        for j in 0..a + b {
            m[(r, j)] = w[(i, col(j))];
        }
        rhs[(r, 0)] = -q[i];
    }
    if let Some(bl) = block {
        for j in 0..nb {
            for (r, &i) in on.iter().enumerate() {
                m[(r, a + b + j)] = bl.cn[(i, j)];
                m[(a + b + j, r)] = bl.cn[(i, j)];
            }
            for (s, &k) in on_t.iter().enumerate() {
                m[(a + b + j, a + s)] = bl.ct[(k, j)];
                if !matches!(state[t.of[k]], State::Slip(_)) {
                    m[(a + s, a + b + j)] = bl.ct[(k, j)];
                }
            }
            rhs[(a + b + j, 0)] = bl.rhs[j];
        }
    }
    for (s, &k) in on_t.iter().enumerate() {
        let r = a + s;
        let i = t.of[k];
        match state[i] {
            State::Slip(sign) => {
                m[(r, r)] = 1.0;
                let li = on.iter().position(|&x| x == i).expect("a sliding point is in contact");
                // τ = γ λ + c, the law linearized at the last iterate
                // (c = 0 for Coulomb: τ + λ n·t = ± μ λ).
                let (gamma, c) = t.slip_line(k, sign, at[i]);
                m[(r, li)] = -gamma;
                if c != 0.0 {
                    rhs[(r, 0)] = c;
                }
            }
            _ => {
                for j in 0..a + b {
                    m[(r, j)] = w[(n + k, col(j))];
                }
                rhs[(r, 0)] = e[k];
            }
        }
    }
    let x = faer::linalg::solvers::Solve::solve(&m.partial_piv_lu(), &rhs);
    let mut lambda = vec![0.0; n];
    let mut tau = vec![0.0; e.len()];
    for (j, &i) in on.iter().enumerate() {
        lambda[i] = x[(j, 0)];
    }
    for (s, &k) in on_t.iter().enumerate() {
        tau[k] = x[(a + s, 0)];
    }
    let beta: Vec<f64> = (0..nb).map(|j| x[(a + b + j, 0)]).collect();
    lambda
        .iter()
        .chain(&tau)
        .chain(&beta)
        .all(|v| v.is_finite())
        .then_some((lambda, tau, beta))
}

/// λ, τ and β of a Newton step.
type NewtonStep = (Vec<f64>, Vec<f64>, Vec<f64>);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::friction_law::Coulomb;

    /// A deterministic stream of numbers in [−1, 1) (64-bit LCG).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// On random compliances (W = A Aᵀ + I, symmetric positive definite with
    /// normal–tangential coupling, as an elastic body's) and random loads,
    /// the active set ends on a point of the discrete Coulomb law: λ ≥ 0,
    /// w ≥ 0, λ w = 0, |τ| ≤ μ λ, −τ Δs ≤ 0 and Δs = 0 inside the cone, each
    /// to 1e-10 of the problem's scale (round-off of the LU of a system of
    /// size ≤ 16).
    #[test]
    fn the_active_set_solves_the_discrete_coulomb_law() {
        let (n, mu) = (8, 0.4);
        let mut rng = Lcg(29);
        for case in 0..200 {
            let a = Mat::<f64>::from_fn(2 * n, 2 * n, |_, _| rng.next());
            let w = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| {
                (0..2 * n).map(|k| a[(i, k)] * a[(j, k)]).sum::<f64>() / (2 * n) as f64 + f64::from(i == j)
            });
            let q: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            let e: Vec<f64> = (0..n).map(|_| 0.5 * rng.next()).collect();
            let t = Tangents {
                of: (0..n).collect(),
                row_of: (0..n).map(Some).collect(),
                law: vec![std::sync::Arc::new(Coulomb { mu }); n],
                ..Default::default()
            };
            let start = q
                .iter()
                .map(|&v| if v < 0.0 { State::Stick } else { State::Open })
                .collect();
            let r = solve_states(&w, &q, &e, &t, None, start, 200);
            assert!(
                r.converged,
                "case {case}: no convergence in {} iterations",
                r.iterations
            );
            let (gap, slip) = gap_and_slip(&w, &q, &e, None, &r.lambda, &r.tau, &[]);
            let tol = 1e-10;
            for i in 0..n {
                let (l, tau) = (r.lambda[i], r.tau[i]);
                assert!(
                    l >= -tol && gap[i] >= -tol && (l * gap[i]).abs() <= tol,
                    "case {case}, point {i}: λ {l}, w {}",
                    gap[i]
                );
                assert!(
                    tau.abs() <= mu * l + tol,
                    "case {case}, point {i}: |τ| {tau} > μλ {}",
                    mu * l
                );
                assert!(-tau * slip[i] <= tol, "case {case}, point {i}: τ {tau}, Δs {}", slip[i]);
                assert!(
                    (mu * l - tau.abs()).max(0.0) * slip[i].abs() <= tol,
                    "case {case}, point {i}: slip {} inside the cone",
                    slip[i]
                );
            }
        }
    }

    /// A trial law through the seam: Tresca's fixed bound |τ| ≤ g, written
    /// here and nowhere else, runs through the same active set. On random
    /// compliances the answer satisfies Tresca's law: λ ≥ 0, w ≥ 0, λ w = 0;
    /// in contact |τ| ≤ g, and where a point slips (|Δs| > 1e-10) its shear
    /// is g exactly against the slip (τ = g sign Δs), to 1e-10 of the
    /// problem's scale (round-off of an LU of size ≤ 16). The slip rows'
    /// constant bound enters as the right-hand side c = ± g of τ = γ λ + c
    /// (`friction_law::slip_line`), which Coulomb's law never exercises.
    #[test]
    fn a_tresca_law_through_the_seam_slips_at_its_fixed_bound() {
        #[derive(Debug)]
        struct Tresca {
            g: f64,
        }
        impl crate::contact::friction_law::FrictionLaw for Tresca {
            fn bound(&self, _lambda: f64) -> f64 {
                self.g
            }
            fn derivative(&self, _lambda: f64) -> f64 {
                0.0
            }
            fn ray_slope(&self) -> f64 {
                0.0
            }
        }
        let (n, g) = (8, 0.15);
        let mut rng = Lcg(31);
        let mut slipping = 0;
        for case in 0..100 {
            let a = Mat::<f64>::from_fn(2 * n, 2 * n, |_, _| rng.next());
            let w = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| {
                (0..2 * n).map(|k| a[(i, k)] * a[(j, k)]).sum::<f64>() / (2 * n) as f64 + f64::from(i == j)
            });
            let q: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            let e: Vec<f64> = (0..n).map(|_| 0.5 * rng.next()).collect();
            let t = Tangents {
                of: (0..n).collect(),
                row_of: (0..n).map(Some).collect(),
                law: vec![std::sync::Arc::new(Tresca { g }); n],
                ..Default::default()
            };
            let start = q
                .iter()
                .map(|&v| if v < 0.0 { State::Stick } else { State::Open })
                .collect();
            let r = solve_states(&w, &q, &e, &t, None, start, 200);
            assert!(r.converged, "case {case}: {} iterations", r.iterations);
            let (gap, slip) = gap_and_slip(&w, &q, &e, None, &r.lambda, &r.tau, &[]);
            let tol = 1e-10;
            for i in 0..n {
                let (l, tau) = (r.lambda[i], r.tau[i]);
                assert!(
                    l >= -tol && gap[i] >= -tol && (l * gap[i]).abs() <= tol,
                    "case {case}, {i}"
                );
                if l <= tol {
                    assert!(tau.abs() <= tol, "case {case}, {i}: friction off contact {tau}");
                    continue;
                }
                assert!(tau.abs() <= g + tol, "case {case}, {i}: |τ| {tau} > g");
                if slip[i].abs() > tol {
                    slipping += 1;
                    assert!(
                        (tau - g * slip[i].signum()).abs() <= tol,
                        "case {case}, {i}: τ {tau}, Δs {}",
                        slip[i]
                    );
                }
            }
        }
        assert!(slipping > 50, "the cases slide somewhere: {slipping} slipping points");
    }
}
