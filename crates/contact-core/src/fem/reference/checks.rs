//! Checks every reference element passes, shared by their tests.

use super::{Point, ReferenceElement};

/// N_i(x_j) = δ_ij at the reference nodes `x` (to 1e-15), Σ N_i = 1 and
/// Σ ∇N_i = 0 there and at an interior point (to 1e-14).
pub fn nodal<E: ReferenceElement<D, N>, const D: usize, const N: usize>(x: &[[f64; D]; N]) {
    for (j, p) in x.iter().enumerate() {
        let (n, _) = E::evaluate(p);
        for (i, v) in n.iter().enumerate() {
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((v - want).abs() < 1e-15, "N_{i}(x_{j}) = {v}");
        }
    }
    let inside = [0.21, 0.17, 0.13];
    for p in x.iter().chain(std::iter::once(&std::array::from_fn(|c| inside[c]))) {
        let (n, g) = E::evaluate(p);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for c in 0..D {
            assert!(g.iter().map(|gi| gi[c]).sum::<f64>().abs() < 1e-14);
        }
    }
}

/// ∂N_i/∂ξ against central differences of N (h = 1e-6: the functions are
/// at most quadratic, so the difference is exact but for rounding, ~1e-10).
pub fn gradients<E: ReferenceElement<D, N>, const D: usize, const N: usize>(xi: &[f64; D]) {
    let (_, g) = E::evaluate(xi);
    let h = 1e-6;
    for r in 0..D {
        let (mut p, mut m) = (*xi, *xi);
        p[r] += h;
        m[r] -= h;
        let (np, nm) = (E::evaluate(&p).0, E::evaluate(&m).0);
        for i in 0..N {
            let fd = (np[i] - nm[i]) / (2.0 * h);
            assert!(
                (fd - g[i][r]).abs() < 1e-8,
                "node {i}, direction {r}: {fd} vs {}",
                g[i][r]
            );
        }
    }
}

/// The rule integrates every monomial ξ^a η^b (ζ^c) of degree ≤ `degree`
/// exactly over the reference simplex: a! b! c! / (a + b + c + D)!, to 1e-15.
pub fn exact<const D: usize>(rule: &[Point<D>], degree: u32) {
    let fact = |k: u32| (1..=k).map(f64::from).product::<f64>();
    let top = degree + 1;
    for a in 0..top {
        for b in 0..top {
            for c in 0..if D == 3 { top } else { 1 } {
                let p = [a, b, c];
                if a + b + c > degree {
                    continue;
                }
                let want = fact(a) * fact(b) * fact(c) / fact(a + b + c + D as u32);
                let got: f64 = rule
                    .iter()
                    .map(|q| q.weight * (0..D).map(|k| q.xi[k].powi(p[k] as i32)).product::<f64>())
                    .sum();
                assert!((got - want).abs() < 1e-15, "monomial {p:?}: {got} vs {want}");
            }
        }
    }
}

/// Each face's corners have the element on their inner side (left of a → b
/// in 2D; (b − a) × (c − a) pointing away in 3D), and its midside nodes lie
/// halfway along its edges in face order.
pub fn faces<E: ReferenceElement<D, N>, const D: usize, const N: usize>(x: &[[f64; D]; N]) {
    let corners = D + 1;
    let centroid: [f64; D] = std::array::from_fn(|c| (0..corners).map(|i| x[i][c]).sum::<f64>() / corners as f64);
    assert_eq!(E::FACES.len(), corners);
    let sub = |p: [f64; D], q: [f64; D]| -> [f64; 3] { std::array::from_fn(|c| if c < D { p[c] - q[c] } else { 0.0 }) };
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    for face in E::FACES {
        let a = x[face[0]];
        let to_centroid = sub(centroid, a);
        if D == 2 {
            let t = sub(x[face[1]], a);
            assert!(t[0] * to_centroid[1] - t[1] * to_centroid[0] > 0.0, "{face:?}");
        } else {
            let n = cross(sub(x[face[1]], a), sub(x[face[2]], a));
            assert!(
                n[0] * to_centroid[0] + n[1] * to_centroid[1] + n[2] * to_centroid[2] < 0.0,
                "{face:?}"
            );
        }
        let k = D; // corners of a face
        for (m, &node) in face[k..].iter().enumerate() {
            let (p, q) = (x[face[m]], x[face[(m + 1) % k]]);
            for c in 0..D {
                assert!(
                    (x[node][c] - 0.5 * (p[c] + q[c])).abs() < 1e-15,
                    "{face:?}: node {node}"
                );
            }
        }
    }
}
