//! Equilibrated tractions and the admissible stress on straight-sided
//! quadratic triangles (T6), by the node systems of `equilibrate` with
//! quadratic test functions.
//!
//! Galerkin orthogonality holds for every P2 shape function φ_i, so on each
//! element K the rows R_K(φ_i) = ∫_K σ_h : ε(φ_i) − ∫_K f φ_i must equal
//! Σ_Γ η_KΓ ∫_Γ t̂_Γ φ_i ds for all six nodes. A midside node's function
//! vanishes on K's other two sides: its condition concerns its side alone,
//! whose moment against it is then the two elements' rows (they agree, up to
//! the solver's residual, where the node is free: their mean is taken) or
//! the data on a boundary side. A corner's function gives node systems of
//! exactly the linear triangles' structure (the unknowns each side's moment
//! against it), solved by `equilibrate::node_systems`. Each sought side's
//! traction is then linear on each half, continuous at the midpoint: three
//! values per component, fixed by its three moments (`from_moments`). A
//! given side's is its data as they are, linear on each half with a jump at
//! the midpoint allowed (a punch's corner on the midside node, where p*
//! keeps the node's pressure on the half it faces and vanishes past it):
//! the node systems balance its moments (`half_moments`), and `split`
//! carries each half-side's traction alone, so τ n is the data exactly,
//! jump included (no projection onto a continuous trace). The P2 functions
//! sum to 1 and reproduce x, so each element is in equilibrium under its
//! sides' tractions, and `split` carries them with an admissible stress.
//!
//! An element's midside nodes must be at its sides' midpoints (affine
//! elements: σ_h linear on K, and the quadrature below exact): `unsupported`
//! refuses curved ones.
//!
//! The P2–P0 element (T6 at ν ≥ 0.45 in plane strain,
//! `fem::kernel::Integration::MeanDilatation`) is orthogonal for the stress
//! it integrates, σ̃_h = D ε(u_h) − λ m (tr ε(u_h) − θ̄_K), not for D ε(u_h):
//! its rows R_K(φ_i) are made of σ̃_h (`element_stress`; still linear on K,
//! so the three-point rule stays exact). Prager–Synge asks nothing of how
//! u_h was found, only that it is admissible: the stress compared with the
//! equilibrated one stays the true D ε(v), and ‖u − u_h‖_E is the true
//! energy's. That energy holds λ ‖tr ε(u_h) − θ̄‖², which the P2–P0 element
//! leaves free (its pressure λ θ̄ does not lock, its displacement
//! converges): the true error, and the bound with it, grows like √λ as
//! ν → ½ (the T6 Hertz block of the test `energy_bound`: relative bound
//! 0.194 at ν = 0.49 and 0.538 at 0.499, the absolute ones' ratio 3.23
//! where √λ's is 3.18, effectivity 1.02–1.04 against the twice-refined
//! answer's true error).
//!
//! Length: about 740 lines, 310 of them the patch tests (full rule,
//! P2–P0, a jump at a midside node) and the half-sides' moments; the rows,
//! the sides' tractions and the four-split stress of an element share its
//! geometry and belong together.

use super::equilibrate::{
    given_at, given_moments, mean_over_areas, node_systems, particular_stress, Bound, Given3, Input, Numbering, NONE,
};
use super::patch::{Patches, Residual, SHARE};
use super::split;
use crate::mesh::Order;
use crate::model::Model;
use std::collections::HashSet;

/// Why a scene with quadratic triangles is out of the bound's reach, if it
/// is: the T6 stress of this module is built on affine elements (Galerkin
/// orthogonality for every P2 function, of the full rule's stress or the
/// P2–P0 element's); what else a scene must be (one body per contact, no
/// friction, rigid obstacles, punches or Winkler beds) is `energy::unsupported`'s.
pub(super) fn unsupported(model: &Model) -> Option<&'static str> {
    if model.meshes.iter().all(|m| m.order == Order::T3) {
        return None;
    }
    // A midside node off its side's midpoint by more than round-off makes
    // the element's map quadratic, and σ_h no longer linear on it.
    const STRAIGHT: f64 = 1e-9;
    for m in model.meshes.iter().filter(|m| m.order == Order::T6) {
        for k in 0..m.n_elems() {
            let e = m.elem(k);
            for j in 0..3 {
                let (a, b, mid) = (m.nodes[e[j]], m.nodes[e[(j + 1) % 3]], m.nodes[e[3 + j]]);
                let l = (b[0] - a[0]).hypot(b[1] - a[1]);
                let off = (mid[0] - 0.5 * (a[0] + b[0])).hypot(mid[1] - 0.5 * (a[1] + b[1]));
                if off > STRAIGHT * l {
                    return Some("curved quadratic sides are not in the bound yet");
                }
            }
        }
    }
    None
}

