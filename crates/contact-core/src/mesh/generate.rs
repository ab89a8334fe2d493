//! Generated meshes graded toward the contact region.
//!
//! Grading: element size `h_min` within `extent` of the focus, growing by
//! `ratio` per element up to the nominal `size`. Graded meshes are made by
//! constrained Delaunay refinement (`refine`) from a boundary discretized at
//! that size, so every angle is at least 28° and the interior grades by itself;
//! a region symmetric about the focus is meshed by halves and mirrored, so the
//! mesh is exactly symmetric (a structured pattern put a node of valence 4 at
//! the focus of the rectangle where its neighbours had 3, and the Hertz
//! pressure dipped 1.2 % there). A uniform rectangle stays a structured grid.
//!
//! Length: about 600 lines of generators (rectangle, half- and quarter-disk,
//! grading) and their tests (node counts, symmetry, element quality).

use std::collections::{BTreeMap, HashMap};

use super::{refine, signed_area, Edge, Mesh2d, Order};

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

/// Rectangle [x0, x0+w] × [y0, y0+h] with edge sets bottom, right, top, left.
pub fn rectangle(
    corner: [f64; 2],
    w: f64,
    h: f64,
    size: f64,
    grading: Option<([f64; 2], Grading)>,
    order: Order,
) -> Result<Mesh2d, refine::MeshFailure> {
    if let Some((focus, g)) = grading {
        // Meshed with its corner at the origin (full relative precision), then moved.
        // The subtraction rounds at the corner's magnitude; a focus meant on a
        // side, a corner or the centre line is put there exactly, so that the
        // mesh does not change when the scene is translated (refinement is
        // not continuous in its input: a shift of 1e-15 changed 1,138 DOF
        // into 1,158).
        let tie = TIE * w.max(h);
        let snap = |x: f64, marks: [f64; 3]| marks.into_iter().find(|m| (x - m).abs() <= tie).unwrap_or(x);
        let local = [
            snap(focus[0] - corner[0], [0.0, 0.5 * w, w]),
            snap(focus[1] - corner[1], [0.0, 0.5 * h, h]),
        ];
        let l = w.max(h);
        let mut t = rectangle_graded(
            unit(w / l),
            unit(h / l),
            unit(size / l),
            [unit(local[0] / l), unit(local[1] / l)],
            Grading {
                h_min: unit(g.h_min / l),
                ratio: g.ratio,
                extent: unit(g.extent / l),
            },
        )?;
        for p in t.nodes.iter_mut() {
            *p = [p[0] * l, p[1] * l];
        }
        for p in t.nodes.iter_mut() {
            *p = [p[0] + corner[0], p[1] + corner[1]];
        }
        return Ok(finish(t.nodes, t.elems, t.sets, order));
    }
    // Uniform: a structured grid of nearly square cells, each cut in two along
    // the same diagonal (smallest angle 45° for square cells).
    let (x0, y0) = (corner[0], corner[1]);
    let nx = (w / size).ceil().max(1.0) as usize;
    let ny = (h / size).ceil().max(1.0) as usize;
    let xs: Vec<f64> = (0..=nx).map(|i| x0 + w * i as f64 / nx as f64).collect();
    let ys: Vec<f64> = (0..=ny).map(|j| y0 + h * j as f64 / ny as f64).collect();
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
            elems.extend_from_slice(&[a, b, c, a, c, d]);
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
    Ok(finish(nodes, elems, sets, order))
}

/// Element size at distance `d` from the focus: `h_min` within `extent`, then
/// growing by the factor `ratio` per element (so linearly in d, slope
/// ratio − 1) up to `size`.
pub fn size_at(d: f64, g: Grading, size: f64) -> f64 {
    let h = if d <= g.extent {
        g.h_min
    } else {
        g.h_min + (g.ratio - 1.0) * (d - g.extent)
    };
    h.min(size)
}

/// Lattice rows of points under a contact surface (`refine::layers`).
const SURFACE_ROWS: usize = 3;

