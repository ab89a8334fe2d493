//! The two-level estimator (`solution::two_level`): the answer against the
//! same scene with every element twice as large (generated meshes), or with
//! every triangle split in four (given meshes, which cannot be coarsened).
//! The method and its measured effectivities are `adapt`'s module doc.

use super::{Companion, Estimator};
use crate::adapt::cost::{solve_seconds, TIME_GROWTH};
use crate::adapt::sizing::{given, resized, RATIO};
use crate::scene::Scene;
use crate::solution::report::{PairAccuracy, PairReport, Report};
use crate::solution::{accuracy, two_level};

/// The coarser companion's time over its solve's, at most (14–50 %
/// measured, the larger on small scenes).
const COARSER_SHARE: f64 = 0.5;
/// Largest finer companion of a given mesh: about 1 kB of factor per unknown
/// at this size (81 M entries of L at 612k DOF), so 1.3 GB of factor besides
/// the mesh and the workspace; a larger mesh's reply carries the zone ends
/// alone.
const FINER_MAX_DOFS: f64 = 1.2e6;

pub struct TwoLevel;

impl Estimator for TwoLevel {
    fn companion(&self, scene: &Scene, report: &Report, max_dofs: usize) -> Result<Option<Companion>, String> {
        // A given mesh's region meshed again with elements twice as large
        // (`mesh::coarsen`) costs a fraction of the finer companion's four
        // times the unknowns; the finer one stays where the region cannot be
        // (a hole, a boundary that is not one loop).
        if let Some(coarser) = self.ahead(scene) {
            return Ok(Some(coarser));
        }
        // A coarsening stopped by the clock (`mesh::coarsen` looks at it) is
        // not a region that cannot be meshed again: say so, not that a finer
        // solve does not fit (review).
        if crate::cancel::expired() {
            return Err(
                "the time limit passed before the error estimate's coarser companion was made; only the zone \
                        ends' uncertainty is estimated"
                    .into(),
            );
        }
        // Only a given mesh whose region cannot be meshed again is left.
        let predicted = report.size.dofs as f64 * (RATIO * RATIO);
        let most = FINER_MAX_DOFS.min(max_dofs as f64);
        if predicted > most {
            return Err(format!(
                "the error estimate needs a finer solve of about {predicted:.0} DOFs (every triangle split in four), \
                 more than the {most:.0} it may take (its own bound, or the service's size or memory limit); only \
                 the zone ends' uncertainty is estimated"
            ));
        }
        let seconds = solve_seconds(report) * (RATIO * RATIO).powf(TIME_GROWTH);
        if seconds > crate::cancel::remaining_secs() {
            return Err(format!(
                "the error estimate needs a finer solve (every triangle split in four) of about {seconds:.2} s, \
                 more than the {:.2} s left of the time limit; only the zone ends' uncertainty is estimated",
                crate::cancel::remaining_secs()
            ));
        }
        Ok(Some(Companion {
            scene: resized(scene, [1.0 / RATIO; 3], None).expect("a given mesh is split in four"),
            ratio: 1.0 / RATIO,
            what: "finer solve (every triangle split in four)",
            next_round: true,
        }))
    }

    /// The coarser companion reads the scene alone (its sizing, or its given
    /// mesh's region); the finer fallback needs the answer's size and time.
    fn ahead(&self, scene: &Scene) -> Option<Companion> {
        resized(scene, [RATIO; 3], None).map(|coarser| Companion {
            scene: coarser,
            ratio: RATIO,
            what: if given(scene) {
                "coarser solve (the given mesh's region meshed again, elements twice as large)"
            } else {
                "coarser solve (elements twice as large)"
            },
            next_round: false,
        })
    }

    fn pair(&self, answer: &PairReport, companion: Option<(&PairReport, f64)>) -> PairAccuracy {
        match companion {
            Some((other, ratio)) => two_level::two_level(answer, other, ratio),
            None => accuracy::zone_edges_only(answer),
        }
    }

    /// The coarser companion's, a given mesh's too: the finer one is the
    /// fallback of the rare region that cannot be meshed again.
    fn share(&self, _: &Scene) -> f64 {
        COARSER_SHARE
    }
}
