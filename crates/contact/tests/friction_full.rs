//! Coulomb friction on the full system (`methods::friction::full`): the same
//! discrete problem as the condensed path, solved on K in coordinates turned
//! to each contact node's normal and tangent instead of on the condensed
//! compliance. It serves `formulation: full` and the scenes whose rows
//! exceed what the condensed operator holds, on nodal rows.

mod common;
use common::*;
use contact::proto::{ErrorCode, FrictionState, SolveReply, SolveStatus};
use contact::scene::Limits;
use contact_verify::build::*;
use serde_json::{json, Value};

const MU: f64 = 0.5;

/// The roller of `common::friction_roller` with μ = 0.5.
fn roller(element: &str, nu: f64, h: f64, shifts: &[f64]) -> Value {
    friction_roller(element, nu, h, shifts, Some(MU))
}

fn on_full(req: &Value) -> Value {
    let mut r = req.clone();
    r["settings"]["formulation"] = json!("full");
    r
}

/// Every step of `a` and `b` has the same states at every point, and the
/// same pressures, tangential tractions and resultants to `tol` of the
/// largest pressure (of the largest force for the resultants).
fn assert_same_steps(a: &SolveReply, b: &SolveReply, tol: f64) {
    let (sa, sb) = (steps(a), steps(b));
    assert_eq!(sa.len(), sb.len());
    let mut worst = 0.0f64;
    for (k, (x, y)) in sa.iter().zip(&sb).enumerate() {
        assert_eq!(x.2, SolveStatus::Solved, "step {k}");
        assert_eq!(y.2, SolveStatus::Solved, "step {k}");
        for (pa, pb) in x.0.iter().zip(&y.0) {
            let peak = pa.points.iter().fold(0.0f64, |m, p| m.max(p.pressure));
            assert!(peak > 0.0, "step {k}: nothing pressed");
            assert_eq!(pa.points.len(), pb.points.len(), "step {k}");
            for (p, q) in pa.points.iter().zip(&pb.points) {
                assert_eq!(p.state, q.state, "step {k} at x = {}", p.x);
                let dp = (p.pressure - q.pressure).abs();
                let dt = (p.tangential_traction.unwrap_or(0.0) - q.tangential_traction.unwrap_or(0.0)).abs();
                worst = worst.max(dp.max(dt) / peak);
            }
        }
        let scale = x.1.fx.abs().max(x.1.fy.abs());
        worst = worst.max((x.1.fx - y.1.fx).abs().max((x.1.fy - y.1.fy).abs()) / scale);
    }
    assert!(worst <= tol, "the two answers differ by {worst:e} of the peak");
}

/// The flat punch of `indentation_flat_punch.json` (half-width 1, T3 block
/// 40 × 20 graded to 0.02, ν = 0.3) with μ = 0.3 and prescribed motions:
/// pressed down by 0.02, then moved sideways by 0.002, 0.004 and 0.012.
fn punch_moved() -> Value {
    let mut r = example("indentation_flat_punch.json");
    r["bodies"][0]["mesh"]["rectangle"]["grading"]["h_min"] = json!(0.02);
    r["contacts"][0]["friction"] = json!({"coefficient": 0.3});
    r["obstacles"][0]["punch"] = json!({
        "reference": [0.0, 0.0],
        "horizontal": {"displacement": 0.004},
        "vertical": {"displacement": -0.02},
        "rotation": {"displacement": 0.0}
    });
    r["load_path"] = json!([0.0, 0.5, 1.0, 3.0]
        .iter()
        .map(|f| json!({"loads": {"/obstacles/0/punch/horizontal": f}}))
        .collect::<Vec<_>>());
    r
}

/// The block of `signorini_hertz_cylinder.json` (T3, graded to 0.02, ν = 0.3)
/// under its fixed rigid cylinder with μ = 0.3, its bottom then moved
/// sideways by 0.002, 0.004 and 0.01.
fn block_sheared() -> Value {
    let mut r = example("signorini_hertz_cylinder.json");
    let b = &mut r["bodies"][0];
    b["mesh"]["rectangle"]["grading"]["h_min"] = json!(0.02);
    b["supports"] = json!([{"edges": "bottom", "uy": 0.0}, {"edges": "bottom", "ux": 1.0}]);
    r["contacts"][0]["friction"] = json!({"coefficient": 0.3});
    r["load_path"] = shift_path(&[0.0, 0.002, 0.004, 0.01]);
    r
}

