//! 3D solids through the wire (`analysis: "solid"`), by the entry the CLI
//! and the service use (`solve_bytes`), against truths and closed forms:
//!
//! - the contact patch test (also through a Gmsh file, the example
//!   `solid_block_on_flat_gmsh.json`): a box on a rigid plane under a uniform
//!   pressure, its four sides on rollers, is oedometric, a field in T4's
//!   space: every point's pressure is p, on T4 (nodal rows) and T10 (dual
//!   mortar rows);
//! - a block whose sides are free except two symmetry planes, under a
//!   pressure and its weight: the reply's resultant balances the load (force
//!   and moment about the origin);
//! - Hertz's sphere on a flat (the example `solid_ball_on_flat.json`, a
//!   quarter model, T10, the sphere's gap a paraboloid on a flat face);
//! - unit invariance: the same scene in mm, N, MPa and in m, N, Pa;
//! - refusals, each with a JSON pointer that resolves in the request.
//!
//! Tolerances: the patch test's field is exact in the discrete space, so
//! its pressures carry the round-off of the factorization and of the dense
//! condensed operator, ε · cond(K) with cond(K) ~ 1e4 on these graded
//! meshes (2e-12), then refined on the active set (`solid::signorini`):
//! 1e-11 of p, over the 1.0e-12 (T4) and 1.3e-12 (T10) measured. Equilibrium is an equation the mixed LCP
//! solves (the free motion's Dᵀλ = Rᵀf), to its round-off: 1e-9 of the load.

mod common;
use common::*;
use serde_json::{json, Value};

const E: f64 = 2.0e5;
const NU: f64 = 0.3;

/// A block [0, lx] × [0, ly] × [0, lz] resting on the plane z = 0.
fn block(element: &str, lengths: [f64; 3], size: f64, supports: Value, tractions: Value) -> Value {
    json!({
        "version": "1",
        "analysis": "solid",
        "solid": {
            "body": {
                "material": {"youngs_modulus": E, "poisson_ratio": NU},
                "mesh": {"box": {"corner": [0.0, 0.0, 0.0], "lengths": lengths, "size": size, "element": element,
                    "grading": {"focus": [0.3, 0.6, 0.0], "h_min": 0.3 * size, "ratio": 1.5, "extent": 0.05}}},
                "supports": supports,
                "tractions": tractions
            },
            "obstacle": {"shape": {"plane": {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}}},
            "contact": {"faces": "z_min"}
        }
    })
}

fn rollers() -> Value {
    json!([
        {"faces": "x_min", "ux": 0.0}, {"faces": "x_max", "ux": 0.0},
        {"faces": "y_min", "uy": 0.0}, {"faces": "y_max", "uy": 0.0}
    ])
}

#[test]
fn a_box_pressed_uniformly_presses_the_plane_uniformly() {
    let p = 25.0;
    for element in ["t4", "t10"] {
        let req = block(
            element,
            [1.0, 1.0, 0.5],
            0.25,
            rollers(),
            json!([{"faces": "z_max", "pressure": p}]),
        );
        let r = solved(&req);
        let s = r.solid.as_ref().expect("a solid answer");
        let worst = s.points.iter().fold(0.0f64, |a, q| a.max((q.pressure - p).abs())) / p;
        println!(
            "{element}: {} DOFs, {} points, pressure error {worst:.1e}",
            r.size.dofs,
            s.points.len()
        );
        assert!(worst < 1e-11, "pressure off p by {worst:e} of p");
        assert!(s.points.iter().all(|q| q.in_contact));
        assert_eq!(s.patches.len(), 1);
        let patch = &s.patches[0];
        // The whole base, of area 1: a sum of face areas (round-off).
        assert!((patch.area - 1.0).abs() < 1e-12, "area {}", patch.area);
        assert!((patch.force - p).abs() < 1e-9 * p, "force {}", patch.force);
        assert!((s.resultant.force[2] - p).abs() < 1e-9 * p);
        assert_eq!(patch.outline.len(), 1, "one loop around the base");
    }
}

