//! Service settings → zenoh::Config. Defaults: peer mode, listen on
//! tcp/127.0.0.1:7447 only, no connect endpoints, multicast and gossip scouting
//! off. With connect endpoints (a router) and no listen endpoint the service is
//! a zenoh client of that router: several instances then run on one machine
//! without competing for a port. A zenoh JSON5 file replaces the defaults;
//! `--listen`/`--connect` still override its endpoints.

use std::path::PathBuf;
use std::time::Duration;

use crate::scene::Limits;

#[derive(Debug, Clone)]
pub struct ServiceConfig {
    pub config_file: Option<PathBuf>,
    /// Listen endpoints (None: from the file, or the loopback default).
    pub listen: Option<Vec<String>>,
    /// Connect endpoints (e.g. a zenohd router).
    pub connect: Vec<String>,
    pub workers: usize,
    /// Requests that may wait for a worker before `busy` is answered.
    pub queue_limit: usize,
    pub max_request_bytes: usize,
    /// Requests read (parsed and validated) at once; the others that fit in
    /// `max_door_bytes` wait for a turn.
    pub max_parses: usize,
    /// Payload bytes held at the door at once (arrived, not yet read into a
    /// scene): a request that would pass it is answered `busy` unread. Reading
    /// costs at most a few times the payload (its numbers as f64), so this
    /// bounds the door's memory whatever arrives.
    pub max_door_bytes: usize,
    pub limits: Limits,
    /// A solve still running after this is stopped at its next stage boundary
    /// or iteration and answered `timeout`.
    pub max_solve_time: Duration,
    /// Memory bound of the factorization cache (0 disables it).
    pub cache_bytes: usize,
}

pub const DEFAULT_LISTEN: &str = "tcp/127.0.0.1:7447";

impl Default for ServiceConfig {
    fn default() -> Self {
        Self {
            config_file: None,
            listen: None,
            connect: Vec::new(),
            workers: std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1),
            queue_limit: 16,
            max_request_bytes: 64 << 20,
            max_parses: std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1),
            max_door_bytes: 128 << 20,
            limits: Limits::default(),
            max_solve_time: Duration::from_secs(300),
            cache_bytes: 2 << 30,
        }
    }
}

impl ServiceConfig {
    pub fn zenoh_config(&self) -> anyhow::Result<zenoh::Config> {
        let mut c = match &self.config_file {
            Some(p) => zenoh::Config::from_file(p).map_err(zerr)?,
            None if !self.connect.is_empty() && self.listen.is_none() => {
                loopback_defaults("client", &[], &self.connect)?
            }
            None => loopback_defaults("peer", &[DEFAULT_LISTEN.to_string()], &[])?,
        };
        if let Some(l) = &self.listen {
            c.insert_json5("listen/endpoints", &serde_json::to_string(l)?)
                .map_err(zerr)?;
        }
        if !self.connect.is_empty() {
            c.insert_json5("connect/endpoints", &serde_json::to_string(&self.connect)?)
                .map_err(zerr)?;
        }
        Ok(c)
    }
}

fn zerr(e: Box<dyn std::error::Error + Send + Sync>) -> anyhow::Error {
    anyhow::anyhow!("zenoh config: {e}")
}

/// `mode` with explicit endpoints only and no scouting, so nothing leaves them.
fn loopback_defaults(mode: &str, listen: &[String], connect: &[String]) -> anyhow::Result<zenoh::Config> {
    let mut c = zenoh::Config::default();
    c.insert_json5("mode", &serde_json::to_string(mode)?).map_err(zerr)?;
    if mode != "client" {
        c.insert_json5("listen/endpoints", &serde_json::to_string(listen)?)
            .map_err(zerr)?;
    }
    c.insert_json5("connect/endpoints", &serde_json::to_string(connect)?)
        .map_err(zerr)?;
    c.insert_json5("scouting/multicast/enabled", "false").map_err(zerr)?;
    c.insert_json5("scouting/gossip/enabled", "false").map_err(zerr)?;
    Ok(c)
}

/// A zenoh router (`contact router`): zenoh's own routing, as `zenohd` does it,
/// listening on `listen` (default tcp/127.0.0.1:7447), multicast scouting off.
pub fn router_config(config_file: Option<&std::path::Path>, listen: &[String]) -> anyhow::Result<zenoh::Config> {
    let mut c = match config_file {
        Some(p) => zenoh::Config::from_file(p).map_err(zerr)?,
        None => loopback_defaults("router", &[DEFAULT_LISTEN.to_string()], &[])?,
    };
    if !listen.is_empty() {
        c.insert_json5("listen/endpoints", &serde_json::to_string(listen)?)
            .map_err(zerr)?;
    }
    Ok(c)
}
