//! Nodal external loads: body forces, tractions and pressures on edge sets
//! (or on the part of one inside an x range), concentrated forces at
//! points of edge sets, and the loads of couplings on their coupled nodes.
//!
//! Surface loads are integrated with the edge's own shape functions (3-point
//! Gauss, exact for a uniform load on T3 and T6 edges); an edge crossing an
//! end of the x range is integrated over its part inside, mapped from the
//! straight chord between its corners. A point force at edge parameter s is
//! shared by the edge's nodes as N_i(s) (the consistent nodal load), so a force
//! at a node stays at that node.

use super::assembly::{assemble_loads, assemble_stiffness, DofMap, Stiffness};
use super::element;
use crate::error::{CoreError, InvalidKind};
use crate::mesh::{boundary::edge_normal, Edge, Mesh2d};
use crate::scene::{Body, Scene, Traction, COMPONENTS};

/// Where a point load falls: its edge's nodes and their shares N_i(s).
pub type Located = Vec<(usize, f64)>;

/// A point within this fraction of the nearest edge's length of the discrete
/// boundary is on it: a point given on the true curve of a meshed arc lies up
/// to the sagitta h²/(8R) off the chords.
const ON_EDGE: f64 = 0.05;

/// The point loads of every body on their meshes, per body in request order;
/// a point off its edge set is an `invalid_geometry` at the load's `at`.
pub fn locate_all(scene: &Scene, meshes: &[Mesh2d]) -> Result<Vec<Vec<Located>>, CoreError> {
    scene
        .bodies
        .iter()
        .zip(meshes)
        .map(|(body, mesh)| {
            body.point_loads
                .iter()
                .map(|pl| {
                    let edges = mesh.edge_sets.get(&pl.edges).map(|v| v.as_slice()).unwrap_or(&[]);
                    locate(mesh, edges, pl.at).map_err(|(distance, nearest)| {
                        let sc = scene.scales;
                        CoreError::invalid(
                            InvalidKind::Geometry,
                            format!("{}/at", pl.path),
                            format!(
                                "the point ({:.6e}, {:.6e}) is {:.3e} from edge set '{}' (nearest point ({:.6e}, \
                                    {:.6e})): a point load must lie on its edge set",
                                sc.length(pl.at[0]),
                                sc.length(pl.at[1]),
                                sc.length(distance),
                                pl.edges,
                                sc.length(nearest[0]),
                                sc.length(nearest[1])
                            ),
                        )
                    })
                })
                .collect()
        })
        .collect()
}

/// The edge of `edges` nearest to `p` and the shares of its nodes at the
/// nearest point, or (distance, nearest point) when `p` is off the edges.
fn locate(mesh: &Mesh2d, edges: &[Edge], p: [f64; 2]) -> Result<Located, (f64, [f64; 2])> {
    let mut best: Option<(f64, f64, &Edge, [f64; 2])> = None;
    for e in edges {
        let s = nearest_parameter(mesh, e, p);
        let x = point_at(mesh, e, s);
        let d = (x[0] - p[0]).hypot(x[1] - p[1]);
        if best.is_none_or(|b| d < b.0) {
            best = Some((d, s, e, x));
        }
    }
    let Some((d, s, e, x)) = best else {
        return Err((f64::INFINITY, p));
    };
    let (_, len) = edge_normal(mesh, e);
    if d > ON_EDGE * len + 1e-12 * mesh.size() {
        return Err((d, x));
    }
    let nodes: Vec<usize> = e.nodes().collect();
    let (n, _) = element::edge_shape(nodes.len(), s);
    Ok(nodes.into_iter().zip(n).filter(|&(_, w)| w != 0.0).collect())
}

fn point_at(mesh: &Mesh2d, e: &Edge, s: f64) -> [f64; 2] {
    let nodes: Vec<usize> = e.nodes().collect();
    let (n, _) = element::edge_shape(nodes.len(), s);
    let mut x = [0.0; 2];
    for (i, &node) in nodes.iter().enumerate() {
        x[0] += n[i] * mesh.nodes[node][0];
        x[1] += n[i] * mesh.nodes[node][1];
    }
    x
}

/// The edge parameter s ∈ [−1, 1] nearest to `p`: the chord's projection,
/// refined by Newton on |x(s) − p|² for a curved (T6) edge.
fn nearest_parameter(mesh: &Mesh2d, e: &Edge, p: [f64; 2]) -> f64 {
    let (a, b) = (mesh.nodes[e.a], mesh.nodes[e.b]);
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
    let mut s = (2.0 * t - 1.0).clamp(-1.0, 1.0);
    if e.mid.is_some() {
        let nodes: Vec<usize> = e.nodes().collect();
        for _ in 0..8 {
            let (_, dn) = element::edge_shape(3, s);
            let x = point_at(mesh, e, s);
            let mut dxds = [0.0; 2];
            for (i, &node) in nodes.iter().enumerate() {
                dxds[0] += dn[i] * mesh.nodes[node][0];
                dxds[1] += dn[i] * mesh.nodes[node][1];
            }
            // Gauss–Newton on the distance (x'' is small on a mesh edge).
            let g = (x[0] - p[0]) * dxds[0] + (x[1] - p[1]) * dxds[1];
            let h = dxds[0] * dxds[0] + dxds[1] * dxds[1];
            if h <= 0.0 {
                break;
            }
            s = (s - g / h).clamp(-1.0, 1.0);
        }
    }
    s
}

