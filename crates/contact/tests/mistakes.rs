//! The mistakes people make most get an answer that names them: a forgotten
//! support, a load range that loads nothing, a mesh too coarse for its contact
//! zone, numbers that overflow; and the warnings fire only where their
//! assumption really fails.
//!
//! Length: about 670 lines, one test per mistake, each with the request that
//! makes it and what its reply must name.

mod common;
use common::*;
use contact::proto::{ErrorCode, SolveReply};
use serde_json::{json, Value};

/// The Hertz example on a coarser mesh (h_min 0.05, a/h ≈ 14): fast, and still
/// a zone of about 27 element edges.
fn hertz_coarse() -> Value {
    let mut req = example("signorini_hertz_cylinder.json");
    req["bodies"][0]["mesh"]["rectangle"]["grading"]["h_min"] = json!(0.05);
    req
}

fn codes(r: &SolveReply) -> Vec<String> {
    r.warnings.iter().map(|w| w.code.to_string()).collect()
}

fn refused(req: &Value, code: ErrorCode, path: &str) -> String {
    let e = solve(req).expect_err("request must be refused");
    assert_eq!((e.code, e.path.as_str()), (code, path), "{e:?}");
    e.message
}

/// A body pressed from one side and held by nothing else is not in
/// equilibrium with any pressure but zero: before, the block under a fixed
/// cylinder with no supports, the same block supported in x only and a plate
/// left unsupported under an elastic roller each came back `numerical_error`.
/// Each is `no_support` at the body's supports, naming the body and the
/// motion nothing holds.
#[test]
fn a_forgotten_support_is_named_with_the_motion_it_leaves_free() {
    let mut none = hertz_coarse();
    none["bodies"][0]["supports"] = json!([]);
    let mut ux_only = hertz_coarse();
    ux_only["bodies"][0]["supports"] = json!([{"edges": "bottom", "ux": 0.0}]);
    let mut lower_free = example("two_bodies_cylinders.json");
    lower_free["bodies"][1]["supports"] = json!([]);
    for (req, path, body) in [
        (&none, "/bodies/0", "'block'"),
        (&ux_only, "/bodies/0/supports", "'block'"),
        (&lower_free, "/bodies/1", "'lower'"),
    ] {
        let message = refused(req, ErrorCode::NoSupport, path);
        assert!(
            message.contains(body) && message.contains("translation in y") && message.contains("support"),
            "{message}"
        );
    }
    // Supported in y only, the block is held: the cylinder's normals resist x
    // on both sides of the axis, and symmetry leaves no sideways force.
    let mut uy_only = hertz_coarse();
    uy_only["bodies"][0]["supports"] = json!([{"edges": "bottom", "uy": 0.0}]);
    let r = solved(&uy_only);
    assert_kkt(&r, 1e-8);
    assert!(r.resultant.fx.abs() <= 1e-9 * r.resultant.fy.abs(), "{:?}", r.resultant);
}

/// A surface load whose x_range misses its edge set would load nothing and
/// the reply would be a solved scene without that load.
#[test]
fn a_load_range_that_meets_no_edge_is_refused_with_the_sets_extent() {
    let mut req = example("signorini_inline_block_on_vee.json");
    req["bodies"][0]["tractions"] = json!([{"edges": "top", "pressure": 1.0, "x_range": [5.0, 6.0]}]);
    let message = refused(&req, ErrorCode::InvalidRequest, "/bodies/0/tractions/0/x_range");
    assert!(
        message.contains("[5, 6]") && message.contains("'top'") && message.contains("[-1, 1]"),
        "{message}"
    );
    // A range reaching into the set loads its part and is accepted.
    req["bodies"][0]["tractions"][0]["x_range"] = json!([0.5, 6.0]);
    assert!(solve(&req).is_ok());
}

