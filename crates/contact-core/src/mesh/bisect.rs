//! Local, conforming refinement of a given mesh by longest-edge bisection
//! (Rivara 1984): a triangle is split at the midpoint of its longest edge,
//! and the neighbour across that edge first bisects its own longest edge
//! until the two share it, so no hanging node is ever made. The smallest
//! angle of any triangle so made is at least half the smallest angle of the
//! mesh it came from (Rosenberg–Stenger), so repeated rounds do not degrade.
//!
//! Edge sets keep their names and orientation: a split boundary edge a → b
//! becomes a → m → b in place.
//!
//! T6 meshes are refined on their corner triangles and keep their geometry:
//! a triangle with a curved edge (a midside off its chord's midpoint) is
//! split along the image of the reference median under its own quadratic
//! map x(ξ, η). The new corner is the split edge's midside (ξ = ½ on the
//! edge), the two new midsides are the edge's x(¼) and x(¾), and the new
//! interior edge's midside is x at the reference midpoint of that median.
//! Each child's quadratic map is then the parent's restricted to the child's
//! reference half (a quadratic map restricted to a sub-triangle is quadratic
//! and fixed by its six nodes), so the refined mesh covers exactly the same
//! curved region: unsplit edges keep their midsides, split ones stay on the
//! parent's parabola, and a child's Jacobian is the parent's (times ½). An
//! element with straight edges only is split as a T3 and gets chord
//! midpoints, bit for bit as before.
//!
//! A straight boundary edge is a chord of the surface the mesh stands for:
//! a polygon whose turns between edges stay below `SMOOTH_TURN` is taken as points
//! of a smooth curve, and the new node of a split boundary edge is put on the
//! cubic through the edge's ends and their neighbours along the boundary
//! (chord-length parameter; Lagrange), not on the chord. Bisection on the
//! chords would keep the polygon's kinks, and a faceted surface pressed on a
//! flat carries a flat punch's d^(−1/2) pressure at every kink: refined that
//! way, a T3 disk's companion read a peak 27× its true error. A sharper turn
//! is a corner of the body, and its side is split on the chord (or on the
//! quadratic through the smooth side); collinear neighbours give the chord's
//! midpoint exactly.
//!
//! Length: about 600 lines, half of them the tests (conformity, edge sets,
//! a straight T6 mesh split as its corners, a curved one keeping its arc);
//! the curved T6 bookkeeping belongs with the bisection it follows.

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
    /// The midside position of every live curved T6 edge (one whose midside
    /// is not its chord's midpoint); straight edges are not listed.
    curved: HashMap<(usize, usize), [f64; 2]>,
    sets: BTreeMap<String, Vec<(usize, usize)>>,
    /// Each boundary node's neighbours along the boundary (nodes on exactly
    /// two boundary edges; others are left out and split on the chord).
    along: HashMap<usize, [usize; 2]>,
}