/// The P2 functions of a side at parameter t (first end, middle, second
/// end): the values along it of a quadratic side's nodal field.
pub fn along_side(t: f64) -> [f64; 3] {
    [(1.0 - t) * (1.0 - 2.0 * t), 4.0 * t * (1.0 - t), t * (2.0 * t - 1.0)]
}

/// ∫_Γ t φ_i ds for the P2 functions of a side (first end, middle,
/// second end) against a traction linear on each half with its own values
/// at the middle (`t` = first end, middle from the first half, middle from
/// the second half, second end; a jump where the two differ):
/// [7 3 −1 −1; 6 10 10 6; −1 −1 3 7] / 48, each half the exact integral of
/// a quadratic times a linear function. Continuous at the middle, the two
/// middle columns add to [7 2 −1; 6 20 6; −1 2 7] / 48.
pub fn half_moments(l: f64, t: [f64; 4]) -> [f64; 3] {
    [
        l * (7.0 * t[0] + 3.0 * t[1] - t[2] - t[3]) / 48.0,
        l * (6.0 * t[0] + 10.0 * t[1] + 10.0 * t[2] + 6.0 * t[3]) / 48.0,
        l * (-t[0] - t[1] + 3.0 * t[2] + 7.0 * t[3]) / 48.0,
    ]
}

/// The traction values at a side's first end, middle and second end whose
/// `half_moments`, continuous at the middle, are `b` (their inverse).
pub fn from_moments(l: f64, b: [f64; 3]) -> [f64; 3] {
    [
        (8.0 * b[0] - b[1] + 2.0 * b[2]) / l,
        (-3.0 * b[0] + 3.0 * b[1] - 3.0 * b[2]) / l,
        (2.0 * b[0] - b[1] + 8.0 * b[2]) / l,
    ]
}

/// One component of a side's traction, `Given`'s four values in the side's
/// own order: a given component's data as they are, which may jump at the
/// middle (a punch's corner on the midside node, `energy::Mid`): the
/// four-split stress carries each half alone (`split`), and the data's
/// moments are the ones the node systems balanced (`half_moments`). A
/// sought one (`data` None) is continuous there, fixed by its three
/// moments `b`.
fn side_values(data: Option<[f64; 4]>, l: f64, b: [f64; 3]) -> [f64; 4] {
    match data {
        Some(data) => data,
        None => {
            let [x, y, z] = from_moments(l, b);
            [x, y, y, z]
        }
    }
}

/// Counter-clockwise corners, the midside nodes in the same order (mid j
/// between corners j and j + 1), the barycentric gradients ∇L_j and the
/// area.
type Geometry = ([usize; 3], [usize; 3], [[f64; 2]; 3], f64);

fn geometry(nodes: &[[f64; 2]], e: [usize; 6]) -> Geometry {
    let [a, b, c, ab, bc, ca] = e;
    let (pa, pb, pc) = (nodes[a], nodes[b], nodes[c]);
    let det = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pc[0] - pa[0]) * (pb[1] - pa[1]);
    let (k, m) = if det >= 0.0 {
        ([a, b, c], [ab, bc, ca])
    } else {
        ([a, c, b], [ca, bc, ab])
    };
    let p = [nodes[k[0]], nodes[k[1]], nodes[k[2]]];
    let two_a = det.abs();
    let grads = std::array::from_fn(|i| {
        let (j, l) = ((i + 1) % 3, (i + 2) % 3);
        [(p[j][1] - p[l][1]) / two_a, (p[l][0] - p[j][0]) / two_a]
    });
    (k, m, grads, two_a / 2.0)
}

/// ∇ of the six P2 functions (corners, then midsides) at barycentric `l`.
fn p2_gradients(g: &[[f64; 2]; 3], l: [f64; 3]) -> [[f64; 2]; 6] {
    std::array::from_fn(|n| {
        if n < 3 {
            let s = 4.0 * l[n] - 1.0;
            [s * g[n][0], s * g[n][1]]
        } else {
            let (i, j) = (n - 3, (n - 2) % 3);
            [
                4.0 * (l[i] * g[j][0] + l[j] * g[i][0]),
                4.0 * (l[i] * g[j][1] + l[j] * g[i][1]),
            ]
        }
    })
}

