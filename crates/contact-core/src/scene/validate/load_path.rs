//! `load_path`: steps that scale named loads and prescribed displacements
//! separately, each named by its JSON pointer in the request.

use contact_proto::SolveRequest;

use super::{finite, invalid};
use crate::error::{CoreError, InvalidKind as K};
use crate::scene::validate::Limits;
use crate::scene::{Body, LoadRef, PathStep};

/// Largest |factor| of a load path step: beyond it the scaled loads leave the
/// range the reply's magnitude check was made for (loads of O(E·L) times 1e6
/// stay far below the 1e200 at which an answer is refused as overflowing).
const MAX_FACTOR: f64 = 1e6;

pub fn load_path(req: &SolveRequest, bodies: &[Body], limits: &Limits) -> Result<Vec<PathStep>, CoreError> {
    let steps = named_steps(req, limits, |name| load_ref(name, bodies, req), HINT_2D)?;
    Ok(steps
        .into_iter()
        .map(|(factors, given)| PathStep { factors, given })
        .collect())
}

/// What a 2D name that resolves to no load should have been.
const HINT_2D: &str = "a traction, point load, support, body force, coupling motion or punch motion, e.g. \
    /bodies/0/tractions/1, /bodies/0/couplings/0/vertical or /obstacles/0/punch/horizontal";

/// The steps of `req.load_path`, each name resolved by `resolve` (2D's
/// bodies and punches, a solid's body), with the checks every analysis
/// shares: not with `load_factors`, at most `max_load_steps` steps, every
/// factor finite and within `MAX_FACTOR`. An unresolved name is refused at
/// its entry's pointer, `hint` saying what it could have named.
pub(super) fn named_steps<R>(
    req: &SolveRequest,
    limits: &Limits,
    resolve: impl Fn(&str) -> Option<R>,
    hint: &str,
) -> Result<Vec<NamedStep<R>>, CoreError> {
    if req.load_path.is_empty() {
        return Ok(Vec::new());
    }
    if !req.load_factors.is_empty() {
        return Err(invalid(
            K::Request,
            "/load_path",
            "give either 'load_factors' (every load scaled alike) or 'load_path' (named loads scaled per step), not \
                both",
        ));
    }
    if req.load_path.len() > limits.max_load_steps {
        return Err(CoreError::TooLarge {
            path: "/load_path".into(),
            reason: format!(
                "{} load path steps; this service solves at most {} load steps per request",
                req.load_path.len(),
                limits.max_load_steps
            ),
        });
    }
    req.load_path
        .iter()
        .enumerate()
        .map(|(k, step)| {
            let factors = step
                .loads
                .iter()
                .map(|(name, &f)| {
                    let path = format!("/load_path/{k}/loads/{}", escape(name));
                    let r = resolve(name).ok_or_else(|| {
                        invalid(
                            K::Request,
                            &path,
                            format!("'{name}' names no load: expected the JSON pointer of {hint}"),
                        )
                    })?;
                    finite(f, &path, K::Request)?;
                    if f.abs() > MAX_FACTOR {
                        return Err(invalid(
                            K::Request,
                            &path,
                            format!("a load path factor must not exceed {MAX_FACTOR:e} in magnitude, got {f:e}"),
                        ));
                    }
                    Ok((r, f))
                })
                .collect::<Result<Vec<_>, CoreError>>()?;
            Ok((factors, step.loads.clone()))
        })
        .collect()
}

/// A step's resolved names with their factors, and the names as given.
pub(super) type NamedStep<R> = (Vec<(R, f64)>, std::collections::BTreeMap<String, f64>);

/// A key as one JSON pointer token (RFC 6901: ~ as ~0, / as ~1).
fn escape(key: &str) -> String {
    key.replace('~', "~0").replace('/', "~1")
}

/// A pointer's array index: digits, no sign, no leading zero.
pub(super) fn index(s: &str) -> Option<usize> {
    (!s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) && (s == "0" || !s.starts_with('0')))
        .then(|| s.parse().ok())
        .flatten()
}

/// The load a pointer names: `/bodies/<i>/<tractions|point_loads|supports>/<j>`
/// or `/bodies/<i>/body_force`, or `/bodies/<i>/couplings/<j>/<horizontal|vertical|rotation>`,
/// with the body by index, or
/// `/obstacles/<i>/punch/<horizontal|vertical|rotation>` of a punch.
fn load_ref(name: &str, bodies: &[Body], req: &SolveRequest) -> Option<LoadRef> {
    if let Some(rest) = name.strip_prefix("/obstacles/") {
        let parts: Vec<&str> = rest.split('/').collect();
        let obstacle = index(parts.first()?)?;
        req.obstacles.get(obstacle)?.punch.as_ref()?;
        let component = match parts[1..] {
            ["punch", "horizontal"] => 0,
            ["punch", "vertical"] => 1,
            ["punch", "rotation"] => 2,
            _ => return None,
        };
        return Some(LoadRef::Punch { obstacle, component });
    }
    let parts: Vec<&str> = name.strip_prefix("/bodies/")?.split('/').collect();
    let body = index(parts.first()?)?;
    let b = bodies.get(body)?;
    match parts[1..] {
        ["body_force"] => Some(LoadRef::BodyForce { body }),
        ["tractions", j] => index(j)
            .filter(|&i| i < b.tractions.len())
            .map(|index| LoadRef::Traction { body, index }),
        ["point_loads", j] => index(j)
            .filter(|&i| i < b.point_loads.len())
            .map(|index| LoadRef::PointLoad { body, index }),
        ["supports", j] => index(j)
            .filter(|&i| i < b.supports.len())
            .map(|index| LoadRef::Support { body, index }),
        ["couplings", j, c] => {
            let index = index(j).filter(|&i| i < b.couplings.len())?;
            let component = crate::scene::COMPONENTS.iter().position(|n| *n == c)?;
            Some(LoadRef::Coupling { body, index, component })
        }
        _ => None,
    }
}
