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

use std::cell::Cell;
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
    DEADLINE.with(|d| d.get()).is_some_and(|l| Instant::now() >= l.at)
}

/// `Err(Timeout)` naming `stage` (the one just finished or cut) once the deadline has passed.
pub fn check(stage: ProgressStage) -> Result<(), Timeout> {
    match DEADLINE.with(|d| d.get()) {
        Some(l) if Instant::now() >= l.at => Err(Timeout {
            stage,
            limit_s: l.limit.as_secs_f64(),
            predicted: None,
        }),
        _ => Ok(()),
    }
}

/// `Err(Timeout)` naming `stage` when less than `secs` are left: work known
/// to take that long, and that does not poll, cannot end in time.
pub fn check_room(stage: ProgressStage, secs: f64) -> Result<(), Timeout> {
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
