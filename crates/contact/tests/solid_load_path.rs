//! `load_path` on a 3D solid: steps that scale the body's tractions, supports
//! (their prescribed values) and body force separately, each named by its
//! JSON pointer as 2D names its loads, solved on one factorization and one
//! condensed W (`solid::path`). Frictionless contact of a linear body has no
//! history, so each step is its own LCP; the steps are checked against:
//!
//! - `load_factors` with the same factors, where a path scales the one load
//!   (1e-9 of the largest pressure: the two differ by the order of the
//!   floating-point products that scale the load, then by the same LCP);
//! - superposition where no point touches: a step's gaps moved by two loads
//!   are the sum of the moves by each (1e-9 of the largest move: a linear
//!   solve's round-off, 1e-16 times a condition number below 1e6);
//! - Hertz's a ∝ P^(1/3) along the ball example's path (3 %, the bound of
//!   `solid_load_factors.rs` on the same mesh);
//! - equilibrium and the KKT certificate at every step (1e-9, as the single
//!   solve's tests in `solid.rs`);
//! - refusals (an unknown name, a step no contact balances, a step whose
//!   supports conflict, a step whose prescribed values its factor takes past
//!   what the solve represents), each at a pointer that resolves in the
//!   request.

mod common;
use common::*;
use contact::proto::{ErrorCode, LoadStep, SolidStepResult, SolveStatus};
use serde_json::{json, Value};

const TRACTION: &str = "/solid/body/tractions/0";

fn step_solid(st: &LoadStep) -> &SolidStepResult {
    st.solid.as_ref().expect("a solid's step")
}

fn assert_kkt_step(st: &LoadStep, tol: f64) {
    let c = st.certificate;
    let worst = [c.primal, c.dual, c.complementarity, c.equilibrium]
        .iter()
        .fold(0.0f64, |a, v| a.max(*v));
    assert!(worst < tol, "step {:?}: certificate {c:?}", st.loads);
}

/// The ball example (P = 6154 N on the quarter's top, T10) along a path that
/// scales its one traction by 0.5, 1 and 2: each step is the `load_factors`
/// answer of the same factor, point by point, and a grows as P^(1/3) (the
/// measured fits of `solid_load_factors.rs`: within 2.3 % of Hertz).
#[test]
fn a_path_of_one_load_is_load_factors_and_follows_hertz() {
    let factors = [0.5, 1.0, 2.0];
    let mut by_factors = example("solid_ball_on_flat.json");
    by_factors["load_factors"] = json!(factors);
    let mut by_path = example("solid_ball_on_flat.json");
    by_path["load_path"] = factors.iter().map(|k| json!({"loads": {TRACTION: k}})).collect();
    let s_ = &by_path["solid"];
    let big_r = s_["contact"]["initial_gap"]["paraboloid"]["radius"].as_f64().unwrap();
    let e = s_["body"]["material"]["youngs_modulus"].as_f64().unwrap();
    let nu = s_["body"]["material"]["poisson_ratio"].as_f64().unwrap();
    let quarter = s_["body"]["tractions"][0]["pressure"].as_f64().unwrap() * 100.0;
    let (rf, rp) = (solved(&by_factors), solved(&by_path));
    let (sf, sp) = (rf.steps.as_ref().unwrap(), rp.steps.as_ref().unwrap());
    assert_eq!(sp.len(), factors.len());
    for ((a, b), k) in sf.iter().zip(sp).zip(factors) {
        // A path step echoes its loads with factor 1, as 2D's.
        assert_eq!(b.factor, 1.0);
        assert_eq!(b.loads.as_ref().unwrap()[TRACTION], k);
        assert_eq!(b.status, SolveStatus::Solved);
        let (pa, pb) = (step_solid(a), step_solid(b));
        let peak = pa.points.iter().fold(0.0f64, |m, q| m.max(q.pressure));
        let worst = pa
            .points
            .iter()
            .zip(&pb.points)
            .fold(0.0f64, |m, (x, y)| m.max((x.pressure - y.pressure).abs()));
        println!(
            "factor {k}: largest pressure difference {:.1e} of the peak",
            worst / peak
        );
        assert!(worst <= 1e-9 * peak, "factor {k}: {worst} of {peak}");
        let same_patch = pa
            .points
            .iter()
            .zip(&pb.points)
            .all(|(x, y)| x.in_contact == y.in_contact);
        assert!(same_patch, "factor {k}: the same points press");
        let f = pb.resultant.force;
        assert!((f[2] - k * quarter).abs() < 1e-9 * k * quarter, "factor {k}: {f:?}");
        let (a_hz, _) = contact_verify::reference::hertz_sphere(4.0 * k * quarter, big_r, e / (1.0 - nu * nu));
        let a_h = circle_fit(&pb.points);
        println!(
            "factor {k}: a_h / a = {:.4}, certificate {:?}",
            a_h / a_hz,
            b.certificate
        );
        assert!((a_h / a_hz - 1.0).abs() < 0.03, "factor {k}: a_h / a = {}", a_h / a_hz);
    }
    // The top level answers the last step, as with `load_factors`.
    assert_eq!(
        rp.solid.as_ref().unwrap().resultant.force,
        step_solid(&sp[2]).resultant.force
    );
}