/// A unit slip (E in Pa with lengths in mm: E a million times too large)
/// leaves a load-controlled punch's zone narrower than one element. The
/// indentation that carries the same load on a block 1000 and 10 000 times
/// stiffer (0.12 / factor) leaves a zone of 2 edges and of one node, both
/// `solved`. Each carries `coarse_contact_zone` with the measured count, the
/// limit and an element size to refine to; the 20-edge zone of the stiffer block under 0.12/√1000 do not.
#[test]
fn a_zone_a_few_elements_wide_is_never_answered_without_a_warning() {
    let hertz = |factor: f64, depth: f64| {
        let mut req = example("signorini_hertz_cylinder.json");
        req["bodies"][0]["material"]["youngs_modulus"] = json!(200.0 * factor);
        req["obstacles"][0]["shape"]["circle"]["center"][1] = json!(8.0 - depth);
        solved(&req)
    };
    for (factor, edges) in [(1e3_f64, 2.0), (1e4, 0.0)] {
        let r = hertz(factor, 0.12 / factor);
        let w = r
            .warnings
            .iter()
            .find(|w| w.code == "coarse_contact_zone")
            .unwrap_or_else(|| panic!("no coarse_contact_zone at E × {factor}: {:?}", r.warnings));
        assert_eq!(
            (w.location.as_str(), w.limit, w.value),
            ("/contacts/0", 8.0, edges),
            "{w:?}"
        );
        assert!(w.message.contains("refine"), "{}", w.message);
        // The error estimate says so too: the zone ends' uncertainty is at
        // least half the zone's half-width, the pressure's 5 % or more
        // (measured 6.4 % and 20 %; 0.27 % on the example itself).
        let acc = r.pairs[0].accuracy.as_ref().expect("estimated");
        let half_width = r.pairs[0].zones.first().map_or(0.0, |z| 0.5 * (z[1] - z[0]));
        assert!(
            acc.zone_edges.iter().flatten().all(|&u| u >= 0.5 * half_width),
            "{acc:?}"
        );
        assert!(acc.pressure_l2.is_some_and(|p| p >= 0.05), "{acc:?}");
    }
    let resolved = hertz(1e3, 0.12 / 1e3_f64.sqrt());
    assert!(
        !codes(&resolved).iter().any(|c| c == "coarse_contact_zone"),
        "{:?}",
        resolved.warnings
    );
    // T6 carries a row on every surface node, midsides included: the count
    // is of element edges still, the corners in contact less one (the
    // example's T6 mesh at E × 1000: measured 3 points in contact, one corner
    // and its two midsides, 0 edges), at most half the points' intervals.
    let mut req = example("signorini_hertz_cylinder_t6.json");
    req["bodies"][0]["material"]["youngs_modulus"] = json!(200.0 * 1e3);
    req["obstacles"][0]["shape"]["circle"]["center"][1] = json!(8.0 - 0.12 / 1e3);
    let r = solved(&req);
    let w = r
        .warnings
        .iter()
        .find(|w| w.code == "coarse_contact_zone")
        .expect("warned");
    let points = r.pairs[0].points.iter().filter(|q| q.pressure > 0.0).count() as f64;
    assert!(
        points >= 3.0 && w.value <= 0.5 * (points - 1.0),
        "{w:?}: {points} points in contact"
    );
    // Load-controlled: the load stays, the zone shrinks as 1/√E.
    let mut req = example("indentation_circular_punch.json");
    req["bodies"][0]["material"]["youngs_modulus"] = json!(200.0e6);
    let r = solve(&req).expect("answered");
    assert!(codes(&r).iter().any(|c| c == "coarse_contact_zone"), "{:?}", r.warnings);
}

