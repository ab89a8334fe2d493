//! The frictional step's states by nonsmooth Gauss–Seidel (Moreau and Jean's
//! NSGS): point after point, the exact answer of its own 2 × 2 Coulomb
//! problem with the others' forces held. It is the fallback of the
//! semismooth Newton (`condensed`), which converges fast from states near the
//! answer but can cycle from far ones: a press fit whose whole interface
//! closes through an interference in one step cycled between stick and slip
//! at most points for every choice of the Newton parameters but two of nine
//! (measured). NSGS converges linearly and needs no parameter; its states
//! then start the Newton iteration again, which ends on the exact answer.
//!
//! Point i with normal row i and tangential row k sees, with the others
//! held, the gap w = a λ + b τ + r_N and the slip Δs = r_T − b′ λ − d τ
//! (a, b, b′, d the point's 2 × 2 block of W). Its Coulomb problem (λ ≥ 0,
//! w ≥ 0, λ w = 0; |τ + ℓ λ| ≤ μ λ, ℓ = n · t the normal force's lean; no
//! slip inside the cone, the friction force against the slip on it) is
//! solved by its four cases: stick (w = 0, Δs = 0), slip ± (w = 0,
//! τ = (±μ − ℓ) λ, ±Δs ≥ 0) and open (λ = τ = 0, w ≥ 0), the first that
//! holds.
//!
//! A tied row (`Tangents::tied`: its free part r times its normal row's, a
//! contact edge also held along x) has a singular block, a d − b b′ = 0 but
//! for round-off, and its slip once closed is a datum (`Tangents::closed_slip`).
//! Its stick case divided by that round-off: where μ ≥ |1/r − ℓ| the cone
//! took it, with a pair of forces about 1e16 times the problem's scale that
//! cancel along the node's one free motion. Such a point instead closes on
//! the datum, as the Newton iteration sets it: sliding with τ = (±μ − ℓ) λ
//! the way the datum slips, or, with a datum of 0, sticking with no force
//! along t (τ = −ℓ λ). Its force then moves its gap by a (1 + r γ) λ,
//! γ = ±μ − ℓ: where 1 + r γ ≤ 0 the friction force pushes the node into the
//! surface at least as hard as the normal force pushes it out (the point
//! wedges: with the node's free motion along y, μ |n_x| ≥ n_y against the
//! slip's sense), and a point pressed in then has no Coulomb answer at all.
//! It is left open and named (`Sweeps::wedged`); the sweeps do not settle.

use faer::Mat;

use super::State;
use crate::contact::friction::Tangents;
use crate::contact::friction_law::{slip_line, FrictionLaw};

/// The forces and states after the sweeps, and whether they settled.
pub struct Sweeps {
    pub lambda: Vec<f64>,
    pub tau: Vec<f64>,
    pub state: Vec<State>,
    pub settled: bool,
    /// The tied points pressed in whose friction, sliding by their datum,
    /// closes them harder than their normal force opens them (module docs):
    /// no Coulomb answer has them in contact.
    pub wedged: Vec<usize>,
}