/// The full system solves the condensed path's discrete problem: on the T3
/// roller at ν = 0.3 (where the normal load alone makes points slip), the
/// flat punch moved sideways (slip relative to a moving obstacle) and the
/// block sheared under a cylinder (rows along a curved obstacle's normals),
/// through pressing, sticking, partial and full sliding, the same points
/// stick, slip and open at every step, and pressures, tractions and
/// resultants agree to 1e-8 of the peak. Both end on the exact solution of
/// the same state set's linear system (GMRES run to 1e-14 on the full
/// system), so they differ by the round-off of two factorizations (measured
/// 5e-13 to 3.8e-12); the certificate holds to 1e-8 as on the condensed path.
#[test]
fn the_full_system_gives_the_condensed_answer() {
    for req in [
        roller("t3", 0.3, 0.01, &[0.0, 0.015, 0.03, 0.06]),
        punch_moved(),
        block_sheared(),
    ] {
        let condensed = solved(&req);
        let full = solved(&on_full(&req));
        assert_eq!(full.method, "active_set_full");
        assert_same_steps(&condensed, &full, 1e-8);
        assert_kkt(&full, 1e-8);
        // Some step slides somewhere: the unsymmetric system was solved.
        assert!(steps(&full)
            .iter()
            .any(|s| s.0[0].points.iter().any(|p| p.state == Some(FrictionState::Slip))));
    }
}

/// Spence's flat punch (`friction.rs::spence_flat_punch_stick_zone`: ν = 0.3,
/// μ = 0.3, block 1280a deep, T3 graded to 0.01) pressed by a prescribed
/// motion, which by symmetry is the load-controlled problem (no horizontal
/// load, no moment; c/a does not depend on the load). With the row limit set
/// below its rows it is solved on the full system, says so, answers as the
/// condensed path does (1e-8 of the peak), and its stick zone is the panel
/// reference's c/a = 0.689 within 2 % (that test's tolerance and reasons;
/// measured 0.695 on both paths, +0.9 %).
#[test]
fn rows_past_the_condensed_limit_are_solved_on_the_full_system() {
    let (nu, mu) = (0.3, 0.3);
    let mut req = spence_block(nu, mu, 0.01, 64.0);
    req["obstacles"][0]["punch"] = json!({
        "reference": [0.0, 0.0],
        "horizontal": {"displacement": 0.0},
        "vertical": {"displacement": -0.1},
        "rotation": {"displacement": 0.0}
    });
    let condensed = solved(&req);
    let limits = Limits {
        max_candidates: 100,
        ..Limits::default()
    };
    let full = solve_with(&req, &limits).expect("solved on the full system");
    assert_eq!(full.status, SolveStatus::Solved);
    assert_eq!(full.method, "active_set_full");
    assert!(
        full.notes
            .iter()
            .any(|n| n.contains("full system") && n.contains("exceed the 100")),
        "{:?}",
        full.notes
    );
    assert_eq!(
        note_kind(&full, "full system"),
        Some(contact::proto::NoteKind::FullSystem)
    );
    for r in [&condensed, &full] {
        let pts = &r.pairs[0].points;
        let stick = run_ends(pts, |q| q.state == Some(FrictionState::Stick));
        let c = 0.5 * (stick[1] - stick[0]);
        let beta = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));
        let coarse = contact_verify::reference::flat_punch_with_friction(beta, mu, 200);
        let fine = contact_verify::reference::flat_punch_with_friction(beta, mu, 400);
        let expect = 2.0 * fine.c - coarse.c;
        assert!((c / expect - 1.0).abs() < 0.02, "{}: c {c} vs {expect}", r.method);
    }
    let peak = condensed.pairs[0].points.iter().fold(0.0f64, |m, p| m.max(p.pressure));
    for (p, q) in condensed.pairs[0].points.iter().zip(&full.pairs[0].points) {
        assert_eq!(p.state, q.state, "x = {}", p.x);
        let dt = (p.tangential_traction.unwrap() - q.tangential_traction.unwrap()).abs();
        assert!((p.pressure - q.pressure).abs().max(dt) <= 1e-8 * peak, "x = {}", p.x);
    }
}

