//! The condensed path: one sparse Cholesky of K in its fill-reducing order,
//! W = B K⁻¹ Bᵀ from the reach of the contact rows (see `linalg::schur`) —
//! both cacheable (`cache::Prepared`) — then per request an LCP solve on the
//! candidates and u = K⁻¹(f − Bᵀλ).

use crate::outcome::MethodRan;
use std::time::Instant;

use faer::Mat;

use super::{LcpResult, Problem, Solution};
use crate::cache::{OperatorCache, Prepared};
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::fem::assembly::Stiffness;
use crate::linalg::cholesky::{pattern_key, SymbolicFactor};
use crate::linalg::schur::Reach;
use crate::linalg::{dense, Cholesky};
use std::sync::Arc;

/// Factorization and condensation: everything that does not depend on the
/// loads or gaps. The ordering and symbolic analysis come from `cache` when it
/// holds one for this pattern (and go into it when not).
pub fn prepare(
    stiffness: Arc<Stiffness>,
    cons: &ConstraintSet,
    cache: Option<&OperatorCache>,
) -> Result<Prepared, CoreError> {
    let rows: Vec<&[(usize, f64)]> = cons.candidates.iter().map(|c| c.row.as_slice()).collect();
    prepare_rows(stiffness, &rows, cache)
}

/// `prepare` for any rows on the free DOFs (the frictional path condenses
/// the normal rows and the tangential ones together).
pub fn prepare_rows(
    stiffness: Arc<Stiffness>,
    rows: &[&[(usize, f64)]],
    cache: Option<&OperatorCache>,
) -> Result<Prepared, CoreError> {
    let t0 = Instant::now();
    let pattern = pattern_key(&stiffness.k);
    let symbolic = match cache.and_then(|c| c.get_symbolic(pattern)) {
        Some(s) => s,
        None => {
            let s = Arc::new(SymbolicFactor::try_new_keyed(&stiffness.k, pattern)?);
            if let Some(c) = cache {
                c.insert_symbolic(s.clone());
            }
            s
        }
    };
    prepare_on(stiffness, rows, symbolic, t0)
}

/// `prepare_rows` on a given analysis of K's pattern (its ordering the
/// caller's), `t0` when the preparation started.
pub fn prepare_on(
    stiffness: Arc<Stiffness>,
    rows: &[&[(usize, f64)]],
    symbolic: Arc<SymbolicFactor>,
    t0: Instant,
) -> Result<Prepared, CoreError> {
    let reach = Reach::new(&symbolic, rows);
    crate::observer::revise_factorization(
        t0.elapsed().as_secs_f64(),
        symbolic.cost().predicted_secs(),
        reach.flops(),
    );
    let chol = Arc::new(Cholesky::with_symbolic(symbolic, &stiffness.k)?);
    let t_factorization = t0.elapsed().as_secs_f64();
    crate::cancel::check(crate::outcome::ProgressStage::Factorization)?;
    crate::progress::stage(crate::outcome::ProgressStage::Condensation);
    condense_on(stiffness, chol, reach, None, t_factorization)
}

/// The factor of K with no row condensed yet, for a solve that chooses its
/// rows from the loads (`solve::screen`), which calls `condense_subset`.
pub fn prepare_factor(stiffness: Arc<Stiffness>, cache: Option<&OperatorCache>) -> Result<Prepared, CoreError> {
    let mut op = prepare_rows(stiffness, &[], cache)?;
    op.rows = Some(Vec::new());
    Ok(op)
}

/// W over the candidates `subset` (by index, increasing; None: every one)
/// on the factor of `op`: within the contact stage of a screened solve, so
/// it announces no stage of its own.
pub fn condense_subset(op: &Prepared, cons: &ConstraintSet, subset: Option<Vec<usize>>) -> Result<Prepared, CoreError> {
    let rows: Vec<&[(usize, f64)]> = match &subset {
        Some(s) => s.iter().map(|&i| cons.candidates[i].row.as_slice()).collect(),
        None => cons.candidates.iter().map(|c| c.row.as_slice()).collect(),
    };
    let reach = Reach::new(op.chol.analysis(), &rows);
    condense_on(op.stiffness.clone(), op.chol.clone(), reach, subset, op.t_factorization)
}

