//! Couplings: an edge set tied rigidly to a reference point whose motions
//! are each a displacement or a load, against the same scene held by
//! supports, against itself under the other control, against
//! Cattaneo–Mindlin through a held axle, and the refusals.
//!
//! The scene: the elastic roller of `signorini_roller_on_flat.json` (a
//! half-disk R = 8, E = 200, arc down, on the rigid floor y = 0) whose flat
//! diameter is the axle, coupled to its centre (0, 8).

mod common;
use common::*;
use contact::proto::{CouplingResult, ErrorCode, FrictionState, SolveReply, SolveStatus};
use serde_json::{json, Value};

const R: f64 = 8.0;
const E: f64 = 200.0;
const MU: f64 = 0.5;

/// The roller with its flat coupled to its centre by `coupling` (the
/// components given; the others held at 0) instead of its supports.
fn roller_on_axle(coupling: Value) -> Value {
    let mut r = example("signorini_roller_on_flat.json");
    let b = &mut r["bodies"][0];
    b.as_object_mut().unwrap().remove("supports");
    let mut c = json!({"edges": "flat", "reference": [0.0, R]});
    c.as_object_mut().unwrap().extend(coupling.as_object().unwrap().clone());
    b["couplings"] = json!([c]);
    r["settings"] = json!({"estimate": false});
    r
}

fn coupling(r: &SolveReply) -> &CouplingResult {
    assert_eq!(r.couplings.len(), 1, "{:?}", r.couplings);
    &r.couplings[0]
}

/// A coupling whose three motions are displacements is the clamp of its edge
/// set moved rigidly: the roller's flat moved down by 0.05 through the
/// coupling is the example's flat clamped and moved down by 0.05, the same
/// discrete problem, so the pressures agree to the solves' round-off (1e-12
/// of the peak; measured 0). The coupling's reported force is the reaction:
/// it balances the contact force (fy = −P, fx = 0) to that round-off, its
/// moment about the centre balances the contact's (the resultant's moment
/// about the origin, which lies on the same vertical line: M = −m). A
/// rotation prescribed too (θ = 0.002) moves the flat's nodes by θ e3 × (x −
/// centre) on top: the reply's displacements there are that rigid motion to
/// round-off (1e-12 of the largest), and the motion is reported as given.
#[test]
fn a_coupling_of_displacements_is_a_clamp_moved_rigidly() {
    let clamped = solved(&{
        let mut r = example("signorini_roller_on_flat.json");
        r["settings"] = json!({"estimate": false});
        r
    });
    let coupled = solved(&roller_on_axle(json!({"vertical": {"displacement": -0.05}})));
    assert!(max_pressure_diff(&clamped, &coupled) <= 1e-12 * peak_pressure(&clamped));
    let c = coupling(&coupled);
    let res = coupled.resultant;
    assert!(
        (c.fy + res.fy).abs() <= 1e-9 * res.fy && c.fx.abs() <= 1e-9 * res.fy,
        "{c:?} {res:?}"
    );
    assert!((c.m + res.m).abs() <= 1e-9 * res.fy * R, "{c:?} {res:?}");
    assert_eq!((c.ux, c.uy, c.theta), (0.0, -0.05, 0.0));

    let theta = 0.002;
    let mut req = roller_on_axle(json!({"vertical": {"displacement": -0.05}, "rotation": {"displacement": theta}}));
    req["outputs"] = json!(["displacement", "mesh"]);
    let turned = solved(&req);
    let body = &turned.bodies.as_ref().expect("outputs")[0];
    let (nodes, disp) = (body.nodes.as_ref().unwrap(), body.displacement.as_ref().unwrap());
    let on_axle: Vec<usize> = (0..nodes.len()).filter(|&i| (nodes[i][1] - R).abs() < 1e-12).collect();
    assert!(on_axle.len() > 10, "{}", on_axle.len());
    for &i in &on_axle {
        let want = [-theta * (nodes[i][1] - R), -0.05 + theta * nodes[i][0]];
        for k in 0..2 {
            assert!(
                (disp[i][k] - want[k]).abs() <= 1e-12 * 0.05,
                "node {i}: {:?} vs {want:?}",
                disp[i]
            );
        }
    }
    assert_eq!(coupling(&turned).theta, theta);
}

