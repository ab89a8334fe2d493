//! A 3D solid's `outputs` (mesh, displacement, stress, vtu) through the wire
//! and the CLI's `--vtu`: the VTU file of the T4 and T10 patch-test box is a
//! well-formed VTK grid of the reply's own nodes, tetrahedra and
//! displacements, with VTK's node order on T10.
//!
//! Tolerances: the file's arrays are the reply's numbers written as
//! little-endian f64, so they agree to 1e-15 (bit for bit in fact); a
//! generated mesh's midside node is the average of its edge's corners, one
//! rounding of O(1) coordinates: 1e-15.

mod common;
use base64::Engine;
use common::*;
use contact::proto::SolveReply;
use serde_json::{json, Value};

/// The patch-test box on a rigid plane (`solid.rs`'s scene), asking `outputs`.
fn block(element: &str, outputs: Value) -> Value {
    json!({
        "version": "1",
        "analysis": "solid",
        "outputs": outputs,
        "solid": {
            "body": {
                "material": {"youngs_modulus": 2.0e5, "poisson_ratio": 0.3},
                "mesh": {"box": {"corner": [0.0, 0.0, 0.0], "lengths": [1.0, 1.0, 0.5], "size": 0.25,
                    "element": element}},
                "supports": [
                    {"faces": "x_min", "ux": 0.0}, {"faces": "x_max", "ux": 0.0},
                    {"faces": "y_min", "uy": 0.0}, {"faces": "y_max", "uy": 0.0}
                ],
                "tractions": [{"faces": "z_max", "pressure": 25.0}]
            },
            "obstacle": {"shape": {"plane": {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}}},
            "contact": {"faces": "z_min"}
        }
    })
}

/// The decoded bytes of the inline binary DataArray `name` (a UInt64 byte
/// count, then the data).
fn array(xml: &str, name: &str) -> Vec<u8> {
    let start = xml
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no array {name}"));
    let body = &xml[start..];
    let (a, b) = (body.find('>').unwrap() + 1, body.find("</DataArray>").unwrap());
    let raw = base64::engine::general_purpose::STANDARD.decode(&body[a..b]).unwrap();
    let n = u64::from_le_bytes(raw[..8].try_into().unwrap()) as usize;
    assert_eq!(n, raw.len() - 8, "{name}: the header counts the data bytes");
    raw[8..].to_vec()
}

fn f64s(b: Vec<u8>) -> Vec<f64> {
    b.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
}

fn i64s(b: Vec<u8>) -> Vec<usize> {
    b.chunks(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()) as usize)
        .collect()
}

/// Every start tag is closed in order (a well-formedness check of the
/// file's element structure; the Python suite reads it with meshio).
fn assert_balanced(xml: &str) {
    let mut open: Vec<&str> = Vec::new();
    for tag in xml.split('<').skip(1).map(|t| &t[..t.find('>').unwrap()]) {
        if tag.starts_with('?') || tag.ends_with('/') {
            continue;
        }
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(open.pop(), Some(name), "closing tag {name}");
        } else {
            open.push(tag.split_whitespace().next().unwrap());
        }
    }
    assert!(open.is_empty(), "unclosed {open:?}");
}

fn vtu_of(r: &SolveReply) -> String {
    let b = base64::engine::general_purpose::STANDARD
        .decode(r.vtu.as_ref().expect("vtu asked"))
        .unwrap();
    String::from_utf8(b).unwrap()
}

