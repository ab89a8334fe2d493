//! Service settings → zenoh::Config. Defaults: peer mode, listen on
//! tcp/127.0.0.1:7447 only, no connect endpoints, multicast and gossip scouting
//! off. A zenoh JSON5 file replaces the defaults; `--listen` still overrides
//! its listen endpoints.

use std::path::PathBuf;

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
    pub limits: Limits,
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
            limits: Limits::default(),
            cache_bytes: 2 << 30,
        }
    }
}

impl ServiceConfig {
    pub fn zenoh_config(&self) -> anyhow::Result<zenoh::Config> {
        let err = |e: Box<dyn std::error::Error + Send + Sync>| anyhow::anyhow!("zenoh config: {e}");
        let mut c = match &self.config_file {
            Some(p) => zenoh::Config::from_file(p).map_err(err)?,
            None => {
                let mut c = zenoh::Config::default();
                c.insert_json5("mode", r#""peer""#).map_err(err)?;
                c.insert_json5("listen/endpoints", &serde_json::to_string(&[DEFAULT_LISTEN])?)
                    .map_err(err)?;
                c.insert_json5("connect/endpoints", "[]").map_err(err)?;
                c.insert_json5("scouting/multicast/enabled", "false").map_err(err)?;
                c.insert_json5("scouting/gossip/enabled", "false").map_err(err)?;
                c
            }
        };
        if let Some(l) = &self.listen {
            c.insert_json5("listen/endpoints", &serde_json::to_string(l)?)
                .map_err(err)?;
        }
        if !self.connect.is_empty() {
            c.insert_json5("connect/endpoints", &serde_json::to_string(&self.connect)?)
                .map_err(err)?;
        }
        Ok(c)
    }
}
