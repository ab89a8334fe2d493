//! Uniform refinement of a given mesh: every triangle split into four by its
//! edge midpoints (red refinement), so that every element side is halved and
//! the children are similar to their parent. This is the companion of a
//! given mesh's error estimate and each round of its refinement
//! (`adapt`): the two-level estimate assumes every element size halved, far
//! field included, and similar children keep the mesh's pattern along the
//! contact surface. Two passes of longest-edge bisection (`bisect`) make
//! children of two shapes that alternate along the surface: on the T3 disk
//! its nodal pressure then alternated by ±1 % of p0, which the estimate read
//! as error (peak effectivity 8–15).
//!
//! T3: a side on the boundary gets its new node on the smooth curve its
//! polygon samples (`bisect::boundary_mid`), not on the chord. T6: the
//! midside nodes become corners; the new midsides follow the parent's
//! quadratic map (on a side, its own quadratic: both parents agree), so
//! curved elements keep their geometry. Edge sets keep their names and
//! orientation: a → b becomes a → m → b.

use std::collections::{BTreeMap, HashMap};

use super::bisect::{boundary_links, boundary_mid, key};
use super::{Edge, Mesh2d, Order};

/// The mesh with every triangle split into four (module doc).
pub fn refine_uniform(mesh: &Mesh2d) -> Mesh2d {
    match mesh.order {
        Order::T3 => t3(mesh),
        Order::T6 => t6(mesh),
    }
}

fn t3(mesh: &Mesh2d) -> Mesh2d {
    let tris: Vec<[usize; 3]> = mesh.elems.chunks(3).map(|e| [e[0], e[1], e[2]]).collect();
    let along = boundary_links(&tris);
    let mut nodes = mesh.nodes.clone();
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let mut elems = Vec::with_capacity(4 * mesh.elems.len());
    for &[a, b, c] in &tris {
        let mut m = |p: usize, q: usize| {
            *mid.entry(key(p, q)).or_insert_with(|| {
                nodes.push(boundary_mid(&mesh.nodes, &along, p, q));
                nodes.len() - 1
            })
        };
        let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
        for child in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
            elems.extend(child);
        }
    }
    Mesh2d {
        order: Order::T3,
        edge_sets: split_sets(mesh, |a, b| (mid[&key(a, b)], None)),
        nodes,
        elems,
    }
}

fn t6(mesh: &Mesh2d) -> Mesh2d {
    let mut nodes = mesh.nodes.clone();
    // The midsides of the half sides, keyed by their end nodes.
    let mut half: HashMap<(usize, usize), usize> = HashMap::new();
    let mut elems = Vec::with_capacity(4 * mesh.elems.len());
    let x = |n: usize| mesh.nodes[n];
    for e in mesh.elems.chunks(6) {
        let (c, m) = ([e[0], e[1], e[2]], [e[3], e[4], e[5]]);
        // x(¼) of side p → q with midside s: (3/8) p − (1/8) q + (3/4) s.
        let mut side_half = |p: usize, q: usize, s: usize, nodes: &mut Vec<[f64; 2]>| {
            *half.entry(key(p, s)).or_insert_with(|| {
                nodes.push([0, 1].map(|k| 0.375 * x(p)[k] - 0.125 * x(q)[k] + 0.75 * x(s)[k]));
                nodes.len() - 1
            })
        };
        let mut halves = [[0usize; 2]; 3];
        for i in 0..3 {
            let (p, q, s) = (c[i], c[(i + 1) % 3], m[i]);
            halves[i] = [side_half(p, q, s, &mut nodes), side_half(q, p, s, &mut nodes)];
        }
        // The interior sides' midsides: the parent's map at barycentric
        // (¼, ½, ¼) and its rotations, where the T6 shape functions are
        // −⅛ at the two ¼ corners, 0 at the ½ one, ½ at the midsides next to
        // the ½ corner and ¼ at the one opposite.
        let mut inner = [0usize; 3];
        for (i, slot) in inner.iter_mut().enumerate() {
            // Between the midsides of sides i and i + 1 (they meet at corner i + 1).
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let at = [0, 1]
                .map(|d| -0.125 * (x(c[i])[d] + x(c[k])[d]) + 0.5 * (x(m[i])[d] + x(m[j])[d]) + 0.25 * x(m[k])[d]);
            nodes.push(at);
            *slot = nodes.len() - 1;
        }
        // Children: the three at the corners and the middle one, corners
        // counter-clockwise then the midsides of their sides 01, 12, 20.
        let [c0, c1, c2] = c;
        let [m0, m1, m2] = m;
        let [[h0a, h0b], [h1a, h1b], [h2a, h2b]] = halves;
        let [i0, i1, i2] = inner;
        elems.extend([c0, m0, m2, h0a, i2, h2b]);
        elems.extend([m0, c1, m1, h0b, h1a, i0]);
        elems.extend([m2, m1, c2, i1, h1b, h2a]);
        elems.extend([m0, m1, m2, i0, i1, i2]);
    }
    Mesh2d {
        order: Order::T6,
        edge_sets: split_sets(mesh, |a, s| (s, Some(half[&key(a, s)]))),
        nodes,
        elems,
    }
}

