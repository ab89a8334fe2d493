//! The quick part of the numerical stress suite (`contact-bench --stability`):
//! the extreme value of every axis on small meshes. Each row must be certified
//! or refused with a clear status, never NaN or a panic, and its error against
//! the reference must be what the physics allows.

use contact_verify::stability::{self, Row};

fn clear(r: &Row) {
    assert!(r.is_clear(), "{}", r.table_line());
}

/// Uniform compression is exact in the FE model whatever the element shape or
/// the initial gap: round-off only.
#[test]
fn aspect_ratio_and_tiny_gaps_stay_exact() {
    for r in [stability::aspect(100.0), stability::gap(1e-12), stability::gap(0.0)] {
        clear(&r);
        assert_eq!(r.status, "solved", "{}", r.table_line());
        assert!(r.error < 1e-10, "{}", r.table_line());
    }
}

/// ζ down to 1e-14 of the natural compliance: still solved, and the penalty's
/// error falls with ζ to round-off (measured 3.7e-12).
#[test]
fn penalty_to_the_limit() {
    let exact = contact_verify::run::solve(
        &contact_verify::bench::hertz_request(0.05, "t3", "active_set"),
        &contact::scene::Limits::default(),
    )
    .unwrap();
    let r = stability::penalty(1e-14, &exact, 0.05);
    clear(&r);
    assert_eq!(r.status, "solved");
    assert!(r.error < 1e-9, "{}", r.table_line());
}

/// Nearly incompressible (ν = 0.4999) on T6: certified, and the pressure does
/// not oscillate from node to node (second difference below 2 % of the peak).
#[test]
fn nearly_incompressible_t6_is_certified_without_oscillation() {
    let mut req = contact_verify::bench::hertz_request(0.05, "t6", "auto");
    req["bodies"][0]["material"]["poisson_ratio"] = serde_json::json!(0.4999);
    let r = contact_verify::run::solve(&req, &contact::scene::Limits::default()).unwrap();
    assert!(r.certificate.worst() <= 1e-8, "{:?}", r.certificate);
    let osc = stability::oscillation(&r);
    assert!(osc < 0.02, "oscillation {osc}");
}

/// 10 000 candidates on a 50k-DOF strip: `auto` solves on the full system
/// (the dense condensed work would cost far more than its factorizations) and
/// gets the exact uniform pressure to round-off (measured 3e-10; 1e-8 asked);
/// the condensed active set asked for by name is refused past the candidate
/// limit with `too_large`, not left to build a 10 000² operator.
#[test]
fn many_candidates_are_solved_on_the_full_system_or_refused() {
    let auto = stability::candidates(10_000, false);
    assert_eq!(auto.status, "solved", "{}", auto.table_line());
    assert!(auto.error < 1e-8, "{}", auto.table_line());
    let mut req = stability::strip_request(10_000, false);
    req["method"] = serde_json::json!("active_set");
    let e = contact::solve_bytes(req.to_string().as_bytes(), &contact::scene::Limits::default()).unwrap_err();
    assert_eq!(e.code, contact::proto::ErrorCode::TooLarge, "{e:?}");
    assert_eq!(e.path, "/contacts");
}
