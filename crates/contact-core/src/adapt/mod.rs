//! The error bar of an answer, and refinement until it meets a requested
//! accuracy.
//!
//! **Estimate** (`estimator`: the seam; `estimator::TwoLevel`, the one
//! registered). After the solve, the same scene is solved again on a
//! companion whose every element differs by a factor 2 in size, far field
//! included, and each pair's nodal pressure, peak and resultant are compared
//! (`solution::two_level`, Richardson-scaled). On generated meshes
//! the companion is coarser (`h_min`, the grading's `ratio − 1` and `size`
//! × 2, the graded window unchanged): about a quarter of the unknowns, its
//! cost measured in `timings.estimate` (14–16 % of the solve on the Hertz
//! example at 30k–391k DOF). A given (inline or Gmsh) mesh cannot be
//! coarsened, so its region is meshed again with elements twice as large
//! (`mesh::coarsen`: every other boundary node, a maximal independent set of
//! the interior nodes, edge sets and curved T6 sides kept), its far field
//! included: the estimate cost 0.34–0.46 of the solve on the inline T3 disk
//! at 10.7k–286k DOF and 0.23–0.28 with T6 at 14.6k–85k (median of five, at
//! load 7), where the finer companion (every triangle split in four) cost
//! 2.5–7.5 solves. The finer one remains for a region that cannot be meshed
//! again (a hole, several boundary loops; basis `two_level_finer`), and
//! beyond `FINER_MAX_DOFS` it is left out with a note (the zone ends alone,
//! basis `zone_edges`). A companion that only refined around the zones would not
//! see the far field's error: on a user's disk mesh with far field R/8 it
//! said 0.30 % where the true error was 0.73 %, and 0.0003 % for a
//! resultant 0.59 % off. The coarser companion depends on the scene alone, so
//! on the default path it is solved on a second thread beside the answer
//! when a core is free (`overlap`).
//!
//! A 3D solid's estimate and rounds are `solid`'s, on the same design and
//! constants.
//!
//! **Energy bound** (`solution::energy`): made by the estimator
//! (`Estimator::energy`) once per reply, for the answer returned, from what
//! its solve kept (`energy::Pending`); a refinement round keeps it through
//! its own estimate and releases it before the next round solves.
//!
//! **Refinement** (`settings.accuracy`). Generated meshes: round after round
//! the smallest element `h_min` shrinks by a factor f sized from the last
//! estimate to land just under the target (`AIM`; ¼ to ¾), the grading's
//! growth `ratio − 1` and the far-field `size` by √f (`field_step`), and the
//! graded window is widened to cover every zone the last round found (with a
//! quarter of margin); since the far field then shrinks less than the zones,
//! two rounds are not in Richardson's ratio, and each round is estimated
//! against its own coarser companion as above (solved beside the round when
//! a core is free: `overlap::round_estimated`). Given meshes: each round
//! splits every triangle in four (its far field too), and is estimated against
//! the round before, which is its coarser companion exactly (the first round
//! against its region meshed again; where that companion is the finer one, it
//! is the second round, solved once). The rounds stop
//! when every estimate meets its target, when nothing is in contact (no
//! contact error to reduce), or at `max_rounds`, at `max_dofs` (predicted
//! from the step and the growth of the last round; a step past it becomes
//! the largest round it holds, where that is still a step), at the
//! service's size or time limit,
//! when two rounds in a row do not improve the estimate, or when a round
//! fails (its mesh, its numerics): the answer is then the last round that
//! solved, `solved` with a `tolerance_not_reached` warning. A target is
//! only reached by a two-level estimate, never by the zone ends alone.
//!
//! Length: about 580 lines: the estimate, where the energy bound and a
//! companion solved ahead enter it, and the rounds that reuse it, sharing
//! their limits (size, time, the budget a last round may fill) and their
//! stop reasons (with a 3D solid's rounds, `solid`), read as one schedule.

mod cost;
pub mod estimator;
pub mod overlap;
mod sizing;
pub mod solid;

use crate::outcome::{EstimateBasis, Note, NoteKind, StopReason, WarningCode};
use std::time::Instant;

