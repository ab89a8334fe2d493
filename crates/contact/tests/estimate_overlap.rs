//! The estimate's companion solved beside the answer (`adapt::overlap`)
//! changes the schedule, not the arithmetic: the reply is the one the
//! sequential schedule gives, and a companion that fails, or an answer that
//! fails while its companion runs, gives the reply kind it gave before.

mod common;

use std::sync::Mutex;
use std::time::Duration;

use common::{example, solve_with};
use contact::scene::{Limits, Overlap};
use contact_core::adapt::overlap;
use contact_core::solution::report::Report;
use contact_core::{CoreError, Scene};
use serde_json::Value;

fn limits(overlap: Overlap) -> Limits {
    Limits {
        overlap,
        ..Limits::default()
    }
}

/// Every number of `a` and `b` agrees to 1e-12 relative (the same operations
/// in the same order give the same bits; the margin only keeps the test
/// from naming the bit), every other value equal. Left out: `timings`, and
/// `diagnostics`, whose factorization prediction scales by a rate measured
/// on the running machine.
fn same(a: &Value, b: &Value, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!((x - y).abs() <= 1e-12 * x.abs().max(y.abs()), "{at}: {x} vs {y}");
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.keys().collect::<Vec<_>>(), y.keys().collect::<Vec<_>>(), "{at}");
            for (k, v) in x
                .iter()
                .filter(|(k, _)| !["timings", "diagnostics"].contains(&k.as_str()))
            {
                same(v, &y[k], &format!("{at}/{k}"));
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}");
            for (i, (u, v)) in x.iter().zip(y).enumerate() {
                same(u, v, &format!("{at}/{i}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

/// A generated mesh, a given (inline) one meshed again, a foundation, and a
/// frictional load path (its companion steps through the same path).
#[test]
fn the_reply_is_the_same_overlapped_or_not() {
    for name in [
        "signorini_hertz_cylinder.json",
        "signorini_inline_block_on_vee.json",
        "foundation_winkler_footing.json",
        "friction_roller_cattaneo_mindlin.json",
    ] {
        let req = example(name);
        let apart = solve_with(&req, &limits(Overlap::Off)).unwrap();
        let beside = solve_with(&req, &limits(Overlap::Always)).unwrap();
        assert!(
            apart.pairs.iter().all(|p| p.accuracy.is_some()),
            "{name}: every pair is estimated"
        );
        same(
            &serde_json::to_value(&apart).unwrap(),
            &serde_json::to_value(&beside).unwrap(),
            name,
        );
    }
}

fn scene(name: &str) -> Scene {
    let parsed: contact_proto::SolveRequest = serde_json::from_value(example(name)).unwrap();
    Scene::try_new(&parsed, &Limits::default()).unwrap()
}

/// A companion that fails beside the answer leaves the reply the sequential
/// schedule leaves: the answer, the zone ends alone, and the same note.
#[test]
fn a_companion_failing_beside_the_answer_gives_the_same_reply() {
    let scene = scene("signorini_hertz_cylinder.json");
    let lim = Limits::default();
    let answer = || contact_core::solve::solve_steps(&scene, &lim, None);
    let threads = Mutex::new(Vec::new());
    let failing = |_: &Scene| -> Result<Report, CoreError> {
        threads.lock().unwrap().push(std::thread::current().id());
        Err(CoreError::from(contact_core::cancel::Timeout {
            stage: contact_core::outcome::ProgressStage::Assembly,
            limit_s: 1.0,
            predicted: None,
        }))
    };
    let apart = overlap::solve_estimated(&scene, &limits(Overlap::Off), answer, &failing).unwrap();
    let beside = overlap::solve_estimated(&scene, &limits(Overlap::Always), answer, &failing).unwrap();
    let here = std::thread::current().id();
    let threads = threads.into_inner().unwrap();
    assert!(
        threads[0] == here && threads[1] != here,
        "the second ran beside: {threads:?}"
    );
    assert_eq!(apart.notes, beside.notes);
    assert!(
        apart.notes.iter().any(|n| n.text.contains("coarser solve")),
        "{:?}",
        apart.notes
    );
    for (a, b) in apart.pairs.iter().zip(&beside.pairs) {
        let (a, b) = (a.accuracy.as_ref().unwrap(), b.accuracy.as_ref().unwrap());
        assert_eq!(a.basis, contact_core::outcome::EstimateBasis::ZoneEdges);
        assert_eq!(
            (a.basis, a.pressure_l2, &a.zone_edges),
            (b.basis, b.pressure_l2, &b.zone_edges)
        );
    }
    assert_eq!(apart.energy.map(|e| e.relative()), beside.energy.map(|e| e.relative()));
}

/// An answer that fails while its companion runs returns its own error, and
/// the companion is told to stop (it would otherwise run to its end, here
/// for a minute).
#[test]
fn an_answer_failing_beside_its_companion_returns_its_own_error() {
    let scene = scene("signorini_hertz_cylinder.json");
    let timeout = contact_core::cancel::Timeout {
        stage: contact_core::outcome::ProgressStage::ContactSolve,
        limit_s: 2.0,
        predicted: None,
    };
    let answer = || -> Result<Report, CoreError> { Err(CoreError::from(timeout)) };
    let waiting = |_: &Scene| -> Result<Report, CoreError> {
        let start = std::time::Instant::now();
        while !contact_core::cancel::expired() {
            assert!(start.elapsed() < Duration::from_secs(60), "never told to stop");
            std::thread::sleep(Duration::from_millis(1));
        }
        Err(CoreError::from(timeout))
    };
    let r = overlap::solve_estimated(&scene, &limits(Overlap::Always), answer, &waiting);
    assert_eq!(
        r.err().map(|e| e.to_string()),
        Some(CoreError::from(timeout).to_string())
    );
}

/// A deadline that has passed gives a `timeout` reply on either schedule.
#[test]
fn a_passed_deadline_gives_a_timeout_either_way() {
    let req = example("signorini_hertz_cylinder.json");
    let _d = contact::cancel::Deadline::install(Duration::ZERO);
    for o in [Overlap::Off, Overlap::Always] {
        let e = solve_with(&req, &limits(o)).unwrap_err();
        assert_eq!(e.code, contact::proto::ErrorCode::Timeout, "{o:?}: {e:?}");
    }
}

/// The client's bar while the companion runs beside: the answer's stages in
/// order, then `estimate`, not moving back from the answer's end (the
/// companion's own stages are not told, so they cannot read as the answer's).
#[test]
fn the_bar_reads_the_answer_then_the_estimate() {
    use contact::progress::{Sink, ESTIMATE, STAGES};
    use std::sync::{Arc, Mutex};
    let seen = Arc::new(Mutex::new(Vec::new()));
    let s = seen.clone();
    let _g = Sink::install(move |p| s.lock().unwrap().push((p.stage, p.done, p.total)));
    solve_with(&example("signorini_hertz_cylinder.json"), &limits(Overlap::Always)).unwrap();
    let seen = seen.lock().unwrap();
    let mut stages: Vec<_> = seen.iter().map(|p| p.0).collect();
    stages.dedup();
    let mut expected = STAGES.to_vec();
    expected.push(ESTIMATE);
    assert_eq!(stages, expected);
    // From the answer's last report on (before it, the factorization's
    // revised cost can lower the fraction: the answer's own plan, as without
    // the companion).
    let first = seen.iter().position(|p| p.0 == ESTIMATE).unwrap();
    let done: Vec<f64> = seen[first - 1..].iter().map(|p| p.1 / p.2).collect();
    assert!(done.windows(2).all(|w| w[0] <= w[1]), "{done:?}");
}

/// A request over half the DOF limit solves its companion after the answer,
/// on the solving thread: both at once could pass the memory it was admitted
/// for (`adapt::overlap`'s module doc).
#[test]
fn a_request_over_half_the_dof_limit_is_not_overlapped() {
    let scene = scene("signorini_hertz_cylinder.json");
    let lim = Limits::default();
    let answer = || contact_core::solve::solve_steps(&scene, &lim, None);
    let dofs = answer().unwrap().size.dofs;
    let threads = Mutex::new(Vec::new());
    let companion = |s: &Scene| {
        threads.lock().unwrap().push(std::thread::current().id());
        contact_core::solve::solve_steps(s, &lim, None)
    };
    let tight = Limits {
        max_dofs: dofs * 3 / 2,
        ..limits(Overlap::Auto)
    };
    let r = overlap::solve_estimated(&scene, &tight, answer, &companion).unwrap();
    assert_eq!(*threads.lock().unwrap(), vec![std::thread::current().id()]);
    assert!(r
        .pairs
        .iter()
        .all(|p| p.accuracy.as_ref().unwrap().pressure_l2.is_some()));
}
