//! What a solve costs, for the rounds' and the companions' predictions.

use crate::solution::report::Report;

/// A solve's time grows like its unknowns to this power: the Hertz example
/// took 0.080, 0.335 and 1.713 s at 30k, 104k and 391k DOF (exponent 1.19).
pub(super) const TIME_GROWTH: f64 = 1.2;

/// Seconds of the report's own solve, its estimate left out.
pub(super) fn solve_seconds(report: &Report) -> f64 {
    (report.timings.total - report.timings.estimate).max(0.0)
}
