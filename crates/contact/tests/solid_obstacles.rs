//! Curved rigid obstacles of a 3D solid (sphere, cylinder, paraboloid, height field)
//! through the wire, against closed forms and against our own 2D answer:
//!
//! - a rigid sphere pressed into a block (the example
//!   `solid_sphere_into_block.json`, a quarter model, T10): Hertz's circle;
//! - a rigid cylinder pressed into a block between frictionless end walls:
//!   plane strain, so the section's pressure is our 2D plane-strain answer
//!   of the same section;
//! - a rigid paraboloid of principal radii R₁ ≠ R₂ pressed into a block:
//!   Hertz's ellipse (Johnson, Contact Mechanics §4.2);
//! - in each: the reply's resultant balances the load to 1e-9 (an equation
//!   the mixed LCP solves, to its round-off) and complementarity holds row
//!   by row (an open row carries no force; a pressed one has a gap below
//!   1e-9 of the approach, the refinement on the active set leaving 1e-12);
//! - refusals of malformed shapes at their pointers.

mod common;
use common::*;
use contact::proto::SolidResult;
use serde_json::{json, Value};

/// Row-by-row complementarity of a solid's answer: λ_i = 0 where the row
/// is open, its gap 0 where it is pressed (to 1e-9 of `approach`, the
/// obstacle's depth into the body).
fn assert_complementary(s: &SolidResult, approach: f64) {
    for q in &s.points {
        assert!(q.pressure >= 0.0, "tensile {q:?}");
        assert!(q.gap >= -1e-9 * approach, "penetrating {q:?}");
        if q.in_contact {
            assert!(q.gap.abs() <= 1e-9 * approach, "pressed but open {q:?}");
        } else {
            assert!(q.pressure == 0.0, "open but pressed {q:?}");
        }
    }
}

/// A least-squares fit of p² = c₀ + c₁ x² + c₂ y² over the points in
/// contact (Hertz's pressure, p = p₀ √(1 − x²/a² − y²/b²), makes p² such a
/// plane in (x², y²)): (p₀, a, b) = (√c₀, √(−c₀/c₁), √(−c₀/c₂)).
fn ellipse_fit(s: &SolidResult) -> (f64, f64, f64) {
    let rows: Vec<[f64; 4]> = s
        .points
        .iter()
        .filter(|q| q.in_contact)
        .map(|q| [1.0, q.at[0].powi(2), q.at[1].powi(2), q.pressure.powi(2)])
        .collect();
    let mut m = [[0.0; 4]; 3];
    for r in &rows {
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += r[i] * r[j];
            }
            m[i][3] += r[i] * r[3];
        }
    }
    // Cramer's rule on the 3 × 3 normal equations (well conditioned: the
    // points spread over the patch).
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let lhs: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| m[i][j]));
    let c: [f64; 3] = std::array::from_fn(|k| {
        det(std::array::from_fn(|i| {
            std::array::from_fn(|j| if j == k { m[i][3] } else { m[i][j] })
        })) / det(lhs)
    });
    (c[0].sqrt(), (-c[0] / c[1]).sqrt(), (-c[0] / c[2]).sqrt())
}

