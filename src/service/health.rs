//! Shared service state and the `contact/health` reply.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::time::Instant;

use serde::Serialize;

use super::ServiceConfig;

pub struct State {
    pub cfg: ServiceConfig,
    pub started: Instant,
    /// Requests admitted and not yet answered (waiting or running).
    pub pending: AtomicUsize,
    pub in_flight: AtomicUsize,
    pub served_ok: AtomicU64,
    pub served_err: AtomicU64,
    pub rejected_busy: AtomicU64,
    pub panics: AtomicU64,
    pub next_id: AtomicU64,
    pub workers: tokio::sync::Semaphore,
    pub cache: crate::cache::OperatorCache,
}

#[derive(Serialize)]
pub struct Health {
    pub version: &'static str,
    pub protocol: &'static str,
    pub uptime_s: f64,
    pub solves_served: u64,
    pub errors_served: u64,
    pub rejected_busy: u64,
    pub panics: u64,
    pub queue_depth: usize,
    pub in_flight: usize,
    pub workers: usize,
    pub queue_limit: usize,
    pub max_request_bytes: usize,
    pub max_dofs: usize,
    pub max_candidates: usize,
    pub cache_entries: usize,
    pub cache_bytes: usize,
    pub cache_limit_bytes: usize,
}

impl State {
    pub fn new(cfg: ServiceConfig) -> Self {
        let workers = tokio::sync::Semaphore::new(cfg.workers.max(1));
        let cache = crate::cache::OperatorCache::new(cfg.cache_bytes);
        Self {
            cfg,
            started: Instant::now(),
            pending: AtomicUsize::new(0),
            in_flight: AtomicUsize::new(0),
            served_ok: AtomicU64::new(0),
            served_err: AtomicU64::new(0),
            rejected_busy: AtomicU64::new(0),
            panics: AtomicU64::new(0),
            next_id: AtomicU64::new(1),
            workers,
            cache,
        }
    }

    pub fn health(&self) -> Health {
        let pending = self.pending.load(Ordering::Relaxed);
        let in_flight = self.in_flight.load(Ordering::Relaxed);
        Health {
            version: env!("CARGO_PKG_VERSION"),
            protocol: crate::proto::PROTOCOL_VERSION,
            uptime_s: self.started.elapsed().as_secs_f64(),
            solves_served: self.served_ok.load(Ordering::Relaxed),
            errors_served: self.served_err.load(Ordering::Relaxed),
            rejected_busy: self.rejected_busy.load(Ordering::Relaxed),
            panics: self.panics.load(Ordering::Relaxed),
            queue_depth: pending.saturating_sub(in_flight),
            in_flight,
            workers: self.cfg.workers,
            queue_limit: self.cfg.queue_limit,
            max_request_bytes: self.cfg.max_request_bytes,
            max_dofs: self.cfg.limits.max_dofs,
            max_candidates: self.cfg.limits.max_candidates,
            cache_entries: self.cache.len(),
            cache_bytes: self.cache.bytes(),
            cache_limit_bytes: self.cfg.cache_bytes,
        }
    }
}
