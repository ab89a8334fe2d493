//! The time to a tolerance on the disk on a flat alone (`tolerance::run`,
//! the table `contact-bench --convergence` prints after its convergence
//! suite): the table on stdout and in `bench_out/tolerance.csv`, then, per
//! adaptive row, where its time goes: every solve the request made (rounds
//! and companions, in order) with its stages, and the final mesh's single
//! solve. `cargo run --release -p contact-verify --example tolerance
//! [LEVELS]` (the fixed levels to try, default the convergence suite's).

use contact_core::observer::Timings;
use contact_core::scene::{AccuracyTarget, Limits, Scene};
use contact_core::solution::report::Report;
use contact_proto::SolveRequest;
use contact_verify::convergence::{disk_request, LEVELS};
use contact_verify::tolerance::{self, Row, START_H, TOLERANCES};
use serde_json::json;
use std::sync::Mutex;
use std::time::Instant;

/// Whole adaptive requests per breakdown, of which the median is shown.
const REPEATS: usize = 5;

fn main() {
    let levels = std::env::args()
        .nth(1)
        .map_or(LEVELS, |a| a.parse().expect("LEVELS: a number"));
    println!("time to a tolerance, disk on a flat (error against its overkill table):");
    println!("{}", Row::table_header());
    let rows = tolerance::run(levels, |r| println!("{}", r.table_line()));
    let csv = std::path::Path::new("bench_out/tolerance.csv");
    std::fs::create_dir_all("bench_out").expect("bench_out");
    let lines: Vec<String> = std::iter::once(Row::HEADER.to_string())
        .chain(rows.iter().map(Row::csv))
        .collect();
    std::fs::write(csv, lines.join("\n") + "\n").expect("tolerance.csv");
    println!("wrote {}", csv.display());
    for element in ["t3", "t6"] {
        for tol in TOLERANCES {
            breakdown(element, tol);
        }
    }
}

/// One adaptive request, its solver wrapped to log each solve (the rounds'
/// and their companions') with its stages.
fn breakdown(element: &str, tol: f64) {
    let limits = Limits::default();
    let mut req = disk_request(START_H, element);
    req["settings"] = json!({"accuracy": {"pressure_l2": tol}});
    let parsed: SolveRequest = serde_json::from_value(req).expect("a valid request");
    let scene = Scene::try_new(&parsed, &limits).expect("a valid scene");
    let target: AccuracyTarget = scene.settings.accuracy.expect("accuracy asked");
    let log = Mutex::new(Vec::<(usize, Timings)>::new());
    let solve = |s: &Scene| {
        let r = contact_core::solve::solve_steps(s, &limits, None);
        if let Ok(r) = &r {
            log.lock().expect("log").push((r.size.dofs, r.timings));
        }
        r
    };
    // The median of `REPEATS` whole requests (the machine is shared); the
    // last one's solves are shown.
    let mut wholes = Vec::new();
    let mut last = None;
    for _ in 0..REPEATS {
        log.lock().expect("log").clear();
        let t = Instant::now();
        let r: Report = contact_core::adapt::refine(&scene, target, &solve, &limits).expect("solved");
        wholes.push(t.elapsed().as_secs_f64());
        last = Some(r);
    }
    let r = last.expect("one request");
    wholes.sort_by(f64::total_cmp);
    let whole = wholes[wholes.len() / 2];
    let f = r.refinement.as_ref().expect("rounds reported");
    println!(
        "\n{} tol {tol}: {} rounds, stopped {}, {whole:.4} s whole (median of {REPEATS}), estimate's share {:.4} s, \
         described error {:.3} %",
        element.to_uppercase(),
        f.rounds.len(),
        f.stopped.as_str(),
        r.timings.estimate,
        100.0 * tolerance::described_error(&r),
    );
    println!(
        "  {:>5} {:>8} {:>10} {:>9} {:>8}",
        "round", "dofs", "h_min", "estimate", "seconds"
    );
    for (i, round) in f.rounds.iter().enumerate() {
        println!(
            "  {:>5} {:>8} {:>10.5} {:>8.3}% {:>8.4}",
            i + 1,
            round.dofs,
            round.h_min,
            100.0 * round.pressure_l2.unwrap_or(f64::NAN),
            round.seconds
        );
    }
    println!(
        "  {:>5} {:>8} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7}",
        "solve", "dofs", "mesh", "assem", "factor", "conds", "lcp", "post", "total"
    );
    let mut sum = 0.0;
    for (i, (dofs, t)) in log.lock().expect("log").iter().enumerate() {
        sum += t.total;
        println!(
            "  {:>5} {:>8} {:>7.4} {:>7.4} {:>7.4} {:>7.4} {:>7.4} {:>7.4} {:>7.4}",
            i + 1,
            dofs,
            t.mesh,
            t.assembly,
            t.factorization,
            t.condensation,
            t.contact_solve,
            t.post,
            t.total
        );
    }
    println!(
        "  solves' sum {sum:.4} s; outside them (estimates' comparisons, energy bound, meshes' sizing) {:.4} s; \
         final round's own stages {:.4} s",
        whole - sum,
        r.timings.total - r.timings.estimate
    );
}