/// Which part of the disk `disk` meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiskPart {
    /// Edge sets "flat" (the diameter) and "arc".
    Half,
    /// The half on the +x side of the centre: edge sets "flat", "arc" and
    /// "axis" (the symmetry line x = centre, where a symmetric model is held).
    Quarter,
}

/// Half- or quarter-disk of the given centre and radius, the arc below the
/// diameter when `down`, graded toward the apex of the arc. The quarter is
/// meshed by constrained Delaunay refinement and the half is its mirror image,
/// so the mesh is exactly symmetric about the apex line.
pub fn disk(
    center: [f64; 2],
    radius: f64,
    down: bool,
    part: DiskPart,
    size: f64,
    grading: Option<Grading>,
    order: Order,
) -> Result<Mesh2d, refine::MeshFailure> {
    let g = grading.unwrap_or(Grading {
        h_min: size,
        ratio: 1.0,
        extent: 0.0,
    });
    let mut t = unit_disk(
        part,
        unit(size / radius),
        Grading {
            h_min: unit(g.h_min / radius),
            ratio: g.ratio,
            extent: unit(g.extent / radius),
        },
    )?;
    if !down {
        // Mirror about the diameter; mirroring reverses orientation.
        for p in t.nodes.iter_mut() {
            p[1] = -p[1];
        }
        for tri in t.elems.chunks_mut(3) {
            tri.swap(1, 2);
        }
        for edges in t.sets.values_mut() {
            for e in edges.iter_mut() {
                *e = (e.1, e.0);
            }
            edges.reverse();
        }
    }
    for p in t.nodes.iter_mut() {
        *p = [center[0] + radius * p[0], center[1] + radius * p[1]];
    }
    let mut mesh = finish(t.nodes, t.elems, t.sets, order);
    // Isoparametric arc: the midsides of the arc's T6 edges on the circle, not
    // on the chords. A midside multiplier (`contact::rows::T6Multiplier`)
    // would see the chord's sagitta h²/8R as a bump in the gap.
    if let Some(arc) = mesh.edge_sets.get("arc") {
        for m in arc.iter().filter_map(|e| e.mid).collect::<Vec<_>>() {
            let p = mesh.nodes[m];
            let (dx, dy) = (p[0] - center[0], p[1] - center[1]);
            let r = dx.hypot(dy);
            mesh.nodes[m] = [center[0] + radius * dx / r, center[1] + radius * dy / r];
        }
    }
    Ok(mesh)
}

/// A parameter of a mesh in its body's own units, rounded to 12 significant
/// digits: a change of units (mm → m) or of the scene's length scale changes
/// it in the last bits, and refinement is not continuous in such changes; the
/// rounding makes the mesh the same to the last bit.
fn unit(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let e = 10f64.powi(x.abs().log10().floor() as i32 - 11);
    (x / e).round() * e
}

