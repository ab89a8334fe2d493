//! Boundary quantities on an edge set: outward normals and tributary weights.
//!
//! The weight of node i is w_i = ∫_Γ N_i ds (h/2 per adjacent T3 edge; h/6 at the
//! corners and 2h/3 at the midside of a T6 edge), so a nodal contact force λ_i
//! corresponds to the pressure p_i = λ_i / w_i. The normal at a node is the
//! length-weighted mean of the outward normals of its edges.

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

/// Boundary nodes of an edge set, each once, in order of first appearance.
pub fn boundary_nodes(mesh: &Mesh2d, edges: &[Edge]) -> Vec<BoundaryNode> {
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut out: Vec<BoundaryNode> = Vec::new();
    let mut nsum: Vec<[f64; 2]> = Vec::new();
    for e in edges {
        let (n, len) = edge_normal(mesh, e);
        let shares: &[(usize, f64)] = &match e.mid {
            None => [(e.a, 0.5), (e.b, 0.5), (usize::MAX, 0.0)],
            Some(m) => [(e.a, 1.0 / 6.0), (m, 2.0 / 3.0), (e.b, 1.0 / 6.0)],
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
    out
}
