//! A 3D refinement round that cannot fit is not built (`adapt::solid`): its
//! factor's bytes are predicted from the last round's before the next mesh
//! is made, and a round past the service's memory per request
//! (`Limits::memory_bytes`, 1500 bytes per DOF of `max_dofs`) stops the
//! rounds with `max_dofs`, as 2D's do, after the first round. Before this
//! prediction the round was made, assembled and analysed, and only then
//! refused by its factor's check (stop `size_limit`; the example's ball took
//! 185 s and 1.68 GB so).
//!
//! Hertz's ball (`contact_verify::solid_ball`) at a coarse `h_min`, with a
//! target far below what its first round reads, so that the rounds would go
//! on: a generated box (regraded rounds) and the same mesh given inline
//! (every tetrahedron split in eight).

use contact_core::mesh3d::refine::refined_nodes;
use contact_core::outcome::StopReason;
use contact_core::{solve_solid, Limits};
use contact_verify::solid_ball::{given, problem, request};
use serde_json::{json, Value};

/// `req` with a pressure target no coarse ball meets (its first round reads
/// 0.2–0.4), solved under `limits`: the rounds' stop, and the DOFs of each.
fn rounds(mut req: Value, limits: &Limits) -> (StopReason, Vec<usize>, contact_core::solid::answer::SolidAnswer) {
    req["settings"] = json!({"accuracy": {"pressure_l2": 1e-3}});
    let answer = solve_solid(&problem(&req, limits), limits).expect("the first round solves");
    let r = answer.refinement.clone().expect("rounds");
    (r.stopped, r.rounds.iter().map(|r| r.dofs).collect(), answer)
}

#[test]
fn a_round_whose_factor_cannot_fit_is_not_built() {
    // The memory a limit of `max_dofs` gives a request (`Limits::memory_bytes`).
    let per_dof = Limits::default().memory_bytes() / Limits::default().max_dofs as f64;
    for req in [request("t4", 0.4), given("t4", 0.4)] {
        let alone = solve_solid(&problem(&req, &Limits::default()), &Limits::default()).expect("solves");
        // Room for the first round's factor with 20 % to spare: any finer
        // round grows it by more (a regraded round's smallest step,
        // `STEP_MAX` = 0.75 on h_min, at least doubles the unknowns near
        // the patch). A given mesh's split round, 8 times the nodes, is
        // let within the DOF limit: its factor, predicted 8² = 64 times the first
        // (`FACTOR_GROWTH`), is what cannot fit.
        let split = problem(&req, &Limits::default()).mesh.map(|m| 3 * refined_nodes(&m));
        let max_dofs = split
            .unwrap_or(0)
            .max((1.2 * alone.factor_bytes / per_dof).ceil() as usize);
        assert!(
            max_dofs as f64 * per_dof < 8.0 * alone.factor_bytes,
            "the next factor cannot fit"
        );
        let limits = Limits {
            max_dofs,
            ..Default::default()
        };
        let (stopped, dofs, answer) = rounds(req, &limits);
        assert_eq!(
            stopped,
            StopReason::MaxDofs,
            "rounds {dofs:?} under max_dofs {max_dofs}"
        );
        // Stopped after the first round, which is the answer.
        assert_eq!(dofs, vec![alone.dofs]);
        assert_eq!(answer.dofs, alone.dofs);
        assert!(answer
            .warnings
            .iter()
            .any(|w| w.location == "/settings/accuracy" && w.message.contains("max_dofs")));
    }
}