/// ε (xx, yy, engineering xy) of `u` at barycentric `l` of the element
/// (`k` corners, `m` midsides).
fn strain_at(g: &[[f64; 2]; 3], k: [usize; 3], m: [usize; 3], l: [f64; 3], u: &[[f64; 2]]) -> [f64; 3] {
    let grads = p2_gradients(g, l);
    let mut eps = [0.0; 3];
    for (n, gr) in grads.iter().enumerate() {
        let un = u[if n < 3 { k[n] } else { m[n - 3] }];
        eps[0] += gr[0] * un[0];
        eps[1] += gr[1] * un[1];
        eps[2] += gr[1] * un[0] + gr[0] * un[1];
    }
    eps
}

/// σ = D ε of `u` at barycentric `l` of the element (`k` corners, `m`
/// midsides).
fn stress_at(
    d: &[[f64; 3]; 3],
    g: &[[f64; 2]; 3],
    k: [usize; 3],
    m: [usize; 3],
    l: [f64; 3],
    u: &[[f64; 2]],
) -> [f64; 3] {
    let eps = strain_at(g, k, m, l, u);
    std::array::from_fn(|r| (0..3).map(|c| d[r][c] * eps[c]).sum())
}

/// The stress the element itself uses for `u` at barycentric `l`, the one
/// its rows (and Galerkin orthogonality) are made of: D ε with the full
/// rule; on the P2–P0 element (`mean_dilatation` = Some(λ),
/// `fem::kernel::Integration::MeanDilatation`) D ε − λ m (tr ε − θ̄), the
/// deviatoric part of D ε plus λ times the mean dilatation θ̄ (D = D_dev +
/// λ m mᵀ, m = (1, 1, 0)). tr ε is linear on an affine T6, so θ̄ is its
/// value at the centroid (the kernel's three-point mean is that exactly).
#[allow(clippy::too_many_arguments)]
fn element_stress(
    d: &[[f64; 3]; 3],
    mean_dilatation: Option<f64>,
    g: &[[f64; 2]; 3],
    k: [usize; 3],
    m: [usize; 3],
    l: [f64; 3],
    u: &[[f64; 2]],
) -> [f64; 3] {
    let mut s = stress_at(d, g, k, m, l, u);
    if let Some(lambda) = mean_dilatation {
        let trace = |l: [f64; 3]| {
            let e = strain_at(g, k, m, l, u);
            e[0] + e[1]
        };
        let excess = lambda * (trace(l) - trace([1.0 / 3.0; 3]));
        s[0] -= excess;
        s[1] -= excess;
    }
    s
}

/// ∫_K σ_h : ε(φ_i) for the six P2 functions (corners, then midsides), σ_h
/// the element's own stress (`element_stress`): linear on K, so the
/// three-point rule at the side midpoints (weights |K|/3, exact for
/// quadratics) integrates it exactly. These are K_e u_e, the element's part
/// of the finite element equations.
#[allow(clippy::too_many_arguments)]
fn element_rows(
    d: &[[f64; 3]; 3],
    mean_dilatation: Option<f64>,
    g: &[[f64; 2]; 3],
    k: [usize; 3],
    m: [usize; 3],
    area: f64,
    u: &[[f64; 2]],
) -> [[f64; 2]; 6] {
    let mut r6 = [[0.0; 2]; 6];
    for l in MIDPOINT {
        let s = element_stress(d, mean_dilatation, g, k, m, l, u);
        for (n, gr) in p2_gradients(g, l).iter().enumerate() {
            let t = traction(s, *gr);
            for c in 0..2 {
                r6[n][c] += area / 3.0 * t[c];
            }
        }
    }
    r6
}

/// Barycentric coordinates of corner i and of the side midpoints.
const CORNER: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const MIDPOINT: [[f64; 3]; 3] = [[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5]];

fn traction(s: [f64; 3], n: [f64; 2]) -> [f64; 2] {
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}