/// An undirected side: its corners in order.
pub(super) fn key(a: usize, b: usize) -> (usize, usize) {
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
        let mut curved = HashMap::new();
        if mesh.order == Order::T6 {
            for (e, tri) in mesh.elems.chunks(k).zip(&tris) {
                for i in 0..3 {
                    let (p, q) = (tri[i], tri[(i + 1) % 3]);
                    let c = mesh.nodes[e[3 + i]];
                    // Bitwise, as `to_t6` places it: a straight edge comes back the same.
                    if c != chord_mid(nodes[p], nodes[q]) {
                        curved.insert(key(p, q), c);
                    }
                }
            }
        }
        let mut on_edge: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                on_edge.entry(key(tri[i], tri[(i + 1) % 3])).or_default().push(t);
            }
        }
        let along = boundary_links(&tris);
        Self {
            along,
            nodes,
            alive: vec![true; tris.len()],
            tris,
            on_edge,
            split_at: HashMap::new(),
            curved,
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
            let arc = self.curved.remove(&e);
            // A curved edge is split at its own midside (ξ = ½); its halves'
            // midsides are x(¼) and x(¾) of its quadratic x(ξ) =
            // (1 − ξ)(1 − 2ξ) a + ξ(2ξ − 1) b + 4ξ(1 − ξ) c.
            let boundary = neighbour.is_none();
            let at = match arc {
                Some(c) => c,
                None if boundary => boundary_mid(&self.nodes, &self.along, a, b),
                None => chord_mid(pa, pb),
            };
            self.nodes.push(at);
            let m = self.nodes.len() - 1;
            if boundary {
                for (end, other) in [(a, b), (b, a)] {
                    if let Some(v) = self.along.get_mut(&end) {
                        for x in v.iter_mut().filter(|x| **x == other) {
                            *x = m;
                        }
                    }
                }
                self.along.insert(m, [a, b]);
            }
            if let Some(c) = arc {
                let quarter = |p: [f64; 2], q: [f64; 2]| [0, 1].map(|k| 0.375 * p[k] - 0.125 * q[k] + 0.75 * c[k]);
                self.curved.insert(key(a, m), quarter(pa, pb));
                self.curved.insert(key(m, b), quarter(pb, pa));
            }
            self.split_at.insert(e, m);
            for tri in std::iter::once(t).chain(neighbour) {
                self.halve(tri, e, m, arc);
            }
        }
    }

    /// Replaces triangle `t` by the two halves on either side of the segment
    /// from `m` (the midpoint of its edge `e`) to the opposite corner; `arc`
    /// is the split edge's midside when it was curved.
    fn halve(&mut self, t: usize, e: (usize, usize), m: usize, arc: Option<[f64; 2]>) {
        let tri = self.tris[t];
        // Rotate so that the split edge is (p → q), counter-clockwise.
        let i = (0..3)
            .find(|&i| key(tri[i], tri[(i + 1) % 3]) == e)
            .expect("the edge is the triangle's");
        let (p, q, r) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
        let (qr, rp) = (self.curved.get(&key(q, r)), self.curved.get(&key(r, p)));
        if arc.is_some() || qr.is_some() || rp.is_some() {
            // The new edge m → r is the image of the reference median from
            // the midpoint of pq (barycentrics ½, ½, 0) to r; its midside is x
            // at (¼, ¼, ½): the T6 shape functions there are −⅛, −⅛, 0 at
            // the corners p, q, r and ¼, ½, ½ at the midsides of pq, qr, rp.
            let x = |n: usize| self.nodes[n];
            let (mpq, mqr, mrp) = (
                x(m),
                qr.copied().unwrap_or_else(|| chord_mid(x(q), x(r))),
                rp.copied().unwrap_or_else(|| chord_mid(x(r), x(p))),
            );
            let (xp, xq) = (x(p), x(q));
            let c = [0, 1].map(|k| -0.125 * (xp[k] + xq[k]) + 0.25 * mpq[k] + 0.5 * (mqr[k] + mrp[k]));
            self.curved.insert(key(m, r), c);
        }
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
            Order::T6 => {
                // Chord midpoints everywhere, then the curved edges' midsides back.
                let mut t6 = to_t6(t3);
                for e in t6.elems.chunks(6) {
                    for i in 0..3 {
                        if let Some(&c) = self.curved.get(&key(e[i], e[(i + 1) % 3])) {
                            t6.nodes[e[3 + i]] = c;
                        }
                    }
                }
                t6
            }
        }
    }
}

/// Each boundary node's two neighbours along the boundary (sides on one
/// triangle only); nodes on more than two boundary sides are left out.
pub(super) fn boundary_links(tris: &[[usize; 3]]) -> HashMap<usize, [usize; 2]> {
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for tri in tris {
        for i in 0..3 {
            *count.entry(key(tri[i], tri[(i + 1) % 3])).or_default() += 1;
        }
    }
    let mut links: HashMap<usize, Vec<usize>> = HashMap::new();
    for (&(a, b), &n) in &count {
        if n == 1 {
            links.entry(a).or_default().push(b);
            links.entry(b).or_default().push(a);
        }
    }
    links
        .into_iter()
        .filter_map(|(n, v)| (v.len() == 2).then(|| (n, [v[0], v[1]])))
        .collect()
}