/// The Gmsh example (a generated box written as MSH 4.1): the same patch
/// test through the Gmsh reader, its physical surfaces as the face sets.
#[test]
fn the_gmsh_block_presses_the_flat_uniformly() {
    let r = solved(&example("solid_block_on_flat_gmsh.json"));
    let s = r.solid.as_ref().unwrap();
    let worst = s.points.iter().fold(0.0f64, |a, q| a.max((q.pressure - 2.0).abs())) / 2.0;
    println!("{} points, pressure error {worst:.1e}", s.points.len());
    assert!(worst < 1e-11 && s.points.iter().all(|q| q.in_contact));
    assert!((s.resultant.force[2] - 3200.0).abs() < 1e-9 * 3200.0);
    assert_eq!(s.patches.len(), 1);
    assert!((s.patches[0].area - 1600.0).abs() < 1e-12 * 1600.0);
}

/// The uniaxial block: rollers on the symmetry planes x = 0 and y = 0 only
/// (no reaction there in the exact field: σxx = σyy = 0, σzz = −p, linear
/// u, in T4's space), a pressure p on top: the plane carries F = p A along
/// +z, at the base's centre, so its moment about the origin is (ly/2 · F,
/// −lx/2 · F, 0). With a weight density w too the base no longer stays
/// flat in the free column (Timoshenko's prism under its own weight), so
/// the supports react and only the force balances: F = p A + w V.
#[test]
fn the_resultant_balances_the_load_and_the_weight() {
    let ([lx, ly, lz], p, w) = ([1.0, 0.8, 0.6], 30.0, 0.5);
    let supports = json!([{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}]);
    for element in ["t4", "t10"] {
        let req = block(
            element,
            [lx, ly, lz],
            0.2,
            supports.clone(),
            json!([{"faces": "z_max", "pressure": p}]),
        );
        let r = solved(&req);
        let s = r.solid.as_ref().unwrap();
        let f = p * lx * ly;
        let want = [[0.0, 0.0, f], [0.5 * ly * f, -0.5 * lx * f, 0.0]];
        let got = [s.resultant.force, s.resultant.moment];
        println!("{element}: resultant {got:?}, want {want:?}");
        for (g, w) in got.iter().flatten().zip(want.iter().flatten()) {
            assert!((g - w).abs() < 1e-9 * f, "{got:?} against {want:?}");
        }
        // The top-level resultant is the x, y force and the moment about z.
        assert_eq!(
            [r.resultant.fx, r.resultant.fy, r.resultant.m],
            [got[0][0], got[0][1], got[1][2]]
        );

        let mut heavy = req.clone();
        heavy["solid"]["body"]["body_force"] = json!([0.0, 0.0, -w]);
        let r = solved(&heavy);
        let s = r.solid.as_ref().unwrap();
        let f = p * lx * ly + w * lx * ly * lz;
        let patches: f64 = s.patches.iter().map(|q| q.force).sum();
        println!("  with its weight: {:?}, want {f}", s.resultant.force);
        assert!((s.resultant.force[2] - f).abs() < 1e-9 * f && (patches - f).abs() < 1e-9 * f);
        assert!(
            s.resultant.force[0] == 0.0 && s.resultant.force[1] == 0.0,
            "along the plane's normal"
        );
    }
}

