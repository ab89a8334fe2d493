//! The domain result of a solve: what the core knows of the answer, in the
//! request's units. The service's reply (`contact::wire`) is written from it
//! field by field; benches and tests read it directly.
//!
//! Length: about 500 lines, the report's types alone (one struct or enum per
//! part of the answer the reply writes), with their few accessors.

pub use crate::observer::Timings;
use crate::outcome::{EstimateBasis, MethodRan, Note, StopReason, WarningCode};
use crate::scene::{Discretization, Outputs};
use std::sync::Arc;

/// The answer to a scene that could be attempted.
#[derive(Debug, Clone)]
pub struct Report {
    /// Echo of the request's `client_id`.
    pub client_id: Option<String>,
    pub status: Status,
    /// The method that ran (after `auto` made its choice).
    pub method: MethodRan,
    /// Iterations of the contact solver.
    pub iterations: usize,
    /// One entry per contact pair, in request order.
    pub pairs: Vec<PairReport>,
    /// Total contact force and moment about the origin acting on the bodies.
    pub resultant: Resultant,
    pub certificate: Certificate,
    pub size: ProblemSize,
    pub diagnostics: Diagnostics,
    pub timings: Timings,
    pub cache: CacheState,
    /// Motion and loads of every punch.
    pub punches: Vec<PunchReport>,
    /// Motion and loads of every coupling (`solution::couplings`).
    pub couplings: Vec<CouplingReport>,
    /// One entry per load factor when the scene lists load factors.
    pub steps: Option<Vec<LoadStep>>,
    /// Per-body fields, when the outputs ask for them.
    pub bodies: Option<Vec<BodyFields>>,
    pub foundations: Vec<FoundationReport>,
    pub notes: Vec<Note>,
    /// Violated assumptions of the model (`solution::validity`).
    pub warnings: Vec<Warning>,
    /// What the request asked to be returned (the reply layer writes the VTU file).
    pub outputs: Outputs,
    /// The bodies are sections of bodies of revolution about the y axis
    /// (the VTU file says so).
    pub axisymmetric: bool,
    /// The rounds of tolerance-driven refinement, when the scene asked for them.
    pub refinement: Option<Refinement>,
    /// The guaranteed bound of the energy-norm error (`solution::energy`),
    /// when the error is estimated and the scene is one the bound covers.
    pub energy: Option<crate::solution::energy::EnergyBound>,
    /// What the energy bound is made from, kept until the answer is known to
    /// be the one returned (`energy::Pending`); never on the wire.
    pub pending_energy: Option<Arc<crate::solution::energy::Pending>>,
}

/// Tolerance-driven refinement (`crate::adapt`).
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    pub reached: bool,
    pub stopped: StopReason,
    pub rounds: Vec<Round>,
}

/// One round of refinement: its size, the smallest generated element size
/// (request units), the largest estimates over the pairs, its seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Round {
    pub dofs: usize,
    pub h_min: f64,
    pub pressure_l2: Option<f64>,
    pub zone_edge: f64,
    pub seconds: f64,
}

