//! Coulomb friction on a body held only by contact: its rigid motions are
//! unknowns of the frictional problem with their equilibrium, and loads no
//! contact force inside the cone can balance are refused.
//!
//! The scene: an elastic 2 × 1 block with no supports on a rigid flat floor,
//! a uniform pressure on its top (resultant P) and a uniform shear traction
//! there (resultant Q). Statics alone fix the floor's resultant: −Q along x,
//! P up, and the moment Q · 1 of Q's line of action at y = 1 about the
//! origin; the block is in equilibrium if and only if |Q| ≤ μ P (the cone of
//! a flat floor is the same at every point).

mod common;
use common::*;
use contact::proto::{ErrorCode, FrictionState, SolveStatus};
use contact_verify::build::*;
use serde_json::{json, Value};

/// A 2 × 1 elastic block with no supports on the rigid floor y = 0, pressed
/// by the pressure `p` on its top (P = 2p) and pushed by the shear traction
/// `q` there (Q = 2q); friction `mu` on the floor (frictionless with None).
fn block(element: &str, p: f64, q: f64, mu: Option<f64>) -> Value {
    let b = body("block", 1000.0, 0.25, rectangle([-1.0, 0.0], 2.0, 1.0, 0.1, element)).pressure("top", p);
    let mut r = request(vec![b], vec![pair("block", "bottom").obstacle("floor")])
        .with_obstacle(obstacle("floor", line([0.0, 0.0], [0.0, 1.0])))
        .to_value();
    if q != 0.0 {
        r["bodies"][0]["tractions"]
            .as_array_mut()
            .unwrap()
            .push(json!({"edges": "top", "traction": [q, 0.0]}));
    }
    if let Some(mu) = mu {
        r["contacts"][0]["friction"] = json!({"coefficient": mu});
    }
    r
}

const MU: f64 = 0.3;
/// The top pressure and P = 2 p, the floor's share of the pressure.
const PRESSURE: f64 = 1.0;
const P: f64 = 2.0 * PRESSURE;

/// |Q| < μP: the block stands. The floor's resultant is (−Q, P) with moment
/// Q (statics; what the free motions' equilibrium rows impose, to round-off:
/// 1e-12 of P, measured ≤ 1e-15), the friction resultant alone −Q, every
/// point inside the cone (|t| ≤ μ p to 1e-12 of μ p_max) and the
/// certificate's residuals, friction's included, at round-off (1e-10;
/// measured ≤ 3.6e-15). Both states appear: the floor's corners slip (the
/// pressure's peak there), the middle sticks; near μP most of it slips.
#[test]
fn a_block_pushed_below_mu_p_is_held_by_friction() {
    for element in ["t3", "t6"] {
        for ratio in [0.0, 0.3, 0.6, -0.6, 0.95] {
            let q = ratio * MU * P;
            let r = solved(&block(element, PRESSURE, 0.5 * q, Some(MU)));
            let what = format!("{element}, Q/μP {ratio}");
            assert_eq!(r.status, SolveStatus::Solved, "{what}");
            assert_kkt(&r, 1e-10);
            let friction = r.certificate.friction.expect("friction residuals");
            for v in [friction.cone, friction.dissipation, friction.stick] {
                assert!(v <= 1e-10, "{what}: {friction:?}");
            }
            let res = r.resultant;
            assert!((res.fx + q).abs() <= 1e-12 * P, "{what}: {res:?}");
            assert!((res.fy - P).abs() <= 1e-12 * P, "{what}: {res:?}");
            assert!((res.m - q).abs() <= 1e-12 * P, "{what}: {res:?}");
            let pair = &r.pairs[0];
            let f = pair.friction.as_ref().expect("friction on the pair");
            assert!((f.tangential_resultant.fx + q).abs() <= 1e-12 * P, "{what}: {f:?}");
            let p_max = pair.points.iter().map(|pt| pt.pressure).fold(0.0, f64::max);
            for pt in &pair.points {
                let t = pt.tangential_traction.expect("a tangential traction");
                assert!(t.abs() <= MU * pt.pressure + 1e-12 * MU * p_max, "{what}: {pt:?}");
            }
            let has = |s: FrictionState| pair.points.iter().any(|pt| pt.state == Some(s));
            assert!(has(FrictionState::Stick) && has(FrictionState::Slip), "{what}");
        }
    }
}

