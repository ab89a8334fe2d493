//! Local, conforming refinement of a given mesh by longest-edge bisection
//! (Rivara 1984): a triangle is split at the midpoint of its longest edge,
//! and the neighbour across that edge first bisects its own longest edge
//! until the two share it, so no hanging node is ever made. The smallest
//! angle of any triangle so made is at least half the smallest angle of the
//! mesh it came from (Rosenberg–Stenger), so repeated rounds do not degrade.
//!
//! Edge sets keep their names and orientation: a split boundary edge a → b
//! becomes a → m → b in place. T6 meshes are refined on their corner
//! triangles and get their (affine) midside nodes back.

use std::collections::{BTreeMap, HashMap};

use super::generate::to_t6;
use super::{Edge, Mesh2d, Order};

/// The mesh with every triangle that has a corner where `marked` holds
/// bisected `passes` times (its descendants included); neighbours are split
/// as conformity needs.
pub fn refine_where(mesh: &Mesh2d, marked: impl Fn([f64; 2]) -> bool, passes: usize) -> Mesh2d {
    let mut b = Bisector::new(mesh);
    for _ in 0..passes {
        let todo: Vec<usize> = (0..b.tris.len())
            .filter(|&t| b.alive[t] && b.tris[t].iter().any(|&n| marked(b.nodes[n])))
            .collect();
        for t in todo {
            b.split(t);
        }
    }
    b.finish(mesh.order)
}

struct Bisector {
    nodes: Vec<[f64; 2]>,
    tris: Vec<[usize; 3]>,
    alive: Vec<bool>,
    /// The live triangles on each edge (key: sorted corner pair).
    on_edge: HashMap<(usize, usize), Vec<usize>>,
    /// The midpoint node of every edge split so far.
    split_at: HashMap<(usize, usize), usize>,
    sets: BTreeMap<String, Vec<(usize, usize)>>,
}

fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

