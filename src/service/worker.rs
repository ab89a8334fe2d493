//! Admission control and the blocking worker pool.
//!
//! A request is admitted when fewer than `workers + queue_limit` are pending,
//! otherwise answered `busy` at once. Admitted requests wait for a worker
//! permit, run `pipeline::solve_bytes_cached` (with the shared operator
//! cache) on a blocking thread under
//! `catch_unwind` (a panic becomes `internal_error`; the process goes on), and
//! reply on `contact/solve`.

use std::panic::AssertUnwindSafe;
use std::sync::atomic::Ordering;
use std::sync::Arc;

use zenoh::query::Query;

use super::health::State;
use super::KEY_SOLVE;
use crate::proto::{ErrorCode, ErrorReply};

pub fn dispatch(query: Query, state: Arc<State>) {
    let id = state.next_id.fetch_add(1, Ordering::Relaxed);
    let capacity = state.cfg.workers + state.cfg.queue_limit;
    let pending = state.pending.fetch_add(1, Ordering::SeqCst);
    if pending >= capacity {
        state.pending.fetch_sub(1, Ordering::SeqCst);
        state.rejected_busy.fetch_add(1, Ordering::Relaxed);
        let err = ErrorReply::new(
            ErrorCode::Busy,
            format!("service busy: {pending} requests pending (limit {capacity}); retry later"),
            "",
        );
        tokio::spawn(async move { send(&query, Err(err), id).await });
        return;
    }
    tokio::spawn(async move {
        let payload: Vec<u8> = query.payload().map(|p| p.to_bytes().into_owned()).unwrap_or_default();
        let result = if payload.len() > state.cfg.max_request_bytes {
            Err(ErrorReply::new(
                ErrorCode::TooLarge,
                format!(
                    "request of {} bytes exceeds the limit of {} bytes",
                    payload.len(),
                    state.cfg.max_request_bytes
                ),
                "",
            ))
        } else {
            let _permit = state.workers.acquire().await.expect("semaphore never closed");
            state.in_flight.fetch_add(1, Ordering::SeqCst);
            let limits = state.cfg.limits;
            let st = state.clone();
            let joined = tokio::task::spawn_blocking(move || {
                std::panic::catch_unwind(AssertUnwindSafe(|| {
                    let cache = (st.cfg.cache_bytes > 0).then_some(&st.cache);
                    crate::pipeline::solve_bytes_cached(&payload, &limits, cache)
                }))
            })
            .await;
            state.in_flight.fetch_sub(1, Ordering::SeqCst);
            match joined {
                Ok(Ok(r)) => r.map(|reply| serde_json::to_vec(&reply).unwrap_or_default()),
                _ => {
                    state.panics.fetch_add(1, Ordering::Relaxed);
                    tracing::error!(request_id = id, "solve panicked");
                    Err(ErrorReply::new(
                        ErrorCode::InternalError,
                        format!("internal error while solving request {id}; the service goes on"),
                        "",
                    ))
                }
            }
        };
        match &result {
            Ok(_) => state.served_ok.fetch_add(1, Ordering::Relaxed),
            Err(_) => state.served_err.fetch_add(1, Ordering::Relaxed),
        };
        send(&query, result, id).await;
        state.pending.fetch_sub(1, Ordering::SeqCst);
    });
}

async fn send(query: &Query, result: Result<Vec<u8>, ErrorReply>, id: u64) {
    let outcome = match result {
        Ok(body) => query.reply(KEY_SOLVE, body).await,
        Err(e) => {
            tracing::info!(request_id = id, code = ?e.code, path = %e.path, "error reply: {}", e.message);
            query.reply_err(serde_json::to_vec(&e).unwrap_or_default()).await
        }
    };
    if let Err(e) = outcome {
        tracing::warn!(request_id = id, "reply failed: {e}");
    }
}
