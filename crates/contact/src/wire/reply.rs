//! Report → reply: the domain result written as the wire message, field by
//! field (the reply's documentation is the schema, `contact_proto::reply`).

use contact_core::outcome::{EstimateBasis, MethodRan, NoteKind, StopReason, WarningCode};
use contact_core::scene::Discretization;
use contact_core::solution::report::{
    self as r, CacheState, LoadStep, PairReport, PairTarget, Report, Resultant, Status,
};
use contact_proto as p;

/// The wire reply of `report`, with the VTU file attached when asked for.
pub fn reply(mut report: Report) -> p::SolveReply {
    let outputs = report.outputs;
    let axisymmetric = report.axisymmetric;
    let stress_zz: Vec<Vec<f64>> = report
        .bodies
        .iter_mut()
        .flatten()
        .map(|b| b.stress_zz.take().unwrap_or_default())
        .collect();
    // In axisymmetry σzz of the section's tensor is the hoop stress, which the
    // reply carries beside `stress`.
    let hoop: Vec<Option<Vec<f64>>> = stress_zz
        .iter()
        .map(|s| (axisymmetric && outputs.stress).then(|| s.clone()))
        .collect();
    let mut reply = p::SolveReply {
        version: p::PROTOCOL_VERSION.to_string(),
        client_id: report.client_id,
        request_id: None,
        status: status(report.status),
        method: method(report.method),
        iterations: report.iterations,
        pairs: report.pairs.into_iter().map(pair).collect(),
        resultant: resultant(report.resultant),
        certificate: certificate(report.certificate),
        size: p::ProblemSize {
            dofs: report.size.dofs,
            candidates: report.size.candidates,
            active: report.size.active,
        },
        diagnostics: p::Diagnostics {
            condition_estimate: report.diagnostics.condition_estimate,
            refinements: report.diagnostics.refinements,
            factorization_predicted: report.diagnostics.factorization_predicted,
            condensed_rows: report.diagnostics.condensed_rows,
        },
        timings: timings(report.timings),
        cache: match report.cache {
            CacheState::Hit => p::CacheState::Hit,
            CacheState::Miss => p::CacheState::Miss,
            CacheState::Off => p::CacheState::Off,
        },
        steps: report.steps.map(|s| s.into_iter().map(step).collect()),
        punches: report.punches.into_iter().map(punch).collect(),
        couplings: report.couplings.into_iter().map(coupling).collect(),
        bodies: report
            .bodies
            .map(|b| b.into_iter().zip(hoop).map(|(b, h)| body(b, h)).collect()),
        foundations: report.foundations.into_iter().map(foundation).collect(),
        note_kinds: report.notes.iter().map(|n| note_kind(n.kind)).collect(),
        notes: report.notes.into_iter().map(|n| n.text).collect(),
        warnings: warnings(report.warnings),
        vtu: None,
        units: None,
        refinement: report.refinement.map(refinement),
        solid: None,
    };
    crate::output::attach_vtu(&mut reply, outputs, &stress_zz, axisymmetric);
    reply
}

pub(super) fn warnings(w: Vec<r::Warning>) -> Vec<p::Warning> {
    w.into_iter()
        .map(|w| p::Warning {
            code: warning_code(w.code),
            value: w.value,
            limit: w.limit,
            location: w.location,
            message: w.message,
        })
        .collect()
}

pub(super) fn refinement(r: r::Refinement) -> p::Refinement {
    p::Refinement {
        reached: r.reached,
        stopped: stop_reason(r.stopped),
        rounds: r
            .rounds
            .into_iter()
            .map(|k| p::RefinementRound {
                dofs: k.dofs,
                h_min: k.h_min,
                pressure_l2: k.pressure_l2,
                zone_edge: k.zone_edge,
                seconds: k.seconds,
            })
            .collect(),
    }
}

// Exhaustive matches: a variant added in the core and not on the wire does
// not compile.
fn method(m: MethodRan) -> p::MethodRan {
    match m {
        MethodRan::ActiveSet => p::MethodRan::ActiveSet,
        MethodRan::InteriorPoint => p::MethodRan::InteriorPoint,
        MethodRan::Penalty => p::MethodRan::Penalty,
        MethodRan::AugmentedLagrangian => p::MethodRan::AugmentedLagrangian,
        MethodRan::Barrier => p::MethodRan::Barrier,
        MethodRan::ActiveSetFull => p::MethodRan::ActiveSetFull,
        MethodRan::InteriorPointFull => p::MethodRan::InteriorPointFull,
    }
}