/// |Q| > μP: no contact force inside the cone balances Q, the block would
/// slide: refused before any step is solved, with Q's admissible range
/// [−μP, μP] in `details` (to the LP's tolerance: 1e-8 relative; measured
/// 3.8e-10), on either side, and also when only a later step of a load path
/// goes beyond it.
#[test]
fn a_block_pushed_beyond_mu_p_is_refused() {
    let expect_range = |e: &contact::proto::ErrorReply, q: f64| {
        assert_eq!(e.code, ErrorCode::IncompatibleLoads, "{e:?}");
        assert_eq!(e.path, "/bodies/0/tractions/1", "{e:?}");
        let loads = &e.details.as_ref().expect("details").loads;
        let b = loads
            .iter()
            .find(|b| (b.value - q).abs() <= 1e-12 * P)
            .unwrap_or_else(|| panic!("no range for Q = {q}: {loads:?}"));
        let (lo, hi) = (b.min.expect("a lower bound"), b.max.expect("an upper bound"));
        assert!((lo + MU * P).abs() <= 1e-8 * MU * P, "{b:?}");
        assert!((hi - MU * P).abs() <= 1e-8 * MU * P, "{b:?}");
    };
    for q in [1.05 * MU * P, -1.05 * MU * P] {
        let e = solve(&block("t3", PRESSURE, 0.5 * q, Some(MU))).expect_err("must be refused");
        expect_range(&e, q);
    }
    let q = 1.05 * MU * P;
    let mut path = block("t3", PRESSURE, 0.5 * q, Some(MU));
    path["load_path"] = json!([{"loads": {"/bodies/0/tractions/1": 0.5}}, {"loads": {"/bodies/0/tractions/1": 1.0}}]);
    let e = solve(&path).expect_err("must be refused");
    expect_range(&e, q);
}

/// The slip of a step is measured from where the previous one left the
/// body, its rigid motion included: the same loads again slip nowhere
/// (|slip| ≤ 1e-12 of the first step's largest, measured 3.6e-14 relative)
/// and leave the same tractions (1e-10 of p_max: the second step solves
/// its states from the first one's, to round-off).
#[test]
fn the_same_loads_again_do_not_slip() {
    let q = 0.8 * MU * P;
    let mut path = block("t3", PRESSURE, 0.5 * q, Some(MU));
    path["load_path"] = json!([{"loads": {"/bodies/0/tractions/1": 1.0}}, {"loads": {"/bodies/0/tractions/1": 1.0}}]);
    let r = solved(&path);
    let all = steps(&r);
    let (first, second) = (&all[0].0[0], &all[1].0[0]);
    let slip0 = first.points.iter().map(|pt| pt.slip.unwrap().abs()).fold(0.0, f64::max);
    assert!(slip0 > 0.0);
    let p_max = first.points.iter().map(|pt| pt.pressure).fold(0.0, f64::max);
    for (a, b) in first.points.iter().zip(&second.points) {
        assert!(b.slip.unwrap().abs() <= 1e-12 * slip0, "{b:?}");
        assert!((a.pressure - b.pressure).abs() <= 1e-10 * p_max, "{a:?} vs {b:?}");
        let (ta, tb) = (a.tangential_traction.unwrap(), b.tangential_traction.unwrap());
        assert!((ta - tb).abs() <= 1e-10 * p_max, "{a:?} vs {b:?}");
    }
}

/// μ = 0 is the frictionless solve, reply for reply, including its note that
/// the block's horizontal translation, which nothing resists and nothing
/// loads, is not determined.
#[test]
fn zero_friction_on_a_free_block_is_the_frictionless_reply() {
    let (mut a, mut b) = (
        solved(&block("t3", PRESSURE, 0.0, None)),
        solved(&block("t3", PRESSURE, 0.0, Some(0.0))),
    );
    for r in [&mut a, &mut b] {
        r.timings = Default::default();
        r.diagnostics.factorization_predicted = None;
    }
    assert!(
        b.notes
            .iter()
            .any(|n| n.contains("translation in x") && n.contains("not determined")),
        "{:?}",
        b.notes
    );
    assert_eq!(serde_json::to_value(&a).unwrap(), serde_json::to_value(&b).unwrap());
}