/// A block [0, 1] × [0, 0.8] × [0, 0.6] on the plane z = 0, rollers on x = 0
/// and y = 0 (free in z: the contact holds it), pressed by p on its top and
/// its weight density w named apart. Every step balances: the plane carries
/// k_p p A + k_w w V along +z, and each step's certificate holds.
#[test]
fn every_step_of_a_path_balances_its_own_loads() {
    let (p, w, area, volume) = (30.0, 50.0, 0.8, 0.48);
    for element in ["t4", "t10"] {
        let mut req = json!({
            "version": "1",
            "analysis": "solid",
            "solid": {
                "body": {
                    "material": {"youngs_modulus": 2.0e5, "poisson_ratio": 0.3},
                    "mesh": {"box": {"corner": [0.0, 0.0, 0.0], "lengths": [1.0, 0.8, 0.6], "size": 0.2,
                        "element": element}},
                    "supports": [{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}],
                    "tractions": [{"faces": "z_max", "pressure": p}],
                    "body_force": [0.0, 0.0, -w]
                },
                "obstacle": {"shape": {"plane": {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}}},
                "contact": {"faces": "z_min"}
            }
        });
        let path = [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (2.0, 0.5)];
        req["load_path"] = path
            .iter()
            .map(|(kp, kw)| json!({"loads": {TRACTION: kp, "/solid/body/body_force": kw}}))
            .collect();
        let r = solved(&req);
        let steps = r.steps.as_ref().unwrap();
        for (st, (kp, kw)) in steps.iter().zip(path) {
            let want = kp * p * area + kw * w * volume;
            let f = step_solid(st).resultant.force;
            println!("{element} ({kp}, {kw}): force {f:?}, want {want}; {:?}", st.certificate);
            assert!((f[2] - want).abs() < 1e-9 * want && f[0] == 0.0 && f[1] == 0.0, "{f:?}");
            assert_kkt_step(st, 1e-9);
        }
    }
}

