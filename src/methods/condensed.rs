//! The condensed path: one sparse Cholesky of K with the contact DOFs ordered
//! last, W from the trailing block of the factor (see `linalg::cholesky`) —
//! both cacheable (`cache::Prepared`) — then per request an LCP solve on the
//! candidates and u = K⁻¹(f − Bᵀλ).

use std::time::Instant;

use faer::Mat;

use super::{LcpResult, Problem, Solution};
use crate::cache::Prepared;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::assembly::Stiffness;
use crate::linalg::{dense, Cholesky};
use std::sync::Arc;

/// Factorization and condensation: everything that does not depend on the loads or gaps.
pub fn prepare(stiffness: Arc<Stiffness>, cons: &ConstraintSet) -> Result<Prepared, CoreError> {
    let t0 = Instant::now();
    let cdofs = cons.dofs();
    let chol = Cholesky::try_new(&stiffness.k, &cdofs)?;
    let t_factorization = t0.elapsed().as_secs_f64();
    crate::cancel::check("factorization")?;
    crate::progress::stage("condensation");
    let t1 = Instant::now();
    let mut pos = std::collections::HashMap::with_capacity(cdofs.len());
    for (k, &d) in cdofs.iter().enumerate() {
        pos.insert(d, k);
    }
    let mut bt = Mat::<f64>::zeros(cdofs.len(), cons.len());
    for (i, c) in cons.candidates.iter().enumerate() {
        for &(d, v) in &c.row {
            bt[(pos[&d], i)] = v;
        }
    }
    let w = dense::gram_of_lower_solve(&chol.trailing_factor(), bt);
    Ok(Prepared {
        pivot_ratio: chol.pivot_ratio(),
        stiffness,
        chol,
        w,
        t_factorization,
        t_condensation: t1.elapsed().as_secs_f64(),
    })
}

/// q = g − B K⁻¹ f, the LCP, then u = K⁻¹ (f − Bᵀλ): two solves with the prepared factor.
pub fn solve_condensed(
    p: &Problem,
    name: &'static str,
    exact: bool,
    lcp: &dyn Fn(&Mat<f64>, &[f64]) -> LcpResult,
) -> Result<Solution, CoreError> {
    let none = Mat::<f64>::zeros(p.cons.len(), 0);
    let pb = super::PunchBlock { c: &none, rhs: &[] };
    solve_condensed_mixed(p, &pb, name, exact, &|w, q| (lcp(w, q), Vec::new()))
}

/// As `solve_condensed`, with load-controlled punch motions β_F: a mixed LCP
/// (equilibrium of the punches as equality constraints).
pub fn solve_condensed_mixed(
    p: &Problem,
    pb: &super::PunchBlock,
    name: &'static str,
    exact: bool,
    mlcp: super::MixedSolver,
) -> Result<Solution, CoreError> {
    let t = Instant::now();
    let op = p.op;
    let (u0, r0) = solve_refined(op, p.f);
    let bu0 = p.cons.apply(&u0);
    let q: Vec<f64> = p.cons.candidates.iter().zip(&bu0).map(|(c, b)| c.g - b).collect();
    // Foundations add their compliance to the bodies' (per request: it is not
    // part of the cached operator).
    let with_foundation;
    let w = match p.compliance {
        Some(c) => {
            with_foundation = &op.w + c;
            &with_foundation
        }
        None => &op.w,
    };
    let (res, beta) = mlcp(w, &q);
    let wl = dense::matvec(w, &res.lambda);
    let in_contact = (0..q.len())
        .map(|i| {
            let cb: f64 = (0..beta.len()).map(|j| pb.c[(i, j)] * beta[j]).sum();
            res.lambda[i] > 0.0 && res.lambda[i] * w[(i, i)] > wl[i] + q[i] + cb
        })
        .collect();
    let mut rhs = p.f.to_vec();
    let neg: Vec<f64> = res.lambda.iter().map(|l| -l).collect();
    p.cons.apply_transpose_into(&neg, &mut rhs);
    let (u, r1) = solve_refined(op, &rhs);
    Ok(Solution {
        refinements: r0 + r1,
        u,
        lambda: res.lambda,
        beta,
        in_contact,
        iterations: res.iterations,
        converged: res.converged,
        method: name,
        exact,
        t_contact: t.elapsed().as_secs_f64(),
    })
}

/// Largest relative residual a solve may leave before it is refined: well
/// above the round-off floor of the residual itself (about 1e-12 measured on
/// the 75k-DOF Hertz example), so that only a poorly conditioned K triggers it.
const REFINE_ABOVE: f64 = 1e-10;

/// K⁻¹ b from the factor, with up to three steps of iterative refinement when
/// the residual b − K x is large relative to b and K x (an ill-conditioned K:
/// nearly incompressible material, extreme stiffness ratios or aspect ratios).
/// Returns x and the number of refinement steps taken.
fn solve_refined(op: &Prepared, b: &[f64]) -> (Vec<f64>, usize) {
    let mut x = op.chol.solve(b);
    let inf = |v: &[f64]| v.iter().fold(0.0f64, |a, y| a.max(y.abs()));
    let scale = inf(b);
    for step in 0..3 {
        let kx = crate::linalg::sparse::sym_lower_matvec(&op.stiffness.k, &x);
        let r: Vec<f64> = b.iter().zip(&kx).map(|(bi, ki)| bi - ki).collect();
        let large = inf(&r) > REFINE_ABOVE * scale.max(inf(&kx));
        if !large {
            return (x, step);
        }
        let dx = op.chol.solve(&r);
        x.iter_mut().zip(&dx).for_each(|(a, d)| *a += d);
    }
    (x, 3)
}
