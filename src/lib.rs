//! # contact — frictionless 2D elastic contact
//!
//! Every scene is one quadratic program after discretization:
//!
//! ```text
//! minimize  ½ uᵀK u − fᵀu     subject to   B u ≤ g
//! ```
//!
//! K: linear elastic stiffness (T3/T6, plane strain or stress) on the free DOFs,
//! B: one row per contact candidate (the outward normal at a boundary node),
//! g: the initial gap along that normal. The multipliers λ ≥ 0 are the nodal
//! contact forces; pressure = λ / tributary length.
//!
//! The default (exact) path condenses onto the candidates with one sparse
//! Cholesky factorization (`linalg::cholesky`) and solves the small LCP there
//! (`methods`). `pipeline::solve_bytes` is the entry point of both shells: the
//! zenoh service (`service`) and the CLI (`main.rs`). Everything but `service`
//! is free of I/O.

pub mod bench;
pub mod cache;
pub mod cancel;
pub mod contact;
pub mod convergence;
pub mod error;
pub mod fem;
pub mod linalg;
pub mod mesh;
pub mod methods;
pub mod output;
pub mod pipeline;
pub mod progress;
pub mod proto;
pub mod request_files;
pub mod scene;
#[cfg(feature = "service")]
pub mod service;
pub mod solution;
pub mod stability;

pub use error::CoreError;
pub use pipeline::{solve, solve_bytes, solve_bytes_cached};
pub use scene::{Limits, Scene};