/// Hertz's sphere pressed into a block (the example): a = (3PR/4E*)^(1/3),
/// p₀ = 3P/(2πa²), E* = E/(1 − ν²). The block is 10a on a side, its
/// cells a/5 at the apex. The sphere's gap to the flat face is its exact
/// distance, r²/2R + O(r⁴/R³): at r = a that is 1e-4 of the paraboloid's,
/// so the answer is the flat-faced ball's (`solid.rs`, which measured
/// 1.006 a and 1.6 % on the peak) to that (measured here: 1.006 a, the peak
/// 1.3 % low): a within 3 % (the cell a/5
/// places the patch's edge, and the fit of p² over the 28 pressed points
/// averages it), p₀ within 5 % (the corner row's pressure is the
/// dual-weighted mean of p over its faces, which lowers a concave maximum
/// by O(h²/a²) = 1/25 at most; and the block's finite size, 10a, moves
/// Hertz's half-space answer by O(a/L)).
#[test]
fn a_sphere_pressed_into_a_block_matches_hertz() {
    let req = example("solid_sphere_into_block.json");
    let s_ = &req["solid"];
    let big_r = s_["obstacle"]["shape"]["sphere"]["radius"].as_f64().unwrap();
    let e = s_["body"]["material"]["youngs_modulus"].as_f64().unwrap();
    let nu = s_["body"]["material"]["poisson_ratio"].as_f64().unwrap();
    let lengths = &s_["body"]["mesh"]["box"]["lengths"];
    let face = lengths[0].as_f64().unwrap() * lengths[1].as_f64().unwrap();
    let quarter = s_["body"]["tractions"][0]["pressure"].as_f64().unwrap() * face;
    let load = 4.0 * quarter;
    let (a, p0) = contact_verify::reference::hertz_sphere(load, big_r, e / (1.0 - nu * nu));
    let r = solved(&req);
    let s = r.solid.as_ref().unwrap();
    let f = s.resultant.force;
    println!("resultant {f:?} against the quarter's load {quarter}");
    assert!(
        (f[2] + quarter).abs() < 1e-9 * quarter,
        "the sphere pushes down (−z) on the block by its load"
    );
    // The sideways components: each row's normal leans by r/R, and the
    // quarter's rows lean outward on both sides of both symmetry planes'
    // quarter, so they add up (the symmetry planes' rollers carry them).
    assert!(f[0].abs() < 0.05 * quarter && f[1].abs() < 0.05 * quarter);
    assert_complementary(s, a * a / big_r);
    assert_eq!(s.patches.len(), 1, "one patch");
    let (_, a_fit, b_fit) = ellipse_fit(s);
    let a_h = (a_fit * b_fit).sqrt();
    let peak = s.patches[0].peak_pressure;
    println!(
        "{} DOFs, {} points in contact: a_h / a = {:.4} (x {:.4}, y {:.4}), peak / p0 = {:.4} at {:?}",
        r.size.dofs,
        s.points.iter().filter(|q| q.in_contact).count(),
        a_h / a,
        a_fit / a,
        b_fit / a,
        peak / p0,
        s.patches[0].peak_at
    );
    assert!((a_h / a - 1.0).abs() < 0.03, "a_h / a = {}", a_h / a);
    assert!((peak / p0 - 1.0).abs() < 0.05, "p0_h / p0 = {}", peak / p0);
    assert_eq!(s.patches[0].peak_at, [0.0; 3], "the peak at the apex");
}

/// The section of the plane-strain scene: a block [0, 20] × [−20, 0] (x = 0
/// a symmetry plane, the bottom held) into whose top a rigid cylinder of
/// radius 8 is pressed by 0.12, E = 200, ν = 0.3; cells of `H_MIN` within 1
/// of the axis (Hertz's half-width, about 0.7, inside), growing by 1.5 up
/// to 2.
const H_MIN: f64 = 0.08;
const R_CYL: f64 = 8.0;
const DEPTH: f64 = 0.12;
const E_CYL: f64 = 200.0;

fn section_2d() -> Value {
    json!({
        "version": "1",
        "analysis": "plane_strain",
        "bodies": [{
            "name": "block",
            "material": {"youngs_modulus": E_CYL, "poisson_ratio": 0.3},
            "mesh": {"rectangle": {"corner": [0.0, -20.0], "width": 20.0, "height": 20.0, "size": 2.0,
                "element": "t6", "grading": {"focus": [0.0, 0.0], "h_min": H_MIN, "ratio": 1.5, "extent": 1.0}}},
            "supports": [{"edges": "left", "ux": 0.0}, {"edges": "bottom", "ux": 0.0, "uy": 0.0}]
        }],
        "obstacles": [{"name": "cylinder", "shape": {"circle": {"center": [0.0, R_CYL - DEPTH], "radius": R_CYL}}}],
        "contacts": [{"body": "block", "edges": "top", "obstacle": "cylinder"}]
    })
}

/// The same section extruded along z by two cells, between end walls that
/// hold u_z = 0 and nothing else (frictionless), under a cylinder along z.
fn extruded_3d() -> Value {
    let lz = 2.0 * H_MIN;
    json!({
        "version": "1",
        "analysis": "solid",
        "solid": {
            "body": {
                "material": {"youngs_modulus": E_CYL, "poisson_ratio": 0.3},
                "mesh": {"box": {"corner": [0.0, -20.0, 0.0], "lengths": [20.0, 20.0, lz], "size": 2.0,
                    "element": "t10",
                    "grading": {"focus": [0.0, 0.0, 0.5 * lz], "h_min": H_MIN, "ratio": 1.5, "extent": 1.0}}},
                "supports": [
                    {"faces": "x_min", "ux": 0.0},
                    {"faces": "y_min", "ux": 0.0, "uy": 0.0, "uz": 0.0},
                    {"faces": "z_min", "uz": 0.0}, {"faces": "z_max", "uz": 0.0}
                ]
            },
            "obstacle": {"shape": {"cylinder": {"point": [0.0, R_CYL - DEPTH, 0.0], "axis": [0.0, 0.0, 1.0],
                "radius": R_CYL}}},
            "contact": {"faces": "y_max"}
        }
    })
}

