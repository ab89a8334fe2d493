//! This machine's speed at the numeric factorization, against the reference
//! machine `FactorCost::predicted_secs` was fitted on: the prediction times
//! `scale()`, learned from the factorizations completed here and, in the
//! service, measured once at start-up (`linalg::calibrate`).
//!
//! Uncalibrated, the prediction was 1.7–1.9× too low on a loaded 2-core
//! machine (8.5 s predicted, 16.1 s real at 2M DOF), so a time limit the
//! prediction called enough was overrun. The scale follows the load: each
//! completed factorization long enough to measure moves it halfway (in
//! log) toward its own real / predicted ratio.

use std::sync::atomic::{AtomicU64, Ordering};

use faer::sparse::{SparseColMat, Triplet};

/// f64 bits of the current scale (1.0 before anything is measured).
static SCALE: AtomicU64 = AtomicU64::new(0x3FF0_0000_0000_0000);

/// Factorizations predicted under this on the reference machine are not
/// learned from: their time is dominated by the timer, page faults and
/// caches rather than by the multiply–adds and stored values the model counts.
const SHORTEST_LEARNED_S: f64 = 0.02;

/// Weight of the newest factorization in the (log) average.
const WEIGHT: f64 = 0.5;

/// Real seconds per predicted reference second on this machine.
pub fn scale() -> f64 {
    f64::from_bits(SCALE.load(Ordering::Relaxed))
}

/// Sets the scale (a start-up measurement, or a test).
pub fn set_scale(s: f64) {
    if s.is_finite() && s > 0.0 {
        SCALE.store(s.to_bits(), Ordering::Relaxed);
    }
}

/// One completed numeric factorization predicted at `reference` seconds on
/// the reference machine (`FactorCost::reference_secs`) that took `secs`.
pub(crate) fn learn(reference: f64, secs: f64) {
    if reference < SHORTEST_LEARNED_S || !secs.is_finite() || secs <= 0.0 {
        return;
    }
    // Concurrent learners may overwrite each other's step: each is an estimate.
    set_scale(blend(scale(), secs / reference));
}

/// The scale moved by `WEIGHT` toward `ratio`, in log (a ratio of 2 and one
/// of 1/2 cancel).
fn blend(old: f64, ratio: f64) -> f64 {
    (old.ln() * (1.0 - WEIGHT) + ratio.ln() * WEIGHT).exp()
}

/// The stiffness pattern of a uniform T3 grid of `nx` × `ny` nodes, 2 DOF each
/// (every cell cut along the same diagonal: each node coupled to 6
/// neighbours, full 2×2 blocks), with SPD values: (graph Laplacian + I) ⊗
/// [[2, 1], [1, 2]]. The lower triangle, as the factorization takes it.
pub fn grid_stiffness(nx: usize, ny: usize) -> SparseColMat<usize, f64> {
    let node = |i: usize, j: usize| i + nx * j;
    let mut t = Vec::with_capacity(nx * ny * 4 * 8);
    let mut degree = vec![0.0f64; nx * ny];
    let mut couple = |a: usize, b: usize, t: &mut Vec<Triplet<usize, usize, f64>>| {
        let (a, b) = (a.max(b), a.min(b));
        degree[a] += 1.0;
        degree[b] += 1.0;
        for (p, q, v) in [(0, 0, -2.0), (1, 0, -1.0), (0, 1, -1.0), (1, 1, -2.0)] {
            let (r, c) = (2 * a + p, 2 * b + q);
            if r >= c {
                t.push(Triplet::new(r, c, v));
            }
        }
    };
    for j in 0..ny {
        for i in 0..nx {
            if i + 1 < nx {
                couple(node(i, j), node(i + 1, j), &mut t);
            }
            if j + 1 < ny {
                couple(node(i, j), node(i, j + 1), &mut t);
            }
            if i + 1 < nx && j + 1 < ny {
                couple(node(i, j), node(i + 1, j + 1), &mut t);
            }
        }
    }
    for (k, d) in degree.iter().enumerate() {
        let d = d + 1.0;
        t.push(Triplet::new(2 * k, 2 * k, 2.0 * d));
        t.push(Triplet::new(2 * k + 1, 2 * k, d));
        t.push(Triplet::new(2 * k + 1, 2 * k + 1, 2.0 * d));
    }
    let n = 2 * nx * ny;
    SparseColMat::try_new_from_triplets(n, n, &t).expect("valid triplets")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::cholesky::Cholesky;

    /// Halfway in log: from 2 toward 8 is 4 (the geometric mean), toward
    /// 1/2 is 1, and a factorization as fast as predicted leaves it.
    #[test]
    fn the_scale_moves_halfway_in_log() {
        assert!((blend(2.0, 8.0) - 4.0).abs() < 1e-12);
        assert!((blend(2.0, 0.5) - 1.0).abs() < 1e-12);
        assert!((blend(3.0, 3.0) - 3.0).abs() < 1e-12);
    }

    /// The grid is what its doc says: 2 DOF per node, each node's 2×2 block
    /// coupled to itself and (interior) 6 neighbours, so an interior column
    /// of the full matrix holds 14 entries; the lower triangle stores the
    /// diagonal block's lower half, and it factors (SPD).
    #[test]
    fn the_grid_has_the_t3_pattern_and_factors() {
        let (nx, ny) = (7, 5);
        let k = grid_stiffness(nx, ny);
        assert_eq!(k.nrows(), 2 * nx * ny);
        // Full-matrix entries: 4 per node pair coupled (both ways) + 4 per node;
        // coupled pairs: horizontal, vertical and diagonal edges of the grid.
        let edges = (nx - 1) * ny + nx * (ny - 1) + (nx - 1) * (ny - 1);
        let full = 8 * edges + 4 * nx * ny;
        // Lower triangle: half the off-diagonal blocks, 3 of 4 in the diagonal ones.
        assert_eq!(k.compute_nnz(), 4 * edges + 3 * nx * ny);
        assert!(full > k.compute_nnz());
        assert!(Cholesky::try_new(&k).is_ok());
    }
}
