//! Shared service state and the `contact/health` reply: counters by outcome,
//! latency percentiles over a bounded ring of recent requests, and every limit.

use std::collections::{BTreeMap, VecDeque};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use serde::Serialize;

use super::ServiceConfig;

/// Latencies kept for the percentiles: the most recent requests only, so the
/// figures follow the current load and the memory is fixed.
pub const LATENCY_WINDOW: usize = 1024;

pub struct State {
    pub cfg: ServiceConfig,
    /// This process's zenoh id: the prefix of its request ids.
    pub instance: String,
    pub started: Instant,
    /// Requests admitted and not yet answered (waiting or running).
    pub pending: AtomicUsize,
    pub in_flight: AtomicUsize,
    /// Payload bytes at the door (arrived, not yet read into a scene).
    pub door_bytes: AtomicUsize,
    /// Requests being parsed and validated.
    pub reading: AtomicUsize,
    pub next_id: AtomicU64,
    pub workers: tokio::sync::Semaphore,
    /// Turns to parse and validate (`max_parses`).
    pub parses: tokio::sync::Semaphore,
    pub cache: crate::cache::OperatorCache,
    /// The session progress is published on (set once it is open).
    pub publisher: std::sync::OnceLock<zenoh::Session>,
    stats: Mutex<Stats>,
}

#[derive(Default)]
struct Stats {
    /// Replies by outcome: the reply's `status` or the error's `code`.
    outcomes: BTreeMap<String, u64>,
    panics: u64,
    /// Seconds from arrival to reply of the last `LATENCY_WINDOW` admitted requests.
    latencies: VecDeque<f64>,
    /// Seconds from arrival to the reply handed to zenoh of the last
    /// `LATENCY_WINDOW` `busy` answers.
    busy_latencies: VecDeque<f64>,
}

#[derive(Serialize)]
pub struct Health {
    pub version: &'static str,
    pub protocol: &'static str,
    pub instance: String,
    pub uptime_s: f64,
    /// Admitted requests waiting for a worker (or being read).
    pub queue_depth: usize,
    pub in_flight: usize,
    /// Requests being parsed and validated, and the payload bytes at the door.
    pub reading: usize,
    pub door_bytes: usize,
    pub workers: usize,
    /// Successful replies (any `status`).
    pub solves_served: u64,
    /// Error replies, `busy` included.
    pub errors_served: u64,
    pub rejected_busy: u64,
    pub panics: u64,
    /// Replies by outcome: `solved`, `max_iterations`, `numerical_error`, or an error code.
    pub outcomes: BTreeMap<String, u64>,
    pub latency_s: Latency,
    /// Of the `busy` answers: from the query's arrival to its reply handed to
    /// zenoh (the link's time to the client comes on top).
    pub busy_latency_s: Latency,
    pub limits: LimitsReport,
    pub cache_entries: usize,
    pub cache_bytes: usize,
    /// Real / predicted time of the numeric factorization on this machine
    /// (measured at start-up, learned from every factorization since): what
    /// the factorization's prediction, and so the refusal of a
    /// factorization that cannot end in time, is scaled by.
    pub factorization_scale: f64,
}

/// Percentiles (nearest rank) of the recent window; all 0 before the first request.
#[derive(Serialize, Debug, PartialEq)]
pub struct Latency {
    pub window: usize,
    pub p50: f64,
    pub p90: f64,
    pub p99: f64,
    pub max: f64,
}

#[derive(Serialize)]
pub struct LimitsReport {
    pub queue_limit: usize,
    pub max_request_bytes: usize,
    pub max_parses: usize,
    pub max_door_bytes: usize,
    pub max_dofs: usize,
    pub max_candidates: usize,
    pub max_load_steps: usize,
    pub max_output_values: usize,
    pub max_solve_time_s: f64,
    pub cache_limit_bytes: usize,
}

impl State {
    pub fn new(cfg: ServiceConfig, instance: String) -> Self {
        let workers = tokio::sync::Semaphore::new(cfg.workers.max(1));
        let parses = tokio::sync::Semaphore::new(cfg.max_parses.max(1));
        let cache = crate::cache::OperatorCache::new(cfg.cache_bytes);
        Self {
            cfg,
            instance,
            started: Instant::now(),
            pending: AtomicUsize::new(0),
            in_flight: AtomicUsize::new(0),
            door_bytes: AtomicUsize::new(0),
            reading: AtomicUsize::new(0),
            next_id: AtomicU64::new(1),
            workers,
            parses,
            cache,
            publisher: std::sync::OnceLock::new(),
            stats: Mutex::new(Stats::default()),
        }
    }

    /// Counts one reply; `latency` is None for requests answered without admission (busy).
    pub fn record(&self, outcome: &str, latency: Option<Duration>, panicked: bool) {
        let mut s = self.stats.lock().unwrap_or_else(|p| p.into_inner());
        *s.outcomes.entry(outcome.to_string()).or_default() += 1;
        s.panics += u64::from(panicked);
        if let Some(l) = latency {
            push_bounded(&mut s.latencies, l);
        }
    }

