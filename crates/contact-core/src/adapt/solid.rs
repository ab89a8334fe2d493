//! The error bar of a 3D solid's answer, and `settings.accuracy` for it.
//!
//! **Estimate.** A generated box is solved again with its grading's `h_min`,
//! growth (ratio − 1) and far-field `size` doubled, its graded window
//! unchanged: the 2D design's coarser companion (`sizing::scaled`, the same
//! rule), every element about twice as large, far field included, at about
//! an eighth of the unknowns. The two answers are compared on the candidate
//! face set (`solid::two_level`). A given (inline or Gmsh) mesh gets no
//! estimate by default (basis `none`, with a note saying how to get one): it
//! cannot be coarsened without a 3D remesher, and its finer companion (every
//! tetrahedron split in eight, `mesh3d::refine`) has eight times the
//! unknowns, whose factor fills faster than linearly, several solves' time
//! where the coarser one costs a fraction of one. `settings.accuracy` pays
//! that price knowingly (below).
//!
//! **Rounds** (`settings.accuracy`). As in 2D (`adapt`'s module doc, whose
//! constants these share), one loop for both kinds of mesh ([`Rounds`]),
//! which differ in how the next mesh is made and what it is compared with:
//!
//! - *a generated box*: each round's `h_min` shrinks by f sized from the
//!   last estimate (`AIM`, `SAFETY`, the pressure's order 1, within
//!   `STEP_MIN`–`STEP_MAX`), the growth and the far field by √f, and the
//!   graded window widens to cover every point in contact with a quarter of
//!   margin. A box's node count is known exactly before it is meshed
//!   (`scene::solid::grid_nodes`), so a round past `max_dofs` is cut to the
//!   largest that fits, where that is still a round's step. Each round is
//!   estimated against its own coarser companion;
//! - *a given mesh*: round 0 is the mesh as given, round k + 1 round k with
//!   every tetrahedron split in eight (`mesh3d::refine`, T10 children on the
//!   parent's curved map), its node count exact before it is made
//!   (`refined_nodes`). Round k ≥ 1 is estimated against round k − 1, which
//!   is its coarser companion exactly as a box's is (every element twice as
//!   large, far field included), already solved: the estimate costs the
//!   comparison only. Round 0 has no estimate, so a given mesh's rounds
//!   solve at least two meshes, the second with eight times the unknowns.
//!
//! The rounds stop when the estimate meets its target (with `SAFETY`), when
//! nothing is in contact, at `max_rounds`, `max_dofs` or the service's
//! memory per request (the next factor's bytes predicted from the last
//! one's as n², `FACTOR_GROWTH`: both judged before the next mesh is
//! made, stop `max_dofs` as in 2D), the time limit (a
//! round's time predicted as t ∝ n², `SOLID_TIME_GROWTH`), when two rounds
//! do not improve the estimate, or when a round fails or is refused by the
//! size, candidate or memory limits `solve` applies to every mesh
//! (`solid::signorini::prepare_within` judges the factor from its symbolic
//! analysis before taking its memory); the last round that solved is the
//! answer, with `tolerance_not_reached` unless it met.

use std::time::Instant;

use super::sizing::{scaled, MARGIN, RATIO};
use super::{field_step, stop_why, Ends, AIM, PROGRESS, SAFETY, STEP_MAX, STEP_MIN};
use crate::error::CoreError;
use crate::mesh::generate::Grading;
use crate::mesh3d::refine::{refine as split, refined_nodes};
use crate::mesh3d::{Mesh3d, EDGES};
use crate::outcome::{EstimateBasis, Note, NoteKind, Status, StopReason, WarningCode};
use crate::scene::solid::{grid_nodes, SolidMesh};
use crate::scene::{AccuracyTarget, Limits, Outputs};
use crate::solid::answer::{SolidAccuracy, SolidAnswer};
use crate::solid::door::SolidProblem;
use crate::solid::two_level::{two_level, Surface, PRESSURE_ORDER};
use crate::solution::report::{Round, Warning};

/// A solve of one 3D problem: its answer and its candidate surface.
pub type SolidSolver<'a> = dyn Fn(&SolidProblem) -> Result<(SolidAnswer, Surface), CoreError> + 'a;