/// The new node of the straight side a–b: its midpoint inside the mesh; on
/// the boundary, on the cubic through a, b and their other neighbours along
/// it (`along`) where the boundary turns by less than `SMOOTH_TURN` at a and at b
/// (module doc), at half the chord a–b in chord-length parameter.
pub(super) fn boundary_mid(nodes: &[[f64; 2]], along: &HashMap<usize, [usize; 2]>, a: usize, b: usize) -> [f64; 2] {
    let x = |n: usize| nodes[n];
    let (pa, pb) = (x(a), x(b));
    let (Some(va), Some(vb)) = (along.get(&a), along.get(&b)) else {
        return chord_mid(pa, pb);
    };
    if !va.contains(&b) || !vb.contains(&a) {
        // An interior side (or one across a pinch of the boundary).
        return chord_mid(pa, pb);
    }
    // The neighbour of `end` along the boundary other than `not`, if the
    // boundary turns smoothly at `end`.
    let beyond = |end: usize, v: &[usize; 2], not: usize| -> Option<[f64; 2]> {
        let o = if v[0] == not { v[1] } else { v[0] };
        let (pe, pn, po) = (x(end), x(not), x(o));
        (super::turn(po, pe, pn) < super::SMOOTH_TURN).then_some(po)
    };
    let (before, after) = (beyond(a, va, b), beyond(b, vb, a));
    let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let h = dist(pa, pb);
    let mut pts = vec![(0.0, pa), (h, pb)];
    if let Some(p) = before {
        pts.push((-dist(p, pa), p));
    }
    if let Some(q) = after {
        pts.push((h + dist(pb, q), q));
    }
    // Lagrange at t = h/2 through the stations (two of them: the chord).
    let t = 0.5 * h;
    let mut out = [0.0; 2];
    for (i, &(ti, pi)) in pts.iter().enumerate() {
        let l: f64 = pts
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &(tj, _))| (t - tj) / (ti - tj))
            .product();
        out[0] += l * pi[0];
        out[1] += l * pi[1];
    }
    // Collinear stations put it on the chord: its midpoint exactly.
    let chord = chord_mid(pa, pb);
    let off = (out[0] - chord[0]) * (pb[1] - pa[1]) - (out[1] - chord[1]) * (pb[0] - pa[0]);
    if pts.len() == 2 || off.abs() <= 1e-12 * h * h {
        chord
    } else {
        out
    }
}

