//! The solve reply. Lengths, forces and pressures are in the request's units.
//!
//! Length: the whole reply in one file, so that its documentation (these doc
//! comments, which become the JSON schema's descriptions) reads as one page.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The answer to a solve request that could be attempted.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolveReply {
    pub version: String,
    /// Echo of the request's `client_id`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub client_id: Option<String>,
    /// Server-side id of this request, `<instance>-<n>` (set by the service, absent from the CLI).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub request_id: Option<String>,
    /// "solved" when the certificate meets the tolerance; otherwise why not.
    pub status: SolveStatus,
    /// The method that ran (after `auto` made its choice).
    pub method: MethodRan,
    /// Iterations of the contact solver.
    pub iterations: usize,
    /// One entry per contact pair, in request order (empty for a 3D solid:
    /// see `solid`).
    pub pairs: Vec<PairResult>,
    /// Total contact force and moment about the origin acting on the bodies
    /// (for a 3D solid: its x and y force and its moment about the z axis;
    /// the whole resultant is `solid.resultant`).
    pub resultant: Resultant,
    /// KKT residuals of the discrete solution, relative and dimensionless.
    pub certificate: Certificate,
    /// Problem sizes.
    pub size: ProblemSize,
    /// Numerical health of the solve.
    #[serde(default)]
    pub diagnostics: Diagnostics,
    /// Wall-clock seconds per stage.
    pub timings: Timings,
    /// Whether the factorization and condensed operator came from the service's cache.
    pub cache: CacheState,
    /// Motion and loads of every punch (obstacle with `punch`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub punches: Vec<PunchResult>,
    /// Motion and loads of every coupling (a body's `couplings`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub couplings: Vec<CouplingResult>,
    /// One entry per load factor when the request lists `load_factors`; the
    /// top-level fields then describe the last factor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<Vec<LoadStep>>,
    /// Per body, when `outputs` asks for it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bodies: Option<Vec<BodyOutput>>,
    /// Surface deflection of every foundation a body rests on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub foundations: Vec<FoundationResult>,
    /// What the user should know about this solution (e.g. a rigid motion of a
    /// body held only by contact that nothing determines).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// What each note is about: `note_kinds[i]` is the kind of `notes[i]`, the
    /// two lists as long (a parallel list, so that a client reading `notes` as
    /// strings reads them as before).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub note_kinds: Vec<NoteKind>,
    /// Assumptions of the model (small strain, small rotation, linearized
    /// gaps) that this solution violates: its numbers answer the linear model,
    /// which is then not a model of the physical scene. Limits: strain 5e-2,
    /// rotation 0.15 rad, displacement 5e-2 of the body's size, contact
    /// half-width 0.3 of a curved obstacle's radius, contact displacement 5e-2
    /// of that radius. With `load_factors` or `load_path`, every step is
    /// read: each kind at each place comes from the step where it is furthest
    /// past its limit, and its message names that step when it is not the
    /// last (a solid's `large_displacement` likewise; its patches' warnings
    /// are the last step's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<Warning>,
    /// With `outputs` listing `vtu`: the VTK XML unstructured grid of every body
    /// (point data `displacement`, `contact_pressure`; cell data `stress`,
    /// `stress_tensor` (XX, YY, ZZ, XY, YZ, XZ), `von_mises`,
    /// `principal_stress`, `body`), base64-encoded; decode and save as `.vtu`
    /// for ParaView. For a 3D solid: its tetrahedra (VTK types 10 and 24),
    /// point data `displacement` (ux, uy, uz) and `contact_pressure`, cell
    /// data `stress_tensor` and `von_mises`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vtu: Option<String>,
    /// Echo of the request's `units` (names only: the numbers are in the
    /// request's units either way).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<crate::Units>,
    /// With `settings.accuracy`: the rounds of refinement that led to this
    /// answer (the top-level fields describe the last round).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refinement: Option<Refinement>,
    /// The answer of a 3D solid (`analysis: "solid"`): its contact patches,
    /// points and resultant. Its `timings.factorization` includes the
    /// condensation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solid: Option<crate::solid::SolidResult>,
}

