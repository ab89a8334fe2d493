//! The energy bound against the truth: each scene on a mesh and on that
//! mesh split in four once and twice (nested, so the potential energy falls
//! monotonically), the exact potential extrapolated from the three, and
//! ‖u − u_h‖_E ≤ √(2 (J(u_h) − J(u))) compared with the bound.
//!
//! `cargo run --release -p contact-verify --example energy_bound [FACTOR] [SCENE…]`
//! (FACTOR coarsens the scene's mesh, `effectivity::scaled`).

use contact_core::mesh::uniform::refine_uniform;
use contact_core::{Limits, Scene};
use contact_proto::SolveRequest;
use serde_json::Value;

fn effectivity_scene(name: &str) -> Value {
    let scene = contact_verify::effectivity::SCENES
        .iter()
        .find(|s| s.name == name)
        .expect("scene");
    (scene.request)()
}

/// The clamped block of the test `energy_bound` (loaded on top, held at its
/// bottom, with no contact), in elements of `element`.
fn clamped_block(element: &str) -> Value {
    use contact_verify::build::*;
    let block = body("block", 100.0, 0.3, rectangle([0.0, 0.0], 2.0, 1.0, 0.2, element))
        .fixed("bottom")
        .traction("top", [0.3, -1.0])
        .body_force([0.0, -0.5]);
    request(vec![block], vec![pair("block", "top").obstacle("far")])
        .with_obstacle(obstacle("far", line([0.0, 1.2], [0.0, -1.0])))
        .to_value()
}

fn main() {
    let t3 = |(name, v): (&'static str, Value)| (name, v, "t3");
    let mut scenes: Vec<(&str, Value, &str)> = vec![
        (
            "hertz_block",
            serde_json::from_str(include_str!("../../../proto/examples/signorini_hertz_cylinder.json")).unwrap(),
        ),
        ("disk_on_flat", contact_verify::convergence::disk_request(0.01, "t3")),
        (
            "flat_punch",
            serde_json::from_str(include_str!("../../../proto/examples/indentation_flat_punch.json")).unwrap(),
        ),
        // A polyline floor whose two segments' normals turn along them
        // (`energy::normal`, a fan on each side).
        (
            "vee",
            serde_json::from_str(include_str!(
                "../../../proto/examples/signorini_inline_block_on_vee.json"
            ))
            .unwrap(),
        ),
        (
            "circular_punch",
            serde_json::from_str(include_str!("../../../proto/examples/indentation_circular_punch.json")).unwrap(),
        ),
        (
            "gmsh_hertz",
            serde_json::from_str(include_str!(
                "../../../proto/examples/signorini_hertz_cylinder_gmsh.json"
            ))
            .unwrap(),
        ),
        // The centred footing of the example: uniform stress and pressure,
        // exact in the model (a bound at round-off).
        (
            "winkler_patch",
            serde_json::from_str(include_str!("../../../proto/examples/foundation_winkler_footing.json")).unwrap(),
        ),
        // Loaded off centre: it lifts off the springs (`effectivity`).
        ("winkler_footing", effectivity_scene("winkler_footing")),
    ]
    .into_iter()
    .map(t3)
    .collect();
    // Quadratic triangles (`solution::energy::quadratic`).
    scenes.push((
        "hertz_t6",
        serde_json::from_str(include_str!("../../../proto/examples/signorini_hertz_cylinder_t6.json")).unwrap(),
        "t6",
    ));
    // Rubber-like: T6 at ν ≥ 0.45 in plane strain is the P2–P0 element.
    for (name, nu) in [("hertz_p2p0_49", 0.49), ("hertz_p2p0_499", 0.499)] {
        let mut req: Value =
            serde_json::from_str(include_str!("../../../proto/examples/signorini_hertz_cylinder_t6.json")).unwrap();
        req["bodies"][0]["material"]["poisson_ratio"] = serde_json::json!(nu);
        scenes.push((name, req, "t6"));
    }
    scenes.push((
        "flat_punch_t6",
        serde_json::from_str(include_str!("../../../proto/examples/indentation_flat_punch.json")).unwrap(),
        "t6",
    ));
    scenes.push(("punch_moment_t6", effectivity_scene("punch_under_moment"), "t6"));
    scenes.push(("winkler_footing_t6", effectivity_scene("winkler_footing"), "t6"));
    scenes.push(("clamped_t3", clamped_block("t3"), "t3"));
    scenes.push(("clamped_t6", clamped_block("t6"), "t6"));
    let scale: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let factor = scale.first().copied().unwrap_or(1.0);
    println!("scene          level    dofs   bound_rel  true_rel(J)  effectivity  correction  contact  t_solve");
    let only: Vec<String> = std::env::args().skip(1).filter(|a| a.parse::<f64>().is_err()).collect();
    for (name, base, element) in scenes {
        if !only.is_empty() && !only.iter().any(|o| o == name) {
            continue;
        }
        // A T3 request run in T6 is converted at the same node spacing.
        let meshed_in = base["bodies"][0]["mesh"]
            .as_object()
            .and_then(|m| m.values().find_map(|g| g["element"].as_str()))
            .unwrap_or("t3");
        let base = if factor != 1.0 || meshed_in != element {
            contact_verify::effectivity::scaled(&base, factor, element)
        } else {
            base
        };
        let parsed: SolveRequest = serde_json::from_value(base.clone()).expect("request");
        let scene = Scene::try_new(&parsed, &Limits::default()).expect("scene");
        let mut meshes = contact_core::meshing::meshes(&scene).expect("meshes");
        let mut levels = Vec::new();
        for _ in 0..3 {
            let req = contact_verify::run::with_meshes(&base, &meshes, scene.scales.length);
            let t = std::time::Instant::now();
            let r = contact_verify::run::solve(&req, &Limits::default()).expect("solve");
            let dt = t.elapsed().as_secs_f64();
            if r.energy.is_none() {
                let why: Vec<&str> = r
                    .notes
                    .iter()
                    .filter(|n| n.text.contains("energy bound"))
                    .map(|n| n.text.as_str())
                    .collect();
                println!("{name:14} no bound: {why:?}");
            }
            levels.push((r.size.dofs, r.energy, dt));
            meshes = meshes.iter().map(refine_uniform).collect();
        }
        let j: Vec<f64> = levels.iter().map(|l| l.1.map_or(f64::NAN, |e| e.potential)).collect();
        let ratio = (j[0] - j[1]) / (j[1] - j[2]);
        let j_inf = j[2] - (j[1] - j[2]) / (ratio - 1.0);
        for (lv, (dofs, e, dt)) in levels.iter().enumerate().take(2) {
            let Some(e) = e else {
                println!("{name:14} {lv:5} {dofs:7}   no bound");
                continue;
            };
            let truth = (2.0 * (j[lv] - j_inf)).max(0.0).sqrt();
            let true_rel = truth / e.norm;
            println!(
                "{name:14} {lv:5} {dofs:7}   {:9.4e}  {:9.4e}    {:8.3}     {:8.2e}  {:8.2e}  {dt:.3}  (J rate {:.2})",
                e.absolute / e.norm,
                true_rel,
                e.absolute / truth,
                e.correction / e.norm,
                e.contact.sqrt() / e.norm,
                ratio
            );
            println!("               shift {:8.2e}", e.shift / e.norm);
        }
    }
}