/// Plane strain recovered: with u_z = 0 on both end walls and nothing
/// varying along z, the block's 3D field is the section's plane-strain
/// field, so the mid-section's pressure is the 2D answer of the same
/// section (T6, the same grading) to the two discretizations' difference.
/// Compared: the force per unit length and the peak, integral and interior
/// quantities the two meshes resolve alike (measured 0.07 % and 0.04 %:
/// 1 % asked); the pressure profile point by point against the 2D answer
/// interpolated (measured 1.5 % of the peak, next to the patch's edge,
/// where p falls like a square root and the two meshes place the edge
/// within a cell of b/9 differently: 3 % asked); and the half-width b of
/// the fit p² = p₀²(1 − x²/b²) over each answer's points in contact (the
/// same estimator on both, so its own bias cancels, but which points are
/// pressed is quantized by the cell: measured 1.7 % at the mid-section and
/// −2.3 % at an end wall, whose rows see other faces of the same field;
/// 4 % asked). The 2D answer's own distance from Hertz's half-space is
/// printed, not asserted (the block is 29 b deep).
#[test]
fn a_cylinder_between_end_walls_is_plane_strain() {
    let two = solved(&section_2d());
    let three = solved(&extruded_3d());
    let s = three.solid.as_ref().unwrap();
    let lz = 2.0 * H_MIN;
    assert_complementary(s, DEPTH);
    // No load but the cylinder's depth: the supports' reactions balance
    // the contact, so the 2D pair's force is the measure of the load.
    let f2 = two.pairs[0].resultant.fy;
    let f3 = s.resultant.force[1] / lz;
    let mid: Vec<(f64, f64)> = s
        .points
        .iter()
        .filter(|q| (q.at[2] - 0.5 * lz).abs() < 1e-12)
        .map(|q| (q.at[0], q.pressure))
        .collect();
    let ends: Vec<(f64, f64)> = s
        .points
        .iter()
        .filter(|q| q.at[2].abs() < 1e-12)
        .map(|q| (q.at[0], q.pressure))
        .collect();
    let line = |pts: &[(f64, f64)]| -> (f64, f64) {
        let pressed: Vec<(f64, f64)> = pts
            .iter()
            .filter(|q| q.1 > 0.0)
            .map(|q| (q.0 * q.0, q.1 * q.1))
            .collect();
        (
            contact_verify::reference::edge_fit(&pressed),
            pts.iter().map(|q| q.1).fold(0.0, f64::max),
        )
    };
    let p2: Vec<(f64, f64)> = two.pairs[0].points.iter().map(|q| (q.x, q.pressure)).collect();
    let ((b2, peak2), (b3, peak3), (b_end, peak_end)) = (line(&p2), line(&mid), line(&ends));
    // The half model carries half the load.
    let (b_h, p0_h) = hertz(-2.0 * f2, R_CYL, E_CYL, 0.3);
    println!(
        "2D: force {f2:.5}, b {b2:.5}, peak {peak2:.5} (Hertz's half-space: b {b_h:.5}, p0 {p0_h:.5}); \
         3D per length: force {f3:.5}, mid-section b {b3:.5}, peak {peak3:.5}; end wall b {b_end:.5}, \
         peak {peak_end:.5}; {} DOFs, {} of {} mid-section points pressed",
        three.size.dofs,
        mid.iter().filter(|q| q.1 > 0.0).count(),
        mid.len()
    );
    // The profile: the 2D pressure interpolated linearly at the 3D
    // mid-section's points, against the 3D pressure there.
    let mut sorted = p2.clone();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let at2 = |x: f64| {
        let k = sorted.partition_point(|q| q.0 <= x).clamp(1, sorted.len() - 1);
        let (a, b) = (sorted[k - 1], sorted[k]);
        a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
    };
    let worst = mid
        .iter()
        .map(|q| ((q.1 - at2(q.0)).abs(), q.0))
        .fold((0.0, 0.0), |a, d| if d.0 > a.0 { d } else { a });
    println!(
        "largest pressure difference {:.4} of the peak at x = {:.4}",
        worst.0 / peak2,
        worst.1
    );
    assert!(f3 < 0.0 && f2 < 0.0, "the cylinder pushes down");
    assert!((f3 / f2 - 1.0).abs() < 0.01, "force per length {f3} against {f2}");
    assert!((b3 / b2 - 1.0).abs() < 0.04, "half-width {b3} against {b2}");
    assert!((peak3 / peak2 - 1.0).abs() < 0.01, "peak {peak3} against {peak2}");
    assert!(
        worst.0 < 0.03 * peak2,
        "profiles differ by {} at x = {}",
        worst.0,
        worst.1
    );
}