impl Bisector {
    fn new(mesh: &Mesh2d) -> Self {
        // Corner nodes only, renumbered (a T6's midside nodes come back at the end).
        let k = mesh.order.nodes_per_element();
        let mut index: HashMap<usize, usize> = HashMap::new();
        let mut nodes = Vec::new();
        let mut corner = |n: usize, nodes: &mut Vec<[f64; 2]>| {
            *index.entry(n).or_insert_with(|| {
                nodes.push(mesh.nodes[n]);
                nodes.len() - 1
            })
        };
        let tris: Vec<[usize; 3]> = mesh
            .elems
            .chunks(k)
            .map(|e| {
                [
                    corner(e[0], &mut nodes),
                    corner(e[1], &mut nodes),
                    corner(e[2], &mut nodes),
                ]
            })
            .collect();
        let sets = mesh
            .edge_sets
            .iter()
            .map(|(name, edges)| {
                let v = edges
                    .iter()
                    .map(|e| (corner(e.a, &mut nodes), corner(e.b, &mut nodes)))
                    .collect();
                (name.clone(), v)
            })
            .collect();
        let mut on_edge: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                on_edge.entry(key(tri[i], tri[(i + 1) % 3])).or_default().push(t);
            }
        }
        Self {
            nodes,
            alive: vec![true; tris.len()],
            tris,
            on_edge,
            split_at: HashMap::new(),
            sets,
        }
    }

    /// The longest edge of triangle `t` (ties broken by the corner pair, so
    /// that both triangles on an edge agree and the recursion ends).
    fn longest(&self, t: usize) -> (usize, usize) {
        let tri = self.tris[t];
        (0..3)
            .map(|i| key(tri[i], tri[(i + 1) % 3]))
            .max_by(|&(a, b), &(c, d)| {
                let len = |p: usize, q: usize| {
                    let (x, y) = (self.nodes[p], self.nodes[q]);
                    (x[0] - y[0]).hypot(x[1] - y[1])
                };
                len(a, b).total_cmp(&len(c, d)).then((a, b).cmp(&(c, d)))
            })
            .expect("three edges")
    }

    /// Bisects triangle `t` (if it still exists) at its longest edge, after
    /// the neighbour across it has been brought to share that edge.
    fn split(&mut self, t: usize) {
        while self.alive[t] {
            let e = self.longest(t);
            let neighbour = self.on_edge[&e].iter().copied().find(|&n| n != t);
            if let Some(n) = neighbour {
                if self.longest(n) != e {
                    self.split(n);
                    continue;
                }
            }
            let (a, b) = e;
            let (pa, pb) = (self.nodes[a], self.nodes[b]);
            self.nodes.push([0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]);
            let m = self.nodes.len() - 1;
            self.split_at.insert(e, m);
            for tri in std::iter::once(t).chain(neighbour) {
                self.halve(tri, e, m);
            }
        }
    }

    /// Replaces triangle `t` by the two halves on either side of the segment
    /// from `m` (the midpoint of its edge `e`) to the opposite corner.
    fn halve(&mut self, t: usize, e: (usize, usize), m: usize) {
        let tri = self.tris[t];
        // Rotate so that the split edge is (p → q), counter-clockwise.
        let i = (0..3)
            .find(|&i| key(tri[i], tri[(i + 1) % 3]) == e)
            .expect("the edge is the triangle's");
        let (p, q, r) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
        self.alive[t] = false;
        for j in 0..3 {
            if let Some(v) = self.on_edge.get_mut(&key(tri[j], tri[(j + 1) % 3])) {
                v.retain(|&x| x != t);
            }
        }
        for child in [[p, m, r], [m, q, r]] {
            self.tris.push(child);
            self.alive.push(true);
            let c = self.tris.len() - 1;
            for j in 0..3 {
                self.on_edge
                    .entry(key(child[j], child[(j + 1) % 3]))
                    .or_default()
                    .push(c);
            }
        }
    }

    fn finish(self, order: Order) -> Mesh2d {
        let elems: Vec<usize> = self
            .tris
            .iter()
            .zip(&self.alive)
            .filter(|(_, &a)| a)
            .flat_map(|(t, _)| *t)
            .collect();
        // A split boundary edge a → b is a → m → b, recursively.
        fn expand(a: usize, b: usize, at: &HashMap<(usize, usize), usize>, out: &mut Vec<(usize, usize)>) {
            match at.get(&key(a, b)) {
                Some(&m) => {
                    expand(a, m, at, out);
                    expand(m, b, at, out);
                }
                None => out.push((a, b)),
            }
        }
        let edge_sets = self
            .sets
            .iter()
            .map(|(name, edges)| {
                let mut out = Vec::new();
                for &(a, b) in edges {
                    expand(a, b, &self.split_at, &mut out);
                }
                let edges = out.into_iter().map(|(a, b)| Edge { a, b, mid: None }).collect();
                (name.clone(), edges)
            })
            .collect();
        let t3 = Mesh2d {
            order: Order::T3,
            nodes: self.nodes,
            elems,
            edge_sets,
        };
        match order {
            Order::T3 => t3,
            Order::T6 => to_t6(t3),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::signed_area;

    /// The unit square as two triangles, edge set "top".
    fn square() -> Mesh2d {
        let mut sets = BTreeMap::new();
        sets.insert("top".to_string(), vec![Edge { a: 2, b: 3, mid: None }]);
        Mesh2d {
            order: Order::T3,
            nodes: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            elems: vec![0, 1, 2, 0, 2, 3],
            edge_sets: sets,
        }
    }

    /// Refining near one corner keeps the area (no overlap, no gap), every
    /// triangle counter-clockwise, every interior edge shared by exactly two
    /// triangles (conforming: no hanging node), and the edge set a chain
    /// covering the same segment.
    #[test]
    fn bisection_is_conforming_and_keeps_the_edge_sets() {
        for order in [Order::T3, Order::T6] {
            let base = square();
            let base = if order == Order::T6 { to_t6(base) } else { base };
            let mut m = base;
            for _ in 0..4 {
                m = refine_where(&m, |p| p[0] < 0.3 && p[1] > 0.7, 2);
            }
            let k = order.nodes_per_element();
            let mut area = 0.0;
            let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
            for e in m.elems.chunks(k) {
                let a = signed_area(m.nodes[e[0]], m.nodes[e[1]], m.nodes[e[2]]);
                assert!(a > 0.0);
                area += a;
                for i in 0..3 {
                    *edges.entry(key(e[i], e[(i + 1) % 3])).or_default() += 1;
                }
            }
            assert!((area - 1.0).abs() < 1e-12, "{area}");
            // Boundary edges (used once) lie on the square's sides.
            for (&(a, b), &n) in &edges {
                assert!(n <= 2);
                if n == 1 {
                    let (p, q) = (m.nodes[a], m.nodes[b]);
                    let on_side = (0..2).any(|c| (p[c] == q[c]) && (p[c] == 0.0 || p[c] == 1.0));
                    assert!(on_side, "{p:?} {q:?}");
                }
            }
            let top = &m.edge_sets["top"];
            assert!(top.len() > 1);
            assert_eq!(m.nodes[top[0].a], [1.0, 1.0]);
            assert_eq!(m.nodes[top.last().unwrap().b], [0.0, 1.0]);
            assert!(top.windows(2).all(|w| w[0].b == w[1].a));
            assert_eq!(top.iter().all(|e| e.mid.is_some()), order == Order::T6);
            assert!(m.n_elems() > 30);
        }
    }
}
