//! A given mesh's coarser companion: the same region meshed again with
//! elements about twice as large, for the two-level error estimate of an
//! inline or Gmsh mesh (`adapt::estimator`).
//!
//! A given mesh cannot be un-refined, and its finer companion (every triangle
//! split in four) has four times its unknowns, which made the estimate cost
//! 2.5–7.5 solves. Here the region is triangulated again (`refine::triangulate`,
//! the generators' constrained Delaunay refinement) from:
//! - the boundary loop with every other node kept, and every node where the
//!   edge set changes or the boundary turns by more than `SMOOTH_TURN` (so the
//!   supports, loads and contact candidates keep their extents exactly);
//! - the interior corner nodes of a maximal independent set of the mesh's
//!   node graph (no two of them share an element edge), chosen greedily: one
//!   node of each cluster of neighbours, so the spacing is about twice the
//!   given mesh's wherever it is graded, far field included.
//!
//! Points the refinement inserts on a boundary segment are moved onto the
//! given boundary (its polyline through every boundary node, midsides
//! included), and so are a T6 companion's boundary midsides: a curved side
//! stays on the given curve. A mesh whose boundary is not one loop (a hole,
//! two regions, a node shared by two loops) has no companion here (`None`),
//! and the estimate falls back to the finer one.
//!
//! The coarsening looks at the request's clock between its phases (`None`
//! once the deadline has passed or the companion is stopped), so that it can
//! run beside the answer (`adapt::overlap`). The triangulation itself
//! (spade's refinement) does not, so the overlap bounds the coarsening's
//! predicted time by the lateness a limit tolerates (its measured cost per
//! node: `adapt::overlap`'s `COARSEN_PER_NODE`).

use std::collections::{BTreeMap, HashMap};

use super::generate::finish;
use super::quality::{self, Conn, Item};
use super::refine::{self, Outline};
use super::{segment_param, turn, Mesh2d, Order, SMOOTH_TURN};
use crate::outcome::ProgressStage;