/// The admissible stress's distance to σ(u_cmp), element by element, on
/// straight-sided quadratic triangles; None for a degenerate element.
pub fn bound(inp: &Input<6>) -> Option<Bound> {
    let ne = inp.elems.len();
    let f = inp.body_force;
    let d = &inp.d;
    let mut corners: Vec<[u32; 3]> = Vec::with_capacity(ne);
    let mut rows: Vec<[[f64; 2]; 3]> = Vec::with_capacity(ne);
    let mut mid_rows: Vec<[[f64; 2]; 3]> = Vec::with_capacity(ne);
    let mut smooth = vec![[0.0; 3]; inp.nodes.len()];
    let mut weight = vec![0.0; inp.nodes.len()];
    for &e in inp.elems {
        let (k, m, g, area) = geometry(inp.nodes, e);
        if area <= 0.0 {
            return None;
        }
        // σ_h is linear on K: its values at the corners (for the nodal
        // average) and at the side midpoints, where the three-point rule
        // (weights |K|/3, exact for quadratics) integrates σ_h : ε(φ_i).
        // σ_h is the element's own stress (on the P2–P0 element not D ε):
        // the rows must be the finite element equations u_eq meets.
        let at = |l: [f64; 3]| element_stress(d, inp.mean_dilatation, &g, k, m, l, inp.u_eq);
        for (i, &n) in k.iter().enumerate() {
            let s = at(CORNER[i]);
            for r in 0..3 {
                smooth[n][r] += area * s[r];
            }
            weight[n] += area;
        }
        let mut r6 = element_rows(d, inp.mean_dilatation, &g, k, m, area, inp.u_eq);
        // ∫_K φ_i: 0 at a corner, |K|/3 at a midside node.
        for row in r6.iter_mut().skip(3) {
            for c in 0..2 {
                row[c] -= f[c] * area / 3.0;
            }
        }
        rows.push([r6[0], r6[1], r6[2]]);
        mid_rows.push([r6[3], r6[4], r6[5]]);
        corners.push(k.map(|n| n as u32));
    }
    mean_over_areas(&mut smooth, &weight);
    let num = Numbering::new(inp.nodes, &corners);
    let (sides, elem_sides) = (&num.sides, &num.elem_sides);
    // Moments against the corners' functions (proj) and the midside one
    // (mid), in each side's own orientation.
    // Given sides take their data's moments; elsewhere the midside moment
    // is the two elements' rows' (their mean: they agree by orthogonality).
    let Given3 {
        mut proj,
        mut mid,
        sought,
    } = given_moments(sides, inp.given, half_moments);
    for (k, es) in elem_sides.iter().enumerate() {
        for (j, &id) in es.iter().enumerate() {
            let eta = num.sign(id, k);
            let share = if sides[id].elems[1] == NONE { 1.0 } else { 0.5 };
            for c in (0..2).filter(|&c| sought[id][c]) {
                mid[id][c] += share * eta * mid_rows[k][j][c];
            }
        }
    }
    // A linear traction's moment against the P2 corner function is |Γ|/6
    // of its value at that corner, whatever it is at the other.
    node_systems(
        &num,
        &corners,
        &rows,
        &smooth,
        |l, near, _| l * near / 6.0,
        &sought,
        &mut proj,
    );
    let compliance = super::equilibrate::inverse3(inp.d);
    // The four sub-triangles of each element (`split`'s order: the corner
    // ones at k[0], k[1], k[2], then the middle one), the mesh of the
    // patches' HCT space, and its boundary half-sides with both components
    // held.
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(4 * ne);
    let mut held = HashSet::new();
    let mut residual: Vec<Residual> = Vec::with_capacity(4 * ne);
    let (mut closure, mut scale) = (0.0_f64, 0.0_f64);
    let mut norm2 = 0.0;
    for (kk, &elem) in inp.elems.iter().enumerate() {
        let (k, m, g, area) = geometry(inp.nodes, elem);
        let p = [inp.nodes[k[0]], inp.nodes[k[1]], inp.nodes[k[2]]];
        tris.extend([[k[0], m[0], m[2]], [m[0], k[1], m[1]], [m[2], m[1], k[2]], m].map(|t| t.map(|n| n as u32)));
        for (j, &id) in elem_sides[kk].iter().enumerate() {
            if sides[id].elems[1] == NONE && sought[id] == [true, true] {
                for [a, b] in [[k[j], m[j]], [m[j], k[(j + 1) % 3]]] {
                    held.insert([a.min(b), a.max(b)]);
                }
            }
        }
        for l in MIDPOINT {
            let s = stress_at(d, &g, k, m, l, inp.u_norm);
            let e = strain_at(&g, k, m, l, inp.u_norm);
            norm2 += area / 3.0 * (s[0] * e[0] + s[1] * e[1] + s[2] * e[2]);
        }
        let particular = particular_stress(f, &p);
        let mut t = [[[[0.0; 2]; 2]; 2]; 3];
        for j in 0..3 {
            let id = elem_sides[kk][j];
            let sd = &sides[id];
            let eta = num.sign(id, kk);
            let (a, b) = (p[j], p[(j + 1) % 3]);
            let xm = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            let n = [(b[1] - a[1]) / sd.len, -(b[0] - a[0]) / sd.len];
            // The side's four values per component (`Given`'s: the middle
            // once from each half), in K's order.
            let mut v = [[0.0; 2]; 4];
            for c in 0..2 {
                let data = if sought[id][c] {
                    None
                } else {
                    given_at(inp.given, sd, c)
                };
                let vals = side_values(data, sd.len, [proj[id][0][c], mid[id][c], proj[id][1][c]]);
                let vals = if sd.ends[0] == k[j] {
                    vals
                } else {
                    [vals[3], vals[2], vals[1], vals[0]]
                };
                for i in 0..4 {
                    v[i][c] = eta * vals[i];
                }
            }
            let pts = [a, xm, xm, b];
            let w: [[f64; 2]; 4] = std::array::from_fn(|i| {
                let sp = traction(particular(pts[i]), n);
                [v[i][0] - sp[0], v[i][1] - sp[1]]
            });
            t[j] = [[w[0], w[1]], [w[2], w[3]]];
        }
        // The stress compared is the true C ε(v) whatever the element
        // integrates: the theorem bounds the error in the true energy.
        let target: [[f64; 3]; 3] = std::array::from_fn(|i| {
            let s = stress_at(d, &g, k, m, CORNER[i], inp.u_cmp);
            let sp = particular(p[i]);
            std::array::from_fn(|r| s[r] - sp[r])
        });
        let out = split::stress(&p, &t, &target, &compliance)?;
        closure = closure.max(out.closure);
        scale = scale.max(out.scale);
        for s in target {
            scale = scale.max(s.iter().fold(0.0_f64, |a, v| a.max(v.abs())));
        }
        residual.extend(out.residual);
    }
    let sub_num = Numbering::new(inp.nodes, &tris);
    let mut patches = Patches::new(inp.nodes, &tris, &sub_num, compliance, &held, residual);
    patches.relax_largest(SHARE);
    // Each element's indicator is its four sub-triangles'.
    let indicators = (0..ne)
        .map(|k| (4 * k..4 * k + 4).map(|t| patches.energy(t)).sum())
        .collect();
    Some(Bound::new(indicators, closure, scale, norm2))
}

