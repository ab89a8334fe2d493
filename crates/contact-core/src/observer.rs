//! The one observer of a solve's stages: it announces each stage to the
//! progress sink, times it, and checks the deadline when it ends, so a stage
//! is named once (in [`Stage`]) rather than three times by string.

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
    /// The name progress reports carry (`progress::STAGES`).
    pub fn name(self) -> &'static str {
        match self {
            Stage::Mesh => "mesh",
            Stage::Assembly => "assembly",
            Stage::Factorization => "factorization",
            Stage::ContactSolve => "contact_solve",
            Stage::Post => "post",
        }
    }

    /// The stage a timeout says it stopped after: the factorization stage ends
    /// with the condensation (its own progress report, `methods::condensed`).
    fn done(self) -> &'static str {
        match self {
            Stage::Factorization => "condensation",
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
        self.total += s.total;
    }
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
