//! `load_path` on a 3D solid: steps that scale the body's tractions,
//! supports (their prescribed values) and body force separately, each named
//! by its JSON pointer in the request as 2D names its loads
//! (`load_path::named_steps`, whose checks they share).

use contact_proto::{SolidBodySpec, SolveRequest};

use super::load_path::{index, named_steps};
use super::Limits;
use crate::error::CoreError;
use crate::scene::solid::SolidPathStep;

/// What a name that resolves to nothing should have been.
const HINT: &str = "a traction (or pressure), support or body force of the solid, e.g. /solid/body/tractions/0, \
    /solid/body/supports/2 (its prescribed values) or /solid/body/body_force (when given)";

/// A solid's load a pointer names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SolidLoad {
    Traction(usize),
    Support(usize),
    BodyForce,
}

/// The steps of the request's `load_path` for the solid `body`: a factor
/// per traction and support and one for the body force, 1 where a step does
/// not name it (as 2D's steps).
pub fn solid_load_path(
    req: &SolveRequest,
    body: &SolidBodySpec,
    limits: &Limits,
) -> Result<Vec<SolidPathStep>, CoreError> {
    let steps = named_steps(req, limits, |name| resolve(name, body), HINT)?;
    Ok(steps
        .into_iter()
        .map(|(named, given)| {
            let mut step = SolidPathStep {
                tractions: vec![1.0; body.tractions.len()],
                supports: vec![1.0; body.supports.len()],
                body_force: 1.0,
                given,
            };
            for (load, f) in named {
                match load {
                    SolidLoad::Traction(j) => step.tractions[j] = f,
                    SolidLoad::Support(j) => step.supports[j] = f,
                    SolidLoad::BodyForce => step.body_force = f,
                }
            }
            step
        })
        .collect())
}

/// `/solid/body/tractions/<j>`, `/solid/body/supports/<j>` with j an entry
/// of the list, or `/solid/body/body_force` when the body has one: every
/// name resolves to a field of the request.
fn resolve(name: &str, body: &SolidBodySpec) -> Option<SolidLoad> {
    let parts: Vec<&str> = name.strip_prefix("/solid/body/")?.split('/').collect();
    match parts[..] {
        ["body_force"] => body.body_force.is_some().then_some(SolidLoad::BodyForce),
        ["tractions", j] => index(j).filter(|&i| i < body.tractions.len()).map(SolidLoad::Traction),
        ["supports", j] => index(j).filter(|&i| i < body.supports.len()).map(SolidLoad::Support),
        _ => None,
    }
}