/// Tolerance-driven refinement: each round halves the generated meshes'
/// element sizes near the contact zones (and shrinks them by √2 away from
/// them), or splits every triangle of a given (inline or Gmsh) mesh in four,
/// and solves again. A 3D solid's rounds shrink its generated box's `h_min`
/// (a given 3D mesh is not refined).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Refinement {
    /// Whether every estimate met its target.
    pub reached: bool,
    /// Why the rounds stopped: `reached` (every estimate within 0.6 of its
    /// target), `no_contact` (nothing touches: no contact error to reduce),
    /// `max_rounds`, `max_dofs`, `size_limit`, `time_limit`, `not_converging`
    /// (two rounds without progress), `not_solved` or `round_failed` (the
    /// next round could not be solved; the warning says why).
    pub stopped: StopReason,
    pub rounds: Vec<RefinementRound>,
}

/// One solve of tolerance-driven refinement.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RefinementRound {
    pub dofs: usize,
    /// Smallest element size asked of the generators in this round (a given
    /// 3D mesh refined in rounds: its shortest element edge) [length].
    pub h_min: f64,
    /// Largest estimated `pressure_l2` over the pairs (null where not estimated).
    pub pressure_l2: Option<f64>,
    /// Largest estimated zone-end error over the pairs [length]; 0 for a 3D
    /// solid, whose patches have no zone ends.
    pub zone_edge: f64,
    /// Wall-clock seconds of the round (its solve and its estimate).
    pub seconds: f64,
}

/// A posteriori error estimate of one pair's answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PairAccuracy {
    /// How the estimate was made: `two_level` (this solve against one with
    /// every element twice as large, Richardson-scaled: generated meshes
    /// with their sizes doubled, a given inline or Gmsh mesh's region meshed
    /// again from every other boundary node and interior node),
    /// `two_level_finer` (a given mesh whose region cannot be meshed again, a
    /// hole or several boundary loops, against the same mesh with every
    /// triangle split in four) or `zone_edges` (the companion
    /// could not be solved or would be too large, as the reply's notes say:
    /// only the zone ends).
    pub basis: EstimateBasis,
    /// Estimated relative L2 error of the pressure over the zone: of the
    /// field the reply describes, p² linear between the nodes and falling as
    /// a square root on each zone's last facet to its fitted edge
    /// (`zones_along[].fitted`), in the L2 norm along the surface. A zone's
    /// last node in contact past its fitted edge reads 0 in that field: its
    /// value is a weighted mean over its facets, not the pressure there.
    pub pressure_l2: Option<f64>,
    /// Estimated relative error of the peak pressure: of the largest nodal
    /// pressure (`points[].pressure`) outside the bands of `singular_ends`,
    /// against the converged peak.
    pub peak: Option<f64>,
    /// Estimated relative error of the pair's resultant force.
    pub resultant: Option<f64>,
    /// Estimated error of each zone's start and end along the surface, in
    /// the order of `zones_along` [length].
    pub zone_edges: Vec<[f64; 2]>,
    /// Estimated error of each zone's fitted start and end
    /// (`zones_along[].fitted`) along the surface, in the order of
    /// `zones_along`, null where no edge is fitted [length]: the two levels'
    /// fitted edges' distance, Richardson-scaled as `pressure_l2`.
    #[serde(default)]
    pub fitted_edges: Vec<[Option<f64>; 2]>,
    /// Zone ends where the pressure is unbounded (a punch's sharp corner,
    /// p ~ d^(-1/2); a footing's edge on a Pasternak layer, which carries a
    /// concentrated line load, or on an elastic half-plane): its L2 norm is
    /// infinite there, so `pressure_l2` and
    /// `peak` leave out the band of radius `band` around each (5 % of the
    /// zone's length). Read the resultant and the zone there.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub singular_ends: Vec<SingularEnd>,
    /// Guaranteed upper bound of the energy-norm error of the whole answer
    /// (all bodies), relative to the answer's own: ‖u − u_h‖_E / ‖u_h‖_E ≤
    /// energy, from a stress in exact equilibrium (Prager–Synge), whatever
    /// the mesh. u is the exact solution of the model solved: the meshed
    /// bodies and the linearized signed-distance gap. It bounds the energy of
    /// the error (stress and strain in the mean square), not the pressure,
    /// the peak or a zone end, which `pressure_l2`, `peak` and `zone_edges`
    /// estimate. Absent where the scene is outside its reach: it covers
    /// frictionless contact of linear triangles (T3) in plane strain or plane
    /// stress against rigid obstacles and punches (under load or motion
    /// control) whose sides in contact face straight or circular pieces, and
    /// on tensionless Winkler foundations (a body they alone hold included),
    /// under supports, uniform tractions and pressures, and body forces, and
    /// straight-sided quadratic triangles (T6) in the same scenes, the P2–P0
    /// element (T6 at ν ≥ 0.45 in plane strain) included: its bound is of
    /// the true energy's error, which holds λ ‖tr ε − its element mean‖²
    /// and grows like √λ as ν → ½ (0.19 at ν = 0.49, 0.54 at 0.499 on a
    /// coarse Hertz block). Not curved T6, axisymmetry, friction, two bodies,
    /// Pasternak or half-plane
    /// foundations, point loads (whose energy is infinite), tractions over
    /// part of a side, couplings, bodies moved by contact with obstacles
    /// alone, or contact at a sharp corner, a polyline's vertex or a spline
    /// (a note then says why).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy: Option<f64>,
}