impl Report {
    /// The first number of the answer that is not finite, named by where it
    /// sits (`pairs/0/points/3/pressure`), or None. However it arose (an
    /// overflow in the user's units, a NaN the certificate did not see), such
    /// an answer must not be `solved`: JSON would write it as null.
    pub fn first_non_finite(&self) -> Option<String> {
        let mut bad: Option<String> = None;
        let mut check = |name: &dyn Fn() -> String, values: &[f64]| {
            if bad.is_none() && values.iter().any(|v| !v.is_finite()) {
                bad = Some(name());
            }
        };
        check(
            &|| "resultant".into(),
            &[self.resultant.fx, self.resultant.fy, self.resultant.m],
        );
        let c = &self.certificate;
        check(
            &|| "certificate".into(),
            &[c.primal, c.dual, c.complementarity, c.equilibrium],
        );
        let steps = self.steps.iter().flatten().map(|s| &s.pairs);
        for (step, pairs) in std::iter::once(&self.pairs).chain(steps).enumerate() {
            let at = |rest: String| {
                if step == 0 {
                    rest
                } else {
                    format!("steps/{}/{rest}", step - 1)
                }
            };
            for (i, p) in pairs.iter().enumerate() {
                let r = &p.resultant;
                check(
                    &|| at(format!("pairs/{i}/resultant")),
                    &[r.fx, r.fy, r.m, p.max_penetration],
                );
                for z in &p.zones {
                    check(&|| at(format!("pairs/{i}/zones")), z);
                }
                for z in &p.zones_along {
                    let v = [
                        z.s[0],
                        z.s[1],
                        z.start[0],
                        z.start[1],
                        z.end[0],
                        z.end[1],
                        z.uncertainty[0],
                        z.uncertainty[1],
                    ];
                    check(&|| at(format!("pairs/{i}/zones_along")), &v);
                }
                for (k, q) in p.points.iter().enumerate() {
                    let v = [q.x, q.y, q.gap, q.pressure, q.force, q.weight, q.normal[0], q.normal[1]];
                    check(&|| at(format!("pairs/{i}/points/{k}")), &v);
                }
                for (k, q) in p.other_points.iter().flatten().enumerate() {
                    let v = [q.x, q.y, q.pressure, q.force, q.weight];
                    check(&|| at(format!("pairs/{i}/other_points/{k}")), &v);
                }
                if let Some(r) = &p.other_resultant {
                    check(&|| at(format!("pairs/{i}/other_resultant")), &[r.fx, r.fy, r.m]);
                }
                if let Some(f) = &p.friction {
                    let r = &f.tangential_resultant;
                    let v: Vec<f64> = [r.fx, r.fy, r.m]
                        .into_iter()
                        .chain(f.points.iter().flat_map(|q| [q.traction, q.slip]))
                        .collect();
                    check(&|| at(format!("pairs/{i}/friction")), &v);
                }
            }
        }
        for (i, w) in self.warnings.iter().enumerate() {
            check(&|| format!("warnings/{i}"), &[w.value, w.limit]);
        }
        for (i, p) in self.punches.iter().enumerate() {
            let v = [p.alpha1, p.alpha2, p.theta, p.p1, p.p2, p.m];
            check(&|| format!("punches/{i}"), &v);
        }
        for (i, c) in self.couplings.iter().enumerate() {
            check(&|| format!("couplings/{i}"), &[c.ux, c.uy, c.theta, c.fx, c.fy, c.m]);
        }
        for (i, f) in self.foundations.iter().enumerate() {
            check(&|| format!("foundations/{i}/w"), &f.w);
            check(&|| format!("foundations/{i}/load"), &[f.load]);
        }
        for (i, b) in self.bodies.iter().flatten().enumerate() {
            let flat = |v: &Option<Vec<[f64; 2]>>| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
            check(&|| format!("bodies/{i}/displacement"), &flat(&b.displacement));
            let stress: Vec<f64> = b.stress.iter().flatten().flatten().copied().collect();
            check(&|| format!("bodies/{i}/stress"), &stress);
            check(
                &|| format!("bodies/{i}/stress_zz"),
                b.stress_zz.as_deref().unwrap_or(&[]),
            );
        }
        bad
    }
}

pub use crate::outcome::Status;

/// Whether the prepared operator came from a cache.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CacheState {
    Hit,
    Miss,
    Off,
}

/// Relative KKT residuals (dimensionless, each ≥ 0; see `solution::certificate`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Certificate {
    pub primal: f64,
    pub dual: f64,
    pub complementarity: f64,
    pub equilibrium: f64,
    /// With friction: the Coulomb conditions' residuals.
    pub friction: Option<FrictionResiduals>,
}

