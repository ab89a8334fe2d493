//! Admission control and the blocking worker pool.
//!
//! On arrival a request over `max_request_bytes` is answered `too_large`
//! without parsing, and the others are parsed and validated on a blocking
//! thread outside the worker pool (`wire::check_bytes`), so that a bad
//! request is answered at once whatever the queue holds. A valid request is
//! admitted when fewer than `workers + queue_limit` are pending, otherwise
//! answered `busy` at once with the queue depth. Admitted requests wait for a
//! worker permit and run `wire::solve_bytes_cached` (with the
//! shared operator cache) on a blocking thread under a deadline of
//! `max_solve_time` (`cancel`: answered `timeout`, the thread is free again)
//! and `catch_unwind` (a panic is answered `internal_error` and logged with the
//! request id; the process goes on). Every reply carries the request id
//! `<instance>-<n>`, and the client's `client_id` when it could be read.

use std::panic::AssertUnwindSafe;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde::Serialize;
use zenoh::query::Query;

use super::health::State;
use crate::proto::{ErrorCode, ErrorReply, SolveReply};

/// What goes back on the wire: `Ok` for `reply`, `Err` for `reply_err`.
type Body = Result<Vec<u8>, Vec<u8>>;

/// Answers one query on `contact/solve`; `key` is the queryable's own key (replies go there).
pub fn dispatch(query: Query, key: &'static str, state: Arc<State>) {
    let arrived = Instant::now();
    let id = format!("{}-{}", state.instance, state.next_id.fetch_add(1, Ordering::Relaxed));
    tokio::spawn(async move {
        let payload: Vec<u8> = query.payload().map(|p| p.to_bytes().into_owned()).unwrap_or_default();
        // Refusals come first and at once, outside the queue: a malformed or
        // invalid request never waits behind solves (measured 0.54 s p50
        // under load when parsing ran in the queue, 1 ms alone).
        if let Some(err) = refusal(&payload, &state).await {
            let (body, outcome) = wire(&id, Err(err));
            state.record(&outcome, Some(arrived.elapsed()), false);
            log_reply(&id, &outcome, arrived);
            send(&query, key, &id, body).await;
            return;
        }
        admit_and_solve(query, key, state, id, payload, arrived).await;
    });
}

/// The error reply a request gets before any solving: over the size limit, or
/// not parseable or not valid (checked on a blocking thread, outside the
/// worker pool: validation is bounded by the payload size).
async fn refusal(payload: &[u8], state: &Arc<State>) -> Option<ErrorReply> {
    if payload.len() > state.cfg.max_request_bytes {
        return Some(ErrorReply::new(
            ErrorCode::TooLarge,
            format!(
                "request of {} bytes exceeds the limit of {} bytes",
                payload.len(),
                state.cfg.max_request_bytes
            ),
            "",
        ));
    }
    let (bytes, limits) = (payload.to_vec(), state.cfg.limits);
    let checked = tokio::task::spawn_blocking(move || {
        std::panic::catch_unwind(AssertUnwindSafe(|| crate::wire::check_bytes(&bytes, &limits)))
    })
    .await;
    match checked {
        Ok(Ok(Ok(()))) => None,
        Ok(Ok(Err(err))) => Some(err),
        // A panic in validation is left to the solve, which reports it with its id.
        _ => None,
    }
}

fn log_reply(id: &str, outcome: &str, arrived: Instant) {
    tracing::info!(
        request_id = %id,
        outcome = %outcome,
        latency_ms = arrived.elapsed().as_secs_f64() * 1e3,
        "reply"
    );
}

