//! One load step on the condensed rows: W over [N; T] from one
//! factorization, each state set's system solved densely by LU, and
//! nonsmooth Gauss–Seidel (`gauss_seidel`) to find states near the answer
//! when the Newton iteration cycles.

use std::time::Instant;

use faer::Mat;

use super::newton::{finish, restarted, starting_states, Iterate, NewtonSystem, Run};
use super::{Friction, History, State};
use crate::cache::Prepared;
use crate::contact::friction::Tangents;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::assembly::DofMap;
use crate::methods::{FreeBlock, Solution};
use crate::outcome::MethodRan;
use crate::scene::Settings;

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
    pub block: Option<&'a FreeBlock>,
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
    // The slip of each row whose normal row fixes it once closed.
    let closed: Vec<Option<f64>> = (0..nt)
        .map(|k| {
            let i = p.tangents.of[k];
            let moves = p.block.map(|b| {
                let m = b.len();
                let cn: Vec<f64> = (0..m).map(|j| b.cn[(i, j)]).collect();
                let ct: Vec<f64> = (0..m).map(|j| b.ct[(k, j)]).collect();
                (cn, ct)
            });
            let moves = moves.as_ref().map(|(a, b)| (a.as_slice(), b.as_slice()));
            p.tangents.closed_slip(k, p.cons.candidates[i].g, ut_before[k], moves)
        })
        .collect();
    let run = solve_states(
        w,
        (&q, &e, &closed),
        p.tangents,
        p.block,
        state,
        p.settings.max_iterations,
    );
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

/// The step's problem for (W, q, e) from the states `state`, on the
/// condensed rows; `closed`: the slip of each tangential row its normal row
/// fixes once closed (`Tangents::closed_slip`; empty: none).
fn solve_states(
    w: &Mat<f64>,
    (q, e, closed): (&[f64], &[f64], &[Option<f64>]),
    t: &Tangents,
    block: Option<&FreeBlock>,
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
    let mut dense = Dense {
        w,
        q,
        e,
        closed,
        t,
        block,
    };
    let run = restarted(&mut dense, t, state, (&c, &ct), max_iterations).expect("the dense Newton step does not fail");
    // Out of iterations is the caller's limit: no more work past it.
    if run.converged || run.iterations >= max_iterations || block.is_some() || crate::cancel::expired() {
        return run;
    }
    // The Newton iteration cycled from these states under every rescaling:
    // nonsmooth Gauss–Seidel finds states near the answer, from which it
    // converges.
    let sweeps = super::gauss_seidel::sweep(w, (q, e, closed), t, GAUSS_SEIDEL_SWEEPS, GAUSS_SEIDEL_TOL);
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

/// The Newton system on the condensed rows: W over [N; T], the right-hand
/// sides q and e, and the free motions' block.
struct Dense<'a> {
    w: &'a Mat<f64>,
    q: &'a [f64],
    e: &'a [f64],
    closed: &'a [Option<f64>],
    t: &'a Tangents,
    block: Option<&'a FreeBlock>,
}

impl NewtonSystem for Dense<'_> {
    fn solve(&mut self, state: &[State], at: &[f64]) -> Result<Option<Iterate>, CoreError> {
        let rhs = (self.q, self.e, self.closed);
        let Some((lambda, tau, beta)) = newton_step(self.w, rhs, self.t, self.block, (state, at)) else {
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
        self.block.map_or(0, FreeBlock::len)
    }

    fn closed_slip(&self, k: usize) -> Option<f64> {
        self.closed.get(k).copied().flatten()
    }
}

/// The gaps w and slips Δs of (λ, τ) and the free motions β.
fn gap_and_slip(
    w: &Mat<f64>,
    q: &[f64],
    e: &[f64],
    block: Option<&FreeBlock>,
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
/// A sticking point whose slip its normal row fixes (`closed`: prescribed to
/// 0) takes no friction force instead (its Δs = 0 repeats w = 0; any force in
/// the cone holds it). None when singular.
fn newton_step(
    w: &Mat<f64>,
    (q, e, closed): (&[f64], &[f64], &[Option<f64>]),
    t: &Tangents,
    block: Option<&FreeBlock>,
    (state, at): (&[State], &[f64]),
) -> Option<NewtonStep> {
    let n = q.len();
    let on: Vec<usize> = (0..n).filter(|&i| state[i] != State::Open).collect();
    let on_t: Vec<usize> = on.iter().filter_map(|&i| t.row_of[i]).collect();
    let (a, b) = (on.len(), on_t.len());
    let nb = block.map_or(0, FreeBlock::len);
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
                // Only a stick row's equation is its slip's.
                let stick_slip = !matches!(state[t.of[k]], State::Slip(_)) && closed.get(k).is_none_or(Option::is_none);
                if stick_slip {
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
            _ if closed.get(k).is_some_and(Option::is_some) => {
                // τ + λ n·t = 0: the whole tangential force vanishes.
                m[(r, r)] = 1.0;
                let li = on.iter().position(|&x| x == i).expect("a sticking point is in contact");
                m[(r, li)] = t.along(k, 1.0, 0.0);
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
    use crate::contact::friction_law::{Coulomb, Law};
    use std::sync::Arc;

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

    /// A random step of n points, each with the law `law`: a compliance
    /// W = A Aᵀ/2n + I (symmetric positive definite with normal–tangential
    /// coupling, as an elastic body's), gaps q and slips e, solved by the
    /// active set from the states the gaps suggest; the run with the gaps
    /// and slips of its answer.
    fn random_step(rng: &mut Lcg, n: usize, law: Law) -> (Run, Vec<f64>, Vec<f64>) {
        let a = Mat::<f64>::from_fn(2 * n, 2 * n, |_, _| rng.next());
        let w = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| {
            (0..2 * n).map(|k| a[(i, k)] * a[(j, k)]).sum::<f64>() / (2 * n) as f64 + f64::from(i == j)
        });
        let q: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let e: Vec<f64> = (0..n).map(|_| 0.5 * rng.next()).collect();
        let t = Tangents {
            of: (0..n).collect(),
            row_of: (0..n).map(Some).collect(),
            law: vec![law; n],
            ..Default::default()
        };
        let start = q
            .iter()
            .map(|&v| if v < 0.0 { State::Stick } else { State::Open })
            .collect();
        let r = solve_states(&w, (&q, &e, &[]), &t, None, start, 200);
        let (gap, slip) = gap_and_slip(&w, &q, &e, None, &r.lambda, &r.tau, &[]);
        (r, gap, slip)
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
            let (r, gap, slip) = random_step(&mut rng, n, Arc::new(Coulomb { mu }));
            assert!(
                r.converged,
                "case {case}: no convergence in {} iterations",
                r.iterations
            );
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
            let (r, gap, slip) = random_step(&mut rng, n, Arc::new(Tresca { g }));
            assert!(r.converged, "case {case}: {} iterations", r.iterations);
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
