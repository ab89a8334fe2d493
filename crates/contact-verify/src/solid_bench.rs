//! The 3D rows of the benchmark: Hertz's ball on a rigid flat as the example
//! `solid_ball_on_flat.json` poses it (a quarter of a 10 mm cube, rollers on
//! x = 0 and y = 0, its face z = 0 carrying the ball's paraboloid gap
//! r²/2R, R = 50, P = 6154 N: a = 1.000 mm, p0 = 2938 MPa), graded to
//! `h_min` within 1.2 mm of the apex, T4 and T10 at four sizes each. Each
//! row times the route's stages (assembly with the contact rows; the
//! nested-dissection ordering, the factorization and the condensation;
//! the contact solve) and measures a (the fit of p² against r² over the
//! points in contact, which Hertz's p makes a straight line) and p0 (the
//! peak) against Hertz. Through the door and the route the service takes
//! (`solid_scene`, `solid::door::admit`, `solve_solid`), in process, on
//! `--threads` threads (1 by default, the service's). The harness returns rows; the CLI prints and writes them.

use crate::reference::{edge_fit, hertz_sphere};
use crate::solid_ball::{problem, request};
use contact_core::solid::answer::SolidAnswer;
use contact_core::Limits;

/// h_min at the apex per element [mm]: T10's quadratic cells are as fine as
/// T4's of half their size, and T10 at 0.1 mm would factor into 4.1 GB
/// (measured: refused by the default limits), so T10 stops at 0.2.
pub const T4_LEVELS: [f64; 4] = [0.4, 0.2, 0.1, 0.05];
pub const T10_LEVELS: [f64; 4] = [0.8, 0.4, 0.28, 0.2];

#[derive(Debug, Clone, Default)]
pub struct SolidRow {
    pub element: &'static str,
    pub h_min: f64,
    pub dofs: usize,
    pub candidates: usize,
    pub active: usize,
    pub iterations: usize,
    pub t_mesh: f64,
    /// Assembly of K and the loads, with the contact rows.
    pub t_assembly: f64,
    /// Ordering (nested dissection), symbolic and numeric factorization and
    /// the condensation W = B K⁻¹ Bᵀ.
    pub t_factorization: f64,
    pub t_contact: f64,
    pub t_total: f64,
    /// a_h / a − 1 and p0_h / p0 − 1 against Hertz for the whole ball's load.
    pub err_a: f64,
    pub err_p0: f64,
    pub certificate: f64,
    pub status: String,
}

impl SolidRow {
    pub const HEADER: &'static str = "scene,element,h_min,dofs,candidates,active,iterations,t_mesh,t_assembly,\
        t_factorization,t_contact,t_total,err_a,err_p0,certificate,status";

    /// Each column of the table: its title, width and cell (the CSV's
    /// columns less the scene, the mesh time and the status).
    fn cells(&self) -> [(&'static str, usize, String); 13] {
        [
            ("element", 7, format!("{:<7}", self.element)),
            ("h_min", 6, self.h_min.to_string()),
            ("dofs", 8, self.dofs.to_string()),
            ("cand", 5, self.candidates.to_string()),
            ("act", 5, self.active.to_string()),
            ("it", 4, self.iterations.to_string()),
            ("assembly", 8, format!("{:.3}", self.t_assembly)),
            ("factor", 8, format!("{:.3}", self.t_factorization)),
            ("contact", 8, format!("{:.4}", self.t_contact)),
            ("total", 8, format!("{:.3}", self.t_total)),
            ("err_a", 9, format!("{:+.2e}", self.err_a)),
            ("err_p0", 9, format!("{:+.2e}", self.err_p0)),
            ("cert", 8, format!("{:.1e}", self.certificate)),
        ]
    }

    pub fn csv(&self) -> String {
        format!(
            "hertz_ball,{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.3e},{:.3e},{:.1e},{}",
            self.element,
            self.h_min,
            self.dofs,
            self.candidates,
            self.active,
            self.iterations,
            self.t_mesh,
            self.t_assembly,
            self.t_factorization,
            self.t_contact,
            self.t_total,
            self.err_a,
            self.err_p0,
            self.certificate,
            self.status
        )
    }

    pub fn table_header() -> String {
        let titles = Self::cells(&Self::default()).map(|(t, w, _)| format!("{t:>w$}"));
        titles.join(" ")
    }

    pub fn table_line(&self) -> String {
        self.cells().map(|(_, w, c)| format!("{c:>w$}")).join(" ")
    }
}

/// The example's (load, radius, E, ν): the quarter's top pressure times its
/// area, four times (the two symmetry planes).
fn ball_data(req: &serde_json::Value) -> (f64, f64, f64, f64) {
    let s = &req["solid"];
    let num = |p: &str| s.pointer(p).and_then(|v| v.as_f64()).expect("the example's number");
    let area = num("/body/mesh/box/lengths/0") * num("/body/mesh/box/lengths/1");
    (
        4.0 * area * num("/body/tractions/0/pressure"),
        num("/contact/initial_gap/paraboloid/radius"),
        num("/body/material/youngs_modulus"),
        num("/body/material/poisson_ratio"),
    )
}

/// Solves `req` (a solid's) as the service does, in process.
pub fn solve(req: &serde_json::Value, limits: &Limits) -> SolidAnswer {
    contact_core::solve_solid(&problem(req, limits), limits)
        .unwrap_or_else(|e| panic!("the bench's ball was refused: {e:?}"))
}

/// a from the points in contact (`reference::edge_fit`).
pub fn fitted_radius(a: &SolidAnswer) -> f64 {
    let pressed: Vec<(f64, f64)> = a
        .report
        .points
        .iter()
        .filter(|q| q.in_contact)
        .map(|q| (q.position[0].powi(2) + q.position[1].powi(2), q.pressure.powi(2)))
        .collect();
    edge_fit(&pressed)
}

/// The rows: T4 then T10, coarse to fine (`quick`: the two coarsest of each),
/// each the median-total of `repeat` solves.
pub fn run(quick: bool, repeat: usize, mut progress: impl FnMut(&SolidRow)) -> Vec<SolidRow> {
    let limits = Limits::default();
    let (load, radius, e, nu) = ball_data(&request("t10", 0.2));
    let (a, p0) = hertz_sphere(load, radius, e / (1.0 - nu * nu));
    let take = if quick { 2 } else { 4 };
    let mut rows = Vec::new();
    for (element, levels) in [("t4", T4_LEVELS), ("t10", T10_LEVELS)] {
        for &h in &levels[..take] {
            let req = request(element, h);
            let mut answers: Vec<SolidAnswer> = (0..repeat.max(1)).map(|_| solve(&req, &limits)).collect();
            answers.sort_by(|x, y| x.timings.total.total_cmp(&y.timings.total));
            let r = answers.swap_remove(answers.len() / 2);
            let peak = r.report.patches.iter().map(|p| p.peak_pressure).fold(0.0, f64::max);
            let t = r.timings;
            let row = SolidRow {
                element,
                h_min: h,
                dofs: r.dofs,
                candidates: r.candidates,
                active: r.active,
                iterations: r.report.iterations,
                t_mesh: t.mesh,
                t_assembly: t.assembly,
                t_factorization: t.factorization + t.condensation,
                t_contact: t.contact_solve,
                t_total: t.total,
                err_a: fitted_radius(&r) / a - 1.0,
                err_p0: peak / p0 - 1.0,
                certificate: r.report.certificate.worst(),
                status: r.status.as_str().to_string(),
            };
            progress(&row);
            rows.push(row);
        }
    }
    rows
}
