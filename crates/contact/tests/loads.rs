//! Point loads and pressures on part of an edge set, on a block held only by
//! a frictionless rigid floor: whatever the mesh, the contact must carry the
//! load and its moment exactly (equilibrium of the discrete problem, to
//! round-off), and a load far off-centre lifts part of the base.

mod common;
use common::*;
use contact::proto::ErrorCode;
use contact_verify::build::*;
use serde_json::json;

/// A 2 × 1 block on the floor y = 0, no supports, loaded by `load`.
fn block_on_floor(
    element: &str,
    load: impl Fn(contact::proto::BodySpec) -> contact::proto::BodySpec,
) -> serde_json::Value {
    let block = load(body(
        "block",
        1000.0,
        0.25,
        rectangle([-1.0, 0.0], 2.0, 1.0, 0.05, element),
    ));
    request(vec![block], vec![pair("block", "bottom").obstacle("floor")])
        .with_obstacle(obstacle("floor", line([0.0, 0.0], [0.0, 1.0])))
        .to_value()
}

/// The floor carries P and the moment P·e of a point load P at x = e on the
/// top, between nodes or at one, for T3 and T6; well beyond the kern
/// (e = 0.6 > b/6) the base lifts on the far side. (A centred point load on
/// this deep block already lifts the corners: it bends like a beam.)
#[test]
fn a_point_load_is_carried_with_its_moment() {
    for element in ["t3", "t6"] {
        for e in [0.0, 0.2, 0.237, 0.6] {
            let r = solved(&block_on_floor(element, |b| b.point_load("top", [e, 1.0], [0.0, -1.0])));
            assert_kkt(&r, 1e-8);
            assert!(
                (r.resultant.fy - 1.0).abs() < 1e-9,
                "{element} e {e}: fy {}",
                r.resultant.fy
            );
            assert!((r.resultant.m - e).abs() < 1e-9, "{element} e {e}: m {}", r.resultant.m);
            let zones = &r.pairs[0].zones;
            if e == 0.6 {
                assert!(zones[0][0] > -0.9, "{element}: the far side lifts: {zones:?}");
            }
        }
    }
}

/// A pressure q on x ∈ [a, b] of the top, the ends between nodes: the floor
/// carries q (b − a) and its moment q (b² − a²)/2.
#[test]
fn a_pressure_on_part_of_an_edge_is_carried_with_its_moment() {
    let (q, a, b) = (2.0, -0.33, 0.71);
    for element in ["t3", "t6"] {
        let r = solved(&block_on_floor(element, |body| body.pressure_on("top", q, [a, b])));
        assert_kkt(&r, 1e-8);
        let (p, m) = (q * (b - a), q * (b * b - a * a) / 2.0);
        assert!(
            (r.resultant.fy / p - 1.0).abs() < 1e-9,
            "{element}: fy {} vs {p}",
            r.resultant.fy
        );
        assert!(
            (r.resultant.m / m - 1.0).abs() < 1e-9,
            "{element}: m {} vs {m}",
            r.resultant.m
        );
    }
}

#[test]
fn point_loads_and_ranges_are_refused_with_their_field() {
    let expect = |req: &serde_json::Value, code: ErrorCode, path: &str| {
        let e = solve(req).expect_err("refused");
        assert_eq!((e.code, e.path.as_str()), (code, path), "{}", e.message);
    };
    let off = block_on_floor("t3", |b| b.point_load("top", [0.0, 0.5], [0.0, -1.0]));
    expect(&off, ErrorCode::InvalidGeometry, "/bodies/0/point_loads/0/at");
    let mut unknown = off.clone();
    unknown["bodies"][0]["point_loads"][0]["edges"] = json!("roof");
    expect(&unknown, ErrorCode::InvalidRequest, "/bodies/0/point_loads/0/edges");
    let inverted = block_on_floor("t3", |b| b.pressure_on("top", 1.0, [0.5, -0.5]));
    expect(&inverted, ErrorCode::InvalidRequest, "/bodies/0/tractions/0/x_range");
}