/// A zone end where the pressure is unbounded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SingularEnd {
    /// The end's position (x, y) [length].
    pub at: [f64; 2],
    /// Radius of the band left out of the pressure's estimate [length].
    pub band: f64,
}

/// A violated assumption of the model, or a discretization too coarse to
/// trust, with the measured value, the limit (both dimensionless) and what
/// it means.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Warning {
    /// `large_strain` (largest principal strain, mean over patches a tenth of
    /// the body's narrowest contact zone wide), `large_rotation` (largest
    /// material or punch rotation, radian), `large_displacement` (largest
    /// displacement over the body's size), `large_contact_zone` (how far the
    /// zone reaches onto the obstacle's curved part, over its radius of
    /// curvature), `gap_linearization` (largest displacement of a contact
    /// point over the obstacle's radius), `rolling` (a body held only by
    /// contact turning under its loads: its rotation times its surface's
    /// radius of curvature at a contact zone, over the zone's half-width):
    /// each fires when value > limit;
    /// `prescribed_slip` (frictional contact points of a pair whose slip
    /// relative to the other surface the supports prescribe, so that their
    /// friction force is μ λ, unbounded as μ grows; checked before the solve;
    /// the message lists their positions and the supports) fires when value >
    /// limit 0;
    /// `coarse_contact_zone` (element edges across a contact zone) fires when
    /// value < limit.
    pub code: WarningCode,
    pub value: f64,
    pub limit: f64,
    /// JSON pointer of the body, obstacle or contact pair concerned.
    pub location: String,
    /// What was measured, what it means and what to do (numbers in the
    /// request's units).
    #[serde(default)]
    pub message: String,
}

/// A punch's rigid motion and the loads on it (prescribed or reactions).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PunchResult {
    pub name: String,
    /// Horizontal displacement α1 [length].
    pub alpha1: f64,
    /// Vertical displacement α2 [length].
    pub alpha2: f64,
    /// Rotation θ about the reference point [radian], counter-clockwise.
    pub theta: f64,
    /// Loads on the punch balancing the contact: P1, P2 [force], M about the reference [force × length].
    pub p1: f64,
    pub p2: f64,
    pub m: f64,
    /// False when some motion is not determined by the contact (e.g. sliding of a flat punch).
    pub unique: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// A coupling's reference point: its motion and the loads acting on the body
/// through it (those given, or the reactions holding the prescribed motions).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CouplingResult {
    /// JSON pointer of the coupling in the request (`/bodies/0/couplings/0`).
    pub path: String,
    /// Name of the coupled body.
    pub body: String,
    /// Displacement of the reference point [length].
    pub ux: f64,
    pub uy: f64,
    /// Rotation about the reference point [radian], counter-clockwise.
    pub theta: f64,
    /// Force on the body through the coupling [force] and its moment about
    /// the reference point [force × length]: a load component as given (to the
    /// solve's round-off), a displacement component's reaction. In axisymmetry
    /// fx and m are 0 (ring forces cancel).
    pub fx: f64,
    pub fy: f64,
    pub m: f64,
}

