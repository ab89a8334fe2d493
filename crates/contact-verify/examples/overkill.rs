//! Makes the overkill reference table of a convergence scene
//! (`contact_verify::overkill`), written to stdout:
//!
//! ```sh
//! cargo run --release -p contact-verify --example overkill -- disk_on_flat 0.0001375 0.03125 \
//!     > crates/contact-verify/data/disk_on_flat.csv
//! cargo run --release -p contact-verify --example overkill -- ball_on_flat 0.0001375 0.03125 \
//!     > crates/contact-verify/data/ball_on_flat.csv
//! cargo run --release -p contact-verify --example overkill -- hertz_block 0.0025 0.5 \
//!     > crates/contact-verify/data/hertz_block.csv
//! ```
//!
//! Arguments: the scene, h_min and the far-field element size. It solves the
//! scene by T6 three times: at (h_min, size), the table, and for its measured
//! uncertainty at (2 h_min, size), the level difference, and at (2 h_min,
//! 2 size), the far field's share; the header states all three (DOF, time,
//! differences). The finest T6 level of the bench is h_min = 0.00055 R, so
//! 0.0001375 is 4× finer (3.7M DOF: above the service's 2.5M limit, which
//! this run lifts; 8.6 GB and 2–4 minutes per scene on a loaded 2-core
//! machine, then about a minute for the checks). The far field at 0.03125 R
//! moves fy by 7.7e-7 (disk) and 5.6e-7 (ball) from 0.0625 R, and h_min
//! 0.000275 R by 5e-8 and 2.7e-7. The block's finest T6 level is h_min 0.01:
//! 0.0025 gives 1.4M DOF, 3 GB, 50 s.
//! With `OVERKILL_POINTS=FILE` it also writes every candidate's x and pressure
//! of the finest solve there (to study the fit).

use std::time::Instant;

