//! Structured meshes graded toward the contact region.
//!
//! Grading: element size `h_min` at the focus, growing by `ratio` per element up
//! to the nominal `size`. The rectangle is a tensor product of two graded 1D
//! distributions; the half-disk is a polar mesh graded toward the apex of the arc
//! in angle and toward the rim in radius, whose rings halve their number of
//! segments inward whenever the tangential spacing falls below the radial one, so
//! that elements stay shape-regular down to the centre.

use std::collections::{BTreeMap, HashMap};

use super::{signed_area, Edge, Mesh2d, Order};

/// Grading parameters (nondimensional).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grading {
    pub h_min: f64,
    pub ratio: f64,
    /// Distance from the focus meshed uniformly at `h_min`.
    pub extent: f64,
}

/// Relative slack of the mesh generators' size comparisons.
const TIE: f64 = 1e-9;

/// Graded 1D points on [lo, hi]: spacing h_min within `extent` of `focus`
/// (clamped into the interval), then growing by `ratio` up to `h_max`, the last
/// interval on each side adjusted to land on the end.
pub fn graded_points(lo: f64, hi: f64, focus: f64, g: Grading, h_max: f64) -> Vec<f64> {
    let Grading { h_min, ratio, extent } = g;
    let f = focus.clamp(lo, hi);
    let side = |len: f64| -> Vec<f64> {
        // Offsets from the focus, 0 excluded, last == len.
        let mut out = Vec::new();
        // A focus on the interval's end (up to round-off, which grows with the
        // coordinates' magnitude) leaves no side there.
        if len <= TIE * h_min {
            return out;
        }
        let mut h = h_min.min(h_max);
        let mut s = 0.0;
        loop {
            // Round-number parameters put these comparisons on exact ties; the
            // slack decides ties the same way at every length scale (the mesh
            // must not change when the scene is rescaled).
            if s + h >= len - 0.5 * h - TIE * h {
                out.push(len);
                break;
            }
            s += h;
            out.push(s);
            if s >= extent - TIE * h {
                h = (h * ratio).min(h_max);
            }
        }
        out
    };
    let left = side(f - lo);
    let right = side(hi - f);
    let mut pts: Vec<f64> = left.iter().rev().map(|d| f - d).collect();
    pts.push(f);
    pts.extend(right.iter().map(|d| f + d));
    pts[0] = lo;
    *pts.last_mut().unwrap() = hi;
    pts.dedup_by(|a, b| (*a - *b).abs() <= TIE * h_min);
    pts
}

/// Number of points `graded_points` would make, without allocating them (for size limits).
pub fn graded_count(len: f64, g: Grading, h_max: f64) -> f64 {
    let Grading { h_min, ratio, extent } = g;
    let fine = extent.min(len);
    let len = len - fine;
    let extra = fine / h_min.min(h_max);
    extra + graded_count_geometric(len, h_min, ratio, h_max)
}

fn graded_count_geometric(len: f64, h_min: f64, ratio: f64, h_max: f64) -> f64 {
    // Geometric part until h_max, then uniform.
    let h0 = h_min.min(h_max);
    if ratio <= 1.0 + 1e-12 || h0 >= h_max {
        return len / h0 + 1.0;
    }
    let n_geo = ((h_max / h0).ln() / ratio.ln()).ceil();
    let geo_len = h0 * (ratio.powf(n_geo) - 1.0) / (ratio - 1.0);
    if geo_len >= len {
        ((len * (ratio - 1.0) / h0 + 1.0).ln() / ratio.ln()).ceil() + 1.0
    } else {
        n_geo + (len - geo_len) / h_max + 1.0
    }
}

