//! Equilibrated tractions on the sides of a linear-triangle mesh (the element
//! equilibration technique of Ladevèze & Leguillon, SIAM J. Numer. Anal. 20,
//! 1983), and the statically admissible stress they make (`airy`).
//!
//! On every side Γ a traction t̂_Γ, linear, is sought whose moments against
//! the hat functions φ_i of its two corners satisfy, on every element K and
//! corner i of K,
//!
//! ```text
//! Σ_{Γ ⊂ ∂K, i ∈ Γ} η_KΓ ∫_Γ t̂_Γ φ_i ds = ∫_K σ_h : ε(φ_i) − ∫_K f φ_i
//! ```
//!
//! (η_KΓ = ±1: Γ's normal is K's outward one or not). Summed over a corner's
//! elements this is the finite element equation of node i, so the system of
//! each node is solvable when the answer is in equilibrium there; its
//! freedom (a node inside has one) is spent on staying closest to the mean of
//! the two elements' own tractions. Each element is then in equilibrium under
//! its sides' tractions (the hats sum to 1 and reproduce x), which is what
//! `airy` needs; that local choice is then improved where the energy is
//! largest by `patch`'s Airy corrections, which minimise it over patches.
//! On sides where the traction is given (loads, the contact pressure, a free
//! surface) t̂ is that traction; on sides with a prescribed
//! displacement component that component is sought like an inner side's.
//!
//! Length: about 800 lines, a seventh of them the patch test; the node
//! systems (the general one and an inner node's fan; `quadratic` solves its
//! corners' with them), the sides' tractions and the elements' energies
//! share the side numbering and belong together
//! (the numbering, the elements' rows kept for the walk and the reused
//! buffers are what keeps the bound a small share of a solve).

use super::airy;
pub(super) use super::numbering::{factor_psd, solve_factored, Numbering, Side, NONE};
use super::patch::{Patches, Residual, SHARE};
use std::collections::{HashMap, HashSet};

/// A boundary side's data, per component: the traction at its first end,
/// at its middle as the first half reaches it, at its middle as the second
/// half reaches it, and at its second end (in the order of `ends`; linear on
/// each half, free to jump at the middle on quadratic triangles, whose
/// four-split stress carries each half-side's traction alone; on linear
/// triangles linear along the side, the middle values unread), or None
/// where that component's displacement is prescribed (the traction is then
/// sought).
#[derive(Debug, Clone, Copy)]
pub struct Given {
    pub ends: [usize; 2],
    pub traction: [Option<[f64; 4]>; 2],
}

/// One body's triangles (N = 3 linear, `quadratic` for N = 6) and what is
/// known on them.
pub struct Input<'a, const N: usize> {
    pub nodes: &'a [[f64; 2]],
    /// N nodes per element (corners first), either orientation.
    pub elems: &'a [[usize; N]],
    /// The answer to equilibrate (in equilibrium with the loads below at
    /// every node whose displacement is not prescribed).
    pub u_eq: &'a [[f64; 2]],
    /// The displacement whose stress is compared with the admissible one.
    pub u_cmp: &'a [[f64; 2]],
    /// The displacement whose energy ‖u‖²_E is summed alongside (the
    /// answer's own norm), on the gradients the equilibration has at hand.
    pub u_norm: &'a [[f64; 2]],
    /// Plane D (Voigt xx, yy, xy with engineering shear).
    pub d: [[f64; 3]; 3],
    pub body_force: [f64; 2],
    /// Boundary sides with data, by their corners (sorted). A boundary side
    /// absent here is free of traction.
    pub given: &'a HashMap<[usize; 2], Given>,
    /// Some(λ) where the elements are P2–P0 (`quadratic`: the stress the
    /// rows are made of is D ε − λ m (tr ε − θ̄), θ̄ the element's mean
    /// dilatation); None for the full rule (always on linear triangles).
    pub mean_dilatation: Option<f64>,
}

