//! The factorization-time prediction against the real time on this machine,
//! after the start-up calibration the service makes and with the learning of
//! every factorization on: five uniform T3 grids (the stiffness pattern of a
//! uniform rectangle) from 0.25M to 2M DOF. With `--compare`, each grid is
//! also factored by faer's own one-call numeric factorization (which cannot
//! be stopped), alternating, to compare the speed.
//!
//! `--speed` factors the 1M-DOF grid 4 times each way, alternating, and prints
//! the fastest of each (the machine's other load only ever adds time).
//!
//! `--stop` factors the 0.5M, 1M and 2M-DOF grids under deadlines of 25, 50
//! and 75 % of their factorization time (the prediction told to let them
//! start) and prints how long after the deadline each stopped.
//!
//! `cargo run --release -p contact-core --example factor_rate [-- --compare | --speed | --stop]`

use std::sync::Arc;
use std::time::Instant;

use contact_core::linalg::cholesky::{Cholesky, SymbolicFactor};
use contact_core::linalg::rate;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, SymmetricOrdering};
use faer::sparse::linalg::SupernodalThreshold;
use faer::Side;

fn main() {
    let compare = std::env::args().any(|a| a == "--compare");
    if std::env::args().any(|a| a == "--stop") {
        for (nx, ny) in [(707, 354), (1000, 500), (1414, 707)] {
            let k = rate::grid_stiffness(nx, ny);
            let analysis = Arc::new(SymbolicFactor::try_new(&k).expect("SPD"));
            let t = Instant::now();
            drop(Cholesky::with_symbolic(analysis.clone(), &k).expect("factors"));
            let full = t.elapsed().as_secs_f64();
            for frac in [0.25, 0.5, 0.75] {
                let limit = std::time::Duration::from_secs_f64(frac * full);
                // A prediction that always fits: the stop alone bounds the time.
                rate::set_scale(1e-9);
                let t = Instant::now();
                let _d = contact_core::cancel::Deadline::install(limit);
                let r = Cholesky::with_symbolic(analysis.clone(), &k);
                let stopped = t.elapsed().as_secs_f64();
                println!(
                    "{:>8} DOF, factorization {full:.2} s, limit {:.2} s: {} after {stopped:.3} s, {:+.3} s past the \
                        limit",
                    k.nrows(),
                    limit.as_secs_f64(),
                    if r.is_err() { "stopped" } else { "finished" },
                    stopped - limit.as_secs_f64()
                );
            }
        }
        return;
    }
    if std::env::args().any(|a| a == "--speed") {
        let k = rate::grid_stiffness(1000, 500);
        let (mut ours, mut theirs) = (f64::INFINITY, f64::INFINITY);
        let analysis = Arc::new(SymbolicFactor::try_new(&k).expect("SPD"));
        let (mut ours_cpu, mut theirs_cpu) = (f64::INFINITY, f64::INFINITY);
        for round in 0..4 {
            // Each goes first in turn.
            if round % 2 == 1 {
                let (wall, cpu) = faer_one_call(&k);
                (theirs, theirs_cpu) = (theirs.min(wall), theirs_cpu.min(cpu));
            }
            let (t, c) = (Instant::now(), cpu_secs());
            drop(Cholesky::with_symbolic(analysis.clone(), &k).expect("factors"));
            ours = ours.min(t.elapsed().as_secs_f64());
            ours_cpu = ours_cpu.min(cpu_secs() - c);
            if round % 2 == 0 {
                let (wall, cpu) = faer_one_call(&k);
                (theirs, theirs_cpu) = (theirs.min(wall), theirs_cpu.min(cpu));
            }
        }
        println!(
            "1M-DOF grid, fastest of 4: stoppable {ours:.3} s ({ours_cpu:.3} s on CPU), faer's one call {theirs:.3} s \
                ({theirs_cpu:.3} s on CPU)"
        );
        return;
    }
    let t = Instant::now();
    let s = contact_core::linalg::calibrate::calibrate();
    println!("calibration: scale {s:.3} ({:.2} s)", t.elapsed().as_secs_f64());
    println!("     DOF   nnz(L)    flops  predicted_s  real_s  error  uncalibrated  scale_after  faer_one_call_s");
    for (nx, ny) in [(500, 250), (707, 354), (1000, 500), (1225, 612), (1414, 707)] {
        let k = rate::grid_stiffness(nx, ny);
        let analysis = Arc::new(SymbolicFactor::try_new(&k).expect("SPD"));
        let cost = analysis.cost();
        let faer = compare.then(|| faer_one_call(&k).0);
        let predicted = cost.predicted_secs();
        let reference = cost.reference_secs();
        let t = Instant::now();
        let chol = Cholesky::with_symbolic(analysis, &k).expect("factors");
        let real = t.elapsed().as_secs_f64();
        drop(chol);
        println!(
            "{:>8} {:>8.2e} {:>8.2e} {:>12.2} {:>7.2} {:>+6.1}%  {:>+11.1}%  {:>11.3}  {}",
            k.nrows(),
            cost.nnz as f64,
            cost.flops,
            predicted,
            real,
            100.0 * (predicted / real - 1.0),
            100.0 * (reference / real - 1.0),
            rate::scale(),
            faer.map_or(String::new(), |f| format!("{f:.2}"))
        );
    }
}

/// Seconds this thread has been on a CPU (the machine's other load does not
/// count), from the kernel's scheduler statistics.
fn cpu_secs() -> f64 {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").unwrap_or_default();
    s.split_whitespace()
        .next()
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap_or(0.0)
        * 1e-9
}

/// Seconds (wall, on CPU) of faer's own numeric factorization (AMD order,
/// forced supernodal, sequential: as `linalg::cholesky` configures it).
fn faer_one_call(k: &faer::sparse::SparseColMat<usize, f64>) -> (f64, f64) {
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let symbolic =
        factorize_symbolic_cholesky(k.symbolic(), Side::Lower, SymmetricOrdering::Amd, params).expect("symbolic");
    let par = faer::Par::Seq;
    let (t, c) = (Instant::now(), cpu_secs());
    let mut values = vec![0.0; symbolic.len_val()];
    let mut mem = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
    symbolic
        .factorize_numeric_llt(
            &mut values,
            k.as_ref(),
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .expect("SPD");
    (t.elapsed().as_secs_f64(), cpu_secs() - c)
}
