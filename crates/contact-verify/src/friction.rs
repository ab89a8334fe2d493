//! Friction under mesh refinement (`contact-bench --convergence`, after the
//! frictionless tables): the Cattaneo–Mindlin stick zone.
//!
//! The scene is the roller of `signorini_roller_on_flat.json` (half-disk
//! R = 8, E = 200) at ν = 0.499, so that the normal–tangential coupling of an
//! elastic body on a rigid floor (second Dundurs constant
//! β = (1 − 2ν) / (2(1 − ν)) = 0.001) is negligible and Cattaneo–Mindlin's
//! similar-materials theory applies; μ = 0.5. Its flat top is moved down by
//! 0.05 (P ≈ 4.9), then sideways by 0.025 (Q/μP ≈ 0.49) in a second load
//! path step. The stick zone is |x| < c with c = a √(1 − Q/(μP)), a Hertz's
//! half-width at the reply's P. The measured c takes the run of sticking
//! points and puts each end midway between its last sticking point and the
//! next one (the transition lies there to ± half a spacing), so its error is
//! bounded by half the node spacing plus the solution's own error.
//!
//! Three levels, node spacing s = 0.015, 0.0075, 0.00375 at the contact (T3
//! at h_min = s, T6 at 2s: equal spacing, a T6 element is twice as long).
//! At ν = 0.499 T3 locks (its stiffness is the incompressibility constraint's,
//! not the material's) while T6 switches to the P2–P0 element: the T3 rows
//! show what locking does to a frictional answer.
//!
//! Then the same stick zone between two elastic bodies
//! (`friction_two_cylinders_cattaneo_mindlin.json`): two identical half-disks
//! (R = 8, E = 200, ν = 0.3, T6, mortar rows), whose common material makes
//! β = 0 at any ν, the upper one pressed by 0.08 and shifted by 0.035
//! (Q/μP ≈ 0.53); a from Hertz for two cylinders (R/2, E* = E / (2(1 − ν²))).
//! Three levels h = 0.02, 0.01, 0.005 on the upper surface (the rows'
//! corners h apart), 1.3 h on the lower one.

use serde_json::{json, Value};

use contact_core::solution::report::{FrictionState, Report};
use contact_core::Limits;

pub const MU: f64 = 0.5;
const RADIUS: f64 = 8.0;
const E: f64 = 200.0;
const NU: f64 = 0.499;
/// The sideways shift of the second step.
const SHIFT: f64 = 0.025;
/// Node spacing at the contact of the coarsest level.
const S0: f64 = 0.015;
pub const LEVELS: usize = 3;

/// The roller at element size `h_min` (contact zone) and `element`.
pub fn roller_request(h_min: f64, element: &str) -> Value {
    let mut r: Value = serde_json::from_str(include_str!("../../../proto/examples/signorini_roller_on_flat.json"))
        .expect("the example is JSON");
    let b = &mut r["bodies"][0];
    b["material"]["poisson_ratio"] = json!(NU);
    let mesh = &mut b["mesh"]["half_disk"];
    mesh["element"] = json!(element);
    mesh["grading"] = json!({"h_min": h_min, "ratio": 1.2, "extent": 0.6});
    // The sideways motion as its own support, scaled alone by the path.
    b["supports"] = json!([{"edges": "flat", "uy": -0.05}, {"edges": "flat", "ux": 1.0}]);
    r["contacts"][0]["friction"] = json!({"coefficient": MU});
    r["load_path"] = json!([
        {"loads": {"/bodies/0/supports/1": 0.0}},
        {"loads": {"/bodies/0/supports/1": SHIFT}}
    ]);
    r["description"] = json!(
        "convergence: elastic roller (nu = 0.499) pressed 0.05 onto a rigid floor, mu = 0.5, then \
        shifted 0.025 sideways"
    );
    r
}

/// The two identical cylinders of the example at element size `h` on the
/// upper surface (1.3 h on the lower one).
pub fn two_cylinders_request(h: f64) -> Value {
    let mut r: Value = serde_json::from_str(include_str!(
        "../../../proto/examples/friction_two_cylinders_cattaneo_mindlin.json"
    ))
    .expect("the example is JSON");
    for (b, hb) in [(0, h), (1, 1.3 * h)] {
        r["bodies"][b]["mesh"]["half_disk"]["grading"]["h_min"] = json!(hb);
    }
    r["load_path"] = json!([
        {"loads": {"/bodies/0/supports/1": 0.0}},
        {"loads": {"/bodies/0/supports/1": TWO_BODY_SHIFT}}
    ]);
    r["description"] = json!(
        "convergence: two identical cylinders (nu = 0.3, beta = 0) pressed by 0.08, mu = 0.5, \
        then the upper one shifted 0.035 sideways"
    );
    r
}