/// ∫ (σ* − σ(u_cmp)) : C⁻¹ (σ* − σ(u_cmp)) per element, and how far the
/// elements' tractions failed to balance, relative to the body's largest
/// traction or stress (round-off when the answer is in equilibrium: an
/// element that carries almost nothing is read against the body, not
/// against itself).
pub struct Bound {
    pub indicators: Vec<f64>,
    pub closure: f64,
    /// ‖u_norm‖²_E = Σ_K |K| ε_Kᵀ D ε_K.
    pub norm2: f64,
}

impl Bound {
    /// The bound of `indicators` with the largest closure read against the
    /// largest traction or stress `scale` (as it is when nothing is carried).
    pub(super) fn new(indicators: Vec<f64>, closure: f64, scale: f64, norm2: f64) -> Self {
        let closure = if scale > 0.0 { closure / scale } else { closure };
        Self {
            indicators,
            closure,
            norm2,
        }
    }
}

/// The nodes' area-weighted sums of the elements' stresses made means.
pub(super) fn mean_over_areas(smooth: &mut [[f64; 3]], weight: &[f64]) {
    for (s, w) in smooth.iter_mut().zip(weight) {
        if *w > 0.0 {
            s.iter_mut().for_each(|v| *v /= w);
        }
    }
}

/// The body force's particular stress on the triangle of corners `p`,
/// div σ_p = −f, zero at its centroid.
pub(super) fn particular_stress(f: [f64; 2], p: &[[f64; 2]; 3]) -> impl Fn([f64; 2]) -> [f64; 3] {
    let centroid = [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0];
    move |x| [-f[0] * (x[0] - centroid[0]), -f[1] * (x[1] - centroid[1]), 0.0]
}

pub(super) fn inverse3(d: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let det = d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0])
        + d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
    // The adjugate's (i, j) entry is the cofactor of (j, i).
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
            let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
            (d[r0][c0] * d[r1][c1] - d[r0][c1] * d[r1][c0]) / det
        })
    })
}

/// An element's counter-clockwise corners, hat gradients and area.
type Geometry = ([usize; 3], [[f64; 2]; 3], f64);

/// Counter-clockwise corners, hat gradients and area of an element.
fn geometry(nodes: &[[f64; 2]], e: [usize; 3]) -> Geometry {
    let [a, b, c] = e;
    let (pa, pb, pc) = (nodes[a], nodes[b], nodes[c]);
    let det = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pc[0] - pa[0]) * (pb[1] - pa[1]);
    let e = if det >= 0.0 { [a, b, c] } else { [a, c, b] };
    let p = [nodes[e[0]], nodes[e[1]], nodes[e[2]]];
    let two_a = det.abs();
    let grads = std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        [(p[j][1] - p[k][1]) / two_a, (p[k][0] - p[j][0]) / two_a]
    });
    (e, grads, two_a / 2.0)
}

/// ε (xx, yy, engineering xy) of `u` on the element with corners `e`.
fn strain(grads: &[[f64; 2]; 3], e: [usize; 3], u: &[[f64; 2]]) -> [f64; 3] {
    let mut eps = [0.0; 3];
    for (i, g) in grads.iter().enumerate() {
        let ui = u[e[i]];
        eps[0] += g[0] * ui[0];
        eps[1] += g[1] * ui[1];
        eps[2] += g[1] * ui[0] + g[0] * ui[1];
    }
    eps
}

fn stress(d: &[[f64; 3]; 3], grads: &[[f64; 2]; 3], e: [usize; 3], u: &[[f64; 2]]) -> [f64; 3] {
    let eps = strain(grads, e, u);
    std::array::from_fn(|r| (0..3).map(|c| d[r][c] * eps[c]).sum())
}

