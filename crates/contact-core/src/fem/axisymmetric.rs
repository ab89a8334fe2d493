//! A body of revolution on its r–z half-section (x = r, y = z): strains
//! (ε_rr, ε_zz, γ_rz, ε_θθ) with the hoop strain ε_θθ = u_r / r, and the
//! measure 2πr dA, so that stiffness, loads and forces are totals over the
//! circumference (Zienkiewicz & Taylor, The Finite Element Method, vol. 1,
//! ch. 5). The stiffness is `kernel::stiffness` with `kernel::Ring`; here are
//! the stresses the reply recovers at the centroid. Every quadrature point is
//! inside the element, where r > 0 even for an element touching the axis: the
//! hoop term N_i / r stays finite (an axis node's u_r is held at 0 by the DOF
//! map).

use super::constitutive::Constitutive;
use super::kernel::{self, Ring, Strains};
use super::reference::{ReferenceElement, T3, T6};
use crate::mesh::Order;

/// The centroid of the reference triangle.
const CENTROID: [f64; 2] = [1.0 / 3.0, 1.0 / 3.0];

/// The strains whose sum is the volume change: ε_rr + ε_zz + ε_θθ.
const VOLUME: [f64; 4] = <Ring as Strains<2, 4>>::VOLUME;

/// The element's nodes and nodal displacements (u_r, u_z) as arrays of its order.
fn arrays<const K: usize>(x: &[[f64; 2]], ue: &[f64]) -> ([[f64; 2]; K], [[f64; 2]; K]) {
    (
        std::array::from_fn(|i| x[i]),
        std::array::from_fn(|i| [ue[2 * i], ue[2 * i + 1]]),
    )
}

/// Centroid stress (rr, zz, rz, θθ) of the P2–P0 element
/// (`kernel::Integration::MeanDilatation`): the deviatoric part from the centroid
/// strain, the volumetric part λ θ̄ from the element's mean dilatation, as
/// the stiffness has it. The centroid's own div u is not θ̄ next to the axis
/// (u_r / r varies by O(1) there): measured on a ball on a flat at ν = 0.49,
/// a/h ≈ 21, the stresses within a/2 of the contact were off by up to 21 % of
/// p0 on elements touching the axis.
pub fn centroid_stress_selective(order: Order, x: &[[f64; 2]], law: &impl Constitutive<4>, ue: &[f64]) -> [f64; 4] {
    fn of<E: ReferenceElement<2, K>, const K: usize>(x: &[[f64; 2]], ue: &[f64]) -> ([f64; 4], f64) {
        let (x, u) = arrays::<K>(x, ue);
        let (bbar, _) = kernel::mean_dilatation::<E, Ring, 2, K, 4>(&x);
        let theta: f64 = u.iter().flatten().zip(bbar.iter().flatten()).map(|(u, b)| u * b).sum();
        (kernel::strain::<E, Ring, 2, K, 4>(&x, &CENTROID, &u), theta)
    }
    let (eps, theta) = match order {
        Order::T3 => of::<T3, 3>(x, ue),
        Order::T6 => of::<T6, 6>(x, ue),
    };
    let lambda = law.volumetric_lambda();
    let d = kernel::deviatoric(&law.tangent(&eps), lambda, VOLUME);
    std::array::from_fn(|i| (0..4).map(|j| d[i][j] * eps[j]).sum::<f64>() + lambda * theta * VOLUME[i])
}

