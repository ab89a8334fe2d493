//! Contact zones, pressures and resultants in the caller's units.
//!
//! Pressure at a candidate p_i = λ_i / w_i (w_i its tributary length), positive
//! in compression. Which candidates are in contact is the method's verdict
//! (`methods::Solution::in_contact`); zones are the runs of consecutive
//! contact candidates along the pair's surface, reported along it (arc length
//! and end points) and as their x1-extents. Forces on nodes come from the
//! rows' nodal terms (−λ · coef), so resultants hold for every discretization,
//! and for two bodies the other side's pressure is its nodal force over its
//! tributary length.

use std::collections::{BTreeMap, HashMap, HashSet};

use crate::contact::ConstraintSet;
use crate::mesh::{boundary::boundary_nodes, Edge, Mesh2d};
use crate::scene::{FoundationModel, Scene, Target};
use crate::solution::accuracy;
use crate::solution::report::{ContactPoint, CounterPoint, FittedEnd, PairReport, PairTarget, Resultant, ZoneAlong};

/// Nodal contact forces of pair `p` on `body`: node → force.
fn nodal_forces(cons: &ConstraintSet, lambda: &[f64], p: usize, body: usize) -> BTreeMap<usize, [f64; 2]> {
    let mut out: BTreeMap<usize, [f64; 2]> = BTreeMap::new();
    for (c, &l) in cons.candidates.iter().zip(lambda) {
        if c.pair != p {
            continue;
        }
        for t in c.terms.iter().filter(|t| t.body == body) {
            let f = out.entry(t.node).or_insert([0.0; 2]);
            f[0] -= l * t.coef[0];
            f[1] -= l * t.coef[1];
        }
    }
    out
}

fn resultant_of(forces: &BTreeMap<usize, [f64; 2]>, mesh: &Mesh2d) -> Resultant {
    let mut r = Resultant::default();
    for (&n, f) in forces {
        let x = mesh.nodes[n];
        r.fx += f[0];
        r.fy += f[1];
        r.m += x[0] * f[1] - x[1] * f[0];
    }
    r
}