/// An edge's straight midside, as `to_t6` places it.
fn chord_mid(p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]
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

    /// A straight T6 mesh is bisected exactly as its corner (T3) mesh and
    /// given chord midpoints, to the last bit (the refinement a T6 mesh had
    /// before curved edges were kept).
    #[test]
    fn a_straight_t6_mesh_is_refined_as_its_corners() {
        let mark = |p: [f64; 2]| p[0] < 0.3 && p[1] > 0.7;
        let (mut t3, mut t6) = (square(), to_t6(square()));
        for _ in 0..4 {
            t3 = refine_where(&t3, mark, 2);
            t6 = refine_where(&t6, mark, 2);
        }
        let expected = to_t6(t3);
        assert_eq!(t6.nodes, expected.nodes);
        assert_eq!(t6.elems, expected.elems);
        assert_eq!(t6.edge_sets, expected.edge_sets);
    }

    /// T6 map of element `x` at (ξ, η): position and det J.
    use crate::fem::element::{t6_map as map, T6_CHECK_POINTS};

    /// Isoparametric area Σ_e Σ_q w_q det J: exact, det J of a quadratic map
    /// being quadratic and the 3-point rule of degree 2.
    fn area(m: &Mesh2d) -> f64 {
        (0..m.n_elems())
            .map(|e| {
                let x: Vec<[f64; 2]> = m.elem(e).iter().map(|&n| m.nodes[n]).collect();
                crate::fem::reference::triangle::RULE3
                    .iter()
                    .map(|q| q.weight * map(&x, q.xi[0], q.xi[1]).1)
                    .sum::<f64>()
            })
            .sum()
    }

    /// Distance from `p` to the quadratic edge a, c, b (Newton on the
    /// closest point from the chord's projection, ξ kept in [0, 1]).
    fn distance_to_edge(p: [f64; 2], a: [f64; 2], c: [f64; 2], b: [f64; 2]) -> f64 {
        let at = |s: f64| {
            let n = [(1.0 - s) * (1.0 - 2.0 * s), s * (2.0 * s - 1.0), 4.0 * s * (1.0 - s)];
            let dn = [4.0 * s - 3.0, 4.0 * s - 1.0, 4.0 - 8.0 * s];
            let f = |w: [f64; 3], k: usize| w[0] * a[k] + w[1] * b[k] + w[2] * c[k];
            ([f(n, 0), f(n, 1)], [f(dn, 0), f(dn, 1)])
        };
        let d = [b[0] - a[0], b[1] - a[1]];
        let mut s = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
        for _ in 0..30 {
            let (x, dx) = at(s);
            // x'' = 4a + 4b − 8c.
            let ddx = [0, 1].map(|k| 4.0 * (a[k] + b[k]) - 8.0 * c[k]);
            let r = [x[0] - p[0], x[1] - p[1]];
            let g = r[0] * dx[0] + r[1] * dx[1];
            let h = dx[0] * dx[0] + dx[1] * dx[1] + r[0] * ddx[0] + r[1] * ddx[1];
            s = (s - g / h).clamp(0.0, 1.0);
        }
        let x = at(s).0;
        (x[0] - p[0]).hypot(x[1] - p[1])
    }

    /// A curved T6 half disk (arc midsides on the circle) bisected three
    /// rounds around the apex of its arc keeps its geometry: every node of the
    /// refined arc lies on the original mesh's quadratic arc (to round-off),
    /// which is the circle to within its interpolation error R θ⁴/32 (θ the
    /// half angle of an original arc edge: r(u)² = R²(1 − θ⁴u²(1 − u²)/4 +
    /// O(θ⁶)) along an edge interpolating the circle at u = −1, 0, 1);
    /// unsplit edges keep their midsides bit for bit; every element has a
    /// positive Jacobian at the 3-point rule's points and its six nodes; the
    /// isoparametric area is the original's to round-off (the children of a
    /// split element are its own map restricted to the reference halves, so
    /// the region is the same); the mesh is conforming and keeps its edge sets.
    #[test]
    fn a_curved_t6_mesh_keeps_its_geometry() {
        let (center, radius) = ([0.3, 2.0], 1.5);
        let base = super::super::generate::disk(
            center,
            radius,
            true,
            super::super::generate::DiskPart::Half,
            0.4,
            None,
            Order::T6,
        )
        .unwrap();
        let apex = [center[0], center[1] - radius];
        let mut m = base.clone();
        for round in 0..3 {
            let pad = 0.3 * radius / (1 << round) as f64;
            m = refine_where(&m, |p| (p[0] - apex[0]).hypot(p[1] - apex[1]) < pad, 2);
        }
        assert!(
            m.n_elems() > 2 * base.n_elems(),
            "{} from {}",
            m.n_elems(),
            base.n_elems()
        );
        let edges_of = |m: &Mesh2d, set: &str| -> Vec<[[f64; 2]; 3]> {
            m.edge_sets[set]
                .iter()
                .map(|e| [m.nodes[e.a], m.nodes[e.mid.unwrap()], m.nodes[e.b]])
                .collect()
        };
        let (old_arc, new_arc) = (edges_of(&base, "arc"), edges_of(&m, "arc"));
        assert!(new_arc.len() > old_arc.len());
        // The original arc's largest half angle and its bound on the distance to the circle.
        let theta = old_arc
            .iter()
            .map(|[a, _, b]| ((a[0] - b[0]).hypot(a[1] - b[1]) / (2.0 * radius)).asin())
            .fold(0.0, f64::max);
        let bound = radius * theta.powi(4) / 32.0;
        let (mut off_arc, mut off_circle) = (0.0_f64, 0.0_f64);
        for p in new_arc.iter().flatten() {
            let d = old_arc
                .iter()
                .map(|[a, c, b]| distance_to_edge(*p, *a, *c, *b))
                .fold(f64::INFINITY, f64::min);
            off_arc = off_arc.max(d);
            off_circle = off_circle.max(((p[0] - center[0]).hypot(p[1] - center[1]) - radius).abs());
        }
        println!(
            "arc: {} → {} edges, θ = {theta:.4}; off the original T6 arc {off_arc:.2e}, off the circle \
            {off_circle:.2e} (bound {bound:.2e})",
            old_arc.len(),
            new_arc.len()
        );
        assert!(off_arc < 1e-14 * radius, "{off_arc}");
        assert!(off_circle < 1.05 * bound, "{off_circle} vs {bound}");
        // The flat stays flat.
        assert!(edges_of(&m, "flat").iter().flatten().all(|p| p[1] == center[1]));
        // Unsplit edges (both corners and no node between them) keep their midsides.
        let bits = |p: [f64; 2]| p.map(f64::to_bits);
        let mut old_mid = HashMap::new();
        for e in 0..base.n_elems() {
            let t = base.elem(e);
            for i in 0..3 {
                let (p, q) = (bits(base.nodes[t[i]]), bits(base.nodes[t[(i + 1) % 3]]));
                old_mid.insert((p.min(q), p.max(q)), base.nodes[t[3 + i]]);
            }
        }
        let (mut kept, mut edges) = (0, HashMap::new());
        let mut min_det = f64::INFINITY;
        for e in 0..m.n_elems() {
            let t = m.elem(e);
            for i in 0..3 {
                let (p, q) = (bits(m.nodes[t[i]]), bits(m.nodes[t[(i + 1) % 3]]));
                if let Some(c) = old_mid.get(&(p.min(q), p.max(q))) {
                    assert_eq!(m.nodes[t[3 + i]], *c);
                    kept += 1;
                }
                let mid = edges.entry(key(t[i], t[(i + 1) % 3])).or_insert(Vec::new());
                mid.push(t[3 + i]);
            }
            let x: Vec<[f64; 2]> = t.iter().map(|&n| m.nodes[n]).collect();
            for [xi, eta] in T6_CHECK_POINTS {
                let det = map(&x, xi, eta).1 / (2.0 * signed_area(x[0], x[1], x[2]));
                assert!(det > 0.0, "element {e}: det J {det} at ({xi}, {eta})");
                min_det = min_det.min(det);
            }
        }
        assert!(kept > base.n_elems(), "{kept}");
        // Conforming: each edge in one or two elements, which share its midside.
        for mids in edges.values() {
            assert!(mids.len() <= 2 && mids.iter().all(|&n| n == mids[0]));
        }
        let (a0, a1) = (area(&base), area(&m));
        println!(
            "area {a0} → {a1} (relative {:.1e}); smallest det J / its corners' 2·area {min_det:.3}",
            (a1 - a0) / a0
        );
        // ~10³ terms each within a few ulps.
        assert!((a1 - a0).abs() < 1e-12 * a0, "{a0} → {a1}");
        assert_eq!(
            m.edge_sets.keys().collect::<Vec<_>>(),
            base.edge_sets.keys().collect::<Vec<_>>()
        );
        // Each set's edges split in place: as many breaks in its chain as before.
        let breaks = |edges: &Vec<Edge>| edges.windows(2).filter(|w| w[0].b != w[1].a).count();
        for (name, edges) in &m.edge_sets {
            assert_eq!(breaks(edges), breaks(&base.edge_sets[name]), "{name}");
        }
    }
}