/// Load or displacement control reach the same state: the roller pressed
/// through its axle by the displacement 0.05 needs the reaction F
/// (`fy`, from the reply); pressed by the load F instead, the axle moves
/// down by 0.05, to the solve's tolerance (1e-8 relative; measured 4e-14),
/// with the same zone. The load is reported as given (the nodal reactions of
/// the coupled nodes sum to it, to the solve's round-off: 1e-9 of F;
/// measured 1.2e-13) and the contact carries it (P = F: equilibrium of the
/// body). Frictionless, then with friction under the held axle (the same
/// state: no tangential load).
#[test]
fn a_load_on_a_coupling_moves_it_as_far_as_its_reaction_says() {
    for mu in [None, Some(MU)] {
        let with = |c: Value| {
            let mut r = roller_on_axle(c);
            if let Some(mu) = mu {
                r["contacts"][0]["friction"] = json!({"coefficient": mu});
            }
            r
        };
        let moved = solved(&with(json!({"vertical": {"displacement": -0.05}})));
        let f = coupling(&moved).fy;
        assert!(f < 0.0, "pressed down: {f}");
        let loaded = solved(&with(json!({"vertical": {"load": f}})));
        let c = coupling(&loaded);
        assert!((c.uy + 0.05).abs() <= 1e-8 * 0.05, "{c:?}");
        assert!(
            (c.fy - f).abs() <= 1e-9 * f.abs() && c.fx.abs() <= 1e-9 * f.abs(),
            "{c:?}"
        );
        assert!((loaded.resultant.fy + f).abs() <= 1e-9 * f.abs());
        assert!((half_width(&loaded) / half_width(&moved) - 1.0).abs() <= 1e-9);
    }
}

/// A reference point far away but within the bound (10⁴ times the body's
/// size from its box) serves as well as the centre when the rotation is held:
/// the coupled nodes then move as u_ref whatever its position, the same
/// discrete problem, so the axle's motion, its force and the zone agree to
/// the solves' round-off (1e-12 relative; measured 0 and 3.6e-16). Its moment about
/// the far point is the same contact force's, d times the horizontal force
/// the solve leaves (round-off of the contact's), so it only checks finite.
#[test]
fn a_far_reference_within_the_bound_is_the_same_coupling() {
    let near = solved(&roller_on_axle(json!({"vertical": {"load": -5.0}})));
    let mut req = roller_on_axle(json!({"vertical": {"load": -5.0}}));
    // The half-disk's box is the square of side 16 about (0, 8): its top is y = 16.
    req["bodies"][0]["couplings"][0]["reference"] = json!([0.0, 16.0 + 1e4 * 16.0]);
    let far = solved(&req);
    let (a, b) = (coupling(&near), coupling(&far));
    for (x, y) in [(a.uy, b.uy), (a.fy, b.fy)] {
        assert!((x - y).abs() <= 1e-12 * x.abs(), "{a:?} {b:?}");
    }
    assert!((half_width(&near) / half_width(&far) - 1.0).abs() <= 1e-12);
    assert!(b.m.is_finite(), "{b:?}");
}

/// `load_factors` scale a coupling's loads and displacements with the rest:
/// the axle pressed by 5 at factors 0.5 and 1 carries 2.5 and 5 (equilibrium,
/// 1e-12), and its displacement pressed at 0.5 is a prescribed half.
#[test]
fn load_factors_scale_a_coupling() {
    for (control, value) in [("load", -5.0), ("displacement", -0.05)] {
        let mut req = roller_on_axle(json!({"vertical": {control: value}}));
        req["load_factors"] = json!([0.5, 1.0]);
        let r = solved(&req);
        let st = r.steps.as_ref().expect("one answer per factor");
        let c = [&st[0].couplings[0], &st[1].couplings[0]];
        if control == "load" {
            for (k, f) in [0.5, 1.0].into_iter().enumerate() {
                assert!(
                    (st[k].resultant.fy - 5.0 * f).abs() <= 1e-12 * 5.0,
                    "{:?}",
                    st[k].resultant
                );
            }
        } else {
            assert_eq!((c[0].uy, c[1].uy), (-0.025, -0.05));
        }
    }
}

