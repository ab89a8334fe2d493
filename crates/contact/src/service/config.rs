//! Service settings → zenoh::Config. Defaults: peer mode, listen on
//! tcp/127.0.0.1:7447 only, no connect endpoints, multicast and gossip scouting
//! off. With connect endpoints (a router) and no listen endpoint the service is
//! a zenoh client of that router: several instances then run on one machine
//! without competing for a port. A zenoh JSON5 file replaces the defaults;
//! `--listen`/`--connect` still override its endpoints.
//!
//! TLS (`--tls-cert`, `--tls-key`, `--tls-ca`) is zenoh's own: the paths go
//! into `transport/link/tls`, and `tls/HOST:PORT` endpoints use them. With all
//! three the links are mutual TLS, which is what lets a router's access control
//! tell solvers from clients by their certificates' common names.
//! Plain TCP is refused on any endpoint that is not loopback unless the caller
//! says `--insecure`: on a network it authenticates no one, so anyone who
//! reaches the port can answer solves or read progress.

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
    /// one costs up to 4.4 times its payload on top (peak resident memory of
    /// a 58 MB Gmsh mesh; 3.5 for a 57 MB inline mesh), so this bounds the
    /// door's memory whatever arrives.
    pub max_door_bytes: usize,
    pub limits: Limits,
    /// A solve still running after this is stopped at its next stage boundary
    /// or iteration and answered `timeout`.
    pub max_solve_time: Duration,
    /// Memory bound of the factorization cache (0 disables it).
    pub cache_bytes: usize,
    pub tls: Tls,
    /// Accept plain TCP on endpoints that are not loopback.
    pub insecure: bool,
}

/// Certificate, private key and CA paths (PEM) for zenoh's TLS links.
#[derive(Debug, Clone, Default)]
pub struct Tls {
    pub cert: Option<PathBuf>,
    pub key: Option<PathBuf>,
    pub ca: Option<PathBuf>,
}

impl Tls {
    fn is_empty(&self) -> bool {
        self.cert.is_none() && self.key.is_none() && self.ca.is_none()
    }

    /// Writes the paths into `transport/link/tls`. The same certificate serves
    /// both directions: a solver may listen and connect, and with mTLS the
    /// router must see the same common name whichever side opened the link.
    pub fn apply(&self, c: &mut zenoh::Config) -> anyhow::Result<()> {
        if self.cert.is_some() != self.key.is_some() {
            anyhow::bail!("--tls-cert and --tls-key go together");
        }
        let mut set = |key: &str, path: &PathBuf| -> anyhow::Result<()> {
            // zenoh would only say so when a link is opened, possibly never.
            std::fs::metadata(path).map_err(|e| anyhow::anyhow!("{key}: cannot read {}: {e}", path.display()))?;
            let path = path
                .to_str()
                .ok_or_else(|| anyhow::anyhow!("{key}: the path {} is not UTF-8", path.display()))?;
            c.insert_json5(&format!("transport/link/tls/{key}"), &serde_json::to_string(path)?)
                .map_err(zerr)
        };
        if let Some(ca) = &self.ca {
            set("root_ca_certificate", ca)?;
        }
        if let (Some(cert), Some(key)) = (&self.cert, &self.key) {
            set("listen_certificate", cert)?;
            set("listen_private_key", key)?;
            set("connect_certificate", cert)?;
            set("connect_private_key", key)?;
            if self.ca.is_some() {
                c.insert_json5("transport/link/tls/enable_mtls", "true").map_err(zerr)?;
            }
        }
        Ok(())
    }
}

pub const DEFAULT_LISTEN: &str = "tcp/127.0.0.1:7447";

pub use contact_core::scene::BYTES_PER_DOF;

/// The degrees of freedom a request may have within `bytes` of memory.
pub fn dofs_within(bytes: usize) -> usize {
    bytes / BYTES_PER_DOF
}