/// The sideways shift of the two cylinders' second step.
const TWO_BODY_SHIFT: f64 = 0.035;
/// The two cylinders' Poisson ratio (as in the example).
const TWO_BODY_NU: f64 = 0.3;
/// Element size at the contact of the two cylinders' coarsest level.
const TWO_BODY_H0: f64 = 0.02;

#[derive(Debug, Clone)]
pub struct Row {
    /// `roller_cattaneo_mindlin` or `two_cylinders_cattaneo_mindlin`.
    pub scene: &'static str,
    pub element: &'static str,
    pub h_min: f64,
    pub dofs: usize,
    /// Q/(μP) of the last step.
    pub ratio: f64,
    /// Measured and Cattaneo–Mindlin stick half-widths, over a.
    pub c_over_a: f64,
    pub exact_over_a: f64,
    /// c / c_exact − 1.
    pub err_c: f64,
    pub order: Option<f64>,
    /// Half the node spacing at the stick zone's ends, over c_exact: the
    /// resolution of the measured ends.
    pub resolution: f64,
    /// Active-set iterations of each step.
    pub iterations: Vec<usize>,
    pub t_total: f64,
    pub status: String,
}

impl Row {
    pub const HEADER: &'static str =
        "scene,element,h_min,dofs,q_over_mu_p,c_over_a,cm_over_a,err_c,order,resolution,iterations_per_step,t_total,\
            status";

    pub fn csv(&self) -> String {
        format!(
            "{},{},{},{},{:.5},{:.5},{:.5},{:.4e},{},{:.4e},{},{:.6},{}",
            self.scene,
            self.element,
            self.h_min,
            self.dofs,
            self.ratio,
            self.c_over_a,
            self.exact_over_a,
            self.err_c,
            self.order.map_or(String::new(), |o| format!("{o:.3}")),
            self.resolution,
            self.iterations_joined(" "),
            self.t_total,
            self.status
        )
    }

    fn iterations_joined(&self, sep: &str) -> String {
        self.iterations
            .iter()
            .map(|i| i.to_string())
            .collect::<Vec<_>>()
            .join(sep)
    }

    pub fn table_header() -> String {
        format!(
            "{:<13} {:<3} {:>9} {:>8} {:>7} {:>7} {:>7} {:>10} {:>6} {:>9} {:>8} {:>8} {}",
            "scene",
            "el",
            "h_min",
            "dofs",
            "Q/μP",
            "c/a",
            "CM c/a",
            "err_c",
            "order",
            "half_sp",
            "it/step",
            "time s",
            "status"
        )
    }

    pub fn table_line(&self) -> String {
        format!(
            "{:<13} {:<3} {:>9.2e} {:>8} {:>7.4} {:>7.4} {:>7.4} {:>+10.3e} {:>6} {:>9.2e} {:>8} {:>8.3} {}",
            self.scene.trim_end_matches("_cattaneo_mindlin"),
            self.element,
            self.h_min,
            self.dofs,
            self.ratio,
            self.c_over_a,
            self.exact_over_a,
            self.err_c,
            self.order.map_or("-".to_string(), |o| format!("{o:.2}")),
            self.resolution,
            self.iterations_joined("/"),
            self.t_total,
            self.status
        )
    }
}

/// The stick half-width of a pair's points and the node spacing at its ends:
/// the run of sticking points, each end midway to the next point out.
fn stick_half_width(r: &Report) -> Option<(f64, f64)> {
    let pair = r.pairs.first()?;
    let states = &pair.friction.as_ref()?.points;
    let x: Vec<f64> = pair.points.iter().map(|p| p.x).collect();
    let stick: Vec<usize> = (0..x.len())
        .filter(|&i| states[i].state == FrictionState::Stick)
        .collect();
    let (lo, hi) = (*stick.first()?, *stick.last()?);
    let left = if lo > 0 { 0.5 * (x[lo] + x[lo - 1]) } else { x[lo] };
    let right = if hi + 1 < x.len() {
        0.5 * (x[hi] + x[hi + 1])
    } else {
        x[hi]
    };
    let spacing = |i: usize, j: usize| if j < x.len() { (x[j] - x[i]).abs() } else { 0.0 };
    let gap = spacing(lo.saturating_sub(1), lo).max(spacing(hi, hi + 1));
    Some((0.5 * (right - left), gap))
}

/// The roller in T3 and T6 over the levels, then the two cylinders.
pub fn run(mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let mut rows = run_elements(&["t3", "t6"], &mut progress);
    rows.extend(run_two_cylinders(progress));
    rows
}