/// The roller (T6, ν = 0.499 for the P2–P0 element, whose second Dundurs
/// constant against a rigid floor is 0.001) pressed through its axle by P in
/// ten steps (the horizontal load held at 0), then pushed through it by Q =
/// 0.3, 0.5 and 0.7 μP, its rotation held (the coupling's default). P =
/// 0.3125 makes a/R = 0.014: the stick zone's shear departs from the
/// half-plane theory by the roller's finiteness, measured as the L1 distance
/// of the tangential traction from Cattaneo–Mindlin's over the zone, relative
/// to Q: 17.5 %, 8.2 %, 3.5 % at Q/μP = 0.3 for a/R = 0.055, 0.027, 0.014
/// (linear in a/R, unchanged by h), so the test runs the smallest.
///
/// Checked, from the reply: P and Q carried exactly (equilibrium, 1e-9), the
/// coupling's force the loads given (1e-8) and its rotation 0; the stick zone
/// Cattaneo–Mindlin's c = a √(1 − Q/μP), a from Hertz, within 2 % (its ends
/// known to half the node spacing h/2, 0.00045 of c = 0.06–0.09, ≤ 0.75 %;
/// measured −0.13, −0.46, −0.80 %), slipping on both sides at μp; the shear
/// at the stick zone's centre μ p0 (1 − c/a) within 2 % (measured ≤ 0.02 %),
/// and, at Q/μP = 0.5 and 0.7, the peak shear μ p0 √(Q/μP) within 2 %: the
/// peak is a cusp sampled at the nodes (spacing s = h/2), low by up to
/// s (c/a²)/(Q/μP), 1.2 % and 0.6 % there (measured −1.6/−0.4 % and
/// −0.8/+0.1 %, left/right); at 0.3 that bound is 2.3 % and the peak is not
/// tested.
#[test]
fn cattaneo_mindlin_through_a_held_axle() {
    let (nu, p, h) = (0.499, 0.3125, 0.0018);
    let mut req = roller_on_axle(json!({"vertical": {"load": -p}, "horizontal": {"load": MU * p}}));
    let b = &mut req["bodies"][0];
    b["material"]["poisson_ratio"] = json!(nu);
    b["mesh"]["half_disk"]["element"] = json!("t6");
    b["mesh"]["half_disk"]["grading"] = json!({"h_min": h, "ratio": 1.2, "extent": 0.15});
    req["contacts"][0]["friction"] = json!({"coefficient": MU});
    let (vertical, horizontal) = ("/bodies/0/couplings/0/vertical", "/bodies/0/couplings/0/horizontal");
    let mut path: Vec<Value> = (1..=10)
        .map(|k| json!({"loads": {vertical: k as f64 / 10.0, horizontal: 0.0}}))
        .collect();
    let ratios = [0.3, 0.5, 0.7];
    path.extend(ratios.iter().map(|q| json!({"loads": {horizontal: q}})));
    req["load_path"] = Value::from(path);
    let r = solved(&req);
    let all = r.steps.as_ref().expect("a load path answers per step");
    assert_eq!(all.len(), 13);
    for (k, &ratio) in ratios.iter().enumerate() {
        let st = &all[10 + k];
        assert_eq!(st.status, SolveStatus::Solved, "step {}", 10 + k);
        let q = ratio * MU * p;
        // On the roller: the floor pushes up by P, friction pulls back by Q.
        assert!((st.resultant.fy - p).abs() <= 1e-9 * p && (st.resultant.fx + q).abs() <= 1e-9 * p);
        let c = &st.couplings[0];
        assert!((c.fy + p).abs() <= 1e-8 * p && (c.fx - q).abs() <= 1e-8 * p, "{c:?}");
        assert_eq!(c.theta, 0.0);
        let (a, p0) = hertz(p, R, E, nu);
        let pts = &st.pairs[0].points;
        let stick = run_ends(pts, |q| q.state == Some(FrictionState::Stick));
        let half = 0.5 * (stick[1] - stick[0]);
        let c_cm = a * (1.0 - ratio).sqrt();
        assert!((half / c_cm - 1.0).abs() < 0.02, "Q/μP {ratio}: c {half} vs {c_cm}");
        let slips = &st.pairs[0].friction.as_ref().expect("friction").slip_zones;
        assert_eq!(slips.len(), 2, "slip on both sides: {slips:?}");
        for pt in pts.iter().filter(|q| q.state == Some(FrictionState::Slip)) {
            let t = pt.tangential_traction.unwrap();
            assert!((t.abs() - MU * pt.pressure).abs() <= 1e-9 * MU * p0, "{pt:?}");
        }
        let centre = pts.iter().min_by(|x, y| x.x.abs().total_cmp(&y.x.abs())).unwrap();
        let q0 = MU * p0 * (1.0 - c_cm / a);
        let got = centre.tangential_traction.unwrap().abs();
        assert!(
            (got / q0 - 1.0).abs() < 0.02,
            "Q/μP {ratio}: centre shear {got} vs {q0}"
        );
        if ratio < 0.5 {
            continue;
        }
        let peak = MU * p0 * ratio.sqrt();
        for side in [-1.0, 1.0] {
            let got = pts
                .iter()
                .filter(|q| q.x * side > 0.0)
                .map(|q| q.tangential_traction.unwrap().abs())
                .fold(0.0, f64::max);
            assert!(
                (got / peak - 1.0).abs() < 0.02,
                "Q/μP {ratio}, side {side}: peak {got} vs {peak}"
            );
        }
    }
}

