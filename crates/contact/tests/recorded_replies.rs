//! Replies recorded before a change, compared after it: the guard of a
//! refactoring that must leave behaviour unchanged (every example, both
//! convergence scenes, and refusals with data).
//!
//! Each request's reply is reduced to what a user reads: status, method,
//! pairs, resultants, punches, foundations, bodies, warnings, notes (solve
//! replies) or code, path and details (errors); timings, cache state, request
//! ids, certificates and diagnostics are round-off or bookkeeping and are left
//! out. Numbers must agree to 1e-12 of the largest magnitude under the same key
//! in the recorded reply (so a pressure to 1e-12 of the peak; forces, moments
//! and gaps against their physical scale, `natural_scale`): above the
//! round-off of these well-conditioned scenes (condition estimates ≤ 1e5, a
//! dense LCP of at most a few hundred rows), far below any change of the
//! discrete problem (a moved node or a changed row moves pressures by 1e-4 and
//! more). Strings, booleans and lengths must be equal.
//!
//! `RECORD_REPLIES=1 cargo test --release -p contact --test recorded_replies` rewrites the
//! records (only when a change of behaviour is intended, and said so in the
//! commit).

mod common;
use common::*;
use serde_json::{json, Map, Value};
use std::collections::HashMap;

/// Relative agreement asked of every number (see the module doc).
const TOL: f64 = 1e-12;

const VOLATILE: [&str; 8] = [
    "timings",
    "cache",
    "request_id",
    "client_id",
    "certificate",
    "diagnostics",
    "iterations",
    "version",
];

fn requests() -> Vec<(String, Value)> {
    let dir = format!("{}/proto/examples", concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("examples directory")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    names.sort();
    let mut out: Vec<(String, Value)> = names
        .iter()
        .map(|n| (n.trim_end_matches(".json").to_string(), example(n)))
        .collect();
    for element in ["t3", "t6"] {
        out.push((
            format!("convergence_disk_{element}"),
            contact_verify::convergence::disk_request(0.0044, element),
        ));
    }
    let mut moment = example("indentation_flat_punch.json");
    moment["obstacles"][0]["punch"]["rotation"] = json!({ "load": 11.0 });
    out.push(("refused_flat_punch_moment".into(), moment));
    let mut material = example("signorini_hertz_cylinder.json");
    material["bodies"][0]["material"]["poisson_ratio"] = json!(0.5);
    out.push(("refused_poisson_ratio".into(), material));
    out
}

/// The reply as a user reads it (see the module doc).
fn digest(req: &Value) -> Value {
    match solve(req) {
        Ok(r) => {
            let mut v = serde_json::to_value(&r).expect("reply serializes");
            if let Value::Object(m) = &mut v {
                for k in VOLATILE {
                    m.remove(k);
                }
            }
            v
        }
        Err(e) => json!({ "code": e.code, "path": e.path, "details": e.details }),
    }
}

/// Largest |number| under each key, over the whole value.
fn scales(v: &Value, key: &str, out: &mut HashMap<String, f64>) {
    match v {
        Value::Number(n) => {
            let s = out.entry(key.to_string()).or_insert(0.0);
            *s = s.max(n.as_f64().unwrap_or(0.0).abs());
        }
        Value::Array(a) => a.iter().for_each(|x| scales(x, key, out)),
        Value::Object(m) => m.iter().for_each(|(k, x)| scales(x, k, out)),
        _ => {}
    }
}

/// The magnitude a number under `key` is judged against. Quantities that are
/// zero up to round-off in a scene (fx and m of a symmetric load, the gaps of
/// rows in contact) are judged against their physical scale, not against
/// their own round-off: forces against the largest force component, moments
/// against that force times the scene's size, gaps against the scene's size,
/// a punch's translations against its largest one and its rotation against
/// that over the scene's size (a punch's undetermined motions, reported as 0,
/// are 0 to round-off), relative error estimates against 1.
fn natural_scale(key: &str, scale: &HashMap<String, f64>) -> f64 {
    let get = |k: &str| scale.get(k).copied().unwrap_or(0.0);
    let force = get("fx").max(get("fy")).max(get("p1")).max(get("p2"));
    let length = get("x").max(get("y"));
    let translation = get("alpha1").max(get("alpha2"));
    match key {
        "fx" | "fy" | "p1" | "p2" => force,
        "alpha1" | "alpha2" => translation,
        "theta" if length > 0.0 => get("theta").max(translation / length),
        "m" => get("m").max(force * length),
        "gap" | "max_penetration" => get(key).max(length),
        // Relative error estimates: 1e-12 absolute, whatever their size.
        // An exact scene's (a patch test's) are round-off, 1e-15 or below,
        // which its own round-off would otherwise be judged against.
        "pressure_l2" | "peak" | "resultant" | "contact_area" | "energy" => get(key).max(1.0),
        _ => get(key),
    }
}

fn compare(want: &Value, got: &Value, key: &str, at: &str, scale: &HashMap<String, f64>, diffs: &mut Vec<String>) {
    match (want, got) {
        (Value::Number(a), Value::Number(b)) => {
            let (a, b) = (a.as_f64().unwrap_or(f64::NAN), b.as_f64().unwrap_or(f64::NAN));
            let tol = TOL * natural_scale(key, scale);
            if (a - b).abs() > tol {
                diffs.push(format!("{at}: {a:e} recorded, {b:e} now (tolerance {tol:e})"));
            }
        }
        (Value::Array(a), Value::Array(b)) => {
            if a.len() != b.len() {
                diffs.push(format!("{at}: {} entries recorded, {} now", a.len(), b.len()));
                return;
            }
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                compare(x, y, key, &format!("{at}/{i}"), scale, diffs);
            }
        }
        (Value::Object(a), Value::Object(b)) => {
            let keys = |m: &Map<String, Value>| m.keys().cloned().collect::<Vec<_>>();
            if keys(a) != keys(b) {
                diffs.push(format!("{at}: fields {:?} recorded, {:?} now", keys(a), keys(b)));
                return;
            }
            for (k, x) in a {
                compare(x, &b[k], k, &format!("{at}/{k}"), scale, diffs);
            }
        }
        (a, b) if a == b => {}
        (a, b) => diffs.push(format!("{at}: {a} recorded, {b} now")),
    }
}

#[test]
fn replies_match_the_recorded_ones() {
    let dir = format!("{}/tests/recorded", env!("CARGO_MANIFEST_DIR"));
    let record = std::env::var_os("RECORD_REPLIES").is_some();
    let mut failures = Vec::new();
    for (name, req) in requests() {
        let got = digest(&req);
        let path = format!("{dir}/{name}.json");
        if record {
            std::fs::create_dir_all(&dir).expect("record directory");
            std::fs::write(&path, serde_json::to_string_pretty(&got).expect("JSON") + "\n").expect("record written");
            continue;
        }
        let want: Value = serde_json::from_str(
            &std::fs::read_to_string(&path).unwrap_or_else(|_| panic!("no record {path}: run with RECORD_REPLIES=1")),
        )
        .expect("record is JSON");
        let mut scale = HashMap::new();
        scales(&want, "", &mut scale);
        let mut diffs = Vec::new();
        compare(&want, &got, "", "", &scale, &mut diffs);
        if !diffs.is_empty() {
            let shown: Vec<String> = diffs.iter().take(5).cloned().collect();
            failures.push(format!(
                "{name}: {} differences, e.g.\n  {}",
                diffs.len(),
                shown.join("\n  ")
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