/// The two cylinders over the levels.
pub fn run_two_cylinders(mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let limits = Limits::default();
    let e_star = E / (2.0 * (1.0 - TWO_BODY_NU * TWO_BODY_NU));
    let mut rows = Vec::new();
    let mut prev: Option<f64> = None;
    for k in 0..LEVELS {
        let h = TWO_BODY_H0 / 2f64.powi(k as i32);
        let r = match crate::run::solve(&two_cylinders_request(h), &limits) {
            Ok(r) => r,
            Err(e) => panic!("two-body friction convergence scene rejected: {e:?}"),
        };
        let row = measure(
            "two_cylinders_cattaneo_mindlin",
            "T6",
            h,
            &r,
            (0.5 * RADIUS, e_star),
            prev,
        );
        progress(&row);
        prev = Some(row.err_c);
        rows.push(row);
    }
    rows
}

/// The row of a solved scene: its stick half-width against
/// Cattaneo–Mindlin's for Hertz's a of (radius, E*) at the reply's P.
fn measure(
    scene: &'static str,
    element: &'static str,
    h: f64,
    r: &Report,
    (radius, e_star): (f64, f64),
    prev: Option<f64>,
) -> Row {
    let (p, q) = (r.resultant.fy, -r.resultant.fx);
    let ratio = q / (MU * p);
    let (a, _) = crate::reference::hertz(p, radius, e_star);
    let exact = a * (1.0 - ratio).max(0.0).sqrt();
    let (c, gap) = stick_half_width(r).unwrap_or((0.0, 0.0));
    let err = c / exact - 1.0;
    Row {
        scene,
        element,
        h_min: h,
        dofs: r.size.dofs,
        ratio,
        c_over_a: c / a,
        exact_over_a: exact / a,
        err_c: err,
        order: prev.and_then(|e: f64| (e != 0.0 && err != 0.0).then(|| (e.abs() / err.abs()).ln() / 2f64.ln())),
        resolution: 0.5 * gap / exact,
        iterations: r
            .steps
            .as_ref()
            .map_or_else(|| vec![r.iterations], |st| st.iter().map(|s| s.iterations).collect()),
        t_total: r.timings.total,
        status: r.status.as_str().to_string(),
    }
}

/// The given elements over the levels.
pub fn run_elements(elements: &[&str], mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let limits = Limits::default();
    let e_star = E / (1.0 - NU * NU);
    let mut rows = Vec::new();
    for &element in elements {
        let mut prev: Option<f64> = None;
        for k in 0..LEVELS {
            let s = S0 / 2f64.powi(k as i32);
            let h = if element == "t6" { 2.0 * s } else { s };
            let req = roller_request(h, element);
            let r = match crate::run::solve(&req, &limits) {
                Ok(r) => r,
                Err(e) => panic!("friction convergence scene rejected: {e:?}"),
            };
            let el = if element == "t3" { "T3" } else { "T6" };
            let row = measure("roller_cattaneo_mindlin", el, h, &r, (RADIUS, e_star), prev);
            progress(&row);
            prev = Some(row.err_c);
            rows.push(row);
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    /// T6 converges to Cattaneo–Mindlin: at every level the stick half-width
    /// is within its resolution (half the node spacing at the zone's ends)
    /// plus 1 % (the half-space idealisation at a/R = 0.06 and β = 0.001:
    /// measured a within 0.2 % of Hertz), and the step's active set stops
    /// on a certified state. Measured: 4.8, 2.7 and 0.57 % against
    /// resolutions of 4.2, 2.1 and 1.05 %.
    #[test]
    fn t6_stick_zone_converges_to_cattaneo_mindlin() {
        let rows = super::run_elements(&["t6"], |_| {});
        assert_eq!(rows.len(), super::LEVELS);
        for r in &rows {
            assert_eq!(r.status, "solved", "{r:?}");
            assert!(r.err_c.abs() <= r.resolution + 0.01, "{r:?}");
        }
        assert!(rows[2].err_c.abs() < rows[0].err_c.abs(), "{rows:?}");
    }

    /// Between two identical cylinders (β = 0) the stick half-width is within
    /// its resolution plus 1 % at every level (a/R = 0.05: the half-space
    /// idealisation's error is near 0.3 %), every step certified.
    #[test]
    fn two_cylinders_stick_zone_within_resolution() {
        let rows = super::run_two_cylinders(|r| println!("{}", r.table_line()));
        assert_eq!(rows.len(), super::LEVELS);
        for r in &rows {
            assert_eq!(r.status, "solved", "{r:?}");
            assert!(r.err_c.abs() <= r.resolution + 0.01, "{r:?}");
        }
    }
}