/// Each warning fires where its assumption fails and stays silent where it
/// holds. The flat punch's sharp corners make the element-wise strain grow
/// without bound under refinement (the linear theory's r^(−1/2)); measured on
/// patches a tenth of the zone wide it stays at the load's level, so the
/// Sadowsky example raises nothing. A flat punch with rounded corners (0.3)
/// under the same load keeps its zone nearly on the flat: no warning at all;
/// pressed 50 times harder its zone runs well onto the rounding and
/// `large_contact_zone` fires with that reach.
#[test]
fn each_warning_fires_only_where_its_assumption_fails() {
    let hertz = solved(&example("signorini_hertz_cylinder.json"));
    assert!(hertz.warnings.is_empty(), "{:?}", hertz.warnings);
    let sadowsky = solve(&example("indentation_flat_punch.json")).expect("answered");
    assert!(sadowsky.warnings.is_empty(), "{:?}", sadowsky.warnings);

    let mut deep = example("signorini_hertz_cylinder.json");
    deep["obstacles"][0]["shape"]["circle"]["center"][1] = json!(5.0);
    let deep = solve(&deep).expect("answered");
    for code in ["large_strain", "large_contact_zone", "gap_linearization"] {
        assert!(
            codes(&deep).iter().any(|c| c == code),
            "{code} missing: {:?}",
            deep.warnings
        );
    }

    let vee = solve(&example("signorini_inline_block_on_vee.json")).expect("answered");
    assert!(
        codes(&vee).iter().any(|c| c == "large_displacement"),
        "{:?}",
        vee.warnings
    );

    // Stepped, a warning is the worst step's, named, not the last step's
    // alone: the vee's move at factor 1 is still told when the steps end
    // on a thousandth of it (the reply read the last step only).
    let mut stepped = example("signorini_inline_block_on_vee.json");
    stepped["load_factors"] = json!([1.0, 1e-3]);
    let stepped = solve(&stepped).expect("answered");
    let moved = vee.warnings.iter().find(|w| w.code == "large_displacement").unwrap();
    let told = stepped.warnings.iter().find(|w| w.code == "large_displacement");
    let told = told.unwrap_or_else(|| panic!("{:?}", stepped.warnings));
    assert!(told.message.ends_with(" (at load factor 1)"), "{}", told.message);
    // The same step's value: the first step is the whole request's.
    assert!(
        (told.value - moved.value).abs() <= 1e-9 * moved.value,
        "{told:?} against {moved:?}"
    );

    let rounded = |load: f64| {
        let mut req = example("indentation_flat_punch.json");
        req["obstacles"][0]["shape"]["profile"]["psi"]["flat"]["corner_radius"] = json!(0.3);
        req["obstacles"][0]["punch"]["vertical"]["load"] = json!(load);
        solve(&req).expect("answered")
    };
    // Before, this punch raised four warnings: large_contact_zone 2.57,
    // gap_linearization 0.34 (the whole punch's sinking counted as sliding
    // across its rounding), large_strain 0.065 and large_rotation 0.156 (at
    // the element by the corner).
    let light = rounded(-10.0);
    assert!(light.warnings.is_empty(), "{:?}", light.warnings);
    let heavy = rounded(-500.0);
    let w = heavy
        .warnings
        .iter()
        .find(|w| w.code == "large_contact_zone")
        .unwrap_or_else(|| panic!("{:?}", heavy.warnings));
    // How far the zone reaches beyond the flat (0.7), over the corner radius.
    let z = heavy.pairs[0].zones[0];
    let reach = (z[1].abs().max(z[0].abs()) - 0.7) / 0.3;
    assert!((w.value - reach).abs() < 1e-9, "{w:?} against {reach}");
    // The gap is the distance to the rounding itself (`Psi::Flat`'s arcs), no
    // parabola: the message names the turn of the surface the zone reached.
    assert!(!w.message.contains("parabolic"), "{}", w.message);
    let turned = format!("turned by {:.1}°", reach.min(1.0).asin().to_degrees());
    assert!(w.message.contains(&turned), "{turned} not in {}", w.message);

    // Every warning says what it measured, in words.
    for w in deep.warnings.iter().chain(&vee.warnings).chain(&heavy.warnings) {
        assert!(w.message.len() > 40, "{w:?}");
    }
}

/// E = 1e300 with a load factor of 1e100 came back `solved` with every force
/// null (infinite in the user's units): it is refused before the solve, and
/// any non-finite number in an answer makes it `numerical_error`.
#[test]
fn numbers_that_overflow_are_never_solved() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/nonfinite_E_1e300_load_factor_1e100.json"
    );
    let req: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let message = refused(&req, ErrorCode::InvalidRequest, "/load_factors/0");
    assert!(message.contains("units"), "{message}");

    let report = contact_verify::run::solve(&hertz_coarse(), &Default::default()).unwrap();
    assert_eq!(report.first_non_finite(), None);
    let mut broken = report.clone();
    broken.pairs[0].points[3].pressure = f64::NAN;
    assert_eq!(broken.first_non_finite().as_deref(), Some("pairs/0/points/3"));
    let mut broken = report;
    broken.resultant.fy = f64::INFINITY;
    assert_eq!(broken.first_non_finite().as_deref(), Some("resultant"));
}

