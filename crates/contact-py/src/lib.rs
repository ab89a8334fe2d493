//! `contact_client._contact`: the solver in the Python process.
//!
//! `solve` answers a request's bytes exactly as the service does (the same
//! `contact::wire::solve_bytes`, without the service's request id and time
//! cap); `cli` runs the `contact` command line, which the package installs
//! as its `contact` script. The GIL is released while the solver runs, so
//! other Python threads go on.

use std::panic::{catch_unwind, AssertUnwindSafe};

use contact::proto::{ErrorCode, ErrorReply};
use pyo3::prelude::*;

/// (True, reply JSON) or (False, error JSON) for the request `payload`.
#[pyfunction]
fn solve(py: Python<'_>, payload: &[u8]) -> (bool, String) {
    let payload = payload.to_vec();
    py.detach(move || {
        let limits = contact::Limits::default();
        let answer = catch_unwind(AssertUnwindSafe(|| contact::solve_bytes(&payload, &limits)));
        match answer {
            Ok(Ok(reply)) => (true, json(&reply)),
            Ok(Err(error)) => (false, json(&error)),
            // A panic is a defect of ours: answered as the service answers it.
            Err(_) => (
                false,
                json(
                    &ErrorReply::new(
                        ErrorCode::InternalError,
                        "the solver failed unexpectedly (a defect: please report the request)",
                        "",
                    )
                    .with_client_id_of(&payload),
                ),
            ),
        }
    })
}

/// Runs the `contact` command line with `args` (the program name first);
/// returns its exit code.
#[pyfunction]
fn cli(py: Python<'_>, args: Vec<String>) -> u8 {
    py.detach(move || contact::cli::main(args))
}

/// The solver's version.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _contact(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(cli, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}

fn json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string(v).unwrap_or_default()
}
