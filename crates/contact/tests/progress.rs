//! Progress reports of a whole solve, as the service publishes them.

use std::sync::{Arc, Mutex};

use contact::progress::{Sink, ESTIMATE, STAGES};

#[test]
fn a_solve_reports_every_stage_in_order() {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let s = seen.clone();
    let _g = Sink::install(move |p| s.lock().unwrap().push(p.clone()));
    let example = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../proto/examples/signorini_roller_on_flat.json"
    );
    let reply = contact::solve_bytes(&std::fs::read(example).unwrap(), &contact::Limits::default()).unwrap();
    let seen = seen.lock().unwrap();
    let mut stages: Vec<_> = seen.iter().map(|p| p.stage).collect();
    stages.dedup();
    // The example's error is estimated (the default): its companion solve is
    // the last stage, and the bar ends where the plan does.
    let mut expected = STAGES.to_vec();
    expected.push(ESTIMATE);
    assert_eq!(stages, expected);
    let last = seen.last().unwrap();
    assert!(last.done <= last.total * (1.0 + 1e-12), "{last:?}");
    let iterations = seen.iter().filter(|p| p.iteration.is_some()).count();
    assert!(
        iterations >= 1 && iterations <= reply.iterations,
        "{iterations} vs {}",
        reply.iterations
    );
    let last = seen.iter().rev().find(|p| p.iteration.is_some()).unwrap();
    assert!(last.residual.unwrap() >= 0.0);
    assert!(seen.windows(2).all(|w| w[0].elapsed <= w[1].elapsed));
}

/// With `settings.accuracy`, every round's stages are reported under its
/// round number, rounds in order, and the estimate's coarser companion
/// reports as the round's last stage, `estimate` (its own stages silent: each
/// round runs the stages once).
#[test]
fn refinement_reports_each_round() {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let s = seen.clone();
    let _g = Sink::install(move |p| s.lock().unwrap().push(p.clone()));
    let mut req = contact_verify::convergence::disk_request(0.02, "t3");
    req["settings"] = serde_json::json!({"accuracy": {"pressure_l2": 0.005}});
    let reply = contact::solve_bytes(&serde_json::to_vec(&req).unwrap(), &contact::Limits::default()).unwrap();
    let rounds = reply.refinement.expect("rounds").rounds.len();
    assert!(rounds >= 2);
    let seen = seen.lock().unwrap();
    let numbers: Vec<usize> = seen.iter().map(|p| p.round.expect("a round number")).collect();
    assert!(numbers.windows(2).all(|w| w[0] <= w[1]), "{numbers:?}");
    for k in 1..=rounds {
        let mut stages: Vec<_> = seen.iter().filter(|p| p.round == Some(k)).map(|p| p.stage).collect();
        stages.dedup();
        let mut expected = STAGES.to_vec();
        expected.push(ESTIMATE);
        assert_eq!(stages, expected, "round {k}");
    }
}