/// What the full system does not take is refused, saying why: a
/// load-controlled punch (its motions are unknowns of the condensed Newton
/// system only) and mortar rows (T6) on `formulation: full` at the setting,
/// and past the row limit as `too_large`.
#[test]
fn what_the_full_system_does_not_take_is_refused() {
    let punch = example("friction_flat_punch_pushed.json");
    let mortar = roller("t6", 0.499, 0.01, &[0.0, 0.02]);
    for (req, why) in [(&punch, "condensed formulation only"), (&mortar, "nodal contact rows")] {
        let e = solve(&on_full(req)).expect_err("refused");
        assert_eq!(e.code, ErrorCode::InvalidRequest, "{e:?}");
        assert_eq!(e.path, "/settings/formulation");
        assert!(e.message.contains(why), "{}", e.message);
        let limits = Limits {
            max_candidates: 10,
            ..Limits::default()
        };
        let e = solve_with(req, &limits).expect_err("refused");
        assert_eq!(e.code, ErrorCode::TooLarge, "{e:?}");
        assert!(e.message.contains(why), "{}", e.message);
    }
}

/// A T3 strip 10 × 0.2 (E = 200, ν = 0.3, elements 0.02) on a rigid floor
/// with μ = 0.3, its top pressed down by 0.001 (held sideways) and then
/// moved sideways by 0.0002 and 0.0005: every bottom node in contact, 1002
/// rows on 11k DOF.
fn strip() -> Value {
    let strip = body("strip", 200.0, 0.3, rectangle([-5.0, 0.0], 10.0, 0.2, 0.02, "t3"))
        .support("top", None, Some(-0.001))
        .support("top", Some(1.0), None);
    let mut r = request(
        vec![strip],
        vec![pair("strip", "bottom").obstacle("floor").friction(0.3)],
    )
    .with_obstacle(obstacle("floor", line([0.0, 0.0], [0.0, 1.0])))
    .to_value();
    r["load_path"] = shift_path(&[0.0, 0.0002, 0.0005]);
    r
}

/// Many rows on few DOFs: `auto` solves the strip on the full system (its
/// dense condensed Newton systems cost more than factoring K: measured on
/// strips of 40k and 80k DOF, 2.6 and 8.6 times the full system's time) and
/// answers as the condensed active set does (1e-8 of the peak, as above).
/// Fifteen thicknesses from its ends the strip is in the uniform state of the
/// theory: the bottom sticks (|τ| = 0.19 < μ p = 0.40), ε_xx = 0, so the
/// pressure is E(1 − ν)/((1 + ν)(1 − 2ν)) · δ/h and the friction traction
/// G s/h for the top's shift s. Linear elements reproduce a uniform state
/// exactly (the patch test), so both hold there to round-off and the end
/// effects' decay: tested at 1e-9, measured 1.1e-12 (ten thicknesses from
/// the ends, 6e-9).
#[test]
fn auto_solves_many_rows_on_few_dofs_on_the_full_system() {
    let req = strip();
    let auto = solved(&req);
    assert_eq!(auto.method, "active_set_full");
    let mut condensed = req.clone();
    condensed["method"] = json!("active_set");
    let condensed = solved(&condensed);
    assert_eq!(condensed.method, "active_set");
    assert_same_steps(&condensed, &auto, 1e-8);
    let (e, nu, h) = (200.0, 0.3, 0.2);
    let p = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) * 0.001 / h;
    let g = e / (2.0 * (1.0 + nu));
    for (k, (pairs, _, _)) in steps(&auto).iter().enumerate() {
        let q = g * [0.0, 0.0002, 0.0005][k] / h;
        let middle: Vec<_> = pairs[0].points.iter().filter(|pt| pt.x.abs() < 2.0).collect();
        assert!(middle.len() > 150);
        for pt in middle {
            assert_eq!(pt.state, Some(FrictionState::Stick), "step {k}: {pt:?}");
            assert!(
                (pt.pressure / p - 1.0).abs() <= 1e-9,
                "step {k}: p {} vs {p}",
                pt.pressure
            );
            let t = pt.tangential_traction.unwrap().abs();
            assert!((t - q).abs() <= 1e-9 * p, "step {k}: |t| {t} vs {q}");
        }
    }
}