pub fn pairs(
    scene: &Scene,
    meshes: &[Mesh2d],
    cons: &ConstraintSet,
    lambda: &[f64],
    in_contact: &[bool],
    gaps: &[f64],
) -> (Vec<PairReport>, Resultant, usize) {
    let sc = scene.scales;
    let axisymmetric = scene.analysis == crate::scene::Analysis::Axisymmetric;
    let mut total = Resultant::default();
    let mut n_active = 0;
    let mut out = Vec::with_capacity(scene.pairs.len());
    // Nondimensional pressure of every row, for the zone ends' estimate.
    let pressure: Vec<f64> = (0..cons.len()).map(|i| lambda[i] / cons.candidates[i].weight).collect();
    for (p, pair) in scene.pairs.iter().enumerate() {
        let mut idx: Vec<usize> = (0..cons.len()).filter(|&i| cons.candidates[i].pair == p).collect();
        idx.sort_by(|&a, &b| {
            let (xa, xb) = (cons.candidates[a].x, cons.candidates[b].x);
            xa[0].total_cmp(&xb[0]).then(xa[1].total_cmp(&xb[1]))
        });
        let mut points = Vec::with_capacity(idx.len());
        let mut max_pen: f64 = 0.0;
        for &i in &idx {
            let c = &cons.candidates[i];
            let l = lambda[i];
            max_pen = max_pen.max(-gaps[i]);
            if in_contact[i] {
                n_active += 1;
            }
            points.push(ContactPoint {
                x: sc.length(c.x[0]),
                y: sc.length(c.x[1]),
                gap: sc.length(gaps[i]),
                pressure: sc.stress(l / c.weight),
                force: sc.force(l),
                weight: sc.weight(c.weight),
                node: c.node,
                normal: c.normal,
            });
        }
        let mesh = &meshes[pair.body];
        let (zones, zones_along) = zones(
            mesh,
            &along(mesh, &mesh.edge_sets[&pair.edges]),
            cons,
            &idx,
            (in_contact, &pressure),
            |v| sc.length(v),
        );
        // The radial forces of a body of revolution and their moments cancel
        // over the circumference.
        let to_user = |r: Resultant| Resultant {
            fx: if axisymmetric { 0.0 } else { sc.force(r.fx) },
            fy: sc.force(r.fy),
            m: if axisymmetric { 0.0 } else { sc.moment(r.m) },
        };
        let res = to_user(resultant_of(
            &nodal_forces(cons, lambda, p, pair.body),
            &meshes[pair.body],
        ));
        let other = match &pair.target {
            Target::Obstacle(_) | Target::Foundation(_) => None,
            Target::Body { body, edges, .. } => {
                let (mesh, forces) = (&meshes[*body], nodal_forces(cons, lambda, p, *body));
                let mut pts: Vec<CounterPoint> = boundary_nodes(mesh, &mesh.edge_sets[edges], axisymmetric)
                    .into_iter()
                    .map(|bn| {
                        let f = forces.get(&bn.node).copied().unwrap_or([0.0; 2]);
                        // Compression pushes against the outward normal.
                        let fn_ = -(f[0] * bn.normal[0] + f[1] * bn.normal[1]);
                        let x = mesh.nodes[bn.node];
                        CounterPoint {
                            x: sc.length(x[0]),
                            y: sc.length(x[1]),
                            // A T6 corner on the axis has no area of its own.
                            pressure: sc.stress(if bn.weight > 0.0 { fn_ / bn.weight } else { 0.0 }),
                            force: sc.force(fn_),
                            weight: sc.weight(bn.weight),
                            node: bn.node,
                        }
                    })
                    .collect();
                pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
                Some((pts, to_user(resultant_of(&forces, mesh))))
            }
        };
        total.fx += res.fx;
        total.fy += res.fy;
        total.m += res.m;
        let target = match &pair.target {
            Target::Obstacle(o) => PairTarget::Obstacle(scene.obstacles[*o].name.clone()),
            Target::Foundation(f) => PairTarget::Foundation(scene.foundations[*f].name.clone()),
            Target::Body {
                body, discretization, ..
            } => PairTarget::Body(scene.bodies[*body].name.clone(), *discretization),
        };
        let (other_points, other_resultant) = other.map_or((None, None), |(p, r)| (Some(p), Some(r)));
        let goes_on = match pair.target {
            Target::Foundation(f) => !matches!(scene.foundations[f].model, FoundationModel::Winkler { .. }),
            _ => false,
        };
        out.push(PairReport {
            body: scene.bodies[pair.body].name.clone(),
            target,
            goes_on,
            other_points,
            other_resultant,
            zones,
            zones_along,
            points,
            resultant: res,
            max_penetration: sc.length(max_pen),
            pruned: cons.pruned[p],
            accuracy: None,
            friction: None,
        });
    }
    (out, total, n_active)
}

