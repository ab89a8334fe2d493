//! Shared helpers of the integration tests.
#![allow(dead_code)]

use contact::proto::{ErrorReply, NoteKind, SolveReply};
use contact::scene::Limits;
use serde_json::Value;

pub fn example(name: &str) -> Value {
    let path = format!(
        "{}/proto/examples/{name}",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../..")
    );
    serde_json::from_str(&std::fs::read_to_string(&path).expect("example exists")).expect("example is JSON")
}

pub fn solve(req: &Value) -> Result<SolveReply, ErrorReply> {
    solve_with(req, &Limits::default())
}

/// `solve` under the deployment limits `limits`; every reply's notes carry
/// their kinds, one each.
pub fn solve_with(req: &Value, limits: &Limits) -> Result<SolveReply, ErrorReply> {
    let r = contact::solve_bytes(serde_json::to_string(req).unwrap().as_bytes(), limits);
    if let Ok(r) = &r {
        assert_eq!(r.note_kinds.len(), r.notes.len(), "{:?} {:?}", r.note_kinds, r.notes);
    }
    r
}

/// The kind of the reply's first note containing `text`.
pub fn note_kind(r: &SolveReply, text: &str) -> Option<NoteKind> {
    let i = r.notes.iter().position(|n| n.contains(text))?;
    r.note_kinds.get(i).copied()
}

pub fn solved(req: &Value) -> SolveReply {
    match solve(req) {
        Ok(r) => {
            assert_eq!(
                r.status,
                contact::proto::SolveStatus::Solved,
                "certificate {:?}",
                r.certificate
            );
            r
        }
        Err(e) => panic!("solve failed: {e:?}"),
    }
}

/// Hertz line contact, one elastic body against a rigid one, plane strain:
/// (a, p0) for load P per unit thickness.
pub fn hertz(p: f64, r: f64, e: f64, nu: f64) -> (f64, f64) {
    contact_verify::reference::hertz(p, r, e / (1.0 - nu * nu))
}

pub fn peak_pressure(r: &SolveReply) -> f64 {
    r.pairs[0].points.iter().map(|p| p.pressure).fold(0.0, f64::max)
}

pub fn half_width(r: &SolveReply) -> f64 {
    assert_eq!(
        r.pairs[0].zones.len(),
        1,
        "one contact zone expected: {:?}",
        r.pairs[0].zones
    );
    let z = r.pairs[0].zones[0];
    0.5 * (z[1] - z[0])
}

/// The certificate's largest residual, NaN if any residual is NaN.
pub fn worst_residual(c: &contact::proto::Certificate) -> f64 {
    [c.primal, c.dual, c.complementarity, c.equilibrium]
        .into_iter()
        .fold(0.0, |a, v| if v.is_nan() || a.is_nan() { f64::NAN } else { a.max(v) })
}

/// Every truth of §6 that holds for any frictionless solution: complementarity
/// and sign conditions to the certificate's tolerance.
pub fn assert_kkt(r: &SolveReply, tol: f64) {
    let c = r.certificate;
    for (name, v) in [
        ("primal", c.primal),
        ("dual", c.dual),
        ("complementarity", c.complementarity),
        ("equilibrium", c.equilibrium),
    ] {
        assert!(v <= tol, "{name} residual {v:e} > {tol:e}");
    }
    let pmax = peak_pressure(r);
    for pair in &r.pairs {
        for p in &pair.points {
            assert!(p.pressure >= -tol * pmax, "tensile pressure {p:?}");
            if p.pressure > tol * pmax {
                assert!(p.gap.abs() <= 1e-9 * (1.0 + p.x.abs()), "pressure on an open gap {p:?}");
            }
        }
    }
}

/// Largest pointwise pressure difference between two replies of the same scene.
pub fn max_pressure_diff(a: &SolveReply, b: &SolveReply) -> f64 {
    a.pairs[0]
        .points
        .iter()
        .zip(&b.pairs[0].points)
        .map(|(p, q)| (p.pressure - q.pressure).abs())
        .fold(0.0, f64::max)
}

/// Solves `req` with `active_set` and with `interior_point`: every candidate's
/// pressure agrees to `tol` of the peak (the exact methods solve one problem).
pub fn assert_exact_methods_agree(req: &Value, tol: f64) {
    let mut req = req.clone();
    req["method"] = Value::from("active_set");
    let a = solved(&req);
    req["method"] = Value::from("interior_point");
    let b = solved(&req);
    let peak = peak_pressure(&a);
    for (p, q) in a.pairs[0].points.iter().zip(&b.pairs[0].points) {
        assert!(
            (p.pressure - q.pressure).abs() <= tol * peak,
            "{} vs {}",
            p.pressure,
            q.pressure
        );
    }
}

/// The ends of the run of points in `state` (or, with None, in contact):
/// midway between the run's end points and their outer neighbours, where the
/// true transition lies to ± half a spacing.
pub fn run_ends(
    points: &[contact::proto::ContactPoint],
    inside: impl Fn(&contact::proto::ContactPoint) -> bool,
) -> [f64; 2] {
    let idx: Vec<usize> = (0..points.len()).filter(|&i| inside(&points[i])).collect();
    assert!(!idx.is_empty(), "no point in the run");
    let (lo, hi) = (idx[0], idx[idx.len() - 1]);
    assert_eq!(hi - lo + 1, idx.len(), "the run is not contiguous");
    let x = |i: usize| points[i].x;
    let l = if lo > 0 { 0.5 * (x(lo) + x(lo - 1)) } else { x(lo) };
    let h = if hi + 1 < points.len() {
        0.5 * (x(hi) + x(hi + 1))
    } else {
        x(hi)
    };
    [l, h]
}