use crate::error::CoreError;
use crate::scene::{AccuracyTarget, Limits, Scene};
use crate::solution::accuracy;
use crate::solution::report::{PairAccuracy, Refinement, Report, Round, Status, Warning};
use cost::{solve_seconds, TIME_GROWTH};
use estimator::Estimator;
use sizing::{given, resized, smallest_size, RATIO};
/// A generated round's factor f on `h_min` is sized to land its estimate at
/// `AIM` of the target's met value, from the last estimate e and the order
/// the estimate assumes (h² for the pressure, h for a zone end):
/// f = (AIM · SAFETY · t / e)^(1/q), within [`STEP_MIN`, `STEP_MAX`]. Halving
/// `h_min` every round overshot: the T3 disk at target 0.005 met it at
/// 92k DOF (true error 0.037 %), the round before having read 0.33 % where
/// 0.30 % was needed.
const AIM: f64 = 0.8;
/// The largest step of `h_min` in one round: ¼ (about 10× the unknowns).
/// The estimates of the first, coarse rounds do not fall like h² (the disk's
/// 1.6 %, 1.2 %, 0.57 % over three T6 rounds halving h), so a longer jump
/// would rest on an order not seen yet.
const STEP_MIN: f64 = 0.25;
/// The smallest step: a round that would refine less is not worth its solve.
const STEP_MAX: f64 = 0.75;
/// The share of `max_dofs` a round cut to fit the budget aims at: its size
/// is predicted from the last rounds' growth, which the next mesh can pass.
const BUDGET_FILL: f64 = 0.8;
/// A round's factor on the grading's growth (ratio − 1) and the far-field
/// size of a generated mesh is √f for f on `h_min`: the error sits at the
/// zones, and halving these too made each round 4× larger (the T3 disk from
/// h_min = 0.02 R met 0.5 % at 27.6k DOF in 0.11 s; by 1/√2, at 9.9k DOF in
/// 0.04 s).
fn field_step(f: f64) -> f64 {
    f.sqrt()
}
/// A round that does not bring the estimate below this fraction of the
/// previous one is not converging (the answer sits at a floor the sizing
/// does not move).
const PROGRESS: f64 = 0.9;
/// A target counts as met when the estimate is within this fraction of it:
/// the estimate is a best guess of the error, not a bound, and on the rounds
/// that met their targets it read 0.67–0.91 of the true error at worst (the
/// Gmsh block at 0.003, the inline T6 disk at 0.002, the T3 ball, against
/// their overkill tables): at the target itself the true error came out up to
/// 1.5× above it.
const SAFETY: f64 = 0.6;

/// A solve of a whole scene (its load factors included).
pub type Solver<'a> = dyn Fn(&Scene) -> Result<Report, CoreError> + 'a;

/// Fills every pair's `accuracy` of a solved report: the two-level estimate
/// when the companion solves, else the zone ends alone (with a note saying
/// why).
/// `max_dofs`: the deployment's size limit (`Limits::max_dofs`, which the
/// service also bounds by its memory per request), which a finer companion
/// may not pass.
/// `ahead`: the companion solved beside the answer (`overlap`), asked for
/// after the energy bound, which is made meanwhile.
pub fn estimate(
    scene: &Scene,
    report: &mut Report,
    solve: &Solver,
    max_dofs: usize,
    ahead: impl FnOnce() -> Option<overlap::Ahead>,
) {
    let est = estimator::of(scene);
    // The bound first: the answer's factor it solves with is then released
    // before the companion's is made (when it is not made already).
    bound_energy(est, scene, report);
    estimate_from(est, scene, report, solve, max_dofs, ahead);
}

/// The estimate's time over the solve's own, for the progress plan (the
/// scene's estimator's `share`).
pub fn estimate_share(scene: &Scene) -> f64 {
    estimator::of(scene).share(scene)
}

/// `estimate` by `est`, returning the companion with its solved report when
/// it is also the next refinement round (`Companion::next_round`).
pub fn estimate_by(
    est: &dyn Estimator,
    scene: &Scene,
    report: &mut Report,
    solve: &Solver,
    max_dofs: usize,
) -> Option<(Scene, Report)> {
    estimate_from(est, scene, report, solve, max_dofs, || None)
}