/// The nodes of an edge set in order along its surface, with their arc length:
/// the edges chained head to tail (a, midside, b; the body on the left), from
/// the start of the chain (a node no edge ends at; on a closed loop, the first
/// edge's first node); further chains follow in the order of their edges, the
/// arc length running on. Every node of the set is listed once, with the
/// number of its chain.
fn along(mesh: &Mesh2d, edges: &[Edge]) -> Vec<Station> {
    let mut next: HashMap<usize, usize> = HashMap::new();
    let mut ends: HashSet<usize> = HashSet::new();
    for e in edges {
        let seq: Vec<usize> = e.nodes().collect();
        for w in seq.windows(2) {
            next.insert(w[0], w[1]);
            ends.insert(w[1]);
        }
    }
    let starts = edges.iter().map(|e| e.a).filter(|a| !ends.contains(a));
    let mut out: Vec<Station> = Vec::new();
    let mut seen: HashSet<usize> = HashSet::new();
    let mut s = 0.0;
    for (chain, start) in starts.chain(edges.iter().map(|e| e.a)).enumerate() {
        let mut n = start;
        let from = out.len();
        let mut closed = false;
        while seen.insert(n) {
            out.push(Station {
                node: n,
                s,
                chain,
                closed: false,
            });
            let Some(&m) = next.get(&n) else { break };
            let (a, b) = (mesh.nodes[n], mesh.nodes[m]);
            s += (b[0] - a[0]).hypot(b[1] - a[1]);
            closed = m == start;
            n = m;
        }
        // A loop (a whole disk's rim) comes back to where it started: its
        // arc length runs on past the closing edge.
        if closed && out.len() > from + 2 {
            for t in &mut out[from..] {
                t.closed = true;
            }
        }
    }
    // A node no walk reached (an edge set that branches) still has a place,
    // on a chain of its own.
    for n in edges.iter().flat_map(|e| e.nodes().collect::<Vec<_>>()) {
        if seen.insert(n) {
            let chain = out.last().map_or(0, |t| t.chain + 1);
            out.push(Station {
                node: n,
                s,
                chain,
                closed: false,
            });
        }
    }
    out
}

/// A node along an edge set: its arc length, the number of its chain, and
/// whether that chain is a closed loop (its last node's next is its first).
struct Station {
    node: usize,
    s: f64,
    chain: usize,
    closed: bool,
}

/// The point at abscissa `x` of the surface `chain` next to its `k`-th node,
/// on the side `dir` (±1), and its arc length; the node itself when no edge
/// on that side reaches `x` (the foundation panels are parts of the edges
/// next to their node).
fn at_x(mesh: &Mesh2d, chain: &[Station], k: usize, dir: isize, x: f64) -> (f64, [f64; 2]) {
    let mut j = k;
    // Once round a closed loop at most.
    let mut left = chain.len();
    while let Some(i) = neighbour(chain, j, dir).filter(|_| left > 0) {
        left -= 1;
        let (p, q) = (mesh.nodes[chain[j].node], mesh.nodes[chain[i].node]);
        if (x - p[0]) * (x - q[0]) <= 0.0 && p[0] != q[0] {
            let t = (x - p[0]) / (q[0] - p[0]);
            let s = chain[j].s + t * (chain[i].s - chain[j].s);
            return (s, [x, p[1] + t * (q[1] - p[1])]);
        }
        j = i;
    }
    (chain[k].s, mesh.nodes[chain[k].node])
}

/// The station next to the `k`-th on the side `dir` (±1), on the same chain
/// (round the closing edge of a loop).
fn neighbour(chain: &[Station], k: usize, dir: isize) -> Option<usize> {
    let same = |i: &usize| *i < chain.len() && chain[*i].chain == chain[k].chain;
    k.checked_add_signed(dir).filter(same).or_else(|| {
        // The other end of a loop.
        let (first, last) = loop_ends(chain, k)?;
        Some(if dir > 0 { first } else { last }).filter(|&i| i != k)
    })
}

/// The first and last station of the closed loop holding station `k`.
fn loop_ends(chain: &[Station], k: usize) -> Option<(usize, usize)> {
    if !chain[k].closed {
        return None;
    }
    let c = chain[k].chain;
    let first = (0..=k).rev().take_while(|&i| chain[i].chain == c).last()?;
    let last = (k..chain.len()).take_while(|&i| chain[i].chain == c).last()?;
    Some((first, last))
}

/// Distance along the surface between neighbouring stations `k` and `j`
/// (across a loop's closing edge, the chord of that edge).
fn spacing(mesh: &Mesh2d, chain: &[Station], k: usize, j: usize) -> f64 {
    if k.abs_diff(j) == 1 {
        (chain[j].s - chain[k].s).abs()
    } else {
        let (a, b) = (mesh.nodes[chain[k].node], mesh.nodes[chain[j].node]);
        (a[0] - b[0]).hypot(a[1] - b[1])
    }
}

