//! The estimate's coarser companion solved on a second thread beside the
//! answer's solve. It reads the scene alone (`Estimator::ahead`: the sizing
//! ×2, or the given mesh's region meshed again), so it need not wait for the
//! answer; the arithmetic of both solves is unchanged, only their schedule,
//! and the reply is the same (the recorded replies, and a test comparing both
//! schedules).
//!
//! What the helper thread keeps: the request's clock (`cancel::handoff`), and
//! a stop flag raised when the answer's solve fails or does not solve (the
//! companion's result is then dropped and the answer's error stands). It has
//! no progress sink: the client's bar is the answer's stages, then the
//! `estimate` stage while the companion is awaited, never the companion's
//! own stages as if they were the answer's. A companion that fails gives the
//! same note as after the answer. The answer's energy bound is made while the
//! companion ends. A given (inline or Gmsh) mesh's companion, its region
//! meshed again, looks at the clock between its phases but not inside its
//! triangulation, which a failing or timed-out answer waits for: `Auto` runs
//! it beside the answer only where that triangulation is predicted to fit
//! the lateness a limit tolerates (max(10 %, 0.2 s)), and after it otherwise.
//! The finer fallback of a region that cannot be meshed again needs the
//! answer's size and stays after it.
//!
//! **Memory.** The two solves are now simultaneous: the companion (a quarter
//! of the unknowns, so about a quarter of the answer's 1.34–1.46 kB per DOF,
//! `BYTES_PER_DOF`) adds about 0.35 kB per DOF of the request to its peak. In
//! `Overlap::Auto` a request overlaps only when its predicted DOFs are at
//! most half of `max_dofs`, so the two together stay within about 0.63 of the
//! memory a request at the limit is admitted for (`Limits::memory_bytes`),
//! with room for a prediction off by half; a larger request runs them one
//! after the other as before.
//!
//! **Cores.** The factorization is sequential by default (`linalg::threads`,
//! 1: the service runs its workers side by side), so on this 2-core machine
//! one core is idle during a CLI solve. `Auto` overlaps only while the
//! solving threads of this process (answers and companions) are fewer than
//! its cores and the factorization is single-threaded: a service whose
//! workers already keep every core busy gains nothing from a third thread.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::estimator::{self, Companion, Estimator};
use crate::error::CoreError;
use crate::scene::{Limits, Overlap, Scene};
use crate::solution::report::{Report, Status};

/// Stops the helper when dropped: after the estimate has joined it, a no-op.
struct StopOnDrop<'a>(&'a crate::cancel::Stopper);

impl Drop for StopOnDrop<'_> {
    fn drop(&mut self) {
        self.0.stop();
    }
}

/// A companion solved beside the answer, for `adapt::estimate`.
pub struct Ahead {
    pub companion: Companion,
    pub solved: Result<Report, CoreError>,
}

/// A solve of a companion scene, callable from the helper thread.
pub type Companions<'a> = dyn Fn(&Scene) -> Result<Report, CoreError> + Sync + 'a;

/// Threads of this process solving now: answers (`busy`) and companions.
static SOLVING: AtomicUsize = AtomicUsize::new(0);

/// Counts a solving thread while alive.
pub struct Busy(());

impl Drop for Busy {
    fn drop(&mut self) {
        SOLVING.fetch_sub(1, Ordering::Relaxed);
    }
}

/// The calling thread solves (a request) until the guard drops.
pub fn busy() -> Busy {
    SOLVING.fetch_add(1, Ordering::Relaxed);
    Busy(())
}

/// A core for the companion, if one is free (counted as solving).
fn free_core() -> Option<Busy> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    SOLVING
        .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |n| (n < cores).then_some(n + 1))
        .ok()
        .map(|_| Busy(()))
}

/// The companion as the estimate solves it: one that is not the next
/// refinement round is never returned, so it keeps nothing for an energy
/// bound (`compose` keeps it only for an estimated answer).
pub fn bare(mut companion: Companion) -> Companion {
    if !companion.next_round {
        companion.scene.settings.estimate = false;
        companion.scene.settings.accuracy = None;
    }
    companion
}

/// The estimate of an answer, given how to get the companion solved ahead
/// (None: solve it after the answer).
type Estimate<'e> = dyn FnOnce(&mut Report, Box<dyn FnOnce() -> Option<Ahead> + '_>) + 'e;

/// `answer()` (the scene's solve) and its estimate (`adapt::estimate`), the
/// coarser companion solved by `companion` on a second thread beside the
/// answer when `limits.overlap` allows it (module doc): the answer's energy
/// bound is made while the companion ends, and the estimate waits for it.
pub fn solve_estimated(
    scene: &Scene,
    limits: &Limits,
    answer: impl FnOnce() -> Result<Report, CoreError>,
    companion: &Companions,
) -> Result<Report, CoreError> {
    let est = estimator::of(scene);
    let estimate = |report: &mut Report, ahead: Box<dyn FnOnce() -> Option<Ahead> + '_>| {
        super::estimate(scene, report, companion, limits.max_dofs, ahead)
    };
    match core(scene, limits) {
        Some(_core) => beside(move || est.ahead(scene), answer, companion, Box::new(estimate)),
        None => {
            let mut report = answer()?;
            estimate(&mut report, Box::new(|| None));
            Ok(report)
        }
    }
}

