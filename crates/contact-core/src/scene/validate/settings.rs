//! `analysis`, `method`, `settings`, `load_factors`, `outputs`, `time_limit`:
//! the choices of model and method, and the limits on the reply's size.

use contact_proto::{self as proto, OutputKind, SolveRequest};

use super::{finite, invalid, positive, Limits};
use crate::error::{CoreError, InvalidKind, InvalidKind as K};
use crate::scene::{
    AccuracyTarget, Analysis, Body, Formulation, GapMeasure, Method, Outputs, Scales, Settings, T6Multipliers, Traction,
};

/// `units`: short printable names, if given.
pub fn units(req: &SolveRequest) -> Result<(), CoreError> {
    let Some(u) = &req.units else { return Ok(()) };
    for (name, v) in [("length", &u.length), ("force", &u.force), ("stress", &u.stress)] {
        if let Some(v) = v {
            if v.chars().count() > 32 || v.chars().any(char::is_control) {
                return Err(invalid(
                    K::Request,
                    format!("/units/{name}"),
                    "a unit name is at most 32 printable characters",
                ));
            }
        }
    }
    Ok(())
}

/// `time_limit`: a positive number of seconds, if given.
pub fn time_limit(req: &SolveRequest) -> Result<Option<f64>, CoreError> {
    if let Some(s) = req.time_limit.filter(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(invalid(
            K::Request,
            "/time_limit",
            format!("time_limit must be a positive number of seconds, got {s}"),
        ));
    }
    Ok(req.time_limit)
}

/// The tolerance and the iteration cap (2D and 3D alike).
pub fn iteration(req: &SolveRequest) -> Result<(f64, usize), CoreError> {
    let s = &req.settings;
    let tol = positive(s.tolerance, "/settings/tolerance", K::Request, "tolerance")?;
    if tol >= 1e-2 {
        return Err(invalid(
            K::Request,
            "/settings/tolerance",
            "tolerance must be below 1e-2",
        ));
    }
    if s.max_iterations == 0 || s.max_iterations > 100_000 {
        return Err(invalid(
            K::Request,
            "/settings/max_iterations",
            "max_iterations must be between 1 and 100000",
        ));
    }
    Ok((tol, s.max_iterations))
}

/// The solver settings, nondimensional; the load factors and the reply's size
/// are judged here too, in the order the checks have always run.
pub fn settings(
    req: &SolveRequest,
    scales: Scales,
    bodies: &[Body],
    nodes: f64,
    limits: &Limits,
) -> Result<Settings, CoreError> {
    let s = &req.settings;
    let (tol, _) = iteration(req)?;
    positive(
        s.prune_gap_ratio,
        "/settings/prune_gap_ratio",
        K::Request,
        "prune_gap_ratio",
    )?;

    let load_size = bodies
        .iter()
        .flat_map(|b| {
            let supports = b.supports.iter().flat_map(|s| [s.ux, s.uy]).flatten();
            let tractions = b.tractions.iter().flat_map(|t| match t {
                Traction::Vector { t, .. } => vec![t[0], t[1]],
                Traction::Pressure { p, .. } => vec![*p],
            });
            let points = b.point_loads.iter().flat_map(|p| p.force);
            supports
                .chain(tractions)
                .chain(points)
                .chain(b.body_force)
                .collect::<Vec<f64>>()
        })
        .fold(0.0f64, |a, v| a.max(v.abs()));
    check_load_factors(&req.load_factors, load_size, scales, limits)?;
    check_output_size(
        &req.outputs,
        req.load_factors.len().max(req.load_path.len()),
        nodes,
        limits,
    )?;

    Ok(Settings {
        tolerance: tol,
        max_iterations: s.max_iterations,
        prune_gap_ratio: s.prune_gap_ratio,
        formulation: match s.formulation {
            proto::Formulation::Condensed => Formulation::Condensed,
            proto::Formulation::Full => Formulation::Full,
        },
        gap: match s.gap {
            proto::GapMeasure::SignedDistance => GapMeasure::SignedDistance,
            proto::GapMeasure::BodyNormal => GapMeasure::BodyNormal,
        },
        t6_multipliers: match s.t6_multipliers {
            proto::T6Multipliers::EveryNode => T6Multipliers::EveryNode,
            proto::T6Multipliers::Corners => T6Multipliers::Corners,
        },
        // ζ is a compliance [length / pressure], the barrier a pressure × length.
        penalty: match s.penalty {
            Some(z) => positive(z, "/settings/penalty", K::Request, "penalty")? * scales.modulus / scales.length,
            None => Settings::default().penalty,
        },
        barrier: match s.barrier {
            Some(z) => positive(z, "/settings/barrier", K::Request, "barrier")? / scales.force_unit(),
            None => Settings::default().barrier,
        },
        estimate: s.estimate,
        accuracy: s.accuracy.as_ref().map(accuracy_target).transpose()?,
    })
}