/// A free axle (rotation a load of 0) pushed sideways by Q = 0.35 μP: the
/// loads' moment about the contact, Q R, is far beyond what the zone can
/// carry (P a, a/R = 0.055), so the roller rolls; the reply must say so, with
/// a `rolling` warning at the coupling's rotation. The same roller with its
/// axle held does not warn, and reports the moment that holds it: Q R less
/// what the contact's own moment about the centre takes (the pressure
/// centre's shift; the body's equilibrium, 1e-9 of Q R).
#[test]
fn a_free_axle_pushed_sideways_is_said_to_roll() {
    let (p, q) = (5.0, 0.35 * MU * 5.0);
    let pushed = |rotation: Value| {
        let mut r = roller_on_axle(json!({
            "vertical": {"load": -p}, "horizontal": {"load": q}, "rotation": rotation
        }));
        r["bodies"][0]["mesh"]["half_disk"]["grading"] = json!({"h_min": 0.03, "ratio": 1.2, "extent": 0.6});
        r["contacts"][0]["friction"] = json!({"coefficient": MU});
        r["load_path"] = json!([
            {"loads": {"/bodies/0/couplings/0/horizontal": 0.0}},
            {"loads": {"/bodies/0/couplings/0/horizontal": 1.0}}
        ]);
        common::solve(&r).expect("answered")
    };
    let free = pushed(json!({"load": 0.0}));
    let w = free
        .warnings
        .iter()
        .find(|w| w.code == "rolling")
        .unwrap_or_else(|| panic!("no rolling warning: {:?}", free.warnings));
    assert_eq!(w.location, "/bodies/0/couplings/0/rotation");
    assert!(w.message.contains("coupling's rotation"), "{}", w.message);
    assert!(coupling(&free).theta.abs() > 1e-3, "{:?}", coupling(&free));

    let held = pushed(json!({"displacement": 0.0}));
    assert_eq!(held.status, SolveStatus::Solved);
    assert!(held.warnings.iter().all(|w| w.code != "rolling"), "{:?}", held.warnings);
    let c = coupling(&held);
    // Moments about the centre (0, R): the contact's is its moment about
    // the origin plus R times its horizontal force.
    let contact_about_centre = held.resultant.m + R * held.resultant.fx;
    assert!(
        (c.m + contact_about_centre).abs() <= 1e-9 * q * R,
        "{c:?} {:?}",
        held.resultant
    );
    assert!(c.m > 0.5 * q * R, "the axle holds most of Q R: {}", c.m);
}

/// An axisymmetric coupling moves its edge set along the axis: the ball of
/// `axisymmetric_ball_on_flat.json` pressed through its equator plane (held
/// radially by the coupling) by 0.04 needs the ring load F; pressed by F it
/// moves by 0.04 (1e-8), the load reported as given, its radial force and
/// moment 0 (ring forces cancel).
#[test]
fn an_axisymmetric_coupling_moves_along_the_axis() {
    let ball = |vertical: Value| {
        let mut r = example("axisymmetric_ball_on_flat.json");
        let b = &mut r["bodies"][0];
        b.as_object_mut().unwrap().remove("supports");
        b["couplings"] = json!([{"edges": "flat", "reference": [0.0, 10.0], "vertical": vertical}]);
        r["settings"] = json!({"estimate": false});
        solved(&r)
    };
    let f = coupling(&ball(json!({"displacement": -0.04}))).fy;
    let loaded = ball(json!({"load": f}));
    let c = coupling(&loaded);
    assert!((c.uy + 0.04).abs() <= 1e-8 * 0.04, "{c:?}");
    assert!((c.fy - f).abs() <= 1e-9 * f.abs() && c.fx == 0.0 && c.m == 0.0, "{c:?}");
}

