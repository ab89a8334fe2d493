//! Requests built as JSON, solved in process: the core's report, not the
//! wire reply (the suites read the numbers, the service tests the wire).

use contact_core::error::{CoreError, InvalidKind};
use contact_core::solution::report::Report;
use contact_core::{Limits, Scene};
use contact_proto::SolveRequest;
use serde_json::Value;

/// Validates and solves `req`; a request that does not fit the schema is an
/// `invalid_request` as the service would call it.
pub fn solve(req: &Value, limits: &Limits) -> Result<Report, CoreError> {
    let req: SolveRequest =
        serde_json::from_value(req.clone()).map_err(|e| CoreError::invalid(InvalidKind::Request, "", e.to_string()))?;
    contact_core::solve(&Scene::try_new(&req, limits)?, limits, None)
}

/// `req` with every generated mesh replaced by the same mesh given inline
/// (its nodes, elements and edge sets, in the request's units): the scene as
/// a user with their own mesher would send it, for the estimate and the
/// refinement of given meshes.
pub fn inlined(req: &Value) -> Value {
    let parsed: SolveRequest = serde_json::from_value(req.clone()).expect("a valid request");
    let scene = Scene::try_new(&parsed, &Limits::default()).expect("a valid scene");
    let meshes = contact_core::meshing::meshes(&scene).expect("generated meshes");
    with_meshes(req, &meshes, scene.scales.length)
}

/// `req` with its bodies' meshes given inline as `meshes` (nondimensional,
/// as the core holds them; `length` the scene's length scale).
pub fn with_meshes(req: &Value, meshes: &[contact_core::mesh::Mesh2d], length: f64) -> Value {
    let mut out = req.clone();
    for (b, m) in meshes.iter().enumerate() {
        let nodes: Vec<[f64; 2]> = m.nodes.iter().map(|p| [p[0] * length, p[1] * length]).collect();
        let k = m.order.nodes_per_element();
        let elements: Vec<&[usize]> = m.elems.chunks(k).collect();
        let sets: serde_json::Map<String, Value> = m
            .edge_sets
            .iter()
            .map(|(name, edges)| {
                (
                    name.clone(),
                    serde_json::json!(edges.iter().map(|e| [e.a, e.b]).collect::<Vec<_>>()),
                )
            })
            .collect();
        out["bodies"][b]["mesh"] =
            serde_json::json!({"inline": {"nodes": nodes, "elements": elements, "edge_sets": sets}});
    }
    out
}