/// One element of an inner node's fan: the side it is entered by, the
/// node's end of that side, the side's sign η for the element and the
/// running sum d before it.
#[derive(Clone, Copy)]
struct Step {
    side: usize,
    end: usize,
    eta: f64,
    d: [f64; 2],
}

/// The two sides of an element at its corner `at`, in the element's side
/// order (side j runs from corner j to corner j + 1).
fn sides_at(sides_of: &[usize; 3], at: usize) -> [usize; 2] {
    match at {
        0 => [sides_of[0], sides_of[2]],
        1 => [sides_of[0], sides_of[1]],
        _ => [sides_of[1], sides_of[2]],
    }
}

/// A side's traction components from a stress (xx, yy, xy) and a normal.
fn traction(s: [f64; 3], n: [f64; 2]) -> [f64; 2] {
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}

/// What the node systems read, element by element and side by side.
struct Around<'a> {
    corners: &'a [[u32; 3]],
    elem_sides: &'a [[usize; 3]],
    /// Each element's rows, per corner i and component:
    /// ∫_K σ_h : ε(φ_i) − ∫_K f φ_i.
    rows: &'a [[[f64; 2]; 3]],
    sides: &'a [Side],
    smooth: &'a [[f64; 3]],
    prior: fn(f64, f64, f64) -> f64,
}

/// The projections b of an inner node's sides, both components in one walk
/// around its elements in turn, each entered by a side (the next one's is
/// the side it is left by): element k's row reads c_k − c_{k+1} = y_k with
/// c_k = η b of the side it is entered by, so c_k = t + d_k with d the
/// running sum of −y, and t keeps Σ (b − b̄)² / |Γ| least (the general
/// path's choice). False, with nothing written, where the node is on the
/// boundary or its elements do not close around it.
fn inner_node(node: usize, elems: &[u32], at: &Around, fan: &mut Vec<Step>, proj: &mut [[[f64; 2]; 2]]) -> bool {
    fan.clear();
    let corner = |k: usize| at.corners[k].iter().position(|&n| n as usize == node).unwrap_or(0);
    let sides_of = |k: usize| at.elem_sides[k];
    let first = elems[0] as usize;
    let mut k = first;
    let mut c_at = corner(k);
    let mut side = sides_at(&sides_of(k), c_at)[0];
    let (mut d, mut num, mut den) = ([0.0; 2], [0.0; 2], 0.0);
    let sn = at.smooth[node];
    for _ in 0..elems.len() {
        let sd = &at.sides[side];
        if sd.elems[1] == NONE {
            return false;
        }
        let eta = if sd.elems[0] == k { 1.0 } else { -1.0 };
        let other = sd.ends[0] + sd.ends[1] - node;
        let (tn, to) = (traction(sn, sd.normal), traction(at.smooth[other], sd.normal));
        let y = at.rows[k][c_at];
        fan.push(Step {
            side,
            end: if sd.ends[0] == node { 0 } else { 1 },
            eta,
            d,
        });
        for c in 0..2 {
            let bbar = (at.prior)(sd.len, tn[c], to[c]);
            num[c] += (eta * bbar - d[c]) / sd.len;
            d[c] -= y[c];
        }
        den += 1.0 / sd.len;
        let two = sides_at(&sides_of(k), c_at);
        let out = if two[0] == side { two[1] } else { two[0] };
        let next = &at.sides[out];
        if next.elems[1] == NONE {
            return false;
        }
        k = if next.elems[0] == k {
            next.elems[1]
        } else {
            next.elems[0]
        };
        c_at = corner(k);
        side = out;
    }
    if k != first || side != fan[0].side {
        return false;
    }
    for st in fan.iter() {
        for c in 0..2 {
            let t = num[c] / den;
            proj[st.side][st.end][c] = st.eta * (t + st.d[c]);
        }
    }
    true
}

