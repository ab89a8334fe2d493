//! Isoparametric T3/T6 kernels. Kernels write into caller buffers.
//!
//! Reference triangle (ξ, η) with L1 = 1 − ξ − η, L2 = ξ, L3 = η. T3: N_i = L_i.
//! T6: corners N_i = L_i(2L_i − 1); midsides N4 = 4L1L2, N5 = 4L2L3, N6 = 4L3L1.
//! K_e = Σ_q w_q det J_q B_qᵀ D B_q. One point is exact for T3; the 3-point
//! rule (degree 2) is exact for affine T6 and standard for curved ones.

use crate::mesh::Order;

/// (ξ, η, weight) of the triangle rules; weights sum to the reference area 1/2.
const RULE1: [[f64; 3]; 1] = [[1.0 / 3.0, 1.0 / 3.0, 0.5]];
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
    let (mut n, mut dxi, mut deta) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    shape(Order::T6, xi, eta, &mut n, &mut dxi, &mut deta);
    let s = |d: &[f64; 6], c: usize| (0..6).map(|i| d[i] * x[i][c]).sum::<f64>();
    (
        [s(&n, 0), s(&n, 1)],
        s(&dxi, 0) * s(&deta, 1) - s(&dxi, 1) * s(&deta, 0),
    )
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
    stiffness_of(order, x, d, plane_column, false, ke);
}

/// Selective integration for nearly incompressible plane strain on T6: the
/// deviatoric part D − λ m mᵀ with the full 3-point rule, the volumetric part
/// λ m mᵀ (m = (1, 1, 0)) on the element's mean dilatation θ̄ = ∫ div u dV / V
/// (B-bar, Nagtegaal, Parks & Rice 1974; Hughes 1980). This is the P2–P0 mixed
/// element with its constant pressure condensed out, which is inf-sup stable in
/// 2D: it does not lock, and the contact pressure does not oscillate, as ν → ½
/// (measured on Hertz at ν = 0.4999: node-to-node oscillation 0.51 of the peak
/// with full integration). On an affine T6 div u is linear, so θ̄ is its value
/// at the centroid, the one-point reduced rule.
pub fn stiffness_selective(order: Order, x: &[[f64; 2]], d: &[[f64; 3]; 3], lambda: f64, ke: &mut [f64; 144]) {
    selective_of(order, x, d, lambda, [1.0, 1.0, 0.0], plane_column, false, ke);
}

/// The S strains of one DOF a (component a % 2 of node a / 2) from the shape
/// functions, their x and y derivatives and the point's radius. A generic
/// parameter, not a fn pointer: the kernel inlines it in its inner loop.
pub(crate) trait Column<const S: usize>:
    Fn(usize, &[f64; 6], &[f64; 6], &[f64; 6], f64) -> [f64; S] + Copy
{
}
impl<const S: usize, F: Fn(usize, &[f64; 6], &[f64; 6], &[f64; 6], f64) -> [f64; S] + Copy> Column<S> for F {}

/// Plane strains (xx, yy, xy): u_x gives (∂x, 0, ∂y), u_y gives (0, ∂y, ∂x).
fn plane_column(a: usize, _n: &[f64; 6], dx: &[f64; 6], dy: &[f64; 6], _r: f64) -> [f64; 3] {
    let i = a / 2;
    if a.is_multiple_of(2) {
        [dx[i], 0.0, dy[i]]
    } else {
        [0.0, dy[i], dx[i]]
    }
}

/// Σ_q w_q det J_q Bᵀ D B over the element's rule, for strains `column`;
/// `ring`: the measure 2πr of a body of revolution.
pub(crate) fn stiffness_of<const S: usize>(
    order: Order,
    x: &[[f64; 2]],
    d: &[[f64; S]; S],
    column: impl Column<S>,
    ring: bool,
    ke: &mut [f64; 144],
) {
    let nd = 2 * order_len(order);
    ke[..nd * nd].iter_mut().for_each(|v| *v = 0.0);
    add_stiffness(order, x, d, rule(order), column, ring, ke);
    symmetrize(nd, ke);
}

/// The P2–P0 split of `stiffness_selective` for strains `column`, with m the
/// strains that change the volume: the deviatoric part over the element's
/// rule, the volumetric part by `add_mean_dilatation`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn selective_of<const S: usize>(
    order: Order,
    x: &[[f64; 2]],
    d: &[[f64; S]; S],
    lambda: f64,
    m: [f64; S],
    column: impl Column<S>,
    ring: bool,
    ke: &mut [f64; 144],
) {
    let nd = 2 * order_len(order);
    ke[..nd * nd].iter_mut().for_each(|v| *v = 0.0);
    add_stiffness(order, x, &deviatoric(d, lambda, m), rule(order), column, ring, ke);
    add_mean_dilatation(order, x, lambda, m, column, ring, ke);
    symmetrize(nd, ke);
}

