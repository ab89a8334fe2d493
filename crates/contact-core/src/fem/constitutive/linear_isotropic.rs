//! Linear isotropic elasticity, Young's modulus E and Poisson's ratio ν.
//! With c = E / ((1 + ν)(1 − 2ν)):
//!
//! - plane strain: D = c [[1−ν, ν, 0], [ν, 1−ν, 0], [0, 0, (1−2ν)/2]];
//! - plane stress: D = E/(1−ν²) [[1, ν, 0], [ν, 1, 0], [0, 0, (1−ν)/2]];
//! - axisymmetric: plane strain's block plus the hoop row (ν, ν, 0, 1−ν) c;
//! - solid: c (1−ν) on the normal diagonal, c ν off it, c (1−2ν)/2 in shear.
//!
//! W = ½ σ·ε = ½ εᵀ D ε.

use super::{Constitutive, Section};

/// Linear isotropic elasticity (Young's modulus E, Poisson's ratio ν).
///
/// D is built once, not at every quadrature point the assembly asks, and held
/// as its largest, 6 × 6, form: a law of S components reads the leading S × S
/// block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearIsotropic {
    youngs_modulus: f64,
    poisson_ratio: f64,
    section: Section,
    d: [[f64; 6]; 6],
}

impl LinearIsotropic {
    pub fn new(youngs_modulus: f64, poisson_ratio: f64, section: Section) -> Self {
        let (e, nu) = (youngs_modulus, poisson_ratio);
        let mut d = [[0.0; 6]; 6];
        match section {
            Section::PlaneStress => {
                let c = e / (1.0 - nu * nu);
                d[0][..3].copy_from_slice(&[c, c * nu, 0.0]);
                d[1][..3].copy_from_slice(&[c * nu, c, 0.0]);
                d[2][2] = c * (1.0 - nu) / 2.0;
            }
            Section::PlaneStrain | Section::Axisymmetric => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                let (a, b) = (c * (1.0 - nu), c * nu);
                d[0][..4].copy_from_slice(&[a, b, 0.0, b]);
                d[1][..4].copy_from_slice(&[b, a, 0.0, b]);
                d[2][2] = c * (1.0 - 2.0 * nu) / 2.0;
                d[3][..4].copy_from_slice(&[b, b, 0.0, a]);
            }
            Section::Solid => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                let (a, b) = (c * (1.0 - nu), c * nu);
                for (i, row) in d.iter_mut().enumerate().take(3) {
                    row[..3].copy_from_slice(&[b, b, b]);
                    row[i] = a;
                }
                for (i, row) in d.iter_mut().enumerate().skip(3) {
                    row[i] = c * (1.0 - 2.0 * nu) / 2.0;
                }
            }
        }
        LinearIsotropic {
            youngs_modulus,
            poisson_ratio,
            section,
            d,
        }
    }

    /// Shear modulus μ = E / (2(1 + ν)).
    #[cfg(test)]
    fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }
}

impl<const S: usize> Constitutive<S> for LinearIsotropic {
    fn stress(&self, strain: &[f64; S]) -> [f64; S] {
        debug_assert!(S <= self.section.voigt_len());
        // Summed from the first term on, as the centroid stresses always were.
        std::array::from_fn(|i| {
            let mut s = self.d[i][0] * strain[0];
            for (d, e) in self.d[i][1..S].iter().zip(&strain[1..]) {
                s += d * e;
            }
            s
        })
    }

    fn tangent(&self, _strain: &[f64; S]) -> [[f64; S]; S] {
        debug_assert!(S <= self.section.voigt_len());
        std::array::from_fn(|i| std::array::from_fn(|j| self.d[i][j]))
    }

    fn energy(&self, strain: &[f64; S]) -> f64 {
        let s = self.stress(strain);
        0.5 * (0..S).map(|i| s[i] * strain[i]).sum::<f64>()
    }