/// Each side's moments of its given traction against its nodes' functions
/// (`moments(length, Given's four values)`, in the side's own order): at
/// both ends (`proj`) and, for quadratic sides, the middle (`mid`); `sought`
/// where an interior side's or a held component's traction is left to the
/// node systems.
pub(super) struct Given3 {
    pub(super) proj: Vec<[[f64; 2]; 2]>,
    pub(super) mid: Vec<[f64; 2]>,
    pub(super) sought: Vec<[bool; 2]>,
}

pub(super) fn given_moments(
    sides: &[Side],
    given: &HashMap<[usize; 2], Given>,
    moments: impl Fn(f64, [f64; 4]) -> [f64; 3],
) -> Given3 {
    let mut out = Given3 {
        proj: vec![[[0.0; 2]; 2]; sides.len()],
        mid: vec![[0.0; 2]; sides.len()],
        sought: vec![[false; 2]; sides.len()],
    };
    for (id, s) in sides.iter().enumerate() {
        for c in 0..2 {
            let t = if s.elems[1] == NONE {
                given_at(given, s, c)
            } else {
                None
            };
            match t {
                Some(t) => {
                    let b = moments(s.len, t);
                    out.proj[id][0][c] = b[0];
                    out.mid[id][c] = b[1];
                    out.proj[id][1][c] = b[2];
                }
                None => out.sought[id][c] = true,
            }
        }
    }
    out
}

/// The boundary sides whose both components are sought (both displacement
/// components held), by their sorted corners: where the patches' Airy
/// corrections may move the reactions.
pub(super) fn held(sides: &[Side], sought: &[[bool; 2]]) -> HashSet<[usize; 2]> {
    sides
        .iter()
        .zip(sought)
        .filter(|(s, h)| s.elems[1] == NONE && h[0] && h[1])
        .map(|(s, _)| [s.ends[0].min(s.ends[1]), s.ends[0].max(s.ends[1])])
        .collect()
}

/// Component c of a boundary side's data in the side's own orientation
/// (`Given`'s four values), None where it is sought.
pub(super) fn given_at(given: &HashMap<[usize; 2], Given>, s: &Side, c: usize) -> Option<[f64; 4]> {
    let key = [s.ends[0].min(s.ends[1]), s.ends[0].max(s.ends[1])];
    match given.get(&key) {
        Some(g) => g.traction[c].map(|t| if g.ends == s.ends { t } else { [t[3], t[2], t[1], t[0]] }),
        None => Some([0.0; 4]),
    }
}