/// Loads contact cannot carry, refused at the coupling's load: a sideways
/// push on a frictionless floor (no contact normal resists the axle's
/// slide), and with friction a push Q = 1.2 μP, whose admissible range is
/// ±μP (the pressed roller's P = 5 on a flat floor: every point's cone
/// gives μ λ along x; to the LP's tolerance, 1e-7 relative, measured
/// 1.1e-8).
#[test]
fn a_push_contact_cannot_carry_is_refused_at_the_coupling() {
    let pushed = |q: f64, mu: Option<f64>| {
        let mut r = roller_on_axle(json!({"vertical": {"load": -5.0}, "horizontal": {"load": q}}));
        r["bodies"][0]["mesh"]["half_disk"]["grading"] = json!({"h_min": 0.03, "ratio": 1.2, "extent": 0.6});
        if let Some(mu) = mu {
            r["contacts"][0]["friction"] = json!({"coefficient": mu});
            r["load_path"] = json!([
                {"loads": {"/bodies/0/couplings/0/horizontal": 0.0}},
                {"loads": {"/bodies/0/couplings/0/horizontal": 1.0}}
            ]);
        }
        common::solve(&r).expect_err("refused")
    };
    let path = "/bodies/0/couplings/0/horizontal/load";
    let e = pushed(1.0, None);
    assert_eq!((e.code, e.path.as_str()), (ErrorCode::IncompatibleLoads, path), "{e:?}");
    assert!(e.message.contains("coupling displacement"), "{}", e.message);
    let e = pushed(1.2 * MU * 5.0, Some(MU));
    assert_eq!((e.code, e.path.as_str()), (ErrorCode::IncompatibleLoads, path), "{e:?}");
    let (value, min, max) = refused_range(&e, path);
    assert!((value - 1.2 * MU * 5.0).abs() <= 1e-9 * value, "{value}");
    assert!(
        (min + MU * 5.0).abs() <= 1e-7 * MU * 5.0 && (max - MU * 5.0).abs() <= 1e-7 * MU * 5.0,
        "{min} {max}"
    );
}

/// What a coupling may not be, each refused at its JSON pointer.
#[test]
fn couplings_that_cannot_be_are_refused_at_their_path() {
    let base = || roller_on_axle(json!({"vertical": {"load": -5.0}}));
    let refused = |req: Value, path: &str, words: &str| {
        let e = common::solve(&req).expect_err("refused");
        assert_eq!(e.path, path, "{e:?}");
        assert!(e.message.contains(words), "{}", e.message);
    };
    let with = |f: &dyn Fn(&mut Value)| {
        let mut r = base();
        f(&mut r);
        r
    };
    let c = "/bodies/0/couplings/0";
    refused(
        with(&|r| r["bodies"][0]["couplings"][0]["edges"] = json!("axle")),
        &format!("{c}/edges"),
        "no edge set named 'axle'",
    );
    refused(
        with(&|r| r["bodies"][0]["supports"] = json!([{"edges": "flat", "ux": 0.0}])),
        "/bodies/0/supports/0",
        "both supported and coupled",
    );
    refused(
        with(&|r| r["bodies"][0]["supports"] = json!([{"edges": "arc", "ux": 0.0}])),
        "/bodies/0/supports/0",
        "takes no supports",
    );
    refused(
        with(&|r| r["bodies"][0]["couplings"][0]["vertical"] = json!({"load": -5.0, "displacement": 0.1})),
        &format!("{c}/vertical"),
        "not both",
    );
    refused(
        with(&|r| r["bodies"][0]["couplings"][0]["edges"] = json!("arc")),
        &format!("{c}/edges"),
        "also a contact surface",
    );
    refused(
        with(&|r| {
            let again = r["bodies"][0]["couplings"][0].clone();
            r["bodies"][0]["couplings"].as_array_mut().unwrap().push(again);
        }),
        "/bodies/0/couplings/1",
        "at most one coupling",
    );
    refused(
        with(&|r| {
            r["analysis"] = json!("axisymmetric");
            r["bodies"][0]["couplings"][0]["rotation"] = json!({"load": 0.0});
        }),
        &format!("{c}/rotation/load"),
        "along the axis only",
    );
    refused(
        with(&|r| r["load_path"] = json!([{"loads": {"/bodies/0/couplings/0/twist": 1.0}}])),
        "/load_path/0/loads/~1bodies~10~1couplings~10~1twist",
        "names no load",
    );
    // A reference point beyond 10⁴ times the body's size (16, the half-disk's
    // square) from it: 1e308 was answered `incompatible_loads` ("would slide
    // or tip"), and 10⁶ sizes away with the rotation free too.
    for far in [[0.0, 1e308], [-1e308, 8.0], [0.0, 8.0 + 16.0 * 1e6]] {
        refused(
            with(&|r| {
                r["bodies"][0]["couplings"][0]["reference"] = json!(far);
                r["bodies"][0]["couplings"][0]["rotation"] = json!({"load": 0.0});
            }),
            &format!("{c}/reference"),
            "times the body's size 1.600e1",
        );
    }
    // A second body in no pair, pressed through a coupling: nothing holds it.
    refused(
        with(&|r| {
            let mut other = r["bodies"][0].clone();
            other["name"] = json!("spare");
            r["bodies"].as_array_mut().unwrap().push(other);
        }),
        "/bodies/1/couplings/0",
        "no contact pair involves body 'spare'",
    );
}