/// The answer at one load factor.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadStep {
    /// The load factor (1 for a `load_path` step, whose factors are `loads`).
    pub factor: f64,
    /// A `load_path` step's factors, as given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loads: Option<std::collections::BTreeMap<String, f64>>,
    pub status: SolveStatus,
    pub iterations: usize,
    pub pairs: Vec<PairResult>,
    pub resultant: Resultant,
    pub certificate: Certificate,
    /// Every coupling at this step (as the reply's `couplings`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub couplings: Vec<CouplingResult>,
    /// A 3D solid's answer at this factor (`resultant` then holds its x and
    /// y force and its moment about z, as the reply's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solid: Option<crate::solid::SolidStepResult>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CacheState {
    /// Reused: assembly of K, factorization and condensation were skipped.
    Hit,
    /// Computed and stored for later requests on the same mesh, material, supports and candidates.
    Miss,
    /// No cache (the CLI).
    Off,
}

/// The contact method that produced the answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MethodRan {
    /// Condensed active set (semismooth Newton on the LCP), the default.
    ActiveSet,
    /// Condensed interior point (Clarabel).
    InteriorPoint,
    /// Exterior penalty: inexact by construction.
    Penalty,
    /// Augmented Lagrangian on the penalty's springs.
    AugmentedLagrangian,
    /// Log barrier: inexact by construction.
    Barrier,
    /// Active set on the full saddle-point system.
    ActiveSetFull,
    /// Interior point on the full QP.
    InteriorPointFull,
}

/// Why tolerance-driven refinement stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// Every estimate within 0.6 of its target.
    Reached,
    /// Nothing touches: no contact error to reduce.
    NoContact,
    /// A round's answer was not `solved`.
    NotSolved,
    /// `accuracy.max_rounds` rounds ran.
    MaxRounds,
    /// The next round would pass `accuracy.max_dofs` (or the service's size or memory limit).
    MaxDofs,
    /// The next round would not end within the time limit.
    TimeLimit,
    /// The next round passed the service's size limit.
    SizeLimit,
    /// The next round could not be solved; the last answer stands.
    RoundFailed,
    /// Two rounds without progress.
    NotConverging,
}

/// What a pair's error estimate is based on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum EstimateBasis {
    /// Against a companion with every element twice as large (generated
    /// meshes resized; a given mesh's region meshed again).
    TwoLevel,
    /// A given inline or Gmsh mesh whose region cannot be meshed again (a
    /// hole, several boundary loops) against itself with every triangle split
    /// in four.
    TwoLevelFiner,
    /// No companion could be solved: the zone ends only.
    ZoneEdges,
    /// No estimate at all (3D solids only): a given inline or Gmsh mesh, for
    /// which no companion is made, or a companion that did not solve; the
    /// reply's notes say why.
    #[serde(rename = "none")]
    NoEstimate,
}

/// What a warning is about (see `Warning`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WarningCode {
    LargeStrain,
    LargeRotation,
    LargeDisplacement,
    Rolling,
    CoarseContactZone,
    LargeContactZone,
    GapLinearization,
    ToleranceNotReached,
    PrescribedSlip,
}

