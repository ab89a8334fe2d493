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

/// A rigid flat punch of half-width 1 pressed by P = 1 (no tangential load, no
/// moment) into an elastic half-plane with Coulomb friction μ, the dissimilar
/// materials coupled by the second Dundurs constant β (Spence 1973's problem):
/// the stick zone's half-width c and the pressure and shear on the panels.
#[derive(Debug, Clone)]
pub struct FlatPunchWithFriction {
    /// Stick half-width over the punch half-width: where the slip just
    /// beyond the stick run vanishes, interpolated between the two runs
    /// that bracket it.
    pub c: f64,
    /// Half the distance between the ends of those two runs.
    pub c_resolution: f64,
    /// Panel midpoints, and the pressure and shear (on the half-plane, +x) on
    /// each panel.
    pub x: Vec<f64>,
    pub p: Vec<f64>,
    pub q: Vec<f64>,
}

/// Spence's frictional flat punch solved independently of the finite
/// elements, on the surface of a half-plane (plane strain, A = 2(1 − ν²)/E
/// scaled out): with p the pressure and q the shear on the surface (+x), the
/// surface displacements (u_z into the solid, u_x along +x) are, to a rigid
/// motion (Johnson, Contact Mechanics, eqs. 2.24–2.25, integrated once),
///
///   u_z / A = −(1/π) ∫ p(s) ln|x − s| ds + (β/2) ∫ q(s) sgn(x − s) ds,
///   u_x / A = −(1/π) ∫ q(s) ln|x − s| ds − (β/2) ∫ p(s) sgn(x − s) ds,
///
/// so a pressure alone pulls the surface inward (u_x′ = −β A p; the β q term
/// of u_z is its reciprocal, by Betti's theorem). Under the
/// flat punch u_z is one constant δ; where the surface sticks u_x is one
/// constant α (proportional loading from rest: the increments are the totals
/// scaled); where it slips q = μ p sgn(x), the friction on the half-plane
/// pointing outward against the inward slip. The load is P = ∫ p = 1 and
/// Q = ∫ q = 0. p and q are piecewise constant on `panels` panels graded
/// towards the punch's corners (x = −cos θ, θ uniform), collocated at the
/// panels' midpoints, the panel integrals of ln and sgn in closed form, and the
/// linear system solved by Gaussian elimination with partial pivoting. The
/// stick zone's end is where the slip just beyond it changes sign (see the
/// bisection below). The answer converges like 1/n (measured for β = 0.286,
/// μ = 0.3: c = 0.6819, 0.6855, 0.6873 at n = 100, 200, 400).
pub fn flat_punch_with_friction(beta: f64, mu: f64, panels: usize) -> FlatPunchWithFriction {
    use std::f64::consts::PI;
    let n = panels;
    let edge: Vec<f64> = (0..=n).map(|k| -(PI * k as f64 / n as f64).cos()).collect();
    let x: Vec<f64> = (0..n).map(|k| -(PI * (k as f64 + 0.5) / n as f64).cos()).collect();
    let h: Vec<f64> = (0..n).map(|k| edge[k + 1] - edge[k]).collect();
    // ∫ ln|x − s| ds over [s1, s2] = F(x − s1) − F(x − s2), F(t) = t ln|t| − t.
    let f = |t: f64| if t == 0.0 { 0.0 } else { t * t.abs().ln() - t };
    let log = |i: usize, j: usize| f(x[i] - edge[j]) - f(x[i] - edge[j + 1]);
    let sgn = |i: usize, j: usize| (x[i] - edge[j]).abs() - (x[i] - edge[j + 1]).abs();
    // Unknowns: p (n), q (n), δ, α.
    let solve_with = |stick: usize| -> (Vec<f64>, Vec<f64>) {
        let lo = (n - stick) / 2;
        let sticks = |i: usize| i >= lo && i < lo + stick;
        let m = 2 * n + 2;
        let mut a = vec![0.0; m * m];
        let mut b = vec![0.0; m];
        for i in 0..n {
            let row = &mut a[i * m..(i + 1) * m];
            for j in 0..n {
                row[j] = -log(i, j) / PI;
                row[n + j] = 0.5 * beta * sgn(i, j);
            }
            row[2 * n] = -1.0;
            let row = &mut a[(n + i) * m..(n + i + 1) * m];
            if sticks(i) {
                for j in 0..n {
                    row[n + j] = -log(i, j) / PI;
                    row[j] = -0.5 * beta * sgn(i, j);
                }
                row[2 * n + 1] = -1.0;
            } else {
                row[n + i] = 1.0;
                row[i] = -mu * x[i].signum();
            }
        }
        for j in 0..n {
            a[2 * n * m + j] = h[j];
            a[(2 * n + 1) * m + n + j] = h[j];
        }
        b[2 * n] = 1.0;
        let s = gauss(a, b, m);
        let p = s[..n].to_vec();
        (p, s[n..2 * n].to_vec())
    };
    // The surface's slip (relative to the punch, +x) on the first panel
    // right of a stick run of `stick` panels.
    let slip_beyond = |stick: usize| -> f64 {
        let (p, q) = solve_with(stick);
        let hi = (n - stick) / 2 + stick;
        let ux = |i: usize| -> f64 {
            (0..n)
                .map(|j| -log(i, j) / PI * q[j] - 0.5 * beta * sgn(i, j) * p[j])
                .sum()
        };
        ux(hi) - ux(hi - 1)
    };
    // Too short a stick run leaves slip zones that move outward, along the
    // friction (outward on the half-plane) instead of against it; too long a run needs |q| > μ p at
    // its ends, where the slip beyond turns inward. Bisect (over runs of the
    // parity of n) for the change of sign of the slip beyond the run.
    let (mut short, mut long) = (2 - n % 2, n - 2 + n % 2);
    assert!(
        slip_beyond(short) > 0.0 && slip_beyond(long) < 0.0,
        "no stick zone inside (β {beta}, μ {mu})"
    );
    while long - short > 2 {
        let mid = short + 2 * ((long - short) / 4).max(1);
        if slip_beyond(mid) > 0.0 {
            short = mid;
        } else {
            long = mid;
        }
    }
    // The stick zone ends where the slip beyond it vanishes: between the
    // run ends of the two bracketing runs, interpolated linearly in it.
    let end = |stick: usize| edge[(n - stick) / 2 + stick];
    let (s0, s1) = (slip_beyond(short), slip_beyond(long));
    let c = end(short) + (end(long) - end(short)) * s0 / (s0 - s1);
    let c_resolution = 0.5 * (end(long) - end(short));
    let (p, q) = solve_with(short);
    FlatPunchWithFriction {
        c,
        c_resolution,
        x,
        p,
        q,
    }
}