/// The machine's memory in bytes (`MemTotal` of /proc/meminfo), if readable.
pub fn machine_memory() -> Option<usize> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

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
            tls: Tls::default(),
            insecure: false,
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
        if !self.tls.is_empty() {
            self.tls.apply(&mut c)?;
        }
        if !self.insecure {
            refuse_plain_tcp_off_loopback(&c)?;
        }
        Ok(c)
    }
}

/// Every endpoint the session would listen on or connect to that is plain TCP
/// on an address other than loopback is an error naming it.
pub fn refuse_plain_tcp_off_loopback(c: &zenoh::Config) -> anyhow::Result<()> {
    let mode: Option<String> = c.get_json("mode").ok().and_then(|m| serde_json::from_str(&m).ok());
    let mode = mode.unwrap_or_else(|| "peer".into());
    let mut exposed = Vec::new();
    for side in ["listen", "connect"] {
        let value: serde_json::Value = c
            .get_json(&format!("{side}/endpoints"))
            .ok()
            .and_then(|v| serde_json::from_str(&v).ok())
            .unwrap_or_default();
        // A list, or one list per mode (zenoh's mode-dependent form).
        let list = match &value {
            serde_json::Value::Object(m) => m.get(&mode).cloned().unwrap_or_default(),
            v => v.clone(),
        };
        // zenoh's default for a peer or router that names none (tcp/[::]:0 or
        // :7447, every interface) is listed here too.
        let endpoints: Vec<String> = serde_json::from_value(list).unwrap_or_default();
        exposed.extend(endpoints.into_iter().filter(|e| is_plain_tcp_off_loopback(e)));
    }
    if exposed.is_empty() {
        return Ok(());
    }
    anyhow::bail!(
        "refusing plain TCP off loopback ({}): unencrypted and unauthenticated, anyone who reaches it can read \
         the requests and progress and answer solves in the service's place. Use tls/ endpoints with \
         --tls-cert, --tls-key and --tls-ca (docs/howto/security.md), or pass --insecure to accept this",
        exposed.join(", ")
    )
}

