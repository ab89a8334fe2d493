//! The zenoh shell: the only module that knows about zenoh and tokio.
//!
//! Key expressions: `contact/solve` (request JSON → reply JSON, or `reply_err`
//! with `{version, code, message, path}`), `contact/health`, `contact/schema`;
//! progress of each solve is published on `contact/progress/<key>` (`progress`).
//! Solves run on a bounded pool of blocking workers; past the queue limit a
//! request is answered `busy` at once.
//!
//! Scale-out is zenoh's: several services on the same keys behind a router.
//! The queryables are declared *complete*, so a query with zenoh's default
//! target (`BestMatching`) is routed to exactly one of them rather than to all
//! (which is what incomplete queryables get); when that one leaves, the router
//! routes to the next. zenoh picks the same instance for every such query, so
//! to spread the load each instance also holds a liveliness token
//! `contact/instance/<zid>` and answers `contact/instance/<zid>/solve`: a
//! client lists the live instances and takes turns (the Python client's
//! `spread=True`). No process of ours sits between clients and services.

pub mod config;
pub mod health;
pub mod priority;
pub mod progress;
pub mod router;
pub mod worker;

use std::sync::Arc;

use zenoh::Wait;

pub use config::{ServiceConfig, Tls};
use health::State;

pub const KEY_SOLVE: &str = "contact/solve";
pub const KEY_HEALTH: &str = "contact/health";
pub const KEY_SCHEMA: &str = "contact/schema";
/// Liveliness tokens of the running instances: `contact/instance/<zid>`.
pub const KEY_INSTANCES: &str = "contact/instance";

/// Runs the service until ctrl-c (or SIGTERM).
pub async fn run(cfg: ServiceConfig) -> anyhow::Result<()> {
    // First, so that a refused configuration stops the process before it measures or opens anything.
    let zconf = cfg.zenoh_config()?;
    // This machine's factorization speed, before the first deadline needs it
    // (measured again by every factorization; `linalg::rate`).
    let scale = tokio::task::spawn_blocking(contact_core::linalg::calibrate::calibrate).await?;
    tracing::info!(factorization_scale = scale, "factorization speed calibrated");
    let session = zenoh::open(zconf)
        .await
        .map_err(|e| anyhow::anyhow!("cannot open zenoh session: {e}"))?;
    let queryable = |key: &'static str| {
        let s = &session;
        async move {
            s.declare_queryable(key)
                .complete(true)
                .await
                .map_err(|e| anyhow::anyhow!("declaring {key}: {e}"))
        }
    };
    let health_q = queryable(KEY_HEALTH).await?;
    let schema_q = queryable(KEY_SCHEMA).await?;
    let state = Arc::new(State::new(cfg.clone(), session.zid().to_string()));
    let _ = state.publisher.set(session.clone());
    let instance_key = format!("{KEY_INSTANCES}/{}", state.instance);
    // Leaked once: the key lives as long as the process, like the constants.
    let own_solve_key: &'static str = Box::leak(format!("{instance_key}/solve").into_boxed_str());
    // Solve queries are admitted or refused in zenoh's callback, on its
    // receiving thread (`worker::dispatch`): through a channel and this loop, a
    // burst's `busy` answers waited for the loop and the runtime's threads.
    let solve_queryable = |key: &'static str| {
        let (s, st, rt) = (&session, state.clone(), tokio::runtime::Handle::current());
        async move {
            s.declare_queryable(key)
                .complete(true)
                .callback(move |q| worker::dispatch(q, key, &st, &rt))
                .await
                .map_err(|e| anyhow::anyhow!("declaring {key}: {e}"))
        }
    };
    let _solve_q = solve_queryable(KEY_SOLVE).await?;
    let _own_solve_q = solve_queryable(own_solve_key).await?;
    let _alive = session
        .liveliness()
        .declare_token(&instance_key)
        .await
        .map_err(|e| anyhow::anyhow!("declaring the liveliness token {instance_key}: {e}"))?;
    let schema_json = schema_payload();
    // A panic message goes through tracing too, so `--log-format json` stays one JSON object per line.
    std::panic::set_hook(Box::new(|info| tracing::error!(panic = %info, "panic")));
    tracing::info!(
        version = env!("CARGO_PKG_VERSION"),
        instance = %state.instance,
        listen = ?cfg.listen,
        connect = ?cfg.connect,
        workers = cfg.workers,
        queue_limit = cfg.queue_limit,
        max_solve_time_s = cfg.max_solve_time.as_secs_f64(),
        "contact {} serving {KEY_SOLVE}, {own_solve_key}, {KEY_HEALTH}, {KEY_SCHEMA}; publishing \
            {}/<client_id|request_id> and liveliness {instance_key}",
        env!("CARGO_PKG_VERSION"),
        progress::KEY_PROGRESS
    );
    let mut term = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate())?;
    loop {
        tokio::select! {
            q = health_q.recv_async() => match q {
                Ok(q) => {
                    let body = serde_json::to_vec(&state.health()).unwrap_or_default();
                    if let Err(e) = q.reply(KEY_HEALTH, body).wait() { tracing::warn!("health reply failed: {e}"); }
                }
                Err(e) => { tracing::error!("health queryable closed: {e}"); break; }
            },
            q = schema_q.recv_async() => match q {
                Ok(q) => {
                    if let Err(e) = q.reply(KEY_SCHEMA, schema_json.clone()).wait() {
                        tracing::warn!("schema reply failed: {e}");
                    }
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

/// `{"request": …, "reply": …, "error": …, "progress": …}` from the generated schemas.
fn schema_payload() -> Vec<u8> {
    let mut map = serde_json::Map::new();
    for (file, text) in crate::proto::schema::schemas() {
        let key = file.trim_end_matches(".schema.json").to_string();
        map.insert(key, serde_json::from_str(&text).unwrap_or(serde_json::Value::Null));
    }
    serde_json::to_vec(&map).unwrap_or_default()
}