/// Numbers in messages are the request's: a node at x = −1 of a block whose
/// length scale is 2 used to be reported at −0.5.
#[test]
fn messages_speak_the_requests_units() {
    let mut req = example("signorini_inline_block_on_vee.json");
    req["analysis"] = json!("axisymmetric");
    let message = refused(&req, ErrorCode::InvalidGeometry, "/bodies/0/mesh");
    assert!(message.contains("x = -1 <"), "{message}");
}

/// A punch of revolution feels no moment and no radial force: the ring forces
/// cancel round the circumference. It used to report −Σ F r / L as `m`.
#[test]
fn a_punch_of_revolution_reports_no_moment() {
    let r = solved(&example("axisymmetric_flat_punch.json"));
    let punch = &r.punches[0];
    assert_eq!((punch.m, punch.p1, punch.theta, punch.alpha1), (0.0, 0.0, 0.0, 0.0));
    assert!((punch.p2 + 100.0).abs() < 1e-9 * 100.0, "{punch:?}");
    assert_eq!((r.resultant.m, r.resultant.fx), (0.0, 0.0));
}

/// A block held only by its floor and pulled upward: the refusal gives the
/// load in the request's units (F_y = 5 × 2 = 10 along the translation in y,
/// which must be ≤ 0), not a nondimensional generalized load, and the bound
/// the LP reaches to 1e-10 is the 0 it means.
#[test]
fn a_body_pulled_off_its_support_is_told_its_load_in_its_units() {
    let mut req = example("signorini_inline_block_on_vee.json");
    req["bodies"][0]["supports"] = json!([]);
    req["bodies"][0]["tractions"] = json!([{"edges": "top", "traction": [0.0, 5.0]}]);
    let e = solve(&req).expect_err("refused");
    assert_eq!(
        (e.code, e.path.as_str()),
        (ErrorCode::IncompatibleLoads, "/bodies/0/tractions/0"),
        "{e:?}"
    );
    let bound = &e.details.as_ref().expect("details").loads[0];
    assert!((bound.value - 10.0).abs() < 1e-9 * 10.0, "{bound:?}");
    assert_eq!((bound.min, bound.max), (None, Some(0.0)), "{bound:?}");
    assert!(
        e.message.contains("load 10 along the translation in y") && e.message.contains("[-inf, 0]"),
        "{}",
        e.message
    );
}

/// A refusal's path resolves in the request and names a load it has. The
/// inline block held only by its floor (no `supports` key) with its weight
/// as its only load was refused at `/bodies/0/tractions`, which the request
/// does not have: tilted sideways (the floor's normals cannot carry F_x) and
/// pulled up alike. Now the path is the load doing most work on the motion
/// contact cannot hold (`/bodies/0/body_force`; a traction outweighing it,
/// `/bodies/0/tractions/0`), every `details.loads` path resolves too, and a
/// body with no load and no supports is told `no_support` at the body.
#[test]
fn a_refusal_points_at_a_load_the_request_has() {
    let held_by_floor = |body_force: [f64; 2], pull: Option<f64>| {
        let mut req = example("signorini_inline_block_on_vee.json");
        let body = req["bodies"][0].as_object_mut().unwrap();
        body.remove("supports");
        body.insert("body_force".into(), json!(body_force));
        if let Some(t) = pull {
            body.insert("tractions".into(), json!([{"edges": "top", "traction": [0.0, t]}]));
        }
        req
    };
    let resolves = |req: &Value, e: &contact::proto::ErrorReply| {
        assert!(
            req.pointer(&e.path).is_some(),
            "{} is not in the request: {e:?}",
            e.path
        );
        for b in e.details.iter().flat_map(|d| &d.loads) {
            assert!(
                req.pointer(&b.path).is_some(),
                "{} is not in the request: {e:?}",
                b.path
            );
        }
    };
    // Weight tilted sideways, pulled up by it, pulled up by a traction of 5
    // on the top (10 in all) against a weight of 2 × 1 = 2.
    for (req, code, path) in [
        (
            held_by_floor([1.0, -1.0], None),
            ErrorCode::IncompatibleLoads,
            "/bodies/0/body_force",
        ),
        (
            held_by_floor([0.0, 1.0], None),
            ErrorCode::IncompatibleLoads,
            "/bodies/0/body_force",
        ),
        (
            held_by_floor([0.0, -1.0], Some(5.0)),
            ErrorCode::IncompatibleLoads,
            "/bodies/0/tractions/0",
        ),
        (held_by_floor([0.0, 0.0], None), ErrorCode::NoSupport, "/bodies/0"),
    ] {
        let e = solve(&req).expect_err("refused");
        assert_eq!((e.code, e.path.as_str()), (code, path), "{e:?}");
        resolves(&req, &e);
    }
    // The bound of the body pulled up by its weight is that weight, 2 along +y.
    let e = solve(&held_by_floor([0.0, 1.0], None)).expect_err("refused");
    let bound = &e.details.as_ref().expect("details").loads[0];
    assert!((bound.value - 2.0).abs() < 1e-9, "{bound:?}");
}

