//! The estimator seam: how an answer's error bar is made. An estimator
//! names the companion solve it compares the answer against (or none), and
//! makes each pair's `accuracy` from the answer and that companion, and the
//! guaranteed energy bound of the answer returned (once per reply, from what
//! its solve kept: `solution::energy::Pending`); `adapt::estimate` and the
//! refinement rounds call it and nothing else of it. A second estimator is
//! one file in this folder plus one arm in `of` (the test
//! `a_trial_estimator_through_the_seam_needs_no_companion` defines one inside
//! the test alone).

mod two_level;

use crate::scene::Scene;
use crate::solution::energy::{EnergyBound, Pending};
use crate::solution::report::{PairAccuracy, PairReport, Report};

pub use two_level::TwoLevel;

/// The companion solve an estimator asks for.
pub struct Companion {
    pub scene: Scene,
    /// Its element size over the answer's (2: coarser, ½: finer).
    pub ratio: f64,
    /// What it is, for the notes when it cannot be solved.
    pub what: &'static str,
    /// Whether it is also the next refinement round (a given mesh's finer
    /// companion is that round exactly), so the rounds reuse its solve.
    pub next_round: bool,
}

/// An a posteriori estimator of a solved report's error.
pub trait Estimator {
    /// The companion the estimate needs (None: it needs none), or why it
    /// cannot be afforded within `max_dofs` and the time left (the reply then
    /// carries the zone ends alone, with that note).
    fn companion(&self, scene: &Scene, report: &Report, max_dofs: usize) -> Result<Option<Companion>, String>;
    /// The companion when it depends on the scene alone, so it can be solved
    /// beside the answer (`adapt::overlap`); None: only after the answer.
    fn ahead(&self, _scene: &Scene) -> Option<Companion> {
        None
    }
    /// One pair's accuracy, from the answer's pair and, when a companion
    /// solved, its pair and `ratio`.
    fn pair(&self, answer: &PairReport, companion: Option<(&PairReport, f64)>) -> PairAccuracy;
    /// The estimate's time over the solve's own, for the progress plan and
    /// the rounds' time prediction.
    fn share(&self, scene: &Scene) -> f64;
    /// The guaranteed energy bound (`solution::energy`) of the answer
    /// returned, from what its solve kept, or why there is none. Called once
    /// per reply, for that answer alone: never for a refinement round that
    /// is not returned, nor for a companion.
    fn energy(&self, scene: &Scene, answer: &Pending) -> Result<EnergyBound, &'static str> {
        answer.bound(scene)
    }
}

/// The estimator of a scene: the registration a second estimator adds its
/// arm to.
pub fn of(_scene: &Scene) -> &'static (dyn Estimator + Sync) {
    &TwoLevel
}