/// Hertz's ellipse: a rigid paraboloid of principal radii R₁ = 80 (along x)
/// and R₂ = 40 (along y) pressed into a steel block by P, a quarter model
/// (the principal sections are the symmetry planes), T10, cells h = 0.15
/// within 1.35 of the apex. Johnson's §4.2 (`reference::hertz_ellipse`, K
/// and E by the AGM) gives e = 0.776, a = 1.183, b = 0.746 for P = 4600 N.
/// Read from the answer as the sphere's is: the semi-axes from the fit of p²
/// over the points in contact, the peak at the apex. Asked within 3 % (the
/// issue's bound): b/a, whose errors in a and b of the same sign (the
/// block's finite size, 8.5 a) cancel, and p₀, lowered by the corner row's
/// dual-weighted mean by O(h²/b²). The narrow axis sets the cell: at
/// h = 0.2 (b/h = 3.7) b came out 4.4 % wide and b/a 3.2 % off; at
/// h = 0.15 (b/h = 5, the sphere's a/h) b/a is 0.7 % off and p₀ 0.9 % low.
#[test]
fn a_paraboloid_of_two_radii_matches_hertz_ellipse() {
    let (e, nu, load, radii) = (210000.0, 0.3, 4600.0, [80.0, 40.0]);
    let (side, depth) = (10.0, 10.0);
    let req = json!({
        "version": "1",
        "analysis": "solid",
        "solid": {
            "body": {
                "material": {"youngs_modulus": e, "poisson_ratio": nu},
                "mesh": {"box": {"corner": [0.0, 0.0, -depth], "lengths": [side, side, depth], "size": 5.0,
                    "element": "t10",
                    "grading": {"focus": [0.0, 0.0, 0.0], "h_min": 0.15, "ratio": 2.0, "extent": 1.35}}},
                "supports": [{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}],
                "tractions": [{"faces": "z_min", "pressure": load / 4.0 / (side * side)}]
            },
            "obstacle": {"shape": {"paraboloid": {"apex": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, -1.0],
                "axis": [1.0, 0.0, 0.0], "radii": radii}}},
            "contact": {"faces": "z_max"}
        }
    });
    let h = contact_verify::reference::hertz_ellipse(load, radii, e / (1.0 - nu * nu));
    let r = solved(&req);
    let s = r.solid.as_ref().unwrap();
    let quarter = load / 4.0;
    assert!(
        (s.resultant.force[2] + quarter).abs() < 1e-9 * quarter,
        "{:?}",
        s.resultant
    );
    assert_complementary(s, h.a * h.b / radii[0].min(radii[1]));
    assert_eq!(s.patches.len(), 1, "one patch");
    let (_, a_fit, b_fit) = ellipse_fit(s);
    let peak = s.patches[0].peak_pressure;
    println!(
        "{} DOFs, {} points in contact: Hertz e {:.4}, a {:.4}, b {:.4}, p0 {:.2}; a_h / a = {:.4}, b_h / b = {:.4}, \
         (b/a)_h / (b/a) = {:.4}, peak / p0 = {:.4}",
        r.size.dofs,
        s.points.iter().filter(|q| q.in_contact).count(),
        h.e,
        h.a,
        h.b,
        h.p0,
        a_fit / h.a,
        b_fit / h.b,
        (b_fit / a_fit) / (h.b / h.a),
        peak / h.p0
    );
    assert!(((b_fit / a_fit) / (h.b / h.a) - 1.0).abs() < 0.03, "b/a off");
    assert!((peak / h.p0 - 1.0).abs() < 0.03, "p0 off");
    assert_eq!(s.patches[0].peak_at, [0.0; 3], "the peak at the apex");
}

