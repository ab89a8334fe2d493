//! `contact`: the command-line shell over the library (the `contact` binary,
//! and `contact_client._contact.cli` in the Python package, run it).
//!
//! - `contact solve FILE|-`: one request, no zenoh; prints the reply JSON (or the
//!   error JSON and exits 1) exactly as the service would answer, or with
//!   `--summary` a short table (`summary`); `--vtu` and `--points-csv` also
//!   write files (see `cli_files`).
//! - `contact serve`: the zenoh service.
//! - `contact router`: a zenoh router (what `zenohd` does) for scale-out without installing zenohd.
//! - `contact schema`: writes the JSON Schemas into proto/.

use std::io::{Read, Write};
use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::cli_files;
use crate::service::ServiceConfig;

#[derive(Parser)]
#[command(
    name = "contact",
    version,
    about = "2D elastic contact solver (frictionless or with Coulomb friction)"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Clone, Copy, ValueEnum)]
enum LogFormat {
    Text,
    Json,
}

/// The TLS files of `serve` and `router`.
#[derive(Args)]
struct TlsArgs {
    /// TLS certificate (PEM) of this process, for tls/ endpoints; with
    /// --tls-key and --tls-ca the links are mutual TLS.
    #[arg(long, value_name = "PEM", requires = "tls_key")]
    tls_cert: Option<PathBuf>,
    /// Private key (PEM) of --tls-cert.
    #[arg(long, value_name = "PEM", requires = "tls_cert")]
    tls_key: Option<PathBuf>,
    /// CA certificate (PEM) the peers' certificates must be signed by.
    #[arg(long, value_name = "PEM")]
    tls_ca: Option<PathBuf>,
}

impl From<TlsArgs> for crate::service::Tls {
    fn from(a: TlsArgs) -> Self {
        Self {
            cert: a.tls_cert,
            key: a.tls_key,
            ca: a.tls_ca,
        }
    }
}