/// `settings.accuracy`: at least one target, each positive and finite (the
/// pressure's a relative error below 1, not so small that the rounds only
/// chase round-off), one round at least.
pub(super) fn accuracy_target(t: &proto::AccuracyTarget) -> Result<AccuracyTarget, CoreError> {
    const AT: &str = "/settings/accuracy";
    if t.pressure_l2.is_none() && t.zone_edge.is_none() {
        return Err(invalid(
            K::Request,
            AT,
            "accuracy needs a target: pressure_l2 (a relative error, e.g. 0.005) and/or zone_edge (a length)",
        ));
    }
    if let Some(p) = t.pressure_l2 {
        positive(p, &format!("{AT}/pressure_l2"), K::Request, "pressure_l2")?;
        if !(1e-6..1.0).contains(&p) {
            return Err(invalid(
                K::Request,
                format!("{AT}/pressure_l2"),
                format!("pressure_l2 is a relative error between 1e-6 and 1 (0.005 is 0.5 %), got {p}"),
            ));
        }
    }
    if let Some(z) = t.zone_edge {
        positive(z, &format!("{AT}/zone_edge"), K::Request, "zone_edge")?;
    }
    if t.max_rounds == 0 || t.max_rounds > 20 {
        return Err(invalid(
            K::Request,
            format!("{AT}/max_rounds"),
            format!("max_rounds must be between 1 and 20, got {}", t.max_rounds),
        ));
    }
    if t.max_dofs == 0 {
        return Err(invalid(
            K::Request,
            format!("{AT}/max_dofs"),
            "max_dofs must be positive",
        ));
    }
    Ok(AccuracyTarget {
        pressure_l2: t.pressure_l2,
        zone_edge: t.zone_edge,
        max_rounds: t.max_rounds,
        max_dofs: t.max_dofs,
    })
}

pub fn analysis(req: &SolveRequest) -> Analysis {
    match req.analysis {
        proto::Analysis::PlaneStrain => Analysis::PlaneStrain,
        proto::Analysis::PlaneStress => Analysis::PlaneStress,
        proto::Analysis::Axisymmetric => Analysis::Axisymmetric,
        proto::Analysis::Solid => unreachable!("`Scene::try_new` refuses a 3D solid before it reads the analysis"),
    }
}

pub fn method(req: &SolveRequest) -> Method {
    match req.method {
        proto::MethodName::Auto => Method::Auto,
        proto::MethodName::ActiveSet => Method::ActiveSet,
        proto::MethodName::InteriorPoint => Method::InteriorPoint,
        proto::MethodName::Penalty => Method::Penalty,
        proto::MethodName::AugmentedLagrangian => Method::AugmentedLagrangian,
        proto::MethodName::Barrier => Method::Barrier,
    }
}

pub fn outputs(req: &SolveRequest) -> Outputs {
    Outputs {
        displacement: req.outputs.contains(&OutputKind::Displacement),
        mesh: req.outputs.contains(&OutputKind::Mesh),
        stress: req.outputs.contains(&OutputKind::Stress),
        vtu: req.outputs.contains(&OutputKind::Vtu),
    }
}

/// Largest |factor| × (largest nondimensional load or prescribed motion): the
/// solve forms products of loads (W λ · λ, energies), which must stay finite,
/// and a strain of 1e150 is meaningless long before.
const MAX_SCALED_LOAD: f64 = 1e150;

/// Largest force, moment or stress the reply may carry in the request's units
/// (nondimensional size × E·L or E·L²): far beyond any physical scene, and far
/// enough below f64::MAX (1.8e308) that sums, squares of the certificate's
/// scales and unit conversions stay finite. E = 1e300 with a load factor of
/// 1e100 came back with every force infinite.
const MAX_REPLY_MAGNITUDE: f64 = 1e200;

