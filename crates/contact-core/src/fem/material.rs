//! Constitutive matrices D (Voigt order xx, yy, xy with engineering shear strain).
//!
//! Plane strain: D = E/((1+ν)(1−2ν)) [[1−ν, ν, 0], [ν, 1−ν, 0], [0, 0, (1−2ν)/2]].
//! Plane stress: D = E/(1−ν²) [[1, ν, 0], [ν, 1, 0], [0, 0, (1−ν)/2]].

use crate::scene::Analysis;

pub fn d_matrix(e: f64, nu: f64, analysis: Analysis) -> [[f64; 3]; 3] {
    match analysis {
        // In axisymmetry the (rr, zz, rz) block of D is plane strain's; the
        // hoop row is `fem::axisymmetric::d_matrix`'s.
        Analysis::PlaneStrain | Analysis::Axisymmetric => {
            let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
            [
                [c * (1.0 - nu), c * nu, 0.0],
                [c * nu, c * (1.0 - nu), 0.0],
                [0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0],
            ]
        }
        Analysis::PlaneStress => {
            let c = e / (1.0 - nu * nu);
            [[c, c * nu, 0.0], [c * nu, c, 0.0], [0.0, 0.0, c * (1.0 - nu) / 2.0]]
        }
    }
}