/// A plate left without supports under a roller pressed onto it (P = 12.5 ×
/// 40 = 500, the roller held in x) was refused `incompatible_loads` at the
/// roller's tractions, in a sentence of four motions that never said the
/// plate had no support. Now it is `no_support` at the plate, naming its
/// translation in y (which moves with the roller without opening any
/// contact) and a support that stops it on an edge set away from the
/// contact; with that support added the request solves and the plate
/// carries the roller's 500.
#[test]
fn a_forgotten_plate_support_names_the_plate_and_the_support() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/plate_support_forgotten_under_loaded_roller.json"
    );
    let mut req: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let message = refused(&req, ErrorCode::NoSupport, "/bodies/1");
    assert!(req.pointer("/bodies/1").is_some());
    for words in [
        "body 'plate'",
        "translation in y",
        "body 'roller'",
        r#"{"edges": "bottom", "uy": 0}"#,
    ] {
        assert!(message.contains(words), "{words}: {message}");
    }
    req["bodies"][1]["supports"] = json!([{"edges": "bottom", "uy": 0.0}]);
    let r = solved(&req);
    assert_kkt(&r, 1e-8);
    assert!(
        (r.resultant.fy.abs() - 500.0).abs() <= 1e-6 * 500.0,
        "{:?}",
        r.resultant
    );
}

/// A unit slip (E in Pa, lengths in mm: the roller's P = 500 is 6e-11 of E
/// per unit area) was diagnosed `no_support` ("add a support"), and at
/// E × 1e4 `numerical_error`. The escape LP's load row had coefficients of
/// 1e-10, inside its feasibility tolerance; and once solved, a combination
/// of the free motions carrying round-off alone read an equilibrium
/// residual of 0.12. Now it solves: the floor carries the 500, at one node,
/// with the certificate at round-off, and the reply warns that the zone is
/// narrower than an element, naming the unit slip; at E × 1e4 as well.
#[test]
fn a_unit_slip_is_solved_and_named() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/unit_slip_E_in_Pa_roller_load_control.json"
    );
    let mut req: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for scale in [1.0, 1e4] {
        req["bodies"][0]["material"]["youngs_modulus"] = json!(2.1e11 * scale);
        let r = solved(&req);
        assert_kkt(&r, 1e-8);
        assert!(
            (r.resultant.fy - 500.0).abs() <= 1e-9 * 500.0,
            "E × {scale}: {:?}",
            r.resultant
        );
        let w = r
            .warnings
            .iter()
            .find(|w| w.code == "coarse_contact_zone")
            .unwrap_or_else(|| panic!("E × {scale}: {:?}", codes(&r)));
        assert!(w.message.contains("unit slip"), "{}", w.message);
    }
}

