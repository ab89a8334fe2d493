//! Exact methods on the full (uncondensed) system, for comparison with the
//! condensed path: they refactor K at every active-set change.
//!
//! Active set: each candidate row n·u_i ≤ g_i acts on one coordinate after a
//! rotation of its node's DOFs to (n, t) (Q block-diagonal, K' = QᵀKQ, same
//! pattern as K); a single free DOF needs no rotation (row c·u_d ≤ g). An active
//! candidate prescribes its coordinate (u'_n = g / c) by replacing its row and
//! column with the identity — the pattern and so the symbolic factorization stay
//! the same; each iteration is one numeric factorization and one solve. The
//! reaction at the coordinate, −(K'u' − f')_n / c, is the contact force λ.
//! A ← {i : λ_i − k_i gap_i > 0} (k_i the coordinate's diagonal stiffness)
//! until A repeats.
//!
//! Interior point: Clarabel on min ½uᵀKu − fᵀu s.t. Bu + s = g, s ≥ 0 (its dual
//! z is λ), then the active-set iteration above from Clarabel's active set
//! (a crossover) for an exact answer.

use crate::outcome::MethodRan;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::Side;

use super::Solution;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::linalg::LinalgError;
use crate::scene::Settings;

/// K in coordinates where every candidate row acts on one coordinate.
pub(super) struct Rotated {
    /// K' = QᵀKQ, lower triangle.
    pub k: SparseColMat<usize, f64>,
    /// Per candidate: (constrained coordinate, coefficient c).
    pub coord: Vec<(usize, f64)>,
    /// Rotated node pairs (normal DOF, tangent DOF, nx, ny): the normal
    /// coordinate lives at the x DOF, the tangential one at the y DOF.
    pub pairs: Vec<(usize, usize, f64, f64)>,
    /// Diagonal of K' (stiffness of each coordinate).
    pub diag: Vec<f64>,
}

pub(super) fn rotate(k: &SparseColMat<usize, f64>, cons: &ConstraintSet) -> Rotated {
    let n = k.nrows();
    let mut spread: Vec<[(usize, f64); 2]> = (0..n).map(|a| [(a, 1.0), (usize::MAX, 0.0)]).collect();
    let mut coord = Vec::with_capacity(cons.len());
    let mut pairs = Vec::new();
    for c in &cons.candidates {
        match *c.row.as_slice() {
            [(dx, nx), (dy, ny)] => {
                // u_x = nx u'_n − ny u'_t, u_y = ny u'_n + nx u'_t: spread[a] lists (p, Q[a, p]).
                spread[dx] = [(dx, nx), (dy, -ny)];
                spread[dy] = [(dx, ny), (dy, nx)];
                pairs.push((dx, dy, nx, ny));
                coord.push((dx, 1.0));
            }
            [(d, cf)] => coord.push((d, cf)),
            _ => unreachable!("ConstraintSet::rows_are_nodal admits only rows of one node"),
        }
    }
    let sym = k.symbolic();
    let vals = k.val();
    let mut trips = Vec::with_capacity(4 * vals.len());
    let mut push = |a: usize, b: usize, v: f64| {
        for &(p, qap) in &spread[a] {
            for &(r, qbr) in &spread[b] {
                if p != usize::MAX && r != usize::MAX && p >= r && qap != 0.0 && qbr != 0.0 {
                    trips.push(Triplet::new(p, r, qap * v * qbr));
                }
            }
        }
    };
    for j in 0..n {
        let range = sym.col_ptr()[j]..sym.col_ptr()[j + 1];
        for (&i, &v) in sym.row_idx()[range.clone()].iter().zip(&vals[range]) {
            push(i, j, v);
            if i != j {
                push(j, i, v);
            }
        }
    }
    let k = SparseColMat::try_new_from_triplets(n, n, &trips).expect("rotated pattern is valid");
    let ks = k.symbolic();
    let diag = (0..n)
        .map(|j| {
            (ks.col_ptr()[j]..ks.col_ptr()[j + 1])
                .find(|&idx| ks.row_idx()[idx] == j)
                .map(|idx| k.val()[idx])
                .unwrap_or(1.0)
        })
        .collect();
    Rotated { k, coord, pairs, diag }
}