/// `tcp/HOST:PORT[#…]` with HOST neither localhost nor a loopback address.
pub fn is_plain_tcp_off_loopback(endpoint: &str) -> bool {
    let Some(addr) = endpoint.strip_prefix("tcp/") else {
        return false;
    };
    let addr = addr.split(['#', '?']).next().unwrap_or(addr);
    let host = match addr.rsplit_once(':') {
        Some((h, _)) => h,
        None => addr,
    };
    let host = host.trim_start_matches('[').trim_end_matches(']');
    if host.eq_ignore_ascii_case("localhost") {
        return false;
    }
    !host.parse::<std::net::IpAddr>().is_ok_and(|ip| ip.is_loopback())
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
/// listening on `listen` (default tcp/127.0.0.1:7447), multicast scouting off;
/// `acl` is a JSON5 file holding zenoh's `access_control` block.
pub fn router_config(
    config_file: Option<&std::path::Path>,
    listen: &[String],
    tls: &Tls,
    acl: Option<&std::path::Path>,
) -> anyhow::Result<zenoh::Config> {
    let mut c = match config_file {
        Some(p) => zenoh::Config::from_file(p).map_err(zerr)?,
        None => loopback_defaults("router", &[DEFAULT_LISTEN.to_string()], &[])?,
    };
    if !listen.is_empty() {
        c.insert_json5("listen/endpoints", &serde_json::to_string(listen)?)
            .map_err(zerr)?;
    }
    tls.apply(&mut c)?;
    if let Some(p) = acl {
        c.insert_json5("access_control", &acl_block(p)?).map_err(zerr)?;
    }
    Ok(c)
}

/// The `access_control` object of an ACL file, which may hold it bare or
/// under an `access_control` key (a zenoh config fragment).
fn acl_block(path: &std::path::Path) -> anyhow::Result<String> {
    let text = std::fs::read_to_string(path).map_err(|e| anyhow::anyhow!("--acl {}: {e}", path.display()))?;
    // Parsed by zenoh's own JSON5 reader: a whole config that holds only the block.
    let c = zenoh::Config::from_json5(&text)
        .or_else(|_| zenoh::Config::from_json5(&format!("{{access_control: {text}}}")))
        .map_err(|e| anyhow::anyhow!("--acl {}: not a zenoh access_control block: {e}", path.display()))?;
    let block = c.get_json("access_control").map_err(zerr)?;
    let enabled = serde_json::from_str::<serde_json::Value>(&block)?["enabled"] == serde_json::Value::Bool(true);
    if !enabled {
        anyhow::bail!(
            "--acl {}: access_control.enabled is not true, so it would allow everything",
            path.display()
        );
    }
    Ok(block)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_tcp_off_loopback_counts_as_exposed() {
        for e in [
            "tcp/0.0.0.0:7447",
            "tcp/[::]:7447",
            "tcp/10.0.0.3:7447",
            "tcp/router.example:7447",
        ] {
            assert!(is_plain_tcp_off_loopback(e), "{e}");
        }
        for e in [
            "tcp/127.0.0.1:7447",
            "tcp/127.3.2.1:1",
            "tcp/[::1]:7447",
            "tcp/localhost:7447",
            "tls/0.0.0.0:7447",
            "tcp/127.0.0.1:7447#iface=lo",
        ] {
            assert!(!is_plain_tcp_off_loopback(e), "{e}");
        }
    }

    #[test]
    fn a_config_file_is_held_to_the_same_rule() {
        let dir = std::env::temp_dir();
        let file = |name: &str, text: &str| {
            let p = dir.join(format!("contact-{name}-{}.json5", std::process::id()));
            std::fs::write(&p, text).unwrap();
            p
        };
        let tls = file(
            "tls",
            r#"{mode: "peer", listen: {endpoints: ["tls/0.0.0.0:7447"]},
                transport: {link: {tls: {enable_mtls: true}}}}"#,
        );
        let open = file("open", r#"{mode: "peer"}"#);
        let with = |p: &std::path::PathBuf| ServiceConfig {
            config_file: Some(p.clone()),
            ..Default::default()
        };
        let tls_ok = with(&tls).zenoh_config();
        let open_err = with(&open).zenoh_config().map(|_| ()).unwrap_err().to_string();
        let _ = (std::fs::remove_file(&tls), std::fs::remove_file(&open));
        assert!(tls_ok.is_ok(), "{:?}", tls_ok.err());
        // zenoh's own default for a peer that names no listen endpoint: every interface.
        assert!(open_err.contains("tcp/[::]:0"), "{open_err}");
    }

    #[test]
    fn the_shipped_acl_loads_and_denies_by_default() {
        let shipped = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../deploy/router-acl.json5"));
        let c = router_config(None, &[], &Tls::default(), Some(shipped)).unwrap();
        let acl: serde_json::Value = serde_json::from_str(&c.get_json("access_control").unwrap()).unwrap();
        assert_eq!(acl["default_permission"], "deny");
        assert_eq!(acl["subjects"][0]["cert_common_names"][0], "contact-solver");
        let off = std::env::temp_dir().join(format!("acl-off-{}.json5", std::process::id()));
        std::fs::write(&off, "{enabled: false, default_permission: 'deny'}").unwrap();
        let err = router_config(None, &[], &Tls::default(), Some(&off))
            .unwrap_err()
            .to_string();
        let _ = std::fs::remove_file(&off);
        assert!(err.contains("enabled"), "{err}");
    }

    #[test]
    fn the_defaults_pass_and_a_public_listen_needs_insecure() {
        assert!(ServiceConfig::default().zenoh_config().is_ok());
        let public = ServiceConfig {
            listen: Some(vec!["tcp/0.0.0.0:7447".into()]),
            ..Default::default()
        };
        let err = public.zenoh_config().unwrap_err().to_string();
        assert!(err.contains("tcp/0.0.0.0:7447") && err.contains("--insecure"), "{err}");
        assert!(ServiceConfig {
            insecure: true,
            ..public
        }
        .zenoh_config()
        .is_ok());
    }
}