#[cfg(test)]
mod tests {
    use super::super::equilibrate::Given;
    use super::super::fixtures::plane_strain;
    use super::*;
    use std::collections::HashMap;

    /// The eight triangles of `fixtures::square_nodes` in both orientations,
    /// with their midside nodes appended.
    fn square_t6() -> (Vec<[f64; 2]>, Vec<[usize; 6]>) {
        let mut nodes = super::super::fixtures::square_nodes();
        let corners = [
            [0, 1, 4],
            [0, 3, 4],
            [1, 2, 5],
            [1, 4, 5],
            [3, 4, 7],
            [3, 7, 6],
            [4, 5, 8],
            [4, 8, 7],
        ];
        let mut mid: HashMap<[usize; 2], usize> = HashMap::new();
        let mut at = |a: usize, b: usize, nodes: &mut Vec<[f64; 2]>| {
            *mid.entry([a.min(b), a.max(b)]).or_insert_with(|| {
                nodes.push([0, 1].map(|c| (nodes[a][c] + nodes[b][c]) / 2.0));
                nodes.len() - 1
            })
        };
        let elems: Vec<[usize; 6]> = corners
            .iter()
            .map(|&[a, b, c]| {
                [
                    a,
                    b,
                    c,
                    at(a, b, &mut nodes),
                    at(b, c, &mut nodes),
                    at(c, a, &mut nodes),
                ]
            })
            .collect();
        (nodes, elems)
    }

    /// The bound of the quadratic displacement `u_at` (stress linear, its
    /// strain `strain` by hand) on the square, the body force f = −div σ and
    /// the boundary's tractions σ n taken from it (or its left side held):
    /// u is then its own finite element answer, and the bound must vanish to
    /// round-off, read against ‖u‖²_E. Returns the largest total and closure
    /// over both boundary conditions, relative.
    fn bound_of_exact_state(
        d: [[f64; 3]; 3],
        mean_dilatation: Option<f64>,
        u_at: impl Fn([f64; 2]) -> [f64; 2],
        strain: impl Fn([f64; 2]) -> [f64; 3],
    ) -> (f64, f64) {
        bound_with_jump(d, mean_dilatation, u_at, strain, 0.0, false)
    }