/// u = Q u' (or f' = Qᵀ f with `transpose`).
pub(super) fn apply_q(rot: &Rotated, x: &[f64], transpose: bool) -> Vec<f64> {
    let mut y = x.to_vec();
    for &(dn, dt, nx, ny) in &rot.pairs {
        let (a, b) = (x[dn], x[dt]);
        if transpose {
            y[dn] = nx * a + ny * b;
            y[dt] = -ny * a + nx * b;
        } else {
            y[dn] = nx * a - ny * b;
            y[dt] = ny * a + nx * b;
        }
    }
    y
}

/// K' with the coordinates `fixed` prescribes (finite entries) replaced by
/// the identity, and f' moved accordingly: the pattern, and so the symbolic
/// factorization, stay K''s.
pub(super) fn prescribed(
    k: &SparseColMat<usize, f64>,
    fixed: &[f64],
    f: &[f64],
) -> (SparseColMat<usize, f64>, Vec<f64>) {
    let n = k.nrows();
    let mut kk = k.clone();
    let mut rhs = f.to_vec();
    let sym = k.symbolic();
    let (col_ptr, row_idx) = (sym.col_ptr(), sym.row_idx());
    let vals = kk.val_mut();
    for j in 0..n {
        for idx in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[idx];
            let (fi, fj) = (fixed[i].is_finite(), fixed[j].is_finite());
            if i == j {
                if fi {
                    vals[idx] = 1.0;
                }
            } else if fi || fj {
                let v = vals[idx];
                if fj && !fi {
                    rhs[i] -= v * fixed[j];
                }
                if fi && !fj {
                    rhs[j] -= v * fixed[i];
                }
                vals[idx] = 0.0;
            }
        }
    }
    for d in 0..n {
        if fixed[d].is_finite() {
            rhs[d] = fixed[d];
        }
    }
    (kk, rhs)
}

struct ActiveSetRun {
    u: Vec<f64>,
    lambda: Vec<f64>,
    iterations: usize,
    converged: bool,
}

fn active_set_full(
    rot: &Rotated,
    f: &[f64],
    g: &[f64],
    s: &Settings,
    mut active: Vec<bool>,
) -> Result<ActiveSetRun, CoreError> {
    let n = rot.k.nrows();
    let m = g.len();
    let fp = apply_q(rot, f, true);
    let symbolic =
        SymbolicLlt::try_new(rot.k.symbolic(), Side::Lower).map_err(|e| LinalgError::Faer(format!("{e:?}")))?;
    // Every iteration refactors: each must fit in the time left.
    let cost = crate::linalg::cholesky::FactorCost::predict(&rot.k)?;
    let diag = &rot.diag;
    let mut seen: Vec<Vec<bool>> = Vec::new();
    let mut last = None;
    for it in 1..=s.max_iterations {
        crate::cancel::check(crate::outcome::ProgressStage::ContactSolve)?;
        let mut fixed = vec![f64::NAN; n];
        for i in 0..m {
            if active[i] {
                let (d, c) = rot.coord[i];
                fixed[d] = g[i] / c;
            }
        }
        let (kk, rhs) = prescribed(&rot.k, &fixed, &fp);
        cost.fits_in_time_left()?;
        let llt = Llt::try_new_with_symbolic(symbolic.clone(), kk.as_ref(), Side::Lower)
            .map_err(|_| LinalgError::NotPositiveDefinite)?;
        let b = faer::Col::<f64>::from_fn(n, |i| rhs[i]);
        let x = faer::linalg::solvers::Solve::solve(&llt, &b);
        let up: Vec<f64> = (0..n).map(|i| x[i]).collect();
        let kup = crate::linalg::sparse::sym_lower_matvec(&rot.k, &up);
        let mut lambda = vec![0.0; m];
        let mut next = vec![false; m];
        for i in 0..m {
            let (d, c) = rot.coord[i];
            if active[i] {
                lambda[i] = -(kup[d] - fp[d]) / c;
            }
            let gap = g[i] - c * up[d];
            // Stiffness of the constraint c·u_d in force per length: diag / c².
            next[i] = lambda[i] - diag[d] / (c * c) * gap > 0.0;
        }
        let done = next == active;
        last = Some(ActiveSetRun {
            u: apply_q(rot, &up, false),
            lambda,
            iterations: it,
            converged: done,
        });
        if done || seen.contains(&next) {
            break;
        }
        seen.push(active.clone());
        active = next;
    }
    Ok(last.expect("at least one iteration"))
}

