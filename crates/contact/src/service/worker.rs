//! Admission control, the door and the blocking worker pool.
//!
//! On arrival, in zenoh's callback before anything is read or awaited (a
//! burst from one session: `busy` p50 4.5–8.4 ms, up to 45 ms, when this was
//! a task behind the queryable's channel): a payload over `max_request_bytes`
//! is answered `too_large`; a request that finds no worker or queue slot
//! (`workers + queue_limit` pending) is answered `busy` with the queue
//! depth; one whose payload would pass `max_door_bytes` of payloads not yet
//! read is answered `busy` too. The payload is taken out of the query at
//! once (the query lives until its reply, the payload only until it is
//! read). An admitted request then waits for one of `max_parses` turns and is
//! parsed and validated on a blocking thread (`wire::validate_bytes`: lists cut
//! at their limits, size estimates), so a bad request is answered as soon as
//! it is read, never behind the solves; a valid one hands its validated
//! scene to the queue, waits for a worker permit and runs
//! `wire::solve_validated` (with the shared operator cache) on a blocking
//! thread under a deadline of `max_solve_time` or the request's `time_limit`,
//! counted from its arrival (`cancel`: answered `timeout`, the thread is free
//! again; still queued at the deadline, answered `timeout` unsolved; a thread
//! that has not ended a short grace past it, starved on a loaded machine or
//! in a stage that does not poll, is answered `timeout` by a watchdog on the
//! runtime and keeps its worker until its next check stops it) and `catch_unwind` (a panic is answered
//! `internal_error` and logged with the request id; the process goes on). Every
//! reply carries the request id `<instance>-<n>`, and the client's
//! `client_id` when it could be read. Reads and solves run at a lower
//! scheduling priority than zenoh's threads (`priority`).
//!
//! Length: the door, admission, the read and the worker pool are one path of
//! a request; a third of the file is their unit tests.

use std::panic::AssertUnwindSafe;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde::Serialize;
use zenoh::bytes::ZBytes;
use zenoh::query::Query;
use zenoh::Wait;

use super::health::State;
use crate::proto::{ErrorCode, ErrorReply, SolveReply};
use crate::wire::Validated;

/// What goes back on the wire: `Ok` for `reply`, `Err` for `reply_err`.
type Body = Result<Vec<u8>, Vec<u8>>;

/// Answers one query on `contact/solve`; `key` is the queryable's own key
/// (replies go there). Called by zenoh on its receiving thread, which hands
/// one session's queries over one after the other: the size limit, admission
/// and the door are decided and a refusal is sent right here, before
/// anything is read or awaited, so that no query of a burst waits behind its
/// predecessors' tasks for its `busy`. Only an admitted request becomes a task
/// on `rt`.
pub fn dispatch(mut query: Query, key: &'static str, state: &Arc<State>, rt: &tokio::runtime::Handle) {
    let arrived = Instant::now();
    let id = format!("{}-{}", state.instance, state.next_id.fetch_add(1, Ordering::Relaxed));
    let payload = query.payload_mut().map(std::mem::take).unwrap_or_default();
    let admitted = match door(payload.len(), state) {
        Ok(admitted) => admitted,
        Err(err) => {
            let busy = err.code == ErrorCode::Busy;
            let (body, outcome) = wire(&id, Err(err));
            send_now(&query, key, &id, body);
            drop(query);
            // `busy` is not a served request: no log line, and its latency
            // (to the reply handed to zenoh) is kept apart.
            state.record(&outcome, (!busy).then(|| arrived.elapsed()), false);
            if busy {
                state.record_busy(arrived.elapsed());
            } else {
                log_reply(&id, &outcome, arrived);
            }
            return;
        }
    };
    let state = state.clone();
    rt.spawn(async move {
        let answer = answer(payload, admitted, &state, &id, arrived).await;
        state.record(&answer.outcome, Some(arrived.elapsed()), answer.panicked);
        log_reply(&id, &answer.outcome, arrived);
        send(&query, key, &id, answer.body).await;
    });
}

struct Answer {
    body: Body,
    outcome: String,
    panicked: bool,
}

impl Answer {
    fn error(id: &str, err: ErrorReply) -> Self {
        let (body, outcome) = wire(id, Err(err));
        Self {
            body,
            outcome,
            panicked: false,
        }
    }
}

/// A request let in: its queue slot and its payload's bytes at the door.
struct Admitted {
    _slot: Counted,
    held: DoorBytes,
}