#[derive(Subcommand)]
enum Cmd {
    /// Solve one request (FILE, or - for stdin) and print the reply JSON.
    Solve {
        file: String,
        /// Indent the JSON output.
        #[arg(long)]
        pretty: bool,
        /// Print a short table (status, method, load, zones, peak pressures,
        /// certificate, time) instead of the JSON.
        #[arg(long, conflicts_with = "pretty")]
        summary: bool,
        /// Also write every body's mesh, displacement, stress and contact pressure as a VTU file (ParaView).
        #[arg(long, value_name = "OUT.vtu")]
        vtu: Option<PathBuf>,
        /// Also write the contact candidates as CSV (x, y, pair, body, gap, pressure, force, node).
        #[arg(long, value_name = "OUT.csv")]
        points_csv: Option<PathBuf>,
    },
    /// Run the zenoh solve service.
    Serve {
        /// zenoh JSON5 configuration file (replaces the loopback defaults).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Listen endpoint(s), e.g. tcp/127.0.0.1:7447 (repeatable).
        #[arg(long)]
        listen: Vec<String>,
        /// Connect endpoint(s), e.g. a zenohd router (repeatable).
        #[arg(long)]
        connect: Vec<String>,
        #[command(flatten)]
        tls: TlsArgs,
        /// Allow plain tcp/ endpoints that are not loopback (unencrypted, unauthenticated).
        #[arg(long)]
        insecure: bool,
        /// Solver threads (default: number of cores).
        #[arg(long)]
        workers: Option<usize>,
        /// Requests that may wait for a worker before `busy` is answered.
        #[arg(long, default_value_t = 16)]
        queue_limit: usize,
        /// Largest accepted number of degrees of freedom.
        #[arg(long)]
        max_dofs: Option<usize>,
        /// Memory one request may take, in MB (default: half the machine's
        /// memory shared among the workers); bounds its degrees of freedom,
        /// refinement rounds and error-estimate companions.
        #[arg(long, value_name = "MB")]
        max_memory: Option<usize>,
        /// Largest accepted number of contact candidates.
        #[arg(long)]
        max_candidates: Option<usize>,
        /// Longest accepted `load_factors` list (each factor is a full solve).
        #[arg(long)]
        max_load_steps: Option<usize>,
        /// Most numbers the requested `outputs` may put in one reply (all steps).
        #[arg(long)]
        max_output_values: Option<usize>,
        /// Largest accepted request payload in bytes.
        #[arg(long, default_value_t = 64 << 20)]
        max_request_bytes: usize,
        /// Requests parsed and validated at once (default: number of cores).
        #[arg(long)]
        max_parses: Option<usize>,
        /// Payload bytes being read at once; past it a request is answered
        /// `busy` unread (default: twice --max-request-bytes, at least that).
        #[arg(long)]
        max_door_bytes: Option<usize>,
        /// Seconds a solve may run before it is stopped and answered `timeout`.
        #[arg(long, default_value_t = 300.0, value_parser = positive_seconds)]
        max_solve_s: f64,
        /// Memory for cached factorizations in MiB (0 disables the cache).
        #[arg(long, default_value_t = 2048)]
        cache_mb: usize,
        #[arg(long, value_enum, default_value_t = LogFormat::Text)]
        log_format: LogFormat,
    },
    /// Run a zenoh router (zenoh's own routing, as zenohd) for several `serve` instances.
    Router {
        /// zenoh JSON5 configuration file (replaces the loopback defaults).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Listen endpoint(s) (default tcp/127.0.0.1:7447; repeatable).
        #[arg(long)]
        listen: Vec<String>,
        #[command(flatten)]
        tls: TlsArgs,
        /// JSON5 file with zenoh's `access_control` block (e.g. deploy/router-acl.json5).
        #[arg(long, value_name = "FILE")]
        acl: Option<PathBuf>,
        #[arg(long, value_enum, default_value_t = LogFormat::Text)]
        log_format: LogFormat,
    },
    /// Write the JSON Schemas of the protocol.
    Schema {
        /// Output directory.
        #[arg(long, default_value = "proto")]
        out: PathBuf,
    },
}

/// `contact solve` exit codes: 0 solved (every load step), 1 the request was
/// refused (an error reply), 2 the command itself failed (usage, files), 3 an
/// answer that is not `solved` (max_iterations, numerical_error): its numbers
/// must not be used as if they were.
const EXIT_REFUSED: u8 = 1;
const EXIT_NOT_SOLVED: u8 = 3;

fn exit_code(reply: &crate::proto::SolveReply) -> u8 {
    use crate::proto::SolveStatus::Solved;
    let steps_solved = reply
        .steps
        .as_ref()
        .is_none_or(|s| s.iter().all(|st| st.status == Solved));
    if reply.status == Solved && steps_solved {
        0
    } else {
        EXIT_NOT_SOLVED
    }
}

