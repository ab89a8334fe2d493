//! The 3D error bar (`adapt::solid`, `solid::two_level`) against a reference
//! it did not see: Hertz's ball on a flat (`contact_verify::solid_ball`)
//! solved much finer, one level per element, and `settings.accuracy`'s
//! reached answer against the same reference. The full table (three levels,
//! T4 and T10, against Hertz and a finer solve) is
//! `examples/solid_effectivity.rs`, in docs/verification/accuracy.md.
//!
//! The reference is T10 at `h_min` = 0.2 mm (35k DOF, a few seconds; the
//! table's T10 at 0.1 mm takes 4 GB and a minute and a half): its own
//! pressure error, 5.1 % in the L2 norm against that finer one
//! (`REFERENCE_ERROR`), is a share of what the coarse levels here are
//! measured against, and is allowed for where a bound is asserted.

use contact_core::adapt::solid::estimate;
use contact_core::solid::door::SolidProblem;
use contact_core::solid::two_level::Surface;
use contact_core::{solve_solid, solve_solid_once, Limits};
use contact_verify::solid_ball::{problem, request};
use serde_json::json;
use std::cell::RefCell;

/// The reference's own relative L2 error, measured against T10 at
/// `h_min` = 0.1 mm by `solid_effectivity` (docs/verification/accuracy.md).
const REFERENCE_ERROR: f64 = 0.052;

fn reference(limits: &Limits) -> Surface {
    solve_solid_once(&problem(&request("t10", 0.2), limits), limits)
        .expect("the reference")
        .1
}

#[test]
fn the_estimate_reads_the_pressure_error_of_a_finer_solve() {
    let limits = Limits::default();
    let fine = reference(&limits);
    let read = fine.reader();
    let once = |p: &SolidProblem| solve_solid_once(p, &limits);
    // T4 at 0.4 mm (0.4 a) is 4 times coarser than the reference in its
    // elements' size and a degree below it; T10 at 0.8 mm 4 times coarser.
    for (element, h) in [("t4", 0.4), ("t10", 0.8)] {
        let p = problem(&request(element, h), &limits);
        let (mut answer, level) = once(&p).expect("a level");
        estimate(&p, &mut answer, &level, &once);
        let est = answer.accuracy.expect("estimated").estimate;
        let l2 = est.pressure_l2.expect("a pressure estimate");
        let truth = level.relative_l2_against(&read).expect("pressure");
        let eff = l2 / truth;
        println!("{element} h_min {h}: estimate {l2:.4}, against the reference {truth:.4}, effectivity {eff:.2}");
        // The band asked of the 2D estimates is [0.5, 2]. The 3D pressure is
        // scaled for an error of order h (`solid::two_level`), so where the
        // levels are not yet asymptotic it reads the whole difference, on
        // the safe side: the table measured 1.36–5.27 over six levels, 3.07
        // for this T4 level and 1.43 for this T10 one against the 0.1 mm
        // reference. Above 4 the bar would be useless; below 0.5, unsafe.
        assert!((0.5..=4.0).contains(&eff), "{element}: effectivity {eff}");
    }
}

#[test]
fn a_reached_target_is_met_against_the_reference() {
    let limits = Limits::default();
    // A target the rounds meet on a mesh coarser than the reference (T4 at
    // 0.2 mm, 5k DOF): at 0.2 they went on to a T4 mesh of 64k DOF, finer
    // than the reference, against which the difference measured the
    // reference's own error.
    let target = 0.4;
    let mut req = request("t4", 0.8);
    req["settings"] = json!({"accuracy": {"pressure_l2": target}});
    let p = problem(&req, &limits);
    let answer = solve_solid(&p, &limits).expect("refined");
    let refinement = answer.refinement.as_ref().expect("rounds");
    assert!(refinement.reached, "{refinement:?}");
    assert!(refinement.rounds.len() >= 2, "the coarse start refines: {refinement:?}");
    // The reached round solved again, for its surface: the rounds are
    // deterministic, so the last one's mesh is rebuilt from the rounds the
    // solver saw (recorded by DOF count, which the companions do not share).
    let seen = RefCell::new(Vec::<(usize, Surface)>::new());
    let record = |q: &SolidProblem| {
        let solved = solve_solid_once(q, &limits)?;
        seen.borrow_mut().push((solved.0.dofs, solved.1.clone()));
        Ok(solved)
    };
    let again = contact_core::adapt::solid::refine(&p, p.scene.settings.accuracy.unwrap(), &record, &limits)
        .expect("refined again");
    assert_eq!(again.dofs, answer.dofs, "the rounds are deterministic");
    let level = seen
        .borrow()
        .iter()
        .rev()
        .find(|(d, _)| *d == answer.dofs)
        .expect("the last round was solved")
        .1
        .clone();
    let fine = reference(&limits);
    // Its T4 elements no smaller than the reference's T10 ones: coarser in
    // size or in degree.
    let reached_h = refinement.rounds.last().unwrap().h_min;
    assert!(
        reached_h >= 0.2 * (1.0 - 1e-9),
        "the reached round's h_min {reached_h} mm"
    );
    let truth = level.relative_l2_against(fine.reader()).expect("pressure");
    let est = answer.accuracy.unwrap().estimate.pressure_l2.unwrap();
    println!(
        "target {target}: {} rounds, {} DOF, estimate {est:.4}, against the reference {truth:.4}",
        refinement.rounds.len(),
        answer.dofs
    );
    // The true error is at most the difference from the reference plus the
    // reference's own (the triangle inequality, to the relative norms'
    // different denominators).
    assert!(
        truth + REFERENCE_ERROR <= target,
        "true error {truth} + the reference's {REFERENCE_ERROR} above {target}"
    );
}

#[test]
fn estimate_false_solves_no_companion() {
    let limits = Limits::default();
    let mut req = request("t4", 0.8);
    req["settings"] = json!({"estimate": false});
    let answer = solve_solid(&problem(&req, &limits), &limits).expect("solved");
    assert!(answer.accuracy.is_none());
    assert_eq!(answer.timings.estimate, 0.0);
}
