//! The zenoh shell: the only module that knows about zenoh and tokio.
//!
//! Key expressions: `contact/solve` (request JSON → reply JSON, or `reply_err`
//! with `{version, code, message, path}`), `contact/health`, `contact/schema`.
//! Solves run on a bounded pool of blocking workers; past the queue limit a
//! request is answered `busy` at once.

pub mod config;
pub mod health;
pub mod worker;

use std::sync::Arc;

use zenoh::Wait;

pub use config::ServiceConfig;
use health::State;

pub const KEY_SOLVE: &str = "contact/solve";
pub const KEY_HEALTH: &str = "contact/health";
pub const KEY_SCHEMA: &str = "contact/schema";

/// Runs the service until ctrl-c (or SIGTERM).
pub async fn run(cfg: ServiceConfig) -> anyhow::Result<()> {
    let zconf = cfg.zenoh_config()?;
    let session = zenoh::open(zconf)
        .await
        .map_err(|e| anyhow::anyhow!("cannot open zenoh session: {e}"))?;
    let solve_q = session
        .declare_queryable(KEY_SOLVE)
        .await
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let health_q = session
        .declare_queryable(KEY_HEALTH)
        .await
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let schema_q = session
        .declare_queryable(KEY_SCHEMA)
        .await
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let state = Arc::new(State::new(cfg.clone()));
    let schema_json = schema_payload();
    tracing::info!(
        version = env!("CARGO_PKG_VERSION"),
        listen = ?cfg.listen,
        workers = cfg.workers,
        queue_limit = cfg.queue_limit,
        "serving {KEY_SOLVE}, {KEY_HEALTH}, {KEY_SCHEMA}"
    );
    let mut term = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate())?;
    loop {
        tokio::select! {
            q = solve_q.recv_async() => match q {
                Ok(q) => worker::dispatch(q, state.clone()),
                Err(e) => { tracing::error!("solve queryable closed: {e}"); break; }
            },
            q = health_q.recv_async() => match q {
                Ok(q) => {
                    let body = serde_json::to_vec(&state.health()).unwrap_or_default();
                    if let Err(e) = q.reply(KEY_HEALTH, body).wait() { tracing::warn!("health reply failed: {e}"); }
                }
                Err(e) => { tracing::error!("health queryable closed: {e}"); break; }
            },
            q = schema_q.recv_async() => match q {
                Ok(q) => {
                    if let Err(e) = q.reply(KEY_SCHEMA, schema_json.clone()).wait() { tracing::warn!("schema reply failed: {e}"); }
                }
                Err(e) => { tracing::error!("schema queryable closed: {e}"); break; }
            },
            _ = tokio::signal::ctrl_c() => { tracing::info!("interrupted, shutting down"); break; }
            _ = term.recv() => { tracing::info!("terminated, shutting down"); break; }
        }
    }
    session.close().await.map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(())
}

/// `{"request": …, "reply": …, "error": …}` from the generated schemas.
fn schema_payload() -> Vec<u8> {
    let mut map = serde_json::Map::new();
    for (file, text) in crate::proto::schema::schemas() {
        let key = file.trim_end_matches(".schema.json").to_string();
        map.insert(key, serde_json::from_str(&text).unwrap_or(serde_json::Value::Null));
    }
    serde_json::to_vec(&map).unwrap_or_default()
}
