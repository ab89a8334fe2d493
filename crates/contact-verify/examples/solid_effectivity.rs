//! The 3D error bar against references it did not see: Hertz's sphere on a
//! flat (`proto/examples/solid_ball_on_flat.json`, a quarter model) at three
//! levels of `h_min`, T4 and T10, each estimate (`adapt::solid`, the coarser
//! companion) over the true error against (a) Hertz's closed form and (b) a
//! much finer solve of the same scene (T10, `h_min` = 0.1 mm unless given; 0.05 mm would
//! factor 24 GB):
//!
//! ```sh
//! cargo run --release -p contact-verify --example solid_effectivity [-- REF_H_MIN]
//! ```
//!
//! Hertz's closed form carries the model's own error besides the mesh's: the
//! block is a 10 mm cube, 10 a, not a half-space, and the paraboloid gap is
//! Hertz's (exact for his model, so only the finite block departs). The finer
//! solve has none of it, but its own discretization error: against it the
//! finest T10 level (half its size) reads about ¾ of its true error, for an
//! error of order 2 of the same sign at both.
//! Pressure: the relative L2 difference at the level's points, weighed by
//! their areas as the estimate weighs them (`Surface::relative_l2_against`);
//! peak: of the largest point pressure; area: of the patches' tributary area
//! (Hertz's quarter disk π a² / 4).

use contact_core::adapt::solid::estimate;
use contact_core::solid::door::SolidProblem;
use contact_core::solid::two_level::Surface;
use contact_core::{solve_solid_once, Limits};
use contact_verify::solid_ball::{hertz, hertz_pressure, problem, request};
use std::time::Instant;

fn main() {
    let reference_h: f64 = std::env::args().nth(1).map_or(0.1, |a| a.parse().expect("h_min [mm]"));
    let limits = Limits {
        max_dofs: 5_000_000,
        ..Limits::default()
    };
    let once = |p: &SolidProblem| solve_solid_once(p, &limits);
    let t = Instant::now();
    let (fine_answer, fine) = once(&problem(&request("t10", reference_h), &limits)).expect("the finer solve");
    println!(
        "reference: T10 h_min {reference_h} mm, {} DOF, {:.1} s",
        fine_answer.dofs,
        t.elapsed().as_secs_f64()
    );
    // Nondimensional, as the surfaces are: lengths over L, pressures over E.
    let (a, p0) = hertz();
    let hertz = hertz_pressure;
    let hertz_area = std::f64::consts::PI * a * a / 4.0;
    let read_fine = fine.reader();
    println!(
        "reference against Hertz: pressure_l2 {:.4}, peak {:.4}, area {:.4}",
        fine.relative_l2_against(hertz).unwrap_or(f64::NAN),
        (fine.peak() - p0).abs() / p0,
        (fine.contact_area() - hertz_area).abs() / hertz_area
    );
    println!(
        "| element | h_min [mm] | DOF | pressure_l2 est. | true (Hertz) | eff. | true (finer) | eff. | peak est. \
         | true (Hertz) | eff. | true (finer) | eff. | area est. | true (Hertz) | true (finer) | solve [s] \
         | estimate [s] |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (element, levels) in [("t4", [0.4, 0.2, 0.1]), ("t10", [0.8, 0.4, 0.2])] {
        for h in levels {
            let p = problem(&request(element, h), &limits);
            let (mut answer, level): (_, Surface) = once(&p).expect("a level");
            let solve_s = answer.timings.total;
            estimate(&p, &mut answer, &level, &once);
            let est = answer.accuracy.expect("estimated").estimate;
            let l2_h = level.relative_l2_against(hertz).unwrap_or(f64::NAN);
            let l2_f = level.relative_l2_against(&read_fine).unwrap_or(f64::NAN);
            let peak_h = (level.peak() - p0).abs() / p0;
            let peak_f = (level.peak() - fine.peak()).abs() / fine.peak();
            let area_h = (level.contact_area() - hertz_area).abs() / hertz_area;
            let area_f = (level.contact_area() - fine.contact_area()).abs() / fine.contact_area();
            let (el2, epk, ear) = (
                est.pressure_l2.unwrap_or(f64::NAN),
                est.peak.unwrap_or(f64::NAN),
                est.contact_area.unwrap_or(f64::NAN),
            );
            println!(
                "| {element} | {h} | {} | {el2:.4} | {l2_h:.4} | {:.2} | {l2_f:.4} | {:.2} | {epk:.4} | {peak_h:.4} | \
                 {:.2} | {peak_f:.4} | {:.2} | {ear:.3} | {area_h:.3} | {area_f:.3} | {solve_s:.2} | {:.2} |",
                answer.dofs,
                el2 / l2_h,
                el2 / l2_f,
                epk / peak_h,
                epk / peak_f,
                answer.timings.estimate,
            );
        }
    }
}
