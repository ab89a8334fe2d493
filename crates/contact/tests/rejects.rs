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
    expect(&r, ErrorCode::NoSupport, "/bodies/1");
    // Held only by contact and pulled off the floor: no pressure can balance that.
    let mut r = base();
    r["bodies"][0]["supports"] = json!([]);
    r["bodies"][0]["tractions"] = json!([{"edges": "top", "traction": [0.0, 1.0]}]);
    expect(&r, ErrorCode::IncompatibleLoads, "/bodies/0/tractions/0");
    // Pushed sideways: the body's normals on the floor are vertical, so contact
    // cannot carry a horizontal load.
    let mut r = base();
    r["bodies"][0]["supports"] = json!([]);
    r["bodies"][0]["tractions"] = json!([{"edges": "top", "traction": [0.1, -1.0]}]);
    expect(&r, ErrorCode::IncompatibleLoads, "/bodies/0/tractions/0");
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
    expect(&r, ErrorCode::TooLarge, "/bodies/0/mesh/rectangle/grading/h_min");
}

/// `too_large` names the field to change and the smallest value accepted: that
/// value is accepted and meshes within 10 % of the limit (the estimate is
/// within ±7 % of the real count), and a value 10 % finer is refused again.
#[test]
fn too_large_names_the_field_and_an_accepted_value() {
    let limits = contact::scene::Limits {
        max_dofs: 20_000,
        ..Default::default()
    };
    let run = |req: &Value| contact::solve_bytes(serde_json::to_string(req).unwrap().as_bytes(), &limits);
    for (example_name, kind) in [
        ("signorini_hertz_cylinder.json", "rectangle"),
        ("signorini_roller_on_flat.json", "half_disk"),
    ] {
        let req = example(example_name);
        let e = run(&req).expect_err("the example is above 20,000 DOF");
        assert_eq!(e.code, ErrorCode::TooLarge);
        assert_eq!(e.path, format!("/bodies/0/mesh/{kind}/grading/h_min"), "{}", e.message);
        let value: f64 = e
            .message
            .split("grading/h_min ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("no value in: {}", e.message));
        let with = |h_min: f64| {
            let mut r = req.clone();
            r["bodies"][0]["mesh"][kind]["grading"]["h_min"] = json!(h_min);
            r
        };
        let reply = run(&with(value)).unwrap_or_else(|e| panic!("{example_name}: {value} refused: {e:?}"));
        assert!(reply.size.dofs as f64 <= 1.1 * 20_000.0, "{} DOF", reply.size.dofs);
        let again = run(&with(value / 1.1)).expect_err("10 % finer is above the limit");
        assert_eq!(again.code, ErrorCode::TooLarge);
    }
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

/// The inline block on the vee with one more node: node 15 at (0, 0.5), where
/// node 7 already is, used by no element (it made K singular: the reply was a
/// `linear_algebra` error with no path).
#[test]
fn unused_and_coinciding_nodes_are_named() {
    let mut req = base();
    req["bodies"][0]["mesh"]["inline"]["nodes"]
        .as_array_mut()
        .unwrap()
        .push(json!([0.0, 0.5]));
    expect(&req, ErrorCode::InvalidMesh, "/bodies/0/mesh/inline/nodes/15");
    let e = solve(&req).unwrap_err();
    assert!(
        e.message.contains("used by no element") && e.message.contains("node 7"),
        "{}",
        e.message
    );
    // Used by an element instead of node 7: the mesh is split along a crack.
    let elements = req["bodies"][0]["mesh"]["inline"]["elements"].as_array_mut().unwrap();
    for el in elements.iter_mut().skip(8) {
        for n in el.as_array_mut().unwrap() {
            if n == 7 {
                *n = json!(15);
            }
        }
    }
    let e = solve(&req).unwrap_err();
    assert_eq!(e.path, "/bodies/0/mesh/inline/nodes/15", "{e:?}");
    assert!(e.message.contains("nodes 7 and 15 coincide"), "{}", e.message);
}

/// Two separate squares in one body: refused, naming a node of the second piece.
#[test]
fn a_mesh_in_pieces_is_refused() {
    let mut req = base();
    let mesh = &mut req["bodies"][0]["mesh"]["inline"];
    let nodes = mesh["nodes"].as_array_mut().unwrap();
    let k = nodes.len();
    nodes.extend([json!([5.0, 0.0]), json!([6.0, 0.0]), json!([6.0, 1.0])]);
    mesh["elements"].as_array_mut().unwrap().push(json!([k, k + 1, k + 2]));
    expect(
        &req,
        ErrorCode::InvalidMesh,
        &format!("/bodies/0/mesh/inline/nodes/{k}"),
    );
}

#[test]
fn an_edge_to_a_missing_node_says_the_node_does_not_exist() {
    let mut req = base();
    req["bodies"][0]["mesh"]["inline"]["edge_sets"]["bottom"][0] = json!([0, 99]);
    let e = solve(&req).unwrap_err();
    assert_eq!(e.path, "/bodies/0/mesh/inline/edge_sets/bottom/0");
    assert!(e.message.contains("node 99 does not exist"), "{}", e.message);
}

/// A load factor of 1.7e308 was answered `solved` with null pressures: the
/// scaled loads overflow, so it is refused at its path; non-finite factors
/// cannot be written in JSON, and too many steps are `too_large`.
#[test]
fn load_factors_are_bounded() {
    let mut req = base();
    req["load_factors"] = json!([1.0, 1.7e308]);
    expect(&req, ErrorCode::InvalidRequest, "/load_factors/1");
    req["load_factors"] = json!(vec![0.5; contact::scene::Limits::default().max_load_steps + 1]);
    expect(&req, ErrorCode::TooLarge, "/load_factors");
}

/// Fields over many load steps are bounded too: the Hertz example (about
/// 15k nodes) with displacements and stresses (6 numbers per node and step)
/// over 100 steps would be about 9e6 numbers, past a limit of 5e6, and is
/// refused at `/outputs` before meshing; 10 steps pass.
#[test]
fn outputs_over_load_steps_are_bounded() {
    let mut req = example("signorini_hertz_cylinder.json");
    req["outputs"] = json!(["displacement", "stress"]);
    req["load_factors"] = json!(vec![0.5; 100]);
    let limits = contact::scene::Limits {
        max_output_values: 5_000_000,
        ..Default::default()
    };
    let run = |req: &Value| contact::check_bytes(serde_json::to_string(req).unwrap().as_bytes(), &limits);
    let e = run(&req).unwrap_err();
    assert_eq!((e.code, e.path.as_str()), (ErrorCode::TooLarge, "/outputs"), "{e:?}");
    req["load_factors"] = json!(vec![0.5; 10]);
    assert!(run(&req).is_ok());
}

/// The full formulation turns each contact row into one rotated nodal
/// coordinate; T6 rows against an obstacle are mortar rows over three nodes,
/// so a full-formulation request on them is refused at the setting (it once
/// reached an internal assertion), while `auto` stays on the condensed path.
#[test]
fn full_formulation_needs_nodal_rows() {
    let mut req = example("signorini_hertz_cylinder.json");
    req["bodies"][0]["mesh"]["rectangle"]["element"] = json!("t6");
    req["method"] = json!("active_set");
    req["settings"] = json!({"formulation": "full"});
    expect(&req, ErrorCode::InvalidRequest, "/settings/formulation");
    req["method"] = json!("auto");
    req["settings"] = json!({});
    let r = solved(&req);
    assert_kkt(&r, 1e-8);
}

/// A time limit is a positive number of seconds; the solve settings' penalty
/// and barrier parameters are positive (JSON has no NaN or infinity, which
/// the parser already refuses as malformed).
#[test]
fn time_limit_penalty_and_barrier_must_be_positive() {
    for bad in [0.0, -1.0] {
        let mut req = base();
        req["time_limit"] = json!(bad);
        expect(&req, ErrorCode::InvalidRequest, "/time_limit");
        for key in ["penalty", "barrier"] {
            let mut req = base();
            req["settings"][key] = json!(bad);
            expect(&req, ErrorCode::InvalidRequest, &format!("/settings/{key}"));
        }
    }
}

/// Unit names are short printable text, echoed as given.
#[test]
fn unit_names_are_short_printable_text() {
    let mut req = base();
    req["units"] = json!({"length": "mm", "stress": "MPa"});
    let r = solve(&req).expect("solved");
    assert_eq!(r.units.and_then(|u| u.stress).as_deref(), Some("MPa"));
    req["units"]["force"] = json!("x".repeat(33));
    expect(&req, ErrorCode::InvalidRequest, "/units/force");
}
