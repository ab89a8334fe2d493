//! Progress of a solve: the stage it entered and the contact iterations, told to
//! a sink the caller installs on the solving thread.
//!
//! Like `cancel`'s deadline, the sink is a thread-local so the numerics keep
//! their signatures and do no I/O: the solve's observer calls [`stage`] at its stage
//! boundaries and the active-set loops call [`iteration`]; without a sink (the
//! CLI, the library) both are a thread-local read. The service installs a sink
//! that publishes each report on zenoh (`service::progress`). The guard puts the
//! previous sink back on drop, also when unwinding.

use std::cell::RefCell;
use std::time::Instant;

/// One report: the stage being run, and within `contact_solve` the iteration
/// and its residual (the largest |min(λ_i, w_i)|, 0 at the solution; nondimensional).
#[derive(Debug, Clone, PartialEq)]
pub struct Progress {
    pub stage: &'static str,
    pub iteration: Option<usize>,
    pub residual: Option<f64>,
    /// Seconds since the sink was installed.
    pub elapsed: f64,
    /// Predicted seconds of work done so far and in all (`plan`, `revise`):
    /// done / total is the fraction of the solve behind, which moves with the
    /// real work (a factorization that takes 80 % of the time is 80 % of the
    /// bar), and elapsed · (total − done) / done estimates what is left.
    /// Both 0 without a plan.
    pub done: f64,
    pub total: f64,
    /// The round of tolerance-driven refinement (from 1), when refining:
    /// each round's stages run from the start of the bar again.
    pub round: Option<usize>,
}

/// The stages in the order a condensed solve runs them (`factorization` and
/// `condensation` are skipped on a cache hit).
pub const STAGES: [&str; 6] = [
    "mesh",
    "assembly",
    "factorization",
    "condensation",
    "contact_solve",
    "post",
];

struct Installed {
    sink: Box<dyn FnMut(&Progress)>,
    start: Instant,
    stage: &'static str,
    /// Predicted seconds of each stage of `STAGES`.
    plan: [f64; 6],
    /// Contact iterations reported in the current stage.
    iterations: usize,
    /// Predicted seconds of the current stage already done (`credit`).
    credit: f64,
    /// The part of `credit` told by `credit` itself (the rest by `within`).
    base: f64,
    /// When the sink was last told.
    told: Instant,
    round: Option<usize>,
}

/// Contact iterations a solve is expected to take (the Hertz scenes take 7 to
/// 10): each one counts as that share of the stage, up to 95 % of it.
const EXPECTED_ITERATIONS: f64 = 12.0;

impl Installed {
    fn done(&self) -> f64 {
        let k = STAGES.iter().position(|s| *s == self.stage).unwrap_or(0);
        let before: f64 = self.plan[..k].iter().sum();
        let within = if self.stage == "contact_solve" {
            (self.iterations as f64 / EXPECTED_ITERATIONS).min(0.95) * self.plan[k]
        } else {
            0.0
        };
        before + within + self.credit
    }
}

thread_local! {
    static SINK: RefCell<Option<Installed>> = const { RefCell::new(None) };
}

/// While alive, progress on this thread goes to `sink`.
#[must_use = "the sink is removed when the guard is dropped"]
pub struct Sink {
    previous: Option<Installed>,
}

impl Sink {
    pub fn install(sink: impl FnMut(&Progress) + 'static) -> Self {
        let new = Installed {
            sink: Box::new(sink),
            start: Instant::now(),
            stage: "",
            plan: [0.0; 6],
            iterations: 0,
            credit: 0.0,
            base: 0.0,
            told: Instant::now(),
            round: None,
        };
        Self {
            previous: SINK.with(|s| s.replace(Some(new))),
        }
    }
}

impl Drop for Sink {
    fn drop(&mut self) {
        let previous = self.previous.take();
        SINK.with(|s| *s.borrow_mut() = previous);
    }
}

