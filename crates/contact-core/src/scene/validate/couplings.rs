//! `bodies/*/couplings`: edge sets tied rigidly to a reference point, each of
//! its three motions a displacement or a load (as a punch's), nondimensional;
//! and, once the pairs are known, what a coupling may not share with them.

use std::collections::BTreeSet;

use contact_proto::{self as proto, BodySpec};

use super::{finite, invalid};
use crate::error::{CoreError, InvalidKind as K};
use crate::scene::{Body, Control, Coupling, Pair, Scales, Target, COMPONENTS as COMPONENT};

/// One motion of a punch or a coupling, nondimensional: component k (0
/// horizontal, 1 vertical, 2 rotation) at `path` (its object; the value's
/// pointer adds `/load` or `/displacement`).
pub(super) fn control(c: proto::Control, k: usize, path: &str, scales: Scales) -> Result<Control, CoreError> {
    let (v, is_load) = match c {
        proto::Control::Displacement(v) => (v, false),
        proto::Control::Load(v) => (v, true),
    };
    let kind = if is_load { "load" } else { "displacement" };
    finite(v, &format!("{path}/{kind}"), K::Request)?;
    let length = scales.length;
    Ok(match (is_load, k) {
        (false, 2) => Control::Displacement(v),
        (false, _) => Control::Displacement(v / length),
        (true, 2) => Control::Load(v / (scales.modulus * length * length)),
        (true, _) => Control::Load(v / scales.force_unit()),
    })
}

/// How far a coupling's reference point may lie from its body, in the body's
/// size (the largest side of its bounding box). The coupled nodes move as
/// u_ref + θ × (x − x_ref): at a distance d the rotation's lever arms are
/// d/L times the body's own, and the rigid motions about the reference lose
/// about log10(d/L) digits. Measured on the roller of
/// `signorini_roller_on_flat.json` (L = 16) pressed through its axle with
/// the rotation free: the same answer (to 1e-15) up to d = 3·10⁵ L, and at
/// 10⁶ L its vertical translation taken for one contact does not resist
/// (`incompatible_loads`); at 10³⁰⁸ a pushed roller (`roller_pushed_through_axle.json`)
/// "would slide or tip". 10⁴ L leaves a factor 30 below the first failure
/// and is still far beyond any lever a body is coupled through.
pub const MAX_REFERENCE_DISTANCE: f64 = 1e4;

