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
            }
            let p = Progress {
                stage: i.stage,
                iteration,
                residual,
                elapsed: i.start.elapsed().as_secs_f64(),
            };
            (i.sink)(&p);
        }
    });
}

/// The solve enters `name`.
pub fn stage(name: &'static str) {
    emit(Some(name), None, None);
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
}