fn condense_on(
    stiffness: Arc<Stiffness>,
    chol: Arc<Cholesky>,
    reach: Reach,
    rows: Option<Vec<usize>>,
    t_factorization: f64,
) -> Result<Prepared, CoreError> {
    let t1 = Instant::now();
    let condensed = reach.condense(&chol)?;
    Ok(Prepared {
        pivot_ratio: chol.pivot_ratio(),
        stiffness,
        chol,
        condensed,
        rows,
        t_factorization,
        t_condensation: t1.elapsed().as_secs_f64(),
    })
}

/// q = g − B K⁻¹ f, the LCP, then u = K⁻¹ (f − Bᵀλ): one forward and one backward sweep of the prepared factor.
pub fn solve_condensed(
    p: &Problem,
    name: MethodRan,
    exact: bool,
    lcp: &dyn Fn(&Mat<f64>, &[f64]) -> LcpResult,
) -> Result<Solution, CoreError> {
    let pb = super::FreeBlock {
        cn: Mat::<f64>::zeros(p.cons.len(), 0),
        ct: Mat::<f64>::zeros(0, 0),
        rhs: Vec::new(),
        bodies: Vec::new(),
    };
    solve_condensed_mixed(p, &pb, name, exact, &|w, q| (lcp(w, q), Vec::new()))
}

/// As `solve_condensed`, with load-controlled punch motions β_F: a mixed LCP
/// (equilibrium of the punches as equality constraints).
///
/// One solve with K costs one forward and one backward sweep: y = L⁻¹ P f
/// before the LCP gives its right-hand side B K⁻¹ f = Xᵀ y, and after it
/// u = Pᵀ L⁻ᵀ (y − X λ), X = L⁻¹ P Bᵀ being kept from the condensation. A K
/// whose u leaves a residual above `REFINE_ABOVE` (ill-conditioned: nearly
/// incompressible, extreme stiffness or aspect ratios) is solved again on
/// the refined path, two refined solves with K.
pub fn solve_condensed_mixed(
    p: &Problem,
    pb: &super::FreeBlock,
    name: MethodRan,
    exact: bool,
    mlcp: super::MixedSolver,
) -> Result<Solution, CoreError> {
    let t = Instant::now();
    let op = p.op;
    let y = op.chol.forward(p.f);
    let bu0 = op.condensed.rows_of(&y);
    let swept = |lambda: &[f64]| -> Option<(Vec<f64>, usize)> {
        let (rhs, size) = load_less_contact(p, lambda);
        let mut yz = y.clone();
        op.condensed.subtract(lambda, &mut yz);
        let u = op.chol.backward(&yz);
        let (r, scale) = residual(op, &rhs, &u, size);
        (inf_norm(&r) <= REFINE_ABOVE * scale).then_some((u, 0))
    };
    if let Some(sol) = contact_stage(p, pb, name, exact, mlcp, &bu0, 0, &swept, t) {
        return Ok(sol);
    }
    let (u0, r0) = solve_refined(op, p.f, inf_norm(p.f));
    let refined = |lambda: &[f64]| Some(displacements(p, lambda));
    let bu0 = p.cons.apply(&u0);
    Ok(contact_stage(p, pb, name, exact, mlcp, &bu0, r0, &refined, t).expect("the refined path always answers"))
}

/// u for the contact forces λ, and the refinement steps it took (None: the
/// residual calls for the refined path).
type Displacements<'a> = &'a dyn Fn(&[f64]) -> Option<(Vec<f64>, usize)>;

