//! The numerical stress suite (`contact-bench --stability`): every scene kind
//! pushed along one axis at a time to the extremes users send, each row either
//! certified or refused with a clear status, with its error against a reference
//! where one exists, the factor's condition estimate and the time.
//!
//! Axes: Poisson's ratio up to 0.4999 (Hertz, T3 and T6), the stiffness ratio
//! between two bodies and between a body and a half-plane foundation (1e-6 to
//! 1e6, two-body Hertz), element aspect ratio up to 100 at the contact and
//! initial gaps down to 1e-12 of the body (a block in uniform compression, exact),
//! the penalty parameter from 1e-2 down to 1e-14 of the natural compliance
//! (against the exact solution), and 1 to 100 000 contact candidates (uniform
//! compression; past the condensed limit the full formulation).

use std::time::Instant;

use contact_core::outcome::MethodRan;
use serde_json::{json, Value};

use crate::bench::{hertz_errors, hertz_request};
use crate::reference::hertz;
use contact_core::error::CoreError;
use contact_core::solution::report::Report;
use contact_core::Limits;

#[derive(Debug, Clone)]
pub struct Row {
    pub scene: &'static str,
    pub axis: &'static str,
    pub value: f64,
    /// `solved`, `max_iterations`, `numerical_error`, or the error code of a refusal.
    pub status: String,
    pub dofs: usize,
    pub candidates: usize,
    pub iterations: usize,
    /// Worst certificate entry (NaN for a refusal).
    pub certificate: f64,
    /// Whether the method is exact; an inexact one (penalty, barrier) violates
    /// the contact conditions by design and is judged on its own equations.
    pub exact: bool,
    /// max(dual, equilibrium) of the certificate: the inexact methods' own equations.
    pub own_equations: f64,
    /// Relative error against the reference (NaN where there is none).
    pub error: f64,
    pub condition: f64,
    pub refinements: usize,
    pub seconds: f64,
    /// What the error is measured against.
    pub reference: &'static str,
}

impl Row {
    pub const HEADER: &'static str =
        "scene,axis,value,status,dofs,candidates,iterations,certificate,error,condition_estimate,refinements,seconds,\
            reference";

    pub fn csv(&self) -> String {
        format!(
            "{},{},{:e},{},{},{},{},{:.2e},{:.2e},{:.2e},{},{:.4},{}",
            self.scene,
            self.axis,
            self.value,
            self.status,
            self.dofs,
            self.candidates,
            self.iterations,
            self.certificate,
            self.error,
            self.condition,
            self.refinements,
            self.seconds,
            self.reference
        )
    }

    pub fn table_header() -> String {
        format!(
            "{:<14} {:<16} {:>9} {:<18} {:>8} {:>6} {:>4} {:>9} {:>9} {:>9} {:>3} {:>8}  reference",
            "scene", "axis", "value", "status", "dofs", "cand", "it", "cert", "error", "cond", "ref", "time"
        )
    }

    pub fn table_line(&self) -> String {
        format!(
            "{:<14} {:<16} {:>9.1e} {:<18} {:>8} {:>6} {:>4} {:>9.1e} {:>9.1e} {:>9.1e} {:>3} {:>8.3}  {}",
            self.scene,
            self.axis,
            self.value,
            self.status,
            self.dofs,
            self.candidates,
            self.iterations,
            self.certificate,
            self.error,
            self.condition,
            self.refinements,
            self.seconds,
            self.reference
        )
    }

    /// Certified (every certificate entry ≤ 1e-8) or refused with a status.
    pub fn is_clear(&self) -> bool {
        let refused = !matches!(self.status.as_str(), "solved" | "max_iterations" | "numerical_error");
        let honest_failure = matches!(self.status.as_str(), "max_iterations" | "numerical_error");
        let certified = if self.exact {
            self.certificate <= 1e-8
        } else {
            self.own_equations <= 1e-8
        };
        refused || honest_failure || certified
    }
}

fn solve(req: &Value, limits: &Limits) -> (Result<Report, CoreError>, f64) {
    let t = Instant::now();
    let r = crate::run::solve(req, limits);
    (r, t.elapsed().as_secs_f64())
}

