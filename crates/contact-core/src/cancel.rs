//! Cooperative cancellation: a deadline per solving thread.
//!
//! The service installs a [`Deadline`] on the blocking thread before it calls the
//! solve; the solve's observer calls [`check`] at its stage boundaries and the
//! iterative methods poll [`expired`] once per iteration (and Clarabel gets
//! [`remaining_secs`] as its own time limit). A solve over its time therefore
//! stops at the next boundary with [`Timeout`] (a `CoreError::Timeout`), unwinding normally,
//! so everything it allocated is dropped and the thread is free again. The
//! numeric factorization polls between its supernode updates
//! (`linalg::numeric`), and the 3D nested dissection at every level of its
//! recursion (`solid::ordering`); what does not poll (faer's AMD ordering of
//! the plane scenes, one sparse sweep) runs to its end: the overshoot is at
//! most one such step.
//!
//! A thread-local rather than a parameter keeps the numerical signatures free of
//! service concerns; the guard restores the previous deadline on drop (also when
//! unwinding), so a reused worker thread never inherits a stale one. Without a
//! deadline (the CLI, the library) every check is a no-op.
//!
//! A helper thread that solves part of the same request (the estimate's
//! companion, `adapt::overlap`) takes the solving thread's clock with it
//! ([`handoff`]) and a stop flag the solving thread raises when its own solve
//! fails: the helper's checks then answer as if its time were up, so it ends
//! at its next check instead of solving for a reply that is already an error.

use std::cell::{Cell, RefCell};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

pub use crate::outcome::ProgressStage;

/// The deadline passed; `stage` is the one just finished or cut (it becomes
/// `CoreError::Timeout`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timeout {
    pub stage: ProgressStage,
    pub limit_s: f64,
    /// From `check_room`: the seconds the work not started was predicted to
    /// take and those left, the deadline not yet passed.
    pub predicted: Option<(f64, f64)>,
}

#[derive(Clone, Copy, Debug)]
struct Limit {
    at: Instant,
    limit: Duration,
}