/// Malformed obstacles are refused at the field at fault, each pointer
/// resolving in the request: a radius not positive, a zero axis or normal,
/// a paraboloid's axis along its normal, a field the shape does not have,
/// an initial gap profile (a flat face standing for a curved one against a
/// plane) with a curved obstacle, and a contact candidate at a sphere's
/// centre, where the obstacle has no normal.
#[test]
fn malformed_obstacles_are_refused_at_their_fields() {
    let good = example("solid_sphere_into_block.json");
    let with = |shape: Value| {
        let mut r = good.clone();
        r["solid"]["obstacle"]["shape"] = shape;
        r
    };
    let mut gap = good.clone();
    gap["solid"]["contact"]["initial_gap"] = json!({"paraboloid": {"apex": [0.0, 0.0, 0.0], "radius": 5.0}});
    let cases = [
        (
            with(json!({"sphere": {"centre": [0.0, 0.0, 5.0], "radius": 0.0}})),
            "invalid_geometry",
            "/solid/obstacle/shape/sphere/radius",
        ),
        (
            with(json!({"cylinder": {"point": [0.0, 0.0, 5.0], "axis": [0.0, 0.0, 0.0], "radius": 5.0}})),
            "invalid_geometry",
            "/solid/obstacle/shape/cylinder/axis",
        ),
        (
            with(
                json!({"paraboloid": {"apex": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, -1.0], "axis": [0.0, 0.0, 2.0],
                "radii": [5.0, 4.0]}}),
            ),
            "invalid_geometry",
            "/solid/obstacle/shape/paraboloid/axis",
        ),
        (
            with(
                json!({"paraboloid": {"apex": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, -1.0], "axis": [1.0, 0.0, 0.0],
                "radii": [5.0, 0.0]}}),
            ),
            "invalid_geometry",
            "/solid/obstacle/shape/paraboloid/radii/1",
        ),
        (gap, "invalid_request", "/solid/contact/initial_gap"),
        // The block's top corner (0, 0, 0) is the sphere's centre.
        (
            with(json!({"sphere": {"centre": [0.0, 0.0, 0.0], "radius": 1.0}})),
            "invalid_geometry",
            "/solid/obstacle",
        ),
    ];
    for (req, code, path) in cases {
        let e = solve(&req).expect_err(path);
        println!("{path}: {}", e.message);
        assert_eq!(serde_json::to_value(e.code).unwrap(), json!(code), "{path}: {e:?}");
        assert_eq!(e.path, path, "{e:?}");
        assert!(req.pointer(&e.path).is_some(), "{} resolves in the request", e.path);
    }
    let unknown = with(json!({"sphere": {"centre": [0.0, 0.0, 5.0], "radius": 5.0, "axis": [0.0, 0.0, 1.0]}}));
    let e = solve(&unknown).expect_err("an unknown field");
    println!("unknown field: {}", e.message);
    assert!(e.message.contains("axis"), "{e:?}");
}

