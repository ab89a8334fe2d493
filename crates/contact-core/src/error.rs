//! Errors of the core library. Every input error carries the JSON pointer of
//! the offending request field.

/// What kind of input was rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InvalidKind {
    Request,
    Version,
    Material,
    Mesh,
    Geometry,
    NoSupport,
    NoContactCandidates,
    IncompatibleLoads,
}

/// A load component that no non-negative contact pressure can balance with
/// the other loads as given, and the interval it would have to lie in
/// (request units; `None`: unbounded on that side).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadBound {
    /// JSON pointer of the load in the request.
    pub path: String,
    pub value: f64,
    pub min: Option<f64>,
    pub max: Option<f64>,
}

#[derive(Debug, thiserror::Error)]
pub enum CoreError {
    /// The payload is not JSON at all.
    #[error("malformed JSON: {message}")]
    Malformed { message: String },
    /// Input that was read but is not acceptable.
    #[error("{reason} (at {path})")]
    Invalid {
        kind: InvalidKind,
        path: String,
        reason: String,
        /// With `IncompatibleLoads`: the loads outside their admissible interval.
        loads: Vec<LoadBound>,
    },
    /// Over a size limit.
    #[error("{reason} (at {path})")]
    TooLarge { path: String, reason: String },
    #[error(transparent)]
    Linalg(crate::linalg::LinalgError),
    /// The solve ran past its time limit and was stopped after `stage`, or
    /// stopped at it when its work was predicted to take (first) more than
    /// the seconds left (second).
    #[error("{}", timeout_message(.stage, *.limit_s, *.predicted))]
    Timeout {
        stage: &'static str,
        limit_s: f64,
        predicted: Option<(f64, f64)>,
    },
}

/// A factorization stopped at the deadline is the solve's timeout, like any stage's.
impl From<crate::linalg::LinalgError> for CoreError {
    fn from(e: crate::linalg::LinalgError) -> Self {
        match e {
            crate::linalg::LinalgError::Deadline(t) => t.into(),
            e => CoreError::Linalg(e),
        }
    }
}

impl From<crate::cancel::Timeout> for CoreError {
    fn from(t: crate::cancel::Timeout) -> Self {
        CoreError::Timeout {
            stage: t.stage.as_str(),
            limit_s: t.limit_s,
            predicted: t.predicted,
        }
    }
}

/// A stage refused before its limit passed says so: the graded block with a
/// 1.5 s limit was answered at 1.2 s "exceeded its time limit".
fn timeout_message(stage: &str, limit_s: f64, predicted: Option<(f64, f64)>) -> String {
    match predicted {
        None => format!("the solve exceeded its time limit of {limit_s} s and was stopped after stage '{stage}'"),
        Some((needed, left)) => format!(
            "the solve would pass its time limit of {limit_s} s: stage '{stage}' was predicted to need {needed:.2} s \
                more, and {left:.2} s were left, so it was not started"
        ),
    }
}

impl CoreError {
    pub fn invalid(kind: InvalidKind, path: impl Into<String>, reason: impl Into<String>) -> Self {
        CoreError::Invalid {
            kind,
            path: path.into(),
            reason: reason.into(),
            loads: Vec::new(),
        }
    }

    /// The same refusal with the loads it is about, as data.
    pub fn with_loads(mut self, bounds: Vec<LoadBound>) -> Self {
        if let CoreError::Invalid { loads, .. } = &mut self {
            *loads = bounds;
        }
        self
    }

    /// The stable name of the refusal, as the service's error codes spell it.
    pub fn code(&self) -> &'static str {
        match self {
            CoreError::Malformed { .. } => "malformed_json",
            CoreError::Invalid { kind, .. } => match kind {
                InvalidKind::Request => "invalid_request",
                InvalidKind::Version => "unsupported_version",
                InvalidKind::Material => "invalid_material",
                InvalidKind::Mesh => "invalid_mesh",
                InvalidKind::Geometry => "invalid_geometry",
                InvalidKind::NoSupport => "no_support",
                InvalidKind::NoContactCandidates => "no_contact_candidates",
                InvalidKind::IncompatibleLoads => "incompatible_loads",
            },
            CoreError::TooLarge { .. } => "too_large",
            CoreError::Linalg(crate::linalg::LinalgError::Overrun { .. }) => "timeout",
            CoreError::Linalg(_) => "linear_algebra",
            CoreError::Timeout { .. } => "timeout",
        }
    }

    pub fn path(&self) -> &str {
        match self {
            CoreError::Invalid { path, .. } | CoreError::TooLarge { path, .. } => path,
            _ => "",
        }
    }
}