impl Certificate {
    pub fn worst(&self) -> f64 {
        let f = self.friction.map_or(0.0, |f| f.cone.max(f.dissipation).max(f.stick));
        self.primal
            .max(self.dual)
            .max(self.complementarity)
            .max(self.equilibrium)
            .max(f)
    }
    /// Every entry finite (`worst` alone would hide a NaN: f64::max ignores it).
    pub fn is_finite(&self) -> bool {
        let f = self.friction.map_or([0.0; 3], |f| [f.cone, f.dissipation, f.stick]);
        [self.primal, self.dual, self.complementarity, self.equilibrium]
            .iter()
            .chain(&f)
            .all(|v| v.is_finite())
    }
}

/// Relative residuals of the Coulomb conditions, each ≥ 0 (`solution::friction`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FrictionResiduals {
    /// max(0, |τ| − μλ) / ‖λ‖∞.
    pub cone: f64,
    /// max(0, −τ Δs) / (‖λ‖∞ D): the friction force may not do positive work.
    pub dissipation: f64,
    /// (μλ − |τ|) |Δs| / (‖λ‖∞ D): no slip inside the cone.
    pub stick: f64,
}

/// Force and moment about the origin (counter-clockwise positive).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Resultant {
    pub fx: f64,
    pub fy: f64,
    pub m: f64,
}

/// A violated assumption of the model, or a discretization too coarse to
/// trust: the measured value and the limit.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    pub code: WarningCode,
    pub value: f64,
    pub limit: f64,
    /// JSON pointer of the body, obstacle or pair concerned.
    pub location: String,
    /// What was measured, what it means and what to do, in the request's units.
    pub message: String,
}

/// A punch's rigid motion and the loads on it.
#[derive(Debug, Clone)]
pub struct PunchReport {
    pub name: String,
    pub alpha1: f64,
    pub alpha2: f64,
    pub theta: f64,
    pub p1: f64,
    pub p2: f64,
    pub m: f64,
    pub unique: bool,
    pub note: Option<String>,
}

/// A coupling's reference point: its motion and the loads that act on the
/// body through it (given, or the reactions that hold it).
#[derive(Debug, Clone)]
pub struct CouplingReport {
    /// JSON pointer of the coupling in the request.
    pub path: String,
    pub body: String,
    pub ux: f64,
    pub uy: f64,
    pub theta: f64,
    pub fx: f64,
    pub fy: f64,
    pub m: f64,
}

/// The answer at one load factor.
#[derive(Debug, Clone)]
pub struct LoadStep {
    pub factor: f64,
    /// A load path step's factors, by JSON pointer (None for a load factor).
    pub loads: Option<std::collections::BTreeMap<String, f64>>,
    pub status: Status,
    pub iterations: usize,
    pub pairs: Vec<PairReport>,
    pub resultant: Resultant,
    pub certificate: Certificate,
    pub couplings: Vec<CouplingReport>,
    /// The step's own warnings, merged into the reply's by `with_steps`
    /// (not on the wire per step).
    pub warnings: Vec<Warning>,
}

impl LoadStep {
    /// The step of `factor` (and a load path's `loads`) that `r` answers.
    pub fn of(factor: f64, loads: Option<std::collections::BTreeMap<String, f64>>, r: &Report) -> Self {
        Self {
            factor,
            loads,
            status: r.status,
            iterations: r.iterations,
            pairs: r.pairs.clone(),
            resultant: r.resultant,
            certificate: r.certificate,
            couplings: r.couplings.clone(),
            warnings: r.warnings.clone(),
        }
    }

    /// Where this step is, for a warning read from it: "load path step i"
    /// or "load factor k".
    fn label(&self, i: usize) -> String {
        match self.loads {
            Some(_) => format!("load path step {i}"),
            None => format!("load factor {}", self.factor),
        }
    }
}