/// Sweeps until no force changes by more than `tol` of the largest, or
/// `max_sweeps` (W over the rows [N; T], q and e the step's right-hand sides,
/// `closed` the slip each tangential row's normal row fixes once closed, if
/// tied: module docs; empty: none).
pub fn sweep(
    w: &Mat<f64>,
    (q, e, closed): (&[f64], &[f64], &[Option<f64>]),
    t: &Tangents,
    max_sweeps: usize,
    tol: f64,
) -> Sweeps {
    let (n, nt) = (q.len(), e.len());
    let (mut lambda, mut tau) = (vec![0.0; n], vec![0.0; nt]);
    let mut state = vec![State::Open; n];
    // The gaps and slips of the current forces, kept up to date.
    let mut gap = q.to_vec();
    let mut slip = e.to_vec();
    let mut settled = n == 0;
    let mut wedged = vec![false; n];
    for _ in 0..max_sweeps {
        if crate::cancel::expired() {
            break;
        }
        let mut change = 0.0f64;
        for i in 0..n {
            let a = w[(i, i)];
            let row = t.row_of[i];
            let (l0, t0) = (lambda[i], row.map_or(0.0, |k| tau[k]));
            let (l1, t1, st) = match row {
                None => {
                    let r_n = gap[i] - a * l0;
                    let l = (-r_n / a).max(0.0);
                    (l, 0.0, if l > 0.0 { State::Stick } else { State::Open })
                }
                Some(k) => {
                    let (b, b2, d) = (w[(i, n + k)], w[(n + k, i)], w[(n + k, n + k)]);
                    let r_n = gap[i] - a * l0 - b * t0;
                    let r_t = slip[k] + b2 * l0 + d * t0;
                    let cone = (t.law[k].as_ref(), t.along(k, 1.0, 0.0), l0);
                    match closed.get(k).copied().flatten() {
                        Some(datum) => {
                            let (l, tau, st, stuck) = local_tied([a, b], r_n, datum, cone);
                            wedged[i] = stuck;
                            (l, tau, st)
                        }
                        None => local([[a, b], [b2, d]], [r_n, r_t], cone),
                    }
                }
            };
            state[i] = st;
            let (dl, dt) = (l1 - l0, t1 - t0);
            if dl == 0.0 && dt == 0.0 {
                continue;
            }
            change = change.max(dl.abs()).max(dt.abs());
            lambda[i] = l1;
            for r in 0..n {
                gap[r] += w[(r, i)] * dl;
            }
            for r in 0..nt {
                slip[r] -= w[(n + r, i)] * dl;
            }
            if let Some(k) = row {
                tau[k] = t1;
                for r in 0..n {
                    gap[r] += w[(r, n + k)] * dt;
                }
                for r in 0..nt {
                    slip[r] -= w[(n + r, n + k)] * dt;
                }
            }
        }
        let largest = lambda.iter().chain(&tau).fold(0.0f64, |m, v| m.max(v.abs()));
        if change <= tol * largest {
            settled = true;
            break;
        }
    }
    let wedged: Vec<usize> = (0..n).filter(|&i| wedged[i]).collect();
    Sweeps {
        lambda,
        tau,
        state,
        settled: settled && wedged.is_empty(),
        wedged,
    }
}

/// One point's Coulomb problem (module docs): its (λ, τ) and state.
/// `block` is the point's [[a, b], [b′, d]], `r` its (r_N, r_T), `cone` its
/// law, ℓ and the normal force where a sliding point's bound is linearized.
fn local(block: [[f64; 2]; 2], r: [f64; 2], cone: (&dyn FrictionLaw, f64, f64)) -> (f64, f64, State) {
    let [[a, b], [b2, d]] = block;
    let [r_n, r_t] = r;
    let (law, lean, at) = cone;
    let det = a * d - b * b2;
    if det > 0.0 {
        let l = (-r_n * d - b * r_t) / det;
        let tau = (a * r_t + b2 * r_n) / det;
        if l >= 0.0 && (tau + lean * l).abs() <= law.bound(l) {
            return (l, tau, State::Stick);
        }
    }
    for sign in [1i8, -1] {
        // τ = g λ + c on the cone's edge (c = 0 for Coulomb, left out of
        // the sums then so that its answers stay what they were).
        let (g, c) = slip_line(law, sign, lean, at);
        let den = a + b * g;
        if den <= 0.0 {
            continue;
        }
        let (l, tau, s) = if c == 0.0 {
            let l = -r_n / den;
            (l, g * l, r_t - b2 * l - d * g * l)
        } else {
            let l = -(r_n + b * c) / den;
            let tau = g * l + c;
            (l, tau, r_t - b2 * l - d * tau)
        };
        if l >= 0.0 && f64::from(sign) * s >= 0.0 {
            return (l, tau, State::Slip(sign));
        }
    }
    if r_n >= 0.0 {
        return (0.0, 0.0, State::Open);
    }
    // No case holds exactly (a cone too wide for this point's coupling):
    // the normal force that closes the gap, the friction at the cone's edge
    // toward the stick answer.
    let l = (-r_n / a).max(0.0);
    let stick = if det > 0.0 { (a * r_t + b2 * r_n) / det } else { 0.0 };
    let along = law.project(l, stick + lean * l);
    let sign = if along >= 0.0 { 1 } else { -1 };
    (l, along - lean * l, State::Slip(sign))
}

