//! Progress of a solve on `contact/progress/<key>`: one JSON message per stage
//! entered and per contact iteration, `{stage, iteration?, residual?, round?,
//! elapsed, done, total, request_id}` (`contact_proto::progress::ProgressMessage`,
//! whose schema is `proto/progress.schema.json`; `crate::progress` for the stages
//! and the residual).
//!
//! `<key>` is the request's `client_id` when it is one plain key chunk (no `/`,
//! `*`, `$`, `?`, `#`, at most 128 bytes), so a client that picks its id can
//! subscribe before it sends the query; otherwise the request id, which the
//! client learns only from the reply (the messages are then for logs and tools
//! listening on `contact/progress/**`). Iteration messages are thinned to one per
//! `MIN_INTERVAL`; stage messages always go out. Publishing is best effort: a
//! failed put is logged and never fails the solve.

use std::time::{Duration, Instant};

use zenoh::Wait;

pub const KEY_PROGRESS: &str = "contact/progress";

/// Shortest time between two iteration messages.
const MIN_INTERVAL: Duration = Duration::from_millis(50);

/// Longest client id used as a key chunk.
const MAX_CHUNK: usize = 128;

/// `contact/progress/<client_id or request id>` for this request.
pub fn key_for(client_id: Option<&str>, request_id: &str) -> String {
    let chunk = client_id.filter(|c| is_plain_chunk(c)).unwrap_or(request_id);
    format!("{KEY_PROGRESS}/{chunk}")
}

fn is_plain_chunk(c: &str) -> bool {
    !c.is_empty() && c.len() <= MAX_CHUNK && !c.contains(['/', '*', '$', '?', '#']) && !c.chars().any(char::is_control)
}

/// Publishes this thread's progress on `key` while the guard lives.
pub fn install(session: zenoh::Session, key: String, request_id: String) -> crate::progress::Sink {
    let mut last_iteration = Instant::now() - MIN_INTERVAL;
    crate::progress::Sink::install(move |p| {
        if p.iteration.is_some() {
            if last_iteration.elapsed() < MIN_INTERVAL {
                return;
            }
            last_iteration = Instant::now();
        }
        let v = crate::wire::progress::message(p, Some(&request_id));
        if let Err(e) = session.put(&key, serde_json::to_vec(&v).unwrap_or_default()).wait() {
            tracing::warn!(request_id = %request_id, "progress not published on {key}: {e}");
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plain_client_id_is_the_key_and_anything_else_falls_back_to_the_request_id() {
        assert_eq!(key_for(Some("run-7"), "z-1"), "contact/progress/run-7");
        for bad in [Some("a/b"), Some("**"), Some(""), Some("a\nb"), None] {
            assert_eq!(key_for(bad, "z-1"), "contact/progress/z-1", "{bad:?}");
        }
        let long = "x".repeat(MAX_CHUNK + 1);
        assert_eq!(key_for(Some(&long), "z-1"), "contact/progress/z-1");
    }
}