/// A row from a reply (or refusal) and the error the caller measured.
fn row(
    scene: &'static str,
    axis: &'static str,
    value: f64,
    reply: &Result<Report, CoreError>,
    seconds: f64,
    error: f64,
    reference: &'static str,
) -> Row {
    match reply {
        Ok(r) => Row {
            scene,
            axis,
            value,
            status: r.status.as_str().to_string(),
            dofs: r.size.dofs,
            candidates: r.size.candidates,
            iterations: r.iterations,
            certificate: r.certificate.worst(),
            exact: !matches!(r.method, MethodRan::Penalty | MethodRan::Barrier),
            own_equations: r.certificate.dual.max(r.certificate.equilibrium),
            error,
            condition: r.diagnostics.condition_estimate.unwrap_or(f64::NAN),
            refinements: r.diagnostics.refinements,
            seconds,
            reference,
        },
        Err(e) => Row {
            scene,
            axis,
            value,
            status: e.code().to_string(),
            dofs: 0,
            candidates: 0,
            iterations: 0,
            certificate: f64::NAN,
            exact: true,
            own_equations: f64::NAN,
            error: f64::NAN,
            condition: f64::NAN,
            refinements: 0,
            seconds,
            reference,
        },
    }
}

/// Hertz (rigid cylinder into a block) at Poisson's ratio ν: L2 error of the
/// pressure against the closed form, and of its node-to-node oscillation.
pub fn poisson(element: &'static str, nu: f64, h_min: f64) -> Row {
    let mut req = hertz_request(h_min, element, "auto");
    req["bodies"][0]["material"]["poisson_ratio"] = json!(nu);
    let (r, t) = solve(&req, &Limits::default());
    let err = r
        .as_ref()
        .map(|r| hertz_errors(r, 8.0, 200.0 / (1.0 - nu * nu)).2)
        .unwrap_or(f64::NAN);
    let scene = if element == "t6" { "hertz_t6" } else { "hertz_t3" };
    row(scene, "poisson_ratio", nu, &r, t, err, "Hertz L2(p)")
}

/// The largest second difference of the pressure inside 0.8 a over the peak:
/// node-to-node oscillation (locking shows as a checkerboard of pressures).
pub fn oscillation(r: &Report) -> f64 {
    let pts = &r.pairs[0].points;
    let peak = pts.iter().map(|p| p.pressure).fold(0.0, f64::max);
    let zone = r.pairs[0].zones.first().copied().unwrap_or([0.0, 0.0]);
    let a = 0.5 * (zone[1] - zone[0]);
    pts.windows(3)
        .filter(|w| w[1].x.abs() < 0.8 * a)
        .map(|w| (w[1].pressure - 0.5 * (w[0].pressure + w[2].pressure)).abs() / peak)
        .fold(0.0, f64::max)
}

/// Peak pressure of pair 0 against Hertz with the reply's load, the effective
/// radius and modulus.
fn hertz_peak_error(r: &Report, r_eff: f64, e_star: f64) -> f64 {
    let (_, p0) = hertz(r.pairs[0].resultant.fy.abs(), r_eff, e_star);
    let peak = r.pairs[0].points.iter().map(|q| q.pressure).fold(0.0, f64::max);
    peak / p0 - 1.0
}

/// Two cylinders with E_lower = ratio · E_upper: peak pressure against two-body Hertz.
pub fn two_body_ratio(ratio: f64) -> Row {
    let mut req: Value = serde_json::from_str(include_str!("../../../proto/examples/two_bodies_cylinders.json"))
        .expect("example is JSON");
    let (e1, nu1, nu2) = (200.0, 0.3, 0.25);
    let e2 = e1 * ratio;
    req["bodies"][1]["material"]["youngs_modulus"] = json!(e2);
    let (r, t) = solve(&req, &Limits::default());
    let es = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    let err = r
        .as_ref()
        .map(|r| hertz_peak_error(r, 1.0 / (1.0 / 8.0 + 1.0 / 12.0), es))
        .unwrap_or(f64::NAN);
    row("two_cylinders", "stiffness_ratio", ratio, &r, t, err, "Hertz p0")
}

