//! The friction law of a tangential row: how large a tangential force the
//! contact admits under a normal force λ ≥ 0.
//!
//! The frictional solvers read the law through this seam only: the bound
//! b(λ) (the cone's half-width, the Alart–Curnier projection's interval),
//! its derivative b′(λ) (a sliding point's Newton row linearizes τ = ± b(λ)
//! at the iterate: τ = ± (b(λ₀) + b′(λ₀)(λ − λ₀))), and the slope of the
//! rays that span the forces admissible at every λ (Fichera's test with
//! friction: its LP takes non-negative combinations of λ (n ± s t)).
//!
//! Coulomb's law b = μ λ is the one the scene states (`Pair::friction`). A
//! new law is a file beside this one implementing `FrictionLaw`, declared
//! here and chosen in `law_of`.

use std::fmt::Debug;
use std::sync::Arc;

use crate::scene::Pair;

/// A friction law, per tangential row.
pub trait FrictionLaw: Debug + Send + Sync {
    /// The largest |τ| admitted under the normal force λ ≥ 0.
    fn bound(&self, lambda: f64) -> f64;

    /// d b / d λ at λ: the coefficient of λ in a sliding point's Newton row.
    fn derivative(&self, lambda: f64) -> f64;

    /// The slope s of the cone's rays λ (n ± s t): the forces admissible at
    /// every λ ≥ 0 (μ for Coulomb; 0 for a bound that does not grow with λ,
    /// whose admissible forces contain no tangential ray).
    fn ray_slope(&self) -> f64;

    /// The point of [−b(λ), b(λ)] nearest a trial tangential force z: the
    /// Alart–Curnier projection.
    fn project(&self, lambda: f64, z: f64) -> f64 {
        let b = self.bound(lambda);
        z.clamp(-b, b)
    }
}

/// A shared law: one per frictional pair, held by each of its rows.
pub type Law = Arc<dyn FrictionLaw>;

/// Coulomb's law, |τ| ≤ μ λ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coulomb {
    pub mu: f64,
}

impl FrictionLaw for Coulomb {
    fn bound(&self, lambda: f64) -> f64 {
        self.mu * lambda
    }

    fn derivative(&self, _lambda: f64) -> f64 {
        self.mu
    }

    fn ray_slope(&self) -> f64 {
        self.mu
    }
}

/// The law of a frictional pair (the registration of the laws).
pub fn law_of(pair: &Pair) -> Law {
    Arc::new(Coulomb { mu: pair.friction })
}

/// A sliding point's tangential force as a line in λ, τ = γ λ + c, for the
/// slip direction `sign`, the normal force's lean ℓ = n · t (the law holds
/// for τ + ℓ λ) and the law linearized at λ₀: γ = ± b′(λ₀) − ℓ,
/// c = ± (b(λ₀) − b′(λ₀) λ₀) (0 for a bound proportional to λ).
pub fn slip_line(law: &dyn FrictionLaw, sign: i8, lean: f64, at: f64) -> (f64, f64) {
    let s = f64::from(sign);
    let d = law.derivative(at);
    (s * d - lean, s * (law.bound(at) - d * at))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bound's derivative is its slope: central differences of b at
    /// λ = 0.1 … 10 match b′ to 1e-9 relative (the truncation error of a
    /// central difference of a linear function is round-off alone, about
    /// ε b / h = 2e-16 · 10 / 1e-6).
    #[test]
    fn coulomb_derivative_is_the_slope_of_its_bound() {
        let law = Coulomb { mu: 0.37 };
        for &l in &[0.1, 1.0, 3.5, 10.0] {
            let h = 1e-6;
            let fd = (law.bound(l + h) - law.bound(l - h)) / (2.0 * h);
            assert!(
                (fd - law.derivative(l)).abs() <= 1e-9 * law.derivative(l),
                "λ {l}: {fd}"
            );
            // b(λ) = b′ λ: the bound is its own tangent line through 0.
            assert_eq!(slip_line(&law, 1, 0.0, l), (law.mu, 0.0));
        }
    }

    /// The projection onto [−b, b] is idempotent (P P z = P z) and
    /// non-expansive (|P z − P y| ≤ |z − y|), exactly: a clamp.
    #[test]
    fn the_projection_is_idempotent_and_non_expansive() {
        let law = Coulomb { mu: 0.5 };
        let zs = [-3.0, -1.0, -0.2, 0.0, 0.4, 0.9, 2.5];
        for &l in &[0.0, 0.5, 2.0] {
            for &z in &zs {
                let p = law.project(l, z);
                assert_eq!(law.project(l, p), p);
                assert!(p.abs() <= law.bound(l));
                for &y in &zs {
                    assert!((p - law.project(l, y)).abs() <= (z - y).abs());
                }
            }
        }
    }

    /// The cone's rays λ (n ± s t) lie on the cone's edge: their tangential
    /// part is the bound of their normal part, for every λ.
    #[test]
    fn coulomb_rays_lie_on_the_edge_of_its_cone() {
        let law = Coulomb { mu: 0.8 };
        for &l in &[0.25, 1.0, 4.0] {
            assert!((law.ray_slope() * l - law.bound(l)).abs() <= 1e-15 * l);
        }
    }
}
