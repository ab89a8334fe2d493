//! Coulomb friction on bodies of revolution: the tangent of a row is the
//! meridian's, so friction acts along the axis or the radius, never around
//! it (no torsion in axisymmetry).
//!
//! The scene (`proto/examples/friction_press_fit_pushed_out.json`): the press
//! fit of `axisymmetric.rs::press_fit_matches_lame` (shaft of radius b = 1 in
//! a ring of outer radius c = 2, both of height L = 1, E = 200, ν = 0.3,
//! radial interference δ = 0.001, mortar rows on the ring's bore) with
//! friction μ, closed through its interference in the first step (the ends
//! held axially), then pushed out: the shaft's end is moved 0.01 along the
//! axis, far beyond the elastic slip (δ/b · L = 0.001).

mod common;
use common::*;
use contact::proto::{FrictionState, PairResult, Resultant, SolveReply, SolveStatus, Warning, WarningCode};
use serde_json::{json, Value};

/// The steps of a frictional reply, after checking that each one solved
/// with the friction residuals at round-off (1e-10; measured ≤ 9e-16).
fn every_step_solved(r: &SolveReply, mu: f64) -> Vec<(Vec<PairResult>, Resultant, SolveStatus)> {
    let friction = r.certificate.friction.expect("friction residuals");
    for v in [friction.cone, friction.dissipation, friction.stick] {
        assert!(v <= 1e-10, "μ {mu}: {friction:?}");
    }
    let all = steps(r);
    assert!(all.iter().all(|s| s.2 == SolveStatus::Solved), "μ {mu}");
    all
}

/// `friction_press_fit_pushed_out.json` with friction `mu`.
fn press_fit(mu: f64) -> Value {
    let mut r = example("friction_press_fit_pushed_out.json");
    r["contacts"][0]["friction"]["coefficient"] = json!(mu);
    r
}

/// Pushed out, the whole bore slides: every point at t = μ p (to 1e-9 of it,
/// the LU's round-off), so the push-out force, the friction resultant along
/// the axis, is μ times the normal ring force Σ λ (to 1e-12: this checks the
/// ring weights of the friction forces against the normal ones'), and the
/// shaft takes the opposite force. With Lamé's pressure p = E δ (c² − b²) /
/// (2 b c²) over the bore's area 2π b L it is μ p 2π b L: at μ = 0.05 within
/// 1.5 % (measured +0.93 %; frictionless the mean pressure is Lamé's within
/// 0.5 %, and the friction's axial traction μ p changes the fit through ν by
/// about 0.16 μ: +1.7, +3.2, +6.2 % at μ = 0.1, 0.2, 0.4, measured).
///
/// Closing the interference with friction, the shaft's Poisson lengthening
/// and the ring's shortening slide against each other on part of the bore
/// while the rest sticks (10 and 11 of its 21 points at μ = 0.2); some
/// points sit exactly on their cone's edge
/// without slip, where the Newton iteration's states alternated with the
/// same answer and the step ran out of iterations (μ = 0.1 and 0.4, one of
/// them with forces of 1e14): the iteration now stops on the Alart–Curnier
/// residual, and a Newton run that cycles hands over to nonsmooth
/// Gauss–Seidel (μ = 0.2). Every step is solved with the friction residuals
/// at round-off (1e-10; measured ≤ 9e-16).
#[test]
fn a_press_fit_pushed_out_slides_at_mu_times_the_fit_force() {
    let lame = 200.0 * 0.001 * (4.0 - 1.0) / (2.0 * 4.0);
    let area = 2.0 * std::f64::consts::PI * 0.999;
    for mu in [0.05, 0.1, 0.2, 0.4] {
        let r = solved(&press_fit(mu));
        let all = every_step_solved(&r, mu);
        let pair = &all[1].0[0];
        let normal: f64 = pair.points.iter().map(|p| p.force).sum();
        for p in &pair.points {
            assert_eq!(p.state, Some(FrictionState::Slip), "μ {mu}: {p:?}");
            let t = p.tangential_traction.unwrap().abs();
            assert!((t - mu * p.pressure).abs() <= 1e-9 * mu * p.pressure, "μ {mu}: {p:?}");
        }
        let f = pair.friction.as_ref().expect("friction").tangential_resultant;
        assert!(
            (f.fy.abs() - mu * normal).abs() <= 1e-12 * mu * normal,
            "μ {mu}: {f:?} vs μ N {}",
            mu * normal
        );
        // The bore is vertical: its slip zone as an x-interval collapses to
        // [0.999, 0.999]; by its end points it is the whole bore.
        let fr = pair.friction.as_ref().unwrap();
        let [[a, b]] = fr.slip_runs[..] else {
            panic!("μ {mu}: one slip run, {:?}", fr.slip_runs)
        };
        let near = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs().max((p[1] - q[1]).abs()) < 1e-12;
        assert!(near(a, [0.999, 0.0]) && near(b, [0.999, 1.0]), "μ {mu}: {a:?} {b:?}");
        assert!(fr.stick_runs.is_empty(), "μ {mu}");
        let other = pair.other_resultant.expect("the shaft's force");
        assert!((other.fy + pair.resultant.fy).abs() <= 1e-12 * normal, "{other:?}");
        if mu == 0.05 {
            let push = f.fy.abs() / (mu * lame * area);
            assert!((push - 1.0).abs() < 0.015, "push-out force {push} of Lamé's");
        }
    }
}