fn stop_reason(r: StopReason) -> p::StopReason {
    match r {
        StopReason::Reached => p::StopReason::Reached,
        StopReason::NoContact => p::StopReason::NoContact,
        StopReason::NotSolved => p::StopReason::NotSolved,
        StopReason::MaxRounds => p::StopReason::MaxRounds,
        StopReason::MaxDofs => p::StopReason::MaxDofs,
        StopReason::TimeLimit => p::StopReason::TimeLimit,
        StopReason::SizeLimit => p::StopReason::SizeLimit,
        StopReason::RoundFailed => p::StopReason::RoundFailed,
        StopReason::NotConverging => p::StopReason::NotConverging,
    }
}

pub(super) fn basis(b: EstimateBasis) -> p::EstimateBasis {
    match b {
        EstimateBasis::TwoLevel => p::EstimateBasis::TwoLevel,
        EstimateBasis::TwoLevelFiner => p::EstimateBasis::TwoLevelFiner,
        EstimateBasis::ZoneEdges => p::EstimateBasis::ZoneEdges,
        EstimateBasis::NoEstimate => p::EstimateBasis::NoEstimate,
    }
}

pub(super) fn note_kind(k: NoteKind) -> p::NoteKind {
    match k {
        NoteKind::PairSwapped => p::NoteKind::PairSwapped,
        NoteKind::NearlyIncompressible => p::NoteKind::NearlyIncompressible,
        NoteKind::P2P0Element => p::NoteKind::P2P0Element,
        NoteKind::UndeterminedMotion => p::NoteKind::UndeterminedMotion,
        NoteKind::MethodFallback => p::NoteKind::MethodFallback,
        NoteKind::FullSystem => p::NoteKind::FullSystem,
        NoteKind::NonFinite => p::NoteKind::NonFinite,
        NoteKind::UnboundedForces => p::NoteKind::UnboundedForces,
        NoteKind::EstimateLimited => p::NoteKind::EstimateLimited,
        NoteKind::NotRefined => p::NoteKind::NotRefined,
        NoteKind::SlidingPunch => p::NoteKind::SlidingPunch,
        NoteKind::UnsettledBody => p::NoteKind::UnsettledBody,
    }
}

fn warning_code(c: WarningCode) -> p::WarningCode {
    match c {
        WarningCode::LargeStrain => p::WarningCode::LargeStrain,
        WarningCode::LargeRotation => p::WarningCode::LargeRotation,
        WarningCode::LargeDisplacement => p::WarningCode::LargeDisplacement,
        WarningCode::Rolling => p::WarningCode::Rolling,
        WarningCode::CoarseContactZone => p::WarningCode::CoarseContactZone,
        WarningCode::LargeContactZone => p::WarningCode::LargeContactZone,
        WarningCode::GapLinearization => p::WarningCode::GapLinearization,
        WarningCode::ToleranceNotReached => p::WarningCode::ToleranceNotReached,
        WarningCode::PrescribedSlip => p::WarningCode::PrescribedSlip,
    }
}

pub fn status(s: Status) -> p::SolveStatus {
    match s {
        Status::Solved => p::SolveStatus::Solved,
        Status::MaxIterations => p::SolveStatus::MaxIterations,
        Status::NumericalError => p::SolveStatus::NumericalError,
    }
}

fn resultant(r: Resultant) -> p::Resultant {
    p::Resultant {
        fx: r.fx,
        fy: r.fy,
        m: r.m,
    }
}

fn certificate(c: r::Certificate) -> p::Certificate {
    p::Certificate {
        primal: c.primal,
        dual: c.dual,
        complementarity: c.complementarity,
        equilibrium: c.equilibrium,
        friction: c.friction.map(|f| p::FrictionResiduals {
            cone: f.cone,
            dissipation: f.dissipation,
            stick: f.stick,
        }),
    }
}

pub(super) fn timings(t: r::Timings) -> p::Timings {
    p::Timings {
        mesh: t.mesh,
        assembly: t.assembly,
        factorization: t.factorization,
        condensation: t.condensation,
        contact_solve: t.contact_solve,
        post: t.post,
        estimate: t.estimate,
        total: t.total,
    }
}

fn step(s: LoadStep) -> p::LoadStep {
    p::LoadStep {
        factor: s.factor,
        loads: s.loads,
        status: status(s.status),
        iterations: s.iterations,
        pairs: s.pairs.into_iter().map(pair).collect(),
        resultant: resultant(s.resultant),
        certificate: certificate(s.certificate),
        couplings: s.couplings.into_iter().map(coupling).collect(),
        solid: None,
    }
}