/// The estimate's share of a solve, for the progress plan and the rounds'
/// time prediction: the coarser companion's eighth of the unknowns costs
/// less than that of the time (`TIME_GROWTH`), the comparison a few
/// milliseconds; 0.25 bounds what `solid_effectivity` measured.
pub const COMPANION_SHARE: f64 = 0.25;

/// The coarser companion of a generated box (module doc), None for a given
/// mesh. It asks for no estimate, no refinement and no fields.
pub fn companion(problem: &SolidProblem) -> Option<SolidProblem> {
    let mut c = resized(problem, [RATIO; 3], &[])?;
    c.scene.settings.estimate = false;
    c.scene.settings.accuracy = None;
    c.scene.outputs = Outputs::default();
    Some(c)
}

/// The box with its grading's `h_min` times `h`, its growth times `growth`
/// and its far-field size times `size`, the graded window widened to cover
/// `pressed` (created around them on an ungraded box); None for a given
/// mesh.
pub fn resized(problem: &SolidProblem, [h, growth, size]: [f64; 3], pressed: &[[f64; 3]]) -> Option<SolidProblem> {
    let SolidMesh::Box {
        lo,
        hi,
        size: s,
        grading,
        t10,
    } = &problem.scene.mesh
    else {
        return None;
    };
    let new_size = s * size;
    let grading = match (grading, pressed.is_empty()) {
        (Some((focus, g)), true) => Some((*focus, scaled(*g, [h, growth], new_size))),
        (None, true) => None,
        (g, false) => {
            let (focus, g0) = match g {
                Some((f, g0)) => (*f, *g0),
                None => (
                    centre(pressed),
                    Grading {
                        h_min: *s,
                        ratio: 1.1,
                        extent: 0.0,
                    },
                ),
            };
            let mut g1 = scaled(g0, [h, growth], new_size);
            g1.extent = g1.extent.max(MARGIN * reach(focus, pressed));
            Some((focus, g1))
        }
    };
    let mut out = problem.clone();
    out.scene.estimated_nodes = grid_nodes(*lo, *hi, new_size, grading, *t10);
    out.scene.mesh = SolidMesh::Box {
        lo: *lo,
        hi: *hi,
        size: new_size,
        grading,
        t10: *t10,
    };
    Some(out)
}

/// Fills `answer.accuracy` when `settings.estimate` asks for it (module
/// doc), timed as the estimate's.
pub fn estimate(problem: &SolidProblem, answer: &mut SolidAnswer, surface: &Surface, solve: &SolidSolver) {
    if problem.scene.settings.estimate {
        estimate_always(problem, answer, surface, solve);
    }
}

/// Why a given 3D mesh's answer has no estimate by default, and how to get
/// one (module doc).
const GIVEN_NOTE: &str = "no error estimate on a given 3D mesh by default: it cannot be coarsened, and its finer \
     companion (every tetrahedron split in eight) has 8 times the unknowns, several solves' time; give \
     `settings.accuracy` (e.g. {\"pressure_l2\": 0.1}) to refine it uniformly in rounds, each estimated against \
     the one before (the answer is then the refined mesh's), or mesh the body as a generated box (`mesh.box`), \
     which carries one";

fn estimate_always(problem: &SolidProblem, answer: &mut SolidAnswer, surface: &Surface, solve: &SolidSolver) {
    let t = Instant::now();
    let limited = |answer: &mut SolidAnswer, why: String| {
        answer.notes.push(Note::new(NoteKind::EstimateLimited, why));
        SolidAccuracy::none()
    };
    let accuracy = match companion(problem) {
        _ if answer.status != Status::Solved => SolidAccuracy::none(),
        None => limited(answer, GIVEN_NOTE.into()),
        Some(c) => {
            // The companion's own stages would restart the caller's bar.
            crate::progress::stage(crate::progress::ESTIMATE);
            let _nested = crate::progress::Sink::nested();
            match solve(&c) {
                Ok((a, s)) if a.status == Status::Solved => SolidAccuracy {
                    basis: EstimateBasis::TwoLevel,
                    estimate: two_level(surface, &s, RATIO),
                },
                Ok((a, _)) => limited(
                    answer,
                    format!("the error estimate's coarser solve ended {:?}: no estimate", a.status),
                ),
                Err(e) => limited(
                    answer,
                    format!("the error estimate's coarser solve failed: {e}; no estimate"),
                ),
            }
        }
    };
    answer.accuracy = Some(accuracy);
    let dt = t.elapsed().as_secs_f64();
    answer.timings.estimate += dt;
    answer.timings.total += dt;
}