/// A roller (E_body) on an elastic half-plane foundation E_f = ratio · E_body:
/// peak pressure against Hertz with both compliances.
pub fn foundation_ratio(ratio: f64) -> Row {
    let mut req: Value = serde_json::from_str(include_str!(
        "../../../proto/examples/foundation_half_plane_roller.json"
    ))
    .expect("example is JSON");
    let (eb, nu) = (200.0, 0.3);
    let ef = eb * ratio;
    req["bodies"][0]["material"]["youngs_modulus"] = json!(eb);
    req["bodies"][0]["mesh"]["half_disk"]["grading"]["h_min"] = json!(0.01);
    req["foundations"][0]["model"]["half_plane"]["youngs_modulus"] = json!(ef);
    // Keep a/R small whatever the stiffness: the load follows the softer side.
    let p = 10.0 * eb.min(ef) / 200.0;
    req["bodies"][0]["tractions"][0]["traction"] = json!([0.0, -p / 16.0]);
    let (r, t) = solve(&req, &Limits::default());
    let es = 1.0 / ((1.0 - nu * nu) / eb + (1.0 - nu * nu) / ef);
    let err = r.as_ref().map(|r| hertz_peak_error(r, 8.0, es)).unwrap_or(f64::NAN);
    row("roller_on_half_plane", "stiffness_ratio", ratio, &r, t, err, "Hertz p0")
}

/// A W × H block (W = 1, H = 1) on rollers, pressed δ by a rigid flat from
/// above with an initial gap g0, meshed by an inline structured T3 mesh of
/// `nx` × `ny` cells: uniaxial stress, exact in the FE model:
/// p = E / (1 − ν²) (δ − g0) / H (plane strain).
fn compression_block(nx: usize, ny: usize, delta: f64, g0: f64) -> Value {
    let (w, h) = (1.0, 1.0);
    let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push(json!([w * i as f64 / nx as f64, h * j as f64 / ny as f64]));
        }
    }
    let id = |i: usize, j: usize| j * (nx + 1) + i;
    let mut elements = Vec::with_capacity(2 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            elements.push(json!([id(i, j), id(i + 1, j), id(i + 1, j + 1)]));
            elements.push(json!([id(i, j), id(i + 1, j + 1), id(i, j + 1)]));
        }
    }
    let bottom: Vec<Value> = (0..nx).map(|i| json!([id(i, 0), id(i + 1, 0)])).collect();
    let top: Vec<Value> = (0..nx).map(|i| json!([id(i + 1, ny), id(i, ny)])).collect();
    let left: Vec<Value> = (0..ny).map(|j| json!([id(0, j + 1), id(0, j)])).collect();
    json!({
        "version": "1",
        "bodies": [{
            "name": "block",
            "material": { "youngs_modulus": 200.0, "poisson_ratio": 0.3 },
            "mesh": { "inline": { "nodes": nodes, "elements": elements,
                "edge_sets": { "bottom": bottom, "top": top, "left": left } } },
            "supports": [{ "edges": "bottom", "uy": 0.0 }, { "edges": "left", "ux": 0.0 }]
        }],
        "obstacles": [{ "name": "flat",
            "shape": { "line": { "point": [0.0, h + g0 - delta], "normal": [0.0, -1.0] } } }],
        "contacts": [{ "body": "block", "edges": "top", "obstacle": "flat" }]
    })
}

fn compression_error(r: &Report, delta: f64, g0: f64) -> f64 {
    let exact = 200.0 / (1.0 - 0.09) * (delta - g0);
    r.pairs[0]
        .points
        .iter()
        .map(|p| (p.pressure - exact).abs() / exact)
        .fold(0.0, f64::max)
}

/// Aspect ratio `a` of the elements (dx = a · dy) in the compressed block.
pub fn aspect(a: f64) -> Row {
    let ny = 100;
    let nx = ((ny as f64) / a).round().max(1.0) as usize;
    let delta = 1e-3;
    let (r, t) = solve(&compression_block(nx, ny, delta, 0.0), &Limits::default());
    let err = r.as_ref().map(|r| compression_error(r, delta, 0.0)).unwrap_or(f64::NAN);
    row("compression", "aspect_ratio", a, &r, t, err, "exact uniform p")
}

/// Initial gap g0 = `gap` · H before the block is pressed δ = 1e-3 H.
pub fn gap(gap: f64) -> Row {
    let delta = 1e-3;
    let (r, t) = solve(&compression_block(20, 20, delta, gap), &Limits::default());
    let err = r.as_ref().map(|r| compression_error(r, delta, gap)).unwrap_or(f64::NAN);
    row("compression", "gap", gap, &r, t, err, "exact uniform p")
}

