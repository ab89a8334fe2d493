//! Bodies of revolution on their r–z section against the 3D closed forms:
//! Hertz (sphere on a flat), Boussinesq (flat cylindrical punch), a Winkler
//! foundation under a uniform load, the locking-free T6 at ν = 0.499, and the
//! refusals of what a body of revolution cannot carry.

mod common;
use common::*;
use contact::proto::{Analysis, BodySpec, Discretization, ErrorCode, FoundationModel, OutputKind, SolveReply};
use contact_verify::build::*;
use serde_json::{json, Value};
use std::f64::consts::PI;

/// 3D Hertz for a sphere of radius r on a flat: (a, p0) for the total load p.
fn hertz3d(p: f64, r: f64, e: f64, nu: f64) -> (f64, f64) {
    let e_star = e / (1.0 - nu * nu);
    let a = (3.0 * p * r / (4.0 * e_star)).cbrt();
    (a, 3.0 * p / (2.0 * PI * a * a))
}

/// (half-width error, peak error, area-weighted L2 error) against 3D Hertz
/// with the reply's own total load.
fn hertz_errors(r: &SolveReply, radius: f64, e: f64, nu: f64) -> (f64, f64, f64) {
    let (a, p0) = hertz3d(r.resultant.fy.abs(), radius, e, nu);
    let pair = &r.pairs[0];
    let (mut num, mut den) = (0.0, 0.0);
    for q in &pair.points {
        let exact = p0 * (1.0 - (q.x / a).powi(2)).max(0.0).sqrt();
        num += q.weight * (q.pressure - exact).powi(2);
        den += q.weight * exact * exact;
    }
    assert_eq!(pair.zones.len(), 1, "one contact zone: {:?}", pair.zones);
    // The zone of a section runs from the axis: [0, a].
    (
        pair.zones[0][1] / a - 1.0,
        peak_pressure(r) / p0 - 1.0,
        (num / den).sqrt(),
    )
}

/// A solid cylinder of revolution (r ≤ radius, 0 ≤ z ≤ height), elements
/// 0.05 apart.
fn cylinder(radius: f64, height: f64, youngs_modulus: f64, poisson_ratio: f64) -> BodySpec {
    let mesh = rectangle([0.0, 0.0], radius, height, 0.05, "t3");
    body("cylinder", youngs_modulus, poisson_ratio, mesh)
}

/// `body` standing on the rigid flat z = 0, held by it alone.
fn on_floor(body: BodySpec) -> Value {
    request(vec![body], vec![pair("cylinder", "bottom").obstacle("floor")])
        .with_obstacle(obstacle("floor", line([0.0, 0.0], [0.0, 1.0])))
        .with_analysis(Analysis::Axisymmetric)
        .to_value()
}

/// `body` resting on a foundation at z = 0 over r ∈ [0, x_max].
fn on_foundation(body: BodySpec, model: FoundationModel, x_max: f64) -> Value {
    request(vec![body], vec![pair("cylinder", "bottom").foundation("soil")])
        .with_foundation(foundation("soil", model, 0.0, x_max, 0.0))
        .with_analysis(Analysis::Axisymmetric)
        .to_value()
}

fn ball(element: &str, h_min: f64) -> Value {
    let mut req = example("axisymmetric_ball_on_flat.json");
    let mesh = &mut req["bodies"][0]["mesh"]["quarter_disk"];
    mesh["element"] = json!(element);
    mesh["grading"]["h_min"] = json!(h_min);
    req
}

/// The ball example (T3, nodes 0.015 = 2.3 % of a apart at the contact):
/// the zone ends on a node (within 2.3 % of a), the peak within 1 % and the
/// pressure within 1 % in L2; radial forces and moments cancel; the
/// certificate holds.
#[test]
fn ball_on_flat_matches_hertz() {
    let r = solved(&example("axisymmetric_ball_on_flat.json"));
    let (ea, ep, el2) = hertz_errors(&r, 10.0, 200.0, 0.3);
    assert!(
        ea.abs() < 0.023 && ep.abs() < 0.01 && el2 < 0.01,
        "a {ea:+.3e} p0 {ep:+.3e} L2 {el2:.3e}"
    );
    assert!(r.resultant.fy > 0.0, "the floor pushes the ball up");
    assert_eq!((r.resultant.fx, r.resultant.m), (0.0, 0.0));
    assert_kkt(&r, 1e-8);
}

