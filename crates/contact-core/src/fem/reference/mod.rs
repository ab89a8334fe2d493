//! The element seam: a reference element is its shape functions N_i(ξ) on a
//! reference cell, their reference gradients ∂N_i/∂ξ, a quadrature rule and
//! its faces. The isoparametric map x(ξ) = Σ N_i(ξ) x_i has the Jacobian
//! J_rc = ∂x_c/∂ξ_r = Σ_i ∂N_i/∂ξ_r x_ic, and the physical gradients are
//! ∇_x N_i = J⁻¹ ∇_ξ N_i. Kernels are generic over the element (dimension D
//! and node count N as const parameters), so each element compiles to its
//! own fixed-size loops: no heap and no runtime node count per element.
//!
//! Faces list local nodes, corners first (in an order whose right-hand
//! normal points out of the element: in 2D the element lies left of the
//! edge a → b), then the midside nodes of the face's edges in that order
//! (corner 0–1, 1–2, 2–0), so that a T10's face is a T6 of this module and
//! a T6's edge a quadratic line with its middle node last.

pub mod tetrahedron;
pub mod triangle;

pub use tetrahedron::{T10, T4};
pub use triangle::{T3, T6};

/// A quadrature point: reference coordinates and weight (the weights of a
/// rule sum to the reference cell's measure: ½ for the triangle, ⅙ for the
/// tetrahedron).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point<const D: usize> {
    pub xi: [f64; D],
    pub weight: f64,
}

/// The point at `xi` of weight `weight` (for the rules' tables).
pub const fn point<const D: usize>(xi: [f64; D], weight: f64) -> Point<D> {
    Point { xi, weight }
}

/// A reference element of dimension D with N nodes.
pub trait ReferenceElement<const D: usize, const N: usize> {
    /// The rule of the stiffness: exact for Bᵀ D B on an affine element.
    const RULE: &'static [Point<D>];
    /// Local nodes of each face (edges in 2D), as in the module doc.
    const FACES: &'static [&'static [usize]];

    /// N_i(ξ) and ∂N_i/∂ξ (row i: the gradient of node i's function).
    fn evaluate(xi: &[f64; D]) -> ([f64; N], [[f64; D]; N]);
}

/// det J and the physical gradients ∇_x N_i of the element with nodes `x`
/// from the reference gradients `g` (det J ≤ 0: a folded element).
#[inline(always)]
pub fn physical_gradients<const D: usize, const N: usize>(
    x: &[[f64; D]; N],
    g: &[[f64; D]; N],
) -> (f64, [[f64; D]; N]) {
    let mut j = [[0.0; D]; D];
    for i in 0..N {
        for r in 0..D {
            for c in 0..D {
                j[r][c] += g[i][r] * x[i][c];
            }
        }
    }
    let mut out = [[0.0; D]; N];
    if D == 2 {
        // Written as the 2D kernels always had it (the recorded replies
        // compare to 1e-12; this keeps them bit for bit).
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let inv = 1.0 / det;
        for i in 0..N {
            out[i][0] = inv * (j[1][1] * g[i][0] - j[0][1] * g[i][1]);
            out[i][1] = inv * (-j[1][0] * g[i][0] + j[0][0] * g[i][1]);
        }
        (det, out)
    } else {
        debug_assert_eq!(D, 3);
        // J⁻¹ = adj(J) / det J, adj(J)_rc the cofactor of J_cr.
        let cof = |r: usize, c: usize| {
            let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
            j[r1][c1] * j[r2][c2] - j[r1][c2] * j[r2][c1]
        };
        let det = j[0][0] * cof(0, 0) + j[0][1] * cof(0, 1) + j[0][2] * cof(0, 2);
        let inv = 1.0 / det;
        let mut jinv = [[0.0; D]; D];
        for (r, row) in jinv.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = inv * cof(c, r);
            }
        }
        for i in 0..N {
            for r in 0..D {
                out[i][r] = (0..D).map(|c| jinv[r][c] * g[i][c]).sum();
            }
        }
        (det, out)
    }
}

#[cfg(test)]
pub(crate) mod checks;