use contact_core::Limits;
use contact_verify::convergence::{ball_request_sized, block_request_sized, disk_request_sized};
use contact_verify::overkill::{Reference, FIT_FROM, FIT_WINDOW_START};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() != 3 {
        eprintln!("usage: overkill <disk_on_flat|ball_on_flat|hertz_block> <h_min> <far-field size>");
        std::process::exit(2);
    }
    let scene = args[0].as_str();
    let num = |s: &str| s.parse::<f64>().unwrap_or_else(|_| panic!("not a number: {s}"));
    let (h, size) = (num(&args[1]), num(&args[2]));
    let request: fn(f64, &str, f64) -> serde_json::Value = match scene {
        "disk_on_flat" => disk_request_sized,
        "ball_on_flat" => ball_request_sized,
        "hertz_block" => block_request_sized,
        _ => panic!("no overkill reference for scene {scene}"),
    };
    let limits = Limits {
        max_dofs: 20_000_000,
        max_candidates: 100_000,
        ..Limits::default()
    };
    let solve = |h: f64, size: f64| {
        let t = Instant::now();
        let req = request(h, "t6", size);
        let grading = req["bodies"][0]["mesh"]
            .as_object()
            .and_then(|m| m.values().next())
            .map(|spec| spec["grading"].clone())
            .unwrap_or_default();
        let r = contact_verify::run::solve(&req, &limits)
            .unwrap_or_else(|e| panic!("{scene} at h_min {h}, size {size}: {e:?}"));
        let dt = t.elapsed().as_secs_f64();
        eprintln!(
            "{scene} T6 h_min {h} size {size}: {} DOF, {} candidates, {:?}, {dt:.1} s",
            r.size.dofs, r.size.candidates, r.status
        );
        let line = format!(
            "T6, h_min {h}, grading ratio {}, extent {}, far-field size {size}: {} DOF, {} candidates, {} iterations, \
                status {:?}, {dt:.1} s",
            grading["ratio"], grading["extent"], r.size.dofs, r.size.candidates, r.iterations, r.status
        );
        let reference = Reference::from_report(scene, &r, Vec::new())
            .unwrap_or_else(|| panic!("{scene} at h_min {h}: too few nodes in the zone for the edge fit"));
        (reference, line, r)
    };
    let (mut fine, fine_line, report) = solve(h, size);
    let (level, level_line, _) = solve(2.0 * h, size);
    let (far, far_line, _) = solve(2.0 * h, 2.0 * size);
    // The fit's own model error (p² is exactly quadratic only for Hertz):
    // the same solve with the window moved inward and outward.
    let window = |lo: f64, hi: f64| {
        let w = Reference::from_report_window(scene, &report, Vec::new(), lo, hi).expect("fit");
        (fine.l2_difference(&w), w.edge - fine.edge)
    };
    let d_level = (
        fine.l2_difference(&level),
        level.fy / fine.fy - 1.0,
        level.edge - fine.edge,
    );
    let d_far = (
        level.l2_difference(&far),
        far.fy / level.fy - 1.0,
        far.edge - level.edge,
    );
    let (w_in, w_out) = (window(0.7, 0.9), window(0.85, 0.97));
    if let Ok(path) = std::env::var("OVERKILL_POINTS") {
        // Every candidate's x and pressure of the finest solve, for study.
        let text: String = report.pairs[0]
            .points
            .iter()
            .map(|q| format!("{:.12e},{:.12e}\n", q.x, q.pressure))
            .collect();
        std::fs::write(&path, text).expect("OVERKILL_POINTS");
    }
    let d_window = (w_in.0.max(w_out.0), w_in.1.abs().max(w_out.1.abs()));
    // How far the outer nodes' values are from the fit (why it replaces them).
    let p0 = fine.p[0];
    let fit_p = |x: f64| (fine.fit[0] + fine.fit[1] * x + fine.fit[2] * x * x).max(0.0).sqrt();
    let outer = report.pairs[0]
        .points
        .iter()
        .filter(|q| q.x > fine.fit_from && q.pressure > 0.0)
        .map(|q| ((q.pressure - fit_p(q.x)) / p0).abs())
        .fold(0.0, f64::max);
    let last = *fine.p.last().expect("stations");
    let jump = (last - fit_p(fine.fit_from)) / p0;
    // A level difference overstates the finer level's own error (by 2^q − 1
    // for order q ≥ 1); adding the far field's share bounds both.
    fine.uncertainty_l2 = d_level.0 + d_far.0 + d_window.0;
    fine.uncertainty_fy = d_level.1.abs() + d_far.1.abs();
    fine.uncertainty_edge = d_level.2.abs() + d_far.2.abs() + d_window.1;
    fine.header =
        vec![
        format!("Overkill reference of the convergence scene {scene} (contact-verify::overkill, contact \
            {}).", env!("CARGO_PKG_VERSION")),
        format!("Made by: cargo run --release -p contact-verify --example overkill -- {scene} {h} {size}"),
        format!("Solve: the scene's request (convergence::{}_request_sized) with {fine_line}.", match scene {
            "disk_on_flat" => "disk",
            "ball_on_flat" => "ball",
            _ => "block",
        }),
        format!("Stations: x (undeformed, along the flat) and nodal pressure of the surface nodes up to fit_from = the \
            last node within {FIT_FROM} of the zone."),
        format!("Past fit_from: p = sqrt(fit_c0 + fit_c1 x + fit_c2 x^2), least squares on p^2 over the nodes in \
            {FIT_WINDOW_START}-{FIT_FROM} of the zone; edge = its falling root."),
        format!("Between stations p^2 is interpolated by the cubic through the four nearest. Stations and fit differ \
            by {jump:+.2e} p0 at fit_from;"),
        format!("past it the nodes in contact differ from the fit by up to {outer:.2e} p0 (the last ones, whose values \
            depend on where the edge falls between them)."),
        if scene == "hertz_block" {
            "fy: the block's resultant per unit thickness at the prescribed indentation.".to_string()
        } else {
            "fy: the model's resultant (the quarter's per unit thickness, or the ball's over the circumference) at the \
                prescribed approach.".to_string()
        },
        format!("Check 1, {level_line}: L2 difference {:.2e}, fy {:+.2e}, edge \
            {:+.2e}.", d_level.0, d_level.1, d_level.2),
        format!("Check 2, {far_line}: against check 1, L2 {:.2e}, fy {:+.2e}, edge \
            {:+.2e}.", d_far.0, d_far.1, d_far.2),
        format!("Check 3, the fit's window moved to 0.7-0.9 / 0.85-0.97 of the zone: L2 {:.2e} / {:.2e}, edge {:+.2e} \
            / {:+.2e}.", w_in.0, w_out.0, w_in.1, w_out.1),
        "uncertainty_*: the sum of the checks' differences, the larger of check 3's (relative L2 of the pressure over \
            the zone, relative fy, the edge in the scene's length unit).".to_string(),
    ];
    print!("{}", fine.to_csv());
}
