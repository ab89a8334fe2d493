//! Screening the rows of a large condensed solve: W = B K⁻¹ Bᵀ is formed
//! over the rows the loads press, and every other row is checked after.
//!
//! The condensation's cost grows with the rows that reach the top of the
//! elimination tree, linearly in its triangular solves and quadratically in
//! its Gram product (`linalg::schur`), while on a contact like Hertz's most
//! candidates stay open: the two-cylinder row of `contact-bench --floor`
//! (1.17M DOF) has 1,121 candidates of which 343 press.
//!
//! The rows are chosen in passes on one factor. The first pass of a fresh
//! factor condenses none: its u is K⁻¹ f, the bodies without contact. Each
//! pass then takes in every row outside it whose gap after its u is negative
//! (a row the LCP over all candidates would press), with the rows whose gap
//! is below half the deepest such penetration (the neighbours those forces
//! will push in too), condenses them on the same factor and solves again.
//! A pass that leaves no row outside it penetrating is the answer of the LCP
//! over every candidate: its own rows satisfy the LCP, and every other row
//! has λ = 0 and a gap ≥ 0, so it is complementary (the displacements of
//! the LCP's answers are one: the potential energy is strictly convex in
//! u). After `MAX_PASSES`, or once the
//! rows chosen pass `FULL_SHARE` of the candidates, every row is condensed.
//!
//! It holds for exact methods on the plain LCP alone: free motions (their
//! equilibrium couples every row) and foundations (their compliance is over
//! every row, per request) keep the whole condensation.

use std::sync::Arc;

use crate::cache::Prepared;
use crate::contact::ConstraintSet;
use crate::error::CoreError;
use crate::methods::{self, condensed, FreeBlock, Problem, Solution};
use crate::model::Model;
use crate::outcome::ProgressStage;
use crate::scene::{Method, Scene};

/// Candidates below which every row is condensed at once: on the examples'
/// 277–381 rows the condensation saved and the extra sweeps of a pass were
/// a wash (±0.03 s of 0.3–0.9 s), while on a 45k-DOF strip with 668 rows
/// the condensation went from 0.11 s to 0.01 s of 0.27 s.
const SCREEN_MIN: usize = 512;
/// Passes of screening before every row is condensed.
const MAX_PASSES: usize = 4;
/// Share of the candidates past which screening saves too little to repeat
/// a condensation for it.
const FULL_SHARE: f64 = 0.6;
/// Rows whose gap is below this share of the deepest penetration join the
/// pressed ones.
const NEIGHBOURS: f64 = 0.5;
/// The first pass takes the rows that penetrate by more than this share of
/// the deepest, without contact forces.
const FIRST: f64 = 0.5;
/// Round-off of the sparse gap g − B u, relative to the larger of its terms.
const ROUND_OFF: f64 = 1e-12;

/// Whether a condensed solve of the scene screens its rows.
pub(super) fn applies(scene: &Scene, model: &Model) -> bool {
    matches!(scene.method, Method::Auto | Method::ActiveSet)
        && model.free.is_empty()
        && model.foundations.is_empty()
        && model.cons.len() >= SCREEN_MIN
}

/// The answer over every candidate, the operator its last pass condensed
/// (for the cache) and the seconds its later condensations took.
pub(super) struct Screened {
    pub op: Arc<Prepared>,
    pub sol: Solution,
    pub t_condensation: f64,
}

/// The contact solve on a prepared operator: screened (`applies`), or over
/// every row, condensing them all first when `op` is a screened solve's from
/// the cache.
pub(super) fn solve_rows(
    scene: &Scene,
    model: &Model,
    op: Arc<Prepared>,
    f: &[f64],
    compliance: Option<&faer::Mat<f64>>,
    screened: bool,
) -> Result<Screened, CoreError> {
    if screened {
        return solve(scene, model, op, f);
    }
    let (op, t_condensation) = match op.rows {
        Some(_) => {
            let all = Arc::new(condensed::condense_subset(&op, &model.cons, None)?);
            let t = all.t_condensation;
            (all, t)
        }
        None => (op, 0.0),
    };
    let problem = Problem {
        op: &op,
        f,
        cons: &model.cons,
        settings: &scene.settings,
        punch: (!model.free.is_empty()).then(|| FreeBlock::frictionless(&model.free)),
        compliance,
    };
    let sol = methods::solve(&problem, scene.method)?;
    Ok(Screened {
        op,
        sol,
        t_condensation,
    })
}

