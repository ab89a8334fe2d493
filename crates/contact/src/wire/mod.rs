//! Bytes ↔ domain: the one place where a payload becomes a request for the
//! core and the core's answer or refusal becomes a wire message.

use contact_core::cache::OperatorCache;
use contact_core::error::CoreError;
use contact_core::scene::validate::solid_scene;
use contact_core::solid::door::{self, SolidProblem};
use contact_core::{Limits, Scene};
use contact_proto::{Analysis, ErrorCode, ErrorDetails, ErrorReply, LoadBound, SolveReply, Units};

use crate::parse::parse_request;

pub mod progress;
pub mod reply;
pub mod solid;

/// Bytes in, reply or structured error out: what the service and the CLI call.
pub fn solve_bytes(bytes: &[u8], limits: &Limits) -> Result<SolveReply, ErrorReply> {
    solve_bytes_cached(bytes, limits, None)
}

/// As `solve_bytes`, reusing prepared operators from `cache` when given.
pub fn solve_bytes_cached(
    bytes: &[u8],
    limits: &Limits,
    cache: Option<&OperatorCache>,
) -> Result<SolveReply, ErrorReply> {
    solve_validated(&validate_bytes(bytes, limits)?, limits, cache)
}

/// A request that passed the door: parsed and validated into its scene, ready
/// for the numerics. The service validates on arrival and hands this to a
/// worker, so a request is validated once.
pub struct Validated {
    scene: Door,
    units: Option<Units>,
}

/// What the door made of a request: a 2D scene, or a 3D solid.
enum Door {
    Plane(Box<Scene>),
    Solid(Box<SolidProblem>),
}

impl Validated {
    /// The request's `client_id`, echoed in its reply.
    pub fn client_id(&self) -> Option<&str> {
        match &self.scene {
            Door::Plane(s) => s.client_id.as_deref(),
            Door::Solid(s) => s.scene.client_id.as_deref(),
        }
    }

    /// The request's own `time_limit`, seconds, if it gives one.
    pub fn time_limit(&self) -> Option<f64> {
        match &self.scene {
            Door::Plane(s) => s.time_limit,
            Door::Solid(s) => s.scene.time_limit,
        }
    }
}

/// The checks of `solve_bytes` that come before any numerics: parse (lists
/// cut at their limits), the time limit, validation (with its size
/// estimates). Cheap and bounded by the payload, so the service runs it on
/// arrival and only valid work queues.
pub fn validate_bytes(bytes: &[u8], limits: &Limits) -> Result<Validated, ErrorReply> {
    let run = || -> Result<Validated, CoreError> {
        let req = parse_request(bytes, limits)?;
        let scene = match req.analysis {
            Analysis::Solid => Door::Solid(Box::new(door::admit(solid_scene(&req, limits)?)?)),
            _ => Door::Plane(Box::new(Scene::try_new(&req, limits)?)),
        };
        Ok(Validated {
            scene,
            units: req.units,
        })
    };
    run().map_err(|e| error_reply(&e).with_client_id_of(bytes))
}

/// `validate_bytes` without its result.
pub fn check_bytes(bytes: &[u8], limits: &Limits) -> Result<(), ErrorReply> {
    validate_bytes(bytes, limits).map(|_| ())
}

/// Solves a validated request.
pub fn solve_validated(
    request: &Validated,
    limits: &Limits,
    cache: Option<&OperatorCache>,
) -> Result<SolveReply, ErrorReply> {
    let solved = match &request.scene {
        Door::Plane(scene) => contact_core::solve(scene, limits, cache).map(reply::reply),
        Door::Solid(scene) => contact_core::solve_solid(scene, limits).map(solid::reply),
    };
    match solved {
        Ok(mut r) => {
            r.units.clone_from(&request.units);
            Ok(r)
        }
        Err(e) => {
            let mut err = error_reply(&e);
            err.client_id = request.client_id().map(Into::into);
            Err(err)
        }
    }
}