/// The couplings of body `b` (at JSON pointer `bp`) whose edge sets are
/// `edges`; `bounds` the body's bounding box in the request's units.
pub fn couplings(
    b: &BodySpec,
    bp: &str,
    edges: &BTreeSet<String>,
    bounds: ([f64; 2], [f64; 2]),
    scales: Scales,
    axisymmetric: bool,
) -> Result<Vec<Coupling>, CoreError> {
    if b.couplings.len() > 1 {
        return Err(invalid(
            K::Request,
            format!("{bp}/couplings/1"),
            "a body takes at most one coupling: two rigid edge sets of one body are one rigid part, give them as one \
                edge set",
        ));
    }
    let mut out = Vec::with_capacity(b.couplings.len());
    for (j, cs) in b.couplings.iter().enumerate() {
        let cp = format!("{bp}/couplings/{j}");
        if !edges.contains(&cs.edges) {
            return Err(invalid(
                K::Request,
                format!("{cp}/edges"),
                format!(
                    "no edge set named '{}' on this body (it has: {})",
                    cs.edges,
                    edges.iter().cloned().collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        finite(cs.reference[0], &format!("{cp}/reference/0"), K::Geometry)?;
        finite(cs.reference[1], &format!("{cp}/reference/1"), K::Geometry)?;
        near_enough(cs.reference, bounds, &format!("{cp}/reference"))?;
        let given = [cs.horizontal, cs.vertical, cs.rotation];
        let mut controls = [Control::Displacement(0.0); 3];
        for (k, c) in given.into_iter().enumerate() {
            controls[k] = control(c, k, &format!("{cp}/{}", COMPONENT[k]), scales)?;
        }
        if axisymmetric {
            for k in [0, 2] {
                let (v, kind) = match given[k] {
                    proto::Control::Displacement(v) => (v, "displacement"),
                    proto::Control::Load(v) => (v, "load"),
                };
                // A load of 0 would leave the motion free, and no row of a
                // body of revolution resists a radial shift or a turn of the
                // section: the only allowed value is a held 0.
                if v != 0.0 || kind == "load" {
                    return Err(invalid(
                        K::Request,
                        format!("{cp}/{}/{kind}", COMPONENT[k]),
                        format!(
                            "in axisymmetry a coupling moves along the axis only: its {} must be left out (held at 0), \
                                got {kind} {v}",
                            COMPONENT[k]
                        ),
                    ));
                }
            }
        }
        let has_load = controls.iter().any(|c| matches!(c, Control::Load(_)));
        for (k, s) in b.supports.iter().enumerate() {
            if s.edges == cs.edges || has_load {
                return Err(invalid(
                    K::Request,
                    format!("{bp}/supports/{k}"),
                    if s.edges == cs.edges {
                        format!(
                            "edge set '{}' is both supported and coupled (`{cp}`): prescribe its motion through the \
                                coupling's displacements",
                            s.edges
                        )
                    } else {
                        format!(
                            "a body whose coupling carries a load (`{cp}`) takes no supports: the coupling's loaded \
                                motions are the body's rigid motions, which contact must hold; hold a motion with a \
                                coupling displacement instead"
                        )
                    },
                ));
            }
        }
        out.push(Coupling {
            edges: cs.edges.clone(),
            reference: [cs.reference[0] / scales.length, cs.reference[1] / scales.length],
            controls,
            path: cp,
        });
    }
    Ok(out)
}

/// Refuses a reference point farther from the body's box `bounds` than
/// `MAX_REFERENCE_DISTANCE` times the box's largest side.
fn near_enough(reference: [f64; 2], (lo, hi): ([f64; 2], [f64; 2]), path: &str) -> Result<(), CoreError> {
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    // Componentwise distance to the box (0 inside); hypot does not overflow.
    let gap = |k: usize| (lo[k] - reference[k]).max(reference[k] - hi[k]).max(0.0);
    let distance = gap(0).hypot(gap(1));
    // A body of no size is the mesh checks' to refuse, not the reference's.
    if distance <= MAX_REFERENCE_DISTANCE * size || size.is_nan() || size <= 0.0 {
        return Ok(());
    }
    Err(invalid(
        K::Request,
        path,
        format!(
            "the reference point [{:?}, {:?}] lies {distance:.3e} from its body, {:.1e} times the body's size \
                {size:.3e} (the largest side of its bounding box); a coupling's reference must lie within \
                {MAX_REFERENCE_DISTANCE:.0e} times that size (the lever arms about it would cost the solve its \
                precision): is it in the body's units?",
            reference[0],
            reference[1],
            distance / size
        ),
    ))
}

/// What the pairs show: a coupled edge set is no contact surface (its nodes
/// move rigidly with the reference point, their rows would see the axle,
/// not the body), and a loaded coupling needs a pair on its body (contact
/// carries the load).
pub fn against_pairs(bodies: &[Body], pairs: &[Pair]) -> Result<(), CoreError> {
    for (b, body) in bodies.iter().enumerate() {
        for cp in &body.couplings {
            let touches = |p: &Pair| {
                (p.body == b && p.edges == cp.edges)
                    || matches!(&p.target, Target::Body { body, edges, .. } if *body == b && *edges == cp.edges)
            };
            if let Some(p) = pairs.iter().find(|p| touches(p)) {
                return Err(invalid(
                    K::Request,
                    format!("{}/edges", cp.path),
                    format!(
                        "edge set '{}' is coupled to a reference point and also a contact surface (`{}`): couple an \
                            edge set away from the contact (an axle, a hub)",
                        cp.edges, p.path
                    ),
                ));
            }
            let in_pair = pairs
                .iter()
                .any(|p| p.body == b || matches!(p.target, Target::Body { body, .. } if body == b));
            if cp.has_load() && !in_pair {
                return Err(invalid(
                    K::NoSupport,
                    cp.path.clone(),
                    format!(
                        "the loads of a coupling are carried by contact, and no contact pair involves body '{}': \
                            prescribe its motions as displacements or add the pair that holds it",
                        body.name
                    ),
                ));
            }
        }
    }
    Ok(())
}
