//! Rigid punches under prescribed loads or motions (issue: rigid indentation),
//! against Sadowsky and Hertz, with the consistency of load and motion control
//! and Fichera's compatibility condition.

mod common;
use common::*;
use contact::proto::ErrorCode;
use serde_json::json;

/// Flat punch, b = 1, P = 10. The resultant is P to round-off (punch
/// equilibrium is an equation of the discrete problem). Away from the singular
/// corners (|x| ≤ 0.8b) the nodal pressure matches P/(π√(b² − x²)); we measure
/// ≤ 1.2 % on this mesh (h = 0.01 = b/100, block 20b deep, whose finite depth
/// and the corner singularity perturb the interior), and test 2 %.
#[test]
fn flat_punch_matches_sadowsky() {
    let r = solved(&example("indentation_flat_punch.json"));
    let (p, b) = (10.0, 1.0);
    assert!((r.resultant.fy + p).abs() < 1e-10 * p, "fy {}", r.resultant.fy);
    let punch = &r.punches[0];
    assert!((punch.p2 + p).abs() < 1e-10 * p && punch.m.abs() < 1e-10 * p * b);
    assert!(punch.alpha2 < 0.0, "the punch moves down into the block");
    assert!(!punch.unique, "a frictionless flat punch may slide: not unique");
    assert_eq!(r.pairs[0].zones.len(), 1);
    let z = r.pairs[0].zones[0];
    assert!(
        (z[0] + b).abs() < 1e-9 && (z[1] - b).abs() < 1e-9,
        "the whole face is in contact: {z:?}"
    );
    for q in &r.pairs[0].points {
        if q.x.abs() <= 0.8 * b + 1e-9 {
            let exact = p / (std::f64::consts::PI * (b * b - q.x * q.x).sqrt());
            assert!(
                (q.pressure / exact - 1.0).abs() < 0.02,
                "x = {}: {} vs {exact}",
                q.x,
                q.pressure
            );
        }
    }
    assert_kkt(&r, 1e-8);
}

/// `load_factors` multiply a punch's load as every other: the flat punch's
/// zone is its face whatever the load, so the answer is linear in it and each
/// step's resultant is its factor times P, to round-off (punch equilibrium is
/// an equation of the discrete problem). Before, the punch kept its full load
/// at every factor.
#[test]
fn load_factors_scale_a_punch_load() {
    let mut req = example("indentation_flat_punch.json");
    req["load_factors"] = json!([0.25, 0.5, 1.0]);
    let r = solved(&req);
    let steps = r.steps.as_ref().expect("one answer per factor");
    assert_eq!(steps.len(), 3);
    for (step, k) in steps.iter().zip([0.25, 0.5, 1.0]) {
        assert!(
            (step.resultant.fy + k * 10.0).abs() < 1e-10 * 10.0,
            "factor {k}: fy {}",
            step.resultant.fy
        );
    }
    let p = |i: usize| steps[i].pairs[0].points.iter().map(|q| q.pressure).fold(0.0, f64::max);
    assert!(
        (p(0) / p(2) - 0.25).abs() < 1e-9,
        "peak pressure proportional to the load"
    );
}

/// Circular punch R = 8 under P = 10: Hertz half-width and peak within 2 %
/// (zone ends on nodes spaced 0.01 = 1.5 % of a).
#[test]
fn circular_punch_matches_hertz() {
    let r = solved(&example("indentation_circular_punch.json"));
    let (a, p0) = hertz(10.0, 8.0, 200.0, 0.3);
    assert!((half_width(&r) / a - 1.0).abs() < 0.02);
    assert!((peak_pressure(&r) / p0 - 1.0).abs() < 0.02);
    assert!((r.resultant.fy + 10.0).abs() < 1e-10 * 10.0);
    assert_kkt(&r, 1e-8);
}

