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