/// The press fit pulled out by the shaft's top (its far end from the ring's
/// held bottom) with friction μ: the bore's points that stay in contact
/// stick, and μ large is the stick limit. Why the top: with both bottoms
/// held axially (`press_fit`), the bore's bottom node lies on both held
/// faces, so moving the shaft's bottom prescribes its slip (0.01 over the
/// step). It must slide there with the friction force μ λ, which grows with
/// μ without bound (2.2e4 at μ = 1e4) and reaches the free nodes through
/// the mortar weights: that scene has no bounded limit as μ grows, and at
/// μ ≥ 100 its second step ends at `max_iterations`.
///
/// Measured (h = 0.05, 21 points): the bore opens except on z ∈ [0.15, 0.55];
/// z ∈ [0.25, 0.4] sticks; the four points at the zone's two ends slip with
/// a pressure that vanishes as 1/μ (≤ 8.8/μ of the peak, measured) while
/// their shear stays finite (0.3–1.9, the stuck points' order): the limit
/// μ → ∞ of Coulomb's law lets a point carry shear at a pressure → 0, so
/// those points slip at every finite μ. The push-out force is 3.2774,
/// 3.3179 and 3.3183 at μ = 1e2, 1e4 and 1e6: it approaches its stick
/// limit as 1/μ, 1.2 % apart between 1e2 and 1e4, tested at 2 %.
#[test]
fn a_press_fit_pulled_by_its_far_end_sticks_as_mu_grows() {
    let mut push = Vec::new();
    for mu in [1e2, 1e4] {
        let mut req = press_fit(mu);
        req["bodies"][0]["supports"][0]["edges"] = json!("top");
        let r = solved(&req);
        assert_kkt(&r, 1e-10);
        let all = every_step_solved(&r, mu);
        let pair = &all[1].0[0];
        let peak = pair.points.iter().map(|p| p.pressure).fold(0.0, f64::max);
        let mut stuck = 0;
        for p in &pair.points {
            match p.state {
                Some(FrictionState::Stick) => stuck += 1,
                Some(FrictionState::Slip) => assert!(p.pressure <= 10.0 / mu * peak, "μ {mu}: {p:?}"),
                _ => {}
            }
        }
        assert!(stuck >= 4, "μ {mu}: the middle of the zone sticks");
        let f = pair.friction.as_ref().expect("friction").tangential_resultant;
        let other = pair.other_resultant.expect("the shaft's force");
        assert!((other.fy + pair.resultant.fy).abs() <= 1e-12 * f.fy.abs(), "{other:?}");
        push.push(f.fy);
    }
    assert!(
        push[0] > 0.0 && (push[1] / push[0] - 1.0).abs() < 0.02,
        "push-out forces {push:?}"
    );
}

/// The reply's `prescribed_slip` warnings.
fn prescribed_slip(r: &SolveReply) -> Vec<&Warning> {
    r.warnings
        .iter()
        .filter(|w| w.code == WarningCode::PrescribedSlip)
        .collect()
}

/// Pushed by the shaft's bottom with the ring's bottom held, the bore's
/// bottom node (0.999, 0) lies on both held faces: its slip is prescribed,
/// and the reply says so before a large μ is read as sticking, naming the
/// node, the pair and both supports. At μ = 0.2 the answer is Coulomb's and
/// solved (the warning beside it); at μ = 100 the step ends at
/// `max_iterations` with the same warning. Pulled by the shaft's top,
/// frictionless, or with both bottoms held still (a slip prescribed to 0), no
/// such warning.
#[test]
fn a_press_fit_pushed_by_its_bottom_warns_of_its_prescribed_slip() {
    for mu in [0.2, 100.0] {
        let r = solve(&press_fit(mu)).expect("a reply");
        let w = prescribed_slip(&r);
        assert_eq!(w.len(), 1, "μ {mu}: {:?}", r.warnings);
        let w = w[0];
        assert_eq!(
            (w.value, w.limit, w.location.as_str()),
            (1.0, 0.0, "/contacts/0"),
            "μ {mu}"
        );
        for part in [
            "body 'ring' at (0.999, 0)",
            "/bodies/0/supports/0 of 'shaft'",
            "/bodies/1/supports/0 of 'ring'",
            "by up to 0.01",
            "Release one of the supports",
        ] {
            assert!(w.message.contains(part), "μ {mu}: {part:?} not in {}", w.message);
        }
        let solved = r.status == SolveStatus::Solved;
        assert_eq!(solved, mu < 1.0, "μ {mu}: {:?}", r.status);
    }
    let mut top = press_fit(100.0);
    top["bodies"][0]["supports"][0]["edges"] = json!("top");
    let mut frictionless = press_fit(0.2);
    frictionless["contacts"][0].as_object_mut().unwrap().remove("friction");
    // Both bottoms held still: the slip is prescribed, to 0, and the node
    // sticks with a bounded force.
    let mut still = press_fit(100.0);
    still["bodies"][0]["supports"][0]["uy"] = json!(0.0);
    for req in [top, frictionless, still] {
        let r = solved(&req);
        assert!(prescribed_slip(&r).is_empty(), "{:?}", r.warnings);
    }
}
