//! Tetrahedral meshes of 3D bodies (nondimensional coordinates), no file I/O.
//!
//! A body is a set of tetrahedra: linear (T4) or quadratic (T10,
//! isoparametric). Its named face sets are boundary triangles (supports,
//! loads, contact candidates), the 3D counterpart of the 2D edge sets.
//!
//! # Invariants
//! - every element has positive signed volume: with corners p0..p3,
//!   (p1 − p0)·((p2 − p0) × (p3 − p0)) > 0, the orientation Gmsh's 3D meshers
//!   write (`quality` rejects the others rather than renumber them);
//! - T10 elements use Gmsh's node order: corners 0..3, then the midsides of
//!   edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1 ([`EDGES`]). VTK's quadratic tetra
//!   (type 24) lists the last two edges as 1-3, 2-3 (its nodes 8 and 9 are
//!   Gmsh's 9 and 8): a writer to VTK swaps them;
//! - the midside nodes of generated meshes sit at the edge midpoints; those
//!   of an imported order-2 mesh may follow a curved boundary, and `quality`
//!   checks that the element map stays invertible;
//! - a face of a face set is a boundary face (used by one element), its
//!   corners ordered so that (q − p) × (r − p) points out of the body, with the
//!   midsides of its edges p-q, q-r, r-p for T10 (Gmsh's 6-node triangle
//!   order, the 2D T6 order).

pub mod generate;
pub mod gmsh;
pub mod quality;
pub mod refine;

use std::collections::{BTreeMap, HashMap};

/// Tetrahedron order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    T4,
    T10,
}

impl Order {
    pub fn nodes_per_element(self) -> usize {
        match self {
            Order::T4 => 4,
            Order::T10 => 10,
        }
    }
}

/// The edges of a tetrahedron in Gmsh's order: the midside node of edge k is
/// local node 4 + k of a T10 (the element's own table).
pub use crate::fem::reference::tetrahedron::T10_EDGES as EDGES;

/// The faces of a positively oriented tetrahedron, face i opposite corner i,
/// each ordered so that its normal (q − p) × (r − p) points out of the element.
pub const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// Local midside nodes of the edges p-q, q-r, r-p of each face of [`FACES`].
pub const FACE_MIDS: [[usize; 3]; 4] = [[5, 8, 9], [7, 8, 6], [4, 9, 7], [6, 5, 4]];

/// A boundary triangle of a body: corners ordered with the outward normal
/// (q − p) × (r − p), and for T10 the midsides of edges p-q, q-r, r-p.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Face {
    pub corners: [usize; 3],
    pub mids: Option<[usize; 3]>,
}

impl Face {
    /// Nodes in Gmsh's triangle order: corners, then midsides.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.corners.iter().chain(self.mids.iter().flatten()).copied()
    }

    /// The corners sorted: the same key for the face seen from either side.
    pub fn key(&self) -> [usize; 3] {
        sorted(self.corners)
    }
}

fn sorted(mut c: [usize; 3]) -> [usize; 3] {
    c.sort_unstable();
    c
}

#[derive(Debug, Clone)]
pub struct Mesh3d {
    pub order: Order,
    pub nodes: Vec<[f64; 3]>,
    /// Connectivity, `order.nodes_per_element()` indices per element.
    pub elems: Vec<usize>,
    pub face_sets: BTreeMap<String, Vec<Face>>,
}

impl Mesh3d {
    pub fn n_elems(&self) -> usize {
        self.elems.len() / self.order.nodes_per_element()
    }

    pub fn elem(&self, e: usize) -> &[usize] {
        let k = self.order.nodes_per_element();
        &self.elems[e * k..(e + 1) * k]
    }

    /// Largest side of the bounding box: the body's size.
    pub fn size(&self) -> f64 {
        crate::mesh::extent(&self.nodes)
    }

    /// Signed volume of element `e`'s corner tetrahedron (the element's volume
    /// for T4 and for a T10 whose midsides are at the edge midpoints).
    pub fn volume(&self, e: usize) -> f64 {
        let c = self.elem(e);
        signed_volume(self.nodes[c[0]], self.nodes[c[1]], self.nodes[c[2]], self.nodes[c[3]])
    }

    /// Area and unit outward normal of the flat triangle through a face's corners.
    pub fn face_area_normal(&self, f: &Face) -> (f64, [f64; 3]) {
        let [p, q, r] = f.corners.map(|n| self.nodes[n]);
        area_normal(p, q, r)
    }

    /// Local face `k` ([`FACES`]) of element `e`, oriented outward.
    pub fn local_face(&self, e: usize, k: usize) -> Face {
        let c = self.elem(e);
        Face {
            corners: FACES[k].map(|i| c[i]),
            mids: (self.order == Order::T10).then(|| FACE_MIDS[k].map(|i| c[i])),
        }
    }

    /// The faces used by one element only, oriented outward, in order of
    /// element and local face.
    pub fn boundary_faces(&self) -> Vec<Face> {
        let mut uses: HashMap<[usize; 3], u32> = HashMap::with_capacity(2 * self.n_elems());
        for e in 0..self.n_elems() {
            for k in 0..4 {
                *uses.entry(self.local_face(e, k).key()).or_default() += 1;
            }
        }
        (0..self.n_elems())
            .flat_map(|e| (0..4).map(move |k| (e, k)))
            .map(|(e, k)| self.local_face(e, k))
            .filter(|f| uses[&f.key()] == 1)
            .collect()
    }

    /// Nodes of a face set, each once, in order of first appearance.
    pub fn face_set_nodes(&self, name: &str) -> Vec<usize> {
        let faces = self.face_sets.get(name).into_iter().flatten();
        crate::mesh::each_once(faces.flat_map(Face::nodes))
    }
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Signed volume of tetrahedron (p, q, r, s): (q − p)·((r − p) × (s − p)) / 6,
/// positive when s lies on the side of triangle (p, q, r)'s normal (q − p) × (r − p).
pub fn signed_volume(p: [f64; 3], q: [f64; 3], r: [f64; 3], s: [f64; 3]) -> f64 {
    dot(sub(q, p), cross(sub(r, p), sub(s, p))) / 6.0
}

/// Area and unit normal (q − p) × (r − p) / |…| of triangle (p, q, r).
pub fn area_normal(p: [f64; 3], q: [f64; 3], r: [f64; 3]) -> (f64, [f64; 3]) {
    let n = cross(sub(q, p), sub(r, p));
    let l = dot(n, n).sqrt();
    (0.5 * l, n.map(|c| c / l))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The face tables follow from the edge table and the orientation rule.
    #[test]
    fn the_face_tables_agree_with_the_edges_and_point_outward() {
        let unit = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(signed_volume(unit[0], unit[1], unit[2], unit[3]), 1.0 / 6.0);
        for k in 0..4 {
            let f = FACES[k];
            assert!(!f.contains(&k));
            for j in 0..3 {
                let (a, b) = (f[j], f[(j + 1) % 3]);
                let edge = EDGES.iter().position(|e| sorted([e[0], e[1], 9]) == sorted([a, b, 9]));
                assert_eq!(Some(FACE_MIDS[k][j]), edge.map(|e| 4 + e), "face {k}, edge {a}-{b}");
            }
            // The opposite corner lies behind the outward normal.
            let (_, n) = area_normal(unit[f[0]], unit[f[1]], unit[f[2]]);
            assert!(dot(n, sub(unit[k], unit[f[0]])) < 0.0, "face {k}");
        }
    }
}