/// The size limit, admission and the door, from the payload's length alone:
/// a few atomic operations.
fn door(len: usize, state: &Arc<State>) -> Result<Admitted, ErrorReply> {
    if len > state.cfg.max_request_bytes {
        return Err(ErrorReply::new(
            ErrorCode::TooLarge,
            format!(
                "request of {len} bytes exceeds the limit of {} bytes",
                state.cfg.max_request_bytes
            ),
            "",
        ));
    }
    // Turned away before anything is read (measured on main: a refusal after
    // validation had a `busy` p50 of 27–61 ms under overflow).
    let slot = admit(state).ok_or_else(|| busy(state, None))?;
    let held = DoorBytes::reserve(state, len).ok_or_else(|| busy(state, Some(len)))?;
    Ok(Admitted { _slot: slot, held })
}

/// Reads the admitted request, then solves it.
async fn answer(payload: ZBytes, admitted: Admitted, state: &Arc<State>, id: &str, arrived: Instant) -> Answer {
    let Admitted { _slot, held } = admitted;
    match read(payload, held, state).await {
        Ok(validated) => {
            let (body, outcome, panicked) = solve_on_worker(validated, state, id, arrived).await;
            Answer {
                body,
                outcome,
                panicked,
            }
        }
        Err((err, panicked)) => Answer {
            panicked,
            ..Answer::error(id, err)
        },
    }
}

/// `busy`, with the queue depth, and why when it is the door's byte budget
/// (`arriving`: the refused payload's size).
fn busy(state: &Arc<State>, arriving: Option<usize>) -> ErrorReply {
    let (pending, running) = (
        state.pending.load(Ordering::SeqCst),
        state.in_flight.load(Ordering::SeqCst),
    );
    // Other refused requests may hold a slot for an instant: never report
    // more queued than the queue can hold.
    let depth = pending.saturating_sub(running).min(state.cfg.queue_limit);
    let message = match arriving {
        None => format!(
            "service busy: {depth} requests queued (limit {}) and {running} solving; retry later",
            state.cfg.queue_limit
        ),
        Some(len) => format!(
            "service busy: {} bytes of requests are being read and {len} more would pass the limit of {} bytes; \
                retry later",
            state.door_bytes.load(Ordering::SeqCst),
            state.cfg.max_door_bytes
        ),
    };
    let mut err = ErrorReply::new(ErrorCode::Busy, message, "");
    err.queue_depth = Some(u32::try_from(depth).unwrap_or(u32::MAX));
    err
}

