//! The condensed path: one sparse Cholesky of K with the contact DOFs ordered
//! last, W from the trailing block of the factor (see `linalg::cholesky`), an
//! LCP solve on the candidates, then u = K⁻¹(f − Bᵀλ).

use std::time::Instant;

use faer::Mat;

use super::{LcpResult, Problem, Solution};
use crate::error::CoreError;
use crate::linalg::{dense, Cholesky};

pub fn solve_condensed(
    p: &Problem,
    name: &'static str,
    exact: bool,
    lcp: &dyn Fn(&Mat<f64>, &[f64]) -> LcpResult,
) -> Result<Solution, CoreError> {
    let t0 = Instant::now();
    let cdofs = p.cons.dofs();
    let chol = Cholesky::try_new(p.k, &cdofs)?;
    let u0 = chol.solve(p.f);
    let t_factorization = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let m = p.cons.len();
    let mut pos = std::collections::HashMap::with_capacity(cdofs.len());
    for (k, &d) in cdofs.iter().enumerate() {
        pos.insert(d, k);
    }
    let mut bt = Mat::<f64>::zeros(cdofs.len(), m);
    for (i, c) in p.cons.candidates.iter().enumerate() {
        for &(d, v) in &c.row {
            bt[(pos[&d], i)] = v;
        }
    }
    let w = dense::gram_of_lower_solve(&chol.trailing_factor(), bt);
    let bu0 = p.cons.apply(&u0);
    let q: Vec<f64> = p.cons.candidates.iter().zip(&bu0).map(|(c, b)| c.g - b).collect();
    let t_condensation = t1.elapsed().as_secs_f64();

    let t2 = Instant::now();
    let res = lcp(&w, &q);
    let t_contact = t2.elapsed().as_secs_f64();

    // u = K⁻¹ (f − Bᵀ λ)
    let mut rhs = p.f.to_vec();
    let neg: Vec<f64> = res.lambda.iter().map(|l| -l).collect();
    p.cons.apply_transpose_into(&neg, &mut rhs);
    let u = chol.solve(&rhs);
    Ok(Solution {
        u,
        lambda: res.lambda,
        iterations: res.iterations,
        converged: res.converged,
        method: name,
        exact,
        t_factorization,
        t_condensation,
        t_contact,
    })
}
