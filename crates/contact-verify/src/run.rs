//! Requests built as JSON, solved in process: the core's report, not the
//! wire reply (the suites read the numbers, the service tests the wire).

use contact_core::error::{CoreError, InvalidKind};
use contact_core::solution::report::Report;
use contact_core::{Limits, Scene};
use contact_proto::SolveRequest;
use serde_json::Value;

/// Validates and solves `req`; a request that does not fit the schema is an
/// `invalid_request` as the service would call it.
pub fn solve(req: &Value, limits: &Limits) -> Result<Report, CoreError> {
    let req: SolveRequest =
        serde_json::from_value(req.clone()).map_err(|e| CoreError::invalid(InvalidKind::Request, "", e.to_string()))?;
    contact_core::solve(&Scene::try_new(&req, limits)?, limits, None)
}
