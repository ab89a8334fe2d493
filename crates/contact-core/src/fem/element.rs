//! T3/T6 kernels by the mesh's runtime `Order`, for the loads and the
//! post-processing (the stiffness is `kernel`'s, monomorphised per element):
//! shape functions, physical gradients, body loads and centroid values, all
//! from the triangles of `reference::triangle`. Kernels write into caller
//! buffers.

use super::constitutive::Constitutive;
use super::reference::{physical_gradients, ReferenceElement, T3, T6};
use crate::mesh::Order;

/// Where the tests check a T6 element's Jacobian: the 3-point rule's points,
/// the corners and the midsides (det J of a quadratic map is quadratic, so
/// these see a fold near any of them).
#[cfg(test)]
pub(crate) const T6_CHECK_POINTS: [[f64; 2]; 9] = [
    [1.0 / 6.0, 1.0 / 6.0],
    [2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0],
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// The isoparametric T6 map of the element with nodes `x` at (ξ, η): the
/// point and det J.
#[cfg(test)]
pub(crate) fn t6_map(x: &[[f64; 2]], xi: f64, eta: f64) -> ([f64; 2], f64) {
    let (n, g) = T6::evaluate(&[xi, eta]);
    let s = |f: &dyn Fn(usize) -> f64, c: usize| (0..6).map(|i| f(i) * x[i][c]).sum::<f64>();
    let (dxi, deta) = (|i: usize| g[i][0], |i: usize| g[i][1]);
    (
        [s(&|i| n[i], 0), s(&|i| n[i], 1)],
        s(&dxi, 0) * s(&deta, 1) - s(&dxi, 1) * s(&deta, 0),
    )
}

/// Physical gradients of the shape functions at (ξ, η); returns det J (≤ 0 means a folded element).
pub fn gradients(
    order: Order,
    x: &[[f64; 2]],
    xi: f64,
    eta: f64,
    n: &mut [f64; 6],
    dx: &mut [f64; 6],
    dy: &mut [f64; 6],
) -> f64 {
    fn of<E: ReferenceElement<2, K>, const K: usize>(
        x: &[[f64; 2]],
        p: [f64; 2],
        n: &mut [f64; 6],
        dx: &mut [f64; 6],
        dy: &mut [f64; 6],
    ) -> f64 {
        let x: &[[f64; 2]; K] = x[..K].try_into().expect("an element has its order's nodes");
        let (v, g) = E::evaluate(&p);
        let (det, grad) = physical_gradients(x, &g);
        n[..K].copy_from_slice(&v);
        for i in 0..K {
            dx[i] = grad[i][0];
            dy[i] = grad[i][1];
        }
        det
    }
    match order {
        Order::T3 => of::<T3, 3>(x, [xi, eta], n, dx, dy),
        Order::T6 => of::<T6, 6>(x, [xi, eta], n, dx, dy),
    }
}

pub fn order_len(order: Order) -> usize {
    order.nodes_per_element()
}

/// Consistent nodal forces of a body force b over the element (into `fe`, 2k
/// entries), with the measure of a point of the section (`Analysis::measure`:
/// 2πr for a body of revolution, 1 otherwise).
pub fn body_load(order: Order, x: &[[f64; 2]], b: [f64; 2], measure: &dyn Fn([f64; 2]) -> f64, fe: &mut [f64; 12]) {
    let k = order_len(order);
    fe[..2 * k].iter_mut().for_each(|v| *v = 0.0);
    let (mut n, mut dx, mut dy) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for q in &super::reference::triangle::RULE3 {
        let det = gradients(order, x, q.xi[0], q.xi[1], &mut n, &mut dx, &mut dy);
        let at = (0..k).fold([0.0; 2], |p, i| [p[0] + n[i] * x[i][0], p[1] + n[i] * x[i][1]]);
        let w = q.weight * det * measure(at);
        for i in 0..k {
            fe[2 * i] += w * n[i] * b[0];
            fe[2 * i + 1] += w * n[i] * b[1];
        }
    }
}

/// Displacement gradient at the centroid: [∂u_x/∂x, ∂u_x/∂y, ∂u_y/∂x, ∂u_y/∂y].
pub fn centroid_gradient(order: Order, x: &[[f64; 2]], ue: &[f64]) -> [f64; 4] {
    let k = order_len(order);
    let (mut n, mut dx, mut dy) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    gradients(order, x, 1.0 / 3.0, 1.0 / 3.0, &mut n, &mut dx, &mut dy);
    let mut g = [0.0; 4];
    for i in 0..k {
        g[0] += dx[i] * ue[2 * i];
        g[1] += dy[i] * ue[2 * i];
        g[2] += dx[i] * ue[2 * i + 1];
        g[3] += dy[i] * ue[2 * i + 1];
    }
    g
}

/// Centroid stress σ(ε) (xx, yy, xy) of `law` for the centroid strain of u_e.
pub fn centroid_stress(order: Order, x: &[[f64; 2]], law: &impl Constitutive<3>, ue: &[f64]) -> [f64; 3] {
    let g = centroid_gradient(order, x, ue);
    law.stress(&[g[0], g[3], g[1] + g[2]])
}

/// Edge shape functions at s ∈ [−1, 1] for nodes (a, [mid], b) and d/ds.
pub fn edge_shape(n_nodes: usize, s: f64) -> ([f64; 3], [f64; 3]) {
    if n_nodes == 2 {
        ([0.5 * (1.0 - s), 0.5 * (1.0 + s), 0.0], [-0.5, 0.5, 0.0])
    } else {
        (
            [0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)],
            [s - 0.5, -2.0 * s, s + 0.5],
        )
    }
}

/// 3-point Gauss–Legendre on [−1, 1] (exact to degree 5).
pub const GAUSS3: [[f64; 2]; 3] = [
    [-0.774_596_669_241_483_4, 5.0 / 9.0],
    [0.0, 8.0 / 9.0],
    [0.774_596_669_241_483_4, 5.0 / 9.0],
];