/// The answer of every step (the reply's `steps`).
pub fn steps(
    r: &SolveReply,
) -> Vec<(
    Vec<contact::proto::PairResult>,
    contact::proto::Resultant,
    contact::proto::SolveStatus,
)> {
    r.steps
        .as_ref()
        .expect("a load path answers per step")
        .iter()
        .map(|s| (s.pairs.clone(), s.resultant, s.status))
        .collect()
}

/// A load path whose steps scale the first body's second support (its
/// sideways motion) by each of `shifts`.
pub fn shift_path(shifts: &[f64]) -> Value {
    Value::from(
        shifts
            .iter()
            .map(|d| serde_json::json!({"loads": {"/bodies/0/supports/1": d}}))
            .collect::<Vec<_>>(),
    )
}

/// The load at `path` of an `incompatible_loads` refusal there, and its
/// admissible range [min, max] (both bounds required).
pub fn refused_range(e: &ErrorReply, path: &str) -> (f64, f64, f64) {
    assert_eq!(e.code, contact::proto::ErrorCode::IncompatibleLoads, "{e:?}");
    assert_eq!(e.path, path, "{e:?}");
    let loads = &e.details.as_ref().expect("details").loads;
    let b = loads
        .iter()
        .find(|b| b.path == e.path)
        .unwrap_or_else(|| panic!("no range at {path}: {loads:?}"));
    (b.value, b.min.expect("bounded below"), b.max.expect("bounded above"))
}

/// The roller of `signorini_roller_on_flat.json` (R = 8, E = 200) with
/// `element` (T3: nodal rows; T6: mortar rows) and Poisson ratio `nu`, graded
/// to `h` at the contact, pressed by 0.05 onto the rigid floor and then moved
/// sideways by each of `shifts` in turn (its own support, so that the path
/// scales it alone), with friction `mu` (frictionless with None).
pub fn friction_roller(element: &str, nu: f64, h: f64, shifts: &[f64], mu: Option<f64>) -> Value {
    let mut r = example("signorini_roller_on_flat.json");
    let b = &mut r["bodies"][0];
    b["material"]["poisson_ratio"] = serde_json::json!(nu);
    let mesh = &mut b["mesh"]["half_disk"];
    mesh["element"] = serde_json::json!(element);
    mesh["grading"] = serde_json::json!({"h_min": h, "ratio": 1.2, "extent": 0.6});
    b["supports"] = serde_json::json!([{"edges": "flat", "uy": -0.05}, {"edges": "flat", "ux": 1.0}]);
    if let Some(mu) = mu {
        r["contacts"][0]["friction"] = serde_json::json!({"coefficient": mu});
    }
    r["load_path"] = shift_path(shifts);
    r
}

/// The flat punch of `indentation_flat_punch.json` (half-width a = 1, P = 10)
/// with friction `mu` on a block of Poisson ratio `nu`, made `scale` times
/// larger (its element size too) so that it approaches the half-plane of
/// Spence's theory, graded to `h` under the punch.
pub fn spence_block(nu: f64, mu: f64, h: f64, scale: f64) -> Value {
    let mut r = example("indentation_flat_punch.json");
    let b = &mut r["bodies"][0];
    b["material"]["poisson_ratio"] = serde_json::json!(nu);
    let m = &mut b["mesh"]["rectangle"];
    m["corner"] = serde_json::json!([-20.0 * scale, -20.0 * scale]);
    m["width"] = serde_json::json!(40.0 * scale);
    m["height"] = serde_json::json!(20.0 * scale);
    m["size"] = serde_json::json!(scale);
    m["grading"]["h_min"] = serde_json::json!(h);
    r["contacts"][0]["friction"] = serde_json::json!({"coefficient": mu});
    r
}

/// Two answers of one scene posed in two systems of units: every number of
/// `x` equals `y`'s read in `x`'s units (`y / unit`) to 1e-9 of `x`'s largest
/// magnitude, the round-off of scaling both to the same nondimensional scene.
pub fn assert_same_in_units(x: &[f64], y: &[f64], unit: f64, what: &str) {
    let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (u, v) in x.iter().zip(y) {
        assert!((u - v / unit).abs() <= 1e-9 * scale, "{what}: {u} against {}", v / unit);
    }
}

/// One number of every contact point of a solid's reply.
pub fn point_values(s: &contact::proto::SolidResult, f: fn(&contact::proto::SolidContactPoint) -> f64) -> Vec<f64> {
    s.points.iter().map(f).collect()
}

/// The radius of a circular Hertz patch centred on the z axis from the
/// points in contact (`contact_verify::reference::edge_fit` over their r²
/// and p²).
pub fn circle_fit(points: &[contact::proto::SolidContactPoint]) -> f64 {
    let pressed: Vec<(f64, f64)> = points
        .iter()
        .filter(|q| q.in_contact)
        .map(|q| (q.at[0].powi(2) + q.at[1].powi(2), q.pressure.powi(2)))
        .collect();
    contact_verify::reference::edge_fit(&pressed)
}