/// Penalty ζ = `c` · L/E on Hertz: largest pressure difference to the exact
/// solution over its peak (the penalty's own error, O(ζ)).
pub fn penalty(c: f64, exact: &Report, h_min: f64) -> Row {
    let mut req = hertz_request(h_min, "t3", "penalty");
    // Natural compliance L/E: body size 40 over E = 200.
    req["settings"] = json!({ "penalty": c * 40.0 / 200.0 });
    let (r, t) = solve(&req, &Limits::default());
    let peak = exact.pairs[0].points.iter().map(|q| q.pressure).fold(0.0, f64::max);
    let err = r
        .as_ref()
        .map(|r| {
            r.pairs[0]
                .points
                .iter()
                .zip(&exact.pairs[0].points)
                .map(|(p, q)| (p.pressure - q.pressure).abs() / peak)
                .fold(0.0, f64::max)
        })
        .unwrap_or(f64::NAN);
    row("hertz_t3", "penalty_zeta", c, &r, t, err, "exact solution")
}

/// `n` contact candidates: a strip n elements long and 2 deep in uniform
/// compression, condensed (refused past the candidate limit) or `full`.
pub fn candidates(n: usize, full: bool) -> Row {
    let req = strip_request(n, full);
    let limits = if full {
        Limits {
            max_candidates: usize::MAX,
            ..Limits::default()
        }
    } else {
        Limits::default()
    };
    let (r, t) = solve(&req, &limits);
    let err = r
        .as_ref()
        .map(|r| {
            r.pairs[0]
                .points
                .iter()
                .map(|p| (p.pressure - STRIP_PRESSURE).abs() / STRIP_PRESSURE)
                .fold(0.0, f64::max)
        })
        .unwrap_or(f64::NAN);
    let scene = if full { "strip_full" } else { "strip" };
    row(scene, "candidates", n as f64, &r, t, err, "exact uniform p")
}

/// Exact contact pressure of `strip_request`: E / (1 − ν²) · 1e-3.
pub const STRIP_PRESSURE: f64 = 200.0 / (1.0 - 0.09) * 1e-3;

/// A strip n elements long and 2 deep, on rollers, pressed 1e-3 of its depth
/// by a rigid flat: n + 1 candidates in uniform compression.
pub fn strip_request(n: usize, full: bool) -> Value {
    use crate::build::*;
    let h = 1.0 / n as f64;
    let strip = body("strip", 200.0, 0.3, rectangle([0.0, 0.0], 1.0, 2.0 * h, h, "t3"))
        .support("bottom", None, Some(0.0))
        .support("left", Some(0.0), None);
    let mut req = request(vec![strip], vec![pair("strip", "top").obstacle("flat")])
        .with_obstacle(obstacle("flat", line([0.0, 2.0 * h * (1.0 - 1e-3)], [0.0, -1.0])));
    if full {
        req.settings.formulation = contact_proto::Formulation::Full;
    }
    req.to_value()
}

/// The whole suite (`quick`: coarser meshes and fewer points per axis).
pub fn run(quick: bool, mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut push = |r: Row, rows: &mut Vec<Row>| {
        progress(&r);
        rows.push(r);
    };
    let h = if quick { 0.05 } else { 0.02 };
    for element in ["t3", "t6"] {
        for nu in [0.3, 0.45, 0.49, 0.499, 0.4999] {
            push(poisson(element, nu, h), &mut rows);
        }
    }
    for ratio in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        push(two_body_ratio(ratio), &mut rows);
        push(foundation_ratio(ratio), &mut rows);
    }
    for a in [1.0, 10.0, 100.0] {
        push(aspect(a), &mut rows);
    }
    for g in [0.0, 1e-12, 1e-9, 1e-6] {
        push(gap(g), &mut rows);
    }
    let exact = crate::run::solve(&hertz_request(h, "t3", "active_set"), &Limits::default()).expect("Hertz is valid");
    for c in [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14] {
        push(penalty(c, &exact, h), &mut rows);
    }
    let counts: &[usize] = if quick {
        &[1, 10, 100, 1000, 3999, 10_000]
    } else {
        &[1, 10, 100, 1000, 3999, 10_000, 100_000]
    };
    for &n in counts {
        push(candidates(n, false), &mut rows);
        if n >= 4000 {
            push(candidates(n, true), &mut rows);
        }
    }
    rows
}