    /// `bound_of_exact_state` with `jump` × `JUMP` added to the vertical
    /// traction of the bottom's first side (from node 0 to node 1).
    fn bound_with_jump(
        d: [[f64; 3]; 3],
        mean_dilatation: Option<f64>,
        u_at: impl Fn([f64; 2]) -> [f64; 2],
        strain: impl Fn([f64; 2]) -> [f64; 3],
        jump: f64,
        flipped: bool,
    ) -> (f64, f64) {
        let (nodes, elems) = square_t6();
        let sigma = |x: [f64; 2]| -> [f64; 3] {
            let eps = strain(x);
            std::array::from_fn(|r| (0..3).map(|c| d[r][c] * eps[c]).sum())
        };
        // f = −div σ (σ is linear: its derivatives by differences are exact
        // up to round-off).
        let (s0, sx, sy) = (sigma([0.0, 0.0]), sigma([1.0, 0.0]), sigma([0.0, 1.0]));
        let f = [
            -((sx[0] - s0[0]) + (sy[2] - s0[2])),
            -((sx[2] - s0[2]) + (sy[1] - s0[1])),
        ];
        let u: Vec<[f64; 2]> = nodes.iter().map(|&x| u_at(x)).collect();
        let boundary = [[0, 1], [1, 2], [2, 5], [5, 8], [8, 7], [7, 6], [6, 3], [3, 0]];
        let (mut worst, mut closure) = (0.0_f64, 0.0_f64);
        for held in [false, true] {
            let mut given = HashMap::new();
            for [a, b] in boundary {
                let (pa, pb) = (nodes[a], nodes[b]);
                let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
                let n = [(pb[1] - pa[1]) / l, -(pb[0] - pa[0]) / l];
                let pm = [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0];
                let t = [pa, pm, pb].map(|x| traction(sigma(x), n));
                let on_left = pa[0] == 0.0 && pb[0] == 0.0;
                let traction = if held && on_left {
                    [None, None]
                } else {
                    [0, 1].map(|c| {
                        let extra = if [a, b] == [0, 1] && c == 1 { jump } else { 0.0 };
                        Some(std::array::from_fn(|i| {
                            [t[0], t[1], t[1], t[2]][i][c] + extra * JUMP[i]
                        }))
                    })
                };
                // The jumped side stored from its other end, its four values
                // reversed: the same traction.
                let (ends, traction) = if flipped && [a, b] == [0, 1] {
                    ([b, a], traction.map(|v| v.map(|[w, x, y, z]| [z, y, x, w])))
                } else {
                    ([a, b], traction)
                };
                given.insert([a.min(b), a.max(b)], Given { ends, traction });
            }
            let inp = Input {
                nodes: &nodes,
                elems: &elems,
                u_eq: &u,
                u_cmp: &u,
                u_norm: &u,
                d,
                body_force: f,
                given: &given,
                mean_dilatation,
            };
            let b = bound(&inp).expect("mesh");
            let total: f64 = b.indicators.iter().sum();
            worst = worst.max(total / b.norm2);
            closure = closure.max(b.closure);
        }
        (worst, closure)
    }

    /// A traction linear on each half with a jump at the middle whose
    /// moments against the three P2 functions all vanish (the null vector
    /// of `half_moments`' matrix): it carries no force and no moment, and
    /// no continuous traction shares its moments but 0.
    const JUMP: [f64; 4] = [1.0, -2.0, 2.0, -1.0];

    /// `half_moments` are the P2 functions' integrals against a traction
    /// linear on each half with a jump at the middle (Gauss–Legendre with
    /// two points on each half: exact for the cubic integrand), to
    /// round-off, and `JUMP` has none.
    #[test]
    fn half_side_moments_are_the_p2_functions_integrals() {
        let (l, t) = (1.7, [0.4, -1.3, 2.2, 0.9]);
        let g = 0.5 / 3.0_f64.sqrt();
        let mut want = [0.0; 3];
        for (start, [ta, tb]) in [(0.0, [t[0], t[1]]), (0.5, [t[2], t[3]])] {
            for q in [0.25 - g / 2.0, 0.25 + g / 2.0] {
                let s = start + q;
                let v = ta + (tb - ta) * (s - start) / 0.5;
                for (w, phi) in want.iter_mut().zip(along_side(s)) {
                    *w += l * 0.25 * v * phi;
                }
            }
        }
        let got = half_moments(l, t);
        for i in 0..3 {
            assert!((got[i] - want[i]).abs() < 1e-14, "{got:?} against {want:?}");
        }
        assert!(half_moments(l, JUMP).iter().all(|m| m.abs() < 1e-15));
    }

    /// A sought component's three moments give the continuous traction
    /// that has them (`from_moments` inverts `half_moments` continuous at
    /// the middle), to round-off.
    #[test]
    fn a_sought_traction_is_continuous_with_its_moments() {
        let l = 0.8;
        let got = side_values(None, l, half_moments(l, [0.3, 1.1, 1.1, 0.5]));
        let want = [0.3, 1.1, 1.1, 0.5];
        assert!((0..4).all(|i| (got[i] - want[i]).abs() < 1e-14), "{got:?}");
    }