    /// Counts the latency of one `busy` answer (its outcome goes through `record`).
    pub fn record_busy(&self, latency: Duration) {
        let mut s = self.stats.lock().unwrap_or_else(|p| p.into_inner());
        push_bounded(&mut s.busy_latencies, latency);
    }

    pub fn health(&self) -> Health {
        let pending = self.pending.load(Ordering::SeqCst);
        let in_flight = self.in_flight.load(Ordering::SeqCst);
        let (outcomes, panics, latency_s, busy_latency_s) = {
            let s = self.stats.lock().unwrap_or_else(|p| p.into_inner());
            (
                s.outcomes.clone(),
                s.panics,
                percentiles(s.latencies.iter().copied().collect()),
                percentiles(s.busy_latencies.iter().copied().collect()),
            )
        };
        let ok: u64 = OK_STATUSES.iter().filter_map(|k| outcomes.get(*k)).sum();
        let all: u64 = outcomes.values().sum();
        let cfg = &self.cfg;
        Health {
            version: env!("CARGO_PKG_VERSION"),
            protocol: crate::proto::PROTOCOL_VERSION,
            instance: self.instance.clone(),
            uptime_s: self.started.elapsed().as_secs_f64(),
            queue_depth: pending.saturating_sub(in_flight),
            in_flight,
            reading: self.reading.load(Ordering::SeqCst),
            door_bytes: self.door_bytes.load(Ordering::SeqCst),
            workers: cfg.workers,
            solves_served: ok,
            errors_served: all - ok,
            rejected_busy: outcomes.get("busy").copied().unwrap_or(0),
            panics,
            outcomes,
            latency_s,
            busy_latency_s,
            limits: LimitsReport {
                queue_limit: cfg.queue_limit,
                max_request_bytes: cfg.max_request_bytes,
                max_parses: cfg.max_parses,
                max_door_bytes: cfg.max_door_bytes,
                max_dofs: cfg.limits.max_dofs,
                max_candidates: cfg.limits.max_candidates,
                max_load_steps: cfg.limits.max_load_steps,
                max_output_values: cfg.limits.max_output_values,
                max_solve_time_s: cfg.max_solve_time.as_secs_f64(),
                cache_limit_bytes: cfg.cache_bytes,
            },
            cache_entries: self.cache.len(),
            cache_bytes: self.cache.bytes(),
            factorization_scale: contact_core::linalg::rate::scale(),
        }
    }
}

/// The `status` values of a successful reply (everything else is an error code).
const OK_STATUSES: [&str; 3] = ["solved", "max_iterations", "numerical_error"];

fn push_bounded(window: &mut VecDeque<f64>, latency: Duration) {
    if window.len() == LATENCY_WINDOW {
        window.pop_front();
    }
    window.push_back(latency.as_secs_f64());
}

fn percentiles(mut v: Vec<f64>) -> Latency {
    v.sort_by(f64::total_cmp);
    let rank = |p: f64| match v.len() {
        0 => 0.0,
        n => v[((p * n as f64).ceil() as usize).clamp(1, n) - 1],
    };
    Latency {
        window: v.len(),
        p50: rank(0.50),
        p90: rank(0.90),
        p99: rank(0.99),
        max: rank(1.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_are_nearest_rank() {
        let l = percentiles((1..=100).rev().map(f64::from).collect());
        assert_eq!(
            l,
            Latency {
                window: 100,
                p50: 50.0,
                p90: 90.0,
                p99: 99.0,
                max: 100.0
            }
        );
        assert_eq!(percentiles(vec![]).max, 0.0);
        assert_eq!(percentiles(vec![2.5]).p50, 2.5);
    }

    #[test]
    fn outcomes_are_counted_and_the_window_is_bounded() {
        let s = State::new(ServiceConfig::default(), "test".into());
        for i in 0..LATENCY_WINDOW + 10 {
            s.record("solved", Some(Duration::from_millis(i as u64)), false);
        }
        s.record("busy", None, false);
        s.record("internal_error", Some(Duration::from_secs(100)), true);
        let h = s.health();
        assert_eq!(h.solves_served, LATENCY_WINDOW as u64 + 10);
        assert_eq!(h.errors_served, 2);
        assert_eq!((h.rejected_busy, h.panics), (1, 1));
        assert_eq!(h.outcomes["internal_error"], 1);
        assert_eq!(h.latency_s.window, LATENCY_WINDOW);
        assert_eq!(h.latency_s.max, 100.0);
        // 0..=10 ms have left the window: it holds 11..=1033 ms and 100 s; rank 512 is 522 ms.
        assert_eq!(h.latency_s.p50, Duration::from_millis(522).as_secs_f64());
    }
}
