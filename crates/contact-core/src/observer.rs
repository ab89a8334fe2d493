//! The one observer of a solve's stages: it announces each stage to the
//! progress sink, times it, and checks the deadline when it ends, so a stage
//! is named once (in [`Stage`]) rather than three times by string.

use crate::outcome::ProgressStage;
use std::time::Instant;

use crate::error::CoreError;

/// The stages of a solve, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    Mesh,
    Assembly,
    /// Factorization of K and condensation onto the contact rows.
    Factorization,
    ContactSolve,
    Post,
}

impl Stage {
    /// The stage progress reports name (`progress::STAGES`).
    pub fn name(self) -> ProgressStage {
        match self {
            Stage::Mesh => ProgressStage::Mesh,
            Stage::Assembly => ProgressStage::Assembly,
            Stage::Factorization => ProgressStage::Factorization,
            Stage::ContactSolve => ProgressStage::ContactSolve,
            Stage::Post => ProgressStage::Post,
        }
    }

    /// The stage a timeout says it stopped after: the factorization stage ends
    /// with the condensation (its own progress report, `methods::condensed`).
    fn done(self) -> ProgressStage {
        match self {
            Stage::Factorization => ProgressStage::Condensation,
            s => s.name(),
        }
    }
}

/// Wall-clock seconds per stage.
#[derive(Debug, Clone, Copy, Default)]
pub struct Timings {
    pub mesh: f64,
    pub assembly: f64,
    pub factorization: f64,
    pub condensation: f64,
    pub contact_solve: f64,
    pub post: f64,
    /// The error estimate's coarser solve and earlier refinement rounds.
    pub estimate: f64,
    pub total: f64,
}

impl Timings {
    /// Stage by stage sum (load steps).
    pub fn add(&mut self, s: &Timings) {
        self.mesh += s.mesh;
        self.assembly += s.assembly;
        self.factorization += s.factorization;
        self.condensation += s.condensation;
        self.contact_solve += s.contact_solve;
        self.post += s.post;
        self.estimate += s.estimate;
        self.total += s.total;
    }
}

/// Predicted seconds of each stage (`progress::STAGES` order) for a mesh of
/// `nodes` nodes, T6 or not, before the factorization's symbolic analysis
/// tells its cost (`revise_factorization`). Fitted on this machine (release,
/// 2 cores) to the Hertz block, T3 73k to 2.1M DOF and T6 1.6M DOF: meshing
/// 5.7e-7 to 8.2e-7 s per node, assembly 7e-7 (T6 1.05e-6),
/// post-processing 1.0e-7 to 1.3e-7 per node; and on T3 66k to 1.2M DOF
/// (`contact-bench --floor`): the factorization 4.0e-9 to 6.4e-9 n^1.5 for n
/// DOFs, the condensation 14 % to 16 % of it and the contact solve 9 % (one
/// forward and one backward sweep and the LCP).
pub fn predicted(nodes: f64, t6: bool) -> [f64; 6] {
    let n = 2.0 * nodes;
    let factorization = 4.5e-9 * n.powf(1.5);
    [
        7e-7 * nodes,
        if t6 { 1.05e-6 } else { 7e-7 } * nodes,
        factorization,
        0.15 * factorization,
        0.09 * factorization,
        1.2e-7 * nodes,
    ]
}

/// Seconds per multiply–add of the condensation (`linalg::schur`), measured
/// on the Hertz block (release, one thread): 2.2e-11 at 1.2M DOF, 2.3e-11 at
/// 615k.
const SECS_PER_CONDENSATION_FLOP: f64 = 2.3e-11;

/// The factorization's cost once its symbolic analysis (which took
/// `symbolic_secs`, done) is known, and what follows from it (condensation of
/// `condensation_flops` multiply–adds, the contact solve).
pub fn revise_factorization(symbolic_secs: f64, predicted_secs: f64, condensation_flops: f64) {
    crate::progress::revise(ProgressStage::Factorization, symbolic_secs + predicted_secs);
    crate::progress::credit(symbolic_secs);
    crate::progress::revise(
        ProgressStage::Condensation,
        SECS_PER_CONDENSATION_FLOP * condensation_flops,
    );
    crate::progress::revise(ProgressStage::ContactSolve, 0.09 * predicted_secs);
    // Told at once: the factorization is most of a large solve, and the
    // estimate of what is left should not wait for its end.
    crate::progress::report();
}

/// Progress, timing and deadline of one solve.
pub struct Observer {
    start: Instant,
    entered: Instant,
    pub timings: Timings,
}

impl Default for Observer {
    fn default() -> Self {
        Self::new()
    }
}

impl Observer {
    pub fn new() -> Self {
        let now = Instant::now();
        Self {
            start: now,
            entered: now,
            timings: Timings::default(),
        }
    }

    /// The solve enters `stage`.
    pub fn enter(&mut self, stage: Stage) {
        crate::progress::stage(stage.name());
        self.entered = Instant::now();
    }

    /// `stage` ended: its time is added to the timings, and the deadline is checked.
    pub fn leave(&mut self, stage: Stage) -> Result<(), CoreError> {
        let dt = self.entered.elapsed().as_secs_f64();
        let t = &mut self.timings;
        *match stage {
            Stage::Mesh => &mut t.mesh,
            Stage::Assembly => &mut t.assembly,
            Stage::Factorization => &mut t.factorization,
            Stage::ContactSolve => &mut t.contact_solve,
            Stage::Post => &mut t.post,
        } += dt;
        self.check(stage)
    }

    /// The deadline, as after `stage` (a stage skipped by the cache still counts).
    pub fn check(&self, stage: Stage) -> Result<(), CoreError> {
        Ok(crate::cancel::check(stage.done())?)
    }

    /// The timings with the total since the observer was made.
    pub fn finish(mut self) -> Timings {
        self.timings.total = self.start.elapsed().as_secs_f64();
        self.timings
    }
}
