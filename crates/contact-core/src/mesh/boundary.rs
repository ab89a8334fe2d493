//! Boundary quantities on an edge set: outward normals and tributary weights.
//!
//! The weight of node i is w_i = ∫_Γ N_i ds (h/2 per adjacent T3 edge; h/6 at the
//! corners and 2h/3 at the midside of a T6 edge), so a nodal contact force λ_i
//! corresponds to the pressure p_i = λ_i / w_i. On the section of a body of
//! revolution it is the area w_i = ∫_Γ N_i 2πr ds (r linear along the chord). The normal at a node is that of
//! the circle through it and its two neighbours where the boundary turns gently,
//! else (corners, ends) the length-weighted mean of its edges' outward normals.

use std::collections::HashMap;

use super::{Edge, Mesh2d};

/// A boundary node with its outward unit normal and tributary weight.
#[derive(Debug, Clone, Copy)]
pub struct BoundaryNode {
    pub node: usize,
    pub normal: [f64; 2],
    pub weight: f64,
}

pub fn edge_normal(mesh: &Mesh2d, e: &Edge) -> ([f64; 2], f64) {
    let (a, b) = (mesh.nodes[e.a], mesh.nodes[e.b]);
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt();
    ([dy / len, -dx / len], len)
}

/// Boundary nodes of an edge set, each once, in order of first appearance;
/// `axisymmetric`: x is the radius and the weights are areas.
pub fn boundary_nodes(mesh: &Mesh2d, edges: &[Edge], axisymmetric: bool) -> Vec<BoundaryNode> {
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut out: Vec<BoundaryNode> = Vec::new();
    let mut nsum: Vec<[f64; 2]> = Vec::new();
    for e in edges {
        let (n, len) = edge_normal(mesh, e);
        let shares: &[(usize, f64)] = &match (e.mid, axisymmetric) {
            (None, false) => [(e.a, 0.5), (e.b, 0.5), (usize::MAX, 0.0)],
            (Some(m), false) => [(e.a, 1.0 / 6.0), (m, 2.0 / 3.0), (e.b, 1.0 / 6.0)],
            // ∫ N_i 2πr ds / len with r = r_a (1 − ξ) + r_b ξ.
            (None, true) => {
                let (ra, rb) = (mesh.nodes[e.a][0], mesh.nodes[e.b][0]);
                let c = std::f64::consts::TAU / 6.0;
                [
                    (e.a, c * (2.0 * ra + rb)),
                    (e.b, c * (ra + 2.0 * rb)),
                    (usize::MAX, 0.0),
                ]
            }
            (Some(m), true) => {
                let (ra, rb) = (mesh.nodes[e.a][0], mesh.nodes[e.b][0]);
                let c = std::f64::consts::TAU / 6.0;
                [(e.a, c * ra), (m, 2.0 * c * (ra + rb)), (e.b, c * rb)]
            }
        };
        for &(node, share) in shares {
            if node == usize::MAX {
                continue;
            }
            let k = *index.entry(node).or_insert_with(|| {
                out.push(BoundaryNode {
                    node,
                    normal: [0.0; 2],
                    weight: 0.0,
                });
                nsum.push([0.0; 2]);
                out.len() - 1
            });
            out[k].weight += share * len;
            nsum[k][0] += n[0] * len;
            nsum[k][1] += n[1] * len;
        }
    }
    for (bn, s) in out.iter_mut().zip(&nsum) {
        let l = (s[0] * s[0] + s[1] * s[1]).sqrt();
        bn.normal = if l > 0.0 { [s[0] / l, s[1] / l] } else { [0.0, 0.0] };
    }
    // Where the boundary is smooth, the circle through a node and its two
    // neighbours gives its normal: exact on a discretized circle or line, which
    // the averaged chord normals are not when the chords differ in length. A
    // frictionless cylinder must not resist rotation about its own centre.
    let mut prev: HashMap<usize, usize> = HashMap::new();
    let mut next: HashMap<usize, usize> = HashMap::new();
    for e in edges {
        let seq: Vec<usize> = e.nodes().collect();
        for w in seq.windows(2) {
            next.insert(w[0], w[1]);
            prev.insert(w[1], w[0]);
        }
    }
    for bn in out.iter_mut() {
        let (Some(&a), Some(&b)) = (prev.get(&bn.node), next.get(&bn.node)) else {
            continue;
        };
        if let Some(n) = circle_normal(mesh.nodes[a], mesh.nodes[bn.node], mesh.nodes[b], bn.normal) {
            bn.normal = n;
        }
    }
    out
}

/// Outward normal at p1 of the circle (or line) through p0, p1, p2 traversed in
/// that order, if the turn at p1 is gentle (below 30°); `guess` fixes the side.
fn circle_normal(p0: [f64; 2], p1: [f64; 2], p2: [f64; 2], guess: [f64; 2]) -> Option<[f64; 2]> {
    let (d0, d1) = ([p1[0] - p0[0], p1[1] - p0[1]], [p2[0] - p1[0], p2[1] - p1[1]]);
    let (l0, l1) = (
        (d0[0] * d0[0] + d0[1] * d0[1]).sqrt(),
        (d1[0] * d1[0] + d1[1] * d1[1]).sqrt(),
    );
    let cos_turn = (d0[0] * d1[0] + d0[1] * d1[1]) / (l0 * l1);
    // A corner (or a degenerate edge, NaN): keep the averaged normal.
    if cos_turn.is_nan() || cos_turn <= 0.866 {
        return None;
    }
    let cross = d0[0] * d1[1] - d0[1] * d1[0];
    let n = if cross.abs() <= 1e-14 * l0 * l1 {
        // Straight: the chord's normal, (dy, −dx) of the direction of travel.
        let c = [p2[0] - p0[0], p2[1] - p0[1]];
        let l = (c[0] * c[0] + c[1] * c[1]).sqrt();
        [c[1] / l, -c[0] / l]
    } else {
        // Circumcentre of the three points.
        let (ax, ay) = (p0[0] - p1[0], p0[1] - p1[1]);
        let (bx, by) = (p2[0] - p1[0], p2[1] - p1[1]);
        let d = 2.0 * (ax * by - ay * bx);
        let (a2, b2) = (ax * ax + ay * ay, bx * bx + by * by);
        let (ux, uy) = ((by * a2 - ay * b2) / d, (ax * b2 - bx * a2) / d);
        let l = (ux * ux + uy * uy).sqrt();
        // From the centre (p1 + u) to p1: −u.
        [-ux / l, -uy / l]
    };
    let dot = n[0] * guess[0] + n[1] * guess[1];
    Some(if dot >= 0.0 { n } else { [-n[0], -n[1]] })
}
