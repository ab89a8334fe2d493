//! # contact — the service and command-line shell of the contact solver
//!
//! The numerics live in `contact-core` (request → scene → meshes → model →
//! constraints → method → report); this crate turns bytes into requests and
//! answers into wire messages (`wire`), writes files (`output`), and serves
//! over zenoh (`service`, behind the `service` feature). `wire::solve_bytes`
//! is the entry point of both shells: the zenoh service and the CLI.

pub use contact_core::{cache, cancel, progress, scene, CoreError, Limits};
pub use contact_proto as proto;

#[cfg(feature = "service")]
pub mod cli;
pub mod cli_files;
pub mod output;
pub mod parse;
pub mod request_files;
#[cfg(feature = "service")]
pub mod service;
pub mod summary;
pub mod wire;

pub use wire::{check_bytes, error_reply, solve_bytes, solve_bytes_cached, solve_validated, validate_bytes, Validated};
