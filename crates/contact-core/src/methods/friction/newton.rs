//! The semismooth Newton iteration on the points' states (open, stick,
//! slip ±), for any linear algebra that solves a state set's system
//! (`NewtonSystem`): the update of the states from an iterate, the restarts
//! after a cycle, the Alart–Curnier residual that ends it, and what a step
//! leaves to the next.

use std::collections::HashMap;
use std::time::Instant;

use crate::contact::friction::Tangents;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::assembly::{DofMap, FIXED};
use crate::methods::Solution;
use crate::outcome::MethodRan;

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
    /// The slip in the step of each point of `Tangents::held` (prescribed;
    /// set by the route, which knows the previous step: `held_slips`).
    pub held_slip: Vec<f64>,
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
        held_slip: Vec::new(),
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

/// The linear algebra of one Newton step: the multipliers, free motions,
/// gaps and slips of the system of a state set (None when singular).
pub(super) trait NewtonSystem {
    /// `at`: the normal forces of the last iterate, where a sliding point's
    /// bound is linearized.
    fn solve(&mut self, state: &[State], at: &[f64]) -> Result<Option<Iterate>, CoreError>;
    /// The number of free motions β among the unknowns.
    fn free_motions(&self) -> usize;
    /// The slip of tangential row k once its point is closed, where the
    /// normal row fixes it (`Tangents::closed_slip`; 0.0 exactly for a slip
    /// prescribed to 0).
    fn closed_slip(&self, _k: usize) -> Option<f64> {
        None
    }
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
                    // Closed, its slip is a datum: it slides that way with
                    // τ = ± μ λ, or, prescribed to 0, sticks with any force
                    // in the cone. Its stick equation Δs = 0 repeats w = 0
                    // (a singular system, whose LU gave forces of 1e20 and
                    // a run to the cap), so the state follows the datum.
                    Some(k) if sys.closed_slip(k).is_some() => {
                        beyond[i] = f64::INFINITY;
                        match sys.closed_slip(k) {
                            Some(s) if s > 0.0 => State::Slip(1),
                            Some(s) if s < 0.0 => State::Slip(-1),
                            _ => State::Stick,
                        }
                    }
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