/// T6 (dual mortar rows weighted by 2πr): the errors fall under refinement
/// (measured L2 3.9 % → 0.69 % → 0.25 % at element sizes 0.12, 0.06, 0.015,
/// 9 % to 2.3 % of a) and the peak is within 1 % on the middle mesh.
#[test]
fn ball_on_flat_t6_converges() {
    let errors: Vec<(f64, f64, f64)> = [0.12, 0.06, 0.015]
        .iter()
        .map(|&h| hertz_errors(&solved(&ball("t6", h)), 10.0, 200.0, 0.3))
        .collect();
    assert!(
        errors[0].2 > errors[1].2 && errors[1].2 > errors[2].2,
        "L2 falls: {errors:?}"
    );
    assert!(errors[1].1.abs() < 0.01 && errors[2].2 < 0.004, "{errors:?}");
}

/// Boussinesq's flat cylindrical punch: p(r) = P / (2πa √(a² − r²)) within
/// 1.5 % up to r = 0.75a (the singular edge is resolved by the mesh only
/// further out), equilibrium exact, and the settlement within 2 % of the
/// half-space's P (1 − ν²) / (2aE) (the cylinder of radius and height 80a is
/// stiffer by about a/L: measured −4.6 %, −1.7 %, −1.0 % at 20a, 80a, 320a).
#[test]
fn flat_punch_matches_boussinesq() {
    let r = solved(&example("axisymmetric_flat_punch.json"));
    let (p, a, e, nu) = (100.0, 1.0, 200.0, 0.3);
    assert!((r.resultant.fy + p).abs() < 1e-10 * p, "fy {}", r.resultant.fy);
    for q in &r.pairs[0].points {
        if q.x <= 0.75 * a {
            let exact = p / (2.0 * PI * a * (a * a - q.x * q.x).sqrt());
            assert!(
                (q.pressure / exact - 1.0).abs() < 0.015,
                "r = {}: {} vs {exact}",
                q.x,
                q.pressure
            );
        }
    }
    let settlement = -r.punches[0].alpha2;
    let exact = p * (1.0 - nu * nu) / (2.0 * a * e);
    assert!((settlement / exact - 1.0).abs() < 0.02, "{settlement} vs {exact}");
    assert_kkt(&r, 1e-8);
}

/// An axial point load on the axis (a ring of radius 0: a point force) on
/// top of a cylinder standing on a rigid flat: the floor carries it exactly.
#[test]
fn an_axial_point_load_on_the_axis_is_a_point_force() {
    let post = cylinder(1.0, 2.0, 100.0, 0.25).point_load("top", [0.0, 2.0], [0.0, -3.0]);
    let req = on_floor(post);
    let r = solved(&req);
    assert!((r.resultant.fy / 3.0 - 1.0).abs() < 1e-9, "{}", r.resultant.fy);
    // Two diameters below the load the pressure has spread: the highest is at
    // the axis, all of the base bears.
    let pts = &r.pairs[0].points;
    assert!(pts.iter().all(|p| p.pressure > 0.0));
    assert!(pts[0].pressure >= pts.iter().map(|p| p.pressure).fold(0.0, f64::max) - 1e-12);
    assert_kkt(&r, 1e-8);
}

/// Two elastic balls (R1 = 8, E1 = 200, ν1 = 0.3 on R2 = 12, E2 = 100,
/// ν2 = 0.25; dual mortar rows on non-matching meshes) against 3D Hertz with
/// 1/R = 1/R1 + 1/R2 and 1/E* = Σ (1 − ν²)/E: measured peak −0.24 %, L2
/// 0.65 % at 44k DOF.
#[test]
fn two_balls_match_hertz() {
    let mut req = example("two_bodies_cylinders.json");
    req["analysis"] = json!("axisymmetric");
    for (b, uy) in [(0, -0.04), (1, 0.0)] {
        let body = &mut req["bodies"][b];
        let disk = body["mesh"]["half_disk"].take();
        body["mesh"] = json!({ "quarter_disk": disk });
        body["supports"] = json!([{ "edges": "flat", "uy": uy }]);
    }
    let r = solved(&req);
    let radius = 1.0 / (1.0 / 8.0 + 1.0 / 12.0);
    let e_star = 1.0 / ((1.0 - 0.09) / 200.0 + (1.0 - 0.0625) / 100.0);
    // With ν = 0 the effective modulus passed is E* itself.
    let (_, ep, el2) = hertz_errors(&r, radius, e_star, 0.0);
    assert!(ep.abs() < 0.01 && el2 < 0.01, "p0 {ep:+.3e} L2 {el2:.3e}");
    assert_kkt(&r, 1e-8);
}