/// Every edge a → b of every set as a → m → b, with m and, T6, the midside
/// of the half at a from `split`, given (a, b) for T3 and (a, midside) for
/// T6 (whose midside is m).
fn split_sets(mesh: &Mesh2d, split: impl Fn(usize, usize) -> (usize, Option<usize>)) -> BTreeMap<String, Vec<Edge>> {
    mesh.edge_sets
        .iter()
        .map(|(name, edges)| {
            let out = edges
                .iter()
                .flat_map(|e| match e.mid {
                    None => {
                        let (m, _) = split(e.a, e.b);
                        [
                            Edge {
                                a: e.a,
                                b: m,
                                mid: None,
                            },
                            Edge {
                                a: m,
                                b: e.b,
                                mid: None,
                            },
                        ]
                    }
                    Some(s) => {
                        let (_, first) = split(e.a, s);
                        let (_, second) = split(e.b, s);
                        [
                            Edge {
                                a: e.a,
                                b: s,
                                mid: first,
                            },
                            Edge {
                                a: s,
                                b: e.b,
                                mid: second,
                            },
                        ]
                    }
                })
                .collect();
            (name.clone(), out)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{disk, DiskPart, Grading};
    use crate::mesh::signed_area;

    fn quarter_disk(order: Order) -> Mesh2d {
        let g = Grading {
            h_min: 0.02,
            ratio: 1.1,
            extent: 0.105,
        };
        disk([0.0, 1.0], 1.0, true, DiskPart::Quarter, 0.125, Some(g), order).unwrap()
    }

    /// Each side of the mesh on one element (boundary) or two (interior),
    /// with one midside for both (T6).
    fn assert_conforming(m: &Mesh2d) {
        let k = m.order.nodes_per_element();
        let mut sides: HashMap<(usize, usize), (usize, Option<usize>)> = HashMap::new();
        for e in m.elems.chunks(k) {
            for i in 0..3 {
                let mid = (k == 6).then(|| e[3 + i]);
                let s = sides.entry(key(e[i], e[(i + 1) % 3])).or_insert((0, mid));
                s.0 += 1;
                assert_eq!(s.1, mid, "two midsides on one side");
            }
        }
        assert!(sides.values().all(|s| s.0 <= 2));
    }

    /// Four children per triangle, each counter-clockwise, covering the
    /// parent exactly (straight sides: the areas add up); an edge set's side
    /// becomes two in order, a square's side split at its midpoint (its
    /// neighbours turn by 90°: corners, not a curve).
    #[test]
    fn a_straight_mesh_is_split_in_four_similar_children() {
        let mut sets = BTreeMap::new();
        sets.insert("top".to_string(), vec![Edge { a: 2, b: 3, mid: None }]);
        let square = Mesh2d {
            order: Order::T3,
            nodes: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            elems: vec![0, 1, 2, 0, 2, 3],
            edge_sets: sets,
        };
        let fine = refine_uniform(&square);
        assert_eq!(fine.n_elems(), 8);
        let areas: Vec<f64> = fine
            .elems
            .chunks(3)
            .map(|e| signed_area(fine.nodes[e[0]], fine.nodes[e[1]], fine.nodes[e[2]]))
            .collect();
        // Each child a quarter of its parent (half the unit square).
        assert!(areas.iter().all(|&a| (a - 0.125).abs() < 1e-15), "{areas:?}");
        assert_conforming(&fine);
        let top = &fine.edge_sets["top"];
        assert_eq!(top.len(), 2);
        assert_eq!((top[0].a, top[1].b, top[0].b), (2, 3, top[1].a));
        assert_eq!(fine.nodes[top[0].b], [0.5, 1.0]);
    }

    /// A T3 quarter disk's arc is a polygon of the circle: the new nodes of
    /// its sides go on the cubic through the neighbours, within a hundredth
    /// of the chord's sagitta of the circle (measured 3.5e-6 R at worst,
    /// where the far field's sides of R/8 have a sagitta of 2e-3 R), and the
    /// refined mesh is conforming with every element counter-clockwise.
    #[test]
    fn a_polygon_of_a_circle_is_refined_onto_the_circle() {
        let m = quarter_disk(Order::T3);
        let fine = refine_uniform(&m);
        assert_eq!(fine.n_elems(), 4 * m.n_elems());
        assert_conforming(&fine);
        for e in fine.elems.chunks(3) {
            assert!(signed_area(fine.nodes[e[0]], fine.nodes[e[1]], fine.nodes[e[2]]) > 0.0);
        }
        let sagitta = m.edge_sets["arc"]
            .iter()
            .map(|e| {
                let (a, b) = (m.nodes[e.a], m.nodes[e.b]);
                ((a[0] - b[0]).hypot(a[1] - b[1])).powi(2) / 8.0
            })
            .fold(0.0, f64::max);
        let off = fine.edge_sets["arc"]
            .iter()
            .map(|e| (fine.nodes[e.b][0].hypot(fine.nodes[e.b][1] - 1.0) - 1.0).abs())
            .fold(0.0, f64::max);
        assert_eq!(fine.edge_sets["arc"].len(), 2 * m.edge_sets["arc"].len());
        assert!(off < 0.01 * sagitta, "{off:.3e} off the circle, sagitta {sagitta:.3e}");
    }

    /// A curved T6 quarter disk keeps its arc: every node of the refined arc
    /// lies on the parent sides' quadratics, within their interpolation error
    /// of the circle (R θ⁴/32 for a side of half angle θ), and the children
    /// share their sides' midsides.
    #[test]
    fn a_curved_t6_mesh_keeps_its_geometry() {
        let m = quarter_disk(Order::T6);
        let fine = refine_uniform(&m);
        assert_eq!(fine.n_elems(), 4 * m.n_elems());
        assert_conforming(&fine);
        let theta = m.edge_sets["arc"]
            .iter()
            .map(|e| {
                let (a, b) = (m.nodes[e.a], m.nodes[e.b]);
                ((a[0] - b[0]).hypot(a[1] - b[1]) / 2.0).asin()
            })
            .fold(0.0, f64::max);
        let off = fine.edge_sets["arc"]
            .iter()
            .flat_map(|e| e.nodes().collect::<Vec<_>>())
            .map(|n| (fine.nodes[n][0].hypot(fine.nodes[n][1] - 1.0) - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(off <= theta.powi(4) / 32.0, "{off:.3e} off the circle, θ = {theta}");
    }
}
