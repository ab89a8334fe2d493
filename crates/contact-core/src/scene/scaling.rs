//! Nondimensionalization: x̂ = x / L, Ê = E / E₀. Then displacements scale by L,
//! stresses and pressures by E₀, forces per thickness by E₀·L (totals over the
//! circumference of a body of revolution by E₀·L²) and moments by E₀·L².

/// A number of the user's, for a message: the round trip through the
/// nondimensional scale (x / L · L) leaves noise in the last bits (−0.1 came
/// back as −0.09999999999999999), and a bound from an LP run to 1e-13 reads
/// 9.999999993 for 10; seven significant digits, printed in the shortest
/// form that reads back the same, say what the user wrote (`details` keep
/// the full values).
pub fn shown(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    // Below 1e-300 the power of ten would overflow: print it as it is.
    if x.abs() < 1e-300 {
        return format!("{x:e}");
    }
    // Dividing an integer by an exact power of ten rounds once, correctly.
    let digits = 6 - x.abs().log10().floor() as i32;
    let v = if digits >= 0 {
        let p = 10f64.powi(digits);
        (x * p).round() / p
    } else {
        let p = 10f64.powi(-digits);
        (x / p).round() * p
    };
    if (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

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

#[cfg(test)]
mod tests {
    use super::shown;

    #[test]
    fn a_number_comes_back_as_the_user_wrote_it() {
        let l = 1.1;
        assert_eq!(shown(-0.1 / l * l), "-0.1");
        assert_eq!(shown(-0.825 / 3.7 * 3.7), "-0.825");
        assert_eq!(shown(2.0e9 / 7.0 * 7.0), "2e9");
        assert_eq!(shown(1.5e-7 / 3.0 * 3.0), "1.5e-7");
        assert_eq!(shown(12.34), "12.34");
        assert_eq!(shown(9.999_999_993), "10");
        assert_eq!(shown(0.0), "0");
    }
}