fn emit(stage: Option<&'static str>, iteration: Option<usize>, residual: Option<f64>) {
    SINK.with(|s| {
        // A sink that reports progress itself would find the cell borrowed: skip, never panic.
        let Ok(mut slot) = s.try_borrow_mut() else { return };
        if let Some(i) = slot.as_mut() {
            if let Some(st) = stage {
                i.stage = st;
                i.iterations = 0;
                i.credit = 0.0;
                i.base = 0.0;
            }
            i.told = Instant::now();
            if let Some(k) = iteration {
                i.iterations = k;
            }
            let p = Progress {
                stage: i.stage,
                iteration,
                residual,
                elapsed: i.start.elapsed().as_secs_f64(),
                done: i.done(),
                total: i.plan.iter().sum(),
                round: i.round,
            };
            (i.sink)(&p);
        }
    });
}

/// The predicted seconds of every stage (in `STAGES` order), replacing any plan.
pub fn plan(seconds: [f64; 6]) {
    with_installed(|i| i.plan = seconds);
}

/// A better prediction of one stage, once the solve knows more (the
/// factorization's cost after its symbolic analysis; 0 for a stage the cache
/// skips).
pub fn revise(stage: &str, seconds: f64) {
    with_installed(|i| {
        if let Some(k) = STAGES.iter().position(|s| *s == stage) {
            i.plan[k] = seconds;
        }
    });
}

/// `seconds` of the current stage's predicted work are done (a part of it
/// that ran, such as the factorization's symbolic analysis).
pub fn credit(seconds: f64) {
    with_installed(|i| {
        i.credit = seconds;
        i.base = seconds;
    });
}

/// Least time between two reports of `within`: a bar that moves four times a
/// second, and a sink (zenoh, Python) that is not flooded.
const WITHIN_EVERY_S: f64 = 0.25;

/// `fraction` of the current stage's work after its `credit` is done (the
/// numeric factorization's share of multiply–adds): told to the sink at most
/// every `WITHIN_EVERY_S`.
pub fn within(fraction: f64) {
    let due = SINK.with(|s| {
        let Ok(mut slot) = s.try_borrow_mut() else { return false };
        let Some(i) = slot.as_mut() else { return false };
        let k = STAGES.iter().position(|s| *s == i.stage).unwrap_or(0);
        i.credit = i.base + fraction.clamp(0.0, 1.0) * (i.plan[k] - i.base).max(0.0);
        i.told.elapsed().as_secs_f64() >= WITHIN_EVERY_S
    });
    if due {
        emit(None, None, None);
    }
}

fn with_installed(f: impl FnOnce(&mut Installed)) {
    SINK.with(|s| {
        if let Ok(mut slot) = s.try_borrow_mut() {
            if let Some(i) = slot.as_mut() {
                f(i);
            }
        }
    });
}

/// A report of where the solve stands (after a revision of the plan).
pub fn report() {
    emit(None, None, None);
}

/// The solve enters `name`.
pub fn stage(name: &'static str) {
    emit(Some(name), None, None);
}

/// Round `k` (from 1) of tolerance-driven refinement begins.
pub fn round(k: usize) {
    with_installed(|i| i.round = Some(k));
}

/// Iteration `k` of the current stage ended with `residual`.
pub fn iteration(k: usize, residual: f64) {
    emit(None, Some(k), Some(residual));
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::{Arc, Mutex};

    #[test]
    fn reports_go_to_the_installed_sink_in_order_and_stop_on_drop() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        {
            let s = seen.clone();
            let _g = Sink::install(move |p| s.lock().unwrap().push((p.stage, p.iteration)));
            stage("mesh");
            stage("contact_solve");
            iteration(1, 0.5);
        }
        stage("post");
        let seen = seen.lock().unwrap();
        assert_eq!(
            *seen,
            vec![("mesh", None), ("contact_solve", None), ("contact_solve", Some(1))]
        );
    }

    /// Within a stage the bar moves by the share of its work done after the
    /// credited part, and the sink hears of it at most every 0.25 s.
    #[test]
    fn a_long_stage_moves_the_bar_within_it() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s = seen.clone();
        let _g = Sink::install(move |p| s.lock().unwrap().push(p.done));
        plan([1.0, 1.0, 10.0, 0.0, 0.0, 0.0]);
        stage("factorization");
        credit(2.0);
        within(0.5);
        assert_eq!(seen.lock().unwrap().len(), 1, "no report sooner than 0.25 s");
        std::thread::sleep(std::time::Duration::from_millis(260));
        within(0.5);
        // mesh + assembly (2) + the credit (2) + half of the remaining 8.
        assert_eq!(*seen.lock().unwrap(), vec![2.0, 8.0]);
    }
}