/// Press fit: a ring (inner radius 0.999, outer c = 2) on a solid shaft
/// (radius b = 1), both of height 1 on axial rollers, E = 200, ν = 0.3: the
/// radial interference δ = 0.001 is a negative initial gap. With free ends and
/// a frictionless interface the exact state is plane stress (σ_z = 0, each
/// body stretching axially on its own), so Lamé's p = E δ (c² − b²) / (2 b c²)
/// = 0.075 holds over the whole height: the mean within 0.5 % (δ/b = 0.1 % is
/// the ambiguity of b), every row within 1 % away from the two end rows
/// (measured 1.7 % at the corners).
#[test]
fn press_fit_matches_lame() {
    let ring = |name: &str, corner: f64, width: f64| {
        body(name, 200.0, 0.3, rectangle([corner, 0.0], width, 1.0, 0.05, "t3")).support("bottom", None, Some(0.0))
    };
    let bodies = vec![ring("shaft", 0.0, 1.0), ring("ring", 0.999, 1.001)];
    let contact = pair("ring", "left").against("shaft", "right", Discretization::default());
    let req = request(bodies, vec![contact]).with_analysis(Analysis::Axisymmetric);
    let r = solved(&req.to_value());
    let lame = 200.0 * 0.001 * (4.0 - 1.0) / (2.0 * 1.0 * 4.0);
    let pts = &r.pairs[0].points;
    let area: f64 = pts.iter().map(|p| p.weight).sum();
    let mean = pts.iter().map(|p| p.pressure * p.weight).sum::<f64>() / area;
    assert!((mean / lame - 1.0).abs() < 0.005, "mean {mean} vs {lame}");
    for p in &pts[1..pts.len() - 1] {
        assert!((p.pressure / lame - 1.0).abs() < 0.01, "z = {}: {}", p.y, p.pressure);
    }
    assert!(
        r.resultant.fy.abs() < 1e-9 * mean * area,
        "no axial force: {:?}",
        r.resultant
    );
    assert_kkt(&r, 1e-8);
    // The interface is vertical: the whole of the ring's bore touches, its
    // zone read along the bore (which runs down from the ring's top corner)
    // over its full height; its x-interval is only the bore's radius.
    let [z] = r.pairs[0].zones_along[..] else {
        panic!("one zone along the bore: {:?}", r.pairs[0].zones_along)
    };
    assert!(z.s_start == 0.0 && (z.s_end - 1.0).abs() < 1e-12, "{z:?}");
    assert_eq!((z.start, z.end), ([0.999, 1.0], [0.999, 0.0]), "{z:?}");
    assert_eq!(r.pairs[0].zones, vec![[0.999, 0.999]]);
    // In the shaft σ_rr = σ_θθ = −p (uniform compression): the reply's hoop
    // stress beside `stress` says so, within 2 % away from the ends.
    let with_stress = req.with_outputs(&[OutputKind::Stress, OutputKind::Mesh]);
    let r = solved(&with_stress.to_value());
    let shaft = &r.bodies.as_ref().expect("bodies")[0];
    let (stress, hoop) = (
        shaft.stress.as_ref().unwrap(),
        shaft.stress_hoop.as_ref().expect("hoop stress"),
    );
    let (nodes, elements) = (shaft.nodes.as_ref().unwrap(), shaft.elements.as_ref().unwrap());
    for (e, conn) in elements.iter().enumerate() {
        let z = conn.iter().map(|&n| nodes[n][1]).sum::<f64>() / conn.len() as f64;
        if (0.25..0.75).contains(&z) {
            assert!((hoop[e] / -lame - 1.0).abs() < 0.02, "σθθ {} at z {z}", hoop[e]);
            assert!(
                (stress[e][0] / -lame - 1.0).abs() < 0.02,
                "σrr {} at z {z}",
                stress[e][0]
            );
        }
    }
}

/// A uniform pressure q on a disk of radius R resting on a Winkler
/// foundation k: the foundation carries q π R² (the ring areas of the rows
/// add up to the disk's area), uniformly.
#[test]
fn winkler_foundation_carries_the_load_of_revolution() {
    let (q, k, radius) = (1.0, 10.0, 2.0);
    let disk = cylinder(radius, 0.5, 1e4, 0.3).pressure("top", q);
    let req = on_foundation(disk, FoundationModel::Winkler { stiffness: k }, 4.0);
    let r = solved(&req);
    let total = q * PI * radius * radius;
    assert!(
        (r.resultant.fy / total - 1.0).abs() < 1e-9,
        "{} vs {total}",
        r.resultant.fy
    );
    // Exact: uniform compression σ_zz = −q through the disk, a linear
    // displacement field the elements hold exactly, and uniform spring
    // pressure q under it (measured to 9e-16).
    for p in &r.pairs[0].points {
        assert!((p.pressure / q - 1.0).abs() < 1e-9, "r = {}: {}", p.x, p.pressure);
    }
    assert_kkt(&r, 1e-8);
}

