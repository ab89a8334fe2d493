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
use std::rc::Rc;
use std::time::Instant;

pub use crate::outcome::ProgressStage;

/// One report: the stage being run, and within `contact_solve` the iteration
/// and its residual (the largest |min(λ_i, w_i)|, 0 at the solution; nondimensional).
#[derive(Debug, Clone, PartialEq)]
pub struct Progress {
    pub stage: ProgressStage,
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
pub const STAGES: [ProgressStage; 6] = [
    ProgressStage::Mesh,
    ProgressStage::Assembly,
    ProgressStage::Factorization,
    ProgressStage::Condensation,
    ProgressStage::ContactSolve,
    ProgressStage::Post,
];

/// The stage after `STAGES` when the reply's error is estimated: the
/// companion solve (`adapt::estimate`), whose own stages move the bar across
/// this one's share of the plan (`Sink::nested`). Without it the bar sat at
/// the end of `post` for the whole companion solve, up to five times the
/// solve's own time on a given mesh.
pub const ESTIMATE: ProgressStage = ProgressStage::Estimate;

struct Installed {
    sink: Box<dyn FnMut(&Progress)>,
    start: Instant,
    /// The stage entered last (`Mesh` before the first).
    stage: ProgressStage,
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
    /// Predicted seconds of the `ESTIMATE` stage over those of `plan`.
    estimate_share: f64,
}

/// Contact iterations a solve is expected to take (the Hertz scenes take 7 to
/// 10): each one counts as that share of the stage, up to 95 % of it.
const EXPECTED_ITERATIONS: f64 = 12.0;

impl Installed {
    fn new(sink: Box<dyn FnMut(&Progress)>) -> Self {
        Self {
            sink,
            start: Instant::now(),
            stage: ProgressStage::Mesh,
            plan: [0.0; 6],
            iterations: 0,
            credit: 0.0,
            base: 0.0,
            told: Instant::now(),
            round: None,
            estimate_share: 0.0,
        }
    }

    fn done(&self) -> f64 {
        if self.stage == ESTIMATE {
            return self.plan.iter().sum::<f64>() + self.credit;
        }
        let k = STAGES.iter().position(|s| *s == self.stage).unwrap_or(0);
        let before: f64 = self.plan[..k].iter().sum();
        let within = if self.stage == ProgressStage::ContactSolve {
            (self.iterations as f64 / EXPECTED_ITERATIONS).min(0.95) * self.plan[k]
        } else {
            0.0
        };
        before + within + self.credit
    }

    /// Predicted seconds of the current stage.
    fn current(&self) -> f64 {
        if self.stage == ESTIMATE {
            return self.estimate_share * self.plan.iter().sum::<f64>();
        }
        self.plan[STAGES.iter().position(|s| *s == self.stage).unwrap_or(0)]
    }

    fn total(&self) -> f64 {
        (1.0 + self.estimate_share) * self.plan.iter().sum::<f64>()
    }

    fn tell(&mut self, iteration: Option<usize>, residual: Option<f64>) {
        self.told = Instant::now();
        let p = Progress {
            stage: self.stage,
            iteration,
            residual,
            elapsed: self.start.elapsed().as_secs_f64(),
            done: self.done(),
            total: self.total(),
            round: self.round,
        };
        (self.sink)(&p);
    }
}

thread_local! {
    static SINK: RefCell<Option<Installed>> = const { RefCell::new(None) };
}

/// While alive, progress on this thread goes to `sink`.
#[must_use = "the sink is removed when the guard is dropped"]
pub struct Sink {
    previous: Option<Installed>,
    /// `nested`: the sink it reports to, put back on drop.
    outer: Option<Rc<RefCell<Option<Installed>>>>,
}

impl Sink {
    pub fn install(sink: impl FnMut(&Progress) + 'static) -> Self {
        Self {
            previous: SINK.with(|s| s.replace(Some(Installed::new(Box::new(sink))))),
            outer: None,
        }
    }