/// Rectangle [x0, x0+w] × [y0, y0+h] with edge sets bottom, right, top, left.
pub fn rectangle(
    corner: [f64; 2],
    w: f64,
    h: f64,
    size: f64,
    grading: Option<([f64; 2], Grading)>,
    order: Order,
) -> Mesh2d {
    let (x0, y0) = (corner[0], corner[1]);
    let (xs, ys) = match grading {
        Some((focus, g)) => (
            graded_points(x0, x0 + w, focus[0], g, size),
            graded_points(y0, y0 + h, focus[1], g, size),
        ),
        None => {
            let nx = (w / size).ceil().max(1.0) as usize;
            let ny = (h / size).ceil().max(1.0) as usize;
            (
                (0..=nx).map(|i| x0 + w * i as f64 / nx as f64).collect(),
                (0..=ny).map(|j| y0 + h * j as f64 / ny as f64).collect(),
            )
        }
    };
    let (nx, ny) = (xs.len(), ys.len());
    let id = |i: usize, j: usize| j * nx + i;
    let mut nodes = Vec::with_capacity(nx * ny);
    for &y in &ys {
        for &x in &xs {
            nodes.push([x, y]);
        }
    }
    let mut elems = Vec::with_capacity(6 * (nx - 1) * (ny - 1));
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            // Alternate the diagonal so the mesh has no preferred direction
            // and is mirror-symmetric about a focus on a grid line.
            let xm = 0.5 * (xs[i] + xs[i + 1]);
            let ym = 0.5 * (ys[j] + ys[j + 1]);
            let (fx, fy) = grading.map(|g| (g.0[0], g.0[1])).unwrap_or((x0, y0));
            if (xm - fx) * (ym - fy) >= 0.0 {
                elems.extend_from_slice(&[a, b, c, a, c, d]);
            } else {
                elems.extend_from_slice(&[a, b, d, b, c, d]);
            }
        }
    }
    let mut sets: BTreeMap<String, Vec<(usize, usize)>> = BTreeMap::new();
    sets.insert("bottom".into(), (0..nx - 1).map(|i| (id(i, 0), id(i + 1, 0))).collect());
    sets.insert(
        "right".into(),
        (0..ny - 1).map(|j| (id(nx - 1, j), id(nx - 1, j + 1))).collect(),
    );
    sets.insert(
        "top".into(),
        (0..nx - 1).rev().map(|i| (id(i + 1, ny - 1), id(i, ny - 1))).collect(),
    );
    sets.insert(
        "left".into(),
        (0..ny - 1).rev().map(|j| (id(0, j + 1), id(0, j))).collect(),
    );
    finish(nodes, elems, sets, order)
}

/// Half-disk of the given centre and radius; the arc below the diameter when
/// `down`. Edge sets "flat" and "arc".
pub fn half_disk(
    center: [f64; 2],
    radius: f64,
    down: bool,
    size: f64,
    grading: Option<Grading>,
    order: Order,
) -> Mesh2d {
    let g = grading.unwrap_or(Grading {
        h_min: size,
        ratio: 1.0,
        extent: 0.0,
    });
    let (h_min, ratio) = (g.h_min, g.ratio);
    // Angles on [−π, 0] (arc below the centre), finest at −π/2 (the apex).
    let pi = std::f64::consts::PI;
    // One quarter arc from the apex, its interval count padded to a multiple of 8
    // by splitting the coarsest intervals, so that the inward ring halvings stay
    // mirror-symmetric about the apex.
    let mut quarter = graded_points(0.0, 0.5 * pi * radius, 0.0, g, size);
    while (quarter.len() - 1) % 8 != 0 {
        let k = (1..quarter.len())
            .max_by(|&a, &b| (quarter[a] - quarter[a - 1]).total_cmp(&(quarter[b] - quarter[b - 1])))
            .unwrap();
        quarter.insert(k, 0.5 * (quarter[k] + quarter[k - 1]));
    }
    let mut thetas: Vec<f64> = quarter.iter().rev().map(|s| -0.5 * pi - s / radius).collect();
    thetas.extend(quarter.iter().skip(1).map(|s| -0.5 * pi + s / radius));
    // Radii from the rim inward: spacing h_min at the rim growing to `size`.
    let mut radii = vec![radius];
    {
        let mut h = h_min.min(size);
        let mut r = radius;
        loop {
            if r - h <= 0.75 * h + TIE * h {
                break;
            }
            r -= h;
            radii.push(r);
            // Keep h_min through the depth of the fine zone below the apex.
            if radius - r >= g.extent - TIE * h {
                h = (h * ratio).min(size);
            }
        }
    }
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    let mut elems: Vec<usize> = Vec::new();
    let polar = |r: f64, t: f64| [center[0] + r * t.cos(), center[1] + r * t.sin()];
    let mut ring: Vec<usize> = thetas
        .iter()
        .map(|&t| {
            nodes.push(polar(radius, t));
            nodes.len() - 1
        })
        .collect();
    let arc: Vec<(usize, usize)> = ring.windows(2).map(|w| (w[0], w[1])).collect();
    let mut flat_left = vec![ring[0]]; // nodes on θ = −π, from rim inward
    let mut flat_right = vec![*ring.last().unwrap()]; // θ = 0
    for k in 1..radii.len() {
        let r = radii[k];
        let dr = radii[k - 1] - r;
        let nseg = thetas.len() - 1;
        let mean_tangential = r * pi / nseg as f64;
        let coarsen = nseg >= 8 && nseg % 4 == 0 && mean_tangential < 0.5 * dr;
        if coarsen {
            // Keep every other angle (nseg is a multiple of 4, so this is symmetric
            // about the apex), then bridge with 3 triangles per pair.
            let keep: Vec<usize> = (0..=nseg).step_by(2).collect();
            let inner: Vec<usize> = keep
                .iter()
                .map(|&i| {
                    nodes.push(polar(r, thetas[i]));
                    nodes.len() - 1
                })
                .collect();
            for (q, w) in keep.windows(2).enumerate() {
                let (i0, i1) = (w[0], w[1]);
                let (a_in, b_in) = (inner[q], inner[q + 1]);
                let (a, m, b) = (ring[i0], ring[i0 + 1], ring[i1]);
                elems.extend_from_slice(&[a_in, a, m, a_in, m, b_in, b_in, m, b]);
            }
            thetas = keep.iter().map(|&i| thetas[i]).collect();
            ring = inner;
        } else {
            let inner: Vec<usize> = thetas
                .iter()
                .map(|&t| {
                    nodes.push(polar(r, t));
                    nodes.len() - 1
                })
                .collect();
            for i in 0..thetas.len() - 1 {
                let (a, b, c, d) = (ring[i], ring[i + 1], inner[i + 1], inner[i]);
                // Mirror the diagonal across the apex so the mesh is symmetric.
                if 2 * i < thetas.len() - 1 {
                    elems.extend_from_slice(&[d, a, b, d, b, c]);
                } else {
                    elems.extend_from_slice(&[a, b, c, a, c, d]);
                }
            }
            ring = inner;
        }
        flat_left.push(ring[0]);
        flat_right.push(*ring.last().unwrap());
    }
    // Fan to the centre.
    nodes.push(center);
    let c = nodes.len() - 1;
    for w in ring.windows(2) {
        elems.extend_from_slice(&[c, w[0], w[1]]);
    }
    // Flat face, oriented with the body on the left: walk from the θ=0 end
    // through the centre to the θ=−π end (for the arc below).
    let mut flat_nodes: Vec<usize> = flat_right.clone();
    flat_nodes.push(c);
    flat_nodes.extend(flat_left.iter().rev());
    let flat: Vec<(usize, usize)> = flat_nodes.windows(2).map(|w| (w[0], w[1])).collect();
    let mut sets = BTreeMap::new();
    sets.insert("arc".to_string(), arc);
    sets.insert("flat".to_string(), flat);
    if !down {
        // Mirror about the diameter; mirroring reverses orientation.
        for p in nodes.iter_mut() {
            p[1] = 2.0 * center[1] - p[1];
        }
        for t in elems.chunks_mut(3) {
            t.swap(1, 2);
        }
        for edges in sets.values_mut() {
            for e in edges.iter_mut() {
                *e = (e.1, e.0);
            }
            edges.reverse();
        }
    }
    finish(nodes, elems, sets, order)
}