/// The coarser companion of `mesh`, or None where its boundary is not a
/// single loop or the new mesh fails the inline checks. `keep`: points of the
/// boundary (point loads) whose boundary edge is kept as it is, so that they
/// stay on the new boundary where it is curved.
pub fn coarsened(mesh: &Mesh2d, keep: &[[f64; 2]]) -> Option<Mesh2d> {
    let polled = || crate::cancel::check(ProgressStage::Estimate).ok();
    polled()?;
    let k = mesh.order.nodes_per_element();
    // Directed corner edges with the body on their left, each with its midside.
    // Sorted and searched rather than hashed: on the Gmsh Hertz example (8k
    // DOF) the hash map of every directed edge was a fifth of the coarsening
    // (perf), itself a fifth of the estimate.
    let mut directed: Vec<((usize, usize), Option<usize>)> = Vec::with_capacity(mesh.elems.len());
    for el in mesh.elems.chunks(k) {
        for (j, (a, b)) in [(el[0], el[1]), (el[1], el[2]), (el[2], el[0])].into_iter().enumerate() {
            directed.push(((a, b), (mesh.order == Order::T6).then(|| el[3 + j])));
        }
    }
    directed.sort_unstable_by_key(|e| e.0);
    directed.dedup_by_key(|e| e.0);
    let has = |e: (usize, usize)| directed.binary_search_by_key(&e, |d| d.0).is_ok();
    let mut next: HashMap<usize, (usize, Option<usize>)> = HashMap::new();
    for &((a, b), mid) in &directed {
        if !has((b, a)) && next.insert(a, (b, mid)).is_some() {
            return None; // two boundary edges leave one node: not a simple loop
        }
    }
    let start = *next.keys().min()?;
    let mut loop_nodes = vec![start];
    let mut mids = Vec::new();
    let mut cur = start;
    loop {
        let (b, mid) = *next.get(&cur)?;
        mids.push(mid);
        if b == start {
            break;
        }
        if loop_nodes.len() > next.len() {
            return None;
        }
        loop_nodes.push(b);
        cur = b;
    }
    if loop_nodes.len() != next.len() || loop_nodes.len() < 6 {
        return None; // more than one loop, or too few nodes to coarsen
    }
    let set_of: HashMap<(usize, usize), &str> = mesh
        .edge_sets
        .iter()
        .flat_map(|(name, edges)| edges.iter().map(move |e| ((e.a, e.b), name.as_str())))
        .collect();
    let n = loop_nodes.len();
    let seg_set = |i: usize| *set_of.get(&(loop_nodes[i], loop_nodes[(i + 1) % n])).unwrap_or(&"");
    let p = |i: usize| mesh.nodes[loop_nodes[i % n]];
    // A corner (T6 midsides left out) is kept as a change of set is.
    let mut feature: Vec<bool> = (0..n)
        .map(|i| seg_set((i + n - 1) % n) != seg_set(i) || turn(p(i + n - 1), p(i), p(i + 1)) > SMOOTH_TURN)
        .collect();
    for &q in keep {
        let nearest = (0..n).min_by(|&i, &j| {
            let d = |i: usize| dist2(nearest_on_segment(q, p(i), p(i + 1)), q);
            d(i).total_cmp(&d(j))
        });
        if let Some(i) = nearest {
            feature[i] = true;
            feature[(i + 1) % n] = true;
        }
    }
    // Start the walk at a feature so that chains end on them.
    let first = (0..n).find(|&i| feature[i]).unwrap_or(0);
    let mut kept = vec![first];
    let mut since = 0;
    for s in 1..n {
        let i = (first + s) % n;
        since += 1;
        let next_is_feature = feature[(i + 1) % n] || (i + 1) % n == first;
        // Every other node, and never a one-edge segment before a feature
        // when a two-edge one can end on it.
        if feature[i] || (since >= 2 && !next_is_feature) {
            kept.push(i);
            since = 0;
        }
    }
    if kept.len() < 3 {
        return None;
    }
    // The fine boundary, for snapping: each loop edge as one or two segments
    // (through its T6 midside), with its set.
    let mut fine: Vec<([f64; 2], [f64; 2], &str)> = Vec::with_capacity(2 * n);
    for (i, mid) in mids.iter().enumerate() {
        let (a, b) = (p(i), p(i + 1));
        match *mid {
            Some(m) => {
                let m = mesh.nodes[m];
                fine.push((a, m, seg_set(i)));
                fine.push((m, b, seg_set(i)));
            }
            None => fine.push((a, b, seg_set(i))),
        }
    }
    let snap = |set: &str, q: [f64; 2]| {
        fine.iter()
            .filter(|s| s.2 == set)
            .map(|s| nearest_on_segment(q, s.0, s.1))
            .min_by(|x, y| dist2(*x, q).total_cmp(&dist2(*y, q)))
            .unwrap_or(q)
    };
    let outline = Outline {
        points: kept.iter().map(|&i| p(i)).collect(),
        // A coarse segment spans fine edges of one set (its ends are kept at
        // every change of set).
        sets: kept.iter().map(|&i| seg_set(i)).collect(),
    };
    let seeds = interior_seeds(mesh, &loop_nodes);
    let largest = mesh
        .elems
        .chunks(k)
        .flat_map(|e| (0..3).map(move |i| (e[i], e[(i + 1) % 3])))
        .map(|(a, b)| dist2(mesh.nodes[a], mesh.nodes[b]).sqrt())
        .fold(0.0, f64::max);
    polled()?;
    let mut t = refine::triangulate(&outline, &seeds, 2.0 * largest, &snap).ok()?;
    polled()?;
    t.sets.remove("");
    let mut out = finish(t.nodes, t.elems, t.sets, mesh.order);
    if mesh.order == Order::T6 {
        let sets = set_of_coarse(&out);
        snap_boundary_midsides(&mut out, &snap, &sets);
    }
    checked(out)
}

/// Each boundary edge's set in `mesh` ("" where none).
fn set_of_coarse(mesh: &Mesh2d) -> HashMap<usize, String> {
    mesh.edge_sets
        .iter()
        .flat_map(|(name, edges)| edges.iter().filter_map(move |e| Some((e.mid?, name.clone()))))
        .collect()
}

/// Moves every boundary midside of a T6 mesh onto the given boundary: those
/// of a named set onto that set's fine segments, the others onto the
/// unnamed ones.
fn snap_boundary_midsides(mesh: &mut Mesh2d, snap: &dyn Fn(&str, [f64; 2]) -> [f64; 2], sets: &HashMap<usize, String>) {
    let mut uses: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    for el in mesh.elems.chunks(6) {
        for (j, (a, b)) in [(el[0], el[1]), (el[1], el[2]), (el[2], el[0])].into_iter().enumerate() {
            let e = uses.entry((a.min(b), a.max(b))).or_insert((0, el[3 + j]));
            e.0 += 1;
        }
    }
    for &(count, mid) in uses.values() {
        if count == 1 {
            let set = sets.get(&mid).map_or("", String::as_str);
            mesh.nodes[mid] = snap(set, mesh.nodes[mid]);
        }
    }
}