    /// While alive, a solve run inside the current one (the error estimate's
    /// companion) moves the current sink's bar across its current stage by
    /// the inner solve's own fraction done, told at most every
    /// `WITHIN_EVERY_S`: the inner stages would restart the bar.
    pub fn nested() -> Self {
        let Some(outer) = SINK.with(|s| s.try_borrow_mut().ok().and_then(|mut slot| slot.take())) else {
            return Self::install(|_| {});
        };
        let shared = Rc::new(RefCell::new(Some(outer)));
        let to = shared.clone();
        let inner = Installed::new(Box::new(move |p: &Progress| {
            if p.total <= 0.0 {
                return;
            }
            let Ok(mut slot) = to.try_borrow_mut() else { return };
            let Some(o) = slot.as_mut() else { return };
            // Forward only: the inner plan's revision (its factorization's
            // cost once analysed) can lower its fraction done.
            o.credit = o.credit.max((p.done / p.total).clamp(0.0, 1.0) * o.current());
            if o.told.elapsed().as_secs_f64() >= WITHIN_EVERY_S {
                o.tell(None, None);
            }
        }));
        SINK.with(|s| *s.borrow_mut() = Some(inner));
        Self {
            previous: None,
            outer: Some(shared),
        }
    }
}

impl Drop for Sink {
    fn drop(&mut self) {
        let previous = match self.outer.take() {
            Some(shared) => shared.borrow_mut().take(),
            None => self.previous.take(),
        };
        SINK.with(|s| *s.borrow_mut() = previous);
    }
}

fn emit(stage: Option<ProgressStage>, iteration: Option<usize>, residual: Option<f64>) {
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
            if let Some(k) = iteration {
                i.iterations = k;
            }
            i.tell(iteration, residual);
        }
    });
}

/// The predicted seconds of every stage (in `STAGES` order), replacing any plan.
pub fn plan(seconds: [f64; 6]) {
    with_installed(|i| i.plan = seconds);
}

/// The solve will end with the `ESTIMATE` stage, predicted to take `share`
/// of the planned stages' time (kept when the plan is replaced).
pub fn expect_estimate(share: f64) {
    with_installed(|i| i.estimate_share = share.max(0.0));
}

/// A better prediction of one stage, once the solve knows more (the
/// factorization's cost after its symbolic analysis; 0 for a stage the cache
/// skips).
pub fn revise(stage: ProgressStage, seconds: f64) {
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
        i.credit = i.base + fraction.clamp(0.0, 1.0) * (i.current() - i.base).max(0.0);
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
pub fn stage(name: ProgressStage) {
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

    /// Every stage a solve can report is in the plan or is the estimate's,
    /// once: a stage added to `ProgressStage` and not placed fails here.
    #[test]
    fn every_stage_is_planned_or_the_estimate() {
        let mut placed: Vec<ProgressStage> = STAGES.to_vec();
        placed.push(ESTIMATE);
        assert_eq!(placed.len(), ProgressStage::ALL.len());
        for s in ProgressStage::ALL {
            assert_eq!(placed.iter().filter(|&&p| p == *s).count(), 1, "{s}");
        }
    }

    #[test]
    fn reports_go_to_the_installed_sink_in_order_and_stop_on_drop() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        {
            let s = seen.clone();
            let _g = Sink::install(move |p| s.lock().unwrap().push((p.stage, p.iteration)));
            stage(ProgressStage::Mesh);
            stage(ProgressStage::ContactSolve);
            iteration(1, 0.5);
        }
        stage(ProgressStage::Post);
        let seen = seen.lock().unwrap();
        assert_eq!(
            *seen,
            vec![
                (ProgressStage::Mesh, None),
                (ProgressStage::ContactSolve, None),
                (ProgressStage::ContactSolve, Some(1))
            ]
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
        stage(ProgressStage::Factorization);
        credit(2.0);
        within(0.5);
        assert_eq!(seen.lock().unwrap().len(), 1, "no report sooner than 0.25 s");
        std::thread::sleep(std::time::Duration::from_millis(260));
        within(0.5);
        // mesh + assembly (2) + the credit (2) + half of the remaining 8.
        assert_eq!(*seen.lock().unwrap(), vec![2.0, 8.0]);
    }

    /// The estimate's companion solve moves the caller's bar across the
    /// estimate's share by its own fraction done, under the stage name
    /// `estimate`, instead of restarting it; the caller's sink is back after.
    #[test]
    fn a_nested_solve_moves_the_bar_across_the_estimate() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s = seen.clone();
        let _g = Sink::install(move |p| s.lock().unwrap().push((p.stage, p.done, p.total)));
        plan([1.0; 6]);
        expect_estimate(0.5);
        stage(ProgressStage::Post);
        stage(ESTIMATE);
        {
            let _inner = Sink::nested();
            plan([1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
            stage(ProgressStage::Mesh);
            std::thread::sleep(std::time::Duration::from_millis(260));
            stage(ProgressStage::Post);
            // A revision that lowers the companion's fraction done (1 of 4)
            // does not move the bar back.
            std::thread::sleep(std::time::Duration::from_millis(260));
            revise(ProgressStage::Post, 3.0);
            report();
        }
        report();
        // 6 planned seconds and half of them again for the estimate (9); the
        // companion half done is half the estimate's 3.
        assert_eq!(
            *seen.lock().unwrap(),
            vec![
                (ProgressStage::Post, 5.0, 9.0),
                (ESTIMATE, 6.0, 9.0),
                (ESTIMATE, 7.5, 9.0),
                (ESTIMATE, 7.5, 9.0),
                (ESTIMATE, 7.5, 9.0)
            ]
        );
    }
}
