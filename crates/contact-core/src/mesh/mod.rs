//! Triangle meshes of the bodies (nondimensional coordinates), no file I/O.
//!
//! # Invariants
//! - every element is counter-clockwise with positive area;
//! - T6 elements list corners first, then the midsides of edges 01, 12, 20, and
//!   midside nodes sit at the edge midpoints (affine elements), except on a
//!   curved boundary (a disk's arc, a Gmsh order-2 mesh), whose elements are
//!   isoparametric (`bisect` keeps their geometry);
//! - boundary edges of an edge set are oriented with the body on their left, so
//!   the outward normal of edge a→b is (dy, −dx)/|ab|.

pub mod bisect;
pub mod boundary;
pub mod coarsen;
pub mod estimate;
pub mod generate;
pub mod gmsh;
pub(crate) mod msh;
pub mod overlap;
pub mod quality;
pub mod refine;
pub mod uniform;

use std::collections::BTreeMap;

/// Triangle order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    T3,
    T6,
}

impl Order {
    pub fn nodes_per_element(self) -> usize {
        match self {
            Order::T3 => 3,
            Order::T6 => 6,
        }
    }
    pub fn nodes_per_edge(self) -> usize {
        match self {
            Order::T3 => 2,
            Order::T6 => 3,
        }
    }
}

/// A boundary edge: corners `a → b` (body on the left) and, for T6, the midside node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    pub a: usize,
    pub b: usize,
    pub mid: Option<usize>,
}

impl Edge {
    /// Nodes in edge-parameter order: a, (mid), b.
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        std::iter::once(self.a).chain(self.mid).chain(std::iter::once(self.b))
    }
}

/// A radius this small against the body's size is round-off of the
/// nondimensional coordinates (1e-16 each), not a position off the axis: the
/// one tolerance of the axis conditions (u_r = 0), the axial point loads and
/// the supports that hold a contact point's slip.
const ON_AXIS: f64 = 1e-9;

#[derive(Debug, Clone)]
pub struct Mesh2d {
    pub order: Order,
    pub nodes: Vec<[f64; 2]>,
    /// Connectivity, `order.nodes_per_element()` indices per element.
    pub elems: Vec<usize>,
    pub edge_sets: BTreeMap<String, Vec<Edge>>,
}

impl Mesh2d {
    pub fn n_elems(&self) -> usize {
        self.elems.len() / self.order.nodes_per_element()
    }
    pub fn elem(&self, e: usize) -> &[usize] {
        let k = self.order.nodes_per_element();
        &self.elems[e * k..(e + 1) * k]
    }

    /// Largest side of the bounding box: the body's size.
    pub fn size(&self) -> f64 {
        extent(&self.nodes)
    }

    /// In axisymmetry, a point at r ≤ this lies on the axis: `ON_AXIS` of
    /// the body's size.
    pub fn axis_tolerance(&self) -> f64 {
        ON_AXIS * self.size()
    }

    /// Nodes of an edge set, each once, in order of first appearance.
    pub fn edge_set_nodes(&self, name: &str) -> Vec<usize> {
        each_once(self.edge_sets.get(name).into_iter().flatten().flat_map(Edge::nodes))
    }
}

/// The nodes of `nodes`, each once, in order of first appearance.
pub fn each_once(nodes: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut seen = std::collections::HashSet::new();
    nodes.filter(|&n| seen.insert(n)).collect()
}

/// Largest turn between two boundary edges (radians) that is read as a
/// sampled smooth curve rather than a corner: a quarter disk given with 89
/// arc edges turns by 1° per edge, a graded far field of R/8 by 7°.
pub(crate) const SMOOTH_TURN: f64 = 0.35;

/// The angle (radians, 0 to π) by which the polyline a → b → c turns at b.
pub(crate) fn turn(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let (u, w) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
    (u[0] * w[1] - u[1] * w[0]).atan2(u[0] * w[0] + u[1] * w[1]).abs()
}

/// The parameter s in [0, 1] of the point of segment a–b nearest to q (0 on
/// a degenerate segment).
pub(crate) fn segment_param(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    if len2 > 0.0 {
        (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Largest side of the bounding box of `nodes` (2D or 3D).
pub fn extent<const D: usize>(nodes: &[[f64; D]]) -> f64 {
    let (lo, hi) = bounds(nodes);
    box_extent(lo, hi)
}

/// Largest side of the box from `lo` to `hi` (−∞ for an inverted, empty box).
pub fn box_extent<const D: usize>(lo: [f64; D], hi: [f64; D]) -> f64 {
    (0..D).map(|c| hi[c] - lo[c]).fold(f64::NEG_INFINITY, f64::max)
}

/// Lowest and highest corners of the bounding box of `nodes` (2D or 3D);
/// inverted (+∞, −∞) when there are none.
pub fn bounds<const D: usize>(nodes: &[[f64; D]]) -> ([f64; D], [f64; D]) {
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for p in nodes {
        for c in 0..D {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    (lo, hi)
}

/// Signed area of triangle (p, q, r); positive when counter-clockwise.
pub fn signed_area(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> f64 {
    0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]))
}