fn pair(pr: PairReport) -> p::PairResult {
    let (obstacle, against, foundation, discretization) = match pr.target {
        PairTarget::Obstacle(o) => (Some(o), None, None, None),
        PairTarget::Foundation(f) => (None, None, Some(f), None),
        PairTarget::Body(b, d) => (
            None,
            Some(b),
            None,
            Some(match d {
                Discretization::Mortar => p::Discretization::Mortar,
                Discretization::NodeToSegment => p::Discretization::NodeToSegment,
            }),
        ),
    };
    p::PairResult {
        accuracy: pr.accuracy.map(|a| p::PairAccuracy {
            basis: basis(a.basis),
            pressure_l2: a.pressure_l2,
            peak: a.peak,
            resultant: a.resultant,
            zone_edges: a.zone_edges,
            fitted_edges: a.fitted_edges,
            energy: a.energy,
            singular_ends: a
                .singular_ends
                .iter()
                .map(|e| p::SingularEnd { at: e.at, band: e.band })
                .collect(),
        }),
        body: pr.body,
        obstacle,
        against,
        foundation,
        discretization,
        zones: pr.zones,
        zones_along: pr
            .zones_along
            .into_iter()
            .map(|z| p::ZoneAlong {
                s_start: z.s[0],
                s_end: z.s[1],
                start: z.start,
                end: z.end,
                uncertainty: z.uncertainty,
                fitted: z.fitted.map(|f| {
                    f.map(|f| p::FittedEnd {
                        s: f.s,
                        x: f.at[0],
                        y: f.at[1],
                    })
                }),
            })
            .collect(),
        points: pr
            .points
            .into_iter()
            .enumerate()
            .map(|(k, c)| {
                let fr = pr.friction.as_ref().map(|f| f.points[k]);
                p::ContactPoint {
                    x: c.x,
                    y: c.y,
                    gap: c.gap,
                    pressure: c.pressure,
                    force: c.force,
                    weight: c.weight,
                    node: c.node,
                    normal: c.normal,
                    tangential_traction: fr.map(|f| f.traction),
                    tangent: fr.and_then(|f| f.tangent),
                    slip: fr.map(|f| f.slip),
                    state: fr.map(|f| match f.state {
                        r::FrictionState::Stick => p::FrictionState::Stick,
                        r::FrictionState::Slip => p::FrictionState::Slip,
                        r::FrictionState::Open => p::FrictionState::Open,
                        r::FrictionState::Prescribed => p::FrictionState::Prescribed,
                    }),
                }
            })
            .collect(),
        resultant: resultant(pr.resultant),
        max_penetration: pr.max_penetration,
        pruned: pr.pruned,
        other_points: pr.other_points.map(|pts| {
            pts.into_iter()
                .map(|c| p::CounterPoint {
                    x: c.x,
                    y: c.y,
                    pressure: c.pressure,
                    force: c.force,
                    weight: c.weight,
                    node: c.node,
                })
                .collect()
        }),
        other_resultant: pr.other_resultant.map(resultant),
        friction: pr.friction.map(|f| p::PairFriction {
            coefficient: f.coefficient,
            stick_zones: f.stick_zones,
            slip_zones: f.slip_zones,
            stick_runs: f.stick_runs,
            slip_runs: f.slip_runs,
            tangential_resultant: resultant(f.tangential_resultant),
        }),
    }
}

fn punch(pu: r::PunchReport) -> p::PunchResult {
    p::PunchResult {
        name: pu.name,
        alpha1: pu.alpha1,
        alpha2: pu.alpha2,
        theta: pu.theta,
        p1: pu.p1,
        p2: pu.p2,
        m: pu.m,
        unique: pu.unique,
        note: pu.note,
    }
}

fn coupling(c: r::CouplingReport) -> p::CouplingResult {
    p::CouplingResult {
        path: c.path,
        body: c.body,
        ux: c.ux,
        uy: c.uy,
        theta: c.theta,
        fx: c.fx,
        fy: c.fy,
        m: c.m,
    }
}

fn body(b: r::BodyFields, stress_hoop: Option<Vec<f64>>) -> p::BodyOutput {
    p::BodyOutput {
        name: b.name,
        nodes: b.nodes,
        elements: b.elements,
        displacement: b.displacement,
        stress: b.stress,
        stress_hoop,
    }
}

fn foundation(f: r::FoundationReport) -> p::FoundationResult {
    p::FoundationResult {
        name: f.name,
        model: f.model.to_string(),
        x: f.x,
        w: f.w,
        reference_distance: f.reference_distance,
        load: f.load,
    }
}
