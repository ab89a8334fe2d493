//! `SolidAnswer` → reply: the 3D answer written as the wire message. The
//! top-level fields the 2D reply always carries are filled from the 3D
//! answer (no pairs; the resultant's x, y force and moment about z); the
//! answer itself is the reply's `solid` section, with the body's fields and
//! the VTU file as `outputs` asks.

use base64::Engine;
use contact_core::mesh3d::Order;
use contact_core::solid::answer::{SolidAnswer, SolidStep};
use contact_core::solid::report::{ContactPoint, Patch, Resultant};
use contact_core::solid::signorini::Certificate;
use contact_proto as p;

use super::reply::{basis, note_kind, refinement, status, timings, warnings};
use crate::output::vtu_solid::{paraview_order, solid_vtu};

pub fn reply(a: SolidAnswer) -> p::SolveReply {
    let o = a.outputs;
    let vtu = a.fields.as_ref().filter(|_| o.vtu).map(|f| {
        let pressure: Vec<(usize, f64)> = a.report.points.iter().map(|q| (q.node, q.pressure)).collect();
        base64::engine::general_purpose::STANDARD.encode(solid_vtu(f, a.order, &pressure))
    });
    let f = a.fields.filter(|_| o.mesh || o.displacement || o.stress);
    let (nodes, elements, displacement, stress) = match f {
        None => (None, None, None, None),
        Some(f) => {
            let k = a.order.nodes_per_element();
            (
                o.mesh.then_some(f.nodes),
                o.mesh.then(|| f.elems.chunks_exact(k).map(<[usize]>::to_vec).collect()),
                o.displacement.then_some(f.displacement),
                o.stress.then(|| f.stress.iter().map(paraview_order).collect()),
            )
        }
    };
    let r = a.report;
    let (force, moment) = (r.resultant.force, r.resultant.moment);
    p::SolveReply {
        version: p::PROTOCOL_VERSION.to_string(),
        client_id: a.client_id,
        request_id: None,
        status: status(a.status),
        method: p::MethodRan::ActiveSet,
        iterations: r.iterations,
        pairs: Vec::new(),
        resultant: plane_resultant(&r.resultant),
        certificate: certificate(&r.certificate),
        size: p::ProblemSize {
            dofs: a.dofs,
            candidates: a.candidates,
            active: a.active,
        },
        diagnostics: p::Diagnostics {
            condition_estimate: None,
            refinements: a.refinements,
            factorization_predicted: None,
            condensed_rows: None,
        },
        timings: timings(a.timings),
        cache: p::CacheState::Off,
        punches: Vec::new(),
        couplings: Vec::new(),
        steps: a.steps.map(|s| s.into_iter().map(step).collect()),
        bodies: None,
        foundations: Vec::new(),
        note_kinds: a.notes.iter().map(|n| note_kind(n.kind)).collect(),
        notes: a.notes.into_iter().map(|n| n.text).collect(),
        warnings: warnings(a.warnings),
        vtu,
        units: None,
        refinement: a.refinement.map(refinement),
        solid: Some(p::SolidResult {
            body: a.body,
            obstacle: a.obstacle,
            faces: a.faces,
            element: match a.order {
                Order::T4 => p::SolidElementKind::T4,
                Order::T10 => p::SolidElementKind::T10,
            },
            patches: r.patches.into_iter().map(patch).collect(),
            points: r.points.into_iter().map(point).collect(),
            resultant: p::SolidResultant { force, moment },
            max_penetration: a.max_penetration,
            nodes,
            elements,
            displacement,
            stress,
            accuracy: a.accuracy.map(|q| p::SolidAccuracy {
                basis: basis(q.basis),
                pressure_l2: q.estimate.pressure_l2,
                peak: q.estimate.peak,
                resultant: q.estimate.resultant,
                contact_area: q.estimate.contact_area,
            }),
        }),
    }
}

/// A load factor's answer: the top-level fields a 2D step carries, and the
/// solid's own in `solid`.
fn step(s: SolidStep) -> p::LoadStep {
    let r = s.report;
    p::LoadStep {
        factor: s.factor,
        loads: s.loads,
        status: status(s.status),
        iterations: r.iterations,
        pairs: Vec::new(),
        resultant: plane_resultant(&r.resultant),
        certificate: certificate(&r.certificate),
        couplings: Vec::new(),
        solid: Some(p::SolidStepResult {
            patches: r.patches.into_iter().map(patch).collect(),
            points: r.points.into_iter().map(point).collect(),
            resultant: p::SolidResultant {
                force: r.resultant.force,
                moment: r.resultant.moment,
            },
            max_penetration: s.max_penetration,
        }),
    }
}

/// The top-level resultant of a solid: its x and y force and its moment
/// about z.
fn plane_resultant(r: &Resultant) -> p::Resultant {
    p::Resultant {
        fx: r.force[0],
        fy: r.force[1],
        m: r.moment[2],
    }
}

fn certificate(c: &Certificate) -> p::Certificate {
    p::Certificate {
        primal: c.primal,
        dual: c.dual,
        complementarity: c.complementarity,
        equilibrium: c.equilibrium,
        friction: None,
    }
}

fn patch(q: Patch) -> p::ContactPatch {
    p::ContactPatch {
        area: q.area,
        tributary_area: q.tributary_area,
        force: q.force,
        centre_of_pressure: q.centre_of_pressure,
        peak_pressure: q.peak_pressure,
        peak_at: q.peak_at,
        outline: q.outline,
    }
}

fn point(q: ContactPoint) -> p::SolidContactPoint {
    p::SolidContactPoint {
        at: q.position,
        pressure: q.pressure,
        gap: q.gap,
        in_contact: q.in_contact,
    }
}
