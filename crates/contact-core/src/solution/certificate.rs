//! KKT certificate of a discrete solution (u, λ) of
//! min ½uᵀKu − fᵀu s.t. Bu ≤ g, all relative and dimensionless:
//!
//! - primal: max(0, max_i (Bu − g)_i) / D, D = max(‖u‖∞, ‖shift‖∞) (displacement scale);
//! - dual: max(0, max_i −λ_i) / ‖λ‖∞;
//! - complementarity: max_i |λ_i (g − Bu)_i| / (‖λ‖∞ D);
//! - equilibrium: ‖K u − f + Bᵀλ‖∞ / max(‖f‖∞, ‖|K||u|‖∞, ‖|B|ᵀ|λ|‖∞), the
//!   normwise backward error: the relative change of K, f and B for which
//!   (u, λ) is in exact equilibrium. A backward-stable solve makes it a small
//!   multiple of the machine epsilon however ill-conditioned K is, so it
//!   certifies the linear algebra without flagging a thin or stiff body whose
//!   K u is a small difference of large terms (a 1/500 plane-stress strip:
//!   ‖Ku‖ against ‖|K||u|‖ is what made a right answer read 5e-8).

use crate::contact::ConstraintSet;
use crate::linalg::sparse::{sym_lower_abs_matvec, sym_lower_matvec};
use crate::solution::report::Certificate;
use faer::sparse::SparseColMat;

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |a, x| a.max(x.abs()))
}

fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else if den > 0.0 {
        num / den
    } else {
        f64::INFINITY
    }
}

/// Returns the certificate and the final gaps g − Bu.
/// `shift`: the rows' share of free punch motions (C_F β), added to the gaps.
pub fn certify(
    k: &SparseColMat<usize, f64>,
    f: &[f64],
    cons: &ConstraintSet,
    u: &[f64],
    lambda: &[f64],
    shift: Option<&[f64]>,
) -> (Certificate, Vec<f64>) {
    let bu = cons.apply(u);
    let gaps: Vec<f64> = (0..cons.len())
        .map(|i| cons.candidates[i].g - bu[i] + shift.map_or(0.0, |s| s[i]))
        .collect();
    let d = {
        // The rows also move with the free rigid motions (a body held only by
        // contact may move mostly rigidly, u being only its deformation): the
        // displacement scale is the larger of the two.
        let du = inf_norm(u).max(shift.map_or(0.0, inf_norm));
        if du > 0.0 {
            du
        } else {
            inf_norm(&cons.g()).max(f64::MIN_POSITIVE)
        }
    };
    let lmax = inf_norm(lambda);
    let primal = ratio(gaps.iter().fold(0.0f64, |a, g| a.max(-g)), d);
    let dual = ratio(lambda.iter().fold(0.0f64, |a, l| a.max(-l)), lmax);
    let comp = ratio(
        gaps.iter().zip(lambda).fold(0.0f64, |a, (g, l)| a.max((g * l).abs())),
        lmax * d,
    );
    let ku = sym_lower_matvec(k, u);
    let mut btl = vec![0.0; u.len()];
    cons.apply_transpose_into(lambda, &mut btl);
    let res: Vec<f64> = (0..u.len()).map(|i| ku[i] - f[i] + btl[i]).collect();
    let abs_ku = sym_lower_abs_matvec(k, u);
    let mut abs_btl = vec![0.0; u.len()];
    cons.apply_abs_transpose_into(lambda, &mut abs_btl);
    let eq = ratio(
        inf_norm(&res),
        inf_norm(f).max(inf_norm(&abs_ku)).max(inf_norm(&abs_btl)),
    );
    (
        Certificate {
            primal,
            dual,
            complementarity: comp,
            equilibrium: eq,
            friction: None,
        },
        gaps,
    )
}

/// How many times the contact forces exceed what the loads and the
/// deformation can balance: ‖|B|ᵀ|λ| + |φ|‖∞ / max(‖f‖∞, ‖|K||u|‖∞), with
/// φ the friction forces on the free DOFs (empty without friction). In
/// equilibrium the forces on a DOF sum to f − K u, so an answer's forces are
/// of that order (a few times it where rows meet on a node); forces far
/// beyond it cancel each other in a direction the body does not feel, as the
/// normal and tangential forces of a node held along one axis when their
/// system is singular (measured: normal forces of 1e20 where the answer's
/// are 10, an excess of 1.3e14).
pub fn force_excess(
    k: &SparseColMat<usize, f64>,
    loads: &[f64],
    cons: &ConstraintSet,
    u: &[f64],
    lambda: &[f64],
    friction: &[f64],
) -> f64 {
    let mut forces = vec![0.0; u.len()];
    cons.apply_abs_transpose_into(lambda, &mut forces);
    forces.iter_mut().zip(friction).for_each(|(a, b)| *a += b.abs());
    let balance = inf_norm(loads).max(inf_norm(&sym_lower_abs_matvec(k, u)));
    ratio(inf_norm(&forces), balance)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::constraints::{Candidate, Link};
    use faer::sparse::Triplet;

    /// A spring of stiffness k on one DOF, and a row on it with coefficient
    /// `coef`.
    fn row(coef: f64) -> Candidate {
        Candidate {
            pair: 0,
            body: 0,
            node: 0,
            x: [0.0; 2],
            normal: [0.0, coef],
            weight: 1.0,
            terms: Vec::new(),
            row: vec![(0, coef)],
            g: 0.0,
            link: Link::Fixed,
        }
    }

    /// One spring (k = 2) pulled by f = 1 and held by one row: the force in
    /// equilibrium, λ = f − k u = 0.5 at u = 0.25, is of the loads' size
    /// (excess λ / max(f, k|u|) = 0.5). Two opposed rows on the
    /// same DOF carrying 1e20 each balance the same load (their sum cancels)
    /// and exceed it by 2e20: the ratio is exact arithmetic on these numbers.
    #[test]
    fn forces_that_cancel_exceed_the_loads() {
        let k = SparseColMat::try_new_from_triplets(1, 1, &[Triplet::new(0, 0, 2.0)]).unwrap();
        let one = ConstraintSet {
            candidates: vec![row(1.0)],
            pruned: vec![0],
        };
        let balanced = force_excess(&k, &[1.0], &one, &[0.25], &[0.5], &[]);
        assert!((balanced - 0.5).abs() <= 1e-15, "{balanced}");
        let two = ConstraintSet {
            candidates: vec![row(1.0), row(-1.0)],
            pruned: vec![0],
        };
        let cancelling = force_excess(&k, &[1.0], &two, &[0.25], &[1e20 + 0.5, 1e20], &[]);
        assert!((cancelling / 2e20 - 1.0).abs() <= 1e-15, "{cancelling}");
        // Friction forces count as contact forces.
        let with_friction = force_excess(&k, &[1.0], &one, &[0.25], &[0.5], &[-3.0]);
        assert!((with_friction - 3.5).abs() <= 1e-15, "{with_friction}");
    }
}