    /// The patch test with a jump: `JUMP` added to one given side leaves
    /// every moment, so the answer, the node systems and the elements'
    /// balance as they are (closure at round-off), but the admissible
    /// stress must carry it exactly: its distance to σ(u) is no longer 0
    /// (measured 1.06e-2 of ‖u‖²_E for a jump of 1e-3, E = 2; a traction
    /// made continuous through its moments would lose it and read 0 to
    /// round-off, 1e-20 as in `a_linear_stress_has_a_zero_bound`, so the
    /// floor 1e-6 tells the two apart by four orders). The same side given
    /// from its other end, its values reversed, is the same traction: the
    /// bound must not move (to round-off) and the balance must still close.
    /// Reversing `JUMP` only flips its sign, which the squared bound cannot
    /// see; but the side's own traction varies along it (σ is linear), so
    /// a reversal that misplaces its values breaks the moments the node
    /// systems balanced and reads in `closure` (one that swapped the ends
    /// but not the middle values was tried: it fails here).
    #[test]
    fn a_traction_jump_at_a_midside_node_is_carried() {
        let u = |x: [f64; 2]| [1e-3 * x[0] * x[0] + 2e-4 * x[1], -3e-4 * x[1] * x[1] + 1e-4 * x[0]];
        let e = |x: [f64; 2]| [2e-3 * x[0], -6e-4 * x[1], 3e-4];
        let d = plane_strain(0.3).0;
        let (total, closure) = bound_with_jump(d, None, u, e, 1e-3, false);
        let (flipped, flipped_closure) = bound_with_jump(d, None, u, e, 1e-3, true);
        println!("jump: {total:e} of ‖u‖²_E, closure {closure:e}; given from the other end {flipped:e}");
        assert!(
            closure < 1e-10 && flipped_closure < 1e-10,
            "closure {closure}, {flipped_closure}"
        );
        assert!(total > 1e-6, "{total:e} of ‖u‖²_E");
        assert!(
            (flipped - total).abs() <= 1e-12 * total,
            "{flipped:e} against {total:e}"
        );
    }

    /// The patch test of quadratic triangles: a quadratic displacement has a
    /// linear stress, in equilibrium with a uniform body force f = −div σ
    /// and with its own tractions σ n, linear along every side (so the
    /// sides' data carry them exactly). It is then its own finite element
    /// answer, the equilibrated tractions are σ n and the four-split stress
    /// is σ: the bound vanishes to round-off, whether a side's traction is
    /// given or its displacement held, on a mesh of eight triangles in both
    /// orientations.
    #[test]
    fn a_linear_stress_has_a_zero_bound() {
        // u = (1e-3 x² − 4e-4 xy + 2e-4 y, −3e-4 y² + 5e-4 x² + 1e-4 x).
        let (total, closure) = bound_of_exact_state(
            plane_strain(0.3).0,
            None,
            |x| {
                [
                    1e-3 * x[0] * x[0] - 4e-4 * x[0] * x[1] + 2e-4 * x[1],
                    -3e-4 * x[1] * x[1] + 5e-4 * x[0] * x[0] + 1e-4 * x[0],
                ]
            },
            |x| [2e-3 * x[0] - 4e-4 * x[1], -6e-4 * x[1], 6e-4 * x[0] + 3e-4],
        );
        assert!(closure < 1e-10, "closure {closure}");
        assert!(total < 1e-20, "{total:e} of ‖u‖²_E");
    }