/// How a 3D solve's time grows with its unknowns, t ∝ n^2: a 3D factor
/// fills far faster than a 2D one (2D's `cost::TIME_GROWTH` is 1.2); the
/// T10 ball went from 5.35 s at 35k DOF to 90–160 s at 149k (exponent
/// 2.0–2.4, loaded machine, docs/verification/accuracy.md).
const SOLID_TIME_GROWTH: f64 = 2.0;

/// A 3D factor's stored values are predicted to grow as nnz(L) ∝ n², above
/// every growth measured (nested dissection of a 3D grid: n^(4/3), George
/// and Liu): the `solid3d_timing` example (`--cost`) measured n^1.40 on
/// graded T4 boxes (47k to 293k DOF), n^1.66 on T10 (49k to 134k), and the
/// ball example's regraded T10 round from 35k DOF n^1.81 (at n^1.5 it was
/// let in under the 3.75 GB a request had, and its analysis then predicted
/// a factor of 6.41 GB, refused after the round was built).
/// Reading high cuts a round smaller; reading low builds it for nothing.
const FACTOR_GROWTH: f64 = 2.0;

/// How the rounds make their next mesh and estimate each answer (module
/// doc): the loop of [`refine`] is the same for both.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rounds {
    /// A generated box, regraded from the last estimate.
    Regraded,
    /// A given mesh, every tetrahedron split in eight.
    Split,
}

impl Rounds {
    fn of(problem: &SolidProblem) -> Self {
        match problem.mesh {
            Some(_) => Rounds::Split,
            None => Rounds::Regraded,
        }
    }

    /// The round after `current`, or why there is none.
    /// `max_bytes`: the memory a factor may take (`Limits::memory_bytes`).
    fn next(
        self,
        current: &SolidProblem,
        answer: &SolidAnswer,
        pressed: &[[f64; 3]],
        target: &AccuracyTarget,
        max_bytes: f64,
    ) -> Result<SolidProblem, StopReason> {
        // The next factor's bytes from this one's (`FACTOR_GROWTH`), the
        // unknowns' growth from the node counts each mesh is made with.
        let now = current.scene.estimated_nodes;
        let factor = |nodes: f64| answer.factor_bytes * (nodes / now).max(1.0).powf(FACTOR_GROWTH);
        let fits = |nodes: f64| 3.0 * nodes <= target.max_dofs as f64 && factor(nodes) <= max_bytes;
        if self == Rounds::Split {
            let mesh = current.mesh.as_ref().expect("a given mesh");
            // Counted before it is made: eight times a mesh at the limit
            // would be made for nothing (a round whose factor the analysis
            // refused as past the memory took 1.68 GB and minutes).
            let nodes = refined_nodes(mesh) as f64;
            if !fits(nodes) {
                return Err(StopReason::MaxDofs);
            }
            let mut scene = current.scene.clone();
            scene.estimated_nodes = nodes;
            return Ok(SolidProblem {
                scene,
                mesh: Some(split(mesh)),
            });
        }
        let nodes =
            |f: f64| resized(current, [f, field_step(f), field_step(f)], pressed).expect("a generated box is resized");
        let next = nodes(step(answer, target));
        if fits(next.scene.estimated_nodes) {
            return Ok(next);
        }
        // The largest round the budget holds, where that is still a step
        // (bisection on f: the node count falls as f grows).
        let widest = nodes(STEP_MAX);
        if !fits(widest.scene.estimated_nodes) {
            return Err(StopReason::MaxDofs);
        }
        let (mut lo, mut hi, mut next) = (step(answer, target), STEP_MAX, widest);
        for _ in 0..20 {
            let mid = 0.5 * (lo + hi);
            let p = nodes(mid);
            if fits(p.scene.estimated_nodes) {
                (hi, next) = (mid, p);
            } else {
                lo = mid;
            }
        }
        Ok(next)
    }

