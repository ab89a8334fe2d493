//! Nondimensionalization: x̂ = x / L, Ê = E / E₀. Then displacements scale by L,
//! stresses and pressures by E₀, forces per thickness by E₀·L and moments by E₀·L².

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Length scale L (largest extent of any body).
    pub length: f64,
    /// Modulus scale E₀ (largest Young's modulus).
    pub modulus: f64,
}

impl Scales {
    pub fn length(&self, x: f64) -> f64 {
        x * self.length
    }
    pub fn stress(&self, s: f64) -> f64 {
        s * self.modulus
    }
    pub fn force(&self, f: f64) -> f64 {
        f * self.modulus * self.length
    }
    pub fn moment(&self, m: f64) -> f64 {
        m * self.modulus * self.length * self.length
    }
}