/// A cantilever [0, 1] × [0, 0.5] × [0, 0.5] clamped on x = 0 (ux, uy by one
/// support, uz by another that may move it), its end x = 1 sheared down, its
/// weight down, 10 above the plane: no point touches at any step, so the
/// answer is linear in the loads, and the gaps moved by the three together
/// are the sum of those moved by each (the all-zero step gives the gaps as
/// they stand).
#[test]
fn where_nothing_touches_the_steps_superpose() {
    let req = |path: Value| {
        json!({
            "version": "1",
            "analysis": "solid",
            "solid": {
                "body": {
                    "material": {"youngs_modulus": 1.0e3, "poisson_ratio": 0.3},
                    "mesh": {"box": {"corner": [0.0, 0.0, 0.0], "lengths": [1.0, 0.5, 0.5], "size": 0.125,
                        "element": "t10"}},
                    "supports": [{"faces": "x_min", "ux": 0.0, "uy": 0.0}, {"faces": "x_min", "uz": -0.01}],
                    "tractions": [{"faces": "x_max", "traction": [0.0, 0.0, -2.0]}],
                    "body_force": [0.0, 0.0, -3.0]
                },
                "obstacle": {"shape": {"plane": {"point": [0.0, 0.0, -10.0], "normal": [0.0, 0.0, 1.0]}}},
                "contact": {"faces": "z_min"}
            },
            "load_path": path
        })
    };
    let names = [TRACTION, "/solid/body/body_force", "/solid/body/supports/1"];
    let step = |f: [f64; 3]| json!({"loads": {names[0]: f[0], names[1]: f[1], names[2]: f[2]}});
    let path = vec![
        step([0.0; 3]),
        step([1.0, 0.0, 0.0]),
        step([0.0, 1.0, 0.0]),
        step([0.0, 0.0, 1.0]),
        step([1.0, 1.0, 1.0]),
    ];
    let r = solved(&req(Value::Array(path)));
    let steps = r.steps.as_ref().unwrap();
    let gaps: Vec<Vec<f64>> = steps
        .iter()
        .map(|st| step_solid(st).points.iter().map(|q| q.gap).collect())
        .collect();
    for st in steps {
        let s = step_solid(st);
        assert!(s.points.iter().all(|q| !q.in_contact && q.pressure == 0.0) && s.patches.is_empty());
    }
    let moved = |k: usize, i: usize| gaps[k][i] - gaps[0][i];
    let scale = (0..gaps[0].len()).fold(0.0f64, |a, i| a.max(moved(4, i).abs()));
    let worst = (0..gaps[0].len()).fold(0.0f64, |a, i| {
        a.max((moved(4, i) - moved(1, i) - moved(2, i) - moved(3, i)).abs())
    });
    println!(
        "largest move {scale:.3e}, superposition error {:.1e} of it",
        worst / scale
    );
    // Each load moves the face: the sum is not a trivial 0 = 0.
    for k in 1..4 {
        assert!(
            (0..gaps[0].len()).any(|i| moved(k, i).abs() > 1e-3 * scale),
            "load {k} moves the face"
        );
    }
    assert!(worst <= 1e-9 * scale, "{worst} of {scale}");
}