/// `estimate_by`, with the companion solved `ahead` or solved here.
fn estimate_from(
    est: &dyn Estimator,
    scene: &Scene,
    report: &mut Report,
    solve: &Solver,
    max_dofs: usize,
    ahead: impl FnOnce() -> Option<overlap::Ahead>,
) -> Option<(Scene, Report)> {
    let t = Instant::now();
    let mut finer = None;
    let outcome: Result<(), Option<String>> = (|| {
        if report.status != Status::Solved {
            return Err(None);
        }
        let (companion, solved) = match ahead() {
            // The bar entered `estimate` before the wait (`overlap`).
            Some(a) => (a.companion, a.solved),
            None => {
                let Some(companion) = est.companion(scene, report, max_dofs).map_err(Some)? else {
                    for p in report.pairs.iter_mut() {
                        p.accuracy = Some(est.pair(p, None));
                    }
                    return Ok(());
                };
                let companion = overlap::bare(companion);
                // The companion's own stages would restart the caller's bar:
                // they move it across the estimate's share instead.
                crate::progress::stage(crate::progress::ESTIMATE);
                let _nested = crate::progress::Sink::nested();
                let solved = solve(&companion.scene);
                (companion, solved)
            }
        };
        let what = companion.what;
        match solved {
            Ok(c) if c.status == Status::Solved && c.pairs.len() == report.pairs.len() => {
                for (f, cp) in report.pairs.iter_mut().zip(&c.pairs) {
                    f.accuracy = Some(est.pair(f, Some((cp, companion.ratio))));
                }
                if companion.next_round {
                    finer = Some((companion.scene, c));
                }
                Ok(())
            }
            Ok(c) => Err(Some(format!(
                "the error estimate's {what} ended {:?}; only the zone ends' uncertainty is estimated",
                c.status
            ))),
            Err(e) => Err(Some(format!(
                "the error estimate's {what} failed: {e}; only the zone ends' uncertainty is estimated"
            ))),
        }
    })();
    if let Err(why) = outcome {
        report
            .notes
            .extend(why.map(|t| Note::new(NoteKind::EstimateLimited, t)));
        for p in report.pairs.iter_mut() {
            p.accuracy = Some(accuracy::zone_edges_only(p));
        }
    }
    with_energy(report);
    let dt = t.elapsed().as_secs_f64();
    report.timings.estimate += dt;
    report.timings.total += dt;
    finer
}

/// The energy bound of the answer returned (`Estimator::energy`), from what
/// its solve kept (which is then released): into the report, or a note
/// saying why there is none. Timed as the estimate's.
fn bound_energy(est: &dyn Estimator, scene: &Scene, report: &mut Report) {
    let Some(answer) = report.pending_energy.take() else {
        return;
    };
    let t = Instant::now();
    // A stepped solve's answer is its last step's (with the request's own
    // loads, a block at load factor 0.5 was bounded for twice its load).
    let step = scene.last_step();
    let scene = step.as_ref().unwrap_or(scene);
    match est.energy(scene, &answer) {
        Ok(b) => report.energy = Some(b),
        Err(why) => report.notes.push(Note::new(
            NoteKind::EstimateLimited,
            format!("no guaranteed energy bound: {why}"),
        )),
    }
    // Timed before the answer's factor is released, as it was when the
    // bound was made in the post stage (the release is the solve's, and
    // happens with or without a bound).
    let dt = t.elapsed().as_secs_f64();
    drop(answer);
    report.timings.estimate += dt;
    report.timings.total += dt;
    with_energy(report);
}

/// Every pair's accuracy carries the answer's energy bound (`solution::energy`).
fn with_energy(report: &mut Report) {
    let bound = report.energy.map(|e| e.relative());
    for a in report.pairs.iter_mut().filter_map(|p| p.accuracy.as_mut()) {
        a.energy = bound;
    }
}

/// Solves, estimates and refines until `target` is met or a limit stops the
/// rounds (module doc).
/// `limits`: the deployment's, whose `max_dofs` no round may pass (its
/// prediction stops the rounds before the mesh is built) and whose `overlap`
/// lets a generated round's companion be solved beside it
/// (`overlap::round_estimated`).
pub fn refine(
    scene: &Scene,
    target: AccuracyTarget,
    solve: &overlap::Companions,
    limits: &Limits,
) -> Result<Report, CoreError> {
    refine_by(estimator::of(scene), scene, target, solve, limits)
}