#[test]
fn the_vtu_of_a_solid_is_its_tetrahedra_and_its_displacement() {
    for (element, k, cell_type) in [("t4", 4, 10u8), ("t10", 10, 24u8)] {
        let r = solved(&block(element, json!(["mesh", "displacement", "stress", "vtu"])));
        let s = r.solid.as_ref().unwrap();
        let (nodes, elements) = (s.nodes.as_ref().unwrap(), s.elements.as_ref().unwrap());
        let u = s.displacement.as_ref().unwrap();
        assert_eq!(u.len(), nodes.len());
        assert_eq!(s.stress.as_ref().unwrap().len(), elements.len());
        assert!(elements.iter().all(|e| e.len() == k));
        let xml = vtu_of(&r);
        assert_balanced(&xml);
        let piece = format!(
            "NumberOfPoints=\"{}\" NumberOfCells=\"{}\"",
            nodes.len(),
            elements.len()
        );
        assert!(xml.contains(&piece), "{element}: {piece}");
        let offsets = i64s(array(&xml, "offsets"));
        assert_eq!(offsets, (1..=elements.len()).map(|c| c * k).collect::<Vec<_>>());
        assert!(array(&xml, "types").iter().all(|&t| t == cell_type));
        let points = f64s(array(&xml, "Points"));
        let d = f64s(array(&xml, "displacement"));
        for (n, (x, ui)) in nodes.iter().zip(u).enumerate() {
            for c in 0..3 {
                assert!((points[3 * n + c] - x[c]).abs() <= 1e-15 * x[c].abs().max(1.0));
                assert!(
                    (d[3 * n + c] - ui[c]).abs() <= 1e-15 * ui[c].abs().max(1e-300),
                    "{element} node {n}"
                );
            }
        }
        // Uniform compression: every tetrahedron's σzz is −p.
        let t = f64s(array(&xml, "stress_tensor"));
        assert_eq!(t.len(), 6 * elements.len());
        assert!(t.chunks(6).all(|s| (s[2] + 25.0).abs() < 1e-9 * 25.0), "σzz = −p");
        // Pressure on the base's nodes only, p on each (the patch test).
        let p = f64s(array(&xml, "contact_pressure"));
        for (n, x) in nodes.iter().enumerate() {
            let want = if x[2] == 0.0 { 25.0 } else { 0.0 };
            assert!(
                (p[n] - want).abs() < 1e-9 * 25.0,
                "{element} node {n} at {x:?}: {}",
                p[n]
            );
        }
        // VTK's quadratic tetra: node 4 + j is the midside of edge j with
        // VTK's edges 01, 12, 20, 03, 13, 23 (vtkQuadraticTetra). On a
        // generated mesh the midside is the edge's midpoint, so a wrong
        // permutation of Gmsh's order puts the wrong node there.
        if k == 10 {
            let conn = i64s(array(&xml, "connectivity"));
            let edges = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
            for cell in conn.chunks(10) {
                for (j, [a, b]) in edges.iter().enumerate() {
                    let (pa, pb, m) = (nodes[cell[*a]], nodes[cell[*b]], nodes[cell[4 + j]]);
                    for c in 0..3 {
                        assert!((0.5 * (pa[c] + pb[c]) - m[c]).abs() < 1e-15, "edge {j} of a cell");
                    }
                }
            }
        }
    }
}

/// Only what is asked is carried: `vtu` alone leaves the fields out, and a
/// reply without `outputs` has neither (the recorded replies stay as they were).
#[test]
fn outputs_carry_only_what_is_asked() {
    let r = solved(&block("t4", json!(["vtu"])));
    let s = r.solid.as_ref().unwrap();
    assert!(r.vtu.is_some() && s.nodes.is_none() && s.displacement.is_none() && s.stress.is_none());
    let r = solved(&block("t4", json!(["displacement"])));
    let s = r.solid.as_ref().unwrap();
    assert!(r.vtu.is_none() && s.nodes.is_none() && s.elements.is_none() && s.stress.is_none());
    assert!(s.displacement.is_some());
    let r = solved(&block("t4", json!([])));
    let s = serde_json::to_value(r.solid.as_ref().unwrap()).unwrap();
    for key in ["nodes", "elements", "displacement", "stress"] {
        assert!(s.get(key).is_none(), "{key} without outputs");
    }
}

