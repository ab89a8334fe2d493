//! A bounding-box tree over a surface's edges, so that a point of the other
//! surface finds the edges it can face without scanning them all.
//!
//! Each edge is boxed by the control polygon of its curve: a T3 edge is its
//! chord; a T6 edge y(ξ) = Σ N_k(ξ) x_k is the quadratic Bézier curve with
//! control points a, q = 2m − (a + b)/2, b, which lies in the convex hull of
//! a, q and b. So a point of edge k at distance r from x puts the box of k,
//! and of every tree node above it, within r of x: a search that skips boxes
//! farther than the best distance found (plus the caller's slack) visits
//! every edge that can attain or tie it, and its answer is the scan's.
//!
//! The tree splits at the median of the box centres along the longer side
//! (a kd-tree of boxes), which keeps it balanced on graded surfaces whose
//! edges shrink by 50× toward the contact, where a uniform grid would either
//! be fine everywhere or put hundreds of edges in one cell.

use std::cmp::Reverse;

/// An axis-aligned box, [x_min, y_min, x_max, y_max].
pub type Aabb = [f64; 4];

/// Edges per leaf: below this a scan is as cheap as a descent.
const LEAF: usize = 4;

/// Deepest descent: a median split halves the edges, so 2^60 edges.
const DEPTH: usize = 64;

struct Node {
    bbox: Aabb,
    /// The node's edges are `order[start..end]`.
    start: usize,
    end: usize,
    /// Children's indices in `nodes` (0: a leaf; the root is never a child).
    left: usize,
    right: usize,
}

pub struct EdgeTree {
    nodes: Vec<Node>,
    order: Vec<usize>,
    /// Each edge's own box, tested in a leaf before the caller's (costlier)
    /// test of the edge.
    boxes: Vec<Aabb>,
}

/// The box of an edge's nodes in edge order a, (mid), b (see the module doc).
pub fn edge_box(pts: &[[f64; 2]]) -> Aabb {
    let mut bbox = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    let mut grow = |p: [f64; 2]| {
        bbox[0] = bbox[0].min(p[0]);
        bbox[1] = bbox[1].min(p[1]);
        bbox[2] = bbox[2].max(p[0]);
        bbox[3] = bbox[3].max(p[1]);
    };
    for &p in pts {
        grow(p);
    }
    if let [a, m, b] = pts {
        grow([2.0 * m[0] - 0.5 * (a[0] + b[0]), 2.0 * m[1] - 0.5 * (a[1] + b[1])]);
    }
    bbox
}

fn union(a: Aabb, b: Aabb) -> Aabb {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])]
}

/// Squared Euclidean distance from x to the box (0 inside). Squared, not
/// `hypot`: the libm call was a sixth of the two-cylinder example's contact
/// rows (perf, 88k DOF), and a rounding apart in the test against the reach
/// cannot drop an edge that attains or ties the best, which lies 1e-6
/// (|g| + scale) inside it (`Projection::see`).
fn distance2(b: &Aabb, x: [f64; 2]) -> f64 {
    let dx = (b[0] - x[0]).max(x[0] - b[2]).max(0.0);
    let dy = (b[1] - x[1]).max(x[1] - b[3]).max(0.0);
    dx * dx + dy * dy
}

impl EdgeTree {
    /// The tree over edges 0..boxes.len() with these boxes.
    pub fn new(boxes: &[Aabb]) -> Self {
        let mut tree = EdgeTree {
            nodes: Vec::with_capacity(2 * boxes.len().div_ceil(LEAF) + 1),
            order: (0..boxes.len()).collect(),
            boxes: boxes.to_vec(),
        };
        tree.split(boxes, 0, boxes.len());
        tree
    }

