//! Generated tetrahedral meshes: boxes, uniform or graded toward a focus.
//!
//! A box [x0, x1] × [y0, y1] × [z0, z1] is a tensor grid of cells, each cut
//! into the 6 tetrahedra of Kuhn's (Freudenthal's) split: for each ordering
//! (a, b, c) of the axes, the path from the cell's lowest corner through
//! +e_a, +e_b, +e_c to its highest corner. Every cell is cut along the same
//! main diagonal, so each cell face is cut along its diagonal through its own
//! lowest corner, the same seen from both cells: the mesh is conforming.
//!
//! Grading is per axis (`mesh::generate::graded_points`, as in 2D): lines
//! spaced `h_min` within `extent` of the focus's coordinate, growing by
//! `ratio` per cell up to `size`. The cells are boxes of the three spacings,
//! so near one focus plane and far from the others they are slabs (aspect
//! ratio up to size / h_min); a graded isotropic mesh is refinement's work.
//! A quarter model (symmetry planes x = x0 and y = y0, say) is the box with
//! its focus at that corner edge: the face sets of the symmetry planes are
//! where its symmetry supports go.

use std::collections::{BTreeMap, HashMap};

use super::{signed_volume, Face, Mesh3d, Order, EDGES};
use crate::mesh::generate::{graded_points, Grading};

/// Names of the box's face sets, by axis and side (low, high).
pub const BOX_FACES: [[&str; 2]; 3] = [["x_min", "x_max"], ["y_min", "y_max"], ["z_min", "z_max"]];

/// The box [lo, hi] with cells of side about `size` (each axis split into
/// ⌈length / size⌉ equal cells), or graded toward `focus` when given.
pub fn box_mesh(lo: [f64; 3], hi: [f64; 3], size: f64, grading: Option<([f64; 3], Grading)>, order: Order) -> Mesh3d {
    debug_assert!((0..3).all(|a| hi[a] > lo[a]) && size > 0.0);
    let lines = [0, 1, 2].map(|a| match grading {
        Some((focus, g)) => graded_points(lo[a], hi[a], focus[a], g, size),
        None => {
            let n = ((hi[a] - lo[a]) / size).ceil().max(1.0) as usize;
            uniform(lo[a], hi[a], n)
        }
    });
    grid(&lines, order)
}

/// `n` equal intervals of [lo, hi], the ends exact.
pub fn uniform(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let mut x: Vec<f64> = (0..=n).map(|i| lo + (hi - lo) * i as f64 / n as f64).collect();
    x[n] = hi;
    x
}

/// The Kuhn-split grid through the given increasing lines of x, y and z,
/// with the face sets of [`BOX_FACES`] on its six sides.
pub fn grid(lines: &[Vec<f64>; 3], order: Order) -> Mesh3d {
    debug_assert!(lines.iter().all(|l| l.len() >= 2 && l.windows(2).all(|w| w[0] < w[1])));
    let [nx, ny, nz] = [0, 1, 2].map(|a| lines[a].len());
    let id = |i: usize, j: usize, k: usize| (k * ny + j) * nx + i;
    let mut nodes = Vec::with_capacity(nx * ny * nz);
    for &z in &lines[2] {
        for &y in &lines[1] {
            for &x in &lines[0] {
                nodes.push([x, y, z]);
            }
        }
    }
    // Corner b of a cell: bit 0 is +x, bit 1 +y, bit 2 +z. The path's tetrahedron
    // has the sign of the axis permutation (its edge vectors reduce to
    // e_a, e_b, e_c by column operations); odd ones swap two corners.
    let kuhn: Vec<[usize; 4]> = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]]
        .iter()
        .enumerate()
        .map(|(p, &[a, b, _])| {
            let (v1, v2) = (1 << a, (1 << a) | (1 << b));
            if p < 3 {
                [0, v1, v2, 7]
            } else {
                [0, v2, v1, 7]
            }
        })
        .collect();
    let mut elems = Vec::with_capacity(24 * (nx - 1) * (ny - 1) * (nz - 1));
    for k in 0..nz - 1 {
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let corner = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                for t in &kuhn {
                    elems.extend(t.iter().map(|&b| corner(b)));
                }
            }
        }
    }
    debug_assert!(elems
        .chunks_exact(4)
        .all(|t| signed_volume(nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]) > 0.0));
    let mut mesh = Mesh3d {
        order: Order::T4,
        nodes,
        elems,
        face_sets: BTreeMap::new(),
    };
    // Each boundary face lies in one side's plane; the lines' end values are
    // the sides' coordinates exactly, so the comparison is exact.
    for f in mesh.boundary_faces() {
        let side = (0..3).find_map(|a| {
            let on = |v: f64| f.corners.iter().all(|&n| mesh.nodes[n][a] == v);
            let ends = [lines[a][0], lines[a][lines[a].len() - 1]];
            (0..2).find(|&s| on(ends[s])).map(|s| BOX_FACES[a][s])
        });
        let side = side.expect("a boundary face of a box lies in one of its sides");
        mesh.face_sets.entry(side.to_string()).or_default().push(f);
    }
    match order {
        Order::T4 => mesh,
        Order::T10 => to_t10(mesh),
    }
}

/// Adds a midside node at the midpoint of every edge, one per edge shared by
/// the elements around it (affine T10), and to the face sets' faces.
pub fn to_t10(mesh: Mesh3d) -> Mesh3d {
    debug_assert_eq!(mesh.order, Order::T4);
    let mut nodes = mesh.nodes;
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let mut elems = Vec::with_capacity(mesh.elems.len() / 4 * 10);
    for t in mesh.elems.chunks_exact(4) {
        elems.extend_from_slice(t);
        for &[i, j] in &EDGES {
            let (p, q) = (t[i], t[j]);
            let m = *mid.entry((p.min(q), p.max(q))).or_insert_with(|| {
                let (a, b) = (nodes[p], nodes[q]);
                nodes.push([0, 1, 2].map(|c| 0.5 * (a[c] + b[c])));
                nodes.len() - 1
            });
            elems.push(m);
        }
    }
    let face_sets = mesh
        .face_sets
        .into_iter()
        .map(|(name, faces)| {
            let faces = faces
                .into_iter()
                .map(|f| {
                    let c = f.corners;
                    let m = |a: usize, b: usize| mid[&(a.min(b), a.max(b))];
                    Face {
                        corners: c,
                        mids: Some([m(c[0], c[1]), m(c[1], c[2]), m(c[2], c[0])]),
                    }
                })
                .collect();
            (name, faces)
        })
        .collect();
    Mesh3d {
        order: Order::T10,
        nodes,
        elems,
        face_sets,
    }
}
