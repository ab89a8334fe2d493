//! Isoparametric T3/T6 kernels. Kernels write into caller buffers.
//!
//! Reference triangle (ξ, η) with L1 = 1 − ξ − η, L2 = ξ, L3 = η. T3: N_i = L_i.
//! T6: corners N_i = L_i(2L_i − 1); midsides N4 = 4L1L2, N5 = 4L2L3, N6 = 4L3L1.
//! K_e = Σ_q w_q det J_q B_qᵀ D B_q. One point is exact for T3; the 3-point
//! rule (degree 2) is exact for affine T6 and standard for curved ones.

use crate::mesh::Order;

/// (ξ, η, weight) of the triangle rules; weights sum to the reference area 1/2.
pub(crate) const RULE1: [[f64; 3]; 1] = [[1.0 / 3.0, 1.0 / 3.0, 0.5]];
pub(crate) const RULE3: [[f64; 3]; 3] = [
    [1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
];

pub fn rule(order: Order) -> &'static [[f64; 3]] {
    match order {
        Order::T3 => &RULE1,
        Order::T6 => &RULE3,
    }
}

/// Shape functions and their reference derivatives at (ξ, η).
pub fn shape(order: Order, xi: f64, eta: f64, n: &mut [f64; 6], dxi: &mut [f64; 6], deta: &mut [f64; 6]) {
    let l1 = 1.0 - xi - eta;
    match order {
        Order::T3 => {
            *n = [l1, xi, eta, 0.0, 0.0, 0.0];
            *dxi = [-1.0, 1.0, 0.0, 0.0, 0.0, 0.0];
            *deta = [-1.0, 0.0, 1.0, 0.0, 0.0, 0.0];
        }
        Order::T6 => {
            let (l2, l3) = (xi, eta);
            *n = [
                l1 * (2.0 * l1 - 1.0),
                l2 * (2.0 * l2 - 1.0),
                l3 * (2.0 * l3 - 1.0),
                4.0 * l1 * l2,
                4.0 * l2 * l3,
                4.0 * l3 * l1,
            ];
            // dL1 = (−1, −1), dL2 = (1, 0), dL3 = (0, 1)
            *dxi = [
                -(4.0 * l1 - 1.0),
                4.0 * l2 - 1.0,
                0.0,
                4.0 * (l1 - l2),
                4.0 * l3,
                -4.0 * l3,
            ];
            *deta = [
                -(4.0 * l1 - 1.0),
                0.0,
                4.0 * l3 - 1.0,
                -4.0 * l2,
                4.0 * l2,
                4.0 * (l1 - l3),
            ];
        }
    }
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
    let k = order_len(order);
    let (mut dxi, mut deta) = ([0.0; 6], [0.0; 6]);
    shape(order, xi, eta, n, &mut dxi, &mut deta);
    let (mut j11, mut j12, mut j21, mut j22) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..k {
        j11 += dxi[i] * x[i][0];
        j12 += dxi[i] * x[i][1];
        j21 += deta[i] * x[i][0];
        j22 += deta[i] * x[i][1];
    }
    let det = j11 * j22 - j12 * j21;
    let inv = 1.0 / det;
    for i in 0..k {
        dx[i] = inv * (j22 * dxi[i] - j12 * deta[i]);
        dy[i] = inv * (-j21 * dxi[i] + j11 * deta[i]);
    }
    det
}

pub fn order_len(order: Order) -> usize {
    order.nodes_per_element()
}

/// Element stiffness (2k × 2k, row-major into `ke`), DOF order u0x, u0y, u1x, ...
pub fn stiffness(order: Order, x: &[[f64; 2]], d: &[[f64; 3]; 3], ke: &mut [f64; 144]) {
    let nd = 2 * order_len(order);
    ke[..nd * nd].iter_mut().for_each(|v| *v = 0.0);
    add_stiffness(order, x, d, rule(order), ke);
    symmetrize(nd, ke);
}

