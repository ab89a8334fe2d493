//! The scene's choices of model and method, as the numerics read them (the
//! request's names for them stay at the scene boundary, `validate`).

/// 2D kinematics of the bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Analysis {
    PlaneStrain,
    PlaneStress,
    /// r–z half-section of a body of revolution (x = r ≥ 0, y = z).
    Axisymmetric,
}

impl Analysis {
    /// The measure of a point of the section: 2πr in axisymmetry (forces
    /// and areas are totals over the circumference), 1 (unit thickness)
    /// otherwise.
    pub fn measure(self, x: [f64; 2]) -> f64 {
        match self {
            Analysis::Axisymmetric => std::f64::consts::TAU * x[0],
            _ => 1.0,
        }
    }
}

/// The contact method asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Fastest exact method for the scene.
    Auto,
    ActiveSet,
    InteriorPoint,
    Penalty,
    AugmentedLagrangian,
    Barrier,
}

/// Where the contact problem is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Formulation {
    /// One factorization, the LCP on the contact rows.
    Condensed,
    /// The whole system, refactored per iteration (exact methods, for comparison).
    Full,
}

/// Discretization of a two-body pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Discretization {
    /// Segment-to-segment, passes the contact patch test.
    Mortar,
    NodeToSegment,
}

/// How the gap of a contact row is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GapMeasure {
    /// Linearized signed distance to the target, the row along its normal.
    SignedDistance,
    /// Along the body's own outward normal (the classical u·n ≤ s).
    BodyNormal,
}

/// Where the mortar rows of a T6 surface carry their multipliers
/// (`contact::rows::T6Multiplier`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum T6Multipliers {
    EveryNode,
    Corners,
}

/// One component of a punch's rigid motion: prescribed, or free with its
/// load prescribed (nondimensional).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    Displacement(f64),
    Load(f64),
}

impl Control {
    /// Multiplies the value, load or displacement, by `k` (a load step).
    pub fn scale(&mut self, k: f64) {
        match self {
            Control::Displacement(v) | Control::Load(v) => *v *= k,
        }
    }
}

/// Tolerances and parameters of the contact solve (nondimensional).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Convergence tolerance on the relative KKT residuals.
    pub tolerance: f64,
    /// Iteration cap of the contact iteration.
    pub max_iterations: usize,
    /// Rows whose initial gap exceeds this multiple of the body size are dropped.
    pub prune_gap_ratio: f64,
    pub formulation: Formulation,
    pub gap: GapMeasure,
    pub t6_multipliers: T6Multipliers,
    /// Penalty compliance ζ of `penalty` and `augmented_lagrangian`.
    pub penalty: f64,
    /// Barrier parameter ζ of `barrier`.
    pub barrier: f64,
    /// Estimate the pressure's error by a coarser second solve (`crate::adapt`).
    pub estimate: bool,
    /// Tolerance-driven refinement, when asked for.
    pub accuracy: Option<AccuracyTarget>,
}

/// What tolerance-driven refinement must reach (`crate::adapt`): a relative
/// L2 error of the pressure, a zone-end error in the request's length unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccuracyTarget {
    pub pressure_l2: Option<f64>,
    pub zone_edge: Option<f64>,
    pub max_rounds: usize,
    pub max_dofs: usize,
}

impl Default for Settings {
    /// The request's defaults: ζ 1e-6 of the natural compliance L/E, barrier
    /// 1e-8 of E·L (1 in the scaled units).
    fn default() -> Self {
        Self {
            tolerance: 1e-8,
            max_iterations: 200,
            prune_gap_ratio: 0.5,
            formulation: Formulation::Condensed,
            gap: GapMeasure::SignedDistance,
            t6_multipliers: T6Multipliers::EveryNode,
            penalty: 1e-6,
            barrier: 1e-8,
            estimate: true,
            accuracy: None,
        }
    }
}
