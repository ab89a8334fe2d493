//! The time-against-error benchmark: the Hertz scene (rigid cylinder into a
//! block) at several mesh sizes, T3 and T6, with every method, each row timed
//! per stage and compared with the closed form and with the physical floor of
//! one symbolic + numeric Cholesky + one solve of the same K (AMD order,
//! sequential: the solver's own kernels and parallelism), the ratios per
//! stage (`r_fact`: factorization, `r_cont`: condensation and contact solve
//! against the floor's solve). Rows with Coulomb friction (one step, the
//! active set of `methods::friction::condensed`, and on T3 of `methods::friction::full`)
//! follow the frictionless ones of each mesh. The floor mode ends with one
//! two-body row (`two_bodies_cylinders.json` refined to about 1.18M DOF),
//! whose contact rows once cost as much as its factorization.
//! The harness returns rows; the CLI prints and writes them.

use std::time::Instant;

use serde_json::json;

use crate::reference::hertz;
use contact_core::solution::report::Report;
use contact_core::{Limits, Scene};
use contact_proto::{Formulation, MethodName};

#[derive(Debug, Clone)]
pub struct Row {
    pub scene: String,
    pub element: &'static str,
    pub h_min: f64,
    pub dofs: usize,
    pub candidates: usize,
    pub method: String,
    pub iterations: usize,
    pub t_mesh: f64,
    pub t_assembly: f64,
    pub t_factorization: f64,
    pub t_condensation: f64,
    pub t_contact: f64,
    pub t_post: f64,
    pub t_total: f64,
    /// Symbolic + numeric Cholesky + one solve of K (AMD, sequential), same mesh.
    pub t_floor: f64,
    /// Its factorization and its solve.
    pub t_floor_factor: f64,
    pub t_floor_solve: f64,
    pub err_half_width: f64,
    pub err_peak: f64,
    pub err_l2: f64,
    pub max_penetration: f64,
    pub certificate: f64,
    pub status: String,
    /// Threads of the factorization and sweeps (`--threads`), the floor's too.
    pub threads: usize,
}

impl Row {
    pub const HEADER: &'static str = "scene,element,h_min,dofs,candidates,method,iterations,t_mesh,t_assembly,\
        t_factorization,t_condensation,t_contact,t_post,t_total,t_floor,ratio_solve_to_floor,ratio_total_to_floor,\
        err_half_width,err_peak,err_l2,max_penetration,certificate,status,t_floor_factor,t_floor_solve,ratio_factor,\
        ratio_contact,threads";

    /// The factorization against the floor's: the same factor of K on the same
    /// kernels and parallelism, so 1 up to run-to-run spread.
    pub fn ratio_factor(&self) -> f64 {
        self.t_factorization / self.t_floor_factor
    }

    /// Condensation and contact solve against the floor's one solve.
    pub fn ratio_contact(&self) -> f64 {
        (self.t_condensation + self.t_contact) / self.t_floor_solve
    }

    /// Time of the contact solve proper (factorization through recovery) over the floor.
    pub fn ratio(&self) -> f64 {
        (self.t_factorization + self.t_condensation + self.t_contact) / self.t_floor
    }

    pub fn csv(&self) -> String {
        format!(
            "{},{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.3},{:.3},{:.3e},{:.3e},{:.3e},\
                {:.3e},{:.1e},{},{:.6},{:.6},{:.3},{:.3},{}",
            self.scene,
            self.element,
            self.h_min,
            self.dofs,
            self.candidates,
            self.method,
            self.iterations,
            self.t_mesh,
            self.t_assembly,
            self.t_factorization,
            self.t_condensation,
            self.t_contact,
            self.t_post,
            self.t_total,
            self.t_floor,
            self.ratio(),
            self.t_total / self.t_floor,
            self.err_half_width,
            self.err_peak,
            self.err_l2,
            self.max_penetration,
            self.certificate,
            self.status,
            self.t_floor_factor,
            self.t_floor_solve,
            self.ratio_factor(),
            self.ratio_contact(),
            self.threads
        )
    }

    pub fn table_header() -> String {
        format!(
            "{:<13} {:<7} {:>7} {:>8} {:>5} {:<28} {:>4} {:>8} {:>8} {:>8} {:>8} {:>8} \
                {:>6} {:>6} {:>6} {:>9} {:>9} {:>9} {:>8}",
            "scene",
            "element",
            "h_min",
            "dofs",
            "cand",
            "method",
            "it",
            "assembly",
            "factor",
            "contact",
            "total",
            "floor",
            "ratio",
            "r_fact",
            "r_cont",
            "err_a",
            "err_p0",
            "err_L2",
            "cert"
        )
    }