/// A solid cylinder (radius 1, height 2) standing on a rigid flat under its
/// own weight (body force 1 per volume), held by contact alone along the
/// axis: the floor carries π R² H exactly, over the whole base.
#[test]
fn self_weight_of_a_cylinder_rests_on_the_floor() {
    let post = cylinder(1.0, 2.0, 100.0, 0.25).body_force([0.0, -1.0]);
    let req = on_floor(post);
    let r = solved(&req);
    assert!((r.resultant.fy / (2.0 * PI) - 1.0).abs() < 1e-9, "{}", r.resultant.fy);
    // The whole base bears, and the ring areas of the rows tile the base: the
    // area-weighted mean pressure is ρ g H. (Not uniform: the base of a free
    // cylinder would bulge by ν ρ g r² / 2E, which the flat flattens.)
    let pts = &r.pairs[0].points;
    assert!(pts.iter().all(|p| p.pressure > 0.0));
    let area: f64 = pts.iter().map(|p| p.weight).sum();
    assert!((area / PI - 1.0).abs() < 1e-12, "{area}");
    let mean = pts.iter().map(|p| p.pressure * p.weight).sum::<f64>() / area;
    assert!((mean / 2.0 - 1.0).abs() < 1e-9, "{mean}");
    assert_kkt(&r, 1e-8);
}

/// K_ν(x) = ∫₀^∞ exp(−x cosh t) cosh(νt) dt (trapezoid to t = 20: the
/// integrand has fallen below 1e-300 there for x ≥ 0.1).
fn bessel_k(nu: f64, x: f64) -> f64 {
    let (n, h) = (20_000, 20.0 / 20_000.0);
    (0..=n)
        .map(|i| {
            let t = i as f64 * h;
            let w = if i == 0 || i == n { 0.5 } else { 1.0 };
            w * (-x * t.cosh()).exp() * (nu * t).cosh()
        })
        .sum::<f64>()
        * h
}

/// A nearly rigid disk (radius R = 2, E = 1e6) under a uniform pressure q on a
/// Pasternak layer (k = 10, μ = 10, ℓ = √(μ/k) = 1): outside the disk
/// w = w0 K0(r/ℓ)/K0(R/ℓ), and the load splits between the springs under the
/// disk and the shear ring at its rim: q π R² = k w0 π R² + 2π R μ w0 K1/(ℓ K0).
/// Measured: w0 +0.17 %, the decay within 0.33 % out to 4ℓ past the rim.
#[test]
fn pasternak_layer_of_revolution_matches_the_bessel_solution() {
    let (q, k, mu, radius): (f64, f64, f64, f64) = (1.0, 10.0, 10.0, 2.0);
    let ell = (mu / k).sqrt();
    let (k0, k1) = (bessel_k(0.0, radius / ell), bessel_k(1.0, radius / ell));
    let w0 = q * PI * radius * radius / (k * PI * radius * radius + 2.0 * PI * radius * mu * k1 / (ell * k0));
    let disk = cylinder(radius, 0.5, 1e6, 0.3).pressure("top", q);
    let req = on_foundation(
        disk,
        FoundationModel::Pasternak {
            stiffness: k,
            shear: mu,
        },
        12.0,
    );
    let r = solved(&req);
    assert!((r.resultant.fy / (q * PI * radius * radius) - 1.0).abs() < 1e-9);
    let f = &r.foundations[0];
    assert!((f.w[0] / w0 - 1.0).abs() < 0.005, "w0 {} vs {w0}", f.w[0]);
    for (x, w) in f.x.iter().zip(&f.w) {
        if *x > radius + 0.2 && *x < radius + 4.0 * ell {
            let exact = w0 * bessel_k(0.0, x / ell) / k0;
            assert!((w / exact - 1.0).abs() < 0.01, "r = {x}: {w} vs {exact}");
        }
    }
    assert_kkt(&r, 1e-8);
}