/// A valid request: `busy` past the queue limit, else queued for a worker.
async fn admit_and_solve(
    query: Query,
    key: &'static str,
    state: Arc<State>,
    id: String,
    payload: Vec<u8>,
    arrived: Instant,
) {
    let Some(admitted) = admit(&state) else {
        let (pending, running) = (
            state.pending.load(Ordering::SeqCst),
            state.in_flight.load(Ordering::SeqCst),
        );
        // Other refused requests may hold a slot for an instant: never report
        // more queued than the queue can hold.
        let depth = pending.saturating_sub(running).min(state.cfg.queue_limit);
        let mut err = ErrorReply::new(
            ErrorCode::Busy,
            format!(
                "service busy: {depth} requests queued (limit {}) and {running} solving; retry later",
                state.cfg.queue_limit
            ),
            "",
        );
        err.queue_depth = Some(u32::try_from(depth).unwrap_or(u32::MAX));
        let (body, outcome) = wire(&id, Err(err));
        state.record(&outcome, None, false);
        send(&query, key, &id, body).await;
        return;
    };
    let (body, outcome, panicked) = solve_on_worker(payload, &state, &id).await;
    state.record(&outcome, Some(arrived.elapsed()), panicked);
    log_reply(&id, &outcome, arrived);
    send(&query, key, &id, body).await;
    drop(admitted);
}

/// Waits for a worker permit, then solves on a blocking thread.
async fn solve_on_worker(payload: Vec<u8>, state: &Arc<State>, id: &str) -> (Body, String, bool) {
    let _permit = state.workers.acquire().await.expect("semaphore never closed");
    let _running = Counted::new(state, |s| &s.in_flight);
    let (st, rid) = (state.clone(), id.to_string());
    let joined = tokio::task::spawn_blocking(move || {
        let _progress = st
            .publisher
            .get()
            .map(|s| super::progress::install(s.clone(), super::progress::key_for(&payload, &rid), rid.clone()));
        let (result, panicked) = run_isolated(&rid, st.cfg.max_solve_time, || {
            let cache = (st.cfg.cache_bytes > 0).then_some(&st.cache);
            crate::wire::solve_bytes_cached(&payload, &st.cfg.limits, cache)
        });
        drop(payload);
        let (body, outcome) = wire(&rid, result);
        (body, outcome, panicked)
    })
    .await;
    joined.unwrap_or_else(|e| {
        tracing::error!(request_id = %id, "worker task failed: {e}");
        let (body, outcome) = wire(id, Err(internal_error(id)));
        (body, outcome, true)
    })
}

/// Runs `solve` under a deadline of `limit` and `catch_unwind`; a panic becomes
/// `internal_error` (second value true), logged with the request id.
pub fn run_isolated(
    id: &str,
    limit: Duration,
    solve: impl FnOnce() -> Result<SolveReply, ErrorReply>,
) -> (Result<SolveReply, ErrorReply>, bool) {
    let _deadline = crate::cancel::Deadline::install(limit);
    match std::panic::catch_unwind(AssertUnwindSafe(solve)) {
        Ok(result) => (result, false),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "non-text panic payload".into());
            tracing::error!(request_id = %id, panic = %what, "solve panicked; answered internal_error");
            (Err(internal_error(id)), true)
        }
    }
}

fn internal_error(id: &str) -> ErrorReply {
    ErrorReply::new(
        ErrorCode::InternalError,
        format!("internal error while solving request {id} (a bug, logged with this id); the service goes on"),
        "",
    )
}

/// Stamps the request id, serializes, and names the outcome (reply status or error code).
fn wire(id: &str, result: Result<SolveReply, ErrorReply>) -> (Body, String) {
    match result {
        Ok(mut reply) => {
            reply.request_id = Some(id.to_string());
            let outcome = snake(&reply.status);
            match serde_json::to_vec(&reply) {
                Ok(bytes) => (Ok(bytes), outcome),
                Err(e) => {
                    tracing::error!(request_id = %id, "reply not serializable: {e}");
                    wire(id, Err(internal_error(id)))
                }
            }
        }
        Err(mut err) => {
            err.request_id = Some(id.into());
            if err.code != ErrorCode::Busy {
                tracing::info!(request_id = %id, code = ?err.code, path = %err.path, "error reply: {}", err.message);
            }
            let outcome = snake(&err.code);
            (Err(serde_json::to_vec(&err).unwrap_or_default()), outcome)
        }
    }
}