/// `contact solve FILE --vtu OUT.vtu` writes the file for a solid request
/// (and the printed reply does not carry it, as in 2D).
#[test]
fn the_cli_writes_a_solids_vtu() {
    let dir = std::env::temp_dir().join(format!("contact-solid-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (req, out) = (dir.join("block.json"), dir.join("block.vtu"));
    std::fs::write(&req, serde_json::to_vec(&block("t10", json!([]))).unwrap()).unwrap();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_contact"))
        .args(["solve", req.to_str().unwrap(), "--vtu", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let xml = std::fs::read_to_string(&out).unwrap();
    assert_balanced(&xml);
    assert!(array(&xml, "types").iter().all(|&t| t == 24));
    let printed: Value = serde_json::from_slice(&run.stdout).unwrap();
    assert!(printed.get("vtu").is_none());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A solid's outputs are bounded like 2D's (`max_output_values`): the ball
/// example (T10, about 12k nodes, 8k tetrahedra) asking every output comes to
/// about 3e5 numbers, refused at `/outputs` under a limit of 1e5 before
/// anything is meshed, and admitted under the default 2e7.
#[test]
fn a_solids_outputs_are_bounded() {
    let mut req = example("solid_ball_on_flat.json");
    req["outputs"] = json!(["mesh", "displacement", "stress", "vtu"]);
    let run =
        |limits: &contact::scene::Limits| contact::check_bytes(serde_json::to_string(&req).unwrap().as_bytes(), limits);
    let small = contact::scene::Limits {
        max_output_values: 100_000,
        ..Default::default()
    };
    let e = run(&small).unwrap_err();
    assert_eq!(
        (e.code, e.path.as_str()),
        (contact::proto::ErrorCode::TooLarge, "/outputs"),
        "{e:?}"
    );
    assert!(run(&Default::default()).is_ok());
}

/// The recorded example with outputs (`solid_block_outputs.json`): a block on
/// a flat under a uniform pressure p, its sides on rollers, is oedometric:
/// σzz = −p, σxx = σyy = −ν/(1−ν) p and no shear in every tetrahedron,
/// u_x = u_y = 0 and u_z = −p z / M at every node (M = E(1−ν)/((1+ν)(1−2ν)),
/// the constrained modulus of the 1D column). The field is linear, in T10's
/// space (and T4's), so the answer is exact but for round-off: the factor's,
/// ε · cond(K) ~ 1e-12 on this 164-DOF mesh, asked to 1e-10 of p and of the
/// top's sinking.
#[test]
fn the_recorded_block_is_the_oedometric_column() {
    let req = example("solid_block_outputs.json");
    let b = &req["solid"]["body"];
    let e = b["material"]["youngs_modulus"].as_f64().unwrap();
    let nu = b["material"]["poisson_ratio"].as_f64().unwrap();
    let p = b["tractions"][0]["pressure"].as_f64().unwrap();
    let height = b["mesh"]["box"]["lengths"][2].as_f64().unwrap();
    let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let r = solved(&req);
    let s = r.solid.as_ref().unwrap();
    let (nodes, u, stress) = (
        s.nodes.as_ref().unwrap(),
        s.displacement.as_ref().unwrap(),
        s.stress.as_ref().unwrap(),
    );
    assert_eq!(stress.len(), s.elements.as_ref().unwrap().len());
    let lateral = -nu / (1.0 - nu) * p;
    for t in stress {
        let want = [lateral, lateral, -p, 0.0, 0.0, 0.0];
        for (got, want) in t.iter().zip(want) {
            assert!((got - want).abs() < 1e-10 * p, "stress {t:?}");
        }
    }
    let sink = p * height / m;
    for (x, ui) in nodes.iter().zip(u) {
        let want = [0.0, 0.0, -p * x[2] / m];
        for c in 0..3 {
            assert!(
                (ui[c] - want[c]).abs() < 1e-10 * sink,
                "node {x:?}: u {ui:?}, want {want:?}"
            );
        }
    }
    assert!(s
        .points
        .iter()
        .all(|q| q.in_contact && (q.pressure - p).abs() < 1e-10 * p));
}