/// Runs the command line `args` (the program name first); returns the exit code.
pub fn main<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // Help and version are answers, usage errors are not.
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            2
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<u8> {
    match cli.cmd {
        Cmd::Solve {
            file,
            pretty,
            summary,
            vtu,
            points_csv,
        } => {
            let bytes = if file == "-" {
                let mut b = Vec::new();
                std::io::stdin().read_to_end(&mut b)?;
                b
            } else {
                std::fs::read(&file).with_context(|| format!("reading {file}"))?
            };
            let out = |v: &dyn erased::Ser| if pretty { v.pretty() } else { v.compact() };
            let (text, code) = match cli_files::solve(&file, &bytes, vtu.is_some()) {
                Ok(reply) => {
                    cli_files::write_outputs(&reply, vtu.as_deref(), points_csv.as_deref())?;
                    let text = if summary {
                        crate::summary::reply(&reply.shown)
                    } else {
                        out(&reply.shown)
                    };
                    (text, exit_code(&reply.shown))
                }
                Err(err) if summary => (crate::summary::error(&err), EXIT_REFUSED),
                Err(err) => (out(&err), EXIT_REFUSED),
            };
            // A closed pipe (e.g. `| head`) is the reader's choice, not an error of ours.
            let _ = writeln!(std::io::stdout().lock(), "{text}");
            Ok(code)
        }
        Cmd::Serve {
            config,
            listen,
            connect,
            tls,
            insecure,
            workers,
            queue_limit,
            max_dofs,
            max_memory,
            max_candidates,
            max_load_steps,
            max_output_values,
            max_request_bytes,
            max_parses,
            max_door_bytes,
            max_solve_s,
            cache_mb,
            log_format,
        } => {
            init_logging(log_format);
            let mut cfg = ServiceConfig {
                config_file: config,
                listen: (!listen.is_empty()).then_some(listen),
                connect,
                queue_limit,
                max_request_bytes,
                // A request the size limit accepts must fit at the door.
                max_door_bytes: max_door_bytes
                    .unwrap_or(max_request_bytes.saturating_mul(2))
                    .max(max_request_bytes),
                max_solve_time: std::time::Duration::from_secs_f64(max_solve_s),
                cache_bytes: cache_mb << 20,
                tls: tls.into(),
                insecure,
                ..Default::default()
            };
            if let Some(w) = workers {
                cfg.workers = w.max(1);
            }
            if let Some(p) = max_parses {
                cfg.max_parses = p.max(1);
            }
            if let Some(m) = max_dofs {
                cfg.limits.max_dofs = m;
            }
            let memory = max_memory
                .map(|mb| mb << 20)
                .or_else(|| crate::service::config::machine_memory().map(|b| b / 2 / cfg.workers));
            if let Some(bytes) = memory {
                cfg.limits.max_dofs = cfg.limits.max_dofs.min(crate::service::config::dofs_within(bytes));
            }
            if let Some(m) = max_candidates {
                cfg.limits.max_candidates = m;
            }
            if let Some(m) = max_load_steps {
                cfg.limits.max_load_steps = m;
            }
            if let Some(m) = max_output_values {
                cfg.limits.max_output_values = m;
            }
            let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build()?;
            rt.block_on(crate::service::run(cfg))?;
            Ok(0)
        }
        Cmd::Router {
            config,
            listen,
            tls,
            acl,
            log_format,
        } => {
            init_logging(log_format);
            let tls = tls.into();
            let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build()?;
            rt.block_on(crate::service::router::run(config, listen, tls, acl))?;
            Ok(0)
        }
        Cmd::Schema { out } => {
            std::fs::create_dir_all(&out)?;
            for (name, text) in crate::proto::schema::schemas() {
                let path = out.join(name);
                std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?;
                println!("wrote {}", path.display());
            }
            Ok(0)
        }
    }
}

fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v < 1e9 => Ok(v),
        _ => Err(format!("expected a positive number of seconds, got '{s}'")),
    }
}

/// Logs to stderr, coloured only on a terminal. zenoh warns at every start
/// that gossip is disabled, which is our loopback configuration's intent
/// (`service::config`), so that one module logs errors only unless RUST_LOG
/// says otherwise.
fn init_logging(format: LogFormat) {
    use std::io::IsTerminal;
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| "info,zenoh=warn,zenoh::net::routing::hat::peer=error".into());
    let builder = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_ansi(std::io::stderr().is_terminal())
        .with_writer(std::io::stderr);
    // A second start in one process (the Python package) keeps the first logger.
    let _ = match format {
        LogFormat::Text => builder.try_init(),
        LogFormat::Json => builder.json().try_init(),
    };
}

/// JSON rendering of the two reply types without duplicating the match arms.
mod erased {
    pub trait Ser {
        fn pretty(&self) -> String;
        fn compact(&self) -> String;
    }
    impl<T: serde::Serialize> Ser for T {
        fn pretty(&self) -> String {
            serde_json::to_string_pretty(self).unwrap_or_default()
        }
        fn compact(&self) -> String {
            serde_json::to_string(self).unwrap_or_default()
        }
    }
}