/// The contact zones of one pair: runs of consecutive candidates in contact
/// along the surface (`chain`), each from its first to its last candidate (a
/// foundation row: to the outer ends of their panels, on which the
/// foundation's pressure is constant). A zone ends at its last node in
/// contact, where the nodal pressure last is positive, also for mortar rows:
/// the interpolated pressure Σ p_i N_i reaches the next, open node, which
/// placed the zone end of two elastic cylinders about one element beyond
/// Hertz's a. Returns the zones' x-extents (in increasing x) and the zones
/// along the surface (in its order), lengths scaled by `length`.
fn zones(
    mesh: &Mesh2d,
    chain: &[Station],
    cons: &ConstraintSet,
    idx: &[usize],
    (in_contact, pressure): (&[bool], &[f64]),
    length: impl Fn(f64) -> f64,
) -> (Vec<[f64; 2]>, Vec<ZoneAlong>) {
    let at: HashMap<usize, usize> = chain.iter().enumerate().map(|(k, t)| (t.node, k)).collect();
    let mut order: Vec<(usize, usize)> = idx
        .iter()
        .filter_map(|&i| at.get(&cons.candidates[i].node).map(|&k| (k, i)))
        .collect();
    order.sort_unstable();
    // One end of a run: the candidate's node, or the outer end of its panel
    // on the side `dir` along the surface.
    let end = |k: usize, i: usize, dir: isize| -> (f64, [f64; 2]) {
        let c = &cons.candidates[i];
        let Some(fr) = c.foundation() else {
            return (chain[k].s, c.x);
        };
        let x = c.x[0];
        let toward = neighbour(chain, k, dir).map_or(x, |j| mesh.nodes[chain[j].node][0]);
        let outer = if toward < x { fr.panel[0] } else { fr.panel[1] };
        at_x(mesh, chain, k, dir, outer)
    };
    // Runs of candidates in contact: (position along the chain, candidate)
    // of the first and the last, and the x-extent.
    struct Run {
        first: (usize, usize),
        last: (usize, usize),
        x: [f64; 2],
    }
    let mut runs: Vec<Run> = Vec::new();
    let mut open: Option<Run> = None;
    for &(k, i) in &order {
        // A zone ends at an open candidate and at the end of its chain.
        let next_chain = open.as_ref().is_some_and(|r| chain[r.last.0].chain != chain[k].chain);
        if !in_contact[i] || next_chain {
            runs.extend(open.take());
        }
        if !in_contact[i] {
            continue;
        }
        let c = &cons.candidates[i];
        let (lo, hi) = c.foundation().map_or((c.x[0], c.x[0]), |fr| (fr.panel[0], fr.panel[1]));
        open = Some(match open {
            Some(r) => Run {
                last: (k, i),
                x: [r.x[0].min(lo), r.x[1].max(hi)],
                ..r
            },
            None => Run {
                first: (k, i),
                last: (k, i),
                x: [lo, hi],
            },
        });
    }
    runs.extend(open);
    let xs: Vec<[f64; 2]> = runs.iter().map(|r| r.x.map(&length)).collect();
    // The candidates of each chain in order, for the zone ends' estimate.
    let stations: Vec<accuracy::Station> = order
        .iter()
        .map(|&(k, i)| accuracy::Station {
            s: chain[k].s,
            pressure: pressure[i],
            in_contact: in_contact[i],
        })
        .collect();
    let position = |k: usize| order.iter().position(|&(kk, _)| kk == k).expect("a run's candidate");
    let along = runs
        .iter()
        .map(|r| {
            let (s0, p0) = end(r.first.0, r.first.1, -1);
            let (s1, p1) = end(r.last.0, r.last.1, 1);
            let (a, b) = (position(r.first.0), position(r.last.0));
            let same = |q: usize| chain[order[q].0].chain == chain[r.first.0].chain;
            let (lo, hi) = (
                (0..=a).rev().take_while(|&q| same(q)).last().unwrap_or(a),
                (b..order.len()).take_while(|&q| same(q)).last().unwrap_or(b),
            );
            let on_chain = &stations[lo..=hi];
            // A foundation row's zone ends at its panel's outer end: its
            // pressure is constant there, no square-root edge to fit.
            let fitted = cons.candidates[r.first.1].foundation().is_none();
            let estimate = |from: usize, to: usize, dir: isize| -> (f64, Option<FittedEnd>) {
                // The surface past the chain's last candidate on that side
                // (pruned nodes past a flat punch's corner).
                let k = order[if dir > 0 { hi } else { lo }].0;
                let beyond = neighbour(chain, k, dir).map_or(0.0, |j| spacing(mesh, chain, k, j));
                if !fitted {
                    return (length(accuracy::panel_end_error(on_chain, to - lo, dir, beyond)), None);
                }
                let fit = accuracy::end_fit(on_chain, from - lo, to - lo, dir, beyond);
                // The fitted edge on the chord from the end's node to the next
                // candidate, at its distance along the surface.
                let edge = fit.edge.and_then(|d| {
                    // Inward of the end's node: on the chord to the node before.
                    let (d, dir) = if d < 0.0 { (-d, -dir) } else { (d, dir) };
                    let next = to.checked_add_signed(dir).filter(|&q| q < order.len())?;
                    let (here, there) = (cons.candidates[order[to].1].x, cons.candidates[order[next].1].x);
                    let gap = (stations[next].s - stations[to].s).abs();
                    let f = if gap > 0.0 { d / gap } else { 0.0 };
                    Some(FittedEnd {
                        s: length(stations[to].s + dir as f64 * d),
                        at: [here[0] + f * (there[0] - here[0]), here[1] + f * (there[1] - here[1])].map(&length),
                        scatter: length(fit.scatter),
                    })
                });
                (length(fit.error), edge)
            };
            let (e0, f0) = estimate(b, a, -1);
            let (e1, f1) = estimate(a, b, 1);
            ZoneAlong {
                s: [length(s0), length(s1)],
                start: p0.map(&length),
                end: p1.map(&length),
                uncertainty: [e0, e1],
                fitted: [f0, f1],
            }
        })
        .collect::<Vec<ZoneAlong>>();
    // A loop's chain starts at an arbitrary node: a zone across it is the run
    // that ends at the loop's last station and the one that starts at its
    // first, one zone (its arc length running on past the closing edge).
    let (mut xs, mut along) = (xs, along);
    let mut r = 0;
    while r < runs.len() {
        let seam = loop_ends(chain, runs[r].first.0).filter(|&(first, _)| runs[r].first.0 == first);
        let partner = seam.and_then(|(_, last)| {
            (0..runs.len())
                .find(|&q| q != r && runs[q].last.0 == last && chain[runs[q].first.0].chain == chain[last].chain)
        });
        if let (Some((first, last)), Some(q)) = (seam, partner) {
            let perimeter = chain[last].s - chain[first].s + spacing(mesh, chain, last, first);
            let (head, tail) = (along[r], along[q]);
            along[q] = ZoneAlong {
                s: [tail.s[0], head.s[1] + length(perimeter)],
                start: tail.start,
                end: head.end,
                uncertainty: [tail.uncertainty[0], head.uncertainty[1]],
                fitted: [
                    tail.fitted[0],
                    head.fitted[1].map(|f| FittedEnd {
                        s: f.s + length(perimeter),
                        ..f
                    }),
                ],
            };
            xs[q] = [xs[q][0].min(xs[r][0]), xs[q][1].max(xs[r][1])];
            along.remove(r);
            xs.remove(r);
            runs.remove(r);
            continue;
        }
        r += 1;
    }
    xs.sort_by(|a, b| a[0].total_cmp(&b[0]));
    (xs, along)
}