/// The LCP on q = g − B u0 (`bu0` = B u0), then the displacements and their refinement steps
/// (`solve_u`; None sends the caller to the refined path) and the refinement
/// of the contact forces.
#[allow(clippy::too_many_arguments)]
fn contact_stage(
    p: &Problem,
    pb: &super::FreeBlock,
    name: MethodRan,
    exact: bool,
    mlcp: super::MixedSolver,
    bu0: &[f64],
    refinements: usize,
    solve_u: Displacements,
    t: Instant,
) -> Option<Solution> {
    let q: Vec<f64> = p.cons.candidates.iter().zip(bu0).map(|(c, b)| c.g - b).collect();
    // Foundations add their compliance to the bodies' (per request: it is not
    // part of the cached operator).
    let with_foundation;
    let w = match p.compliance {
        Some(c) => {
            with_foundation = &p.op.condensed.w + c;
            &with_foundation
        }
        None => &p.op.condensed.w,
    };
    let (res, beta) = mlcp(w, &q);
    let wl = dense::matvec(w, &res.lambda);
    let in_contact = (0..q.len())
        .map(|i| {
            let cb: f64 = (0..beta.len()).map(|j| pb.cn[(i, j)] * beta[j]).sum();
            res.lambda[i] > 0.0 && res.lambda[i] * w[(i, i)] > wl[i] + q[i] + cb
        })
        .collect();
    let (mut u, r1) = solve_u(&res.lambda)?;
    let mut lambda = res.lambda;
    let mut beta = beta;
    let r2 = if exact && res.converged {
        refine_contact(p, pb, w, &mut u, &mut lambda, &mut beta)
    } else {
        0
    };
    Some(Solution {
        refinements: refinements + r1 + r2,
        u,
        lambda,
        beta,
        in_contact,
        iterations: res.iterations,
        converged: res.converged,
        breakdown: res.breakdown,
        method: name,
        exact,
        t_contact: t.elapsed().as_secs_f64(),
        fallback: None,
    })
}

/// f − Bᵀλ and the size of its terms: f and Bᵀλ nearly cancel on a body held
/// only by contact, so the round-off of the right-hand side is that of its
/// terms, not of their small difference.
fn load_less_contact(p: &Problem, lambda: &[f64]) -> (Vec<f64>, f64) {
    let mut btl = vec![0.0; p.f.len()];
    p.cons.apply_transpose_into(lambda, &mut btl);
    let rhs: Vec<f64> = p.f.iter().zip(&btl).map(|(f, b)| f - b).collect();
    let terms_size = inf_norm(p.f).max(inf_norm(&btl));
    (rhs, terms_size)
}

/// u = K⁻¹ (f − Bᵀλ), refined; returns u and the refinement steps.
fn displacements(p: &Problem, lambda: &[f64]) -> (Vec<f64>, usize) {
    let (rhs, terms_size) = load_less_contact(p, lambda);
    solve_refined(p.op, &rhs, terms_size)
}

/// b − K x and the scale it is judged against: the size of b's terms, of b
/// and of K x.
fn residual(op: &Prepared, b: &[f64], x: &[f64], size: f64) -> (Vec<f64>, f64) {
    let kx = crate::linalg::sparse::sym_lower_matvec(&op.stiffness.k, x);
    let r: Vec<f64> = b.iter().zip(&kx).map(|(bi, ki)| bi - ki).collect();
    let scale = size.max(inf_norm(b)).max(inf_norm(&kx));
    (r, scale)
}

/// The gaps g − B u + C β + F λ of the rows, from the sparse solution u.
fn gaps(p: &Problem, pb: &super::FreeBlock, u: &[f64], lambda: &[f64], beta: &[f64]) -> Vec<f64> {
    let bu = p.cons.apply(u);
    let opened = p.compliance.map(|f| dense::matvec(f, lambda));
    (0..bu.len())
        .map(|i| {
            let cb: f64 = (0..beta.len()).map(|j| pb.cn[(i, j)] * beta[j]).sum();
            p.cons.candidates[i].g - bu[i] + cb + opened.as_ref().map_or(0.0, |o| o[i])
        })
        .collect()
}

