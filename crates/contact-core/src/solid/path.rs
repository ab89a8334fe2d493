//! A load path on a solid: each step's loads and prescribed values
//! (`StepLoads`, from the step's scaled supports, face loads and body force)
//! and the `Operator` that solves every step, its balance judged per step.
//! Frictionless contact of a linear elastic body is path-independent (the
//! LCP of a step has no term from the step before), so each step is its own
//! LCP on the one factor of K and the one W (`signorini`).

use super::dofs::dof_map;
use super::obstacle::ObstacleRows;
use super::signorini::{compatible, motion_loads, prepare_checked, Operator, StepLoads};
use super::{loads, SolidBody};
use crate::error::CoreError;
use crate::scene::solid::SolidLoads;

/// The operator of `body` against the rows for a load path whose steps'
/// supports, face loads and body force are `steps`: as `prepare_within`,
/// with each step's loads made and checked for balance before the
/// factorization (a path's steps are not multiples of one load, so every
/// step is judged, not every sign), a step that fails refused at
/// `/load_path/<i>`. The operator is made on the first step's supports:
/// only the steps are solved, so the request's own prescribed values need
/// not agree where two supports meet (every step shares their sets). Each
/// step's loads are made again when it is solved (`step_loads`,
/// O(elements)) rather than kept: 100 steps of a million-DOF body would
/// hold 1.6 GB of them.
pub fn prepare_path(
    body: &SolidBody,
    rows: &ObstacleRows,
    steps: &[SolidLoads],
    max_bytes: f64,
) -> Result<Operator, CoreError> {
    let Some(first) = steps.first() else {
        return Err(CoreError::invalid(
            crate::error::InvalidKind::Request,
            "/load_path",
            "a load path has at least one step",
        ));
    };
    let first = step_body(body, first);
    // Its conflicts at the step's pointer, before the operator reads them.
    let loads0 = step_loads(&first, rows).map_err(|e| at_step(e, 0))?;
    prepare_checked(&first, rows, max_bytes, |c, fields, _| {
        compatible(c, &motion_loads(fields, &loads0.f_ext, 1.0)).map_err(|e| at_step(e, 0))?;
        for (i, s) in steps.iter().enumerate().skip(1) {
            let l = step_loads(&step_body(body, s), rows).map_err(|e| at_step(e, i))?;
            compatible(c, &motion_loads(fields, &l.f_ext, 1.0)).map_err(|e| at_step(e, i))?;
        }
        Ok(())
    })
}

/// `body` with a step's supports, face loads and body force.
pub fn step_body<'a>(body: &SolidBody<'a>, step: &SolidLoads) -> SolidBody<'a> {
    SolidBody {
        supports: step.supports.clone(),
        loads: step.loads.clone(),
        body_force: step.body_force,
        ..body.clone()
    }
}

/// A refusal of step `i`'s loads (conflicting prescribed values where two
/// supports meet, or loads no contact balances), at the step's pointer.
pub fn at_step(e: CoreError, i: usize) -> CoreError {
    match e {
        CoreError::Invalid {
            kind, reason, loads, ..
        } => CoreError::Invalid {
            kind,
            path: format!("/load_path/{i}"),
            reason: format!("at load path step {i}: {reason}"),
            loads,
        },
        other => other,
    }
}

/// The loads of `body` (a load path step's supports, face loads and body
/// force on the operator's mesh) against the rows.
pub fn step_loads(body: &SolidBody, rows: &ObstacleRows) -> Result<StepLoads, CoreError> {
    let touching: Vec<usize> = rows.terms.iter().flatten().map(|t| t.0).collect();
    Ok(StepLoads {
        f_ext: loads::external(body)?,
        prescribed: dof_map(body, Some(&touching))?.prescribed,
    })
}