/// The curved obstacles are scaled with the scene: a coarse T4 block (nodal
/// rows, each along its own node's normal) pressed on a cylinder lying
/// across it and then on a sphere, in mm, N, MPa and in m, N, Pa (lengths
/// ×1e-3, stresses ×1e6, forces as they are, moments ×1e-3). The door
/// scales both to the same nondimensional scene up to the scaling's
/// round-off, so every number agrees to 1e-9 of its key's largest
/// magnitude, as the plane's does (`solid.rs`).
#[test]
fn curved_obstacles_do_not_depend_on_the_units() {
    let mm = |shape: Value| {
        json!({
            "version": "1",
            "analysis": "solid",
            "solid": {
                "body": {
                    "material": {"youngs_modulus": 210000.0, "poisson_ratio": 0.3},
                    "mesh": {"box": {"corner": [0.0, 0.0, -8.0], "lengths": [10.0, 10.0, 8.0], "size": 5.0,
                        "grading": {"focus": [0.0, 0.0, 0.0], "h_min": 0.4, "ratio": 2.0, "extent": 1.2}}},
                    "supports": [{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}],
                    "tractions": [{"faces": "z_min", "pressure": 15.0}]
                },
                "obstacle": {"shape": shape},
                "contact": {"faces": "z_max"}
            }
        })
    };
    let metres = |req: &Value| {
        let mut m = req.clone();
        let b = &mut m["solid"]["body"];
        b["material"]["youngs_modulus"] = json!(210000.0e6);
        b["mesh"]["box"] = json!({"corner": [0.0, 0.0, -0.008], "lengths": [0.01, 0.01, 0.008], "size": 0.005,
            "grading": {"focus": [0.0, 0.0, 0.0], "h_min": 0.0004, "ratio": 2.0, "extent": 0.0012}});
        b["tractions"][0]["pressure"] = json!(15.0e6);
        m
    };
    let shapes = [
        (
            json!({"cylinder": {"point": [0.0, 0.0, 40.001], "axis": [1.0, 0.0, 0.0], "radius": 40.0}}),
            json!({"cylinder": {"point": [0.0, 0.0, 0.040001], "axis": [1.0, 0.0, 0.0], "radius": 0.04}}),
        ),
        (
            json!({"sphere": {"centre": [0.0, 0.0, 50.0], "radius": 50.0}}),
            json!({"sphere": {"centre": [0.0, 0.0, 0.05], "radius": 0.05}}),
        ),
    ];
    for (in_mm, in_m) in shapes {
        let a_req = mm(in_mm);
        let mut b_req = metres(&a_req);
        b_req["solid"]["obstacle"]["shape"] = in_m;
        let (a, b) = (solved(&a_req), solved(&b_req));
        let (sa, sb) = (a.solid.unwrap(), b.solid.unwrap());
        let active = sa.points.iter().filter(|q| q.in_contact).count();
        println!("{active} of {} points in contact", sa.points.len());
        assert!(active > 3 && active < sa.points.len(), "a patch inside the face set");
        assert_complementary(&sa, 1e-3);
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
        assert_same_in_units(&sa.resultant.force, &sb.resultant.force, 1.0, "force");
        assert_same_in_units(&sa.resultant.moment, &sb.resultant.moment, 1e-3, "moment");
        let load = 15.0 * 100.0;
        assert!((sa.resultant.force[2] + load).abs() < 1e-9 * load, "{:?}", sa.resultant);
    }
}

/// A direction is a direction at any magnitude: a cylinder's axis and a
/// plane's normal given as 1e200 or 1e-170 times a unit vector (whose norms
/// overflow or underflow when squared) give the answer of the unit vector to
/// the last bit, the door dividing each by its largest component first.
#[test]
fn directions_of_any_magnitude_are_the_same_direction() {
    let base = example("solid_sphere_into_block.json");
    let with = |shape: Value| {
        let mut r = base.clone();
        r["solid"]["obstacle"]["shape"] = shape;
        solved(&r).solid.unwrap()
    };
    for s in [1e200, 1e-170] {
        let cyl =
            |k: f64| with(json!({"cylinder": {"point": [0.0, 0.0, 50.0], "axis": [k, 0.0, 0.0], "radius": 50.0}}));
        let plane = |k: f64| with(json!({"plane": {"point": [0.0, 0.0, 0.001], "normal": [0.0, 0.0, -k]}}));
        for (a, b) in [(cyl(1.0), cyl(s)), (plane(1.0), plane(s))] {
            assert_eq!(a.resultant.force, b.resultant.force, "axis or normal scaled by {s}");
            let p = |r: &SolidResult| r.points.iter().map(|q| q.pressure).collect::<Vec<_>>();
            assert_eq!(p(&a), p(&b), "axis or normal scaled by {s}");
        }
    }
}

/// The elliptical scene's paraboloid (R₁ = 80 along x, R₂ = 40 along y,
/// normal −z at the origin) pressed into a quarter block, as a table of
/// heights: a 21 × 21 grid of spacing 0.5 over the whole contact face, its
/// origin at (0, 10, 0) so that its rows run along x and across them along
/// normal × axis = −y. The interpolant reproduces quadratics exactly, so
/// the table is the paraboloid to round-off and the two answers on the same
/// T4 mesh agree to 1e-9 of the peak (the LCP's own round-off is ~1e-14).
fn paraboloid_block(shape: Value) -> Value {
    json!({
        "version": "1",
        "analysis": "solid",
        "solid": {
            "body": {
                "material": {"youngs_modulus": 210000.0, "poisson_ratio": 0.3},
                "mesh": {"box": {"corner": [0.0, 0.0, -10.0], "lengths": [10.0, 10.0, 10.0], "size": 5.0,
                    "grading": {"focus": [0.0, 0.0, 0.0], "h_min": 0.25, "ratio": 2.0, "extent": 2.0}}},
                "supports": [{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}],
                "tractions": [{"faces": "z_min", "pressure": 1150.0 / 100.0}]
            },
            "obstacle": {"shape": shape},
            "contact": {"faces": "z_max"}
        }
    })
}

