//! Shared test data of the bound's unit tests.

/// A unit square's nine nodes, its middle one off centre (0.45, 0.55) so
/// that no patch is symmetric; the tests mesh it into eight triangles in
/// the orientations they need.
pub(super) fn square_nodes() -> Vec<[f64; 2]> {
    vec![
        [0.0, 0.0],
        [0.5, 0.0],
        [1.0, 0.0],
        [0.0, 0.5],
        [0.45, 0.55],
        [1.0, 0.5],
        [0.0, 1.0],
        [0.5, 1.0],
        [1.0, 1.0],
    ]
}

/// Plane-strain compliance (E = 2, ν = 0.3), engineering shear.
pub(super) fn compliance() -> [[f64; 3]; 3] {
    let (e, nu) = (2.0, 0.3);
    let c = (1.0 + nu) / e;
    [
        [c * (1.0 - nu), -c * nu, 0.0],
        [-c * nu, c * (1.0 - nu), 0.0],
        [0.0, 0.0, 2.0 * c],
    ]
}

/// Plane-strain D (E = 2, ν; engineering shear) and Lamé's λ, the law's
/// own (`LinearIsotropic`).
pub(super) fn plane_strain(nu: f64) -> ([[f64; 3]; 3], f64) {
    use crate::fem::constitutive::{Constitutive, LinearIsotropic, Section};
    let law = LinearIsotropic::new(2.0, nu, Section::PlaneStrain);
    (
        Constitutive::<3>::tangent(&law, &[0.0; 3]),
        Constitutive::<3>::volumetric_lambda(&law),
    )
}