/// The node systems: every corner's sought projections b[side][end][c]
/// = ∫ t̂ φ_end ds from its elements' rows, the projections given already
/// in `proj`; `prior` (the side's length, the smoothed traction at the
/// node's end and at the other) is the moment the sought ones stay closest
/// to.
#[allow(clippy::too_many_arguments)]
pub(super) fn node_systems(
    num: &Numbering,
    corners: &[[u32; 3]],
    rows: &[[[f64; 2]; 3]],
    smooth: &[[f64; 3]],
    prior: fn(f64, f64, f64) -> f64,
    sought: &[[bool; 2]],
    proj: &mut [[[f64; 2]; 2]],
) {
    let (sides, elem_sides) = (&num.sides, &num.elem_sides);
    let (mut cols, mut last): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    let (mut a, mut m, mut y, mut bbar, mut wt, mut skip) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    let mut fan: Vec<Step> = Vec::new();
    let around = Around {
        corners,
        elem_sides,
        rows,
        sides,
        smooth,
        prior,
    };
    for node in 0..num.node_start.len() - 1 {
        let elems = num.elems_at(node);
        if elems.is_empty() {
            continue;
        }
        if inner_node(node, elems, &around, &mut fan, proj) {
            // A node inside: its elements and sides form a cycle, solved in
            // one pass instead of through A Aᵀ (most nodes).
            continue;
        }
        last.clear();
        for c in 0..2 {
            // Unknown sides at this node, and each element's row.
            cols.clear();
            for k in elems.iter().map(|&k| k as usize) {
                for &id in &elem_sides[k] {
                    if sides[id].ends.contains(&node) && sought[id][c] && !cols.contains(&id) {
                        cols.push(id);
                    }
                }
            }
            let (nr, nc) = (elems.len(), cols.len());
            // The second component reuses the first's factor when the same
            // sides are sought (every node but those of a partial support).
            let same = c == 1 && cols == last;
            a.clear();
            a.resize(nr * nc, 0.0);
            y.clear();
            y.resize(nr, 0.0);
            for (r, k) in elems.iter().map(|&k| k as usize).enumerate() {
                let i = corners[k].iter().position(|&n| n as usize == node).unwrap_or(0);
                let mut rhs = rows[k][i][c];
                for &id in &elem_sides[k] {
                    let sd = &sides[id];
                    let Some(end) = sd.ends.iter().position(|&n| n == node) else {
                        continue;
                    };
                    let eta = num.sign(id, k);
                    match cols.iter().position(|&x| x == id) {
                        Some(col) => a[r * nc + col] = eta,
                        None => rhs -= eta * proj[id][end][c],
                    }
                }
                y[r] = rhs;
            }
            if nc == 0 {
                continue;
            }
            // Closest to the mean of the two elements' own tractions:
            // b = b̄ + W⁻¹ Aᵀ z with A W⁻¹ Aᵀ z = y − A b̄; the deviations
            // weighed by W = 1 / |Γ|, the traction's mean square along the
            // side (b scales with |Γ|).
            bbar.clear();
            bbar.extend(cols.iter().map(|&id| {
                let sd = &sides[id];
                let n = sd.normal;
                let t = |s: [f64; 3]| {
                    if c == 0 {
                        s[0] * n[0] + s[2] * n[1]
                    } else {
                        s[2] * n[0] + s[1] * n[1]
                    }
                };
                let other = sd.ends[0] + sd.ends[1] - node;
                prior(sd.len, t(smooth[node]), t(smooth[other]))
            }));
            for r in 0..nr {
                y[r] -= (0..nc).map(|j| a[r * nc + j] * bbar[j]).sum::<f64>();
            }
            if !same {
                wt.clear();
                wt.extend(cols.iter().map(|&id| sides[id].len));
                m.clear();
                m.resize(nr * nr, 0.0);
                for r in 0..nr {
                    for q in 0..=r {
                        let v: f64 = (0..nc).map(|j| a[r * nc + j] * wt[j] * a[q * nc + j]).sum();
                        m[r * nr + q] = v;
                        m[q * nr + r] = v;
                    }
                }
                factor_psd(&mut m, nr, &mut skip);
            }
            solve_factored(&m, &skip, &mut y, nr);
            for (j, &id) in cols.iter().enumerate() {
                let end = sides[id].ends.iter().position(|&n| n == node).unwrap_or(0);
                proj[id][end][c] = bbar[j] + wt[j] * (0..nr).map(|r| a[r * nc + j] * y[r]).sum::<f64>();
            }
            std::mem::swap(&mut last, &mut cols);
        }
    }
}