/// Orients triangles, upgrades to T6 if asked, and attaches the edge sets.
fn finish(
    nodes: Vec<[f64; 2]>,
    mut elems: Vec<usize>,
    sets: BTreeMap<String, Vec<(usize, usize)>>,
    order: Order,
) -> Mesh2d {
    for t in elems.chunks_mut(3) {
        if signed_area(nodes[t[0]], nodes[t[1]], nodes[t[2]]) < 0.0 {
            t.swap(1, 2);
        }
    }
    let mesh = Mesh2d {
        order: Order::T3,
        nodes,
        elems,
        edge_sets: sets
            .into_iter()
            .map(|(k, v)| (k, v.into_iter().map(|(a, b)| Edge { a, b, mid: None }).collect()))
            .collect(),
    };
    match order {
        Order::T3 => mesh,
        Order::T6 => to_t6(mesh),
    }
}

/// Adds a midside node on every edge (affine T6).
pub fn to_t6(mesh: Mesh2d) -> Mesh2d {
    let mut nodes = mesh.nodes;
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let mut elems = Vec::with_capacity(2 * mesh.elems.len());
    for t in mesh.elems.chunks(3) {
        elems.extend_from_slice(t);
        for (p, q) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let key = (p.min(q), p.max(q));
            let m = *mid.entry(key).or_insert_with(|| {
                let (a, b) = (nodes[p], nodes[q]);
                nodes.push([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
                nodes.len() - 1
            });
            elems.push(m);
        }
    }
    let edge_sets = mesh
        .edge_sets
        .into_iter()
        .map(|(k, v)| {
            let v = v
                .into_iter()
                .map(|e| Edge {
                    mid: Some(mid[&(e.a.min(e.b), e.a.max(e.b))]),
                    ..e
                })
                .collect();
            (k, v)
        })
        .collect();
    Mesh2d {
        order: Order::T6,
        nodes,
        elems,
        edge_sets,
    }
}