/// A small μ approaches the frictionless pressures (which are uniform, p = 1
/// to round-off, on this block with its horizontal slide free): the friction
/// tractions μ p change them by O(μ) through the block's normal–tangential
/// coupling, measured max |p − 1| = 3.15 μ at μ = 1e-3, 1e-6 and 1e-9 (the
/// corners); tested at 5 μ. (At μ = 1e-9 the slide's equilibrium is judged
/// against the loads' size too, not the 1e-9 friction forces alone.) At such μ the first update slides every point,
/// which leaves the block's slide with no equation; the point nearest its
/// cone sticks instead, and the run converges with the middle point stuck.
#[test]
fn small_friction_approaches_the_frictionless_pressures() {
    let plain = solved(&block("t3", PRESSURE, 0.0, None));
    for mu in [1e-3, 1e-6, 1e-9] {
        let r = solved(&block("t3", PRESSURE, 0.0, Some(mu)));
        for (a, b) in plain.pairs[0].points.iter().zip(&r.pairs[0].points) {
            assert!(
                (a.pressure - b.pressure).abs() <= 5.0 * mu * PRESSURE,
                "μ {mu}: {a:?} vs {b:?}"
            );
        }
        let stuck = r.pairs[0]
            .points
            .iter()
            .filter(|pt| pt.state == Some(FrictionState::Stick));
        assert!(stuck.count() >= 1, "μ {mu}");
    }
}