/// The interior corner nodes of a greedy maximal independent set of the
/// node graph, none next to a boundary node (the boundary's every other node
/// stands for that layer).
fn interior_seeds(mesh: &Mesh2d, loop_nodes: &[usize]) -> Vec<[f64; 2]> {
    let k = mesh.order.nodes_per_element();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); mesh.nodes.len()];
    for el in mesh.elems.chunks(k) {
        for (a, b) in [(el[0], el[1]), (el[1], el[2]), (el[2], el[0])] {
            neighbours[a].push(b);
            neighbours[b].push(a);
        }
    }
    let mut blocked = vec![false; mesh.nodes.len()];
    for &v in loop_nodes {
        blocked[v] = true;
        for &w in &neighbours[v] {
            blocked[w] = true;
        }
    }
    let mut seeds = Vec::new();
    for v in 0..mesh.nodes.len() {
        // Midsides have no corner neighbours and are never seeds.
        if !blocked[v] && !neighbours[v].is_empty() {
            seeds.push(mesh.nodes[v]);
            blocked[v] = true;
            for &w in &neighbours[v] {
                blocked[w] = true;
            }
        }
    }
    seeds
}

/// The new mesh through the inline mesh's checks (orientation, shape, T6
/// midsides, edge sets on the boundary); None if it fails them.
fn checked(mesh: Mesh2d) -> Option<Mesh2d> {
    let sets: BTreeMap<String, Vec<[usize; 2]>> = mesh
        .edge_sets
        .iter()
        .map(|(name, edges)| (name.clone(), edges.iter().map(|e| [e.a, e.b]).collect()))
        .collect();
    let per = mesh.order.nodes_per_element();
    let conn = Conn::Flat {
        nodes: &mesh.elems,
        per,
    };
    quality::try_build(mesh.nodes.clone(), conn, &sets, &|_: Item| {
        (String::new(), String::new())
    })
    .ok()
}

fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

