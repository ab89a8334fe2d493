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

/// Hertz's contact radius from pressed points (r², p²): p² = p0² (1 − r²/a²)
/// is a straight line in r², so the least-squares line through them meets
/// p² = 0 at r² = a²; a is returned (NaN with fewer than two points).
pub fn edge_fit(pressed: &[(f64, f64)]) -> f64 {
    let n = pressed.len() as f64;
    let (mx, my) = pressed.iter().fold((0.0, 0.0), |(x, y), q| (x + q.0 / n, y + q.1 / n));
    let sxy: f64 = pressed.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    let sxx: f64 = pressed.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let slope = sxy / sxx;
    ((slope * mx - my) / slope).sqrt()
}

/// Complete elliptic integrals of the first and second kinds, K(k) and E(k),
/// of modulus k ∈ [0, 1), by the arithmetic–geometric mean: with a₀ = 1,
/// b₀ = √(1 − k²), c₀ = k and a_{n+1} = (a_n + b_n)/2,
/// b_{n+1} = √(a_n b_n), c_{n+1} = (a_n − b_n)/2, K = π / (2 a_∞) and
/// E = K (1 − Σ 2^{n−1} c_n²) (Abramowitz & Stegun 17.6). The mean
/// converges quadratically: a few steps reach round-off.
pub fn elliptic_ke(k: f64) -> (f64, f64) {
    let (mut a, mut b, mut c) = (1.0f64, (1.0 - k * k).sqrt(), k);
    let (mut sum, mut pow) = (0.5 * c * c, 0.5);
    // Near convergence the two means can settle an ulp apart and swap
    // forever (k = 0.984375: |c| stays 1.1e-16 a): stop at 4 ulps, or after
    // 40 steps, far past the 5–6 quadratic convergence needs.
    for _ in 0..40 {
        if c.abs() <= 4.0 * f64::EPSILON * a {
            break;
        }
        let next = (0.5 * (a + b), (a * b).sqrt(), 0.5 * (a - b));
        (a, b, c) = next;
        pow *= 2.0;
        sum += pow * c * c;
    }
    let big_k = std::f64::consts::PI / (2.0 * a);
    (big_k, big_k * (1.0 - sum))
}

/// Hertz's elliptical contact (Johnson, Contact Mechanics §4.2): a rigid
/// body of principal relative radii R₁ ≥ R₂ (gap h = x²/2R₁ + y²/2R₂)
/// pressed by P on an elastic half-space of modulus E*.
#[derive(Debug, Clone, Copy)]
pub struct HertzEllipse {
    /// Semi-axis along the R₁ direction (the larger).
    pub a: f64,
    /// Semi-axis along the R₂ direction.
    pub b: f64,
    /// Peak pressure 3P / (2π a b).
    pub p0: f64,
    /// Eccentricity e = √(1 − b²/a²).
    pub e: f64,
}

/// Hertz's ellipse for the load P. With A = 1/2R₁ ≤ B = 1/2R₂ the
/// eccentricity solves (Johnson eqs. 4.39–4.40, with K, E of modulus e)
///
/// ```text
/// B/A = ((a/b)² E − K) / (K − E),   (a/b)² = 1 / (1 − e²),
/// ```
///
/// whose right side grows from 1 at e = 0 without bound as e → 1, so it is
/// found by bisection; then A = p₀ b (K − E) / (E* a² e²) with
/// P = (2/3) π a b p₀ gives a³ = 3 P (K − E) / (2π A E* e²). A circle
/// (R₁ = R₂) is `hertz_sphere`'s.
pub fn hertz_ellipse(p: f64, radii: [f64; 2], e_star: f64) -> HertzEllipse {
    let (r1, r2) = (radii[0].max(radii[1]), radii[0].min(radii[1]));
    if r1 == r2 {
        let (a, p0) = hertz_sphere(p, r1, e_star);
        return HertzEllipse { a, b: a, p0, e: 0.0 };
    }
    let (big_a, big_b) = (0.5 / r1, 0.5 / r2);
    let ratio = |e: f64| {
        let (k, ee) = elliptic_ke(e);
        (ee / (1.0 - e * e) - k) / (k - ee)
    };
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            break;
        }
        if ratio(mid) < big_b / big_a {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let e = 0.5 * (lo + hi);
    let (k, ee) = elliptic_ke(e);
    let a = (3.0 * p * (k - ee) / (2.0 * std::f64::consts::PI * big_a * e_star * e * e)).cbrt();
    let b = a * (1.0 - e * e).sqrt();
    HertzEllipse {
        a,
        b,
        p0: 3.0 * p / (2.0 * std::f64::consts::PI * a * b),
        e,
    }
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

    /// K and E at k² = ½ (the lemniscatic case: K = Γ(¼)²/(4√π),
    /// E = K/2 + π/(4K)), and the ellipse's limits: R₁ → R₂ gives the
    /// circle, and its semi-axes satisfy Johnson's B relation too,
    /// B = p₀ b ((a/b)² E − K) / (E* a² e²), to round-off.
    #[test]
    fn elliptic_integrals_and_hertz_ellipse() {
        let (k, e) = elliptic_ke(0.5f64.sqrt());
        let k_ref = 1.854_074_677_301_372;
        assert!((k - k_ref).abs() < 1e-14 && (e - (k_ref / 2.0 + std::f64::consts::PI / (4.0 * k_ref))).abs() < 1e-14);
        let near = hertz_ellipse(1.0, [1.0 + 1e-9, 1.0], 1.0);
        let (a, p0) = hertz_sphere(1.0, 1.0, 1.0);
        assert!(
            (near.a / a - 1.0).abs() < 1e-4 && (near.b / a - 1.0).abs() < 1e-4 && (near.p0 / p0 - 1.0).abs() < 1e-4
        );
        let h = hertz_ellipse(2.0, [3.0, 1.0], 5.0);
        let (kk, ee) = elliptic_ke(h.e);
        let big_b = h.p0 * h.b * (h.a * h.a / (h.b * h.b) * ee - kk) / (5.0 * h.a * h.a * h.e * h.e);
        assert!((big_b - 0.5).abs() < 1e-9, "B = {big_b}");
        assert!(h.b < h.a);
        // Legendre's relation E K' + E' K − K K' = π/2 (K', E' of the
        // complementary modulus), at moduli where the means once swapped an
        // ulp apart forever (0.984375), and a ratio of radii of 10 whose
        // bisection passes there.
        for m in [0.3, 0.984375, 0.999] {
            let ((k, e), (k1, e1)) = (elliptic_ke(m), elliptic_ke((1.0f64 - m * m).sqrt()));
            let legendre = e * k1 + e1 * k - k * k1;
            assert!(
                (legendre - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
                "{m}: {legendre}"
            );
        }
        let far = hertz_ellipse(1.0, [10.0, 1.0], 1.0);
        assert!(far.b < far.a && far.p0.is_finite());
    }

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