/// A block twice as tall as it is wide (b = 1, h = 2) with μ = 1 tips before
/// it slides. Statics with the floor's normal forces N_i at x_i and friction
/// forces F_i: Σ N = P, Σ F = −F_x, and about the body's centre c = (0, h/2)
/// (its rotation mode's) Σ x_i N_i = −M_c + (h/2) F_x, which the base holds
/// while |Σ x N| ≤ P b/2 (tipping about a corner); sliding needs |F_x| ≤ μP.
/// A shear Q on the top gives F_x = Q and M_c = −Q h/2, so the block stands
/// while |Q| ≤ P b/(2h) = P/4 < μP. At Q = 1.05 P/4 the cone check's LP
/// refuses it and gives each rigid mode's load range with the others held,
/// the closed forms F_x ∈ [(2/h)(M_c − Pb/2), (2/h)(M_c + Pb/2)] ∩ [−μP, μP],
/// M_c ∈ [(h/2)F_x − Pb/2, (h/2)F_x + Pb/2] and −F_y = P ≥ 2|Σ x N|/b, to the
/// LP's tolerance (1e-8 relative; measured 1.3e-9). At Q = 0.9 P/4 it stands:
/// the floor's resultant is (−Q, P) and the normal forces' centre at
/// Q h / P (0.9 of the half base), to 1e-10. So far out of the kern (b/6)
/// the heel lifts off: a rigid base's linear pressure would touch only on
/// 3(b/2 − e) from the toe, x > −0.325; the elastic block's zone is shorter
/// still (measured x ≥ 0.3), so every point with x < −0.325 is open.
#[test]
fn a_tall_block_tips_before_it_slides() {
    let mu = 1.0;
    let (b, h) = (1.0, 2.0);
    let tall = |q: f64| {
        let body = body("block", 1000.0, 0.25, rectangle([-0.5 * b, 0.0], b, h, 0.1, "t3")).pressure("top", PRESSURE);
        let mut r = request(vec![body], vec![pair("block", "bottom").obstacle("floor")])
            .with_obstacle(obstacle("floor", line([0.0, 0.0], [0.0, 1.0])))
            .to_value();
        r["bodies"][0]["tractions"]
            .as_array_mut()
            .unwrap()
            .push(json!({"edges": "top", "traction": [q / b, 0.0]}));
        r["contacts"][0]["friction"] = json!({"coefficient": mu});
        r
    };
    let p = PRESSURE * b;
    let limit = p * b / (2.0 * h);
    for q in [1.05 * limit, -1.05 * limit] {
        let e = solve(&tall(q)).expect_err("the block tips");
        assert_eq!(e.code, ErrorCode::IncompatibleLoads, "{e:?}");
        assert!(e.message.contains("tip"), "{}", e.message);
        let loads = &e.details.as_ref().expect("details").loads;
        let m_c = -q * h / 2.0;
        let close = |v: Option<f64>, expect: f64| v.is_some_and(|v| (v - expect).abs() <= 1e-8 * p);
        let of = |value: f64| {
            loads
                .iter()
                .find(|l| (l.value - value).abs() <= 1e-12 * p)
                .unwrap_or_else(|| panic!("no range for the load {value}: {loads:?}"))
        };
        let fx = of(q);
        let (lo, hi) = ((2.0 / h) * (m_c - p * b / 2.0), (2.0 / h) * (m_c + p * b / 2.0));
        assert!(
            close(fx.min, lo.max(-mu * p)) && close(fx.max, hi.min(mu * p)),
            "F_x: {fx:?}"
        );
        let m = of(m_c);
        let (lo, hi) = (h / 2.0 * q - p * b / 2.0, h / 2.0 * q + p * b / 2.0);
        assert!(close(m.min, lo) && close(m.max, hi), "M_c: {m:?}");
        let fy = of(-p);
        let needed = 2.0 * (-m_c + h / 2.0 * q).abs() / b;
        assert!(close(fy.max, -needed) && fy.min.is_none(), "F_y: {fy:?}");
    }
    let q = 0.9 * limit;
    let r = solved(&tall(q));
    let res = r.resultant;
    assert!(
        (res.fx + q).abs() <= 1e-10 * p && (res.fy - p).abs() <= 1e-10 * p,
        "{res:?}"
    );
    let points = &r.pairs[0].points;
    let moment: f64 = points.iter().map(|pt| pt.x * pt.force).sum();
    let normal: f64 = points.iter().map(|pt| pt.force).sum();
    assert!(
        (moment / normal - q * h / p).abs() <= 1e-10,
        "centre {} vs {}",
        moment / normal,
        q * h / p
    );
    let heel = points.iter().filter(|pt| pt.x < -0.325);
    assert!(heel.clone().count() >= 2 && heel.clone().all(|pt| pt.state == Some(FrictionState::Open)));
}

/// A step that runs out of iterations is not a silent answer: with one
/// iteration allowed the block's step ends `max_iterations`, and the reply
/// says that its loads pass the check with the friction cone and that the
/// step's normal forces leave friction enough to carry them (so the
/// iteration fell short, not the loads) and what to change; with the
/// default allowance the same request is solved.
#[test]
fn a_free_body_step_out_of_iterations_says_why() {
    let mut req = block("t3", PRESSURE, 0.5 * 0.6 * MU * P, Some(MU));
    req["settings"] = json!({"max_iterations": 1});
    let r = solve(&req).expect("an answer");
    assert_eq!(r.status, SolveStatus::MaxIterations);
    assert!(
        r.notes
            .iter()
            .any(|n| n.contains("body 'block'") && n.contains("max_iterations") && n.contains("friction enough")),
        "{:?}",
        r.notes
    );
    assert_eq!(
        note_kind(&r, "friction enough"),
        Some(contact::proto::NoteKind::UnsettledBody)
    );
    req["settings"] = json!({});
    solved(&req);
}

