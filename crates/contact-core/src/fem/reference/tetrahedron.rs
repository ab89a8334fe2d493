//! The tetrahedra T4 and T10 on the reference cell ξ, η, ζ ≥ 0,
//! ξ + η + ζ ≤ 1 (volume ⅙), with L0 = 1 − ξ − η − ζ, L1 = ξ, L2 = η,
//! L3 = ζ. T4: N_i = L_i. T10: corners N_i = L_i(2L_i − 1), midsides
//! N = 4 L_a L_b.
//!
//! Node order is Gmsh's (MSH 4.1, element type 11), the format the 3D meshes
//! will come in: corners 0..3, then the midsides of edges 0–1, 1–2, 2–0, 3–0,
//! 3–2, 3–1 (nodes 4..9).
//!
//! Rules: one point (degree 1) for T4's constant B; the 4-point rule of
//! degree 2 (points at a = (5 + 3√5)/20, b = (5 − √5)/20, weights 1/24) for
//! T10's linear B on an affine element. The 4-point rule is also exact for a
//! T4 consistent mass (N_i N_j, degree 2) and a T10 load of a constant body
//! force (N_i, degree 2); a T10 consistent mass (degree 4) would need a
//! larger rule.

use super::{point, Point, ReferenceElement};

/// The centroid rule (degree 1).
pub const TET1: [Point<3>; 1] = [point([0.25, 0.25, 0.25], 1.0 / 6.0)];

const A: f64 = 0.585_410_196_624_968_5;
const B: f64 = 0.138_196_601_125_010_5;

/// The symmetric 4-point rule (degree 2).
pub const TET4: [Point<3>; 4] = [
    point([B, B, B], 1.0 / 24.0),
    point([A, B, B], 1.0 / 24.0),
    point([B, A, B], 1.0 / 24.0),
    point([B, B, A], 1.0 / 24.0),
];

/// The corners (a, b) of the edge of each T10 midside node 4..9 (Gmsh order).
pub const T10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];

/// The 4-node linear tetrahedron.
#[derive(Debug, Clone, Copy)]
pub struct T4;

/// The 10-node quadratic tetrahedron (Gmsh node order).
#[derive(Debug, Clone, Copy)]
pub struct T10;

/// ∇_ξ L_i of the barycentric coordinates.
const DL: [[f64; 3]; 4] = [[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn barycentric(xi: &[f64; 3]) -> [f64; 4] {
    [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]]
}

impl ReferenceElement<3, 4> for T4 {
    const RULE: &'static [Point<3>] = &TET1;
    // Outward: the face opposite corner k, ordered so (b − a) × (c − a)
    // points away from k.
    const FACES: &'static [&'static [usize]] = &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]];

    #[inline(always)]
    fn evaluate(xi: &[f64; 3]) -> ([f64; 4], [[f64; 3]; 4]) {
        (barycentric(xi), DL)
    }
}

impl ReferenceElement<3, 10> for T10 {
    const RULE: &'static [Point<3>] = &TET4;
    // T4's faces, each followed by the midsides of its edges in face order.
    const FACES: &'static [&'static [usize]] = &[
        &[0, 2, 1, 6, 5, 4],
        &[0, 1, 3, 4, 9, 7],
        &[0, 3, 2, 7, 8, 6],
        &[1, 2, 3, 5, 8, 9],
    ];

    #[inline(always)]
    fn evaluate(xi: &[f64; 3]) -> ([f64; 10], [[f64; 3]; 10]) {
        let l = barycentric(xi);
        let mut n = [0.0; 10];
        let mut g = [[0.0; 3]; 10];
        for i in 0..4 {
            n[i] = l[i] * (2.0 * l[i] - 1.0);
            g[i] = DL[i].map(|d| (4.0 * l[i] - 1.0) * d);
        }
        for (k, [a, b]) in T10_EDGES.into_iter().enumerate() {
            n[4 + k] = 4.0 * l[a] * l[b];
            g[4 + k] = std::array::from_fn(|c| 4.0 * (l[a] * DL[b][c] + l[b] * DL[a][c]));
        }
        (n, g)
    }
}

#[cfg(test)]
mod tests {
    use super::super::checks;
    use super::*;

    const CORNERS: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

    fn t10_nodes() -> [[f64; 3]; 10] {
        let mid = |[a, b]: [usize; 2]| std::array::from_fn(|c| 0.5 * (CORNERS[a][c] + CORNERS[b][c]));
        std::array::from_fn(|i| if i < 4 { CORNERS[i] } else { mid(T10_EDGES[i - 4]) })
    }

    /// N_i(x_j) = δ_ij to 1e-15, Σ N_i = 1 and Σ ∇N_i = 0 to 1e-14.
    #[test]
    fn shape_functions_interpolate_and_sum_to_one() {
        checks::nodal::<T4, 3, 4>(&CORNERS);
        checks::nodal::<T10, 3, 10>(&t10_nodes());
    }

    #[test]
    fn gradients_match_finite_differences() {
        checks::gradients::<T4, 3, 4>(&[0.2, 0.3, 0.1]);
        checks::gradients::<T10, 3, 10>(&[0.2, 0.3, 0.1]);
    }

    /// Monomials ξ^a η^b ζ^c of degree ≤ p against a! b! c! / (a+b+c+3)!, to 1e-15.
    #[test]
    fn rules_are_exact_to_their_degree() {
        checks::exact::<3>(T4::RULE, 1);
        checks::exact::<3>(T10::RULE, 2);
        assert!((A - (5.0 + 3.0 * 5f64.sqrt()) / 20.0).abs() < 1e-16);
        assert!((B - (5.0 - 5f64.sqrt()) / 20.0).abs() < 1e-16);
    }

    #[test]
    fn faces_point_out_and_carry_their_midsides() {
        checks::faces::<T4, 3, 4>(&CORNERS);
        checks::faces::<T10, 3, 10>(&t10_nodes());
    }
}