/// Selective reduced integration for nearly incompressible plane strain on T6:
/// the deviatoric part D − λ m mᵀ with the full 3-point rule, the volumetric
/// part λ m mᵀ (m = (1, 1, 0)) at the centroid only. This is the P2–P0 mixed
/// element with its constant pressure condensed out, which is inf-sup stable in
/// 2D: it does not lock, and the contact pressure does not oscillate, as ν → ½
/// (measured on Hertz at ν = 0.4999: node-to-node oscillation 0.51 of the peak
/// with full integration).
pub fn stiffness_selective(order: Order, x: &[[f64; 2]], d: &[[f64; 3]; 3], lambda: f64, ke: &mut [f64; 144]) {
    let nd = 2 * order_len(order);
    ke[..nd * nd].iter_mut().for_each(|v| *v = 0.0);
    let mut dev = *d;
    for row in dev.iter_mut().take(2) {
        for v in row.iter_mut().take(2) {
            *v -= lambda;
        }
    }
    let vol = [[lambda, lambda, 0.0], [lambda, lambda, 0.0], [0.0, 0.0, 0.0]];
    add_stiffness(order, x, &dev, rule(order), ke);
    add_stiffness(order, x, &vol, &RULE1, ke);
    symmetrize(nd, ke);
}

pub(crate) fn symmetrize(nd: usize, ke: &mut [f64; 144]) {
    for a in 0..nd {
        for b in 0..a {
            ke[a * nd + b] = ke[b * nd + a];
        }
    }
}

/// Adds Σ_q w_q det J_q B_qᵀ D B_q over `points` to the upper triangle of `ke`.
fn add_stiffness(order: Order, x: &[[f64; 2]], d: &[[f64; 3]; 3], points: &[[f64; 3]], ke: &mut [f64; 144]) {
    let k = order_len(order);
    let nd = 2 * k;
    let (mut n, mut dx, mut dy) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for q in points {
        let det = gradients(order, x, q[0], q[1], &mut n, &mut dx, &mut dy);
        let w = q[2] * det;
        // DB columns for each DOF: B column of ux_i = (dx, 0, dy), of uy_i = (0, dy, dx).
        for a in 0..nd {
            let (ia, ca) = (a / 2, a % 2);
            let ba = if ca == 0 {
                [dx[ia], 0.0, dy[ia]]
            } else {
                [0.0, dy[ia], dx[ia]]
            };
            let dba = [
                d[0][0] * ba[0] + d[0][1] * ba[1] + d[0][2] * ba[2],
                d[1][0] * ba[0] + d[1][1] * ba[1] + d[1][2] * ba[2],
                d[2][0] * ba[0] + d[2][1] * ba[1] + d[2][2] * ba[2],
            ];
            for b in a..nd {
                let (ib, cb) = (b / 2, b % 2);
                let bb = if cb == 0 {
                    [dx[ib], 0.0, dy[ib]]
                } else {
                    [0.0, dy[ib], dx[ib]]
                };
                ke[a * nd + b] += w * (bb[0] * dba[0] + bb[1] * dba[1] + bb[2] * dba[2]);
            }
        }
    }
}

/// Consistent nodal forces of a body force b over the element (into `fe`, 2k
/// entries), with the measure of a point of the section (`Analysis::measure`:
/// 2πr for a body of revolution, 1 otherwise).
pub fn body_load(order: Order, x: &[[f64; 2]], b: [f64; 2], measure: &dyn Fn([f64; 2]) -> f64, fe: &mut [f64; 12]) {
    let k = order_len(order);
    fe[..2 * k].iter_mut().for_each(|v| *v = 0.0);
    let (mut n, mut dx, mut dy) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for q in &RULE3 {
        let det = gradients(order, x, q[0], q[1], &mut n, &mut dx, &mut dy);
        let at = (0..k).fold([0.0; 2], |p, i| [p[0] + n[i] * x[i][0], p[1] + n[i] * x[i][1]]);
        let w = q[2] * det * measure(at);
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

/// Centroid stress σ = D B u_e (xx, yy, xy).
pub fn centroid_stress(order: Order, x: &[[f64; 2]], d: &[[f64; 3]; 3], ue: &[f64]) -> [f64; 3] {
    let g = centroid_gradient(order, x, ue);
    let eps = [g[0], g[3], g[1] + g[2]];
    [
        d[0][0] * eps[0] + d[0][1] * eps[1] + d[0][2] * eps[2],
        d[1][0] * eps[0] + d[1][1] * eps[1] + d[1][2] * eps[2],
        d[2][0] * eps[0] + d[2][1] * eps[1] + d[2][2] * eps[2],
    ]
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
