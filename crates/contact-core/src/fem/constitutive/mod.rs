//! The constitutive seam: what a material gives at a quadrature point.
//!
//! A law maps the strain ε (Voigt, engineering shear) at a point to the stress
//! σ, the tangent D = ∂σ/∂ε and the strain energy density W with σ = ∂W/∂ε.
//! The element kernels ask the law, never a formula, so a new law (or finite
//! deformation, where ε becomes the Green–Lagrange strain and σ the second
//! Piola–Kirchhoff stress) touches this module alone.
//!
//! Voigt orders: plane (xx, yy, xy); axisymmetric (rr, zz, rz, θθ); solid
//! (xx, yy, zz, yz, xz, xy).
//!
//! Every caller (the 2D and 3D assemblies, the stress recovery, the energy
//! bound, the couplings' reactions) holds a body's law as a [`Law`], made by
//! [`law_of`] alone. A new law is a file beside `linear_isotropic.rs`
//! implementing `Constitutive<S>` for the three Voigt lengths, declared here
//! and chosen in `law_of` (`trial.rs`, a test module, defines one there alone
//! and runs it through the assembly's `each_element`).
//!
//! A `Law` calls its material through one dynamic dispatch per call. The
//! kernels ask for the tangent once per element (`kernel::stiffness`), so the
//! element loops stay monomorphised on the element and the strains.

mod linear_isotropic;
#[cfg(test)]
mod trial;

use std::fmt::Debug;
use std::sync::Arc;

use crate::scene::Analysis;

pub use linear_isotropic::LinearIsotropic;

/// The stress state a law works in: the three 2D sections and the 3D solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Section {
    PlaneStrain,
    PlaneStress,
    /// r–z half-section of a body of revolution, with the hoop strain u_r / r.
    Axisymmetric,
    Solid,
}

impl Section {
    /// The number of Voigt components of its strain and stress.
    pub const fn voigt_len(self) -> usize {
        match self {
            Section::PlaneStrain | Section::PlaneStress => 3,
            Section::Axisymmetric => 4,
            Section::Solid => 6,
        }
    }
}

impl From<Analysis> for Section {
    fn from(a: Analysis) -> Self {
        match a {
            Analysis::PlaneStrain => Section::PlaneStrain,
            Analysis::PlaneStress => Section::PlaneStress,
            Analysis::Axisymmetric => Section::Axisymmetric,
        }
    }
}

/// A material at a quadrature point, with S Voigt components.
///
/// A plane law's 4-component form is also its out-of-plane answer: the
/// fourth component is the strain normal to the plane (the hoop strain of a
/// ring), so σ_zz of a plane strain state is `stress([εxx, εyy, γxy, 0])[3]`
/// (0 for a law in plane stress), which the stress recovery reports.
pub trait Constitutive<const S: usize> {
    /// σ(ε).
    fn stress(&self, strain: &[f64; S]) -> [f64; S];
    /// D = ∂σ/∂ε at ε (the stiffness kernel asks at ε = 0, the reference state).
    fn tangent(&self, strain: &[f64; S]) -> [[f64; S]; S];
    /// W(ε), the strain energy per unit volume.
    fn energy(&self, strain: &[f64; S]) -> f64;
    /// λ of the split D = D_dev + λ m mᵀ (m the strains whose sum is the
    /// volume change) that the P2–P0 element integrates on the mean
    /// dilatation (`kernel::Integration::MeanDilatation`): Lamé's λ for isotropy.
    fn volumetric_lambda(&self) -> f64;
}

/// A law every section can ask: plane (3 components), ring (4) and solid (6).
pub trait Material: Constitutive<3> + Constitutive<4> + Constitutive<6> + Debug + Send + Sync {}

impl<T: Constitutive<3> + Constitutive<4> + Constitutive<6> + Debug + Send + Sync> Material for T {}

/// A body's law, whichever material it is: what `law_of` returns and every
/// caller asks.
#[derive(Debug, Clone)]
pub struct Law(Arc<dyn Material>);

impl Law {
    pub fn new(material: impl Material + 'static) -> Self {
        Law(Arc::new(material))
    }
}

/// `Law` answers as its material does, for each Voigt length.
macro_rules! forward {
    ($s:literal) => {
        impl Constitutive<$s> for Law {
            #[inline]
            fn stress(&self, strain: &[f64; $s]) -> [f64; $s] {
                Constitutive::<$s>::stress(&*self.0, strain)
            }
            #[inline]
            fn tangent(&self, strain: &[f64; $s]) -> [[f64; $s]; $s] {
                Constitutive::<$s>::tangent(&*self.0, strain)
            }
            #[inline]
            fn energy(&self, strain: &[f64; $s]) -> f64 {
                Constitutive::<$s>::energy(&*self.0, strain)
            }
            #[inline]
            fn volumetric_lambda(&self) -> f64 {
                Constitutive::<$s>::volumetric_lambda(&*self.0)
            }
        }
    };
}
forward!(3);
forward!(4);
forward!(6);

/// The law of a body of Young's modulus E and Poisson's ratio ν in
/// `section`: the registration of the laws (linear isotropic today).
pub fn law_of(youngs_modulus: f64, poisson_ratio: f64, section: Section) -> Law {
    Law::new(LinearIsotropic::new(youngs_modulus, poisson_ratio, section))
}