/// What a note is about (see `notes`, `note_kinds`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum NoteKind {
    /// A two-body pair turned round: the much stiffer body is the other side.
    PairSwapped,
    /// A nearly incompressible body on linear triangles, which lock.
    NearlyIncompressible,
    /// A nearly incompressible body on T6 ran the locking-free P2–P0 element.
    #[serde(rename = "p2_p0_element")]
    P2P0Element,
    /// A rigid motion that nothing determines, reported at 0.
    UndeterminedMotion,
    /// `auto`'s active set did not converge; the interior point ran.
    MethodFallback,
    /// Too many frictional rows for the condensed formulation: solved on the full system.
    FullSystem,
    /// The answer holds a number that is not finite: it must not be used.
    NonFinite,
    /// The contact forces are far beyond what the loads and the deformation can balance: they cancel each other and
    /// must not be read.
    UnboundedForces,
    /// The error estimate's companion was not solved: only the zone ends are estimated.
    EstimateLimited,
    /// Nothing is in contact: `settings.accuracy` did not refine.
    NotRefined,
    /// A frictional step with a load-controlled punch ran out of iterations: it most likely slides.
    SlidingPunch,
    /// A frictional step with a body held only by contact ran out of iterations.
    UnsettledBody,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SolveStatus {
    /// Converged; the certificate is within the tolerance.
    Solved,
    /// Stopped at the iteration cap; the certificate tells how far off it is.
    MaxIterations,
    /// The linear algebra lost accuracy (see certificate); do not trust the numbers.
    NumericalError,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PairResult {
    pub body: String,
    /// The rigid obstacle of an obstacle pair.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<String>,
    /// The other body of a two-body pair (its `against` edge set).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub against: Option<String>,
    /// The foundation of a foundation pair.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub foundation: Option<String>,
    /// Discretization of a two-body pair.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub discretization: Option<crate::Discretization>,
    /// Intervals [x_start, x_end] along x1 where the body touches, in
    /// increasing x: the x-extent of each zone of `zones_along`, from its
    /// first to its last node in contact (the last node whose pressure is
    /// positive, for every discretization; foundation: the union of the
    /// active nodes' panels, on which the foundation pressure is constant).
    /// Where the pair's surface is not a graph over x (a vertical or
    /// re-entrant face) this is only the zones' shadow on x: read `zones_along`.
    pub zones: Vec<[f64; 2]>,
    /// The same zones along the pair's own surface, in the order of its edge
    /// set: arc length from the edge set's first node and the coordinates of
    /// both ends. Absent from replies written before it existed.
    #[serde(default)]
    pub zones_along: Vec<ZoneAlong>,
    /// Every contact candidate of the pair, ordered along the boundary.
    pub points: Vec<ContactPoint>,
    /// Contact force and moment about the origin on the body from this pair.
    pub resultant: Resultant,
    /// Largest penetration (−gap) over the candidates, ≥ 0.
    pub max_penetration: f64,
    /// Candidates dropped because their initial gap cannot close.
    pub pruned: usize,
    /// Two bodies: the pressure as the other body sees it, at its nodes on the
    /// `against` edge set (nodal contact force over its tributary length).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub other_points: Option<Vec<CounterPoint>>,
    /// Two bodies: contact force and moment about the origin on the other body
    /// (equal and opposite to `resultant`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub other_resultant: Option<Resultant>,
    /// The estimated error of this pair's answer (absent with `settings.estimate` false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<PairAccuracy>,
    /// A pair with friction: its stick and slip zones and tangential resultant
    /// (`resultant` includes the friction forces).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<PairFriction>,
}

/// Friction on one pair.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PairFriction {
    /// μ.
    pub coefficient: f64,
    /// Runs of consecutive points that stick, [x_start, x_end] (first and
    /// last point of the run) in increasing x.
    pub stick_zones: Vec<[f64; 2]>,
    /// Runs of consecutive points that slip, [x_start, x_end].
    pub slip_zones: Vec<[f64; 2]>,
    /// The runs of `stick_zones` by their first and last points,
    /// [[x, y], [x, y]]: on a surface that is not a graph over x (a vertical
    /// bore, a re-entrant face) the x-intervals collapse, these do not.
    #[serde(default)]
    pub stick_runs: Vec<[[f64; 2]; 2]>,
    /// The runs of `slip_zones` by their first and last points.
    #[serde(default)]
    pub slip_runs: Vec<[[f64; 2]; 2]>,
    /// Force and moment about the origin of the tangential (friction)
    /// tractions on the body.
    pub tangential_resultant: Resultant,
}

