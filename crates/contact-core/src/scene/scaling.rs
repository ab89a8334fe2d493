//! Nondimensionalization: x̂ = x / L, Ê = E / E₀. Then displacements scale by L,
//! stresses and pressures by E₀, forces per thickness by E₀·L (totals over the
//! circumference of a body of revolution by E₀·L²) and moments by E₀·L².

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Length scale L (largest extent of any body).
    pub length: f64,
    /// Modulus scale E₀ (largest Young's modulus).
    pub modulus: f64,
    /// Forces are totals over the circumference of a body of revolution
    /// (force scale E₀L²), not per unit thickness (E₀L).
    pub axisymmetric: bool,
}

impl Scales {
    pub fn length(&self, x: f64) -> f64 {
        x * self.length
    }
    pub fn stress(&self, s: f64) -> f64 {
        s * self.modulus
    }
    /// The force of nondimensional 1.
    pub fn force_unit(&self) -> f64 {
        let per_thickness = self.modulus * self.length;
        if self.axisymmetric {
            per_thickness * self.length
        } else {
            per_thickness
        }
    }
    pub fn force(&self, f: f64) -> f64 {
        f * self.force_unit()
    }
    /// A row's weight: its tributary length, or area in axisymmetry.
    pub fn weight(&self, w: f64) -> f64 {
        self.force(w) / self.modulus
    }
    pub fn moment(&self, m: f64) -> f64 {
        m * self.modulus * self.length * self.length
    }
}
