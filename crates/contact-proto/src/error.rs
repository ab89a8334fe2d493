//! Structured error replies: `{code, message, path}` where `path` is a JSON
//! pointer into the request.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Machine-readable error class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ErrorCode {
    /// The payload is not JSON (or not UTF-8).
    MalformedJson,
    /// JSON that does not fit the schema: unknown field, missing field, wrong type.
    InvalidRequest,
    /// `version` is not one this service speaks.
    UnsupportedVersion,
    /// E ≤ 0, ν outside (−1, 0.5), non-finite values.
    InvalidMaterial,
    /// Inverted, degenerate or badly indexed elements; bad mesh parameters.
    InvalidMesh,
    /// Obstacle or contact geometry that makes no sense.
    InvalidGeometry,
    /// A body whose supports leave a rigid motion free.
    NoSupport,
    /// A contact pair with no candidate that can close.
    NoContactCandidates,
    /// Loads on a body or punch held only by contact that no non-negative
    /// contact pressure can balance (Fichera's condition fails).
    IncompatibleLoads,
    /// The problem exceeds a size limit of the service.
    TooLarge,
    /// The linear algebra failed (e.g. the stiffness is not positive definite).
    LinearAlgebra,
    /// The service queue is full; retry later.
    Busy,
    /// The solve exceeded its time limit.
    Timeout,
    /// A bug: the solve panicked. The service goes on.
    InternalError,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ErrorReply {
    pub version: Box<str>,
    pub code: ErrorCode,
    pub message: String,
    /// JSON pointer into the request ("" for the whole request).
    pub path: String,
    // Boxed strings, a u32 and a boxed detail keep the error small: it is the `Err` of every solve.
    /// Echo of the request's `client_id`, when the payload was JSON with one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub client_id: Option<Box<str>>,
    /// Server-side id of this request, `<instance>-<n>` (set by the service, absent from the CLI).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub request_id: Option<Box<str>>,
    /// With `busy`: requests waiting for a worker when this one arrived (as in `contact/health`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub queue_depth: Option<u32>,
    /// The refusal as data, where there is more to it than one path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub details: Option<Box<ErrorDetails>>,
}

/// Machine-readable detail of a refusal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ErrorDetails {
    /// With `incompatible_loads`: every load component that no non-negative
    /// contact pressure (on a frictional pair: no contact force inside the
    /// friction cone |t| ≤ μ p) can balance with the other loads as given, and the
    /// interval it would have to lie in. The reply's `path` is the one that is
    /// furthest outside its interval, relative to the interval's nearer bound.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<LoadBound>,
}

/// A load component outside its admissible interval, in the request's units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadBound {
    /// JSON pointer of the load in the request.
    pub path: String,
    /// The load as given.
    pub value: f64,
    /// Lower end of the admissible interval (absent: unbounded below).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
    /// Upper end (absent: unbounded above).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
}

impl ErrorReply {
    pub fn new(code: ErrorCode, message: impl Into<String>, path: impl Into<String>) -> Self {
        Self {
            version: super::PROTOCOL_VERSION.into(),
            code,
            message: message.into(),
            path: path.into(),
            client_id: None,
            request_id: None,
            queue_depth: None,
            details: None,
        }
    }

    /// Echoes the `client_id` of `payload` (best effort: a payload that is not
    /// a JSON object with a string `client_id` leaves it absent).
    pub fn with_client_id_of(mut self, payload: &[u8]) -> Self {
        #[derive(Deserialize)]
        struct Id {
            client_id: Option<Box<str>>,
        }
        self.client_id = serde_json::from_slice::<Id>(payload).ok().and_then(|i| i.client_id);
        self
    }
}
