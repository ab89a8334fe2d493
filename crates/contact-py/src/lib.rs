//! `contact_client._contact`: the solver in the Python process.
//!
//! `solve` answers a request's bytes exactly as the service does (the same
//! `contact::wire::solve_bytes`, without the service's request id and time
//! cap), and hands the solve's progress to a Python callable as the service
//! publishes it; `summary` is the CLI's `--summary` text of a reply; `cli`
//! runs the `contact` command line, which the package installs as its
//! `contact` script. The GIL is released while the solver runs, so other
//! Python threads go on.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use contact::proto::{ErrorCode, ErrorReply, SolveReply};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Shortest time between two iteration messages, as the service thins them
/// (`contact::service::progress`): stage messages and reports always go out.
const MIN_ITERATION_INTERVAL: Duration = Duration::from_millis(50);

/// (True, reply JSON) or (False, error JSON) for the request `payload`.
///
/// `progress`, when given, is called on the solving thread (holding the GIL
/// only for the call) with each progress message as a dict `{stage, elapsed,
/// done, total, iteration?, residual?}`, the fields the service publishes. An
/// exception it raises stops further calls and is raised after the solve.
#[pyfunction]
#[pyo3(signature = (payload, progress=None))]
fn solve(py: Python<'_>, payload: &[u8], progress: Option<Py<PyAny>>) -> PyResult<(bool, String)> {
    let payload = payload.to_vec();
    let failed: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let answer = py.detach(|| {
        let _sink = progress.map(|callback| install(callback, failed.clone()));
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
    });
    if let Some(e) = failed.lock().unwrap_or_else(|e| e.into_inner()).take() {
        return Err(e);
    }
    Ok(answer)
}

/// A progress sink on this thread that calls `callback` (see `solve`).
fn install(callback: Py<PyAny>, failed: Arc<Mutex<Option<PyErr>>>) -> contact::progress::Sink {
    let mut last_iteration = Instant::now() - MIN_ITERATION_INTERVAL;
    contact::progress::Sink::install(move |p| {
        let mut first_error = failed.lock().unwrap_or_else(|e| e.into_inner());
        if first_error.is_some() {
            return;
        }
        if p.iteration.is_some() {
            if last_iteration.elapsed() < MIN_ITERATION_INTERVAL {
                return;
            }
            last_iteration = Instant::now();
        }
        Python::attach(|py| {
            let call = || -> PyResult<()> {
                let msg = PyDict::new(py);
                msg.set_item("stage", p.stage.as_str())?;
                msg.set_item("elapsed", p.elapsed)?;
                msg.set_item("done", p.done)?;
                msg.set_item("total", p.total)?;
                if let Some(k) = p.iteration {
                    msg.set_item("iteration", k)?;
                }
                if let Some(r) = p.residual {
                    msg.set_item("residual", r)?;
                }
                callback.call1(py, (msg,))?;
                Ok(())
            };
            if let Err(e) = call() {
                *first_error = Some(e);
            }
        });
    })
}

/// The `contact solve --summary` text of a reply (its JSON), or None when the
/// JSON is not a reply this solver's version reads (e.g. a newer service's).
#[pyfunction]
fn summary(reply: &str) -> Option<String> {
    serde_json::from_str::<SolveReply>(reply)
        .ok()
        .map(|r| contact::summary::reply(&r))
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
    m.add_function(wrap_pyfunction!(summary, m)?)?;
    m.add_function(wrap_pyfunction!(cli, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}

fn json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string(v).unwrap_or_default()
}