/// The snake_case wire name of a unit enum value.
fn snake<T: Serialize>(v: &T) -> String {
    serde_json::to_value(v)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

async fn send(query: &Query, key: &str, id: &str, body: Body) {
    let outcome = match body {
        Ok(bytes) => query.reply(key, bytes).await,
        Err(bytes) => query.reply_err(bytes).await,
    };
    if let Err(e) = outcome {
        tracing::warn!(request_id = %id, "reply failed: {e}");
    }
}

/// A slot of `pending`, taken only while under `workers + queue_limit` and
/// given back on drop, whatever path the request takes.
fn admit(state: &Arc<State>) -> Option<Counted> {
    let capacity = state.cfg.workers + state.cfg.queue_limit;
    let slot = Counted::new(state, |s| &s.pending);
    (slot.before < capacity).then_some(slot)
}

/// +1 on a counter of the state for the guard's life.
struct Counted {
    state: Arc<State>,
    counter: fn(&State) -> &std::sync::atomic::AtomicUsize,
    before: usize,
}

impl Counted {
    fn new(state: &Arc<State>, counter: fn(&State) -> &std::sync::atomic::AtomicUsize) -> Self {
        let before = counter(state).fetch_add(1, Ordering::SeqCst);
        Self {
            state: state.clone(),
            counter,
            before,
        }
    }
}

impl Drop for Counted {
    fn drop(&mut self) {
        (self.counter)(&self.state).fetch_sub(1, Ordering::SeqCst);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panicking_solve_is_an_internal_error_with_the_request_id() {
        let (result, panicked) = run_isolated("inst-7", Duration::from_secs(60), || panic!("injected fault"));
        assert!(panicked);
        let err = result.unwrap_err();
        assert_eq!(err.code, ErrorCode::InternalError);
        assert!(err.message.contains("inst-7"), "{}", err.message);
        let (body, outcome) = wire("inst-7", Err(err));
        assert_eq!(outcome, "internal_error");
        let json: serde_json::Value = serde_json::from_slice(&body.unwrap_err()).unwrap();
        assert_eq!(json["request_id"], "inst-7");
        // The thread goes on, without the panicking solve's deadline.
        assert!(crate::cancel::check("post").is_ok());
    }

    #[test]
    fn an_expired_deadline_is_answered_timeout_and_lifted() {
        let example = concat!(
            concat!(env!("CARGO_MANIFEST_DIR"), "/../.."),
            "/proto/examples/signorini_hertz_cylinder.json"
        );
        let bytes = std::fs::read(example).unwrap();
        let limits = crate::scene::Limits::default();
        let (result, panicked) = run_isolated("inst-8", Duration::ZERO, || crate::wire::solve_bytes(&bytes, &limits));
        assert!(!panicked);
        let err = result.unwrap_err();
        assert_eq!(err.code, ErrorCode::Timeout);
        assert!(err.message.contains("'mesh'"), "{}", err.message);
        assert!(crate::cancel::check("mesh").is_ok());
    }

    #[test]
    fn admission_stops_at_workers_plus_queue_and_gives_slots_back() {
        let cfg = super::super::ServiceConfig {
            workers: 1,
            queue_limit: 1,
            ..Default::default()
        };
        let state = Arc::new(State::new(cfg, "t".into()));
        let a = admit(&state).expect("first");
        let b = admit(&state).expect("second");
        assert!(admit(&state).is_none(), "third must be refused");
        assert_eq!(
            state.pending.load(Ordering::SeqCst),
            2,
            "a refusal leaves no slot taken"
        );
        drop(a);
        let c = admit(&state).expect("a slot came back");
        drop((b, c));
        assert_eq!(state.pending.load(Ordering::SeqCst), 0);
    }
}