/// Longest message and pointer a refusal carries. Both may quote the
/// request (a key, a field name), and a 28 MB `load_path` key came back
/// whole in both: a 56 MB reply, 1.1 GB for 32 of them at once.
const MAX_MESSAGE: usize = 2000;
const MAX_POINTER: usize = 500;

/// `text` cut to at most `max` bytes (at a character boundary), saying how
/// much was cut.
fn clipped(text: String, max: usize) -> String {
    if text.len() <= max {
        return text;
    }
    let mut end = max;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}… ({} bytes cut)", &text[..end], text.len() - end)
}

/// The longest ancestor of the JSON pointer `path` within `max` bytes: it
/// still resolves in the request wherever `path` did.
fn pointer_within(path: &str, max: usize) -> String {
    if path.len() <= max {
        return path.to_string();
    }
    let mut end = max;
    while !path.is_char_boundary(end) {
        end -= 1;
    }
    path[..end].rfind('/').map_or(String::new(), |k| path[..k].to_string())
}

/// The wire form of a refusal: its code (the core's name for it,
/// `CoreError::code`), message, pointer and details.
pub fn error_reply(e: &CoreError) -> ErrorReply {
    let code: ErrorCode =
        serde_json::from_value(serde_json::Value::String(e.code().into())).unwrap_or(ErrorCode::InternalError);
    let message = match e {
        CoreError::Invalid { reason, .. } | CoreError::TooLarge { reason, .. } => reason.clone(),
        other => other.to_string(),
    };
    let mut reply = ErrorReply::new(
        code,
        clipped(message, MAX_MESSAGE),
        pointer_within(e.path(), MAX_POINTER),
    );
    if let CoreError::Invalid { loads, .. } = e {
        if !loads.is_empty() {
            reply.details = Some(Box::new(ErrorDetails {
                loads: loads
                    .iter()
                    .map(|b| LoadBound {
                        path: pointer_within(&b.path, MAX_POINTER),
                        value: b.value,
                        min: b.min,
                        max: b.max,
                    })
                    .collect(),
            }));
        }
    }
    reply
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_core::error::InvalidKind;
    use contact_core::linalg::{cholesky::FactorCost, LinalgError};

    /// A factorization refused for want of time is a `timeout` (the user's
    /// remedy is a longer limit or a coarser mesh), not a linear-algebra failure.
    /// Every name the core gives a refusal is one of the wire's error codes
    /// (an unknown one would be answered as internal_error).
    #[test]
    fn error_codes_are_the_cores_names() {
        use InvalidKind as K;
        let mut errors: Vec<CoreError> = [
            K::Request,
            K::Version,
            K::Material,
            K::Mesh,
            K::Geometry,
            K::NoSupport,
            K::NoContactCandidates,
            K::IncompatibleLoads,
        ]
        .into_iter()
        .map(|k| CoreError::invalid(k, "/x", "why"))
        .collect();
        errors.push(CoreError::Malformed { message: "m".into() });
        errors.push(CoreError::TooLarge {
            path: "/x".into(),
            reason: "r".into(),
        });
        errors.push(CoreError::Timeout {
            stage: "mesh",
            limit_s: 1.0,
            predicted: None,
        });
        for e in errors {
            let code = serde_json::to_value(error_reply(&e).code).unwrap();
            assert_eq!(code.as_str(), Some(e.code()), "{e:?}");
            assert_ne!(error_reply(&e).code, ErrorCode::InternalError, "{e:?}");
        }
    }

    #[test]
    fn a_predicted_overrun_is_a_timeout_with_the_prediction() {
        let cost = FactorCost {
            nnz: 494_000_000,
            flops: 9.6e11,
        };
        let e = CoreError::Linalg(LinalgError::Overrun { cost, left_s: 1.1 });
        let r = error_reply(&e);
        assert_eq!(r.code, ErrorCode::Timeout);
        let predicted = format!("{:.1} s", cost.predicted_secs());
        assert!(
            r.message.contains(&predicted) && r.message.contains("1.1 s left"),
            "{}",
            r.message
        );
    }
}
