//! `contacts`: each pair's body, edge set and target (obstacle, another
//! body's edge set, foundation), the softer body of two made the slave side.

use contact_proto::{self as proto, BodyRef, SolveRequest};

use super::bodies::{edge_names, Survey};
use super::invalid;
use crate::error::{CoreError, InvalidKind as K};
use crate::outcome::{Note, NoteKind};
use crate::scene::{Discretization, Pair, Target};

/// The names pairs refer to.
pub struct Names<'a> {
    pub bodies: &'a [String],
    pub obstacles: &'a [String],
    pub foundations: &'a [String],
}

/// The pairs, and the notes on pairs turned round.
pub fn pairs(req: &SolveRequest, survey: &Survey, n: &Names) -> Result<(Vec<Pair>, Vec<Note>), CoreError> {
    let (names, obstacle_names, foundation_names) = (n.bodies, n.obstacles, n.foundations);
    let parsed = &survey.parsed;
    if req.contacts.is_empty() {
        return Err(invalid(
            K::NoContactCandidates,
            "/contacts",
            "at least one contact pair is required",
        ));
    }
    let mut pairs = Vec::new();
    let mut notes = Vec::new();
    for (k, c) in req.contacts.iter().enumerate() {
        let cp = format!("/contacts/{k}");
        let body = resolve(&c.body, names, &format!("{cp}/body"), "body")?;
        let has_edges = |b: usize, edges: &str, path: String| {
            if edge_names(&req.bodies[b].mesh, parsed[b].as_ref())
                .iter()
                .any(|e| e == edges)
            {
                Ok(())
            } else {
                Err(invalid(
                    K::Request,
                    path,
                    format!("body '{}' has no edge set named '{}'", names[b], edges),
                ))
            }
        };
        has_edges(body, &c.edges, format!("{cp}/edges"))?;
        let target =
            match (&c.obstacle, &c.against, &c.foundation) {
                (Some(o), None, None) => {
                    Target::Obstacle(resolve(o, obstacle_names, &format!("{cp}/obstacle"), "obstacle")?)
                }
                (None, None, Some(f)) => {
                    Target::Foundation(resolve(f, foundation_names, &format!("{cp}/foundation"), "foundation")?)
                }
                (None, Some(a), None) => {
                    let other = resolve(&a.body, names, &format!("{cp}/against/body"), "body")?;
                    if other == body {
                        return Err(invalid(
                            K::Request,
                            format!("{cp}/against/body"),
                            "a body cannot be in contact with itself (self-contact is not supported)",
                        ));
                    }
                    has_edges(other, &a.edges, format!("{cp}/against/edges"))?;
                    Target::Body {
                        body: other,
                        edges: a.edges.clone(),
                        discretization: discretization(c.discretization),
                    }
                }
                _ => return Err(invalid(
                    K::Request,
                    cp.clone(),
                    "a contact pair names exactly one of 'obstacle' (rigid), 'against' (another body's edge set) or \
                        'foundation'",
                )),
            };
        // The side that carries the pressure (slave) must be the softer one:
        // a stiff slave's pressure oscillates from node to node (measured 80 %
        // at a stiffness ratio of 1e6, against 2 % the other way round).
        let stiffness = |b: usize| {
            let m = &req.bodies[b].material;
            match req.analysis {
                // A 3D solid never reaches the pairs (`Scene::try_new`); its E* is plane strain's.
                proto::Analysis::PlaneStrain | proto::Analysis::Axisymmetric | proto::Analysis::Solid => {
                    m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio)
                }
                proto::Analysis::PlaneStress => m.youngs_modulus,
            }
        };
        let (body, edges, target) = match target {
            Target::Body {
                body: other,
                edges: other_edges,
                discretization,
            } if stiffness(body) > SWAP_STIFFNESS_RATIO * stiffness(other) => {
                notes.push(Note::new(
                    NoteKind::PairSwapped,
                    format!(
                    "contact pair {k}: body '{}' is {:.1e} times stiffer than '{}', so '{}' carries the pressure (its \
                        edge set '{}' is the slave side) and the pair is reported that way round",
                    names[body],
                    stiffness(body) / stiffness(other),
                    names[other],
                    names[other],
                    other_edges
                ),
                ));
                (
                    other,
                    other_edges,
                    Target::Body {
                        body,
                        edges: c.edges.clone(),
                        discretization,
                    },
                )
            }
            t => (body, c.edges.clone(), t),
        };
        let friction = friction(req, c, &cp, &target)?;
        pairs.push(Pair {
            body,
            edges,
            target,
            path: cp,
            friction,
        });
    }

    Ok((pairs, notes))
}