/// A contact point's friction state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FrictionState {
    /// In contact, |t| < μ p (no slip in this step; |t| = μ p only by chance).
    Stick,
    /// In contact and sliding: |t| = μ p, opposite to the slip.
    Slip,
    /// Not in contact.
    Open,
    /// In contact where no free motion moves the point along the surface
    /// (supports hold every displacement its slip reads, on both sides): the
    /// slip is the one the supports prescribe, and the model applies no
    /// friction force there (the supports take it, outside the reply's
    /// friction). `tangential_traction` is then the normal force's share
    /// along the tangent alone (0 against an obstacle). A `prescribed_slip`
    /// warning names such points when their slip is not 0.
    Prescribed,
}
/// A contact zone along the surface of the pair's edge set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ZoneAlong {
    /// Arc length of the zone's start from the edge set's first node,
    /// measured along its edges (chained head to tail, the body on their
    /// left; the start of the chain holding them, further chains following
    /// with the arc length running on) [length].
    pub s_start: f64,
    /// Arc length of the zone's end, ≥ `s_start` [length]. On a closed edge
    /// set (a whole disk's rim) a zone across the node its chain starts at
    /// is one zone whose end runs on past the perimeter.
    pub s_end: f64,
    /// Undeformed position [x, y] of the zone's start.
    pub start: [f64; 2],
    /// Undeformed position [x, y] of the zone's end.
    pub end: [f64; 2],
    /// Estimated error of the start's and the end's position along the
    /// surface [length]: the zone ends at its last node in contact, and a
    /// least-squares fit of the square-root pressure drop places the edge
    /// between that node and the next (at least a quarter of their spacing);
    /// the spacing to the next surface node where no such edge is found (a
    /// sharp punch corner); half the spacing at a foundation's lift-off; 0
    /// where the zone ends with its edge set.
    #[serde(default)]
    pub uncertainty: [f64; 2],
    /// The start's and the end's smooth edge where the least-squares fit of
    /// p² (linear in the distance to a square-root edge) places it, within a
    /// facet of the last node in contact: between it and the next node, or
    /// between it and the node before (a mortar row's last node can lie
    /// just past the edge, its pressure a weighted mean over both facets),
    /// or null (a sharp punch corner, a foundation's lift-off, the end of the
    /// edge set, too few nodes in contact to fit). This is the zone end the
    /// reply describes: on the facet from the last node in contact before
    /// it, the pressure falls as p_node √(1 − d/d_edge) (d from that node),
    /// and it is 0 beyond.
    /// `accuracy.pressure_l2` estimates the error of that described field
    /// and `accuracy.fitted_edges` the error of these ends.
    #[serde(default)]
    pub fitted: [Option<FittedEnd>; 2],
}

/// A zone's smooth edge placed between nodes by the fit of p².
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FittedEnd {
    /// Arc length along the surface, as `s_start`/`s_end` [length].
    pub s: f64,
    /// Undeformed position, on the chord of the facet it lies on [length].
    pub x: f64,
    pub y: f64,
}

/// A node of the other body of a two-body pair.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CounterPoint {
    /// Undeformed position.
    pub x: f64,
    pub y: f64,
    /// Contact pressure on this body, positive in compression [force/length²].
    pub pressure: f64,
    /// Nodal contact force (per unit thickness) along the inward normal.
    pub force: f64,
    /// Tributary length of the node on the edge set.
    pub weight: f64,
    /// Node index in this body's mesh.
    pub node: usize,
}

/// A contact candidate node.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactPoint {
    /// Undeformed position.
    pub x: f64,
    pub y: f64,
    /// Gap after deformation, along the row's direction `normal` (≥ 0; 0 in
    /// contact): the distance to the obstacle or other body (`settings.gap`).
    pub gap: f64,
    /// Contact pressure, positive in compression (= −r_n) [force/length²].
    pub pressure: f64,
    /// Nodal contact force (per unit thickness) = pressure × tributary length.
    pub force: f64,
    /// Tributary length of the row: ∫ N_i ds of the node on the contact edges,
    /// or ∫ Φ_i ds of its multiplier (mortar rows: two bodies, T6 against rigid
    /// obstacles) over the part that sees the target.
    pub weight: f64,
    /// Node index in the body's mesh.
    pub node: usize,
    /// Unit direction of the row and of the contact force on the other side:
    /// the obstacle's (or other body's) inward normal at the point facing the
    /// node with `settings.gap = signed_distance`, the body's outward normal at
    /// the node with `body_normal` (mean over the support for mortar rows).
    pub normal: [f64; 2],
    /// Pairs with friction: tangential traction on the body [force/length²] along `tangent` or (−n_y, n_x).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_traction: Option<f64>,
    /// Against another body: t ⟂ the bisector of `normal` and the body's normal (the traction has p's share on t).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangent: Option<[f64; 2]>,
    /// Pairs with friction: slip in this load step [length] relative to the other surface, along the tangent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slip: Option<f64>,
    /// Pairs with friction: stick, slip, open or prescribed (the supports
    /// fix the slip; no friction force in the model there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state: Option<FrictionState>,
}

#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Resultant {
    pub fx: f64,
    pub fy: f64,
    /// Moment about the origin (counter-clockwise positive).
    pub m: f64,
}