/// Every constraint method, condensed or on the full system, solves the
/// ball. The exact ones solve the same discrete problem: every pressure
/// within the solve's tolerance (1e-8) of the peak (measured ≤ 8e-14). The
/// regularized ones (penalty springs of compliance ζ, log barrier of weight
/// ζ) converge linearly in ζ: measured 99× to 100× less error per 100× less
/// ζ; at least 20× is asked, as of the plane-strain ones.
#[test]
fn every_method_solves_the_ball() {
    let exact = solved(&ball("t3", 0.06));
    let peak = peak_pressure(&exact);
    let with = |method: &str, formulation: &str, zeta: Option<f64>| {
        let mut req = ball("t3", 0.06);
        req["method"] = json!(method);
        req["settings"] = json!({ "formulation": formulation });
        if let Some(z) = zeta {
            let key = if method == "barrier" { "barrier" } else { "penalty" };
            req["settings"][key] = json!(z);
        }
        max_pressure_diff(&solved(&req), &exact) / peak
    };
    for (method, formulation, zeta) in [
        ("interior_point", "condensed", None),
        ("augmented_lagrangian", "condensed", Some(1e-5)),
        ("active_set", "full", None),
        ("interior_point", "full", None),
    ] {
        let err = with(method, formulation, zeta);
        assert!(
            err < 1e-8,
            "{method} ({formulation}): {err:.3e} of the peak from the active set"
        );
    }
    for method in ["penalty", "barrier"] {
        let (coarse, fine) = (
            with(method, "condensed", Some(1e-6)),
            with(method, "condensed", Some(1e-8)),
        );
        assert!(
            fine < coarse / 20.0,
            "{method}: {coarse:.3e} at ζ = 1e-6, {fine:.3e} at 1e-8"
        );
    }
}

/// ν = 0.499: the T6 block runs the P2–P0 element and says so, within 2.5 %
/// of Hertz in peak and L2 (measured peak +2.3 %, L2 1.5 %: the same mesh at
/// ν = 0.44 reads +1.7 % on the axis, Hertz's half-space against a/R = 0.18
/// on a finite block); plain T3 locks (measured L2 19 %).
#[test]
fn nearly_incompressible_seal_does_not_lock_on_t6() {
    let r = solved(&example("axisymmetric_seal_block.json"));
    let (_, ep, el2) = hertz_errors(&r, 5.0, 10.0, 0.499);
    assert!(ep.abs() < 0.025 && el2 < 0.025, "p0 {ep:+.3e} L2 {el2:.3e}");
    assert!(r.notes.iter().any(|n| n.contains("P2–P0")), "{:?}", r.notes);
    let mut t3 = example("axisymmetric_seal_block.json");
    t3["bodies"][0]["mesh"]["rectangle"]["element"] = json!("t3");
    t3["bodies"][0]["mesh"]["rectangle"]["grading"]["h_min"] = json!(0.015);
    let locked = solved(&t3);
    let (_, _, l2_t3) = hertz_errors(&locked, 5.0, 10.0, 0.499);
    assert!(l2_t3 > 4.0 * el2, "T3 {l2_t3:.3e} against T6 {el2:.3e}");
    assert!(locked.notes.iter().any(|n| n.contains("lock")), "{:?}", locked.notes);
}

/// A ball on a rigid flat at ν = 0.49 and 0.4999 (T6: the P2–P0 element),
/// against 3D Hertz at the axis r = 0 and at the next node (a midside: nodes
/// 0.015 = a/42 apart), within 1 % (measured −0.21 % and +0.39 % at both ν).
/// The volumetric constraint is the mean dilatation over the ring 2πr dA;
/// with div u at the centroid it read +5.5 % and −9.6 % here (multipliers on
/// the corners only, the next node a/21 out), and refinement did not help
/// (+5.3 %, −10.2 % at a/85). The tolerance: the same mesh at ν = 0.44 (plain
/// T6, full integration) reads +0.012 % and +0.026 % (asked within 0.5 %), and
/// the finite ball (a/R = 0.064) departs from the half-space by less than
/// 0.1 % at the axis (measured at a/85: +0.04 % at ν = 0.49, −0.04 % at 0.44).
#[test]
fn nearly_incompressible_ball_matches_hertz_on_the_axis() {
    let axis_errors = |nu: f64| -> [f64; 2] {
        let mut req = ball("t6", 0.03);
        req["bodies"][0]["material"]["poisson_ratio"] = json!(nu);
        let r = solved(&req);
        let (a, p0) = hertz3d(r.resultant.fy.abs(), 10.0, 200.0, nu);
        let mut pts: Vec<(f64, f64)> = r.pairs[0].points.iter().map(|q| (q.x, q.pressure)).collect();
        pts.sort_by(|p, q| p.0.total_cmp(&q.0));
        assert!(
            pts[0].0.abs() < 1e-12 * a,
            "the first candidate is on the axis: {pts:?}"
        );
        std::array::from_fn(|i| {
            let (x, p) = pts[i];
            p / (p0 * (1.0 - (x / a).powi(2)).sqrt()) - 1.0
        })
    };
    let plain = axis_errors(0.44);
    assert!(plain.iter().all(|e| e.abs() < 0.005), "ν = 0.44: {plain:.5?}");
    for nu in [0.49, 0.4999] {
        let mixed = axis_errors(nu);
        assert!(mixed.iter().all(|e| e.abs() < 0.01), "ν = {nu}: {mixed:.5?}");
    }
}