    /// Fills `answer.accuracy`: a box against its coarser companion, solved
    /// now; a given mesh's round against the round before (`coarser`), None
    /// for round 0.
    fn estimate(
        self,
        problem: &SolidProblem,
        answer: &mut SolidAnswer,
        surface: &Surface,
        coarser: Option<&Surface>,
        solve: &SolidSolver,
    ) {
        if self == Rounds::Regraded {
            return estimate_always(problem, answer, surface, solve);
        }
        let t = Instant::now();
        answer.accuracy = Some(match coarser {
            Some(c) if answer.status == Status::Solved => SolidAccuracy {
                basis: EstimateBasis::TwoLevel,
                estimate: two_level(surface, c, RATIO),
            },
            Some(_) => SolidAccuracy::none(),
            None => {
                answer.notes.push(Note::new(
                    NoteKind::EstimateLimited,
                    "the given 3D mesh's own answer has no estimate: the first refinement round (every tetrahedron \
                     split in eight) is estimated against it"
                        .to_string(),
                ));
                SolidAccuracy::none()
            }
        });
        let dt = t.elapsed().as_secs_f64();
        answer.timings.estimate += dt;
        answer.timings.total += dt;
    }

    /// The estimate's share of a round's solve time (`COMPANION_SHARE`; a
    /// given mesh's comparison is a few milliseconds).
    fn companion_share(self) -> f64 {
        match self {
            Rounds::Regraded => COMPANION_SHARE,
            Rounds::Split => 0.0,
        }
    }
}

/// Solves, estimates and refines the problem's mesh until `target` is met
/// or a limit stops the rounds (module doc). `limits`: the deployment's
/// `max_dofs`, its size limit, and `memory_bytes`, the memory a factor may take, which no
/// round may pass.
pub fn refine(
    problem: &SolidProblem,
    target: AccuracyTarget,
    solve: &SolidSolver,
    limits: &Limits,
) -> Result<SolidAnswer, CoreError> {
    let max_bytes = limits.memory_bytes();
    let target = AccuracyTarget {
        max_dofs: target.max_dofs.min(limits.max_dofs),
        ..target
    };
    let kind = Rounds::of(problem);
    let started = Instant::now();
    crate::progress::round(1);
    let mut current = problem.clone();
    let (mut answer, mut surface) = solve(&current)?;
    kind.estimate(&current, &mut answer, &surface, None, solve);
    let mut rounds = vec![round(&current, &answer, started.elapsed().as_secs_f64())];
    let (mut stalled, mut failure) = (0, None::<String>);
    let stopped = loop {
        let pressed: Vec<[f64; 3]> = (0..surface.points.len())
            .filter(|&i| surface.pressure[i] > 0.0)
            .map(|i| surface.points[i])
            .collect();
        if answer.status == Status::Solved && pressed.is_empty() {
            break StopReason::NoContact;
        }
        if met(&answer, &target) {
            break StopReason::Reached;
        }
        if answer.status != Status::Solved {
            break StopReason::NotSolved;
        }
        if rounds.len() >= target.max_rounds {
            break StopReason::MaxRounds;
        }
        let t = Instant::now();
        let next = match kind.next(&current, &answer, &pressed, &target, max_bytes) {
            Ok(next) => next,
            Err(stop) => break stop,
        };
        let growth = next.scene.estimated_nodes / current.scene.estimated_nodes;
        let seconds = (answer.timings.total - answer.timings.estimate).max(0.0);
        let predicted = seconds * growth.powf(SOLID_TIME_GROWTH) * (1.0 + kind.companion_share());
        if predicted > crate::cancel::remaining_secs() {
            break StopReason::TimeLimit;
        }
        crate::progress::round(rounds.len() + 1);
        let (mut fine, fine_surface) = match solve(&next) {
            Ok(solved) => solved,
            Err(CoreError::Timeout { .. }) => break StopReason::TimeLimit,
            Err(e @ CoreError::TooLarge { .. }) => {
                failure = Some(e.to_string());
                break StopReason::SizeLimit;
            }
            Err(e) => {
                failure = Some(e.to_string());
                break StopReason::RoundFailed;
            }
        };
        kind.estimate(&next, &mut fine, &fine_surface, Some(&surface), solve);
        let r = round(&next, &fine, t.elapsed().as_secs_f64());
        let last = *rounds.last().expect("one round ran");
        rounds.push(r);
        if fine.status != Status::Solved {
            // The answer stays the last round that solved (module doc).
            break StopReason::NotSolved;
        }
        let improving = match (r.pressure_l2, last.pressure_l2) {
            (Some(a), Some(b)) => a <= PROGRESS * b,
            // The first estimate of a given mesh's rounds: nothing before
            // it to improve on.
            (Some(_), None) => kind == Rounds::Split,
            _ => false,
        };
        (answer, surface, current) = (fine, fine_surface, next);
        stalled = if improving { 0 } else { stalled + 1 };
        if stalled >= 2 && !met(&answer, &target) {
            break StopReason::NotConverging;
        }
    };
    let missed = not_reached(&answer, &target, stopped, failure.as_deref());
    let ends = Ends {
        timings: &mut answer.timings,
        notes: &mut answer.notes,
        warnings: &mut answer.warnings,
    };
    answer.refinement = Some(ends.close(started, stopped, rounds, missed));
    Ok(answer)
}

