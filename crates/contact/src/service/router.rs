//! `contact router`: a zenoh router in this binary, for tests and small
//! deployments without `zenohd`. It is zenoh's own router (a session in router
//! mode), not a dispatcher of ours: services and clients connect to it and
//! zenoh routes every query to one complete queryable.

use super::config::{router_config, Tls};

/// Routes until ctrl-c (or SIGTERM).
pub async fn run(
    config_file: Option<std::path::PathBuf>,
    listen: Vec<String>,
    tls: Tls,
    acl: Option<std::path::PathBuf>,
) -> anyhow::Result<()> {
    let conf = router_config(config_file.as_deref(), &listen, &tls, acl.as_deref())?;
    let session = zenoh::open(conf)
        .await
        .map_err(|e| anyhow::anyhow!("cannot open the zenoh router: {e}"))?;
    tracing::info!(zid = %session.zid(), listen = ?listen, acl = ?acl, "zenoh router up");
    let mut term = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate())?;
    tokio::select! {
        _ = tokio::signal::ctrl_c() => tracing::info!("interrupted, router shutting down"),
        _ = term.recv() => tracing::info!("terminated, router shutting down"),
    }
    session.close().await.map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(())
}