    pub fn table_line(&self) -> String {
        format!(
            "{:<13} {:<7} {:>7} {:>8} {:>5} {:<28} {:>4} {:>8.3} {:>8.3} {:>8.4} {:>8.3} {:>8.3} \
                {:>6.2} {:>6.2} {:>6.2} {:>+9.2e} {:>+9.2e} {:>9.2e} {:>8.1e}",
            self.scene,
            self.element,
            self.h_min,
            self.dofs,
            self.candidates,
            self.method,
            self.iterations,
            self.t_assembly,
            self.t_factorization,
            self.t_condensation + self.t_contact,
            self.t_total,
            self.t_floor,
            self.ratio(),
            self.ratio_factor(),
            self.ratio_contact(),
            self.err_half_width,
            self.err_peak,
            self.err_l2,
            self.certificate
        )
    }
}

/// The benchmark's Hertz request: rigid cylinder R = 8 pressed 0.12 into a
/// 40 × 20 block (E = 200, ν = 0.3), uniform `h_min` within 0.8 of the apex.
pub fn hertz_request(h_min: f64, element: &str, method: &str) -> serde_json::Value {
    use crate::build::*;
    let mesh = graded(
        rectangle([-20.0, -20.0], 40.0, 20.0, 1.0, element),
        grading(h_min, 1.1, 0.8, Some([0.0, 0.0])),
    );
    request(
        vec![body("block", 200.0, 0.3, mesh).fixed("bottom")],
        vec![pair("block", "top").obstacle("cylinder")],
    )
    .with_obstacle(obstacle("cylinder", circle([0.0, 7.88], 8.0)))
    .with_method(method_name(method))
    .with_description("benchmark: Hertz, rigid cylinder into a block")
    .to_value()
}

/// Errors of a Hertz reply against the closed form with pair 0's own load
/// (on a rigid obstacle the pair's resultant is the scene's):
/// (half-width, peak pressure, relative L2 of the pressure along the contact line).
pub fn hertz_errors(r: &Report, radius: f64, e_star: f64) -> (f64, f64, f64) {
    let pair = &r.pairs[0];
    let (a, p0) = hertz(pair.resultant.fy.abs(), radius, e_star);
    let a_fe = pair.zones.first().map(|z| 0.5 * (z[1] - z[0])).unwrap_or(0.0);
    let p_fe = pair.points.iter().map(|q| q.pressure).fold(0.0, f64::max);
    let (mut num, mut den) = (0.0, 0.0);
    for q in &pair.points {
        let exact = if q.x.abs() < a {
            p0 * (1.0 - (q.x / a).powi(2)).sqrt()
        } else {
            0.0
        };
        // Tributary lengths integrate along the contact line.
        num += q.weight * (q.pressure - exact).powi(2);
        den += q.weight * exact * exact;
    }
    (a_fe / a - 1.0, p_fe / p0 - 1.0, (num / den).sqrt())
}

/// Floor: one AMD-ordered supernodal Cholesky of K_ff (symbolic and numeric)
/// and one solve with it, on the solver's own code path with no contact DOFs
/// held last: the same faer kernels, the same (sequential) parallelism as the
/// solve it is compared with, and faer's global setting left alone. Returns
/// (factorization seconds, solve seconds, DOFs).
fn floor_time(scene: &Scene) -> (f64, f64, usize) {
    let meshes = contact_core::meshing::meshes(scene).expect("the bench's scenes mesh");
    let dofs = contact_core::fem::assembly::dof_map(scene, &meshes).expect("benchmark scene is valid");
    let asm = contact_core::fem::assemble(scene, &meshes, dofs).expect("benchmark scene assembles");
    let k = &asm.stiffness.k;
    let t = Instant::now();
    let chol = contact_core::linalg::Cholesky::try_new(k).expect("the bench's K is positive definite");
    let factor = t.elapsed().as_secs_f64();
    let t = Instant::now();
    std::hint::black_box(chol.solve(&asm.f));
    (factor, t.elapsed().as_secs_f64(), k.nrows())
}

/// Coulomb coefficient of the frictional row (the scene's ν = 0.3 makes the
/// normal load alone slip near the zone's edges, so the step has stick and
/// slip points).
const FRICTION: f64 = 0.3;

/// Which rows the benchmark runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Every method at five mesh sizes, T3 and T6.
    Full,
    /// The two smallest meshes (for CI).
    Quick,
    /// `auto` alone, T3, at the three sizes the floor is judged at (about
    /// 75k, 612k and 1.19M DOF), then the two-cylinder row (about 1.18M).
    Floor,
}

