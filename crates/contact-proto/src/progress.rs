//! The progress message a solve publishes while it runs (`contact/progress/<key>`),
//! and what the Python progress callback receives.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One progress message: the stage a solve entered, or within `contact_solve`
/// one of its iterations.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProgressMessage {
    /// The stage being run.
    pub stage: ProgressStage,
    /// Seconds since the solve started.
    pub elapsed: f64,
    /// Predicted seconds of work done so far: `done / total` is the fraction of
    /// the solve behind (0 and 0 without a plan).
    pub done: f64,
    /// Predicted seconds of work in all.
    pub total: f64,
    /// Within `contact_solve`: the contact iteration (at most one message per
    /// 50 ms).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iteration: Option<usize>,
    /// With `iteration`: its residual, the largest |min(λᵢ, wᵢ)|, 0 at the
    /// solution (nondimensional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
    /// The round of tolerance-driven refinement (from 1), when refining: each
    /// round's stages run from the start of the bar again.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub round: Option<usize>,
    /// The service's id of the request (absent from the in-process callback).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub request_id: Option<String>,
}

/// The stage a solve is in, in the order a condensed solve runs them
/// (`factorization` and `condensation` are skipped on a cache hit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProgressStage {
    /// Reading or generating the meshes.
    Mesh,
    /// The stiffness, the loads and the contact rows.
    Assembly,
    /// The sparse Cholesky factorization of K.
    Factorization,
    /// K's inverse condensed onto the contact rows.
    Condensation,
    /// The contact iterations.
    ContactSolve,
    /// Pressures, zones, certificate and fields.
    Post,
    /// The error estimate's companion solve.
    Estimate,
}