/// The largest friction coefficient accepted. A normal force at round-off,
/// ε = 2.2e-16 of the largest, carries a friction force up to μ ε of it:
/// at 1e6 that is 2.2e-10, 45 times below the default tolerance 1e-8 of the
/// certificate; at μ = 1e10 it was 2e-6 and a correct all-stick answer on
/// the T3 roller was reported as `numerical_error`, and at 1e308 μ λ
/// overflowed. Real coefficients stay below about 10; on the T3 roller the
/// answer no longer changes with μ from 1e2 up (it sticks).
///
/// Within the range a large μ is the stick limit where a stick answer
/// exists: the points in contact stick, but those at a zone's ends, which
/// slip with a pressure vanishing as 1/μ and a finite shear (the limit of
/// Coulomb's cone lets a point carry shear at a pressure → 0). The axisymmetric
/// press fit pulled out by the shaft's far end solves at μ = 1e2, 1e4 and 1e6
/// in 10 iterations with a push-out force of 3.2774, 3.3179 and 3.3183
/// (1/μ convergence). Where a contact point's slip is prescribed (its node
/// on two held faces moved against each other, as the press fit pushed out
/// by the shaft's bottom with the ring's bottom held), it must slide with
/// μ λ, which has no bounded limit (push-out force ∝ μ: 40.9 and 354 at
/// μ = 1e2 and 1e3, the rest of the bore as in the stick limit): the step
/// needs 202 and 205 iterations there (the default cap is 200) and from
/// 1e4 up its iteration cycles under every restart (`max_iterations`).
pub const MAX_FRICTION: f64 = 1e6;

/// The pair's Coulomb coefficient μ (0 without `friction`); friction where
/// it is not supported yet is refused rather than ignored.
fn friction(req: &SolveRequest, c: &proto::ContactSpec, cp: &str, target: &Target) -> Result<f64, CoreError> {
    let Some(f) = c.friction else {
        return Ok(0.0);
    };
    let mu = f.coefficient;
    if !mu.is_finite() || mu < 0.0 {
        return Err(invalid(
            K::Request,
            format!("{cp}/friction/coefficient"),
            format!("the friction coefficient must be a finite number ≥ 0, got {mu}"),
        ));
    }
    if mu > MAX_FRICTION {
        return Err(invalid(
            K::Request,
            format!("{cp}/friction/coefficient"),
            format!(
                "the friction coefficient must lie in [0, {MAX_FRICTION:.0e}], got {mu:e}: beyond it the friction a \
                    normal force at round-off carries is no longer round-off; a coefficient this large means the \
                    surfaces do not slide, which {MAX_FRICTION:.0e} already gives"
            ),
        ));
    }
    if mu == 0.0 {
        return Ok(0.0);
    }
    let refuse = |what: &str| -> Result<f64, CoreError> {
        Err(invalid(
            K::Request,
            format!("{cp}/friction"),
            format!("friction {what} is not supported yet (remove 'friction' to solve the pair frictionless)"),
        ))
    };
    // Two bodies: the tangential rows are the normal ones turned by 90°,
    // which turns the other body's terms too, so they read the relative
    // tangential displacement of the two surfaces (`contact::friction`).
    if let Target::Foundation(_) = target {
        return refuse("on a foundation");
    }
    if !matches!(req.method, proto::MethodName::Auto | proto::MethodName::ActiveSet) {
        return refuse("with a method other than 'auto' or 'active_set'");
    }
    if req.contacts.iter().any(|p| p.foundation.is_some()) {
        return refuse("in a scene with foundations");
    }
    Ok(mu)
}

fn resolve(r: &BodyRef, names: &[String], path: &str, what: &str) -> Result<usize, CoreError> {
    match r {
        BodyRef::Index(i) if *i < names.len() => Ok(*i),
        BodyRef::Index(i) => Err(invalid(
            K::Request,
            path,
            format!("{what} index {i} out of range ({} given)", names.len()),
        )),
        BodyRef::Name(n) => names
            .iter()
            .position(|x| x == n)
            .ok_or_else(|| invalid(K::Request, path, format!("no {what} named '{n}'"))),
    }
}

fn discretization(d: proto::Discretization) -> Discretization {
    match d {
        proto::Discretization::Mortar => Discretization::Mortar,
        proto::Discretization::NodeToSegment => Discretization::NodeToSegment,
    }
}

/// A two-body pair whose named body is this many times stiffer than the other
/// is turned round, so that the softer body carries the pressure.
const SWAP_STIFFNESS_RATIO: f64 = 10.0;