/// The requested fields over all load steps, against `max_output_values`
/// (`nodes`: the estimated node count of all bodies).
fn check_output_size(outputs: &[OutputKind], steps: usize, nodes: f64, limits: &Limits) -> Result<(), CoreError> {
    let per_node: f64 = outputs
        .iter()
        .map(|o| match o {
            OutputKind::Displacement => 2.0,
            OutputKind::Stress => 4.0,
            OutputKind::Mesh => 0.0,
            OutputKind::Vtu => 8.0,
        })
        .sum();
    // The mesh is written once, not per step: 2 coordinates and about 3
    // element indices per node.
    let once = if outputs.contains(&OutputKind::Mesh) {
        5.0 * nodes
    } else {
        0.0
    };
    let values = per_node * nodes * steps.max(1) as f64 + once;
    within_output_limit(
        values,
        &format!(" over {} load step(s)", steps.max(1)),
        "load steps or ",
        limits,
    )
}

/// `values` numbers of requested outputs against `max_output_values`, 2D and
/// 3D alike: refused at `/outputs`, saying what would bring them under it.
pub(super) fn within_output_limit(values: f64, over: &str, fewer: &str, limits: &Limits) -> Result<(), CoreError> {
    if values <= limits.max_output_values as f64 {
        return Ok(());
    }
    Err(CoreError::TooLarge {
        path: "/outputs".into(),
        reason: format!(
            "the requested outputs{over} come to about {values:.3e} numbers; this service returns at most {} per \
                reply (fewer {fewer}outputs, or a coarser mesh)",
            limits.max_output_values
        ),
    })
}

/// The reply's forces, moments and stresses for nondimensional loads of
/// `size` stay representable in the request's units.
fn check_reply_magnitude(size: f64, scales: Scales, path: &str) -> Result<(), CoreError> {
    let unit = scales.force_unit().max(scales.moment(1.0)).max(scales.modulus);
    let reach = size * unit;
    if reach.is_finite() && reach <= MAX_REPLY_MAGNITUDE {
        return Ok(());
    }
    Err(invalid(
        InvalidKind::Request,
        path,
        format!(
            "the reply's forces would reach about {reach:.1e} in the request's units (loads of {size:.1e} E·L with E = \
                {:e} and L = {:e}), beyond the {MAX_REPLY_MAGNITUDE:e} that double precision carries through the \
                solve: choose units in which the numbers are moderate (MPa and mm rather than Pa and m), or smaller \
                load factors",
            scales.modulus, scales.length
        ),
    ))
}

/// Loads of the nondimensional `size` (a 3D solid's largest load or
/// prescribed value, or one load path step's: its factors times them)
/// against `MAX_SCALED_LOAD` and the reply's magnitude, refused at `path`.
pub(super) fn check_load_size(size: f64, scales: Scales, path: &str) -> Result<(), CoreError> {
    if size > MAX_SCALED_LOAD {
        return Err(invalid(
            InvalidKind::Request,
            path,
            format!(
                "these loads or prescribed values reach {size:.1e} (nondimensional: stresses in units of E, \
                    displacements of L), beyond what the solve can represent (below {MAX_SCALED_LOAD:e}): a unit \
                    slip? (a modulus in MPa with stresses in Pa, say)"
            ),
        ));
    }
    check_reply_magnitude(size, scales, path)
}

/// `load_factors`: a bounded list of finite factors whose scaled loads stay
/// representable. `size`: the largest nondimensional load or prescribed motion.
pub(super) fn check_load_factors(factors: &[f64], size: f64, scales: Scales, limits: &Limits) -> Result<(), CoreError> {
    if factors.len() > limits.max_load_steps {
        return Err(CoreError::TooLarge {
            path: "/load_factors".into(),
            reason: format!(
                "{} load factors; this service solves at most {} load steps per request (split the list)",
                factors.len(),
                limits.max_load_steps
            ),
        });
    }
    if factors.is_empty() {
        check_reply_magnitude(size, scales, "/bodies")?;
    }
    for (k, &f) in factors.iter().enumerate() {
        let path = format!("/load_factors/{k}");
        finite(f, &path, InvalidKind::Request)?;
        if f.abs() * size > MAX_SCALED_LOAD {
            return Err(invalid(
                InvalidKind::Request,
                path,
                format!(
                    "load factor {f:e} scales the loads beyond what the solve can represent (|factor| × load must stay \
                        below {MAX_SCALED_LOAD:e} in units of E·L)"
                ),
            ));
        }
        check_reply_magnitude(f.abs() * size, scales, &path)?;
    }
    Ok(())
}