fn estimated(answer: &SolidAnswer) -> Option<f64> {
    answer
        .accuracy
        .filter(|a| a.basis == EstimateBasis::TwoLevel)
        .and_then(|a| a.estimate.pressure_l2)
}

/// The factor on `h_min` of the next round: the estimate landed at `AIM` of
/// the target's met value, for an error of the pressure's order
/// (`solid::two_level::PRESSURE_ORDER`).
fn step(answer: &SolidAnswer, target: &AccuracyTarget) -> f64 {
    match (target.pressure_l2, estimated(answer)) {
        (Some(t), Some(e)) if e > 0.0 && e.is_finite() => (AIM * SAFETY * t / e).powf(1.0 / PRESSURE_ORDER),
        _ => 1.0 / RATIO,
    }
    .clamp(STEP_MIN, STEP_MAX)
}

/// Whether the two-level estimate meets the target with the margin `SAFETY`.
fn met(answer: &SolidAnswer, target: &AccuracyTarget) -> bool {
    target
        .pressure_l2
        .is_none_or(|t| estimated(answer).is_some_and(|p| p <= SAFETY * t))
}

fn round(problem: &SolidProblem, answer: &SolidAnswer, seconds: f64) -> Round {
    let h_min = match (&problem.scene.mesh, &problem.mesh) {
        (SolidMesh::Box { size, grading, .. }, _) => grading.map_or(*size, |(_, g)| g.h_min.min(*size)),
        (_, Some(mesh)) => shortest_edge(mesh),
        _ => f64::NAN,
    };
    Round {
        dofs: answer.dofs,
        h_min: h_min * problem.scene.length,
        pressure_l2: estimated(answer),
        // A solid's patch has no zone ends.
        zone_edge: 0.0,
        seconds,
    }
}

fn not_reached(answer: &SolidAnswer, target: &AccuracyTarget, stopped: StopReason, failure: Option<&str>) -> Warning {
    let why = stop_why(stopped, target, failure);
    let limit = target.pressure_l2.unwrap_or(0.0);
    let (value, what) = match estimated(answer) {
        Some(p) => (p, format!("the pressure's estimated relative L2 error is {p:.3e}")),
        None => (f64::MAX, "the pressure's error could not be estimated".to_string()),
    };
    Warning {
        code: WarningCode::ToleranceNotReached,
        value,
        limit,
        location: "/settings/accuracy".into(),
        message: format!("{what}, above the target {limit:.3e}: refinement stopped because {why}"),
    }
}

/// The shortest element edge of a given mesh (its corners'): its `h_min`.
fn shortest_edge(mesh: &Mesh3d) -> f64 {
    (0..mesh.n_elems())
        .flat_map(|e| {
            let c = mesh.elem(e);
            EDGES.map(|[i, j]| {
                let d = crate::mesh3d::sub(mesh.nodes[c[i]], mesh.nodes[c[j]]);
                crate::mesh3d::dot(d, d).sqrt()
            })
        })
        .fold(f64::INFINITY, f64::min)
}

/// The farthest of `points` from `from`.
fn reach(from: [f64; 3], points: &[[f64; 3]]) -> f64 {
    points
        .iter()
        .map(|p| (0..3).map(|c| (p[c] - from[c]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
}

/// The centre of the points' bounding box.
fn centre(points: &[[f64; 3]]) -> [f64; 3] {
    std::array::from_fn(|c| {
        let lo = points.iter().map(|p| p[c]).fold(f64::INFINITY, f64::min);
        let hi = points.iter().map(|p| p[c]).fold(f64::NEG_INFINITY, f64::max);
        0.5 * (lo + hi)
    })
}