/// Prescribing the motion found under load control gives the load back
/// (vertical: α2 ↔ P2; rotation: θ ↔ M with an eccentric load).
#[test]
fn load_and_motion_control_are_consistent() {
    let mut req = example("indentation_flat_punch.json");
    req["obstacles"][0]["punch"]["rotation"] = json!({ "load": 2.0 }); // eccentric: M = 2 with P2 = −10
    let loaded = solved(&req);
    let pu = &loaded.punches[0];
    assert!(pu.theta != 0.0);
    let mut by_alpha = req.clone();
    by_alpha["obstacles"][0]["punch"]["vertical"] = json!({ "displacement": pu.alpha2 });
    let r = solved(&by_alpha);
    assert!(
        (r.punches[0].p2 - pu.p2).abs() <= 1e-8 * pu.p2.abs(),
        "{} vs {}",
        r.punches[0].p2,
        pu.p2
    );
    let mut by_theta = req.clone();
    by_theta["obstacles"][0]["punch"]["rotation"] = json!({ "displacement": pu.theta });
    let r = solved(&by_theta);
    assert!((r.punches[0].m - 2.0).abs() <= 1e-8 * 2.0, "M {}", r.punches[0].m);
}

/// Fichera: loads no non-negative pressure can balance are refused, naming the
/// component furthest outside its admissible range (relative to the range's
/// nearer bound) and giving every offending component with its range as data.
#[test]
fn incompatible_loads_are_refused() {
    let cases = [
        ("horizontal", json!({ "load": 1.0 })), // a flat punch carries no P1
        ("vertical", json!({ "load": 10.0 })),  // pulling the punch off
        ("rotation", json!({ "load": 20.0 })),  // |M| must stay below P2·b = 10
        ("rotation", json!({ "load": 11.0 })),  // 10 % over, while P2 is 9 % under
    ];
    for (component, control) in cases {
        let mut req = example("indentation_flat_punch.json");
        req["obstacles"][0]["punch"][component] = control;
        let e = solve(&req).expect_err("incompatible loads must be refused");
        assert_eq!(e.code, ErrorCode::IncompatibleLoads, "{component}: {e:?}");
        assert_eq!(e.path, format!("/obstacles/0/punch/{component}/load"), "{e:?}");
        let details = e.details.as_ref().expect("details");
        assert!(details.loads.iter().any(|b| b.path == e.path), "{e:?}");
    }
    // Given P2 = −10 the moment's admissible range is [P2·b, −P2·b] = [−10, 10];
    // the LP runs to a gap of 1e-13, so the bounds are met to 1e-8 (measured
    // 7e-10; Clarabel's default tolerance gave 9.999926).
    let mut req = example("indentation_flat_punch.json");
    req["obstacles"][0]["punch"]["rotation"] = json!({ "load": 11.0 });
    let e = solve(&req).unwrap_err();
    let loads = &e.details.as_ref().expect("details").loads;
    let m = loads
        .iter()
        .find(|b| b.path.ends_with("rotation/load"))
        .expect("the moment's range");
    assert_eq!(m.value, 11.0);
    let (lo, hi) = (m.min.expect("bounded below"), m.max.expect("bounded above"));
    assert!((lo + 10.0).abs() < 1e-7 && (hi - 10.0).abs() < 1e-7, "{m:?}");
    // With M = 11 the vertical load must be at most −11 (pressing harder).
    let p = loads
        .iter()
        .find(|b| b.path.ends_with("vertical/load"))
        .expect("the vertical load's range");
    assert!(
        p.min.is_none() && (p.max.expect("bounded above") + 11.0).abs() < 1e-7,
        "{p:?}"
    );
    let range = e.message.split("rotation load").nth(1).expect("rotation range named");
    assert!(range.contains("[-10, 10]"), "{}", e.message);
}

