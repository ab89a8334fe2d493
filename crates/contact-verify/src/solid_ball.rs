//! Hertz's sphere on a flat in 3D (`proto/examples/solid_ball_on_flat.json`,
//! a quarter of a 10 mm cube standing for the ball, its gap Hertz's
//! paraboloid) at any element and `h_min`, solved through the core with its
//! candidate surface (`solid::two_level::Surface`), and Hertz's pressure in
//! the surface's nondimensional units: what the 3D error bar is checked
//! against (`examples/solid_effectivity.rs`, `tests/solid_error_bar.rs`).

use contact_core::solid::door::{admit, SolidProblem};
use contact_core::Limits;
use serde_json::{json, Value};

use crate::reference::hertz_sphere;

pub const E: f64 = 210000.0;
pub const NU: f64 = 0.3;
pub const R: f64 = 50.0;
/// The whole ball's load (the quarter carries a fourth).
pub const P: f64 = 6153.846153846154;
/// The scene's length scale: the cube's side.
pub const L: f64 = 10.0;

/// The example's request with its element (`t4`, `t10`) and `h_min` [mm].
pub fn request(element: &str, h_min: f64) -> Value {
    // Built in: the bench binary runs from anywhere.
    let mut req: Value =
        serde_json::from_str(include_str!("../../../proto/examples/solid_ball_on_flat.json")).expect("the example");
    let b = &mut req["solid"]["body"]["mesh"]["box"];
    b["element"] = json!(element);
    b["grading"]["h_min"] = json!(h_min);
    req
}

/// The same request with the box meshed here and handed over as a given
/// inline mesh (nodes, tetrahedra and face sets, in mm), as a user's own mesh
/// comes: the core's generator (`mesh3d::generate::box_mesh`) with the
/// example's box and grading, `h_min` [mm].
pub fn given(element: &str, h_min: f64) -> Value {
    use contact_core::mesh::generate::Grading;
    use contact_core::mesh3d::{generate::box_mesh, Order};
    let mut req = request(element, h_min);
    let b = req["solid"]["body"]["mesh"]["box"].clone();
    let three = |v: &Value| -> [f64; 3] { std::array::from_fn(|c| v[c].as_f64().expect("a number")) };
    let (lo, lengths) = (three(&b["corner"]), three(&b["lengths"]));
    let g = &b["grading"];
    let grading = Grading {
        h_min,
        ratio: g["ratio"].as_f64().expect("ratio"),
        extent: g["extent"].as_f64().expect("extent"),
    };
    let order = if element == "t10" { Order::T10 } else { Order::T4 };
    let hi = std::array::from_fn(|c| lo[c] + lengths[c]);
    let size = b["size"].as_f64().expect("size");
    let mesh = box_mesh(lo, hi, size, Some((three(&g["focus"]), grading)), order);
    let elements: Vec<&[usize]> = (0..mesh.n_elems()).map(|e| mesh.elem(e)).collect();
    let face_sets: serde_json::Map<String, Value> = mesh
        .face_sets
        .iter()
        .map(|(name, faces)| (name.clone(), json!(faces.iter().map(|f| f.corners).collect::<Vec<_>>())))
        .collect();
    req["solid"]["body"]["mesh"] = json!({"inline": {
        "nodes": mesh.nodes,
        "elements": elements,
        "face_sets": face_sets,
    }});
    req
}

/// The request through the door, as the service admits it.
pub fn problem(req: &Value, limits: &Limits) -> SolidProblem {
    let parsed: contact_proto::SolveRequest = serde_json::from_value(req.clone()).expect("a request");
    let scene = contact_core::scene::validate::solid_scene(&parsed, limits).expect("a valid scene");
    admit(scene).expect("an admitted problem")
}

/// Hertz's contact radius and peak over the scene's scales (a / L, p0 / E).
pub fn hertz() -> (f64, f64) {
    let (a, p0) = hertz_sphere(P, R, E / (1.0 - NU * NU));
    (a / L, p0 / E)
}

/// Hertz's pressure p0 √(1 − r²/a²) at a point of the flat face z = 0, in
/// the scene's units.
pub fn hertz_pressure(x: [f64; 3]) -> f64 {
    let (a, p0) = hertz();
    p0 * (1.0 - (x[0] * x[0] + x[1] * x[1]) / (a * a)).max(0.0).sqrt()
}