/// Whether warning `a` is further past its limit than `b` (the same kind at
/// the same place), whichever side of its limit it fires on (a displacement
/// above it, a zone's width in spacings below it). A limit of 0 (a count of
/// nodes, say) compares the values; a NaN value is the worst: it must not be
/// hidden behind a finite one.
fn worse(a: &Warning, b: &Warning) -> bool {
    if a.value.is_nan() || b.value.is_nan() {
        return a.value.is_nan() && !b.value.is_nan();
    }
    if a.limit == 0.0 || b.limit == 0.0 {
        return a.value.abs() > b.value.abs();
    }
    let past = |w: &Warning| {
        let (v, l) = (w.value.abs(), w.limit.abs());
        (v / l).max(l / v)
    };
    past(a) > past(b)
}

/// The last step's report with every step and their summed timings: only as
/// good as its worst step.
pub fn with_steps(mut last: Report, steps: Vec<LoadStep>, timings: Timings) -> Report {
    if let Some(bad) = steps.iter().find(|st| st.status != Status::Solved) {
        last.status = bad.status;
    }
    last.warnings = step_warnings(std::mem::take(&mut last.warnings), &steps);
    last.timings = timings;
    last.steps = Some(steps);
    last
}

/// The last step's warnings with every earlier step's: each kind at each
/// place from the step where it is furthest past its limit, named there
/// when that is not the last step. A path through a load far too large for
/// the modulus that ends on a small one must still say so; the reply read
/// the last step's alone. The last step's warnings keep their order; the
/// others follow in the order the steps first raised them.
fn step_warnings(last: Vec<Warning>, steps: &[LoadStep]) -> Vec<Warning> {
    let earlier = steps.len().saturating_sub(1);
    let named = steps
        .iter()
        .enumerate()
        .take(earlier)
        .map(|(i, step)| (step.label(i), step.warnings.as_slice()));
    worst_of_steps(last, named)
}

/// `last` (the last step's warnings) with the `earlier` steps' (each with
/// the label that names it, "load factor k" or "load path step i"), as
/// `step_warnings` merges them; a tie stays with the last step. Shared by
/// the 2D steps and a solid's.
pub fn worst_of_steps<'a>(
    last: Vec<Warning>,
    earlier: impl IntoIterator<Item = (String, &'a [Warning])>,
) -> Vec<Warning> {
    let same = |a: &Warning, b: &Warning| a.code == b.code && a.location == b.location;
    let mut out = last;
    for (label, warnings) in earlier {
        for w in warnings {
            let mut named = w.clone();
            named.message = format!("{} (at {label})", w.message);
            match out.iter().position(|o| same(o, w)) {
                Some(j) if worse(w, &out[j]) => out[j] = named,
                Some(_) => {}
                None => out.push(named),
            }
        }
    }
    out
}

/// What touches what in one pair.
#[derive(Debug, Clone)]
pub enum PairTarget {
    Obstacle(String),
    /// The other body and its discretization.
    Body(String, Discretization),
    Foundation(String),
}

#[derive(Debug, Clone)]
pub struct PairReport {
    pub body: String,
    pub target: PairTarget,
    /// The target's surface goes on past the ends of the body's edge set
    /// and carries load there (a Pasternak layer, an elastic half-plane):
    /// an end of the edge set pressed into it is a corner on it, where the
    /// pressure may be unbounded (`corners`).
    pub goes_on: bool,
    /// Intervals [x_start, x_end] along x1 where the body touches: the
    /// x-extent of each zone of `zones_along`, in increasing x.
    pub zones: Vec<[f64; 2]>,
    /// The same zones along the pair's own surface, in the order of its edge set.
    pub zones_along: Vec<ZoneAlong>,
    pub points: Vec<ContactPoint>,
    pub resultant: Resultant,
    pub max_penetration: f64,
    pub pruned: usize,
    /// Two bodies: the pressure at the other body's nodes, and its resultant.
    pub other_points: Option<Vec<CounterPoint>>,
    pub other_resultant: Option<Resultant>,
    /// The estimated error of the pair's answer (`solution::accuracy`).
    pub accuracy: Option<PairAccuracy>,
    /// A pair with friction (`solution::friction`).
    pub friction: Option<PairFriction>,
}