/// Passes from the rows `op` holds until none outside them penetrates.
fn solve(scene: &Scene, model: &Model, mut op: Arc<Prepared>, f: &[f64]) -> Result<Screened, CoreError> {
    let cons = &model.cons;
    let m = cons.len();
    let (mut t_condensation, mut iterations, mut t_contact) = (0.0, 0, 0.0);
    let mut pass = 0;
    if op.rows.as_ref().is_some_and(Vec::is_empty) && f.iter().all(|v| *v == 0.0) {
        // No load (the obstacles' places alone press the body): without
        // contact u = 0, and the first pass reads the gaps as given, with no
        // sweep. On the Hertz block of `contact-bench --floor` (1.2M DOF)
        // 1,267 of 1,371 rows overlap past half the deepest, 1,053 press:
        // every row is condensed at once, and the sweep would have been lost.
        let g = cons.g();
        let deepest = g.iter().fold(0.0f64, |a, v| a.max(-v));
        if deepest > 0.0 {
            let chosen: Vec<usize> = (0..m).filter(|&i| g[i] < -FIRST * deepest).collect();
            let full = chosen.len() as f64 > FULL_SHARE * m as f64;
            op = Arc::new(condensed::condense_subset(&op, cons, (!full).then_some(chosen))?);
            t_condensation += op.t_condensation;
            pass = 1;
        }
    }
    loop {
        pass += 1;
        let rows: Vec<usize> = op.rows.clone().unwrap_or_else(|| (0..m).collect());
        let subset = ConstraintSet {
            candidates: rows.iter().map(|&i| cons.candidates[i].clone()).collect(),
            pruned: cons.pruned.clone(),
        };
        let problem = Problem {
            op: &op,
            f,
            cons: &subset,
            settings: &scene.settings,
            punch: None,
            compliance: None,
        };
        let mut sol = methods::solve(&problem, scene.method)?;
        iterations += sol.iterations;
        t_contact += sol.t_contact;
        (sol.iterations, sol.t_contact) = (iterations, t_contact);
        let sol = spread(sol, &rows, m);
        if op.rows.is_none() || !sol.converged {
            return Ok(Screened {
                op,
                sol,
                t_condensation,
            });
        }
        // A row's g and B are per unit of its weight already (`contact::rows`):
        // its gap is a length. A penetration within the round-off of
        // g − B u is not a row to press.
        let bu = cons.apply(&sol.u);
        let (mut gaps, mut noise) = (vec![0.0; m], vec![0.0; m]);
        for (i, c) in cons.candidates.iter().enumerate() {
            gaps[i] = c.g - bu[i];
            noise[i] = ROUND_OFF * c.g.abs().max(bu[i].abs());
        }
        let mut taken = vec![false; m];
        rows.iter().for_each(|&i| taken[i] = true);
        let deepest = (0..m)
            .filter(|&i| !taken[i] && -gaps[i] > noise[i])
            .fold(0.0f64, |a, i| a.max(-gaps[i]));
        if deepest == 0.0 {
            return Ok(Screened {
                op,
                sol,
                t_condensation,
            });
        }
        crate::cancel::check(ProgressStage::Condensation)?;
        // Without contact forces (the first pass) the zone lies within the
        // rows that penetrate, the forces pushing the surfaces apart: on two
        // cylinders pressed together (1.17M DOF) 683 of 1,121 rows penetrate,
        // 343 press, and the 483 that penetrate by more than half the deepest
        // hold them all. With forces, a row they left penetrating has
        // neighbours that will follow it.
        let margin = match rows.is_empty() {
            true => -FIRST * deepest,
            false => NEIGHBOURS * deepest,
        };
        for i in 0..m {
            taken[i] |= gaps[i] < margin;
        }
        let chosen: Vec<usize> = (0..m).filter(|&i| taken[i]).collect();
        let full = pass >= MAX_PASSES || chosen.len() as f64 > FULL_SHARE * m as f64;
        op = Arc::new(condensed::condense_subset(&op, cons, (!full).then_some(chosen))?);
        t_condensation += op.t_condensation;
    }
}

/// A pass's solution over its rows as one over every candidate (λ = 0 and
/// open off them).
fn spread(sol: Solution, rows: &[usize], m: usize) -> Solution {
    if rows.len() == m {
        return sol;
    }
    let (mut lambda, mut in_contact) = (vec![0.0; m], vec![false; m]);
    for (k, &i) in rows.iter().enumerate() {
        lambda[i] = sol.lambda[k];
        in_contact[i] = sol.in_contact[k];
    }
    Solution {
        lambda,
        in_contact,
        ..sol
    }
}