/// A steel roller (R 20) held only by contact on a plate, pressed by
/// P = 12.5 × 40 and pushed at its axle (the half disk's flat, through the
/// centre) by Q = 0.5 μ P: the loads' moment about the contact, Q R = 2 P
/// (mm), is six times what its zone of half-width 0.33 can carry (P a), so
/// the linearized roller turns until its pressure centre sits Q R / P aside
/// and the answer is not Cattaneo–Mindlin's (stick zone −72 %, measured).
/// The reply must say so: a `rolling` warning at the roller, its value the
/// roll over the half-width (measured 7.2). Pressed alone (Q = 0), nothing
/// turns and nothing warns.
#[test]
fn a_free_roller_pushed_at_its_axle_is_said_to_roll() {
    let roller = |q: f64| {
        let disk = half_disk([0.0, 20.0], 20.0, true, 1.25, "t3");
        let roller = body("roller", 210000.0, 0.3, graded(disk, grading(0.011, 1.1, 0.66, None)))
            .pressure("flat", 12.5)
            .traction("flat", [q, 0.0]);
        let plate = rectangle([-30.0, -10.0], 60.0, 10.0, 1.0, "t3");
        let plate = body(
            "plate",
            210000.0,
            0.3,
            graded(plate, grading(0.0144, 1.1, 0.66, Some([0.0, 0.0]))),
        );
        let contact = pair("roller", "arc")
            .against("plate", "top", Default::default())
            .friction(0.2);
        let mut req = request(vec![roller, plate.fixed("bottom")], vec![contact]);
        req.settings.estimate = false;
        let mut r = req.to_value();
        r["load_path"] = json!([{"loads": {"/bodies/0/tractions/1": 0.0}}, {"loads": {"/bodies/0/tractions/1": 1.0}}]);
        r
    };
    let pushed = common::solve(&roller(1.25)).expect("solved");
    let w = pushed
        .warnings
        .iter()
        .find(|w| w.code == "rolling")
        .unwrap_or_else(|| panic!("no rolling warning: {:?}", pushed.warnings));
    assert_eq!(w.location, "/bodies/0");
    // The pressure centre moves by Q R / P = 2 against a half-width of 0.33.
    assert!(w.value > 3.0, "{w:?}");
    assert!(
        w.message.contains("roller") && w.message.contains("rotation"),
        "{}",
        w.message
    );
    let pressed = common::solve(&roller(0.0)).expect("solved");
    assert!(
        pressed.warnings.iter().all(|w| w.code != "rolling"),
        "{:?}",
        pressed.warnings
    );
}

/// The check of the loads with the friction cone sees loads, not the normal
/// force a prescribed displacement makes: the block pressed down by uy =
/// −0.001 on its top (P ≈ 2.28, from the reply) and pushed by Q = 1 =
/// 1.46 μP passes it, and its step runs out of iterations. Its note said
/// "an equilibrium exists"; now it checks the cone against the step's own
/// normal forces and says the block most likely slides, with |Q| / (μ P)
/// as the ratio (a flat floor: every point's cone gives μ λ along x), to
/// 1e-3. Below μP (Q = 0.2) the same block solves.
#[test]
fn a_block_pressed_by_a_displacement_and_pushed_beyond_mu_p_is_not_said_to_hold() {
    let pressed = |q: f64| {
        let mut r = block("t3", 0.0, 0.0, Some(MU));
        r["bodies"][0]["supports"] = json!([{"edges": "top", "uy": -0.001}]);
        r["bodies"][0]["tractions"] = json!([{"edges": "top", "traction": [0.5 * q, 0.0]}]);
        r
    };
    let r = solve(&pressed(1.0)).expect("answered");
    assert_eq!(r.status, SolveStatus::MaxIterations, "{:?}", r.notes);
    let note = r
        .notes
        .iter()
        .find(|n| n.contains("'block'"))
        .expect("a note on the block");
    assert!(!note.contains("equilibrium exists"), "{note}");
    assert!(
        note.contains("most likely slides") && note.contains("translation in x"),
        "{note}"
    );
    let words: Vec<&str> = note.split_whitespace().collect();
    let at = words.iter().position(|w| *w == "times").expect("a ratio");
    let ratio: f64 = words[at - 1].parse().expect("a number");
    let expected = 1.0 / (MU * r.resultant.fy.abs());
    assert!(
        (ratio - expected).abs() <= 1e-3 * expected,
        "{ratio} against {expected}"
    );
    assert!(expected > 1.4, "{expected}");
    let held = solved(&pressed(0.2));
    assert_eq!(held.status, SolveStatus::Solved);
}