fn nearest_on_segment(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let t = segment_param(q, a, b);
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{disk, rectangle, DiskPart, Grading};
    use crate::mesh::signed_area;

    fn area(m: &Mesh2d) -> f64 {
        let k = m.order.nodes_per_element();
        m.elems
            .chunks(k)
            .map(|e| signed_area(m.nodes[e[0]], m.nodes[e[1]], m.nodes[e[2]]))
            .sum()
    }

    fn set_length(m: &Mesh2d, name: &str) -> f64 {
        m.edge_sets[name]
            .iter()
            .map(|e| dist2(m.nodes[e.a], m.nodes[e.b]).sqrt())
            .sum()
    }

    fn corners_used(m: &Mesh2d) -> usize {
        let k = m.order.nodes_per_element();
        let mut used = vec![false; m.nodes.len()];
        for e in m.elems.chunks(k) {
            for &v in &e[..3] {
                used[v] = true;
            }
        }
        used.iter().filter(|&&u| u).count()
    }

    /// A graded rectangle's companion covers the same rectangle (its sides
    /// are straight, so to round-off), every edge set keeps its length and
    /// ends, and it has about a quarter of the corners (one in 2² for
    /// elements twice as large; measured 0.28 here).
    #[test]
    fn a_graded_rectangle_is_meshed_again_twice_as_coarse() {
        let g = Grading {
            h_min: 0.01,
            ratio: 1.1,
            extent: 0.05,
        };
        let m = rectangle([0.0, 0.0], 2.0, 1.0, 0.2, Some(([1.0, 1.0], g)), Order::T3).unwrap();
        let c = coarsened(&m, &[]).expect("a rectangle has one boundary loop");
        assert!((area(&c) - 2.0).abs() < 1e-12, "area {}", area(&c));
        for name in m.edge_sets.keys() {
            let (a, b) = (set_length(&m, name), set_length(&c, name));
            assert!((a - b).abs() < 1e-12, "{name}: {a} vs {b}");
        }
        let ratio = corners_used(&c) as f64 / corners_used(&m) as f64;
        assert!((0.15..=0.45).contains(&ratio), "{ratio}");
    }

    /// A coarsening whose deadline has passed, or whose companion was told
    /// to stop, gives no companion (so it can run beside the answer: an
    /// answer that fails does not wait for it), and the same mesh with time
    /// left gives one.
    #[test]
    fn a_coarsening_past_its_deadline_gives_none() {
        let m = rectangle([0.0, 0.0], 2.0, 1.0, 0.1, None, Order::T3).unwrap();
        {
            let _d = crate::cancel::Deadline::install(std::time::Duration::ZERO);
            assert!(coarsened(&m, &[]).is_none());
        }
        let _d = crate::cancel::Deadline::install(std::time::Duration::from_secs(3600));
        assert!(coarsened(&m, &[]).is_some());
    }

    /// A curved T6 quarter disk's companion has every boundary node, corners
    /// and midsides, on the given boundary (its polyline through every
    /// boundary node, to round-off). Its corner polygon's area falls short of
    /// the quarter circle's by the segments under its chords, L³/(12 R) each:
    /// with chords at most twice the far-field size 0.125, at most
    /// (π/2) 0.25²/12 over π/4, 1.04 % (measured 0.42 %).
    #[test]
    fn a_curved_t6_companion_keeps_its_boundary_on_the_given_one() {
        let g = Grading {
            h_min: 0.02,
            ratio: 1.1,
            extent: 0.105,
        };
        let m = disk([0.0, 1.0], 1.0, true, DiskPart::Quarter, 0.125, Some(g), Order::T6).unwrap();
        let c = coarsened(&m, &[]).expect("a quarter disk has one boundary loop");
        let given: Vec<([f64; 2], [f64; 2])> = m
            .edge_sets
            .values()
            .flatten()
            .flat_map(|e| {
                let mid = m.nodes[e.mid.unwrap()];
                [(m.nodes[e.a], mid), (mid, m.nodes[e.b])]
            })
            .collect();
        for e in c.edge_sets.values().flatten() {
            for v in e.nodes() {
                let q = c.nodes[v];
                let d = given
                    .iter()
                    .map(|&(a, b)| dist2(nearest_on_segment(q, a, b), q).sqrt())
                    .fold(f64::INFINITY, f64::min);
                assert!(d < 1e-12, "node {v} at {q:?} is {d:.3e} off the given boundary");
            }
        }
        let quarter = std::f64::consts::PI / 4.0;
        assert!(
            (area(&c) - quarter).abs() < 0.0105 * quarter,
            "{} vs {quarter}",
            area(&c)
        );
    }

    /// A point load's boundary edge is kept as it is: on a curved side the
    /// coarse chord through every other node would pass the load by its
    /// sagitta, and the companion's solve would refuse the load as off its
    /// edge set.
    #[test]
    fn a_point_loads_edge_is_kept() {
        let g = Grading {
            h_min: 0.02,
            ratio: 1.1,
            extent: 0.105,
        };
        let m = disk([0.0, 1.0], 1.0, true, DiskPart::Quarter, 0.125, Some(g), Order::T3).unwrap();
        let arc = &m.edge_sets["arc"];
        for e in &arc[arc.len() / 3..arc.len() / 3 + 2] {
            let (a, b) = (m.nodes[e.a], m.nodes[e.b]);
            let at = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
            let c = coarsened(&m, &[at]).expect("one loop");
            let kept = c.edge_sets["arc"].iter().any(|f| {
                let (p, q) = (c.nodes[f.a], c.nodes[f.b]);
                dist2(p, a) + dist2(q, b) < 1e-24
            });
            assert!(kept, "the edge of the load at {at:?} is not in the companion");
        }
    }

    /// A region with a hole has two boundary loops: no companion here (the
    /// estimate then falls back to the finer one).
    #[test]
    fn a_region_with_a_hole_has_no_coarser_companion() {
        // A 4×4 grid of unit squares without its middle 2×2.
        let idx = |i: usize, j: usize| i * 5 + j;
        let nodes: Vec<[f64; 2]> = (0..5).flat_map(|i| (0..5).map(move |j| [j as f64, i as f64])).collect();
        let mut elems = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                if (1..3).contains(&i) && (1..3).contains(&j) {
                    continue;
                }
                let (a, b, c, d) = (idx(i, j), idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j));
                elems.extend_from_slice(&[a, b, c, a, c, d]);
            }
        }
        let m = Mesh2d {
            order: Order::T3,
            nodes,
            elems,
            edge_sets: BTreeMap::new(),
        };
        assert!(coarsened(&m, &[]).is_none());
    }
}