thread_local! {
    static DEADLINE: Cell<Option<Limit>> = const { Cell::new(None) };
    /// The flag of a helper thread (`handoff`); None on a solving thread.
    static STOP: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

/// This thread's deadline and a fresh stop flag, for a helper thread
/// (`Handoff::install` there).
pub fn handoff() -> Handoff {
    Handoff {
        limit: DEADLINE.with(|d| d.get()),
        stop: Arc::new(AtomicBool::new(false)),
    }
}

/// A deadline and a stop flag on their way to a helper thread.
pub struct Handoff {
    limit: Option<Limit>,
    stop: Arc<AtomicBool>,
}

/// Raises a helper thread's stop flag.
pub struct Stopper(Arc<AtomicBool>);

impl Stopper {
    /// The helper's next check fails as if its deadline had passed.
    pub fn stop(&self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

impl Handoff {
    /// What raises the flag, kept by the thread that hands off.
    pub fn stopper(&self) -> Stopper {
        Stopper(self.stop.clone())
    }

    /// On the helper thread: the same clock (an earlier deadline already
    /// installed there wins, as with `Deadline::install`) and the flag, until
    /// the guard drops.
    pub fn install(self) -> Helper {
        let previous = DEADLINE.with(|d| d.get());
        let kept = match (previous, self.limit) {
            (Some(p), Some(l)) if p.at <= l.at => Some(p),
            (p, None) => p,
            (_, l) => l,
        };
        DEADLINE.with(|d| d.set(kept));
        Helper {
            previous,
            previous_stop: STOP.with(|s| s.replace(Some(self.stop))),
        }
    }
}

/// While alive, this thread keeps the clock and the flag it was handed.
#[must_use = "the deadline and the flag are lifted when the guard is dropped"]
pub struct Helper {
    previous: Option<Limit>,
    previous_stop: Option<Arc<AtomicBool>>,
}

impl Drop for Helper {
    fn drop(&mut self) {
        DEADLINE.with(|d| d.set(self.previous));
        STOP.with(|s| *s.borrow_mut() = self.previous_stop.take());
    }
}

/// Whether this helper thread was told to stop.
fn stopped() -> bool {
    STOP.with(|s| s.borrow().as_ref().is_some_and(|f| f.load(Ordering::Relaxed)))
}

/// While alive, solves on this thread are limited to `limit` from its creation
/// (or to an earlier deadline already installed).
#[must_use = "the deadline is lifted when the guard is dropped"]
pub struct Deadline {
    previous: Option<Limit>,
}

impl Deadline {
    pub fn install(limit: Duration) -> Self {
        Self::install_from(Instant::now(), limit)
    }

    /// As `install`, with the clock started at `start` (a request's arrival:
    /// its time in the queue counts against its limit).
    pub fn install_from(start: Instant, limit: Duration) -> Self {
        let new = Limit {
            at: start
                .checked_add(limit)
                .unwrap_or(start + Duration::from_secs(86_400 * 365)),
            limit,
        };
        let previous = DEADLINE.with(|d| d.get());
        let kept = match previous {
            Some(p) if p.at <= new.at => p,
            _ => new,
        };
        DEADLINE.with(|d| d.set(Some(kept)));
        Self { previous }
    }
}

impl Drop for Deadline {
    fn drop(&mut self) {
        DEADLINE.with(|d| d.set(self.previous));
    }
}

/// Whether this thread's deadline has passed (false without one).
pub fn expired() -> bool {
    stopped() || DEADLINE.with(|d| d.get()).is_some_and(|l| Instant::now() >= l.at)
}

/// `Err(Timeout)` naming `stage` (the one just finished or cut) once the deadline has passed.
pub fn check(stage: ProgressStage) -> Result<(), Timeout> {
    let limit = DEADLINE.with(|d| d.get());
    match limit {
        Some(l) if Instant::now() >= l.at => Err(Timeout {
            stage,
            limit_s: l.limit.as_secs_f64(),
            predicted: None,
        }),
        // A stopped helper's result is thrown away: the error only ends it.
        _ if stopped() => Err(Timeout {
            stage,
            limit_s: limit.map_or(0.0, |l| l.limit.as_secs_f64()),
            predicted: None,
        }),
        _ => Ok(()),
    }
}

/// `Err(Timeout)` naming `stage` when less than `secs` are left: work known
/// to take that long, and that does not poll, cannot end in time.
pub fn check_room(stage: ProgressStage, secs: f64) -> Result<(), Timeout> {
    if stopped() {
        return check(stage);
    }
    match DEADLINE.with(|d| d.get()) {
        Some(l) if remaining_secs() < secs => Err(Timeout {
            stage,
            limit_s: l.limit.as_secs_f64(),
            predicted: Some((secs, remaining_secs())),
        }),
        _ => Ok(()),
    }
}

/// Seconds left (infinite without a deadline; never negative).
pub fn remaining_secs() -> f64 {
    if stopped() {
        return 0.0;
    }
    match DEADLINE.with(|d| d.get()) {
        Some(l) => l.at.saturating_duration_since(Instant::now()).as_secs_f64(),
        None => f64::INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_deadline_never_expires() {
        assert!(!expired());
        assert!(check(ProgressStage::Mesh).is_ok());
        assert_eq!(remaining_secs(), f64::INFINITY);
    }

    #[test]
    fn a_passed_deadline_names_the_stage_and_is_lifted_on_drop() {
        {
            let _d = Deadline::install(Duration::ZERO);
            assert!(expired());
            match check(ProgressStage::Assembly) {
                Err(Timeout { stage, limit_s, .. }) => {
                    assert_eq!(stage, "assembly");
                    assert_eq!(limit_s, 0.0);
                }
                other => panic!("expected a timeout, got {other:?}"),
            }
        }
        assert!(check(ProgressStage::Assembly).is_ok());
    }

    #[test]
    fn work_longer_than_the_time_left_is_not_started() {
        assert!(
            check_room(ProgressStage::Factorization, 1e9).is_ok(),
            "no deadline, no limit"
        );
        let _d = Deadline::install(Duration::from_secs(3600));
        assert!(check_room(ProgressStage::Factorization, 1.0).is_ok());
        let t = check_room(ProgressStage::Factorization, 7200.0).unwrap_err();
        assert_eq!((t.stage, t.limit_s), (ProgressStage::Factorization, 3600.0));
        // The limit not yet passed: the reply says what was predicted.
        let (needed, left) = t.predicted.expect("a prediction");
        assert!(needed == 7200.0 && left > 3500.0 && left <= 3600.0, "{needed} {left}");
        let e = crate::error::CoreError::from(t).to_string();
        assert!(e.contains("was not started") && !e.contains("exceeded"), "{e}");
    }

    /// A helper thread keeps the solving thread's clock, stops when told,
    /// and leaves its thread as it found it.
    #[test]
    fn a_helper_keeps_the_clock_and_stops_when_told() {
        let _d = Deadline::install(Duration::from_secs(3600));
        let handoff = handoff();
        let stopper = handoff.stopper();
        std::thread::scope(|s| {
            s.spawn(move || {
                {
                    let _h = handoff.install();
                    let left = remaining_secs();
                    assert!(left > 3500.0 && left <= 3600.0, "{left}");
                    assert!(check(ProgressStage::Mesh).is_ok() && !expired());
                    stopper.stop();
                    assert!(expired() && remaining_secs() == 0.0);
                    let t = check(ProgressStage::Assembly).unwrap_err();
                    assert_eq!((t.stage, t.limit_s), (ProgressStage::Assembly, 3600.0));
                    assert!(check_room(ProgressStage::Factorization, 0.0).is_err());
                }
                assert!(!expired() && remaining_secs() == f64::INFINITY);
            });
        });
        assert!(!expired(), "the solving thread's own checks are not stopped");
    }

    #[test]
    fn the_earlier_deadline_wins_and_nesting_restores() {
        let _outer = Deadline::install(Duration::ZERO);
        {
            let _inner = Deadline::install(Duration::from_secs(3600));
            assert!(expired(), "a later inner deadline must not extend the outer one");
        }
        assert!(expired());
        let _long = Deadline::install(Duration::from_secs(3600));
        assert!(expired());
    }
}