/// Iterative refinement of the contact forces on the final active set A.
///
/// The LCP is solved on the dense W, whose entries carry the round-off of the
/// compliance they were formed from; where the body's compliance is large
/// against its actual displacement (a thin strip held only by a foundation:
/// virtual supports, a bending compliance ~ (L/H)³) the gaps of the active
/// rows, recomputed from the sparse u, keep a residue far above the tolerance
/// (measured 1.5e-5 of the displacement on a 1/500 strip) although the forces
/// are right to 2e-6. Solving [W_AA C_A; C_Aᵀ 0] δ = −residual with the
/// residual from the sparse route converges while ε · cond(W_AA) < 1; a step
/// that would make a force negative or does not halve the residual is dropped.
/// Returns the steps taken.
fn refine_contact(
    p: &Problem,
    pb: &super::FreeBlock,
    w: &Mat<f64>,
    u: &mut Vec<f64>,
    lambda: &mut [f64],
    beta: &mut [f64],
) -> usize {
    let idx: Vec<usize> = (0..lambda.len()).filter(|&i| lambda[i] > 0.0).collect();
    if idx.is_empty() {
        return 0;
    }
    let worst = |g: &[f64]| idx.iter().fold(0.0f64, |a, &i| a.max(g[i].abs()));
    let target = 0.1 * p.settings.tolerance;
    let mut g = gaps(p, pb, u, lambda, beta);
    for step in 0..REFINE_STEPS {
        let scale = inf_norm(u).max(f64::MIN_POSITIVE);
        let now = worst(&g);
        if now <= target * scale {
            return step;
        }
        // The punch equilibrium's residual C_Aᵀ λ_A − r goes in as −(r − C_Aᵀ λ_A).
        let eq: Vec<f64> = (0..pb.rhs.len())
            .map(|j| pb.rhs[j] - idx.iter().map(|&i| pb.cn[(i, j)] * lambda[i]).sum::<f64>())
            .collect();
        let Some((dl, db)) = super::active_set::saddle(w, &g, &pb.cn, &eq, &idx) else {
            return step;
        };
        let mut l2 = lambda.to_vec();
        for (t, &i) in idx.iter().enumerate() {
            l2[i] += dl[t];
        }
        if idx.iter().any(|&i| l2[i] < 0.0) {
            return step;
        }
        let b2: Vec<f64> = beta.iter().zip(&db).map(|(b, d)| b + d).collect();
        let (u2, _) = displacements(p, &l2);
        let g2 = gaps(p, pb, &u2, &l2, &b2);
        if worst(&g2) > 0.5 * now {
            return step;
        }
        lambda.copy_from_slice(&l2);
        beta.copy_from_slice(&b2);
        *u = u2;
        g = g2;
    }
    REFINE_STEPS
}

/// Refinement steps of the contact forces at most (each a dense solve on A).
const REFINE_STEPS: usize = 2;

/// Largest relative residual a solve may leave before it is refined: well
/// above the round-off floor of the residual itself (about 1e-12 measured on
/// the 75k-DOF Hertz example), so that only a poorly conditioned K triggers it.
const REFINE_ABOVE: f64 = 1e-10;

/// K⁻¹ b from the factor, with up to three steps of iterative refinement when
/// the residual b − K x is large relative to b and K x (an ill-conditioned K:
/// nearly incompressible material, extreme stiffness ratios or aspect ratios).
/// Returns x and the number of refinement steps taken.
/// `size`: the magnitude of the terms b was formed from (≥ ‖b‖∞), against which
/// its round-off is judged.
fn solve_refined(op: &Prepared, b: &[f64], size: f64) -> (Vec<f64>, usize) {
    let residual = |x: &[f64]| residual(op, b, x, size);
    let mut x = op.chol.solve(b);
    let (mut r, scale) = residual(&x);
    for step in 0..3 {
        if inf_norm(&r) <= REFINE_ABOVE * scale {
            return (x, step);
        }
        let dx = op.chol.solve(&r);
        let next: Vec<f64> = x.iter().zip(&dx).map(|(a, d)| a + d).collect();
        let (r_next, _) = residual(&next);
        // A step that does not shrink the residual only adds noise (and moves u
        // away from the factor's own W, with which the LCP was solved): stop.
        if inf_norm(&r_next) >= 0.5 * inf_norm(&r) {
            return (x, step);
        }
        (x, r) = (next, r_next);
    }
    (x, 3)
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, y| a.max(y.abs()))
}
