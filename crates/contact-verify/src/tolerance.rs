//! Time to a tolerance on the disk on a flat: the first fixed mesh level of
//! the convergence suite whose true error meets it (found by running the
//! levels in turn, each timed on its own), against `settings.accuracy` from
//! a coarse start (one request, timed whole: its rounds and estimates),
//! beside the final mesh's own solve (`t_single`: the stages of the last
//! round's solve, its estimate left out).
//!
//! The true error is that of the field the reply describes
//! (`accuracy::described`, what `pressure_l2` estimates) against the disk's
//! stored overkill table (`overkill`: T6 at 3.7M DOF), at the same prescribed
//! displacement; `err_nodal` is the nodal values' beside it.

use contact_core::scene::Limits;
use contact_core::solution::accuracy::described_l2;
use contact_core::solution::report::Report;
use serde_json::json;

use crate::convergence::disk_request;

/// Targets of the table (relative L2 error of the described pressure).
pub const TOLERANCES: [f64; 2] = [0.005, 0.003];
/// The adaptive runs' coarse start: 6 element edges across the half-zone.
pub const START_H: f64 = 0.02;

#[derive(Debug, Clone)]
pub struct Row {
    pub element: &'static str,
    pub tolerance: f64,
    /// `fixed` (the levels h0 / 2^k of the convergence suite) or `adaptive`.
    pub mode: &'static str,
    pub dofs: usize,
    /// Levels run (fixed) or refinement rounds (adaptive).
    pub solves: usize,
    /// Seconds of the solve that met the tolerance (fixed: that level alone;
    /// adaptive: the whole request).
    pub t_total: f64,
    /// Seconds to get there (fixed: every level run until then).
    pub t_cumulative: f64,
    /// Seconds of the final mesh's own solve (adaptive), or `t_total`.
    pub t_single: f64,
    /// The described field's relative L2 error (`described_error`).
    pub error: f64,
    /// The nodal values' relative L2 error (`error`).
    pub nodal: f64,
    /// The reply's own estimate (adaptive), or its two-level estimate (fixed).
    pub estimate: Option<f64>,
    pub reached: bool,
}

impl Row {
    pub const HEADER: &'static str =
        "element,tolerance,mode,dofs,solves,t_total,t_cumulative,t_single,err_described,err_nodal,estimate,reached";

    pub fn csv(&self) -> String {
        format!(
            "{},{},{},{},{},{:.6},{:.6},{:.6},{:.6e},{:.6e},{},{}",
            self.element,
            self.tolerance,
            self.mode,
            self.dofs,
            self.solves,
            self.t_total,
            self.t_cumulative,
            self.t_single,
            self.error,
            self.nodal,
            self.estimate.map_or(String::new(), |e| format!("{e:.6e}")),
            self.reached
        )
    }

    pub fn table_header() -> String {
        format!(
            "{:<4} {:>6} {:<8} {:>8} {:>6} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {}",
            "el",
            "tol",
            "mode",
            "dofs",
            "solves",
            "t[s]",
            "t_cum[s]",
            "t_single",
            "err_desc",
            "err_node",
            "estimate",
            "reached"
        )
    }

    pub fn table_line(&self) -> String {
        format!(
            "{:<4} {:>6} {:<8} {:>8} {:>6} {:>9.4} {:>9.4} {:>9.4} {:>8.3}% {:>8.3}% {:>9} {}",
            self.element,
            self.tolerance,
            self.mode,
            self.dofs,
            self.solves,
            self.t_total,
            self.t_cumulative,
            self.t_single,
            100.0 * self.error,
            100.0 * self.nodal,
            self.estimate.map_or("-".into(), |e| format!("{:.3}%", 100.0 * e)),
            self.reached
        )
    }
}

/// Nodal relative L2 error of a reply of the disk on a flat against its
/// overkill table.
pub fn error(r: &Report) -> f64 {
    crate::overkill::reference_error("disk_on_flat", r)
        .expect("the disk's stored reference")
        .l2
}

/// Relative L2 error of the pressure a reply of the disk on a flat
/// describes (`accuracy::described`) against its overkill table, along the
/// surface.
pub fn described_error(r: &Report) -> f64 {
    let table = crate::overkill::reference("disk_on_flat").expect("the disk's stored reference");
    let (num, _, den) = described_l2(&r.pairs[0], &|x, _| table.pressure(x), &|_, _| true);
    if den > 0.0 {
        (num / den).sqrt()
    } else {
        f64::INFINITY
    }
}

fn solve(req: &serde_json::Value) -> Report {
    match crate::run::solve(req, &Limits::default()) {
        Ok(r) => r,
        Err(e) => panic!("time-to-tolerance scene rejected: {e:?}"),
    }
}

/// The table: T3 and T6, each tolerance, fixed levels (up to `levels`) and
/// adaptive.
pub fn run(levels: usize, mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let mut rows = Vec::new();
    for element in ["t3", "t6"] {
        let label = if element == "t3" { "T3" } else { "T6" };
        for tol in TOLERANCES {
            // Fixed levels, coarse to fine, until one meets the tolerance.
            let mut cumulative = 0.0;
            let mut fixed = None;
            for k in 0..levels {
                let h = 0.0088 / 2f64.powi(k as i32) * if element == "t6" { 2.0 } else { 1.0 };
                let r = solve(&disk_request(h, element));
                // The level's own cost, without its estimate.
                let t = r.timings.total - r.timings.estimate;
                cumulative += t;
                let error = described_error(&r);
                let row = Row {
                    element: label,
                    tolerance: tol,
                    mode: "fixed",
                    dofs: r.size.dofs,
                    solves: k + 1,
                    t_total: t,
                    t_cumulative: cumulative,
                    t_single: t,
                    error,
                    nodal: self::error(&r),
                    estimate: r.pairs[0].accuracy.as_ref().and_then(|a| a.pressure_l2),
                    reached: error <= tol,
                };
                let done = row.reached;
                fixed = Some(row);
                if done {
                    break;
                }
            }
            if let Some(row) = fixed {
                progress(&row);
                rows.push(row);
            }
            let mut req = disk_request(START_H, element);
            req["settings"] = json!({"accuracy": {"pressure_l2": tol}});
            let r = solve(&req);
            let refinement = r.refinement.as_ref().expect("rounds reported");
            let error = described_error(&r);
            let row = Row {
                element: label,
                tolerance: tol,
                mode: "adaptive",
                dofs: r.size.dofs,
                solves: refinement.rounds.len(),
                t_total: r.timings.total,
                t_cumulative: r.timings.total,
                // The last round's own stages (the rounds before and every
                // estimate are counted in `estimate`).
                t_single: r.timings.total - r.timings.estimate,
                error,
                nodal: self::error(&r),
                estimate: r.pairs[0].accuracy.as_ref().and_then(|a| a.pressure_l2),
                reached: error <= tol,
            };
            progress(&row);
            rows.push(row);
        }
    }
    rows
}