/// The Hertz block with its contact edge also held along x (`ux` on `top`,
/// the contact's own edge set) and friction μ = 0.3. The cylinder's normal
/// has an x-component off centre, so the supports leave each contact node
/// its y motion only, which the closed gap fixes (n·u = d0, d0 the node's
/// distance to the circle, exact for these rows): the slip t·u is a datum,
/// (d0 − n_x ū) / n_y along y with ū along x, and Coulomb's answer is
/// sliding by it with |q| = μ p against it. Before, the point's stick
/// equation repeated its gap's, the singular system gave forces of 1e20 and
/// the run stopped at `max_iterations` with no cause named. Now: solved, each
/// sliding point's slip the closed form to 1e-9 (the LU's round-off on the
/// forces, measured 8e-14) and its traction μ p against it to 1e-9
/// (measured 5e-14); the horizontal resultant within μ |fy|; and the
/// `prescribed_slip` warning names the support. With ū = 0 the slip,
/// d0 n_x / n_y, is still prescribed (smaller, and opposite on the two
/// sides), and solves the same way.
#[test]
fn a_contact_edge_held_along_x_slides_by_the_slip_its_contact_prescribes() {
    let mu = 0.3;
    for ux in [0.001, 0.0] {
        let mut req = hertz_coarse();
        req["bodies"][0]["supports"]
            .as_array_mut()
            .unwrap()
            .push(json!({"edges": "top", "ux": ux}));
        req["contacts"][0]["friction"] = json!({"coefficient": mu});
        let r = solved(&req);
        let (centre, radius) = (
            req["obstacles"][0]["shape"]["circle"]["center"][1].as_f64().unwrap(),
            8.0,
        );
        let mut sliding = 0;
        for p in r.pairs[0].points.iter().filter(|p| p.pressure > 0.0) {
            if p.state != Some(contact::proto::FrictionState::Slip) {
                continue;
            }
            sliding += 1;
            let n = p.normal;
            let d0 = p.x.hypot(p.y - centre) - radius;
            let uy = (d0 - n[0] * ux) / n[1];
            let expect = -n[1] * ux + n[0] * uy;
            let (slip, q) = (p.slip.unwrap(), p.tangential_traction.unwrap());
            assert!(
                (slip - expect).abs() <= 1e-9 * expect.abs(),
                "ū {ux}, x {}: slip {slip}, {expect}",
                p.x
            );
            assert!(
                (q + mu * p.pressure * expect.signum()).abs() <= 1e-9 * mu * p.pressure,
                "ū {ux}, x {}: q {q}, μp {}",
                p.x,
                mu * p.pressure
            );
        }
        let in_contact = r.pairs[0].points.iter().filter(|p| p.pressure > 0.0).count();
        // Every node but the centre's (its tangent is x alone, held: no row).
        assert!(
            sliding + 1 >= in_contact && sliding > 20,
            "ū {ux}: {sliding} of {in_contact} slide"
        );
        assert!(r.resultant.fx.abs() <= mu * r.resultant.fy.abs(), "{:?}", r.resultant);
        let w = r.warnings.iter().find(|w| w.code == "prescribed_slip");
        let w = w.unwrap_or_else(|| panic!("ū {ux}: {:?}", codes(&r)));
        assert_eq!(w.location, "/contacts/0");
        assert!(w.message.contains("/bodies/0/supports/1 of 'block'"), "{}", w.message);
    }
}