/// `refine` by `est`. The energy bound is made once, for the round returned
/// (`Estimator::energy`): a round is known to be the last only after its own
/// estimate, so each round keeps what the bound needs through that
/// estimate, and releases it before the next round solves (should that round
/// fail, the last one stands without a bound, and a note says why).
pub fn refine_by(
    est: &dyn Estimator,
    scene: &Scene,
    target: AccuracyTarget,
    solve: &overlap::Companions,
    limits: &Limits,
) -> Result<Report, CoreError> {
    let max_dofs = limits.max_dofs;
    let target = AccuracyTarget {
        max_dofs: target.max_dofs.min(max_dofs),
        ..target
    };
    let started = Instant::now();
    crate::progress::round(1);
    // Given meshes refine uniformly: each round is the previous one's finer
    // companion (module doc).
    let uniform = given(scene);
    let (mut report, mut finer) = if uniform {
        let mut report = solve(scene)?;
        let finer = estimate_by(est, scene, &mut report, solve, max_dofs);
        (report, finer)
    } else {
        (overlap::round_estimated(est, scene, limits, solve)?, None)
    };
    let mut current = scene.clone();
    let mut rounds = vec![round(&current, &report, started.elapsed().as_secs_f64())];
    let mut growth = None::<f64>;
    let mut stalled = 0;
    let mut failure = None::<String>;
    let stopped = loop {
        if report.status == Status::Solved && report.pairs.iter().all(|p| p.zones_along.is_empty()) {
            break StopReason::NoContact;
        }
        if met(&report, &target) {
            break StopReason::Reached;
        }
        if report.status != Status::Solved {
            break StopReason::NotSolved;
        }
        if rounds.len() >= target.max_rounds {
            break StopReason::MaxRounds;
        }
        let t = Instant::now();
        let (next, mut fine) = match finer.take() {
            Some(solved) => solved,
            None => {
                // Unknowns grow by about the last round's factor (4 before
                // the first); both limits are judged before the round's mesh
                // is built (a given mesh's took 34 s, at 3.3 GB, to be thrown
                // away past its time limit).
                let mut f = if uniform { 1.0 / RATIO } else { step(&report, &target) };
                // The unknowns grow like (1/f)^k, k from the last round (2
                // before the first: a uniform split's 4).
                let k = growth.unwrap_or(2.0);
                let mut g = (1.0 / f).powf(k);
                if report.size.dofs as f64 * g > target.max_dofs as f64 {
                    // A step the budget cannot hold becomes the largest round
                    // it can, where that is still a round's worth: stopping
                    // there left a tight target's answer at a fraction of the
                    // unknowns the user allowed (docs/verification/accuracy.md).
                    let room = BUDGET_FILL * target.max_dofs as f64 / report.size.dofs as f64;
                    let fits = room.powf(-1.0 / k);
                    if uniform || fits > STEP_MAX {
                        break StopReason::MaxDofs;
                    }
                    (f, g) = (fits, room);
                }
                // A generated round also solves its coarser companion; a
                // given mesh's round is the last one's finer companion.
                let companion = if uniform { 1.0 } else { 1.0 + est.share(&current) };
                if solve_seconds(&report) * g.powf(TIME_GROWTH) * companion > crate::cancel::remaining_secs() {
                    break StopReason::TimeLimit;
                }
                let mut next = if uniform {
                    resized(&current, [1.0 / RATIO; 3], None)
                } else {
                    resized(&current, [f, field_step(f), field_step(f)], Some(&report))
                }
                .expect("refining always succeeds");
                // The round's size as the budget predicts it (the unknowns'
                // measured growth, 2 per node), where the resized scene's own
                // count, compounded from round to round, reads low: what
                // `overlap` judges a companion beside it by (review).
                next.estimated_nodes = next.estimated_nodes.max(report.size.dofs as f64 * g / 2.0);
                // The round as built, whose spacing a punch's corners may have
                // moved (`sizing`), against the budget once more.
                let built = smallest_size(&next) / smallest_size(&current);
                if !uniform && built > 0.0 && report.size.dofs as f64 * built.powf(-k) > target.max_dofs as f64 {
                    break StopReason::MaxDofs;
                }
                crate::progress::round(rounds.len() + 1);
                // The last round's factor goes before this round's is made,
                // not beside it past the memory the request was admitted for;
                // should this round fail, the last stands without a bound.
                let released = report.pending_energy.take().is_some();
                let unbounded = |report: &mut Report| {
                    if released {
                        report.notes.push(Note::new(
                            NoteKind::EstimateLimited,
                            "no guaranteed energy bound: this round's factor was released for the next round, \
                             which did not solve",
                        ));
                    }
                };
                // A generated round is estimated with it (its companion
                // beside it when a core is free), a given mesh's below.
                let solved = if uniform {
                    solve(&next)
                } else {
                    overlap::round_estimated(est, &next, limits, solve)
                };
                match solved {
                    Ok(r) => (next, r),
                    Err(CoreError::Timeout { .. }) => {
                        unbounded(&mut report);
                        break StopReason::TimeLimit;
                    }
                    Err(CoreError::TooLarge { .. }) => {
                        unbounded(&mut report);
                        break StopReason::SizeLimit;
                    }
                    // A later round that cannot be solved (its mesh, its
                    // numerics) leaves the last round's answer standing.
                    Err(e) => {
                        unbounded(&mut report);
                        failure = Some(e.to_string());
                        break StopReason::RoundFailed;
                    }
                }
            }
        };
        if uniform {
            // Every element of this round is half the last round's: that
            // round is its coarser companion.
            if fine.pairs.len() == report.pairs.len() && fine.status == Status::Solved {
                for (f, c) in fine.pairs.iter_mut().zip(&report.pairs) {
                    f.accuracy = Some(est.pair(f, Some((c, RATIO))));
                }
            } else {
                for p in fine.pairs.iter_mut() {
                    p.accuracy = Some(accuracy::zone_edges_only(p));
                }
            }
            with_energy(&mut fine);
        }
        let h_step = smallest_size(&next) / smallest_size(&current);
        if h_step > 0.0 && h_step < 1.0 {
            growth = Some((fine.size.dofs as f64 / report.size.dofs.max(1) as f64).ln() / (1.0 / h_step).ln());
        }
        let r = round(&next, &fine, t.elapsed().as_secs_f64());
        let last = *rounds.last().expect("one round ran");
        rounds.push(r);
        if fine.status != Status::Solved {
            // The answer stays the last round that solved (module doc).
            break StopReason::NotSolved;
        }
        let better = |now: f64, before: f64| now <= PROGRESS * before;
        let improving = match (r.pressure_l2, last.pressure_l2) {
            (Some(a), Some(b)) if target.pressure_l2.is_some() => better(a, b),
            _ => target.zone_edge.is_none() || better(r.zone_edge, last.zone_edge) || r.zone_edge == 0.0,
        };
        report = fine;
        current = next;
        // Where the zone edge falls between nodes makes single rounds step
        // up as well as down (measured on the disk: 1.03, 1.08, 0.20, 0.21,
        // 0.10 % over five T6 levels with corner multipliers, T3 0.43, 0.24,
        // 0.26, 0.24 %): only two rounds without progress stop.
        stalled = if improving { 0 } else { stalled + 1 };
        if stalled >= 2 && !met(&report, &target) {
            break StopReason::NotConverging;
        }
    };
    bound_energy(est, &current, &mut report);
    let missed = not_reached(&report, &target, stopped, failure.as_deref());
    let ends = Ends {
        timings: &mut report.timings,
        notes: &mut report.notes,
        warnings: &mut report.warnings,
    };
    report.refinement = Some(ends.close(started, stopped, rounds, missed));
    Ok(report)
}