/// Only a path's steps are solved, so only theirs must agree: base values
/// that disagree where two supports meet (uz −0.02 and −0.01 on the edge of
/// z_max and x_max) are not refused when every step moves them into
/// agreement, and that step is then the base's supports with x_max's doubled.
#[test]
fn a_paths_base_values_need_not_agree_where_its_steps_do() {
    let mut r = example("solid_ball_on_flat.json");
    let supports = |x_max: f64| {
        json!([
            {"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0},
            {"faces": "z_max", "uz": -0.02}, {"faces": "x_max", "uz": x_max}
        ])
    };
    r["solid"]["body"]["supports"] = supports(-0.01);
    r["solid"]["body"]["tractions"] = json!([]);
    r["load_path"] = json!([{"loads": {"/solid/body/supports/3": 2.0}}]);
    let path = solved(&r);
    let mut plain = r.clone();
    plain.as_object_mut().unwrap().remove("load_path");
    plain["solid"]["body"]["supports"] = supports(-0.02);
    let alone = solved(&plain);
    let fa = step_solid(&path.steps.as_ref().unwrap()[0]).resultant.force[2];
    let fb = alone.solid.as_ref().unwrap().resultant.force[2];
    assert!(fb.abs() > 0.0, "the pushed quarter touches");
    // The same linear system and LCP: equal to the solver's tolerance.
    assert!((fa - fb).abs() <= 1e-9 * fb.abs(), "{fa} against {fb}");
}

/// Refusals, each with its code and a pointer that resolves in the request.
#[test]
fn a_path_is_refused_where_it_is_wrong() {
    let path = |steps: Value| {
        let mut r = example("solid_ball_on_flat.json");
        r["load_path"] = steps;
        r
    };
    let cases = [
        // A traction the body does not have; a body force it was not given.
        (
            path(json!([{"loads": {TRACTION: 1.0}}, {"loads": {"/solid/body/tractions/3": 1.0}}])),
            ErrorCode::InvalidRequest,
            "/load_path/1/loads/~1solid~1body~1tractions~13",
        ),
        (
            path(json!([{"loads": {"/solid/body/body_force": 2.0}}])),
            ErrorCode::InvalidRequest,
            "/load_path/0/loads/~1solid~1body~1body_force",
        ),
        // A 2D pointer names nothing in a solid.
        (
            path(json!([{"loads": {"/bodies/0/tractions/0": 1.0}}])),
            ErrorCode::InvalidRequest,
            "/load_path/0/loads/~1bodies~10~1tractions~10",
        ),
        // The quarter held only by its contact, its load pulling it off:
        // no pressure balances it (Fichera), judged before the factorization.
        (
            path(json!([{"loads": {TRACTION: 1.0}}, {"loads": {TRACTION: -1.0}}])),
            ErrorCode::IncompatibleLoads,
            "/load_path/1",
        ),
        // Unloaded, nothing decides where it rests.
        (
            path(json!([{"loads": {TRACTION: 0.0}}])),
            ErrorCode::NoSupport,
            "/load_path/0",
        ),
        (
            path(json!([{"loads": {TRACTION: 1e7}}])),
            ErrorCode::InvalidRequest,
            "/load_path/0/loads/~1solid~1body~1tractions~10",
        ),
    ];
    let mut both = path(json!([{"loads": {TRACTION: 1.0}}]));
    both["load_factors"] = json!([1.0]);
    // Two supports meeting on an edge prescribe the same uz there; a step
    // moving one alone makes them disagree.
    let mut conflict = path(json!([{"loads": {"/solid/body/supports/2": 2.0}}]));
    conflict["solid"]["body"]["supports"] = json!([
        {"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0},
        {"faces": "z_max", "uz": -0.02}, {"faces": "x_max", "uz": -0.02}
    ]);
    conflict["solid"]["body"]["tractions"] = json!([]);
    // A step's prescribed values are judged as the request's: uz of 1e145
    // cube sides is representable (below 1e150), a step's 1e6 times it is
    // not, and is refused at the step, not at the support.
    let mut pushed =
        path(json!([{"loads": {"/solid/body/supports/2": 1.0}}, {"loads": {"/solid/body/supports/2": 1e6}}]));
    pushed["solid"]["body"]["supports"] = json!([
        {"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}, {"faces": "z_max", "uz": -1e146}
    ]);
    pushed["solid"]["body"]["tractions"] = json!([]);
    let cases = cases.into_iter().chain([
        (both, ErrorCode::InvalidRequest, "/load_path"),
        (conflict, ErrorCode::InvalidRequest, "/load_path/0"),
        (pushed, ErrorCode::InvalidRequest, "/load_path/1"),
    ]);
    for (req, code, at) in cases {
        let e = solve(&req).expect_err(at);
        println!("{at}: {}", e.message);
        assert_eq!(e.code, code, "{at}: {e:?}");
        assert_eq!(e.path, at, "{e:?}");
        assert!(req.pointer(&e.path).is_some(), "{} resolves in the request", e.path);
    }
    // As many steps as 2D allows.
    let limits = contact::scene::Limits::default();
    let many = path(Value::Array(vec![json!({"loads": {}}); limits.max_load_steps + 1]));
    let e = solve(&many).expect_err("too many steps");
    assert_eq!(e.code, ErrorCode::TooLarge);
    assert_eq!(e.path, "/load_path");
}
