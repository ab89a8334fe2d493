//! `load_path` on a 3D solid: steps that scale the body's tractions,
//! supports (their prescribed values) and body force separately, each named
//! by its JSON pointer in the request as 2D names its loads
//! (`load_path::named_steps`, whose checks they share). Every step's
//! loads, its factors times the request's, stay within what the solve and
//! the reply can represent (`Sizes`), as the request's own do.

use contact_proto::{SolidBodySpec, SolveRequest};

use super::load_path::{index, named_steps};
use super::settings::check_load_size;
use super::Limits;
use crate::error::CoreError;
use crate::scene::solid::{FaceLoad, SolidPathStep, Support};
use crate::scene::Scales;

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

/// The largest nondimensional value of each of a solid's supports (its
/// prescribed values), tractions and body force, in the order a load path
/// step's factors are: what its loads' magnitude is judged by.
pub struct Sizes {
    supports: Vec<f64>,
    tractions: Vec<f64>,
    body_force: f64,
}

impl Sizes {
    pub fn of(supports: &[Support], loads: &[FaceLoad], body_force: [f64; 3]) -> Self {
        let largest = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |a, x| a.max(x.abs()));
        Sizes {
            supports: supports
                .iter()
                .map(|s| largest(&mut s.fix.iter().flatten().copied()))
                .collect(),
            tractions: loads
                .iter()
                .map(|l| match l {
                    FaceLoad::Traction { t, .. } => largest(&mut t.iter().copied()),
                    FaceLoad::Pressure { p, .. } => p.abs(),
                })
                .collect(),
            body_force: largest(&mut body_force.into_iter()),
        }
    }

    /// The largest of them all.
    pub fn largest(&self) -> f64 {
        self.scaled(None).0
    }

    /// The largest entry times its factor in `step` (1 each without), with
    /// the pointer of the entry.
    fn scaled(&self, step: Option<&SolidPathStep>) -> (f64, String) {
        let f = |v: Option<&Vec<f64>>, j: usize| v.map_or(1.0, |v| v[j]).abs();
        let supports = self
            .supports
            .iter()
            .enumerate()
            .map(|(j, s)| (s * f(step.map(|s| &s.supports), j), format!("/solid/body/supports/{j}")));
        let tractions = self.tractions.iter().enumerate().map(|(j, t)| {
            (
                t * f(step.map(|s| &s.tractions), j),
                format!("/solid/body/tractions/{j}"),
            )
        });
        let body_force = (
            self.body_force * step.map_or(1.0, |s| s.body_force.abs()),
            "/solid/body/body_force".to_string(),
        );
        supports
            .chain(tractions)
            .chain([body_force])
            .fold((0.0, "/solid/body".to_string()), |a, b| if b.0 > a.0 { b } else { a })
    }

    /// The request's own loads, refused at the largest one.
    pub fn check_base(&self, scales: Scales) -> Result<(), CoreError> {
        let (size, path) = self.scaled(None);
        check_load_size(size, scales, &path)
    }

    /// Every load path step's loads (a factor may reach 1e6), refused at the
    /// step.
    pub fn check_steps(&self, steps: &[SolidPathStep], scales: Scales) -> Result<(), CoreError> {
        for (k, step) in steps.iter().enumerate() {
            check_load_size(self.scaled(Some(step)).0, scales, &format!("/load_path/{k}"))?;
        }
        Ok(())
    }
}