/// The part [s0, s1] of an edge with x in `range` (the chord's map), or None.
pub(crate) fn clip(mesh: &Mesh2d, e: &Edge, range: Option<[f64; 2]>) -> Option<(f64, f64)> {
    let Some([lo, hi]) = range else {
        return Some((-1.0, 1.0));
    };
    let (xa, xb) = (mesh.nodes[e.a][0], mesh.nodes[e.b][0]);
    if xa == xb {
        return (xa >= lo && xa <= hi).then_some((-1.0, 1.0));
    }
    let s_of = |x: f64| 2.0 * (x - xa) / (xb - xa) - 1.0;
    let (s0, s1) = {
        let (u, v) = (s_of(lo), s_of(hi));
        (u.min(v).max(-1.0), u.max(v).min(1.0))
    };
    (s1 > s0).then_some((s0, s1))
}

/// Which of a body's loads a nodal force comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    BodyForce,
    Traction(usize),
    PointLoad(usize),
    /// Component k (0 horizontal, 1 vertical, 2 rotation) of coupling j.
    Coupling(usize, usize),
}

impl Source {
    /// The load's JSON pointer in the request.
    pub fn path(self, body: &Body) -> String {
        match self {
            Source::BodyForce => format!("{}/body_force", body.path),
            Source::Traction(k) => format!("{}/tractions/{k}", body.path),
            Source::PointLoad(k) => body.point_loads[k].path.clone(),
            Source::Coupling(j, k) => format!("{}/{}/load", body.couplings[j].path, COMPONENTS[k]),
        }
    }
}

/// Nodal external loads (tractions, pressures, point forces, body forces) on
/// every global DOF, fixed ones included: the rigid modes of a body need them
/// all. `points`: `locate_all` of the scene.
pub fn external(scene: &Scene, meshes: &[Mesh2d], dofs: &DofMap, points: &[Vec<Located>]) -> Vec<f64> {
    let mut f = vec![0.0; dofs.free.len()];
    for (b, mesh) in meshes.iter().enumerate().take(scene.bodies.len()) {
        each_load(scene, b, mesh, &points[b], |_, node, c, v| f[dofs.dof(b, node, c)] += v);
    }
    f
}

/// Resultant force and moment about `center` (Fx, Fy, M) of each load of
/// body `b` that has one, with the load's source.
pub fn resultants(
    scene: &Scene,
    b: usize,
    mesh: &Mesh2d,
    points: &[Located],
    center: [f64; 2],
) -> Vec<(Source, [f64; 3])> {
    let mut out: Vec<(Source, [f64; 3])> = Vec::new();
    each_load(scene, b, mesh, points, |src, node, c, v| {
        let k = match out.iter().position(|(s, _)| *s == src) {
            Some(k) => k,
            None => {
                out.push((src, [0.0; 3]));
                out.len() - 1
            }
        };
        let (dx, dy) = (mesh.nodes[node][0] - center[0], mesh.nodes[node][1] - center[1]);
        out[k].1[c] += v;
        out[k].1[2] += if c == 0 { -dy * v } else { dx * v };
    });
    out
}