fn paraboloid_table(rows: usize, columns: usize, d: f64) -> Vec<Vec<f64>> {
    (0..rows)
        .map(|j| {
            (0..columns)
                .map(|i| {
                    let (xi, eta) = (i as f64 * d, j as f64 * d - 10.0);
                    -(xi * xi / 160.0 + eta * eta / 80.0)
                })
                .collect()
        })
        .collect()
}

#[test]
fn a_height_field_sampled_from_a_paraboloid_is_that_paraboloid() {
    let par = solved(&paraboloid_block(json!({"paraboloid": {"apex": [0.0, 0.0, 0.0],
        "normal": [0.0, 0.0, -1.0], "axis": [1.0, 0.0, 0.0], "radii": [80.0, 40.0]}})));
    let table = solved(&paraboloid_block(json!({"height_field": {"origin": [0.0, 10.0, 0.0],
        "normal": [0.0, 0.0, -1.0], "axis": [1.0, 0.0, 0.0], "spacing": [0.5, 0.5],
        "heights": paraboloid_table(21, 21, 0.5)}})));
    let (a, b) = (par.solid.as_ref().unwrap(), table.solid.as_ref().unwrap());
    let peak = a.patches[0].peak_pressure;
    let pressed = a.points.iter().filter(|q| q.in_contact).count();
    println!("{} points, {pressed} in contact, peak {peak:.1}", a.points.len());
    assert!(pressed >= 10, "a patch of several points");
    assert_eq!(a.points.len(), b.points.len());
    for (p, q) in a.points.iter().zip(&b.points) {
        assert_eq!(p.in_contact, q.in_contact, "at {:?}", p.at);
        assert!((p.pressure - q.pressure).abs() <= 1e-9 * peak, "at {:?}", p.at);
    }
    assert_complementary(b, 0.05);
}

/// A height field is refused at the field at fault: rows of unequal
/// length, a grid that does not reach under the whole contact face (a
/// candidate off the grid has no height), a zero spacing, a single row. A
/// height that is no number is refused by the door's parser (JSON carries
/// no NaN or infinity).
#[test]
fn malformed_height_fields_are_refused_at_their_fields() {
    let field = |heights: Value, spacing: Value| {
        paraboloid_block(
            json!({"height_field": {"origin": [0.0, 10.0, 0.0], "normal": [0.0, 0.0, -1.0],
            "axis": [1.0, 0.0, 0.0], "spacing": spacing, "heights": heights}}),
        )
    };
    let mut ragged = paraboloid_table(21, 21, 0.5);
    ragged[3].pop();
    let mut nan = json!(paraboloid_table(21, 21, 0.5));
    nan[4][7] = json!("NaN");
    let cases = [
        (
            field(json!(ragged), json!([0.5, 0.5])),
            "/solid/obstacle/shape/height_field/heights/3",
        ),
        (
            field(json!(paraboloid_table(11, 11, 0.5)), json!([0.5, 0.5])),
            "/solid/obstacle",
        ),
        (
            field(json!(paraboloid_table(21, 21, 0.5)), json!([0.5, 0.0])),
            "/solid/obstacle/shape/height_field/spacing/1",
        ),
        (
            field(json!([[0.0, 0.0]]), json!([0.5, 0.5])),
            "/solid/obstacle/shape/height_field/heights",
        ),
    ];
    for (req, path) in cases {
        let e = solve(&req).expect_err(path);
        println!("{path}: {}", e.message);
        assert_eq!(e.path, path, "{e:?}");
        assert!(req.pointer(&e.path).is_some(), "{} resolves in the request", e.path);
    }
    // A string where a number belongs is refused by the door's parser.
    assert!(solve(&field(nan, json!([0.5, 0.5]))).is_err());
}