/// Solves the dense m × m system `a` (row-major) x = `b` by Gaussian
/// elimination with partial pivoting.
fn gauss(mut a: Vec<f64>, mut b: Vec<f64>, m: usize) -> Vec<f64> {
    for k in 0..m {
        let piv = (k..m)
            .max_by(|&i, &j| a[i * m + k].abs().total_cmp(&a[j * m + k].abs()))
            .unwrap();
        if piv != k {
            for j in 0..m {
                a.swap(k * m + j, piv * m + j);
            }
            b.swap(k, piv);
        }
        let d = a[k * m + k];
        for i in k + 1..m {
            let l = a[i * m + k] / d;
            if l != 0.0 {
                for j in k..m {
                    a[i * m + j] -= l * a[k * m + j];
                }
                b[i] -= l * b[k];
            }
        }
    }
    let mut x = vec![0.0; m];
    for k in (0..m).rev() {
        let s: f64 = (k + 1..m).map(|j| a[k * m + j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k * m + k];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The panel solution of Spence's punch is symmetric (p even, q odd: no
    /// tangential load), inside the cone where it sticks and on it where it
    /// slips, and its stick zone converges like 1/n (the differences between
    /// 50, 100 and 200 panels halve, to 20 %).
    #[test]
    fn flat_punch_with_friction_is_consistent() {
        let (beta, mu) = (0.4 / 1.4, 0.3);
        let c: Vec<f64> = [50, 100, 200]
            .iter()
            .map(|&n| {
                let r = flat_punch_with_friction(beta, mu, n);
                for i in 0..n {
                    let j = n - 1 - i;
                    assert!((r.p[i] - r.p[j]).abs() <= 1e-9 * r.p[i], "p not even at {}", r.x[i]);
                    assert!((r.q[i] + r.q[j]).abs() <= 1e-9 * r.p[i], "q not odd at {}", r.x[i]);
                    if r.x[i].abs() < r.c - r.c_resolution {
                        assert!(r.q[i].abs() <= mu * r.p[i], "outside the cone at {}", r.x[i]);
                    } else if r.x[i].abs() > r.c + r.c_resolution {
                        assert!((r.q[i] - mu * r.p[i] * r.x[i].signum()).abs() <= 1e-9 * r.p[i]);
                    }
                }
                r.c
            })
            .collect();
        let (d1, d2) = (c[1] - c[0], c[2] - c[1]);
        assert!(
            d1 > 0.0 && d2 > 0.0 && (d2 / d1 - 0.5).abs() < 0.1,
            "{c:?}: ratio {}",
            d2 / d1
        );
    }
}