pub fn bound(inp: &Input<3>) -> Option<Bound> {
    let ne = inp.elems.len();
    let f = inp.body_force;
    // One pass over the elements keeps what the node systems need of σ_h:
    // the corners in 32 bits, each corner's row and the nodal stresses,
    // averaged over each node's elements (by area): the tractions sought
    // stay closest to theirs, which are nearer the exact traction than
    // either element's own (Zienkiewicz–Zhu recovery). The gradients are
    // made again where they are needed next: cheaper than the first touch
    // of the memory that would keep them (about a millisecond per megabyte,
    // measured with perf on the roller example's fresh process).
    let mut corners: Vec<[u32; 3]> = Vec::with_capacity(ne);
    let mut rows: Vec<[[f64; 2]; 3]> = Vec::with_capacity(ne);
    let mut smooth = vec![[0.0; 3]; inp.nodes.len()];
    let mut weight = vec![0.0; inp.nodes.len()];
    for &e in inp.elems {
        let (e, grads, area) = geometry(inp.nodes, e);
        if area <= 0.0 {
            return None;
        }
        let s = stress(&inp.d, &grads, e, inp.u_eq);
        for &n in &e {
            for r in 0..3 {
                smooth[n][r] += area * s[r];
            }
            weight[n] += area;
        }
        rows.push(std::array::from_fn(|i| {
            let ty = traction(s, grads[i]);
            std::array::from_fn(|c| area * ty[c] - f[c] * area / 3.0)
        }));
        corners.push(e.map(|n| n as u32));
    }
    mean_over_areas(&mut smooth, &weight);
    let num = Numbering::new(inp.nodes, &corners);
    let (sides, elem_sides) = (&num.sides, &num.elem_sides);
    // The given traction of a side at its ends, in the side's own order.
    // Projections b[side][end][component] = ∫ t̂ φ_end ds.
    let Given3 { mut proj, sought, .. } = given_moments(sides, inp.given, |l, [ta, _, _, tb]| {
        [l * (2.0 * ta + tb) / 6.0, 0.0, l * (ta + 2.0 * tb) / 6.0]
    });
    // The hats' moments of the nodal stresses' linear traction.
    node_systems(
        &num,
        &corners,
        &rows,
        &smooth,
        |l, near, far| l * (2.0 * near + far) / 6.0,
        &sought,
        &mut proj,
    );
    // Each element's admissible stress against σ(u_cmp).
    let compliance = inverse3(inp.d);
    let mut residual: Vec<Residual> = Vec::with_capacity(ne);
    let (mut closure, mut scale) = (0.0_f64, 0.0_f64);
    let mut norm2 = 0.0;
    for (k, &elem) in inp.elems.iter().enumerate() {
        let (e, grads, area) = geometry(inp.nodes, elem);
        let grads = &grads;
        let eps = strain(grads, e, inp.u_norm);
        let sn: [f64; 3] = std::array::from_fn(|r| (0..3).map(|c| inp.d[r][c] * eps[c]).sum());
        norm2 += area * (sn[0] * eps[0] + sn[1] * eps[1] + sn[2] * eps[2]);
        let p = [inp.nodes[e[0]], inp.nodes[e[1]], inp.nodes[e[2]]];
        let particular = particular_stress(f, &p);
        let mut t = [[[0.0; 2]; 2]; 3];
        for j in 0..3 {
            let sd = &sides[elem_sides[k][j]];
            let eta = num.sign(elem_sides[k][j], k);
            let (a, b) = (e[j], e[(j + 1) % 3]);
            let l = sd.len;
            // Linear traction from its two end moments, at the side's ends.
            let pr = &proj[elem_sides[k][j]];
            let at_end =
                |end: usize| -> [f64; 2] { std::array::from_fn(|c| 2.0 / l * (2.0 * pr[end][c] - pr[1 - end][c])) };
            let (t0, t1) = (at_end(0), at_end(1));
            let (ta, tb) = if sd.ends[0] == a { (t0, t1) } else { (t1, t0) };
            debug_assert!(sd.ends.contains(&b));
            let n = [(p[(j + 1) % 3][1] - p[j][1]) / l, -(p[(j + 1) % 3][0] - p[j][0]) / l];
            let sp = |x: [f64; 2]| {
                let s = particular(x);
                [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
            };
            let (pa, pb) = (sp(p[j]), sp(p[(j + 1) % 3]));
            t[j] = [
                [eta * ta[0] - pa[0], eta * ta[1] - pa[1]],
                [eta * tb[0] - pb[0], eta * tb[1] - pb[1]],
            ];
        }
        let sub = airy::stress(&p, &t)?;
        closure = closure.max(sub.closure);
        scale = scale.max(sub.scale);
        let sh = stress(&inp.d, grads, e, inp.u_cmp);
        scale = scale.max(sh.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
        residual.push(std::array::from_fn(|j| {
            std::array::from_fn(|q| {
                let sp = particular(sub.points[j][q]);
                std::array::from_fn(|r| sub.at[j][q][r] + sp[r] - sh[r])
            })
        }));
    }
    let mut patches = Patches::new(inp.nodes, &corners, &num, compliance, &held(sides, &sought), residual);
    patches.relax_largest(SHARE);
    let indicators = (0..ne).map(|k| patches.energy(k)).collect();
    Some(Bound::new(indicators, closure, scale, norm2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square of eight triangles around a middle node, in both orientations.
    fn square() -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
        let nodes = super::super::fixtures::square_nodes();
        let elems = vec![
            [0, 1, 4],
            [0, 3, 4],
            [1, 2, 5],
            [1, 4, 5],
            [3, 4, 7],
            [3, 7, 6],
            [4, 5, 8],
            [4, 8, 7],
        ];
        (nodes, elems)
    }

    /// The patch test: a linear displacement is the exact answer under the
    /// uniform tractions it makes, so the admissible stress is its own and
    /// the bound vanishes (to round-off), whether a side's displacement is
    /// prescribed or its traction given.
    #[test]
    fn a_uniform_state_has_a_zero_bound() {
        let (nodes, elems) = square();
        let d = super::super::fixtures::plane_strain(0.3).0;
        let grad = [[1e-3, 4e-4], [-2e-4, -7e-4]];
        let u: Vec<[f64; 2]> = nodes
            .iter()
            .map(|x| {
                [
                    grad[0][0] * x[0] + grad[0][1] * x[1],
                    grad[1][0] * x[0] + grad[1][1] * x[1],
                ]
            })
            .collect();
        let eps = [grad[0][0], grad[1][1], grad[0][1] + grad[1][0]];
        let s: [f64; 3] = std::array::from_fn(|r| (0..3).map(|c| d[r][c] * eps[c]).sum());
        let boundary = [[0, 1], [1, 2], [2, 5], [5, 8], [8, 7], [7, 6], [6, 3], [3, 0]];
        for held in [false, true] {
            let mut given = HashMap::new();
            for [a, b] in boundary {
                let (pa, pb) = (nodes[a], nodes[b]);
                let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
                // Outward normal of the counter-clockwise boundary walk above.
                let n = [(pb[1] - pa[1]) / l, -(pb[0] - pa[0]) / l];
                let t = [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]];
                let on_left = pa[0] == 0.0 && pb[0] == 0.0;
                let traction = if held && on_left {
                    [None, None]
                } else {
                    [Some([t[0]; 4]), Some([t[1]; 4])]
                };
                given.insert([a.min(b), a.max(b)], Given { ends: [a, b], traction });
            }
            let inp = Input {
                nodes: &nodes,
                elems: &elems,
                u_eq: &u,
                u_cmp: &u,
                u_norm: &u,
                d,
                body_force: [0.0, 0.0],
                given: &given,
                mean_dilatation: None,
            };
            let b = bound(&inp).expect("mesh");
            let energy: f64 = 0.5 * (s[0] * eps[0] + s[1] * eps[1] + s[2] * eps[2]);
            let total: f64 = b.indicators.iter().sum();
            assert!(total < 1e-24 * energy.max(1.0), "held {held}: {total:e}");
            assert!(b.closure < 1e-10, "closure {}", b.closure);
            // ‖u‖²_E of the uniform state on the unit square is σ : ε.
            let norm2 = s[0] * eps[0] + s[1] * eps[1] + s[2] * eps[2];
            assert!(
                (b.norm2 - norm2).abs() < 1e-14 * norm2,
                "norm² {} against {norm2}",
                b.norm2
            );
        }
    }
}
