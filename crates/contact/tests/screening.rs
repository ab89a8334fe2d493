//! Screening the contact rows of a large condensed solve (`solve::screen`):
//! W is formed over the rows the loads press, every other row checked open
//! after. The answer must be the LCP's over every candidate, which the
//! full-system active set (no condensation, no screening) solves exactly.

mod common;

use common::{assert_kkt, solved};
use serde_json::{json, Value};

/// A thin strip (40 × 2, T3, h = 0.06: 668 contact candidates on its top)
/// pushed up by its bottom (u_y = `lift`) against a rigid cylinder R = 8
/// touching it at x = 0. On a layer this thin the pressure follows the
/// overlap nearly as a Winkler bed would, so the zone reaches well past the
/// rows the first pass takes (those overlapping by more than half the
/// deepest): the passes must grow.
fn strip(lift: f64) -> Value {
    json!({
        "version": "1",
        "analysis": "plane_strain",
        "bodies": [{
            "name": "strip",
            "material": {"youngs_modulus": 200.0, "poisson_ratio": 0.3},
            "mesh": {"rectangle": {"corner": [-20.0, -2.0], "width": 40.0, "height": 2.0, "size": 0.06}},
            "supports": [{"edges": "bottom", "ux": 0.0, "uy": lift}]
        }],
        "obstacles": [{"name": "cylinder", "shape": {"circle": {"center": [0.0, 8.0], "radius": 8.0}}}],
        "contacts": [{"body": "strip", "edges": "top", "obstacle": "cylinder"}],
        "settings": {"estimate": false}
    })
}

/// Every candidate's pressure from the screened solve against the full
/// system's, to 1e-9 of the peak: both solve the same LCP exactly (direct
/// solves on the active set), so they differ by round-off, which 1e-9 holds
/// with room (the certificates read 1e-15).
fn assert_same_as_full(req: &Value) -> contact::proto::SolveReply {
    let screened = solved(req);
    assert_same_pressures(&screened.pairs[0].points, req);
    assert_kkt(&screened, 1e-9);
    screened
}

/// `points` against the full system's answer of `req`.
fn assert_same_pressures(points: &[contact::proto::ContactPoint], req: &Value) {
    let mut full = req.clone();
    full["settings"]["formulation"] = json!("full");
    let full = solved(&full);
    let peak = common::peak_pressure(&full);
    assert!(peak > 0.0);
    assert_eq!(points.len(), full.pairs[0].points.len());
    for (p, q) in points.iter().zip(&full.pairs[0].points) {
        assert!(
            (p.pressure - q.pressure).abs() <= 1e-9 * peak,
            "at {:?}: {} screened, {} full",
            p.x,
            p.pressure,
            q.pressure
        );
    }
}

#[test]
fn a_screened_solve_is_the_lcp_over_every_row() {
    let r = assert_same_as_full(&strip(0.05));
    let rows = r.diagnostics.condensed_rows.expect("668 candidates are screened");
    // Screening took fewer rows than the candidates, and every row in
    // contact among them (a pressed row outside would have λ = 0).
    assert!(rows < r.size.candidates, "{rows} of {}", r.size.candidates);
    assert!(rows >= r.size.active, "{rows} rows, {} in contact", r.size.active);
}

#[test]
fn load_factors_grow_the_rows_the_first_factor_screened() {
    // The second and third factors start from the rows the first one
    // condensed (the operator is reused), too few for their wider zones.
    let mut req = strip(0.05);
    req["load_factors"] = json!([0.25, 1.0, 4.0]);
    let r = solved(&req);
    let steps = r.steps.as_ref().expect("three steps");
    assert_eq!(steps.len(), 3);
    for (step, k) in steps.iter().zip([0.25, 1.0, 4.0]) {
        assert_same_pressures(&step.pairs[0].points, &strip(0.05 * k));
    }
    // The last factor's rows cover its zone.
    let rows = r.diagnostics.condensed_rows.expect("screened");
    assert!(
        rows >= r.size.active && rows < r.size.candidates,
        "{rows}, {:?}",
        r.size
    );
}