/// The same held edge at μ = 20: no Coulomb answer was found (the iteration
/// runs to its cap). Closed and sliding by the slip its contact fixes, a node
/// free along y alone feels λ n_y from its normal force and τ n_x = ±μ λ n_x
/// from its friction: where μ |n_x| ≥ n_y against the slip's sense it wedges,
/// its friction pushing it in at least as hard as its normal force pushes it
/// out, and pressed in it has no answer, closed or open. Before, the reply
/// said nothing of it beside the `prescribed_slip` warning's "it grows with μ
/// without bound". Now the warning says the step did not settle and that
/// its values are the last iterate's, and names the wedging points: each
/// listed one meets μ |n_x| ≥ n_y on the cylinder's own normal (checked to
/// 1e-9, round-off of the positions' six printed digits aside: 1e-5 of x).
#[test]
fn a_held_edge_that_wedges_at_a_large_mu_says_so() {
    let mu = 20.0;
    let mut req = hertz_coarse();
    req["bodies"][0]["supports"]
        .as_array_mut()
        .unwrap()
        .push(json!({"edges": "top", "ux": 0.001}));
    req["contacts"][0]["friction"] = json!({"coefficient": mu});
    let r = solve(&req).expect("a reply");
    assert_ne!(r.status, contact::proto::SolveStatus::Solved, "{:?}", r.status);
    let w = r
        .warnings
        .iter()
        .find(|w| w.code == "prescribed_slip")
        .expect("prescribed_slip");
    let m = &w.message;
    assert!(m.contains("did not settle") && m.contains("not an answer"), "{m}");
    let listed = m.split(" wedge (").nth(1).expect("the wedging points listed");
    let listed = &listed[..listed.find("):").expect("their list ends")];
    let centre = req["obstacles"][0]["shape"]["circle"]["center"]
        .as_array()
        .unwrap()
        .clone();
    let (cx, cy) = (centre[0].as_f64().unwrap(), centre[1].as_f64().unwrap());
    let mut seen = 0;
    for point in listed.split("), (") {
        let xy: Vec<f64> = point
            .trim_matches(|c| c == '(' || c == ')')
            .split(", ")
            .filter_map(|v| v.parse().ok())
            .collect();
        if xy.len() != 2 {
            continue;
        }
        let (nx, ny) = (xy[0] - cx, cy - xy[1]);
        assert!(
            mu * nx.abs() >= ny * (1.0 - 1e-5),
            "{xy:?}: μ |n_x| {} < n_y {ny}",
            mu * nx.abs()
        );
        seen += 1;
    }
    assert!(seen > 0, "{m}");
    let from: f64 = m
        .split("from μ = ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|v| v.parse().ok())
        .expect("the μ from which they wedge");
    assert!(from <= mu && from > 1.0, "{from}");
}

/// A punch over the block's top, the top also held along x (the contact's
/// own edge set), μ = 0.3. Each contact node's slip is then the punch's own
/// motion (a flat punch: no free DOF along x, no tangential row) or that and
/// what its closed gap fixes (a circular one), and its friction passes from
/// the punch straight to the support. With a punch component along that slip
/// load-controlled the model cannot share that force: before, the flat
/// punch pushed by 1 (μ P = 3) was refused `incompatible_loads` as sliding
/// ("must lie in [0, 0]"), the circular one ran to the iteration cap with
/// α1 of 5.7e14, pushed or not. Now both are `invalid_request` at the punch's
/// horizontal load, saying why and to prescribe that motion. The flat punch
/// left unpushed still answers: it sticks (α1 = 0) and its vertical load
/// balances the contact (to 1e-10 of it; round-off measured 1e-15).
#[test]
fn a_load_controlled_punch_over_a_held_edge_is_refused_with_its_cause() {
    let punch = |file: &str, q: f64| {
        let mut req = example(file);
        req["bodies"][0]["mesh"]["rectangle"]["grading"]["h_min"] = json!(0.05);
        req["bodies"][0]["supports"]
            .as_array_mut()
            .unwrap()
            .push(json!({"edges": "top", "ux": 0.0}));
        req["obstacles"][0]["punch"]["horizontal"] = json!({"load": q});
        req["contacts"][0]["friction"] = json!({"coefficient": 0.3});
        req
    };
    for (file, q) in [
        ("indentation_flat_punch.json", 1.0),
        ("indentation_circular_punch.json", 0.0),
    ] {
        let m = refused(
            &punch(file, q),
            ErrorCode::InvalidRequest,
            "/obstacles/0/punch/horizontal/load",
        );
        assert!(m.contains("Prescribe the punch's horizontal motion"), "{file}: {m}");
    }
    let r = solved(&punch("indentation_flat_punch.json", 0.0));
    let p = &r.punches[0];
    assert!(p.alpha1.abs() <= 1e-12 * p.alpha2.abs(), "{p:?}");
    assert!((p.p2 + 10.0).abs() <= 1e-10 * 10.0, "{p:?}");
}

/// The flat punch moved sideways by 0.001 over that held top: every node in
/// contact slides by 0.001 and the support takes its friction μ λ, so
/// pushing the punch takes μ P; its reported load (0) leaves that out. Before,
/// nothing said so (a vertical load on the punch, which does not move the
/// slip, hid every such point from `prescribed_slip`). Now the warning counts
/// every node in contact and says the punch's load leaves their friction out.
#[test]
fn a_punch_moved_over_a_held_edge_warns_that_its_load_leaves_friction_out() {
    let mut req = example("indentation_flat_punch.json");
    req["bodies"][0]["mesh"]["rectangle"]["grading"]["h_min"] = json!(0.05);
    req["bodies"][0]["supports"]
        .as_array_mut()
        .unwrap()
        .push(json!({"edges": "top", "ux": 0.0}));
    req["obstacles"][0]["punch"]["horizontal"] = json!({"displacement": 0.001});
    req["obstacles"][0]["punch"]["rotation"] = json!({"displacement": 0.0});
    req["contacts"][0]["friction"] = json!({"coefficient": 0.3});
    let r = solved(&req);
    let in_contact = r.pairs[0].points.iter().filter(|p| p.pressure > 0.0).count();
    let w = r.warnings.iter().find(|w| w.code == "prescribed_slip");
    let w = w.unwrap_or_else(|| panic!("{:?}", codes(&r)));
    assert_eq!(w.value as usize, in_contact, "{}", w.message);
    assert!(w.message.contains("nor the punch's reported load"), "{}", w.message);
}

/// The roller on the flat floor with its arc (the contact's own edge set)
/// also held along x, and the whole roller moved by 0.001 along x, with
/// μ = 0.3: on a flat floor every contact node's tangent is x, held, so no
/// free DOF moves along it and the node slides by 0.001 with its friction
/// force μ λ taken by the support, outside the solve. Before, the reply read
/// "stick" with no friction and said nothing. Now the `prescribed_slip`
/// warning counts every point in contact (the slip of each is the support's
/// 0.001) and says the supports take their friction force. Each point in
/// contact says so too: state `prescribed` (it read `stick`), its slip the
/// support's 0.001 along its tangent (−n_y, n_x) (it read 0; exact but for
/// the tangent's round-off, 1e-12), and no tangential traction (the model
/// applies none; against an obstacle the normal force has no share along
/// t): exactly 0. In two load steps (factors 0.5 and 1) each step's slip is
/// its increment, 0.0005, counted from where the previous step left it.
#[test]
fn a_contact_edge_whose_slip_the_supports_take_is_named() {
    let mut req = example("signorini_roller_on_flat.json");
    req["bodies"][0]["supports"][0]["ux"] = json!(0.001);
    req["bodies"][0]["supports"]
        .as_array_mut()
        .unwrap()
        .push(json!({"edges": "arc", "ux": 0.001}));
    req["contacts"][0]["friction"] = json!({"coefficient": 0.3});
    let r = solved(&req);
    let in_contact = r.pairs[0].points.iter().filter(|p| p.pressure > 0.0).count();
    let w = r.warnings.iter().find(|w| w.code == "prescribed_slip");
    let w = w.unwrap_or_else(|| panic!("{:?}", codes(&r)));
    assert_eq!((w.value, w.location.as_str()), (in_contact as f64, "/contacts/0"));
    for part in [
        "/bodies/0/supports/1 of 'roller'",
        "the fixed obstacle 'floor'",
        "by up to 0.001:",
        &format!("The supports take the friction force of {in_contact} of them"),
    ] {
        assert!(w.message.contains(part), "{part:?} not in {}", w.message);
    }
    let prescribed = |points: &[contact::proto::ContactPoint], slip: f64| {
        for p in points {
            if p.pressure <= 0.0 {
                assert_eq!(p.state, Some(contact::proto::FrictionState::Open), "{p:?}");
                continue;
            }
            assert_eq!(p.state, Some(contact::proto::FrictionState::Prescribed), "{p:?}");
            let along = -p.normal[1] * slip;
            assert!((p.slip.unwrap() - along).abs() <= 1e-12 * slip, "{p:?}");
            assert_eq!(p.tangential_traction, Some(0.0), "{p:?}");
        }
    };
    prescribed(&r.pairs[0].points, 0.001);
    req["load_factors"] = json!([0.5, 1.0]);
    let r = solved(&req);
    let steps = r.steps.as_ref().expect("two steps");
    assert_eq!(steps.len(), 2);
    for step in steps {
        prescribed(&step.pairs[0].points, 0.0005);
    }
}