/// Every nodal force of body `b`'s loads, as (source, node, component, value)
/// in assembly order (the sum over them is `external`, bit for bit).
fn each_load(
    scene: &Scene,
    b: usize,
    mesh: &Mesh2d,
    points: &[Located],
    mut add: impl FnMut(Source, usize, usize, f64),
) {
    let body = &scene.bodies[b];
    let mut fe = [0.0; 12];
    let k = mesh.order.nodes_per_element();
    if body.body_force != [0.0, 0.0] {
        let mut x = [[0.0; 2]; 6];
        for e in 0..mesh.n_elems() {
            let conn = mesh.elem(e);
            for (i, &node) in conn.iter().enumerate() {
                x[i] = mesh.nodes[node];
            }
            element::body_load(
                mesh.order,
                &x[..k],
                body.body_force,
                &|p| scene.analysis.measure(p),
                &mut fe,
            );
            for (i, &node) in conn.iter().enumerate() {
                for c in 0..2 {
                    add(Source::BodyForce, node, c, fe[2 * i + c]);
                }
            }
        }
    }
    for (j, t) in body.tractions.iter().enumerate() {
        let (edges, vector, pressure, range) = match t {
            Traction::Vector { edges, t, x_range } => (edges, Some(*t), 0.0, *x_range),
            Traction::Pressure { edges, p, x_range } => (edges, None, *p, *x_range),
        };
        for edge in mesh.edge_sets.get(edges).map(|v| v.as_slice()).unwrap_or(&[]) {
            let Some((s0, s1)) = clip(mesh, edge, range) else {
                continue;
            };
            let nodes: Vec<usize> = edge.nodes().collect();
            let (normal, _) = edge_normal(mesh, edge);
            let half = 0.5 * (s1 - s0);
            for g in &element::GAUSS3 {
                // The whole edge keeps the plain Gauss points (bit for bit).
                let s = if range.is_none() {
                    g[0]
                } else {
                    s0 + half * (g[0] + 1.0)
                };
                let (nn, dn) = element::edge_shape(nodes.len(), s);
                let (mut tx, mut ty, mut at) = (0.0, 0.0, [0.0; 2]);
                for (i, &node) in nodes.iter().enumerate() {
                    tx += dn[i] * mesh.nodes[node][0];
                    ty += dn[i] * mesh.nodes[node][1];
                    at[0] += nn[i] * mesh.nodes[node][0];
                    at[1] += nn[i] * mesh.nodes[node][1];
                }
                // 2πr in axisymmetry: the nodal forces are ring totals.
                let measure = scene.analysis.measure(at);
                let jac = (tx * tx + ty * ty).sqrt();
                // Pressure acts against the local outward normal (−t⊥ of the tangent).
                let tr = vector.unwrap_or_else(|| {
                    let (nx, ny) = if jac > 0.0 {
                        (ty / jac, -tx / jac)
                    } else {
                        (normal[0], normal[1])
                    };
                    [-pressure * nx, -pressure * ny]
                });
                for (i, &node) in nodes.iter().enumerate() {
                    for (c, tc) in tr.iter().enumerate() {
                        add(Source::Traction(j), node, c, g[1] * half * jac * measure * nn[i] * tc);
                    }
                }
            }
        }
    }
    for (j, (pl, at)) in body.point_loads.iter().zip(points).enumerate() {
        for &(node, share) in at {
            for c in 0..2 {
                add(Source::PointLoad(j), node, c, share * pl.force[c]);
            }
        }
    }
    for (j, cp) in body.couplings.iter().enumerate() {
        for k in 0..3 {
            for (node, f) in coupling_forces(cp, mesh, k) {
                for (c, v) in f.into_iter().enumerate() {
                    add(Source::Coupling(j, k), node, c, v);
                }
            }
        }
    }
}

/// Nodal forces on the coupled nodes statically equivalent to the load of
/// the coupling's component k (Fx, Fy or M about the reference point; none
/// where it is a displacement): F/n each, plus the moment about the nodes'
/// centroid c as forces M_c e3 × (x − c) / Σ|x − c|². The coupled nodes are
/// held in K̃, so these forces act only through the body's rigid modes, on
/// which their work is F·U + M θ whatever the split.
pub fn coupling_forces(cp: &crate::scene::Coupling, mesh: &Mesh2d, k: usize) -> Vec<(usize, [f64; 2])> {
    let load = |c: usize| if c == k { cp.load(c) } else { 0.0 };
    let (fx, fy, m) = (load(0), load(1), load(2));
    if fx == 0.0 && fy == 0.0 && m == 0.0 {
        return Vec::new();
    }
    let nodes = mesh.edge_set_nodes(&cp.edges);
    let n = nodes.len() as f64;
    let c = nodes.iter().fold([0.0; 2], |a, &i| {
        [a[0] + mesh.nodes[i][0] / n, a[1] + mesh.nodes[i][1] / n]
    });
    let spread: f64 = nodes
        .iter()
        .map(|&i| (mesh.nodes[i][0] - c[0]).powi(2) + (mesh.nodes[i][1] - c[1]).powi(2))
        .sum();
    let (rx, ry) = (cp.reference[0] - c[0], cp.reference[1] - c[1]);
    let m_c = m + rx * fy - ry * fx;
    // An edge set has two distinct corners at least, so spread > 0.
    let turn = if spread > 0.0 { m_c / spread } else { 0.0 };
    nodes
        .into_iter()
        .map(|i| {
            let (dx, dy) = (mesh.nodes[i][0] - c[0], mesh.nodes[i][1] - c[1]);
            (i, [fx / n - turn * dy, fy / n + turn * dx])
        })
        .collect()
}

/// Stiffness and loads together (no cache): `assembly`'s two halves and the
/// loads of this module, here so that `assembly` does not read the loads.
pub struct Assembled {
    pub dofs: DofMap,
    pub stiffness: std::sync::Arc<Stiffness>,
    /// f_f − K_fd u_d.
    pub f: Vec<f64>,
}

/// Stiffness and loads together (no cache).
pub fn assemble(scene: &Scene, meshes: &[Mesh2d], dofs: DofMap) -> Result<Assembled, CoreError> {
    let stiffness = assemble_stiffness(scene, meshes, &dofs)?;
    let points = locate_all(scene, meshes)?;
    let f = assemble_loads(&external(scene, meshes, &dofs, &points), &dofs, &stiffness);
    Ok(Assembled {
        dofs,
        stiffness: std::sync::Arc::new(stiffness),
        f,
    })
}
