//! Bad requests get the right error code and a JSON pointer to the culprit.

mod common;
use common::*;
use contact::proto::ErrorCode;
use serde_json::{json, Value};

fn base() -> Value {
    example("signorini_inline_block_on_vee.json")
}

fn expect(req: &Value, code: ErrorCode, path: &str) {
    let e = solve(req).expect_err("request must be rejected");
    assert_eq!(e.code, code, "{e:?}");
    assert_eq!(e.path, path, "{e:?}");
    assert!(!e.message.is_empty());
}

#[test]
fn malformed_payloads() {
    let limits = contact::scene::Limits::default();
    for bytes in [
        &b"{\"version\": "[..],
        b"NaN",
        b"{\"version\": NaN}",
        b"\xff\xfe",
        b"[1, 2",
    ] {
        let e = contact::solve_bytes(bytes, &limits).unwrap_err();
        assert_eq!(
            e.code,
            ErrorCode::MalformedJson,
            "{:?}: {e:?}",
            String::from_utf8_lossy(bytes)
        );
    }
}

#[test]
fn schema_violations_carry_paths() {
    let mut r = base();
    r["bogus"] = json!(1);
    expect(&r, ErrorCode::InvalidRequest, "/bogus");
    let mut r = base();
    r["bodies"][0]["material"]["colour"] = json!("red");
    expect(&r, ErrorCode::InvalidRequest, "/bodies/0/material/colour");
    let mut r = base();
    r["bodies"][0]["material"]["youngs_modulus"] = json!("stiff");
    expect(&r, ErrorCode::InvalidRequest, "/bodies/0/material/youngs_modulus");
    let mut r = base();
    r.as_object_mut().unwrap().remove("bodies");
    expect(&r, ErrorCode::InvalidRequest, "");
    let mut r = base();
    r["version"] = json!("99");
    expect(&r, ErrorCode::UnsupportedVersion, "/version");
}

#[test]
fn invalid_physics() {
    for (field, value) in [
        ("youngs_modulus", 0.0),
        ("youngs_modulus", -5.0),
        ("poisson_ratio", 0.5),
        ("poisson_ratio", -1.0),
        ("poisson_ratio", 0.7),
    ] {
        let mut r = base();
        r["bodies"][0]["material"][field] = json!(value);
        expect(&r, ErrorCode::InvalidMaterial, &format!("/bodies/0/material/{field}"));
    }
    // A literal beyond f64 range is not a number we can use.
    let text = serde_json::to_string(&base())
        .unwrap()
        .replace("\"youngs_modulus\":1000.0", "\"youngs_modulus\":1e400");
    let e = contact::solve_bytes(text.as_bytes(), &Default::default()).unwrap_err();
    assert!(
        matches!(e.code, ErrorCode::MalformedJson | ErrorCode::InvalidRequest),
        "{e:?}"
    );
}

#[test]
fn bad_meshes() {
    let mut r = base();
    let el = r["bodies"][0]["mesh"]["inline"]["elements"][3].clone();
    r["bodies"][0]["mesh"]["inline"]["elements"][3] = json!([el[0], el[2], el[1]]);
    expect(&r, ErrorCode::InvalidMesh, "/bodies/0/mesh/inline/elements/3");
    let mut r = base();
    r["bodies"][0]["mesh"]["inline"]["nodes"][4] = r["bodies"][0]["mesh"]["inline"]["nodes"][3].clone();
    assert_eq!(solve(&r).unwrap_err().code, ErrorCode::InvalidMesh);
    let mut r = base();
    r["bodies"][0]["mesh"]["inline"]["elements"][0] = json!([0, 1, 99]);
    expect(&r, ErrorCode::InvalidMesh, "/bodies/0/mesh/inline/elements/0/2");
    let mut r = base();
    r["bodies"][0]["mesh"]["inline"]["edge_sets"]["bottom"][0] = json!([0, 6]);
    expect(&r, ErrorCode::InvalidMesh, "/bodies/0/mesh/inline/edge_sets/bottom/0");
    let mut r = example("signorini_hertz_cylinder.json");
    r["bodies"][0]["mesh"]["rectangle"]["grading"]["ratio"] = json!(5.0);
    expect(&r, ErrorCode::InvalidMesh, "/bodies/0/mesh/rectangle/grading/ratio");
}

#[test]
fn missing_supports_and_candidates() {
    // A body with rigid modes and no contact pair that could hold it.
    let mut r = base();
    let mut free_body = r["bodies"][0].clone();
    free_body["name"] = json!("loose");
    free_body["supports"] = json!([]);
    r["bodies"].as_array_mut().unwrap().push(free_body);
    expect(&r, ErrorCode::NoSupport, "/bodies/1/supports");
    // Held only by contact and pulled off the floor: no pressure can balance that.
    let mut r = base();
    r["bodies"][0]["supports"] = json!([]);
    r["bodies"][0]["tractions"] = json!([{"edges": "top", "traction": [0.0, 1.0]}]);
    expect(&r, ErrorCode::IncompatibleLoads, "/bodies/0/tractions");
    // Pushed sideways: the body's normals on the floor are vertical, so contact
    // cannot carry a horizontal load.
    let mut r = base();
    r["bodies"][0]["supports"] = json!([]);
    r["bodies"][0]["tractions"] = json!([{"edges": "top", "traction": [0.1, -1.0]}]);
    expect(&r, ErrorCode::IncompatibleLoads, "/bodies/0/tractions");
    let mut r = base();
    r["contacts"][0]["edges"] = json!("nowhere");
    expect(&r, ErrorCode::InvalidRequest, "/contacts/0/edges");
    let mut r = base();
    r["bodies"][0]["supports"][0]["edges"] = json!("nowhere");
    expect(&r, ErrorCode::InvalidRequest, "/bodies/0/supports/0/edges");
    // An obstacle that no boundary normal can reach.
    let mut r = base();
    r["obstacles"][0]["shape"] = json!({"line": {"point": [0.0, 5.0], "normal": [0.0, -1.0]}});
    expect(&r, ErrorCode::NoContactCandidates, "/contacts/0/edges");
    let mut r = base();
    r["obstacles"][0]["shape"] = json!({"circle": {"center": [0.0, -3.0], "radius": -1.0}});
    expect(&r, ErrorCode::InvalidGeometry, "/obstacles/0/shape/circle/radius");
}

#[test]
fn too_large_is_refused_before_meshing() {
    let mut r = example("signorini_hertz_cylinder.json");
    r["bodies"][0]["mesh"]["rectangle"]["grading"]["h_min"] = json!(1e-5);
    r["bodies"][0]["mesh"]["rectangle"]["grading"]["extent"] = json!(20.0);
    expect(&r, ErrorCode::TooLarge, "/bodies");
}

/// The dense condensed operator grows as m²: past the deployment's candidate
/// limit the request is refused before anything is factored.
#[test]
fn too_many_candidates_are_refused() {
    let req = example("signorini_roller_on_flat.json");
    let limits = contact::scene::Limits {
        max_candidates: 100,
        ..Default::default()
    };
    let e = contact::solve_bytes(serde_json::to_string(&req).unwrap().as_bytes(), &limits).unwrap_err();
    assert_eq!(e.code, ErrorCode::TooLarge);
    assert_eq!(e.path, "/contacts");
}