/// Where the rounds' end is written in a reply (2D's `Report`, a solid's
/// answer: `solid`).
struct Ends<'a> {
    timings: &'a mut crate::observer::Timings,
    notes: &'a mut Vec<Note>,
    warnings: &'a mut Vec<Warning>,
}

impl Ends<'_> {
    /// The rounds' end, whatever the dimension: the earlier rounds' time
    /// counted as the estimate's, a note when nothing touched or the
    /// `missed` warning when the target was not reached, and their record.
    fn close(self, started: Instant, stopped: StopReason, rounds: Vec<Round>, missed: Warning) -> Refinement {
        let total = started.elapsed().as_secs_f64();
        self.timings.estimate += (total - self.timings.total).max(0.0);
        self.timings.total = total;
        let reached = stopped == StopReason::Reached;
        if stopped == StopReason::NoContact {
            self.notes.push(Note::new(
                NoteKind::NotRefined,
                "nothing is in contact: there is no contact error to reduce, so the mesh was not refined \
                 (settings.accuracy)",
            ));
        } else if !reached {
            self.warnings.push(missed);
        }
        Refinement {
            reached,
            stopped,
            rounds,
        }
    }
}

/// Why the rounds stopped short of the target, for its warning.
fn stop_why(stopped: StopReason, target: &AccuracyTarget, failure: Option<&str>) -> String {
    match stopped {
        StopReason::MaxRounds => format!("after {} rounds (max_rounds)", target.max_rounds),
        StopReason::MaxDofs => format!(
            "the next round would exceed max_dofs = {} (the request's, or the service's size or memory limit)",
            target.max_dofs
        ),
        StopReason::SizeLimit => match failure {
            Some(why) => format!("the next round exceeds the service's size limit: {why}"),
            None => "the next round exceeds the service's size limit".into(),
        },
        StopReason::TimeLimit => {
            "the next round would not end within the time limit (predicted from the last round's time and growth)"
                .into()
        }
        StopReason::NotSolved => "a round did not solve".into(),
        StopReason::RoundFailed => format!("the next round failed: {}", failure.unwrap_or("unknown")),
        _ => "a round no longer reduced the estimate (a floor the element sizes do not move)".into(),
    }
}