/// The disk of `disk` with radius 1 and centre at the origin, arc below.
fn unit_disk(part: DiskPart, size: f64, g: Grading) -> Result<refine::Triangulated, refine::MeshFailure> {
    let radius = 1.0;
    let center = [0.0, 0.0];
    let half_pi = 0.5 * std::f64::consts::PI;
    let apex = [center[0], center[1] - radius];
    let rim = [center[0] + radius, center[1]];
    let h = |p: [f64; 2]| size_at(((p[0] - apex[0]).powi(2) + (p[1] - apex[1]).powi(2)).sqrt(), g, size);
    // Counter-clockwise: apex → rim along the arc, rim → centre, centre → apex.
    let mut points: Vec<[f64; 2]> = graded_points(0.0, half_pi * radius, 0.0, g, size)
        .iter()
        .map(|s| {
            let t = -half_pi + s / radius;
            [center[0] + radius * t.cos(), center[1] + radius * t.sin()]
        })
        .collect();
    points.pop();
    let mut sets = vec!["arc"; points.len()];
    for (set, mut pts) in [
        ("flat", refine::side(rim, center, &h)),
        ("axis", refine::toward(center, apex, SURFACE_ROWS, &h)),
    ] {
        pts.pop();
        sets.extend(std::iter::repeat_n(set, pts.len()));
        points.extend(pts);
    }
    let snap = |set: &str, p: [f64; 2]| {
        if set != "arc" {
            return p;
        }
        let (dx, dy) = (p[0] - center[0], p[1] - center[1]);
        let r = (dx * dx + dy * dy).sqrt();
        [center[0] + radius * dx / r, center[1] + radius * dy / r]
    };
    let n_arc = sets.iter().filter(|&&s| s == "arc").count();
    let mut arc_chain: Vec<[f64; 2]> = points[..n_arc].to_vec();
    arc_chain.push(rim);
    let to_straight_sides = |p: [f64; 2]| (center[1] - p[1]).min(p[0] - center[0]);
    let inward = |p: [f64; 2]| {
        let (dx, dy) = (center[0] - p[0], center[1] - p[1]);
        let l = (dx * dx + dy * dy).sqrt();
        [dx / l, dy / l]
    };
    let mut seeds = refine::layers(&arc_chain, SURFACE_ROWS, &inward, &|p, h| {
        to_straight_sides(p) >= 0.25 * h
    });
    let clearance = |p: [f64; 2]| {
        let r = ((p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2)).sqrt();
        let step = size_at(((p[0] - apex[0]).powi(2) + (p[1] - apex[1]).powi(2)).sqrt(), g, size);
        // Below the surface rows.
        (radius - r - SURFACE_ROWS as f64 * 0.866 * step).min(to_straight_sides(p))
    };
    let region = [[center[0], center[1] - radius], [center[0] + radius, center[1]]];
    seeds.extend(refine::rings(apex, &|d| size_at(d, g, size), &clearance, size, region));
    let mut t = refine::triangulate(&refine::Outline { points, sets }, &seeds, size, &snap)?;
    if part == DiskPart::Half {
        t = refine::mirror(t, center[0], "axis", &|name: &str| name.to_string());
    }
    Ok(t)
}