/// A posteriori error estimate of a pair (`solution::accuracy`): relative
/// errors, and the zone ends' in the request's length unit.
#[derive(Debug, Clone, PartialEq)]
pub struct PairAccuracy {
    pub basis: EstimateBasis,
    pub pressure_l2: Option<f64>,
    pub peak: Option<f64>,
    pub resultant: Option<f64>,
    pub zone_edges: Vec<[f64; 2]>,
    /// Estimated error of each zone's fitted edges (`ZoneAlong::fitted`),
    /// None where none is fitted.
    pub fitted_edges: Vec<[Option<f64>; 2]>,
    /// Zone ends where the pressure is unbounded (`solution::corners`):
    /// `pressure_l2` and `peak` leave out the band around each.
    pub singular_ends: Vec<SingularEnd>,
    /// Guaranteed upper bound of the relative energy-norm error of the whole
    /// answer (`solution::energy`), None where the scene is outside its reach.
    pub energy: Option<f64>,
}

/// A zone end where the pressure is unbounded, and the radius of the band
/// around it that the pressure's estimate leaves out (request's units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularEnd {
    pub at: [f64; 2],
    pub band: f64,
}

/// Friction on one pair, in the request's units.
#[derive(Debug, Clone)]
pub struct PairFriction {
    pub coefficient: f64,
    /// Runs of sticking and of slipping points, [x_first, x_last].
    pub stick_zones: Vec<[f64; 2]>,
    pub slip_zones: Vec<[f64; 2]>,
    /// The same runs by their first and last points (x, y).
    pub stick_runs: Vec<[[f64; 2]; 2]>,
    pub slip_runs: Vec<[[f64; 2]; 2]>,
    /// Of the friction forces on the body.
    pub tangential_resultant: Resultant,
    /// One per entry of `PairReport::points`, in the same order.
    pub points: Vec<PointFriction>,
}

/// A contact point's tangential traction (along the normal turned 90° counter-clockwise, on the body), its slip
/// in the step along the same direction, and its state (`proto::FrictionState` says what each means).
#[derive(Debug, Clone, Copy)]
pub struct PointFriction {
    pub traction: f64,
    /// The row's tangent where it is not the normal turned 90° (two bodies).
    pub tangent: Option<[f64; 2]>,
    pub slip: f64,
    pub state: FrictionState,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionState {
    Stick,
    Slip,
    Open,
    Prescribed,
}

/// A contact zone along the surface of its edge set: arc length from the
/// set's first node (along its edges, chain after chain) and the coordinates
/// of its two ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZoneAlong {
    pub s: [f64; 2],
    pub start: [f64; 2],
    pub end: [f64; 2],
    /// Estimated error of the start's and the end's position along the
    /// surface (`solution::accuracy`).
    pub uncertainty: [f64; 2],
    /// The start's and the end's smooth edge where the fit of p² places it
    /// (`solution::accuracy::end_fit`), within a facet of the last node in
    /// contact, either side; None at a sharp corner, a foundation's lift-off, the
    /// end of the edge set or where too few nodes are in contact to fit.
    pub fitted: [Option<FittedEnd>; 2],
}

/// A zone's smooth edge between nodes: arc length along the surface, as
/// `ZoneAlong::s`, and position (on the chord of its facet).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FittedEnd {
    pub s: f64,
    pub at: [f64; 2],
    /// `accuracy::EndFit::scatter`.
    pub scatter: f64,
}

/// A node of the other body of a two-body pair.
#[derive(Debug, Clone)]
pub struct CounterPoint {
    pub x: f64,
    pub y: f64,
    pub pressure: f64,
    pub force: f64,
    pub weight: f64,
    pub node: usize,
}