    fn volumetric_lambda(&self) -> f64 {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plane strain D as `material::d_matrix` built it before the seam,
    /// written out: the law must give it bit for bit (the recorded replies
    /// compare to 1e-12).
    #[test]
    fn plane_strain_tangent_is_the_former_d_matrix() {
        let (e, nu) = (200.0, 0.3);
        let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let former = [
            [c * (1.0 - nu), c * nu, 0.0],
            [c * nu, c * (1.0 - nu), 0.0],
            [0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0],
        ];
        let law = LinearIsotropic::new(e, nu, Section::PlaneStrain);
        assert_eq!(Constitutive::<3>::tangent(&law, &[0.0; 3]), former);
        let c = e / (1.0 - nu * nu);
        let stress = [[c, c * nu, 0.0], [c * nu, c, 0.0], [0.0, 0.0, c * (1.0 - nu) / 2.0]];
        let law = LinearIsotropic::new(e, nu, Section::PlaneStress);
        assert_eq!(Constitutive::<3>::tangent(&law, &[0.0; 3]), stress);
    }

    /// W = ½ σ·ε in every section, and W is the quadratic form of D (its
    /// second difference along ε is εᵀ D ε): to 1e-14 of W.
    #[test]
    fn energy_is_half_stress_dot_strain() {
        fn check<const S: usize>(law: &LinearIsotropic, eps: [f64; S]) {
            let w = law.energy(&eps);
            let d = law.tangent(&eps);
            let quad: f64 = (0..S)
                .map(|i| (0..S).map(|j| eps[i] * d[i][j] * eps[j]).sum::<f64>())
                .sum();
            assert!(w > 0.0);
            assert!((2.0 * w - quad).abs() <= 1e-14 * w, "{:?}: {w} vs {quad}", law.section);
        }
        let (e, nu) = (70.0, 0.33);
        check(&LinearIsotropic::new(e, nu, Section::PlaneStrain), [1e-3, -4e-4, 7e-4]);
        check(&LinearIsotropic::new(e, nu, Section::PlaneStress), [1e-3, -4e-4, 7e-4]);
        check(
            &LinearIsotropic::new(e, nu, Section::Axisymmetric),
            [1e-3, -4e-4, 7e-4, 2e-4],
        );
        check(
            &LinearIsotropic::new(e, nu, Section::Solid),
            [1e-3, -4e-4, 3e-4, 7e-4, -2e-4, 5e-4],
        );
    }

    /// The energy density is Lamé's, W = μ ε:ε + λ/2 (tr ε)² with the tensor
    /// strains (half the engineering shears), written independently of D:
    /// in plane strain (ε_zz = 0) and in the solid, to round-off.
    #[test]
    fn energy_is_lames() {
        let (e, nu) = (70.0, 0.33);
        let (lambda, mu) = (e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu)));
        let lame = |normal: &[f64], shear: &[f64]| {
            let tr: f64 = normal.iter().sum();
            let ee: f64 = normal.iter().map(|v| v * v).sum::<f64>() + shear.iter().map(|g| 0.5 * g * g).sum::<f64>();
            mu * ee + 0.5 * lambda * tr * tr
        };
        let plane = [1e-3, -4e-4, 7e-4];
        let w = LinearIsotropic::new(e, nu, Section::PlaneStrain).energy(&plane);
        let want = lame(&plane[..2], &plane[2..]);
        assert!((w / want - 1.0).abs() < 1e-14, "{w} vs {want}");
        let solid = [1e-3, -4e-4, 3e-4, 7e-4, -2e-4, 5e-4];
        let w = LinearIsotropic::new(e, nu, Section::Solid).energy(&solid);
        let want = lame(&solid[..3], &solid[3..]);
        assert!((w / want - 1.0).abs() < 1e-14, "{w} vs {want}");
    }

    /// The plane law's 4-form answers out of the plane (`Constitutive`'s
    /// doc): at ε_zz = 0 its fourth component is σ_zz = ν (σ_xx + σ_yy) in
    /// plane strain and 0 in plane stress, its first three the plane stress
    /// state; to 1e-14 of the stresses (a few roundings apart).
    #[test]
    fn the_plane_four_form_gives_the_out_of_plane_stress() {
        let (e, nu) = (70.0, 0.33);
        let eps = [1e-3, -4e-4, 7e-4];
        let four = [eps[0], eps[1], eps[2], 0.0];
        for section in [Section::PlaneStrain, Section::PlaneStress] {
            let law = LinearIsotropic::new(e, nu, section);
            let s3 = Constitutive::<3>::stress(&law, &eps);
            let s4 = Constitutive::<4>::stress(&law, &four);
            let scale = s3.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let zz = if section == Section::PlaneStrain {
                nu * (s3[0] + s3[1])
            } else {
                0.0
            };
            assert!((s4[3] - zz).abs() <= 1e-14 * scale, "{section:?}: {} vs {zz}", s4[3]);
            for i in 0..3 {
                assert!((s4[i] - s3[i]).abs() <= 1e-14 * scale, "{section:?} {i}");
            }
        }
    }

    /// The solid law is Hooke's: a uniaxial stress σ_xx alone comes from
    /// ε = σ/E (1, −ν, −ν, 0, 0, 0), and a pure shear γ gives τ = μ γ.
    #[test]
    fn solid_law_is_hookes() {
        let (e, nu, s) = (200.0, 0.3, 0.1);
        let law = LinearIsotropic::new(e, nu, Section::Solid);
        let eps = [s / e, -nu * s / e, -nu * s / e, 0.0, 0.0, 0.0];
        let sigma = law.stress(&eps);
        assert!((sigma[0] / s - 1.0).abs() < 1e-14);
        assert!(sigma[1..].iter().all(|v| v.abs() < 1e-15 * s));
        let tau = law.stress(&[0.0, 0.0, 0.0, 0.0, 1e-3, 0.0])[4];
        assert!((tau / (law.shear_modulus() * 1e-3) - 1.0).abs() < 1e-14);
    }
}