/// The factor on `h_min` of a generated mesh's next round (`AIM`).
fn step(report: &Report, target: &AccuracyTarget) -> f64 {
    let (p, z) = worst(report);
    let want = |t: f64, e: f64, q: f64| {
        if e > 0.0 && e.is_finite() {
            (AIM * SAFETY * t / e).powf(1.0 / q)
        } else {
            1.0 / RATIO
        }
    };
    let by_pressure = match (target.pressure_l2, p) {
        (Some(t), Some(e)) => want(t, e, 2.0),
        (Some(_), None) => 1.0 / RATIO,
        _ => STEP_MAX,
    };
    let by_edge = target.zone_edge.map_or(STEP_MAX, |t| want(t, z, 1.0));
    by_pressure.min(by_edge).clamp(STEP_MIN, STEP_MAX)
}

/// Whether every pair's estimate meets the target with the margin
/// `SAFETY`.
fn met(report: &Report, target: &AccuracyTarget) -> bool {
    let (p, z) = worst(report);
    // The zone ends alone do not see the pressure's error away from them.
    let seen = report
        .pairs
        .iter()
        .all(|p| p.accuracy.as_ref().is_some_and(|a| a.basis != EstimateBasis::ZoneEdges));
    target
        .pressure_l2
        .is_none_or(|t| seen && p.is_some_and(|p| p <= SAFETY * t))
        && target.zone_edge.is_none_or(|t| z <= SAFETY * t)
}

/// The largest estimates over the pairs: pressure (None if no pair has a
/// two-level estimate), zone end.
fn worst(report: &Report) -> (Option<f64>, f64) {
    let acc: Vec<&PairAccuracy> = report.pairs.iter().filter_map(|p| p.accuracy.as_ref()).collect();
    let p = acc
        .iter()
        .filter_map(|a| a.pressure_l2)
        .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))));
    let z = acc
        .iter()
        .flat_map(|a| a.zone_edges.iter().flatten())
        .fold(0.0, |m: f64, &v| m.max(v));
    (p, z)
}

fn round(scene: &Scene, report: &Report, seconds: f64) -> Round {
    let (pressure_l2, zone_edge) = worst(report);
    Round {
        dofs: report.size.dofs,
        h_min: smallest_size(scene),
        pressure_l2,
        zone_edge,
        seconds,
    }
}

fn not_reached(report: &Report, target: &AccuracyTarget, stopped: StopReason, failure: Option<&str>) -> Warning {
    let (p, z) = worst(report);
    let why = stop_why(stopped, target, failure);
    let (value, limit, what) = match (target.pressure_l2, p) {
        (Some(t), Some(p)) if p > t => (p, t, format!("the pressure's estimated relative L2 error is {p:.3e}")),
        (Some(t), None) => (
            f64::INFINITY,
            t,
            "the pressure's error could not be estimated".to_string(),
        ),
        _ => {
            let t = target.zone_edge.unwrap_or(0.0);
            (z, t, format!("the zone ends' estimated error is {z:.3e}"))
        }
    };
    Warning {
        code: WarningCode::ToleranceNotReached,
        value: if value.is_finite() { value } else { f64::MAX },
        limit,
        location: "/settings/accuracy".into(),
        message: format!("{what}, above the target {limit:.3e}: refinement stopped because {why}"),
    }
}