/// Relative KKT residuals (dimensionless, each ≥ 0).
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Certificate {
    /// Largest penetration relative to the displacement scale.
    pub primal: f64,
    /// Largest tensile (negative) contact force relative to the largest force.
    pub dual: f64,
    /// Largest |force × gap| relative to (largest force × displacement scale).
    pub complementarity: f64,
    /// ‖K u − f + Bᵀλ‖∞ on the free DOFs relative to the largest nodal force.
    pub equilibrium: f64,
    /// With friction: its conditions' residuals.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionResiduals>,
}

/// Relative residuals of the Coulomb conditions (dimensionless, each ≥ 0).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionResiduals {
    /// Largest max(0, |t| − μ p) (as nodal forces) relative to the largest normal force.
    pub cone: f64,
    /// Largest max(0, t · slip) (the friction force doing positive work)
    /// relative to (largest normal force × displacement scale).
    pub dissipation: f64,
    /// Largest (μ p − |t|) · |slip| (slip inside the cone) relative to
    /// (largest of the normal forces and the cone bounds μ p × displacement scale).
    pub stick: f64,
}

#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProblemSize {
    /// Free degrees of freedom of all bodies.
    pub dofs: usize,
    /// Contact candidates after pruning.
    pub candidates: usize,
    /// Candidates in contact.
    pub active: usize,
}

#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Timings {
    pub mesh: f64,
    pub assembly: f64,
    pub factorization: f64,
    /// Condensation onto the contact candidates.
    pub condensation: f64,
    pub contact_solve: f64,
    pub post: f64,
    /// What the error estimate adds after the answer's solve: its energy
    /// bound and its coarser solve, or, when that solve ran beside the
    /// answer's on a second thread, the wait for its end (with
    /// `settings.accuracy`, also the refinement rounds before the last).
    #[serde(default)]
    pub estimate: f64,
    pub total: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyOutput {
    pub name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nodes: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<Vec<Vec<usize>>>,
    /// Nodal displacement [ux, uy].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub displacement: Option<Vec<[f64; 2]>>,
    /// Element-centroid stress [σxx, σyy, σxy] (in axisymmetry [σrr, σzz, σrz]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stress: Option<Vec<[f64; 3]>>,
    /// Axisymmetry: the element-centroid hoop stress σθθ, with `stress`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stress_hoop: Option<Vec<f64>>,
}

/// A foundation's surface deflection w(x) (downward positive) along its whole
/// length, also outside the contact zone where the model spreads it.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FoundationResult {
    pub name: String,
    /// "winkler", "pasternak" or "half_plane".
    pub model: String,
    pub x: Vec<f64>,
    pub w: Vec<f64>,
    /// Half-plane: the distance from a load at which its deflection is zero
    /// (the reference that fixes the 2D half-plane's rigid motion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_distance: Option<f64>,
    /// Total force the foundation carries (per unit thickness, downward).
    pub load: f64,
}

/// How well-posed the linear algebra was.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Diagnostics {
    /// (max / min pivot of the Cholesky factor of K)², a lower bound of its
    /// condition number (absent for the full formulation, which refactors).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub condition_estimate: Option<f64>,
    /// Iterative-refinement steps the solves with K needed to bring their
    /// residual below 1e-10 (relative); 0 on a well-conditioned K.
    pub refinements: usize,
    /// Seconds the numeric factorization was predicted to take from its
    /// symbolic analysis, before it ran (what a `time_limit` is judged against;
    /// a factor from the cache gives its own; absent for the full formulation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factorization_predicted: Option<f64>,
    /// How many contact rows the condensed operator W = B K⁻¹ Bᵀ was formed
    /// over, when the solve screened them (large scenes: only the rows the
    /// loads press, every other row checked open after the solve); absent
    /// when every candidate was condensed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub condensed_rows: Option<usize>,
}

/// Display as the wire's own name (`active_set`, `max_dofs`, ...): the text a
/// summary prints is the JSON value a client matches on.
macro_rules! display_as_wire {
    ($($name:ident),+) => {
        $(impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                match serde_json::to_value(self) {
                    Ok(serde_json::Value::String(s)) => f.write_str(&s),
                    _ => Err(std::fmt::Error),
                }
            }
        }

        impl PartialEq<&str> for $name {
            fn eq(&self, other: &&str) -> bool {
                matches!(serde_json::to_value(self), Ok(serde_json::Value::String(s)) if s == *other)
            }
        })+
    };
}
display_as_wire!(MethodRan, StopReason, EstimateBasis, WarningCode, NoteKind, SolveStatus);
