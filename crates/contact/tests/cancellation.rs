//! Every iterative method stops at an expired deadline (and only then): the
//! per-iteration hooks of `contact::cancel`, below the stage checks that turn
//! such a cut into a `timeout` reply.

use std::time::Duration;

use contact::cancel::Deadline;
use contact_core::methods::{active_set, barrier, interior_point, penalty, LcpResult};
use contact_core::scene::Settings as SolverSettings;
use faer::Mat;

/// A 1D chain of springs pushed into a wavy floor: about half the candidates
/// touch, so every method needs several iterations.
fn lcp() -> (Mat<f64>, Vec<f64>) {
    let m = 60;
    let w = Mat::<f64>::from_fn(m, m, |i, j| match i.abs_diff(j) {
        0 => 2.0,
        1 => -0.9,
        _ => 0.0,
    });
    let q = (0..m)
        .map(|i| if i % 3 == 0 { 0.4 } else { -1.0 + 0.01 * i as f64 })
        .collect();
    (w, q)
}

const METHODS: [&str; 5] = [
    "active_set",
    "interior_point",
    "penalty",
    "augmented_lagrangian",
    "barrier",
];

fn solve(method: &str, w: &Mat<f64>, q: &[f64]) -> LcpResult {
    let s = SolverSettings::default();
    let ones = vec![1.0; q.len()];
    let d = penalty::springs(&ones, 1e-3);
    match method {
        "active_set" => active_set::solve_lcp(w, q, &s),
        "interior_point" => interior_point::solve_lcp(w, q, &s),
        "penalty" => penalty::solve_penalty(w, q, &d, &s),
        "augmented_lagrangian" => penalty::solve_augmented_lagrangian(w, q, &d, &s),
        _ => barrier::solve_barrier(w, q, &ones, 1e-6, &s),
    }
}

#[test]
fn every_method_converges_without_a_deadline_and_stops_at_an_expired_one() {
    let (w, q) = lcp();
    for name in METHODS {
        let free = solve(name, &w, &q);
        assert!(
            free.converged && free.iterations > 1,
            "{name}: {} iterations",
            free.iterations
        );
        let _expired = Deadline::install(Duration::ZERO);
        let cut = solve(name, &w, &q);
        assert!(!cut.converged, "{name} ignored the expired deadline");
    }
}