/// Hertz's sphere (the example): a = (3PR/4E*)^(1/3), p(r) = p0 √(1 − r²/a²)
/// with p0 = 3P/(2πa²). The contact radius is read from the points in
/// contact by a least-squares fit of p² against r², which Hertz's p makes
/// a line, p² = p0² (1 − r²/a²): a² = −intercept / slope. The cells are a/5
/// at the apex, so the outline alone places a within a cell; the fit, over
/// the 28 points in contact, measured a_h / a = 1.006: 2 % is asked, the
/// issue's bound. The peak sits at the apex (a corner row): its pressure
/// is the dual-weighted mean of p over the corner's faces, which lowers a
/// concave maximum by O(h²/a²) of p0 (1 / 25 at h = a/5 less the mortar's
/// weights' share, measured 1.6 %): 3 % is asked.
#[test]
fn a_ball_on_a_flat_matches_hertz() {
    let req = example("solid_ball_on_flat.json");
    let s_ = &req["solid"];
    let big_r = s_["contact"]["initial_gap"]["paraboloid"]["radius"].as_f64().unwrap();
    let e = s_["body"]["material"]["youngs_modulus"].as_f64().unwrap();
    let nu = s_["body"]["material"]["poisson_ratio"].as_f64().unwrap();
    let quarter = s_["body"]["tractions"][0]["pressure"].as_f64().unwrap() * 100.0;
    let load = 4.0 * quarter;
    let e_star = e / (1.0 - nu * nu);
    let a = (3.0 * load * big_r / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * load / (2.0 * std::f64::consts::PI * a * a);
    let r = solved(&req);
    let s = r.solid.as_ref().unwrap();
    assert!(
        (s.resultant.force[2] - quarter).abs() < 1e-9 * quarter,
        "{:?}",
        s.resultant
    );
    assert_eq!(s.patches.len(), 1, "one patch");
    let a_h = circle_fit(&s.points);
    let peak = s.patches[0].peak_pressure;
    // The relative L2 error of the pressure at the points (Hertz's p, 0
    // outside the circle), reported, not asserted: the points are no
    // quadrature.
    let hertz = |r2: f64| p0 * (1.0 - r2 / (a * a)).max(0.0).sqrt();
    let (num, den) = s.points.iter().fold((0.0, 0.0), |(n, d), q| {
        let h = hertz(q.at[0].powi(2) + q.at[1].powi(2));
        (n + (q.pressure - h).powi(2), d + h * h)
    });
    println!(
        "{} DOFs, {} points in contact: a_h / a = {:.4}, peak / p0 = {:.4} at {:?}, pointwise L2 error {:.3}",
        r.size.dofs,
        s.points.iter().filter(|q| q.in_contact).count(),
        a_h / a,
        peak / p0,
        s.patches[0].peak_at,
        (num / den).sqrt()
    );
    assert!((a_h / a - 1.0).abs() < 0.02, "a_h / a = {}", a_h / a);
    assert!((peak / p0 - 1.0).abs() < 0.03, "p0_h / p0 = {}", peak / p0);
    assert_eq!(s.patches[0].peak_at, [0.0; 3], "the peak at the apex");
}

/// A patch narrower than the mesh resolves is never answered without a
/// warning. The Hertz ball on T4 at h_min 0.2 mm (a / h = 5, inside the
/// bench's band of a few % off Hertz: `contact-bench --solid`) is not
/// warned; the same scene with E read in Pa as if in MPa (10⁶ too stiff, a
/// 100 times smaller: the unit slip) presses one node and is `solved` with
/// `coarse_contact_zone`, the limit 4 and a size to refine to. One node's
/// patch spans at most 2/√π = 1.13 spacings: its tributary area is at most
/// a third of its six faces', h² on a grid of right triangles, whose disk's
/// diameter is 2h/√π (fewer faces at the box's corner, where the apex is:
/// measured 0.65); the width taken is at most that diameter. A load path
/// is warned at its narrowest step's patch.
#[test]
fn a_patch_the_mesh_does_not_resolve_is_warned() {
    let ball = |stiffer: f64| {
        let mut req = example("solid_ball_on_flat.json");
        let body = &mut req["solid"]["body"];
        body["mesh"]["box"]["element"] = json!("t4");
        body["mesh"]["box"]["grading"]["h_min"] = json!(0.2);
        let e = body["material"]["youngs_modulus"].as_f64().unwrap();
        body["material"]["youngs_modulus"] = json!(e * stiffer);
        solved(&req)
    };
    let resolved = ball(1.0);
    let coarse = |r: &contact::proto::SolveReply| r.warnings.iter().find(|w| w.code == "coarse_contact_zone").cloned();
    assert!(coarse(&resolved).is_none(), "{:?}", resolved.warnings);
    // `solved` checks the status.
    let slipped = ball(1e6);
    let w = coarse(&slipped).unwrap_or_else(|| panic!("no coarse_contact_zone: {:?}", slipped.warnings));
    println!("{w:?}");
    assert_eq!((w.location.as_str(), w.limit), ("/solid/contact", 4.0), "{w:?}");
    assert!(w.value <= 2.0 / std::f64::consts::PI.sqrt(), "one node's patch: {w:?}");
    assert!(w.message.contains("1 row(s) in contact"), "{}", w.message);
    assert!(
        w.message.contains("unit slip") && w.message.contains("Refine"),
        "{}",
        w.message
    );
    // A path through the load ×1e-6 (a ∝ P^(1/3): the same 100 times smaller
    // patch) that ends on the load as meant: the narrow patch of its first
    // step is warned and named, though the last step's is resolved (the
    // reply read the last step's patches alone).
    let mut path = example("solid_ball_on_flat.json");
    path["solid"]["body"]["mesh"]["box"]["element"] = json!("t4");
    path["solid"]["body"]["mesh"]["box"]["grading"]["h_min"] = json!(0.2);
    path["load_path"] =
        json!([{"loads": {"/solid/body/tractions/0": 1e-6}}, {"loads": {"/solid/body/tractions/0": 1.0}}]);
    let through = solved(&path);
    let w = coarse(&through).unwrap_or_else(|| panic!("no coarse_contact_zone: {:?}", through.warnings));
    assert!(w.value <= 2.0 / std::f64::consts::PI.sqrt(), "one node's patch: {w:?}");
    assert!(w.message.contains("(at load path step 0)"), "{}", w.message);
}

/// Loads far too large for the modulus, without `load_factors`, are treated
/// as 2D treats them: answered with a `large_displacement` warning naming
/// the likely unit slip when the solve can represent them, refused at the
/// load's pointer when it cannot (nondimensional loads past 1e150 E·L²), and
/// a `load_path` step's factor (up to 1e6) counts: the step is refused at
/// its own pointer where its scaled loads pass that.
#[test]
fn loads_far_too_large_for_the_modulus_are_warned_or_refused() {
    let pressed = |p: f64| {
        let mut req = example("solid_ball_on_flat.json");
        let body = &mut req["solid"]["body"];
        body["mesh"]["box"]["element"] = json!("t4");
        body["mesh"]["box"]["grading"]["h_min"] = json!(0.4);
        body["tractions"][0]["pressure"] = json!(p);
        req
    };
    let p = example("solid_ball_on_flat.json")["solid"]["body"]["tractions"][0]["pressure"]
        .as_f64()
        .unwrap();
    let moved = |r: &contact::proto::SolveReply| r.warnings.iter().find(|w| w.code == "large_displacement").cloned();
    let as_meant = solved(&pressed(p));
    assert!(moved(&as_meant).is_none(), "{:?}", as_meant.warnings);
    // ×1e9: the whole base is pressed, and the linear answer moves the 10 mm
    // cube by about p/E times its side (15.4e9 / 2.1e5 × 10 mm): some 7e4 of
    // its size, past 5e-2.
    let slipped = solved(&pressed(p * 1e9));
    let w = moved(&slipped).unwrap_or_else(|| panic!("no large_displacement: {:?}", slipped.warnings));
    assert_eq!((w.location.as_str(), w.limit), ("/solid/body", 5e-2), "{w:?}");
    assert!(w.value > 1e3, "{w:?}");
    assert!(w.message.contains("unit slip"), "{}", w.message);
    // A path through ×1e9 that ends on the load as meant: the warning is the
    // largest step's, not the last's (it read the last step only), and names it.
    // (A step's factor is at most 1e6, so the base is ×1e4.)
    let mut through = pressed(p * 1e4);
    through["load_path"] = json!([
        {"loads": {"/solid/body/tractions/0": 1e5}},
        {"loads": {"/solid/body/tractions/0": 1e-4}}
    ]);
    let through = solved(&through);
    let w = moved(&through).unwrap_or_else(|| panic!("no large_displacement: {:?}", through.warnings));
    assert!(w.value > 1e3, "{w:?}");
    assert!(w.message.contains("at load path step 0"), "{}", w.message);
    // p / E = 1e155 > 1e150: refused at the pressure.
    let e = solve(&pressed(2.1e5 * 1e155)).expect_err("beyond what the solve represents");
    assert_eq!(e.path, "/solid/body/tractions/0", "{e:?}");
    assert!(e.message.contains("unit slip"), "{}", e.message);
    // p / E = 1e145 is, but a step's factor of 1e6 takes it past.
    let mut path = pressed(2.1e5 * 1e145);
    solved(&path);
    path["load_path"] =
        json!([{"loads": {"/solid/body/tractions/0": 1.0}}, {"loads": {"/solid/body/tractions/0": 1e6}}]);
    let e = solve(&path).expect_err("a step beyond what the solve represents");
    assert_eq!(e.path, "/load_path/1", "{e:?}");
}

/// A coarse Hertz ball on T4 (nonuniform pressure, a patch edge inside the
/// mesh) in mm, N, MPa and in m, N, Pa: lengths ×1e-3, stresses ×1e6,
/// forces as they are, moments ×1e-3. The door scales both to the same
/// nondimensional scene up to the round-off of the scaling (the generated
/// grid lines are computed from the scaled numbers), so every number agrees
/// to 1e-9 of its key's largest magnitude.
#[test]
fn the_answer_does_not_depend_on_the_units() {
    let mm = json!({
        "version": "1",
        "analysis": "solid",
        "solid": {
            "body": {
                "material": {"youngs_modulus": 210000.0, "poisson_ratio": 0.3},
                "mesh": {"box": {"corner": [0.0, 0.0, 0.0], "lengths": [10.0, 10.0, 8.0], "size": 5.0,
                    "grading": {"focus": [0.0, 0.0, 0.0], "h_min": 0.4, "ratio": 2.0, "extent": 1.2}}},
                "supports": [{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}],
                "tractions": [{"faces": "z_max", "pressure": 15.0}],
                "body_force": [0.0, 0.0, -7.8e-5]
            },
            "obstacle": {"shape": {"plane": {"point": [0.0, 0.0, -0.001], "normal": [0.0, 0.0, 1.0]}}},
            "contact": {"faces": "z_min", "initial_gap": {"paraboloid": {"apex": [0.0, 0.0, 0.0], "radius": 50.0}}}
        }
    });
    let mut m = mm.clone();
    let b = &mut m["solid"]["body"];
    b["material"]["youngs_modulus"] = json!(210000.0e6);
    b["mesh"]["box"] = json!({"corner": [0.0, 0.0, 0.0], "lengths": [0.01, 0.01, 0.008], "size": 0.005,
        "grading": {"focus": [0.0, 0.0, 0.0], "h_min": 0.0004, "ratio": 2.0, "extent": 0.0012}});
    b["tractions"][0]["pressure"] = json!(15.0e6);
    b["body_force"] = json!([0.0, 0.0, -7.8e4]);
    m["solid"]["obstacle"]["shape"]["plane"]["point"] = json!([0.0, 0.0, -1e-6]);
    m["solid"]["contact"]["initial_gap"]["paraboloid"]["radius"] = json!(0.05);
    let (a, b) = (solved(&mm), solved(&m));
    let (sa, sb) = (a.solid.unwrap(), b.solid.unwrap());
    assert_eq!(sa.points.len(), sb.points.len());
    let active = sa.points.iter().filter(|q| q.in_contact).count();
    println!("{active} of {} points in contact", sa.points.len());
    assert!(active > 3 && active < sa.points.len(), "a patch inside the face set");
    assert_same_in_units(
        &point_values(&sa, |q| q.pressure),
        &point_values(&sb, |q| q.pressure),
        1e6,
        "pressure",
    );
    assert_same_in_units(
        &point_values(&sa, |q| q.gap),
        &point_values(&sb, |q| q.gap),
        1e-3,
        "gap",
    );
    assert_same_in_units(
        &point_values(&sa, |q| q.at[0]),
        &point_values(&sb, |q| q.at[0]),
        1e-3,
        "x",
    );
    assert_eq!(
        point_values(&sa, |q| q.in_contact as u8 as f64),
        point_values(&sb, |q| q.in_contact as u8 as f64)
    );
    assert_same_in_units(&sa.resultant.force, &sb.resultant.force, 1.0, "force");
    assert_same_in_units(&sa.resultant.moment, &sb.resultant.moment, 1e-3, "moment");
    assert_same_in_units(&[sa.patches[0].area], &[sb.patches[0].area], 1e-6, "area");
}

/// Refused requests: the code, and a pointer that resolves in the request.
#[test]
fn mistakes_are_refused_with_their_place() {
    let good = example("solid_ball_on_flat.json");
    let change = |pointer: &str, v: Value| -> Value {
        let mut r = good.clone();
        *r.pointer_mut(pointer).unwrap() = v;
        r
    };
    let mut inverted = good.clone();
    inverted["solid"]["body"]["mesh"] = json!({"inline": {
        "nodes": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        "elements": [[0, 2, 1, 3]],
        "face_sets": {"z_min": [[0, 1, 2]]}
    }});
    let mut flat = inverted.clone();
    flat["solid"]["body"]["mesh"]["inline"]["nodes"][3] = json!([0.3, 0.3, 0.0]);
    flat["solid"]["body"]["mesh"]["inline"]["elements"][0] = json!([0, 1, 2, 3]);
    let mut unsupported = good.clone();
    unsupported["solid"]["body"]["supports"] = json!([]);
    let mut with_2d = good.clone();
    with_2d["contacts"] = json!([{"body": 0, "edges": "top", "obstacle": 0}]);
    let cases = [
        (
            change("/solid/body/material/youngs_modulus", json!(-1.0)),
            "invalid_material",
            "/solid/body/material/youngs_modulus",
        ),
        (
            change("/solid/body/material/poisson_ratio", json!(0.5)),
            "invalid_material",
            "/solid/body/material/poisson_ratio",
        ),
        (
            change("/solid/body/supports/1/faces", json!("y_low")),
            "invalid_request",
            "/solid/body/supports/1/faces",
        ),
        (
            change("/solid/contact/faces", json!("bottom")),
            "invalid_request",
            "/solid/contact/faces",
        ),
        (
            change("/solid/obstacle/shape/plane/normal", json!([0.0, 0.0, 0.0])),
            "invalid_geometry",
            "/solid/obstacle/shape/plane/normal",
        ),
        (
            change("/solid/body/mesh/box/grading/ratio", json!(3.0)),
            "invalid_mesh",
            "/solid/body/mesh/box/grading/ratio",
        ),
        // A generated box too thin to mesh, or too far from the origin for
        // its sides to be distinct once scaled: refused at the door, as a 2D
        // rectangle is, before any sliver is made.
        (
            change("/solid/body/mesh/box/lengths/0", json!(1e-12)),
            "invalid_mesh",
            "/solid/body/mesh/box/lengths/0",
        ),
        (
            change("/solid/body/mesh/box/corner/0", json!(1e300)),
            "invalid_mesh",
            "/solid/body/mesh/box/corner/0",
        ),
        (inverted, "invalid_mesh", "/solid/body/mesh/inline/elements/0"),
        (flat, "invalid_mesh", "/solid/body/mesh/inline/elements/0"),
        (unsupported, "no_support", "/solid/body/supports"),
        (with_2d, "invalid_request", "/contacts"),
        (change("/analysis", json!("plane_strain")), "invalid_request", "/solid"),
    ];
    let mut penalty = good.clone();
    penalty["method"] = json!("penalty");
    let cases = cases.into_iter().chain([(penalty, "invalid_request", "/method")]);
    for (req, code, path) in cases {
        let e = solve(&req).expect_err(path);
        println!("{path}: {}", e.message);
        assert_eq!(serde_json::to_value(e.code).unwrap(), json!(code), "{path}: {e:?}");
        assert_eq!(e.path, path, "{e:?}");
        assert!(req.pointer(&e.path).is_some(), "{} resolves in the request", e.path);
    }
    // Past the size limit before any mesh is built.
    let limits = contact::scene::Limits {
        max_dofs: 10_000,
        ..Default::default()
    };
    let e = solve_with(&good, &limits).expect_err("too large");
    assert_eq!(serde_json::to_value(e.code).unwrap(), json!("too_large"));
    assert_eq!(e.path, "/solid/body/mesh/box");
    // Within the DOF limit, but a 3D factor fills far more per DOF than the
    // 2D rate the limit was set from (the ball's: 0.28 GB at 35k DOF, 8 kB
    // per DOF, against 1.5 kB for a whole 2D solve): at twice its DOF it is
    // refused from the symbolic analysis, before the factor's memory is
    // taken.
    let ball: Value = serde_json::from_str(include_str!("../../../proto/examples/solid_ball_on_flat.json")).unwrap();
    let dofs = solve(&ball).expect("the example solves").size.dofs;
    let tight = contact::scene::Limits {
        max_dofs: 2 * dofs,
        ..Default::default()
    };
    let e = solve_with(&ball, &tight).expect_err("its factor is too large");
    assert_eq!(serde_json::to_value(e.code).unwrap(), json!("too_large"), "{e:?}");
    assert_eq!(e.path, "/solid/body/mesh");
    assert!(e.message.contains("factor"), "{}", e.message);
    // Grid lines are bounded before they are made: an h_min at the least
    // double would ask for 1e323 of them, a side of 1e308 for as many cells.
    for (pointer, v) in [
        ("/solid/body/mesh/box/grading/h_min", json!(5e-324)),
        ("/solid/body/mesh/box/lengths/0", json!(1e308)),
    ] {
        let e = solve(&change(pointer, v)).expect_err(pointer);
        assert_eq!(
            serde_json::to_value(e.code).unwrap(),
            json!("too_large"),
            "{pointer}: {e:?}"
        );
        assert_eq!(e.path, "/solid/body/mesh/box");
    }
}

/// The error bar through the wire (`adapt::solid`; its effectivity against a
/// finer solve is contact-verify's `solid_error_bar`): a generated box's
/// reply carries the two-level estimate, a given mesh's says it has none, why
/// and how to get one; `settings.accuracy` refines a given mesh in rounds
/// (each estimated against the one before) and is refused for zone ends,
/// which a 3D patch has not.
#[test]
fn the_error_bar_is_two_level_on_a_box_and_by_refinement_on_a_given_mesh() {
    let mut ball = example("solid_ball_on_flat.json");
    ball["solid"]["body"]["mesh"]["box"]["element"] = json!("t4");
    ball["solid"]["body"]["mesh"]["box"]["grading"]["h_min"] = json!(0.4);
    let r = solved(&ball);
    let a = r.solid.as_ref().unwrap().accuracy.as_ref().expect("an estimate");
    assert_eq!(serde_json::to_value(a.basis).unwrap(), json!("two_level"));
    for (name, v) in [
        ("pressure_l2", a.pressure_l2),
        ("peak", a.peak),
        ("contact_area", a.contact_area),
    ] {
        let v = v.unwrap_or_else(|| panic!("{name} estimated"));
        // A relative error of a solve that converged: positive and below 1
        // at 0.4 a (0.40 for the pressure, `solid_effectivity`).
        assert!(v > 0.0 && v < 1.0, "{name} {v}");
    }
    // The load is the contact force's whole balance: the two levels agree to
    // round-off, so the resultant is exact, not estimated at the floor.
    assert!(a.resultant.unwrap() < 1e-12, "{:?}", a.resultant);
    assert!(r.timings.estimate > 0.0);
    ball["settings"] = json!({"estimate": false});
    assert!(solved(&ball).solid.unwrap().accuracy.is_none());

    let given = example("solid_block_on_flat_gmsh.json");
    let r = solved(&given);
    let a = r.solid.as_ref().unwrap().accuracy.as_ref().expect("the basis");
    assert_eq!(serde_json::to_value(a.basis).unwrap(), json!("none"));
    assert!(a.pressure_l2.is_none() && a.peak.is_none() && a.resultant.is_none());
    assert_eq!(
        note_kind(&r, "no error estimate on a given 3D mesh"),
        Some(contact::proto::NoteKind::EstimateLimited)
    );
    assert!(
        r.notes.iter().any(|n| n.contains("settings.accuracy")),
        "the note says how to get an estimate: {:?}",
        r.notes
    );
    let given_dofs = r.size.dofs;
    let mut refine = given.clone();
    refine["settings"] = json!({"accuracy": {"pressure_l2": 0.01}});
    let r = solved(&refine);
    let s = r.solid.as_ref().unwrap();
    let rounds = r.refinement.as_ref().expect("rounds");
    // The block's oedometric state is exact on T4 at every level: the first
    // refinement agrees with the given mesh to round-off, and meets the
    // target in the second round, the first that has an estimate.
    assert!(rounds.reached, "{rounds:?}");
    assert_eq!(rounds.rounds.len(), 2, "{rounds:?}");
    assert!(rounds.rounds[0].pressure_l2.is_none());
    let a = s.accuracy.as_ref().expect("an estimate");
    assert_eq!(serde_json::to_value(a.basis).unwrap(), json!("two_level"));
    assert!(a.pressure_l2.unwrap() < 1e-9, "{:?}", a.pressure_l2);
    // Every tetrahedron in eight: the free DOFs grow about eightfold on a
    // mesh this coarse (its many boundary nodes held by the rollers).
    assert!(r.size.dofs > 4 * given_dofs, "{} from {given_dofs}", r.size.dofs);
    ball["settings"] = json!({"accuracy": {"zone_edge": 0.1}});
    assert_eq!(
        solve(&ball).expect_err("no zone ends").path,
        "/settings/accuracy/zone_edge"
    );
}