/// Runs the benchmark. Each timing is the median of `repeat` runs (the floor
/// too), since run-to-run spread on this machine reaches ±30 % for the same
/// factorization.
pub fn run(mode: Mode, repeat: usize, mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let repeat = repeat.max(1);
    // Node spacing at the contact (T6 elements are twice as long): ~3k to ~1M DOF.
    let sizes: &[f64] = match mode {
        Mode::Quick => &[0.16, 0.04],
        Mode::Full => &[0.16, 0.04, 0.01, 0.0025, 0.0017],
        Mode::Floor => &[0.0058, 0.00186, 0.00132],
    };
    let elements: &[&str] = if mode == Mode::Floor { &["t3"] } else { &["t3", "t6"] };
    let e_star = 200.0 / (1.0 - 0.09);
    let mut rows = Vec::new();
    let limits = Limits::default();
    for &element in elements {
        // The finest T6 mesh would be ~1.8M DOF; T3 alone reaches ~1.2M.
        let sizes = if element == "t6" && sizes.len() > 4 {
            &sizes[..4]
        } else {
            sizes
        };
        for &h in sizes {
            // T6 has twice the node density per element: compare at equal node spacing.
            let h_el = if element == "t6" { 2.0 * h } else { h };
            let req0 = hertz_request(h_el, element, "auto");
            let scene0 = Scene::try_new(&serde_json::from_value(req0).unwrap(), &limits).unwrap();
            let floor = Floor::median(&scene0, repeat);
            let n_free = floor.dofs;
            // (method, formulation, ζ); the full-system variants refactor per
            // iteration, so they run only where that takes seconds, not minutes.
            let mut runs: Vec<(MethodName, Formulation, Option<f64>)> = if mode == Mode::Floor {
                vec![(MethodName::Auto, Formulation::Condensed, None)]
            } else {
                vec![
                    (MethodName::ActiveSet, Formulation::Condensed, None),
                    (MethodName::InteriorPoint, Formulation::Condensed, None),
                    (MethodName::AugmentedLagrangian, Formulation::Condensed, Some(1e-5)),
                    (MethodName::Penalty, Formulation::Condensed, Some(1e-4)),
                    (MethodName::Penalty, Formulation::Condensed, Some(1e-6)),
                    (MethodName::Penalty, Formulation::Condensed, Some(1e-8)),
                    (MethodName::Barrier, Formulation::Condensed, Some(1e-4)),
                    (MethodName::Barrier, Formulation::Condensed, Some(1e-6)),
                ]
            };
            // T6 contact rows are mortar rows over three nodes, which the full
            // formulation does not take (it rotates one node per row).
            let nodal = element == "t3" && mode != Mode::Floor;
            if nodal && n_free < 200_000 {
                runs.push((MethodName::ActiveSet, Formulation::Full, None));
            }
            if nodal && n_free < 40_000 {
                runs.push((MethodName::InteriorPoint, Formulation::Full, None));
            }
            // The same scene with Coulomb friction (μ = FRICTION), one step: its
            // cost against the frictionless active set's row above it; on the
            // full system too where its rows are nodal (a factorization and
            // a GMRES run per iteration).
            let mut frictional = Vec::new();
            if mode != Mode::Floor {
                frictional.push((MethodName::ActiveSet, Formulation::Condensed, None, true));
            }
            if nodal && n_free < 200_000 {
                frictional.push((MethodName::ActiveSet, Formulation::Full, None, true));
            }
            let all = runs.into_iter().map(|(m, f, z)| (m, f, z, false)).chain(frictional);
            for (method, formulation, zeta, with_friction) in all {
                let name = serde_json::to_value(method).unwrap().as_str().unwrap().to_string();
                let mut req = hertz_request(h_el, element, &name);
                // The methods are timed alone: the error estimate's coarser
                // second solve (default on, about a quarter of the time) is
                // measured by `contact-bench --convergence` (effectivity.csv).
                let mut settings = json!({ "formulation": formulation, "estimate": false });
                if with_friction {
                    req["contacts"][0]["friction"] = json!({ "coefficient": FRICTION });
                }
                match (method, zeta) {
                    (MethodName::Barrier, Some(z)) => settings["barrier"] = json!(z),
                    (_, Some(z)) => settings["penalty"] = json!(z),
                    _ => {}
                }
                req["settings"] = settings;
                let r = median_solve(&req, repeat, &limits);
                let method = match zeta {
                    _ if with_friction => format!("{}+friction(μ={FRICTION})", r.method),
                    Some(z) => format!("{}(ζ={z:.0e})", r.method),
                    None => r.method.to_string(),
                };
                let element = if element == "t3" { "T3" } else { "T6" };
                let row = Row::of(
                    "hertz_block",
                    element,
                    h_el,
                    method,
                    &r,
                    &floor,
                    hertz_errors(&r, 8.0, e_star),
                );
                progress(&row);
                rows.push(row);
            }
        }
    }
    if mode == Mode::Floor {
        let row = two_cylinders(repeat, &limits);
        progress(&row);
        rows.push(row);
    }
    rows
}