/// Rectangle [x0, x0+w] × [y0, y0+h] graded toward `focus` by constrained
/// Delaunay refinement (edge sets bottom, right, top, left). A focus on a side
/// is a node; a rectangle symmetric about the focus's x gets a mesh that is
/// exactly symmetric too (its left half mirrored).
fn rectangle_graded(
    w: f64,
    hgt: f64,
    size: f64,
    focus: [f64; 2],
    g: Grading,
) -> Result<refine::Triangulated, refine::MeshFailure> {
    let (x0, y0, x1, y1) = (0.0, 0.0, w, hgt);
    let h = |p: [f64; 2]| size_at(((p[0] - focus[0]).powi(2) + (p[1] - focus[1]).powi(2)).sqrt(), g, size);
    let tie = TIE * w.max(hgt);
    let symmetric = focus[0] > x0 + tie && focus[0] < x1 - tie && ((focus[0] - x0) - (x1 - focus[0])).abs() <= tie;
    let xr = if symmetric { focus[0] } else { x1 };
    let corners = [[x0, y0], [xr, y0], [xr, y1], [x0, y1]];
    let names = ["bottom", if symmetric { "axis" } else { "right" }, "top", "left"];
    let (mut points, mut sets) = (Vec::new(), Vec::new());
    // The contact surface: the side through the focus, lattice rows under it.
    let mut surface: Option<(usize, Vec<[f64; 2]>, [f64; 2])> = None;
    let same = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() <= tie && (p[1] - q[1]).abs() <= tie;
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        // A focus on this side (strictly inside it) becomes a node.
        let on_side = |p: [f64; 2]| {
            let (d, r) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
            let l2 = d[0] * d[0] + d[1] * d[1];
            let t = (r[0] * d[0] + r[1] * d[1]) / l2;
            (r[0] * d[1] - r[1] * d[0]).abs() <= tie * l2.sqrt() && t * l2.sqrt() > tie && (1.0 - t) * l2.sqrt() > tie
        };
        let mut pts = if on_side(focus) {
            let mut first = refine::side(a, focus, &h);
            first.pop();
            first.extend(refine::side(focus, b, &h));
            first
        } else if names[k] == "axis" && same(b, focus) {
            refine::toward(a, focus, SURFACE_ROWS, &h)
        } else if names[k] == "axis" && same(a, focus) {
            let mut p = refine::toward(b, focus, SURFACE_ROWS, &h);
            p.reverse();
            p
        } else {
            refine::side(a, b, &h)
        };
        let through_focus = on_side(focus) || (symmetric && names[k] != "axis" && (same(a, focus) || same(b, focus)));
        if through_focus && surface.is_none() {
            // Into the body: the left normal of the counter-clockwise side.
            let l = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            surface = Some((k, pts.clone(), [-(b[1] - a[1]) / l, (b[0] - a[0]) / l]));
        }
        pts.pop();
        sets.extend(std::iter::repeat_n(names[k], pts.len()));
        points.extend(pts);
    }
    // Distance to side k (bottom, right or axis, top, left).
    let dist = move |k: usize, p: [f64; 2]| [p[1] - y0, xr - p[0], y1 - p[1], p[0] - x0][k];
    let apart = move |skip: Option<usize>, p: [f64; 2]| {
        (0..4)
            .filter(|&k| Some(k) != skip)
            .map(|k| dist(k, p))
            .fold(f64::INFINITY, f64::min)
    };
    let mut seeds = Vec::new();
    let clearance: Box<dyn Fn([f64; 2]) -> f64> = match surface {
        Some((ks, chain, n)) => {
            seeds = refine::layers(&chain, SURFACE_ROWS, &|_| n, &|p, hh| apart(Some(ks), p) >= 0.25 * hh);
            // Below the surface rows, away from the other sides.
            Box::new(move |p| (dist(ks, p) - SURFACE_ROWS as f64 * 0.866 * h(p)).min(apart(Some(ks), p)))
        }
        None => Box::new(move |p| apart(None, p)),
    };
    let region = [[x0, y0], [xr, y1]];
    seeds.extend(refine::rings(
        focus,
        &|d| size_at(d, g, size),
        &*clearance,
        size,
        region,
    ));
    let t = refine::triangulate(&refine::Outline { points, sets }, &seeds, size, &|_, p| p)?;
    Ok(if symmetric {
        refine::mirror(t, focus[0], "axis", &|name: &str| {
            if name == "left" { "right" } else { name }.to_string()
        })
    } else {
        t
    })
}

