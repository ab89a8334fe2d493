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
        details: Option<Box<crate::proto::ErrorDetails>>,
    },
    /// Over a size limit.
    #[error("{reason} (at {path})")]
    TooLarge { path: String, reason: String },
    #[error(transparent)]
    Linalg(#[from] crate::linalg::LinalgError),
    /// The solve ran past its time limit and was stopped after `stage`.
    #[error("the solve exceeded its time limit of {limit_s} s and was stopped after stage '{stage}'")]
    Timeout { stage: &'static str, limit_s: f64 },
}

impl CoreError {
    pub fn invalid(kind: InvalidKind, path: impl Into<String>, reason: impl Into<String>) -> Self {
        CoreError::Invalid {
            kind,
            path: path.into(),
            reason: reason.into(),
            details: None,
        }
    }

    /// The same refusal with its detail as data.
    pub fn with_details(mut self, d: crate::proto::ErrorDetails) -> Self {
        if let CoreError::Invalid { details, .. } = &mut self {
            *details = Some(Box::new(d));
        }
        self
    }

    pub fn path(&self) -> &str {
        match self {
            CoreError::Invalid { path, .. } | CoreError::TooLarge { path, .. } => path,
            _ => "",
        }
    }
}
