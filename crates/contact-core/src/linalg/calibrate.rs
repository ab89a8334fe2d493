//! This machine's factorization speed measured once (the service does it at
//! start-up): a factorization of a known grid against its prediction sets
//! `rate::scale`. Apart from `rate`, which the factorization itself reads
//! and teaches, so that `rate` needs no factorization of its own.

use super::cholesky::{Cholesky, SymbolicFactor};
use super::rate::{grid_stiffness, scale, set_scale};

/// Measures the scale on a 100k-DOF grid (about 0.1 s of factorization on
/// the reference machine), twice, keeping the second (the first pays the
/// page faults of fresh memory), and sets it. Returns the scale.
pub fn calibrate() -> f64 {
    let k = grid_stiffness(250, 200);
    for _ in 0..2 {
        let analysis = std::sync::Arc::new(SymbolicFactor::try_new(&k).expect("SPD grid"));
        let started = std::time::Instant::now();
        let before = scale();
        // Without learning: the measurement replaces what was known.
        set_scale(1.0);
        let ran = Cholesky::with_symbolic(analysis.clone(), &k);
        let secs = started.elapsed().as_secs_f64();
        set_scale(before);
        if ran.is_ok() {
            set_scale(secs / analysis.cost().reference_secs());
        }
    }
    scale()
}