/// Centroid stress (rr, zz, rz, θθ).
pub fn centroid_stress(order: Order, x: &[[f64; 2]], law: &impl Constitutive<4>, ue: &[f64]) -> [f64; 4] {
    fn of<E: ReferenceElement<2, K>, const K: usize>(x: &[[f64; 2]], ue: &[f64]) -> [f64; 4] {
        let (x, u) = arrays::<K>(x, ue);
        kernel::strain::<E, Ring, 2, K, 4>(&x, &CENTROID, &u)
    }
    let eps = match order {
        Order::T3 => of::<T3, 3>(x, ue),
        Order::T6 => of::<T6, 6>(x, ue),
    };
    law.stress(&eps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::constitutive::{LinearIsotropic, Section};
    use crate::fem::kernel::Integration;

    /// K_e of a T3 or T6 ring element through the generic kernel.
    fn stiffness(x: &[[f64; 2]], law: &impl Constitutive<4>, ke: &mut [f64; 144]) {
        match x.len() {
            3 => kernel::stiffness::<T3, Ring, _, 2, 3, 4>(&std::array::from_fn(|i| x[i]), law, Integration::Full, ke),
            _ => kernel::stiffness::<T6, Ring, _, 2, 6, 4>(&std::array::from_fn(|i| x[i]), law, Integration::Full, ke),
        }
    }

    /// The straight-sided T6 on `corners` (midside nodes at the midpoints).
    fn straight_t6(c: [[f64; 2]; 3]) -> [[f64; 2]; 6] {
        let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        [c[0], c[1], c[2], mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[0])]
    }

    /// A uniform radial expansion u_r = ε r, u_z = ε z is a state of uniform
    /// strain ε in every direction (hoop included): K u is the nodal force of
    /// the uniform stress σ = 3Kε on the element's boundary, and the element's
    /// strain energy is ½ uᵀ K u = ½ σ:ε V with V = 2π r̄ A (Pappus). Holds
    /// for T3 (one point at the centroid) and for T6 (affine element, the
    /// 3-point rule integrates r exactly).
    #[test]
    fn uniform_dilatation_has_the_exact_energy() {
        let (e, nu, eps) = (200.0, 0.3, 1e-3);
        let law = LinearIsotropic::new(e, nu, Section::Axisymmetric);
        let corners = [[0.5, 0.0], [2.0, 0.3], [0.9, 1.4]];
        let area = 0.5
            * ((corners[1][0] - corners[0][0]) * (corners[2][1] - corners[0][1])
                - (corners[2][0] - corners[0][0]) * (corners[1][1] - corners[0][1]));
        let rbar = (corners[0][0] + corners[1][0] + corners[2][0]) / 3.0;
        let volume = std::f64::consts::TAU * rbar * area;
        let bulk = e / (3.0 * (1.0 - 2.0 * nu));
        let exact = 0.5 * 9.0 * bulk * eps * eps * volume;
        let t6 = straight_t6(corners);
        for x in [&corners[..], &t6[..]] {
            let mut ke = [0.0; 144];
            stiffness(x, &law, &mut ke);
            let nd = 2 * x.len();
            let u: Vec<f64> = x.iter().flat_map(|p| [eps * p[0], eps * p[1]]).collect();
            let energy: f64 = 0.5
                * (0..nd)
                    .map(|a| (0..nd).map(|b| u[a] * ke[a * nd + b] * u[b]).sum::<f64>())
                    .sum::<f64>();
            assert!(
                (energy / exact - 1.0).abs() < 1e-12,
                "{} nodes: {energy} vs {exact}",
                x.len()
            );
        }
    }

    /// The P2–P0 element's volumetric energy is ½ λ V θ̄², θ̄ = ∫ div u dV / V
    /// the mean dilatation over the ring (dV = 2πr dA): for u_r = r², u_z = 0
    /// on an element touching the axis, div u = 2r + r²/r = 3r and θ̄ =
    /// 3 ∫ r² dA / ∫ r dA, in closed form for a triangle (∫ r dA = A Σr_i / 3,
    /// ∫ r² dA = A (Σ r_i² + Σ_{i<j} r_i r_j) / 6). With a pure volumetric
    /// material (D = λ m mᵀ) the deviatoric part vanishes and the energy is
    /// that alone. The centroid value 3 r_c is not θ̄: on this element it is
    /// 0.84 θ̄, the energy 0.71 of the exact one.
    #[test]
    fn p2_p0_constraint_is_the_mean_dilatation_over_the_ring() {
        /// A law whose tangent is its volumetric part alone.
        struct Volumetric(f64);
        impl Constitutive<4> for Volumetric {
            fn stress(&self, eps: &[f64; 4]) -> [f64; 4] {
                let tr: f64 = (0..4).map(|i| VOLUME[i] * eps[i]).sum();
                VOLUME.map(|m| self.0 * tr * m)
            }
            fn tangent(&self, _: &[f64; 4]) -> [[f64; 4]; 4] {
                std::array::from_fn(|i| std::array::from_fn(|j| self.0 * VOLUME[i] * VOLUME[j]))
            }
            fn energy(&self, eps: &[f64; 4]) -> f64 {
                0.5 * (0..4).map(|i| self.stress(eps)[i] * eps[i]).sum::<f64>()
            }
            fn volumetric_lambda(&self) -> f64 {
                self.0
            }
        }
        let lambda = 7.0;
        let corners = [[0.0, 0.2], [0.7, 0.0], [0.3, 1.1]];
        let area = 0.5
            * ((corners[1][0] - corners[0][0]) * (corners[2][1] - corners[0][1])
                - (corners[2][0] - corners[0][0]) * (corners[1][1] - corners[0][1]));
        let r = [corners[0][0], corners[1][0], corners[2][0]];
        let int_r = area * (r[0] + r[1] + r[2]) / 3.0;
        let int_r2 = area * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[0] * r[1] + r[1] * r[2] + r[2] * r[0]) / 6.0;
        let volume = std::f64::consts::TAU * int_r;
        let theta = 3.0 * int_r2 / int_r;
        let exact = 0.5 * lambda * volume * theta * theta;
        let x = straight_t6(corners);
        let mut ke = [0.0; 144];
        kernel::stiffness::<T6, Ring, _, 2, 6, 4>(&x, &Volumetric(lambda), Integration::MeanDilatation, &mut ke);
        let u: Vec<f64> = x.iter().flat_map(|p| [p[0] * p[0], 0.0]).collect();
        let energy: f64 = 0.5
            * (0..12)
                .map(|a| (0..12).map(|b| u[a] * ke[a * 12 + b] * u[b]).sum::<f64>())
                .sum::<f64>();
        assert!((energy / exact - 1.0).abs() < 1e-12, "{energy} vs {exact}");
    }

    /// A translation along the axis is the one rigid motion of a body of
    /// revolution: K u = 0 for u_z = const, not for u_r = const (which
    /// stretches the hoops).
    #[test]
    fn axial_translation_is_free_and_radial_is_not() {
        let law = LinearIsotropic::new(1.0, 0.25, Section::Axisymmetric);
        let x = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let mut ke = [0.0; 144];
        stiffness(&x, &law, &mut ke);
        let apply = |u: [f64; 6]| -> f64 {
            (0..6)
                .map(|a| (0..6).map(|b| ke[a * 6 + b] * u[b]).sum::<f64>().abs())
                .fold(0.0, f64::max)
        };
        assert!(apply([0.0, 1.0, 0.0, 1.0, 0.0, 1.0]) < 1e-14);
        assert!(apply([1.0, 0.0, 1.0, 0.0, 1.0, 0.0]) > 0.1);
    }
}