/// A contact row.
#[derive(Debug, Clone)]
pub struct ContactPoint {
    pub x: f64,
    pub y: f64,
    pub gap: f64,
    /// Positive in compression.
    pub pressure: f64,
    pub force: f64,
    pub weight: f64,
    pub node: usize,
    pub normal: [f64; 2],
}

#[derive(Debug, Clone, Copy, Default)]
pub struct ProblemSize {
    pub dofs: usize,
    pub candidates: usize,
    pub active: usize,
}

#[derive(Debug, Clone, Copy, Default)]
pub struct Diagnostics {
    pub condition_estimate: Option<f64>,
    pub refinements: usize,
    pub factorization_predicted: Option<f64>,
    /// The contact rows W was formed over when screening left some out
    /// (`solve::screen`); None: every candidate.
    pub condensed_rows: Option<usize>,
}

/// Per-body fields (each present when asked for).
#[derive(Debug, Clone)]
pub struct BodyFields {
    pub name: String,
    pub nodes: Option<Vec<[f64; 2]>>,
    pub elements: Option<Vec<Vec<usize>>>,
    pub displacement: Option<Vec<[f64; 2]>>,
    /// Element-centroid stress [σxx, σyy, σxy].
    pub stress: Option<Vec<[f64; 3]>>,
    /// σzz at the same points (plane strain: ν (σxx + σyy); plane stress: 0;
    /// axisymmetry: the hoop stress), with the VTU output or, in axisymmetry,
    /// with the stress.
    pub stress_zz: Option<Vec<f64>>,
}

/// A foundation's surface deflection along its whole length.
#[derive(Debug, Clone)]
pub struct FoundationReport {
    pub name: String,
    /// "winkler", "pasternak" or "half_plane".
    pub model: &'static str,
    pub x: Vec<f64>,
    pub w: Vec<f64>,
    pub reference_distance: Option<f64>,
    pub load: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn warning(code: WarningCode, value: f64, limit: f64) -> Warning {
        Warning {
            code,
            value,
            limit,
            location: "/contacts/0".into(),
            message: "m".into(),
        }
    }

    fn step(factor: f64, warnings: Vec<Warning>) -> LoadStep {
        LoadStep {
            factor,
            loads: None,
            status: Status::Solved,
            iterations: 0,
            pairs: Vec::new(),
            resultant: Resultant::default(),
            certificate: Certificate::default(),
            couplings: Vec::new(),
            warnings,
        }
    }

    /// The worst step's warning is kept, named when not the last: a zone 1
    /// spacing wide is further past the limit of 4 than one 2 wide (the
    /// warning fires below its limit); a count against a limit of 0 is
    /// compared as a count; a NaN is never replaced by a finite value.
    #[test]
    fn each_warning_is_the_worst_steps() {
        let coarse = WarningCode::CoarseContactZone;
        let slip = WarningCode::PrescribedSlip;
        let last = vec![warning(coarse, 2.0, 4.0), warning(slip, 3.0, 0.0)];
        let steps = [
            step(0.5, vec![warning(coarse, 1.0, 4.0), warning(slip, 5.0, 0.0)]),
            step(1.0, last.clone()),
        ];
        let out = step_warnings(last, &steps);
        assert_eq!(out.len(), 2);
        assert_eq!((out[0].value, out[0].message.as_str()), (1.0, "m (at load factor 0.5)"));
        assert_eq!((out[1].value, out[1].message.as_str()), (5.0, "m (at load factor 0.5)"));
        let last = vec![warning(coarse, f64::NAN, 4.0)];
        let steps = [step(0.5, vec![warning(coarse, 1.0, 4.0)]), step(1.0, last.clone())];
        assert!(step_warnings(last, &steps)[0].value.is_nan());
        // A kind only an earlier step raised is added after the last step's.
        let steps = [step(0.5, vec![warning(slip, 1.0, 0.0)]), step(1.0, Vec::new())];
        let out = step_warnings(Vec::new(), &steps);
        assert_eq!((out.len(), out[0].code), (1, slip));
    }
}