/// A refinement round of a generated mesh: its solve and its estimate by
/// `est` (`adapt::estimate_by`, no energy bound: the rounds make one, for
/// the round returned), its coarser companion beside it as in
/// `solve_estimated`. The companion is made here, before the helper starts:
/// `est` need not be shared with it. Of the rounds to 0.5 % on the T3 disk
/// from a coarse start, the companions took 17 % of the solves' time
/// (docs/verification/accuracy.md, time to a tolerance).
pub(super) fn round_estimated(
    est: &dyn Estimator,
    scene: &Scene,
    limits: &Limits,
    solve: &Companions,
) -> Result<Report, CoreError> {
    let estimate = |report: &mut Report, ahead: Box<dyn FnOnce() -> Option<Ahead> + '_>| {
        // A coarser companion is never the next round: nothing to keep.
        let _ = super::estimate_from(est, scene, report, solve, limits.max_dofs, ahead);
    };
    match core(scene, limits) {
        Some(_core) => {
            let made = est.ahead(scene);
            beside(move || made, || solve(scene), solve, Box::new(estimate))
        }
        None => {
            let mut report = solve(scene)?;
            estimate(&mut report, Box::new(|| None));
            Ok(report)
        }
    }
}

/// The core a companion beside the answer takes, when `limits.overlap`
/// allows one (module doc).
fn core(scene: &Scene, limits: &Limits) -> Option<Busy> {
    match limits.overlap {
        Overlap::Off => None,
        Overlap::Always => Some(busy()),
        // A given mesh's companion is its region meshed again, whose
        // triangulation does not look at the clock: an answer that fails or
        // times out waits for it, so it runs beside only when it fits in the
        // lateness a limit tolerates.
        Overlap::Auto if super::sizing::given(scene) && coarsening_secs(scene) > tolerated_lateness() => None,
        Overlap::Auto if 2.0 * (2.0 * scene.estimated_nodes) <= limits.max_dofs as f64 => {
            (crate::linalg::threads() == 1).then(free_core).flatten()
        }
        Overlap::Auto => None,
    }
}

/// Seconds per given node of `mesh::coarsen`: measured on T3 disks from 1k
/// to 274k nodes (1.3–3.7 µs, growing with the size), so above that size
/// and for T6 (not measured) an extrapolation; times the machine's
/// factorization rate (`rate::scale`).
const COARSEN_PER_NODE: f64 = 4e-6;

/// The coarsening of a given mesh, predicted.
fn coarsening_secs(scene: &Scene) -> f64 {
    COARSEN_PER_NODE * scene.estimated_nodes * crate::linalg::rate::scale()
}

/// How late an answer may come for its limit: max(10 %, 0.2 s) of the time
/// left, the bound the service's load test holds every reply to; without a
/// limit, any.
fn tolerated_lateness() -> f64 {
    (0.1 * crate::cancel::remaining_secs()).max(0.2)
}

/// `answer()` with the companion `make` gives solved on a second thread
/// beside it, then `estimate`, which waits for that companion.
fn beside(
    make: impl FnOnce() -> Option<Companion> + Send,
    answer: impl FnOnce() -> Result<Report, CoreError>,
    companion: &Companions,
    estimate: Box<Estimate<'_>>,
) -> Result<Report, CoreError> {
    let handoff = crate::cancel::handoff();
    let stopper = handoff.stopper();
    std::thread::scope(|s| {
        // A helper that panics gives no companion (the estimate then solves
        // it after the answer, as without the overlap), never a panic of the
        // scope that would replace the answer's own error; a thread the
        // system refuses is the same.
        let helper = std::thread::Builder::new()
            .spawn_scoped(s, move || {
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    let _clock = handoff.install();
                    let c = bare(make()?);
                    let solved = companion(&c.scene);
                    Some(Ahead { companion: c, solved })
                }))
                .ok()
                .flatten()
            })
            .ok();
        // The scope waits for the helper on every way out: the guard stops
        // it on each (an error, a panic of the answer or of its bound), and
        // a stopped one ends at its next check.
        let _stop = StopOnDrop(&stopper);
        let mut report = answer()?;
        if report.status != Status::Solved {
            stopper.stop();
        }
        // The bar reads `estimate` while the companion is awaited.
        let ahead = || {
            crate::progress::stage(crate::progress::ESTIMATE);
            helper.and_then(|h| h.join().ok().flatten())
        };
        estimate(&mut report, Box::new(ahead));
        Ok(report)
    })
}
