//! The core's progress reports as wire messages (`contact_proto::progress`).

use contact_core::progress::{Progress, ProgressStage};
use contact_proto::progress::{self as p, ProgressMessage};

/// The message of one progress report; `request_id` is the service's.
pub fn message(r: &Progress, request_id: Option<&str>) -> ProgressMessage {
    ProgressMessage {
        stage: stage(r.stage),
        elapsed: r.elapsed,
        done: r.done,
        total: r.total,
        iteration: r.iteration,
        residual: r.residual,
        round: r.round,
        request_id: request_id.map(String::from),
    }
}

/// Exhaustive, so a stage added in the core and not on the wire does not compile.
pub fn stage(s: ProgressStage) -> p::ProgressStage {
    match s {
        ProgressStage::Mesh => p::ProgressStage::Mesh,
        ProgressStage::Assembly => p::ProgressStage::Assembly,
        ProgressStage::Factorization => p::ProgressStage::Factorization,
        ProgressStage::Condensation => p::ProgressStage::Condensation,
        ProgressStage::ContactSolve => p::ProgressStage::ContactSolve,
        ProgressStage::Post => p::ProgressStage::Post,
        ProgressStage::Estimate => p::ProgressStage::Estimate,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each stage's wire spelling is the core's `as_str`.
    #[test]
    fn stages_are_spelled_as_the_core_does() {
        for &s in ProgressStage::ALL {
            assert_eq!(serde_json::to_value(stage(s)).unwrap(), s.as_str());
        }
    }
}