/// The stresses of the P2–P0 element come from its own constant pressure,
/// λ θ̄ over the element, not from div u at the centroid, which next to the
/// axis differs from θ̄ by O(1) of itself. Below the centre of the ball (T6,
/// the example's mesh: nodes a/42 apart at the contact) σ_zz on the elements
/// touching the axis follows 3D Hertz, −p0 / (1 + z²/a²), to 2.5 % of p0 from
/// z = 0.2 a to 1.5 a at ν = 0.49 (measured 1.3 %; plain T6 at ν = 0.44 on the
/// same mesh: 1.1 %, the scene's own departure; the centroid's div u gave 6.4 %).
#[test]
fn nearly_incompressible_ball_stress_follows_hertz_below_the_axis() {
    for nu in [0.44, 0.49] {
        let mut req = ball("t6", 0.015);
        req["bodies"][0]["material"]["poisson_ratio"] = json!(nu);
        req["outputs"] = json!(["stress", "mesh"]);
        let r = solved(&req);
        let (a, p0) = hertz3d(r.resultant.fy.abs(), 10.0, 200.0, nu);
        let body = &r.bodies.as_ref().expect("fields")[0];
        let (nodes, elements) = (body.nodes.as_ref().unwrap(), body.elements.as_ref().unwrap());
        let stress = body.stress.as_ref().unwrap();
        let (mut checked, mut worst) = (0, 0.0f64);
        for (e, s) in elements.iter().zip(stress) {
            let centroid = |i: usize| e[..3].iter().map(|&n| nodes[n][i]).sum::<f64>() / 3.0;
            let (r_c, depth) = (centroid(0), centroid(1));
            if r_c < 0.05 * a && depth > 0.2 * a && depth < 1.5 * a {
                let hertz = -p0 / (1.0 + (depth / a).powi(2));
                worst = worst.max((s[1] - hertz).abs() / p0);
                checked += 1;
            }
        }
        assert!(checked >= 10, "{checked} elements on the axis");
        assert!(worst < 0.025, "ν = {nu}: σ_zz off Hertz by {worst:.4} p0");
    }
}

/// What a body of revolution cannot carry is refused with the place to fix.
#[test]
fn what_a_body_of_revolution_cannot_carry_is_refused() {
    let mut sideways = example("axisymmetric_flat_punch.json");
    sideways["obstacles"][0]["punch"]["horizontal"] = json!({ "load": 5.0 });
    let e = solve(&sideways).expect_err("a sideways load on a punch of revolution");
    assert_eq!(e.code, ErrorCode::InvalidRequest);
    assert_eq!(e.path, "/obstacles/0/punch/horizontal/load");

    let mut negative = example("axisymmetric_flat_punch.json");
    negative["bodies"][0]["mesh"]["rectangle"]["corner"] = json!([-1.0, -80.0]);
    let e = solve(&negative).expect_err("a section reaching r < 0");
    assert!(e.message.contains("radius"), "{}", e.message);

    let mut radial = example("axisymmetric_ball_on_flat.json");
    radial["bodies"][0]["point_loads"] = json!([{ "edges": "flat", "at": [0.0, 10.0], "force": [1.0, -1.0] }]);
    let e = solve(&radial).expect_err("a radial point load on the axis");
    assert_eq!(e.path, "/bodies/0/point_loads/0/force/0");

    let mut half_plane = example("foundation_half_plane_roller.json");
    half_plane["analysis"] = json!("axisymmetric");
    let e = solve(&half_plane).expect_err("the half-plane in axisymmetry");
    assert!(e.path.starts_with("/foundations/0/model"), "{}", e.path);
}