/// Parses and validates on a blocking thread, in one of `max_parses` turns;
/// the payload and its bytes at the door are let go when it has been read.
/// A panic is an internal error (true), logged.
async fn read(payload: ZBytes, held: DoorBytes, state: &Arc<State>) -> Result<Validated, (ErrorReply, bool)> {
    let _turn = state.parses.acquire().await.expect("semaphore never closed");
    let _reading = Counted::new(state, |s| &s.reading);
    let limits = state.cfg.limits;
    let read = tokio::task::spawn_blocking(move || {
        super::priority::lower_this_thread();
        let checked = std::panic::catch_unwind(AssertUnwindSafe(|| {
            crate::wire::validate_bytes(&payload.to_bytes(), &limits)
        }));
        drop((payload, held));
        checked
    })
    .await;
    match read {
        Ok(Ok(checked)) => checked.map_err(|e| (e, false)),
        Ok(Err(_)) | Err(_) => {
            tracing::error!("reading a request panicked; answered internal_error");
            Err((
                ErrorReply::new(
                    ErrorCode::InternalError,
                    "internal error while reading the request (a bug, logged); the service goes on",
                    "",
                ),
                true,
            ))
        }
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

/// Waits for a worker permit, then solves on a blocking thread. The limit,
/// the smaller of the request's `time_limit` and `max_solve_time`, counts
/// from the request's arrival: two long frictional requests ahead of a
/// Hertz request with `time_limit` 1 had it answered `solved` after 5.8–6.4 s.
/// A request still waiting for a worker when its limit passes is answered
/// `timeout` then, unsolved; one that gets a worker with its time gone is
/// answered so at once.
async fn solve_on_worker(request: Validated, state: &Arc<State>, id: &str, arrived: Instant) -> (Body, String, bool) {
    let limit = request.time_limit().map_or(state.cfg.max_solve_time, |s| {
        state.cfg.max_solve_time.min(Duration::from_secs_f64(s.min(1e9)))
    });
    let deadline = arrived
        .checked_add(limit)
        .unwrap_or(arrived + Duration::from_secs(86_400 * 365));
    let permit = tokio::time::timeout_at(deadline.into(), state.workers.acquire()).await;
    let Ok(permit) = permit else {
        return queued_past(state, id, &request, arrived, limit);
    };
    let permit = permit.expect("semaphore never closed");
    if Instant::now() >= deadline {
        return queued_past(state, id, &request, arrived, limit);
    }
    // The worker and the in-flight count go with the thread, not with this
    // answer: a solve answered by the watchdog below holds its worker until
    // its next deadline check stops it.
    permit.forget();
    let held = (WorkerSlot(state.clone()), Counted::new(state, |s| &s.in_flight));
    let client_id = request.client_id().map(Into::into);
    let (st, rid) = (state.clone(), id.to_string());
    let handle = tokio::task::spawn_blocking(move || {
        let _held = held;
        super::priority::lower_this_thread();
        let _progress = st.publisher.get().map(|s| {
            let key = super::progress::key_for(request.client_id(), &rid);
            super::progress::install(s.clone(), key, rid.clone())
        });
        let (result, panicked) = run_isolated_from(&rid, arrived, limit, || {
            let cache = (st.cfg.cache_bytes > 0).then_some(&st.cache);
            crate::wire::solve_validated(&request, &st.cfg.limits, cache)
        });
        drop(request);
        let (body, outcome) = wire(&rid, result);
        (body, outcome, panicked)
    });
    let Some(joined) = by(deadline + watchdog_grace(limit), handle).await else {
        return overran(id, client_id, arrived, limit);
    };
    joined.unwrap_or_else(|e| {
        tracing::error!(request_id = %id, "worker task failed: {e}");
        let (body, outcome) = wire(id, Err(internal_error(id)));
        (body, outcome, true)
    })
}

/// How long past its deadline a solve may still end before the watchdog
/// answers for it: 5 % of the limit, at most 0.1 s, inside the lateness a
/// reply is allowed (max(10 %, 0.2 s)). The solve polls its deadline, but
/// at nice 10 on a loaded machine its thread may not run: the burst test
/// measured a `solved` 2.328 s after its sending under a limit of 2 s, with
/// two test suites building beside it.
fn watchdog_grace(limit: Duration) -> Duration {
    limit.mul_f64(0.05).min(Duration::from_millis(100))
}

/// The blocking task's result if it ends by `when`, None if not (the task
/// goes on, detached, until its own deadline check stops it).
async fn by<T>(when: Instant, handle: tokio::task::JoinHandle<T>) -> Option<Result<T, tokio::task::JoinError>> {
    tokio::time::timeout_at(when.into(), handle).await.ok()
}

/// The `timeout` of a solve that did not end by its deadline and the
/// watchdog's grace: answered for it, from the runtime's threads.
fn overran(id: &str, client_id: Option<Box<str>>, arrived: Instant, limit: Duration) -> (Body, String, bool) {
    let message = format!(
        "the solve did not end within its time limit of {} s counted from its arrival ({:.3} s ago): the machine \
            may be loaded; it is stopped at its next check. Retry later, or give a longer time_limit",
        limit.as_secs_f64(),
        arrived.elapsed().as_secs_f64()
    );
    timeout_reply(id, client_id, message)
}

/// A `timeout` answered for a request, with its client's id.
fn timeout_reply(id: &str, client_id: Option<Box<str>>, message: String) -> (Body, String, bool) {
    let mut err = ErrorReply::new(ErrorCode::Timeout, message, "");
    err.client_id = client_id;
    let (body, outcome) = wire(id, Err(err));
    (body, outcome, false)
}

/// A worker permit given back when the solve's thread ends (the permit
/// itself borrows the state, and the thread may outlive the answer).
struct WorkerSlot(Arc<State>);

impl Drop for WorkerSlot {
    fn drop(&mut self) {
        self.0.workers.add_permits(1);
    }
}

/// The `timeout` of a request whose limit passed while it waited for a
/// worker: not started.
fn queued_past(
    state: &Arc<State>,
    id: &str,
    request: &Validated,
    arrived: Instant,
    limit: Duration,
) -> (Body, String, bool) {
    let running = state.in_flight.load(Ordering::SeqCst);
    let message = format!(
        "the request waited {:.3} s for a worker ({running} solving), past its time limit of {} s counted from its \
            arrival; it was not started: retry later, or give a longer time_limit",
        arrived.elapsed().as_secs_f64(),
        limit.as_secs_f64()
    );
    timeout_reply(id, request.client_id().map(Into::into), message)
}

/// Runs `solve` under a deadline of `limit` and `catch_unwind`; a panic becomes
/// `internal_error` (second value true), logged with the request id.
pub fn run_isolated(
    id: &str,
    limit: Duration,
    solve: impl FnOnce() -> Result<SolveReply, ErrorReply>,
) -> (Result<SolveReply, ErrorReply>, bool) {
    run_isolated_from(id, Instant::now(), limit, solve)
}

/// As `run_isolated`, the deadline counted from `start`.
pub fn run_isolated_from(
    id: &str,
    start: Instant,
    limit: Duration,
    solve: impl FnOnce() -> Result<SolveReply, ErrorReply>,
) -> (Result<SolveReply, ErrorReply>, bool) {
    let _deadline = crate::cancel::Deadline::install_from(start, limit);
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

/// As `send`, from the receiving thread: zenoh's reply is a push onto the
/// link's queue, with nothing to await.
fn send_now(query: &Query, key: &str, id: &str, body: Body) {
    let outcome = match body {
        Ok(bytes) => query.reply(key, bytes).wait(),
        Err(bytes) => query.reply_err(bytes).wait(),
    };
    if let Err(e) = outcome {
        tracing::warn!(request_id = %id, "reply failed: {e}");
    }
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

/// Bytes of a payload at the door, counted while they fit under
/// `max_door_bytes` and given back on drop.
struct DoorBytes {
    state: Arc<State>,
    len: usize,
}

impl DoorBytes {
    fn reserve(state: &Arc<State>, len: usize) -> Option<Self> {
        let cap = state.cfg.max_door_bytes;
        state
            .door_bytes
            .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |held| {
                held.checked_add(len).filter(|&total| total <= cap)
            })
            .ok()?;
        Some(Self {
            state: state.clone(),
            len,
        })
    }
}

impl Drop for DoorBytes {
    fn drop(&mut self) {
        self.state.door_bytes.fetch_sub(self.len, Ordering::SeqCst);
    }
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
        assert!(crate::cancel::check(crate::cancel::ProgressStage::Post).is_ok());
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
        assert!(crate::cancel::check(crate::cancel::ProgressStage::Mesh).is_ok());
    }

    /// A solve whose thread runs past its deadline and the grace is answered
    /// by the watchdog at once, while its worker stays taken until the thread
    /// ends (a slow thread must not let a second solve start beside it).
    #[test]
    fn a_solve_past_its_deadline_is_answered_and_keeps_its_worker() {
        let cfg = super::super::ServiceConfig {
            workers: 1,
            ..Default::default()
        };
        let state = Arc::new(State::new(cfg, "t".into()));
        let rt = tokio::runtime::Runtime::new().unwrap();
        rt.block_on(async {
            state.workers.acquire().await.unwrap().forget();
            let slot = WorkerSlot(state.clone());
            let (tx, rx) = std::sync::mpsc::channel::<()>();
            let handle = tokio::task::spawn_blocking(move || {
                let _slot = slot;
                rx.recv_timeout(Duration::from_secs(30)).ok();
            });
            let t0 = Instant::now();
            let limit = Duration::from_millis(50);
            assert!(by(t0 + limit + watchdog_grace(limit), handle).await.is_none());
            assert!(t0.elapsed() < Duration::from_secs(5), "answered at {:?}", t0.elapsed());
            assert_eq!(
                state.workers.available_permits(),
                0,
                "the thread still holds its worker"
            );
            tx.send(()).unwrap();
            // The thread ends and gives it back.
            let t1 = Instant::now();
            while state.workers.available_permits() == 0 && t1.elapsed() < Duration::from_secs(10) {
                tokio::time::sleep(Duration::from_millis(5)).await;
            }
            assert_eq!(state.workers.available_permits(), 1);
        });
        let (body, outcome, panicked) = overran("t-1", Some("c".into()), Instant::now(), Duration::from_secs(2));
        assert_eq!((outcome.as_str(), panicked), ("timeout", false));
        let json: serde_json::Value = serde_json::from_slice(&body.unwrap_err()).unwrap();
        assert_eq!(
            (json["client_id"].as_str(), json["request_id"].as_str()),
            (Some("c"), Some("t-1"))
        );
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

    /// The door's byte budget: payloads are let in while their sum stays
    /// within `max_door_bytes`, and their bytes come back when they are read.
    #[test]
    fn the_door_lets_in_payloads_up_to_its_byte_budget() {
        let cfg = super::super::ServiceConfig {
            max_door_bytes: 100,
            ..Default::default()
        };
        let state = Arc::new(State::new(cfg, "t".into()));
        let a = DoorBytes::reserve(&state, 60).expect("fits");
        assert!(DoorBytes::reserve(&state, 41).is_none(), "60 + 41 > 100");
        let b = DoorBytes::reserve(&state, 40).expect("60 + 40 = 100 fits");
        assert!(DoorBytes::reserve(&state, 1).is_none());
        assert_eq!(state.door_bytes.load(Ordering::SeqCst), 100);
        drop(a);
        assert!(DoorBytes::reserve(&state, 101).is_none(), "never more than the budget");
        let c = DoorBytes::reserve(&state, 60).expect("room again");
        drop((b, c));
        assert_eq!(state.door_bytes.load(Ordering::SeqCst), 0);
        let e = busy(&state, Some(60));
        assert_eq!(e.code, ErrorCode::Busy);
        assert!(e.message.contains("limit of 100 bytes"), "{}", e.message);
    }
}