/// D − λ m mᵀ: the part of D the P2–P0 element integrates with the full rule.
pub(crate) fn deviatoric<const S: usize>(d: &[[f64; S]; S], lambda: f64, m: [f64; S]) -> [[f64; S]; S] {
    std::array::from_fn(|i| std::array::from_fn(|j| d[i][j] - lambda * m[i] * m[j]))
}

/// Adds the volumetric stiffness λ V b̄ b̄ᵀ to the upper triangle of `ke`, with
/// b̄_a = ∫ m·B_a dV / V (θ̄ = b̄·u, the L2 projection of div u onto constants:
/// the P0 pressure's constraint) and V = ∫ dV, over the element's rule.
///
/// With `ring` dV = 2πr dA and div u = ∂u_r/∂r + u_r/r + ∂u_z/∂z: then m·B_a r
/// = r ∂N_a/∂r + N_a (or r ∂N_a/∂z) is quadratic on an affine T6, which the
/// 3-point rule integrates exactly. div u at the centroid is not θ̄ there: on
/// an element touching the axis r varies by O(1) of itself, so the error does
/// not shrink under refinement (measured on a ball on a flat at ν = 0.49:
/// pressure +5.5 % at r = 0 and −9.0 % at the next node at a/h = 11, +5.3 % and
/// −10.2 % at a/h = 85; with θ̄ within 0.14 % at both).
fn add_mean_dilatation<const S: usize>(
    order: Order,
    x: &[[f64; 2]],
    lambda: f64,
    m: [f64; S],
    column: impl Column<S>,
    ring: bool,
    ke: &mut [f64; 144],
) {
    let nd = 2 * order_len(order);
    let (bbar, volume) = mean_dilatation(order, x, m, column, ring);
    for a in 0..nd {
        for b in a..nd {
            ke[a * nd + b] += lambda * volume * bbar[a] * bbar[b];
        }
    }
}

/// b̄ (θ̄ = b̄·u_e) and the volume V of `add_mean_dilatation`.
pub(crate) fn mean_dilatation<const S: usize>(
    order: Order,
    x: &[[f64; 2]],
    m: [f64; S],
    column: impl Column<S>,
    ring: bool,
) -> ([f64; 12], f64) {
    let k = order_len(order);
    let nd = 2 * k;
    let (mut n, mut dx, mut dy) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    let mut bbar = [0.0; 12];
    let mut volume = 0.0;
    for q in rule(order) {
        let det = gradients(order, x, q[0], q[1], &mut n, &mut dx, &mut dy);
        let (w, r) = measure(k, x, &n, q[2] * det, ring);
        volume += w;
        for (a, b) in bbar.iter_mut().enumerate().take(nd) {
            *b += w * dot(&m, &column(a, &n, &dx, &dy, r));
        }
    }
    for b in bbar.iter_mut().take(nd) {
        *b /= volume;
    }
    (bbar, volume)
}

fn symmetrize(nd: usize, ke: &mut [f64; 144]) {
    for a in 0..nd {
        for b in 0..a {
            ke[a * nd + b] = ke[b * nd + a];
        }
    }
}

/// Adds Σ_q w_q det J_q B_qᵀ D B_q (times 2π r_q with `ring`) over `points` to
/// the upper triangle of `ke`.
fn add_stiffness<const S: usize>(
    order: Order,
    x: &[[f64; 2]],
    d: &[[f64; S]; S],
    points: &[[f64; 3]],
    column: impl Column<S>,
    ring: bool,
    ke: &mut [f64; 144],
) {
    let k = order_len(order);
    let nd = 2 * k;
    let (mut n, mut dx, mut dy) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for q in points {
        let det = gradients(order, x, q[0], q[1], &mut n, &mut dx, &mut dy);
        let (w, r) = measure(k, x, &n, q[2] * det, ring);
        for a in 0..nd {
            let ba = column(a, &n, &dx, &dy, r);
            let dba: [f64; S] = std::array::from_fn(|i| dot(&d[i], &ba));
            for b in a..nd {
                let bb = column(b, &n, &dx, &dy, r);
                ke[a * nd + b] += w * dot(&bb, &dba);
            }
        }
    }
}

/// (weight, radius) of a quadrature point of weight w·det J: times 2πr with
/// `ring` (r interpolated from the nodes' x), radius 1 otherwise.
fn measure(k: usize, x: &[[f64; 2]], n: &[f64; 6], w: f64, ring: bool) -> (f64, f64) {
    if ring {
        let r: f64 = (0..k).map(|i| n[i] * x[i][0]).sum();
        (w * std::f64::consts::TAU * r, r)
    } else {
        (w, 1.0)
    }
}

/// u · v summed from the first term on (the order the plane kernel always had).
fn dot<const S: usize>(u: &[f64; S], v: &[f64; S]) -> f64 {
    let mut s = u[0] * v[0];
    for i in 1..S {
        s += u[i] * v[i];
    }
    s
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