    /// Builds the node over `order[start..end]` and returns its index.
    fn split(&mut self, boxes: &[Aabb], start: usize, end: usize) -> usize {
        let bbox = self.order[start..end].iter().fold(
            [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
            |acc, &k| union(acc, boxes[k]),
        );
        let index = self.nodes.len();
        self.nodes.push(Node {
            bbox,
            start,
            end,
            left: 0,
            right: 0,
        });
        if end - start > LEAF {
            let axis = if bbox[2] - bbox[0] >= bbox[3] - bbox[1] { 0 } else { 1 };
            let centre = |k: usize| boxes[k][axis] + boxes[k][axis + 2];
            let mid = start + (end - start) / 2;
            self.order[start..end].select_nth_unstable_by(mid - start, |&i, &j| centre(i).total_cmp(&centre(j)));
            let left = self.split(boxes, start, mid);
            let right = self.split(boxes, mid, end);
            self.nodes[index].left = left;
            self.nodes[index].right = right;
        }
        index
    }

    /// Calls `visit(k)` for every edge k whose box lies within `reach` of x,
    /// nearest subtree first (best-first, by the distance to its box);
    /// `visit` returns the reach from then on (never more than before), so
    /// that the search narrows as answers are found. Each edge is visited at
    /// most once, in no particular order.
    ///
    /// Best-first rather than depth-first: a depth-first descent finished
    /// whichever subtree's box held x before it reached the facing edge, and
    /// the two-cylinder example's points at gap 0.005 each projected onto up
    /// to 84 edges at the full search reach (15 per point on average).
    pub fn near(&self, x: [f64; 2], mut reach: f64, mut visit: impl FnMut(usize) -> f64) {
        if self.order.is_empty() {
            return;
        }
        let mut reach2 = reach * reach;
        // A non-negative f64's bits order as its value does.
        let mut heap = std::collections::BinaryHeap::with_capacity(2 * DEPTH);
        heap.push(Reverse((distance2(&self.nodes[0].bbox, x).to_bits(), 0usize)));
        while let Some(Reverse((d2, i))) = heap.pop() {
            if f64::from_bits(d2) > reach2 {
                break;
            }
            let node = &self.nodes[i];
            if node.left == 0 {
                for &k in &self.order[node.start..node.end] {
                    if distance2(&self.boxes[k], x) <= reach2 {
                        reach = reach.min(visit(k));
                        reach2 = reach * reach;
                    }
                }
                continue;
            }
            for child in [node.left, node.right] {
                let d2 = distance2(&self.nodes[child].bbox, x);
                if d2 <= reach2 {
                    heap.push(Reverse((d2.to_bits(), child)));
                }
            }
        }
    }

    /// Calls `visit(k)` for every edge k whose box may hold a point y with
    /// 0 < (y − a) · d < |d|² (inside the slab across the chord a → a + d),
    /// and for some edges just outside it: the caller tests each point itself.
    pub fn across(&self, a: [f64; 2], d: [f64; 2], mut visit: impl FnMut(usize)) {
        if self.order.is_empty() {
            return;
        }
        let len2 = d[0] * d[0] + d[1] * d[1];
        let mut stack = [0usize; DEPTH];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top]];
            let b = &node.bbox;
            // (y − a) · d over the box: its extremes are at corners.
            let sx = [(b[0] - a[0]) * d[0], (b[2] - a[0]) * d[0]];
            let sy = [(b[1] - a[1]) * d[1], (b[3] - a[1]) * d[1]];
            let lo = sx[0].min(sx[1]) + sy[0].min(sy[1]);
            let hi = sx[0].max(sx[1]) + sy[0].max(sy[1]);
            // The caller's own (y − a) · d rounds by a few ulps of its terms,
            // far below this even where they cancel.
            let terms = sx[0].abs().max(sx[1].abs()) + sy[0].abs().max(sy[1].abs());
            let slack = 1e-9 * (terms + len2);
            if hi < -slack || lo > len2 + slack {
                continue;
            }
            if node.left == 0 {
                for &k in &self.order[node.start..node.end] {
                    visit(k);
                }
                continue;
            }
            stack[top] = node.left;
            stack[top + 1] = node.right;
            top += 2;
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A small xorshift generator: the tests need spread, not quality.
    pub struct Rng(u64);
    impl Rng {
        pub fn new(seed: u64) -> Self {
            Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
        }
        pub fn uniform(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A quadratic edge stays inside its box: 200 random T6 edges, 100
    /// points each (the Bézier hull property the search's exactness rests on).
    #[test]
    fn a_t6_edge_lies_in_its_box() {
        let mut rng = Rng::new(7);
        for _ in 0..200 {
            let mut p = || [4.0 * rng.uniform() - 2.0, 4.0 * rng.uniform() - 2.0];
            let pts = [p(), p(), p()];
            let b = edge_box(&pts);
            for i in 0..=100 {
                let xi = i as f64 / 100.0;
                let n = [
                    (1.0 - xi) * (1.0 - 2.0 * xi),
                    4.0 * xi * (1.0 - xi),
                    xi * (2.0 * xi - 1.0),
                ];
                let y = [0, 1].map(|c| (0..3).map(|k| n[k] * pts[k][c]).sum::<f64>());
                assert!(distance2(&b, y) <= 1e-24, "{pts:?} at {xi}: {y:?} outside {b:?}");
            }
        }
    }

    /// The tree visits exactly the boxes within reach (fixed reach), each
    /// once, and the slab query every box that meets the slab: random boxes.
    #[test]
    fn the_tree_finds_every_box_in_reach() {
        let mut rng = Rng::new(11);
        for n in [0, 1, 3, 5, 17, 200] {
            let boxes: Vec<Aabb> = (0..n)
                .map(|_| {
                    let (x, y) = (10.0 * rng.uniform(), 10.0 * rng.uniform());
                    [x, y, x + rng.uniform(), y + 0.1 * rng.uniform()]
                })
                .collect();
            let tree = EdgeTree::new(&boxes);
            for _ in 0..50 {
                let x = [12.0 * rng.uniform() - 1.0, 12.0 * rng.uniform() - 1.0];
                let reach = 3.0 * rng.uniform();
                let mut seen = vec![0; n];
                tree.near(x, reach, |k| {
                    seen[k] += 1;
                    reach
                });
                for k in 0..n {
                    let want = usize::from(distance2(&boxes[k], x) <= reach * reach);
                    assert_eq!(seen[k], want, "box {k} {:?} from {x:?}, reach {reach}", boxes[k]);
                }
                let d = [rng.uniform() - 0.5, rng.uniform() - 0.5];
                let mut hit = vec![false; n];
                tree.across(x, d, |k| hit[k] = true);
                for k in 0..n {
                    let b = boxes[k];
                    let s = [[b[0], b[1]], [b[2], b[1]], [b[0], b[3]], [b[2], b[3]]]
                        .map(|c| (c[0] - x[0]) * d[0] + (c[1] - x[1]) * d[1]);
                    let len2 = d[0] * d[0] + d[1] * d[1];
                    let meets = s.iter().any(|&v| v > 0.0) && s.iter().any(|&v| v < len2);
                    assert!(hit[k] || !meets, "box {k} {b:?} meets the slab of {x:?} {d:?}");
                }
            }
        }
    }
}
