//! The sides of a triangle mesh, each numbered once with its one or two
//! elements, and the elements around each node: what the node systems of
//! `equilibrate` and the patches of `patch` walk; and the semi-definite
//! Cholesky both solve their small systems with.

pub(super) struct Side {
    pub(super) ends: [usize; 2],
    /// Elements on each side of it (the first one's outward normal is the
    /// side's).
    pub(super) elems: [usize; 2],
    pub(super) normal: [f64; 2],
    pub(super) len: f64,
}

pub(super) const NONE: usize = usize::MAX;

/// Cholesky of the symmetric positive semi-definite `m` (n × n, row-major,
/// lower triangle) that marks null pivots in `skip` instead of failing: for
/// a consistent right-hand side `solve_factored` then gives a solution y
/// whose Aᵀ y (the traction sought) is the unique one.
pub(super) fn factor_psd(m: &mut [f64], n: usize, skip: &mut Vec<bool>) {
    let scale = (0..n).map(|i| m[i * n + i]).fold(0.0, f64::max);
    skip.clear();
    skip.resize(n, false);
    for k in 0..n {
        let piv = m[k * n + k];
        if piv <= 1e-10 * scale {
            skip[k] = true;
            continue;
        }
        let r = piv.sqrt();
        for i in k..n {
            m[i * n + k] /= r;
        }
        for j in k + 1..n {
            for i in j..n {
                m[i * n + j] -= m[i * n + k] * m[j * n + k];
            }
        }
    }
}

pub(super) fn solve_factored(m: &[f64], skip: &[bool], rhs: &mut [f64], n: usize) {
    for k in 0..n {
        if skip[k] {
            rhs[k] = 0.0;
            continue;
        }
        let s: f64 = (0..k).filter(|&j| !skip[j]).map(|j| m[k * n + j] * rhs[j]).sum();
        rhs[k] = (rhs[k] - s) / m[k * n + k];
    }
    for k in (0..n).rev() {
        if skip[k] {
            continue;
        }
        let s: f64 = (k + 1..n).filter(|&j| !skip[j]).map(|j| m[j * n + k] * rhs[j]).sum();
        rhs[k] = (rhs[k] - s) / m[k * n + k];
    }
}

/// The sides of a mesh's corner triangles, each numbered once with its one
/// or two elements, and the elements around each node.
pub(super) struct Numbering {
    pub(super) sides: Vec<Side>,
    pub(super) elem_sides: Vec<[usize; 3]>,
    pub(super) node_start: Vec<usize>,
    pub(super) node_list: Vec<u32>,
}

impl Numbering {
    /// `corners`: each element's corners, counter-clockwise.
    pub(super) fn new(nodes: &[[f64; 2]], corners: &[[u32; 3]]) -> Numbering {
        let ne = corners.len();
        // Elements around each node, in increasing order (a counting sort into
        // one array instead of a list per node: no allocation per node).
        let mut node_start = vec![0usize; nodes.len() + 1];
        for e in corners {
            for &n in e {
                node_start[n as usize + 1] += 1;
            }
        }
        for n in 0..nodes.len() {
            node_start[n + 1] += node_start[n];
        }
        let mut node_list = vec![0u32; node_start[nodes.len()]];
        let mut fill = node_start.clone();
        for (k, e) in corners.iter().enumerate() {
            for n in e.map(|n| n as usize) {
                node_list[fill[n]] = k as u32;
                fill[n] += 1;
            }
        }
        let elems_at = |n: usize| &node_list[node_start[n]..node_start[n + 1]];
        // Sides, oriented by their first (lowest-numbered) element's
        // counter-clockwise walk; the other element is found among the
        // elements of the side's first corner (the elements in turn, so a
        // side's first element numbers it).
        let mut sides: Vec<Side> = Vec::with_capacity(2 * ne);
        let mut elem_sides = vec![[NONE; 3]; ne];
        for k in 0..ne {
            let e = corners[k].map(|n| n as usize);
            for j in 0..3 {
                if elem_sides[k][j] != NONE {
                    continue;
                }
                let (a, b) = (e[j], e[(j + 1) % 3]);
                let (pa, pb) = (nodes[a], nodes[b]);
                // A plain root, not hypot (whose guard against overflow is slow,
                // once per side): a side is far from overflow.
                let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
                let len = (dx * dx + dy * dy).sqrt();
                let id = sides.len();
                let mut side = Side {
                    ends: [a, b],
                    elems: [k, NONE],
                    normal: [(pb[1] - pa[1]) / len, -(pb[0] - pa[0]) / len],
                    len,
                };
                elem_sides[k][j] = id;
                // A side has at most two elements (a third would make the mesh
                // non-manifold, which the mesh checks refuse).
                let (a32, b32) = (a as u32, b as u32);
                for &k2 in elems_at(a) {
                    let k2 = k2 as usize;
                    if k2 <= k {
                        continue;
                    }
                    let e2 = corners[k2];
                    if let Some(j2) = (0..3).find(|&j2| {
                        let (c, d) = (e2[j2], e2[(j2 + 1) % 3]);
                        (c == a32 && d == b32) || (c == b32 && d == a32)
                    }) {
                        side.elems[1] = k2;
                        elem_sides[k2][j2] = id;
                    }
                }
                sides.push(side);
            }
        }
        Numbering {
            sides,
            elem_sides,
            node_start,
            node_list,
        }
    }

    pub(super) fn elems_at(&self, n: usize) -> &[u32] {
        &self.node_list[self.node_start[n]..self.node_start[n + 1]]
    }

    /// η of side `id` for element k: 1 where the side's normal is k's
    /// outward one.
    pub(super) fn sign(&self, id: usize, k: usize) -> f64 {
        if self.sides[id].elems[0] == k {
            1.0
        } else {
            -1.0
        }
    }
}