    /// The P2–P0 element's patch test: where tr ε is uniform on every
    /// element, its stress D ε − λ m (tr ε − θ̄) is D ε and the exact state
    /// is its answer: a uniform strain (every component) and a quadratic,
    /// divergence-free u = (x² + 2xy, −2xy − y²) + rigid motion, whose
    /// stress is linear. Its rows are then the full rule's and the bound
    /// vanishes, at ν = 0.49 and 0.499 (λ/μ = 49 and 499: C⁻¹'s volumetric
    /// part is 1/(λ + μ) against 1/μ, and round-off stays at the 1e-20 of
    /// the energy the full rule's test reads, relative to a stress whose
    /// volumetric part is λ times its strain).
    #[test]
    fn a_p2_p0_element_has_a_zero_bound_where_its_dilatation_is_uniform() {
        for nu in [0.49, 0.499] {
            let (d, lambda) = plane_strain(nu);
            let uniform = bound_of_exact_state(
                d,
                Some(lambda),
                |x| [1e-3 * x[0] + 3e-4 * x[1], -2e-4 * x[1] + 5e-4 * x[0]],
                |_| [1e-3, -2e-4, 8e-4],
            );
            let solenoidal = bound_of_exact_state(
                d,
                Some(lambda),
                |x| {
                    [
                        1e-3 * (x[0] * x[0] + 2.0 * x[0] * x[1]) + 1e-4 * x[1],
                        -1e-3 * (2.0 * x[0] * x[1] + x[1] * x[1]) - 1e-4 * x[0],
                    ]
                },
                |x| {
                    [
                        1e-3 * (2.0 * x[0] + 2.0 * x[1]),
                        -1e-3 * (2.0 * x[0] + 2.0 * x[1]),
                        1e-3 * (2.0 * x[0] - 2.0 * x[1]),
                    ]
                },
            );
            for (name, (total, closure)) in [("uniform", uniform), ("solenoidal", solenoidal)] {
                assert!(closure < 1e-10, "ν {nu} {name}: closure {closure}");
                assert!(total < 1e-20, "ν {nu} {name}: {total:e} of ‖u‖²_E");
            }
        }
    }

    /// The rows are the element's equations: on one affine T6 with a
    /// displacement whose dilatation varies within it (arbitrary nodal
    /// values), ∫ σ_h : ε(φ_i) equals K_e u_e of the assembly's kernel, with
    /// the full rule and as the P2–P0 element (ν 0.3 and 0.49), to the
    /// round-off of entries of size |K_e| |u_e|.
    #[test]
    fn the_rows_are_the_kernels_element_equations() {
        use crate::fem::constitutive::{LinearIsotropic, Section};
        use crate::fem::kernel::{stiffness, Integration, Plane};
        use crate::fem::reference::T6;
        let corners = [[0.1, -0.2], [1.3, 0.1], [0.4, 0.9]];
        let mid = |a: usize, b: usize| {
            [
                0.5 * (corners[a][0] + corners[b][0]),
                0.5 * (corners[a][1] + corners[b][1]),
            ]
        };
        let x = [corners[0], corners[1], corners[2], mid(0, 1), mid(1, 2), mid(2, 0)];
        let u: Vec<[f64; 2]> = (0..6)
            .map(|n| [0.3 * (n as f64).sin() - 0.1, 0.2 * (1.7 * n as f64).cos() + 0.05])
            .collect();
        for nu in [0.3, 0.49] {
            let law = LinearIsotropic::new(2.0, nu, Section::PlaneStrain);
            let (d, lambda) = plane_strain(nu);
            for (how, md) in [(Integration::Full, None), (Integration::MeanDilatation, Some(lambda))] {
                let mut ke = [0.0; 144];
                stiffness::<T6, Plane, _, 2, 6, 3>(&x, &law, how, &mut ke);
                let (k, m, g, area) = geometry(&x, [0, 1, 2, 3, 4, 5]);
                assert_eq!((k, m), ([0, 1, 2], [3, 4, 5]), "counter-clockwise as given");
                let rows = element_rows(&d, md, &g, k, m, area, &u);
                let scale = ke.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
                for a in 0..12 {
                    let ku: f64 = (0..12).map(|b| ke[a * 12 + b] * u[b / 2][b % 2]).sum();
                    let got = rows[a / 2][a % 2];
                    assert!(
                        (got - ku).abs() < 1e-13 * scale,
                        "ν {nu} {how:?}: row {a} {got} against K_e u_e {ku}"
                    );
                }
            }
        }
    }

    /// The P2–P0 rows are the element's own: a quadratic u whose dilatation
    /// varies within the elements, u = (x², 0) (tr ε = 2x), is not a P2–P0
    /// answer for σ = D ε's data, and the rows of σ̃ = D ε − λ m (tr ε − θ̄)
    /// do not balance with those data: the node systems' closure reads it
    /// (against a full rule's round-off above), so a bound made with the
    /// wrong stress cannot pass the closure check of `energy::bound`.
    #[test]
    fn p2_p0_rows_differ_from_the_full_rules_where_the_dilatation_varies() {
        let (d, lambda) = plane_strain(0.49);
        let u = |x: [f64; 2]| [1e-3 * x[0] * x[0], 0.0];
        let e = |x: [f64; 2]| [2e-3 * x[0], 0.0, 0.0];
        let (_, full) = bound_of_exact_state(d, None, u, e);
        let (_, reduced) = bound_of_exact_state(d, Some(lambda), u, e);
        assert!(full < 1e-10, "full rule: closure {full}");
        assert!(reduced > 1e-6, "P2–P0 rows on the full rule's data: closure {reduced}");
    }
}