fn solution(run: ActiveSetRun, name: MethodRan, t: std::time::Instant, extra_iterations: usize) -> Solution {
    let in_contact = run.lambda.iter().map(|&l| l > 0.0).collect();
    Solution {
        refinements: 0,
        u: run.u,
        lambda: run.lambda,
        beta: Vec::new(),
        in_contact,
        iterations: run.iterations + extra_iterations,
        converged: run.converged,
        breakdown: false,
        method: name,
        exact: true,
        t_contact: t.elapsed().as_secs_f64(),
        fallback: None,
    }
}

pub fn solve_active_set(
    k: &SparseColMat<usize, f64>,
    f: &[f64],
    cons: &ConstraintSet,
    g: &[f64],
    s: &Settings,
) -> Result<Solution, CoreError> {
    let t = std::time::Instant::now();
    let rot = rotate(k, cons);
    // From no contact: the first iteration is the unconstrained solve.
    let run = active_set_full(&rot, f, g, s, vec![false; g.len()])?;
    Ok(solution(run, MethodRan::ActiveSetFull, t, 0))
}

pub fn solve_interior_point(
    k: &SparseColMat<usize, f64>,
    f: &[f64],
    cons: &ConstraintSet,
    g: &[f64],
    s: &Settings,
) -> Result<Solution, CoreError> {
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT};
    let t = std::time::Instant::now();
    let n = k.nrows();
    let m = g.len();
    // Upper triangle in CSC = our lower triangle in CSR: transpose by counting.
    let sym = k.symbolic();
    let mut counts = vec![0usize; n + 1];
    for &i in sym.row_idx() {
        counts[i + 1] += 1;
    }
    for i in 0..n {
        counts[i + 1] += counts[i];
    }
    let mut colptr = counts.clone();
    let mut rowval = vec![0usize; sym.row_idx().len()];
    let mut nzval = vec![0.0; sym.row_idx().len()];
    for j in 0..n {
        for idx in sym.col_ptr()[j]..sym.col_ptr()[j + 1] {
            let i = sym.row_idx()[idx];
            let dst = colptr[i];
            rowval[dst] = j;
            nzval[dst] = k.val()[idx];
            colptr[i] += 1;
        }
    }
    let p = CscMatrix::new(n, n, counts, rowval, nzval);
    let qv: Vec<f64> = f.iter().map(|v| -v).collect();
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for (i, c) in cons.candidates.iter().enumerate() {
        for &(d, v) in &c.row {
            rows.push(i);
            cols.push(d);
            vals.push(v);
        }
    }
    let a = CscMatrix::new_from_triplets(m, n, rows, cols, vals);
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(s.max_iterations as u32)
        .time_limit(crate::cancel::remaining_secs())
        .build()
        .expect("static clarabel settings are valid");
    let mut solver = DefaultSolver::new(&p, &qv, &a, g, &[NonnegativeConeT(m)], settings)
        .map_err(|e| LinalgError::Clarabel(format!("{e:?}")))?;
    solver.solve();
    let sol = &solver.solution;
    let ipm_iterations = sol.iterations as usize;
    // Crossover: finish with the exact active-set iteration from Clarabel's active set.
    let rot = rotate(k, cons);
    // Active where the force's own displacement (z / stiffness) exceeds the slack (gap).
    let start: Vec<bool> = (0..m)
        .map(|i| {
            let (d, c) = rot.coord[i];
            sol.z[i] * c * c / rot.diag[d] > sol.s[i]
        })
        .collect();
    let run = active_set_full(&rot, f, g, s, start)?;
    Ok(solution(run, MethodRan::InteriorPointFull, t, ipm_iterations))
}