/// Medians of `repeat` floor runs (`floor_time`), as the solve's rows are.
struct Floor {
    factor: f64,
    solve: f64,
    dofs: usize,
}

impl Floor {
    fn median(scene: &Scene, repeat: usize) -> Self {
        let floors: Vec<(f64, f64, usize)> = (0..repeat).map(|_| floor_time(scene)).collect();
        let median = |f: &dyn Fn(&(f64, f64, usize)) -> f64| {
            let mut v: Vec<f64> = floors.iter().map(f).collect();
            v.sort_by(f64::total_cmp);
            v[repeat / 2]
        };
        Floor {
            factor: median(&|f| f.0),
            solve: median(&|f| f.1),
            dofs: floors[0].2,
        }
    }
}

/// The run of median total time among `repeat` solves of `req`.
fn median_solve(req: &serde_json::Value, repeat: usize, limits: &Limits) -> Report {
    let mut replies: Vec<Report> = (0..repeat)
        .map(|_| match crate::run::solve(req, limits) {
            Ok(r) => r,
            Err(e) => panic!("benchmark scene rejected: {e:?}"),
        })
        .collect();
    replies.sort_by(|a, b| a.timings.total.total_cmp(&b.timings.total));
    replies.swap_remove(repeat / 2)
}

impl Row {
    /// A row of a solve's report against its floor; `errors` are
    /// (half-width, peak, L2) against the closed form.
    fn of(
        scene: &str,
        element: &'static str,
        h_min: f64,
        method: String,
        r: &Report,
        floor: &Floor,
        errors: (f64, f64, f64),
    ) -> Row {
        Row {
            scene: scene.into(),
            element,
            h_min,
            dofs: r.size.dofs,
            candidates: r.size.candidates,
            method,
            iterations: r.iterations,
            t_mesh: r.timings.mesh,
            t_assembly: r.timings.assembly,
            t_factorization: r.timings.factorization,
            t_condensation: r.timings.condensation,
            t_contact: r.timings.contact_solve,
            t_post: r.timings.post,
            t_total: r.timings.total,
            t_floor: floor.factor + floor.solve,
            t_floor_factor: floor.factor,
            t_floor_solve: floor.solve,
            err_half_width: errors.0,
            err_peak: errors.1,
            err_l2: errors.2,
            max_penetration: r.pairs[0].max_penetration,
            certificate: r.certificate.worst(),
            status: r.status.as_str().to_string(),
            threads: contact_core::linalg::threads(),
        }
    }
}

/// Mesh sizes of `two_bodies_cylinders.json` times this: about 1.18M DOF
/// (T3, both bodies), the size at which the two-body contact rows took 4.9 s
/// of a 22 s run before they found facing edges through a tree.
const TWO_CYLINDERS_REFINE: f64 = 0.257;

/// The floor's two-body row: `auto` on the two-cylinder example refined by
/// `TWO_CYLINDERS_REFINE`, against the floor of its K (both bodies) and
/// two-body Hertz (1/R = 1/8 + 1/12, 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2).
fn two_cylinders(repeat: usize, limits: &Limits) -> Row {
    let mut req: serde_json::Value =
        serde_json::from_str(include_str!("../../../proto/examples/two_bodies_cylinders.json"))
            .expect("example is JSON");
    for b in 0..2 {
        let mesh = &mut req["bodies"][b]["mesh"]["half_disk"];
        for size in ["/size", "/grading/h_min"] {
            let v = mesh.pointer_mut(size).expect("the example's half-disk mesh");
            *v = json!(v.as_f64().expect("a number") * TWO_CYLINDERS_REFINE);
        }
    }
    req["method"] = json!("auto");
    req["settings"] = json!({ "formulation": Formulation::Condensed, "estimate": false });
    // The upper body's, rounded off the product's last bits for the table.
    let h_min = req["bodies"][0]["mesh"]["half_disk"]["grading"]["h_min"]
        .as_f64()
        .map(|h| (h * 1e12).round() / 1e12)
        .expect("a number");
    let scene = Scene::try_new(&serde_json::from_value(req.clone()).unwrap(), limits).unwrap();
    let floor = Floor::median(&scene, repeat);
    let r = median_solve(&req, repeat, limits);
    let e_star = 1.0 / ((1.0 - 0.3 * 0.3) / 200.0 + (1.0 - 0.25 * 0.25) / 100.0);
    let errors = hertz_errors(&r, 1.0 / (1.0 / 8.0 + 1.0 / 12.0), e_star);
    let method = r.method.to_string();
    Row::of("two_cylinders", "T3", h_min, method, &r, &floor, errors)
}