/// A tied point's problem (module docs): closed, it slips by `datum`
/// whatever its forces, so its friction force lies on the cone's edge that
/// opposes the datum (τ = γ λ + c, `slip_line`), or along −ℓ λ for a datum of
/// 0, and λ closes the gap, (a + b γ) λ + b c + r_N = 0; open where that λ is
/// negative, or where a + b γ ≤ 0 (wedged, the last value true, when the gap
/// is then closed). `row` is the point's (a, b).
fn local_tied(row: [f64; 2], r_n: f64, datum: f64, cone: (&dyn FrictionLaw, f64, f64)) -> (f64, f64, State, bool) {
    let [a, b] = row;
    let (law, lean, at) = cone;
    let (g, c, st) = match datum.partial_cmp(&0.0) {
        Some(std::cmp::Ordering::Greater) => {
            let (g, c) = slip_line(law, 1, lean, at);
            (g, c, State::Slip(1))
        }
        Some(std::cmp::Ordering::Less) => {
            let (g, c) = slip_line(law, -1, lean, at);
            (g, c, State::Slip(-1))
        }
        _ => (-lean, 0.0, State::Stick),
    };
    let den = a + b * g;
    if den <= 0.0 {
        return (0.0, 0.0, State::Open, r_n < 0.0);
    }
    let l = -(r_n + b * c) / den;
    if l > 0.0 {
        (l, g * l + c, st, false)
    } else {
        (0.0, 0.0, State::Open, false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::friction_law::{Coulomb, Law};

    /// A single point whose answer is known in each case: with a = d = 1,
    /// b = b′ = 0.3, μ = 0.5, a gap closed by r_N = −1 and a slip push r_T:
    /// r_T = 0.1 sticks (τ = −0.22, within μλ = 0.53), r_T = 2 slides
    /// forward at τ = μλ, r_T = −2 backward; r_N = 1 is open. Each answer
    /// satisfies its case's equations to round-off.
    #[test]
    fn the_local_problem_takes_the_case_that_holds() {
        let (a, b, d, mu) = (1.0, 0.3, 1.0, 0.5);
        let block = [[a, b], [b, d]];
        let (l, tau, st) = local(block, [-1.0, 0.1], (&Coulomb { mu }, 0.0, 0.0));
        assert_eq!(st, State::Stick);
        assert!((a * l + b * tau - 1.0).abs() < 1e-15 && (0.1 - b * l - d * tau).abs() < 1e-15);
        for (r_t, sign) in [(2.0, 1), (-2.0, -1)] {
            let (l, tau, st) = local(block, [-1.0, r_t], (&Coulomb { mu }, 0.0, 0.0));
            assert_eq!(st, State::Slip(sign));
            assert!((tau - f64::from(sign) * mu * l).abs() < 1e-15);
            assert!((a * l + b * tau - 1.0).abs() < 1e-15);
            assert!(f64::from(sign) * (r_t - b * l - d * tau) > 0.0);
        }
        assert_eq!(
            local(block, [1.0, 0.3], (&Coulomb { mu }, 0.0, 0.0)),
            (0.0, 0.0, State::Open)
        );
    }

    /// Each point's (λ, τ, Δs) after asserting the discrete Coulomb law's
    /// normal part, cone and dissipation to 1e-9 (see the tests' docs).
    fn coulomb_holds(w: &Mat<f64>, (q, e): (&[f64], &[f64]), r: &Sweeps, mu: f64, case: u64) -> Vec<(f64, f64, f64)> {
        let n = q.len();
        let x: Vec<f64> = r.lambda.iter().chain(&r.tau).copied().collect();
        let wx = crate::linalg::dense::matvec(w, &x);
        let tol = 1e-9;
        (0..n)
            .map(|i| {
                let (l, tau) = (r.lambda[i], r.tau[i]);
                let (gap, slip) = (wx[i] + q[i], e[i] - wx[n + i]);
                assert!(
                    l >= -tol && gap >= -tol && (l * gap).abs() <= tol,
                    "case {case}, {i}: λ {l}, w {gap}"
                );
                assert!(tau.abs() <= mu * l + tol, "case {case}, {i}: τ {tau}, λ {l}");
                assert!(-tau * slip <= tol, "case {case}, {i}: τ {tau}, Δs {slip}");
                (l, tau, slip)
            })
            .collect()
    }

    /// A generator of numbers in [−1, 1) (a linear congruence: the tests'
    /// cases are the same on every run).
    fn numbers(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// On random compliances with normal–tangential coupling (W = A Aᵀ/2n + I,
    /// as in `friction`'s test of the Newton iteration) the sweeps settle on
    /// the discrete Coulomb law: λ ≥ 0, w ≥ 0, λ w = 0, |τ| ≤ μλ, −τ Δs ≤ 0 and
    /// no slip inside the cone, each to 1e-9 of the problem's scale (sweeps run
    /// to a change of 1e-13 per sweep; their linear convergence leaves about
    /// that divided by the contraction's gap).
    #[test]
    fn the_sweeps_settle_on_the_discrete_coulomb_law() {
        let (n, mu) = (8, 0.4);
        let mut next = numbers(7);
        for case in 0..100 {
            let a = Mat::<f64>::from_fn(2 * n, 2 * n, |_, _| next());
            let w = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| {
                (0..2 * n).map(|k| a[(i, k)] * a[(j, k)]).sum::<f64>() / (2 * n) as f64 + f64::from(i == j)
            });
            let q: Vec<f64> = (0..n).map(|_| next()).collect();
            let e: Vec<f64> = (0..n).map(|_| 0.5 * next()).collect();
            let t = Tangents {
                of: (0..n).collect(),
                row_of: (0..n).map(Some).collect(),
                law: (0..n).map(|_| -> Law { std::sync::Arc::new(Coulomb { mu }) }).collect(),
                ..Default::default()
            };
            let r = sweep(&w, (&q, &e, &[]), &t, 100_000, 1e-13);
            assert!(r.settled, "case {case}");
            let tol = 1e-9;
            for (i, (l, tau, slip)) in coulomb_holds(&w, (&q, &e), &r, mu, case).into_iter().enumerate() {
                assert!(
                    (mu * l - tau.abs()).max(0.0) * slip.abs() <= tol,
                    "case {case}, {i}: slip {slip} inside"
                );
            }
        }
    }

    /// Points whose tangential row is tied to their normal row (its row of W
    /// r times the normal row's, as for a contact edge held along x) beside
    /// untied ones, μ = 0.4 on all. W = B Bᵀ / m with the tied rows of B
    /// proportional, so a tied point's slip at w = 0 is the datum e + r q.
    /// With ratio r of W in (−1, 1) here, 1 + r γ > 0: every point has a
    /// Coulomb answer.
    struct TiedCase {
        w: Mat<f64>,
        q: Vec<f64>,
        e: Vec<f64>,
        datum: Vec<Option<f64>>,
        t: Tangents,
    }

    fn tied_case(seed: u64, n: usize, mu_tied: f64) -> TiedCase {
        let (m, mu) = (3 * n, 0.4);
        let mut next = numbers(seed);
        let ratio: Vec<Option<f64>> = (0..n).map(|i| (i % 2 == 0).then(&mut next)).collect();
        let mut b = Mat::<f64>::from_fn(2 * n, m, |_, _| next());
        for (i, r) in ratio.iter().enumerate() {
            if let Some(r) = r {
                for j in 0..m {
                    b[(n + i, j)] = r * b[(i, j)];
                }
            }
        }
        let w = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| {
            (0..m).map(|k| b[(i, k)] * b[(j, k)]).sum::<f64>() / m as f64
        });
        let q: Vec<f64> = (0..n).map(|_| next()).collect();
        let e: Vec<f64> = (0..n).map(|_| 0.5 * next()).collect();
        let datum: Vec<Option<f64>> = (0..n).map(|i| ratio[i].map(|r| e[i] + r * q[i])).collect();
        let law = |i: usize| -> Law {
            let mu = if ratio[i].is_some() { mu_tied } else { mu };
            std::sync::Arc::new(Coulomb { mu })
        };
        let t = Tangents {
            of: (0..n).collect(),
            row_of: (0..n).map(Some).collect(),
            law: (0..n).map(law).collect(),
            ..Default::default()
        };
        TiedCase { w, q, e, datum, t }
    }

    /// On such cases (`tied_case`, μ = 0.4 everywhere) the sweeps settle on
    /// the discrete Coulomb law (as in the test above, 1e-9 of the problem's
    /// scale) with each tied point in contact slipping by its datum and
    /// τ = ± μ λ against it.
    #[test]
    fn tied_points_slip_by_the_datum_their_gap_fixes() {
        let (n, mu) = (8, 0.4);
        let mut checked = 0;
        for case in 0..100 {
            let TiedCase { w, q, e, datum, t } = tied_case(11 + case, n, mu);
            let r = sweep(&w, (&q, &e, &datum), &t, 100_000, 1e-13);
            assert!(r.settled && r.wedged.is_empty(), "case {case}");
            let tol = 1e-9;
            for (i, (l, tau, slip)) in coulomb_holds(&w, (&q, &e), &r, mu, case).into_iter().enumerate() {
                match datum[i] {
                    Some(d) if l > tol => {
                        checked += 1;
                        assert!((slip - d).abs() <= tol, "case {case}, {i}: slip {slip}, datum {d}");
                        assert!(
                            (tau - d.signum() * mu * l).abs() <= tol,
                            "case {case}, {i}: τ {tau}, λ {l}"
                        );
                    }
                    Some(_) => {}
                    None => assert!(
                        (mu * l - tau.abs()).max(0.0) * slip.abs() <= tol,
                        "case {case}, {i}: slip {slip} inside"
                    ),
                }
            }
        }
        // Tied points in contact were met (most cases close some).
        assert!(checked > 50, "{checked}");
    }

    /// With μ = 20 on the tied points (|r| μ > 1 for most: a tied point
    /// pressed in and sliding would wedge) no force comes out beyond the
    /// problem's scale, max |q| / min a (before, the stick case divided by
    /// the round-off of the singular block and gave forces up to about 1e16
    /// times it), and a tied point left penetrating is one named wedged,
    /// with 1 + r γ ≤ 0 for its datum's sense; the sweeps then do not settle.
    #[test]
    fn a_tied_point_that_would_wedge_is_named_not_forced() {
        let (n, mu) = (8, 20.0);
        let mut wedged = 0;
        for case in 0..100 {
            let TiedCase { w, q, e, datum, t } = tied_case(11 + case, n, mu);
            let r = sweep(&w, (&q, &e, &datum), &t, 100_000, 1e-13);
            let a_min = (0..n).map(|i| w[(i, i)]).fold(f64::INFINITY, f64::min);
            let q_max = q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            // 1e3: the others' couplings add to a point's right-hand side at
            // most a few times q; a wedge gave 1e13 and more.
            let scale = 1e3 * q_max / a_min;
            for i in 0..n {
                assert!(
                    r.lambda[i].abs() <= scale && r.tau[i].abs() <= mu * scale,
                    "case {case}, {i}: λ {}, τ {}, scale {scale}",
                    r.lambda[i],
                    r.tau[i]
                );
            }
            let x: Vec<f64> = r.lambda.iter().chain(&r.tau).copied().collect();
            let wx = crate::linalg::dense::matvec(&w, &x);
            for i in 0..n {
                let gap = wx[i] + q[i];
                if gap < -1e-9 {
                    assert!(
                        r.wedged.contains(&i),
                        "case {case}, {i}: w {gap}, wedged {:?}",
                        r.wedged
                    );
                }
            }
            for &i in &r.wedged {
                let d = datum[i].expect("a tied point");
                let ratio = w[(n + i, i)] / w[(i, i)];
                assert!(1.0 + ratio * d.signum() * mu <= 0.0 || d == 0.0, "case {case}, {i}");
            }
            assert!(r.wedged.is_empty() || !r.settled, "case {case}");
            wedged += r.wedged.len();
        }
        assert!(wedged > 0, "no case wedged");
    }
}
