//! The triangles T3 and T6 on the reference cell (ξ, η) ≥ 0, ξ + η ≤ 1, with
//! L1 = 1 − ξ − η, L2 = ξ, L3 = η. T3: N_i = L_i. T6: corners
//! N_i = L_i(2L_i − 1), midsides N4 = 4L1L2, N5 = 4L2L3, N6 = 4L3L1 (nodes 3,
//! 4, 5 on edges 0–1, 1–2, 2–0). One point is exact for T3's constant B; the
//! 3-point rule (degree 2) is exact for an affine T6 (B linear) and standard
//! for curved ones.

use super::{point, Point, ReferenceElement};

/// The centroid rule (degree 1).
pub const RULE1: [Point<2>; 1] = [point([1.0 / 3.0, 1.0 / 3.0], 0.5)];

/// The 3-point interior rule (degree 2).
pub const RULE3: [Point<2>; 3] = [
    point([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
    point([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
    point([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
];

const DA: f64 = 0.445_948_490_915_965;
const DB: f64 = 0.091_576_213_509_771;
const WA: f64 = 0.223_381_589_678_011 / 2.0;
const WB: f64 = 0.109_951_743_655_322 / 2.0;

/// Dunavant's 6-point rule (degree 4): for products of a quadratic shape
/// function with a linear one and a linear field (dual mortar rows on T6
/// faces, degree 3 or 4).
pub const RULE6: [Point<2>; 6] = [
    point([DA, DA], WA),
    point([1.0 - 2.0 * DA, DA], WA),
    point([DA, 1.0 - 2.0 * DA], WA),
    point([DB, DB], WB),
    point([1.0 - 2.0 * DB, DB], WB),
    point([DB, 1.0 - 2.0 * DB], WB),
];

/// The 3-node linear triangle.
#[derive(Debug, Clone, Copy)]
pub struct T3;

/// The 6-node quadratic triangle.
#[derive(Debug, Clone, Copy)]
pub struct T6;

impl ReferenceElement<2, 3> for T3 {
    const RULE: &'static [Point<2>] = &RULE1;
    const FACES: &'static [&'static [usize]] = &[&[0, 1], &[1, 2], &[2, 0]];

    #[inline(always)]
    fn evaluate(xi: &[f64; 2]) -> ([f64; 3], [[f64; 2]; 3]) {
        let l1 = 1.0 - xi[0] - xi[1];
        ([l1, xi[0], xi[1]], [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])
    }
}

impl ReferenceElement<2, 6> for T6 {
    const RULE: &'static [Point<2>] = &RULE3;
    const FACES: &'static [&'static [usize]] = &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]];

    #[inline(always)]
    fn evaluate(xi: &[f64; 2]) -> ([f64; 6], [[f64; 2]; 6]) {
        let (l2, l3) = (xi[0], xi[1]);
        let l1 = 1.0 - l2 - l3;
        let n = [
            l1 * (2.0 * l1 - 1.0),
            l2 * (2.0 * l2 - 1.0),
            l3 * (2.0 * l3 - 1.0),
            4.0 * l1 * l2,
            4.0 * l2 * l3,
            4.0 * l3 * l1,
        ];
        // dL1 = (−1, −1), dL2 = (1, 0), dL3 = (0, 1)
        let g = [
            [-(4.0 * l1 - 1.0), -(4.0 * l1 - 1.0)],
            [4.0 * l2 - 1.0, 0.0],
            [0.0, 4.0 * l3 - 1.0],
            [4.0 * (l1 - l2), -4.0 * l2],
            [4.0 * l3, 4.0 * l2],
            [-4.0 * l3, 4.0 * (l1 - l3)],
        ];
        (n, g)
    }
}

#[cfg(test)]
mod tests {
    use super::super::checks;
    use super::*;

    const NODES6: [[f64; 2]; 6] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]];

    #[test]
    fn shape_functions_interpolate_and_sum_to_one() {
        checks::nodal::<T3, 2, 3>(&[NODES6[0], NODES6[1], NODES6[2]]);
        checks::nodal::<T6, 2, 6>(&NODES6);
    }

    #[test]
    fn gradients_match_finite_differences() {
        checks::gradients::<T3, 2, 3>(&[0.2, 0.3]);
        checks::gradients::<T6, 2, 6>(&[0.2, 0.3]);
    }

    #[test]
    fn rules_are_exact_to_their_degree() {
        checks::exact::<2>(T3::RULE, 1);
        checks::exact::<2>(T6::RULE, 2);
        checks::exact::<2>(&RULE6, 4);
    }

    #[test]
    fn faces_are_the_edges_with_the_element_on_their_left() {
        checks::faces::<T3, 2, 3>(&[NODES6[0], NODES6[1], NODES6[2]]);
        checks::faces::<T6, 2, 6>(&NODES6);
    }
}
