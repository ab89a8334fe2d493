//! Closed-form references the suites and tests compare with.

/// Hertz line contact: half-width a and peak p0 for the
/// load P per unit thickness, the effective radius and the effective modulus.
pub fn hertz(p: f64, radius: f64, e_star: f64) -> (f64, f64) {
    let a = (4.0 * p * radius / (std::f64::consts::PI * e_star)).sqrt();
    (a, 2.0 * p / (std::f64::consts::PI * a))
}

/// Hertz point contact (3D, a sphere of the effective radius on a flat):
/// contact radius a and peak p0 for the total load P.
pub fn hertz_sphere(p: f64, radius: f64, e_star: f64) -> (f64, f64) {
    let a = (3.0 * p * radius / (4.0 * e_star)).cbrt();
    (a, 3.0 * p / (2.0 * std::f64::consts::PI * a * a))
}