/// Orients triangles, upgrades to T6 if asked, and attaches the edge sets.
pub(super) fn finish(
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

#[cfg(test)]
mod tests {
    use super::*;

    fn min_angle_deg(m: &Mesh2d) -> f64 {
        let mut worst = 180.0f64;
        for e in 0..m.n_elems() {
            let t = m.elem(e);
            let p = [m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]];
            for k in 0..3 {
                let (a, b, c) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
                let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
                let cos = (u[0] * v[0] + u[1] * v[1]) / ((u[0].hypot(u[1])) * (v[0].hypot(v[1])));
                worst = worst.min(cos.clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
        worst
    }

    /// Every graded generator at three sizes: the smallest angle is at least
    /// 25° (refinement asks 28°; snapping split arc points onto the circle may
    /// take a little), every element is positively oriented, every node is
    /// used, and the symmetric ones are exactly symmetric.
    #[test]
    fn graded_meshes_are_well_shaped_and_symmetric() {
        for h_min in [0.02, 0.005, 0.00125] {
            let g = Grading {
                h_min,
                ratio: 1.1,
                extent: 0.1,
            };
            let meshes = [
                (
                    "half disk",
                    disk([0.0, 1.0], 1.0, true, DiskPart::Half, 0.2, Some(g), Order::T3).unwrap(),
                    true,
                ),
                (
                    "quarter disk",
                    disk([0.0, 1.0], 1.0, true, DiskPart::Quarter, 0.2, Some(g), Order::T3).unwrap(),
                    false,
                ),
                (
                    "rectangle",
                    rectangle([-2.0, -1.0], 4.0, 1.0, 0.5, Some(([0.0, 0.0], g)), Order::T3).unwrap(),
                    true,
                ),
                (
                    "off-centre",
                    rectangle([-2.0, -1.0], 4.0, 1.0, 0.5, Some(([0.7, 0.0], g)), Order::T3).unwrap(),
                    false,
                ),
            ];
            for (name, m, symmetric) in meshes {
                let angle = min_angle_deg(&m);
                eprintln!("{name} h_min {h_min}: {} nodes, {:.1}°", m.nodes.len(), angle);
                assert!(angle >= 25.0, "{name} h_min {h_min}: {angle:.1}°");
                for e in 0..m.n_elems() {
                    let t = m.elem(e);
                    assert!(signed_area(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]) > 0.0);
                }
                let mut used = vec![false; m.nodes.len()];
                m.elems.iter().for_each(|&n| used[n] = true);
                assert!(used.iter().all(|&u| u), "{name}: unused nodes");
                if symmetric {
                    let key = |p: [f64; 2]| ((p[0] * 1e9).round() as i64, (p[1] * 1e9).round() as i64);
                    let all: std::collections::HashSet<_> = m.nodes.iter().map(|&p| key(p)).collect();
                    // A neighbouring key too: a coordinate within round-off of a rounding boundary.
                    let has = |p: [f64; 2]| {
                        let (i, j) = key(p);
                        (-1..=1).any(|di| (-1..=1).any(|dj| all.contains(&(i + di, j + dj))))
                    };
                    let odd: Vec<_> = m.nodes.iter().filter(|&&p| !has([-p[0], p[1]])).collect();
                    assert!(
                        odd.is_empty(),
                        "{name}: {} nodes without a mirror image, e.g. {:?}",
                        odd.len(),
                        &odd[..odd.len().min(4)]
                    );
                }
            }
        }
    }

    /// A T6 disk's arc is isoparametric: every arc midside lies on the circle
    /// (to round-off) and projects onto its chord's midpoint (by symmetry: the
    /// tolerance is round-off of the radial projection), while every other
    /// midside is its edge's midpoint; the curved elements stay positively
    /// oriented (the Jacobian at the 3-point rule's points and at the six
    /// nodes).
    #[test]
    fn t6_arc_midsides_lie_on_the_circle() {
        let (center, radius) = ([0.3, 2.0], 1.5);
        let g = Grading {
            h_min: 0.01,
            ratio: 1.2,
            extent: 0.1,
        };
        let m = disk(center, radius, true, DiskPart::Half, 0.5, Some(g), Order::T6).unwrap();
        let arc: Vec<Edge> = m.edge_sets["arc"].clone();
        assert!(arc.len() > 20);
        let mut on_arc = std::collections::HashSet::new();
        for e in &arc {
            let (a, b, c) = (m.nodes[e.a], m.nodes[e.b], m.nodes[e.mid.unwrap()]);
            on_arc.insert(e.mid.unwrap());
            let r = (c[0] - center[0]).hypot(c[1] - center[1]);
            assert!((r - radius).abs() < 1e-12 * radius, "midside at r = {r}");
            let d = [b[0] - a[0], b[1] - a[1]];
            let t = ((c[0] - a[0]) * d[0] + (c[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]);
            assert!((t - 0.5).abs() < 1e-9, "midside at {t} of its chord");
        }
        for e in 0..m.n_elems() {
            let t = m.elem(e);
            for (k, (p, q)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                let (a, b, c) = (m.nodes[t[p]], m.nodes[t[q]], m.nodes[t[3 + k]]);
                if !on_arc.contains(&t[3 + k]) {
                    assert!((c[0] - 0.5 * (a[0] + b[0])).abs() + (c[1] - 0.5 * (a[1] + b[1])).abs() < 1e-12);
                }
            }
            let x: Vec<[f64; 2]> = t.iter().map(|&n| m.nodes[n]).collect();
            for [xi, eta] in crate::fem::element::T6_CHECK_POINTS {
                let det = crate::fem::element::t6_map(&x, xi, eta).1;
                assert!(det > 0.0, "element {e}: det J {det} at ({xi}, {eta})");
            }
        }
    }
}