/// Every method handles the punch's free motions and equilibrium: the exact ones
/// agree to 1e-8 of the peak, penalty (ζ = 1e-8, penetration ζ·p) and barrier
/// (ζ = 1e-8) to their own inherent error, and all balance the load exactly.
#[test]
fn every_method_solves_punches() {
    for name in ["indentation_flat_punch.json", "indentation_circular_punch.json"] {
        let mut req = example(name);
        req["method"] = json!("active_set");
        let reference = solved(&req);
        let peak = peak_pressure(&reference);
        for (method, settings, tol) in [
            ("interior_point", json!({}), 1e-8),
            ("augmented_lagrangian", json!({ "penalty": 1e-5 }), 1e-8),
            ("penalty", json!({ "penalty": 1e-8 }), 1e-4),
            // The barrier leaves pressure ζ/gap next to the zone edge, where gaps are
            // tiny: its error there is the largest (measured 1.3e-4 of the peak).
            ("barrier", json!({ "barrier": 1e-8 }), 1e-3),
        ] {
            req["method"] = json!(method);
            req["settings"] = settings;
            let r = solved(&req);
            assert!(
                (r.resultant.fy + 10.0).abs() < 1e-9 * 10.0,
                "{name} {method}: fy {}",
                r.resultant.fy
            );
            let d = max_pressure_diff(&r, &reference);
            assert!(
                d <= tol * peak,
                "{name} {method}: pressure differs by {d:e} (peak {peak})"
            );
            let (a, b) = (r.punches[0].alpha2, reference.punches[0].alpha2);
            assert!(
                (a - b).abs() <= tol.max(1e-8) * b.abs(),
                "{name} {method}: α2 {a} vs {b}"
            );
        }
    }
}

/// The profile kinds describe the same geometry the same way: a circle given as
/// a table (and as a polyline) of 2001 samples gives the circle's answer to the
/// sampling error (chord sagitta (h²/8R) ≈ 1e-6 of the 0.12 indentation).
#[test]
fn tabulated_and_polyline_profiles_match_the_circle() {
    let circle = solved(&example("indentation_circular_punch.json"));
    let r = 8.0f64;
    let t: Vec<f64> = (0..=2000).map(|i| -2.0 + 4.0 * i as f64 / 2000.0).collect();
    let psi: Vec<f64> = t.iter().map(|x| r - (r * r - x * x).sqrt()).collect();
    for profile in [
        json!({ "table": { "t": t, "psi": psi } }),
        json!({ "polyline": { "points": t.iter().zip(&psi).map(|(a, b)| [*a, *b]).collect::<Vec<_>>() } }),
    ] {
        let mut req = example("indentation_circular_punch.json");
        req["obstacles"][0]["shape"]["profile"]["psi"] = profile;
        let s = solved(&req);
        assert_eq!(s.pairs[0].zones, circle.pairs[0].zones);
        // The table covers |t| ≤ 2 only, so it has fewer candidates: compare by node.
        let by_node: std::collections::HashMap<usize, f64> =
            circle.pairs[0].points.iter().map(|p| (p.node, p.pressure)).collect();
        for p in &s.pairs[0].points {
            let d = (p.pressure - by_node[&p.node]).abs();
            assert!(
                d < 1e-3 * peak_pressure(&circle),
                "x = {}: {} vs {}",
                p.x,
                p.pressure,
                by_node[&p.node]
            );
        }
    }
}

/// Rounding the corners of a flat punch removes the edge singularity: the peak
/// pressure drops well below the sharp punch's corner value while the resultant
/// stays exact, and the contact zone stays within the rounded face.
#[test]
fn rounded_corners_soften_the_edge() {
    let sharp = solved(&example("indentation_flat_punch.json"));
    let mut req = example("indentation_flat_punch.json");
    req["obstacles"][0]["shape"]["profile"]["psi"] = json!({ "flat": { "half_width": 1.0, "corner_radius": 0.3 } });
    let rounded = solved(&req);
    assert!((rounded.resultant.fy + 10.0).abs() < 1e-10 * 10.0);
    assert!(peak_pressure(&rounded) < 0.5 * peak_pressure(&sharp));
    let z = rounded.pairs[0].zones[0];
    assert!(z[1] <= 1.0 && z[0] >= -1.0);
}
