//! Linear algebra kernels: sparse Cholesky, the condensed contact operator on its
//! factor, small dense kernels.

pub mod calibrate;
pub mod cholesky;
pub mod cost;
pub mod dense;
pub mod gmres;
mod numeric;
pub mod rate;
pub mod schur;
pub mod sparse;
mod symbolic;

pub use cholesky::{Cholesky, LinalgError};

use std::sync::atomic::{AtomicUsize, Ordering};

/// Threads of the factorization, the sweeps and the dense kernels. One by
/// default: the service runs requests side by side on the machine's cores, so
/// a request's own parallelism would only compete with the next request's.
static THREADS: AtomicUsize = AtomicUsize::new(1);

/// Sets the threads every later factorization and solve uses (process-wide;
/// the benchmark's 2-thread rows and a single-user CLI run).
pub fn set_threads(n: usize) {
    THREADS.store(n.max(1), Ordering::Relaxed);
}

/// The threads `set_threads` chose.
pub fn threads() -> usize {
    THREADS.load(Ordering::Relaxed)
}

/// The parallelism `set_threads` chose.
pub fn par() -> faer::Par {
    match THREADS.load(Ordering::Relaxed) {
        1 => faer::Par::Seq,
        n => faer::Par::rayon(n),
    }
}
