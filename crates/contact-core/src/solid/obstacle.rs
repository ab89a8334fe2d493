//! Contact rows of a face set against a rigid obstacle (a plane, a sphere,
//! a cylinder or a paraboloid: `scene::solid_obstacle`): nodal on T4 faces,
//! dual mortar on T10 faces.
//!
//! The obstacle answers, for a point x, its signed distance d(x) (positive
//! outside, where the body is) and the unit normal n(x) out of it at the
//! closest obstacle point; non-penetration d(x + u) ≥ 0 is linearized as
//! d(x) + n(x)·u ≥ 0, the signed-distance rows of the 2D rigid obstacles
//! (`contact::rows`), exact for a plane. On T4 faces
//!
//! ```text
//! −n_i·u_i ≤ d(x_i)      (one row per node of the face set, n_i = n(x_i))
//! ```
//!
//! whose multiplier λ_i ≥ 0 is the node's contact force (+λ_i n_i on the
//! body). Its tributary area a_i = ∫ N_i dA over the face set gives the
//! nodal pressure λ_i / a_i, exact for a uniform pressure (the consistent
//! load of a uniform p is p a_i).
//!
//! On T10 faces (6-node triangles) nodal rows cannot work: a corner's
//! shape function integrates to 0 over a triangle, so a corner carries no
//! share of a uniform pressure. The rows there are dual mortar rows on the
//! corners (Wohlmuth 2000; the 2D T6 `Corners` scheme of `contact::rows`):
//! multiplier hats Φ_i = L_i (linear on each face), tested with their
//! biorthogonal partners Ψ_i = 4 L_i − 1 (∫ Ψ_i Φ_j dA = δ_ij ∫ Φ_j dA on a
//! flat triangle: its mass matrix is A/12 (1 + δ_ij)), so row i reads
//!
//! ```text
//! −n_i · Σ_j (∫ Ψ_i N_j dA / a_i) u_j ≤ ∫ Ψ_i d dA / a_i,   a_i = ∫ Φ_i dA,
//! ```
//!
//! the weighted mean of the gap over the corner's faces, with N_j the face's
//! quadratic shape functions. Since Σ_i Ψ_i = 1, λ_i = p a_i puts the
//! consistent load p ∫ N_j dA on every node: a uniform pressure is
//! transmitted exactly, and p_i = λ_i / a_i is the pressure at corner i.
//! Non-penetration then holds in this weighted mean, not at every node.
//! Integrated with Dunavant's degree-4 rule (Ψ N d is of degree 4 on a flat
//! face against a plane: exact there; against a curved obstacle d is
//! smooth and the rule's error is of higher order than the mean's own).
//!
//! **Which normal a T10 row follows.** The gap d is sampled at every
//! quadrature point (the distance to the closest obstacle point from there),
//! but the row moves along one direction, n_i = n(x_i), the normal at the
//! obstacle point closest to its corner. The 2D mortar rows carry each
//! point's own direction inside the integral instead, ∫ Ψ_i n(x)·u; the two
//! differ by ∫ Ψ_i (n(x) − n_i)·u, where |n(x) − n_i| is at most the
//! angle the corner's faces subtend on the obstacle, h/R: a fraction h/R of
//! the tangential displacement (h/R from 1/270 to 1/100 at the patches of the tests).
//! One direction per row keeps a row's force a force along one normal at
//! one point (λ_i n_i, whose pressure λ_i / a_i is a normal pressure), the
//! rows' terms scalar weights summing to 1 (where the force acts:
//! `report`), and against a plane the rows are the plane's rows bit for bit.

use super::SolidBody;
use crate::error::{CoreError, InvalidKind};
use crate::fem::reference::{triangle::RULE6, ReferenceElement, T6};
use crate::mesh3d::{cross, dot, Face, Mesh3d, Order};
pub use crate::scene::solid::{Obstacle, Plane};

/// The candidate rows: one per node of the contact face set (T4), one per
/// corner (T10).
#[derive(Debug, Clone)]
pub struct ObstacleRows {
    pub obstacle: Obstacle,
    /// The contact face set the rows were made from (`report` reads its
    /// faces).
    pub faces: String,
    /// The multiplier node of each row.
    pub nodes: Vec<usize>,
    /// Each row's nodal terms (node, c): the row reads −n_i · Σ c u_node ≤
    /// gap (T4: its own node, c = 1).
    pub terms: Vec<Vec<(usize, f64)>>,
    /// Each row's unit direction n_i, out of the obstacle at the point
    /// closest to the row's node (module doc).
    pub normal: Vec<[f64; 3]>,
    /// The row's area a_i = ∫ Φ_i dA (pressure = λ_i / a_i).
    pub area: Vec<f64>,
    /// The gap before deformation (T4: d(x_i); T10: its dual-weighted mean).
    pub gap: Vec<f64>,
}

impl ObstacleRows {
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The rows' gaps after the displacement `u` (every DOF, 3·node + c).
    pub fn gaps_after(&self, u: &[f64]) -> Vec<f64> {
        let moved = |n: &[f64; 3], &(node, c): &(usize, f64)| c * (0..3).map(|k| n[k] * u[3 * node + k]).sum::<f64>();
        self.terms
            .iter()
            .zip(&self.normal)
            .zip(&self.gap)
            .map(|((t, n), g)| g + t.iter().map(|term| moved(n, term)).sum::<f64>())
            .collect()
    }
}

/// The rows of face set `faces` against `obstacle`.
pub fn rows(body: &SolidBody, faces: &str, obstacle: impl Into<Obstacle>) -> Result<ObstacleRows, CoreError> {
    rows_with(body, faces, obstacle.into(), &|_| 0.0)
}

/// The rows with `extra(x)` added to the distance d(x) before it is
/// weighted: a flat face set standing for a curved one (Hertz's paraboloid
/// r²/2R, `scene::SolidScene::extra_gap`). Integrated as d is on T10
/// faces (a quadratic `extra` exactly on a flat face).
pub fn rows_with(
    body: &SolidBody,
    faces: &str,
    obstacle: Obstacle,
    extra: &dyn Fn([f64; 3]) -> f64,
) -> Result<ObstacleRows, CoreError> {
    let mesh = body.mesh;
    let set = body.face_set(faces, "contact/faces")?;
    if set.is_empty() {
        return Err(CoreError::invalid(
            InvalidKind::NoContactCandidates,
            "contact/faces",
            format!("face set '{faces}' is empty: there is nothing to touch the obstacle"),
        ));
    }
    match mesh.order {
        Order::T4 => nodal(mesh, set, faces, obstacle, extra),
        Order::T10 => mortar(mesh, set, faces, obstacle, extra),
    }
}

/// The distance and normal at x, or the refusal of a candidate where the
/// obstacle has no normal.
fn closest(obstacle: &Obstacle, x: [f64; 3]) -> Result<(f64, [f64; 3]), CoreError> {
    obstacle.closest(x).ok_or_else(|| {
        CoreError::invalid(
            InvalidKind::Geometry,
            "obstacle",
            // x is nondimensional here: the message names no coordinates.
            "a contact candidate lies where the obstacle has no normal (a sphere's centre, a cylinder's axis) or \
             off a height field's grid: place the obstacle outside the body, and a height field's grid under the \
             whole contact face set",
        )
    })
}

fn nodal(
    mesh: &Mesh3d,
    set: &[Face],
    faces: &str,
    obstacle: Obstacle,
    extra: &dyn Fn([f64; 3]) -> f64,
) -> Result<ObstacleRows, CoreError> {
    let nodes = mesh.face_set_nodes(faces);
    let mut index = std::collections::HashMap::with_capacity(nodes.len());
    for (i, &n) in nodes.iter().enumerate() {
        index.insert(n, i);
    }
    let mut area = vec![0.0; nodes.len()];
    for f in set {
        let (a, _) = mesh.face_area_normal(f);
        for c in f.corners {
            area[index[&c]] += a / 3.0;
        }
    }
    let seen = nodes
        .iter()
        .map(|&n| closest(&obstacle, mesh.nodes[n]))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(ObstacleRows {
        obstacle,
        faces: faces.to_string(),
        terms: nodes.iter().map(|&n| vec![(n, 1.0)]).collect(),
        normal: seen.iter().map(|s| s.1).collect(),
        gap: nodes
            .iter()
            .zip(&seen)
            .map(|(&n, s)| s.0 + extra(mesh.nodes[n]))
            .collect(),
        nodes,
        area,
    })
}

/// A quadrature point of a 6-node face: its barycentric coordinates L, the
/// face's shape functions N there, the area it weighs (the rule's weight
/// times |∂x/∂ξ × ∂x/∂η|, the curved face's) and its position.
pub(super) struct FacePoint {
    pub l: [f64; 3],
    pub n: [f64; 6],
    pub da: f64,
    pub at: [f64; 3],
}

/// Dunavant's degree-4 points on a 6-node face (`mids` present).
pub(super) fn t6_points<'a>(mesh: &'a Mesh3d, f: &Face) -> impl Iterator<Item = FacePoint> + 'a {
    let nodes: Vec<usize> = f.nodes().collect();
    debug_assert_eq!(nodes.len(), 6, "a 6-node face");
    let x: [[f64; 3]; 6] = std::array::from_fn(|i| mesh.nodes[nodes[i]]);
    RULE6.iter().map(move |q| {
        let (n, g) = T6::evaluate(&q.xi);
        let tangent = |r: usize| -> [f64; 3] { std::array::from_fn(|c| (0..6).map(|i| g[i][r] * x[i][c]).sum()) };
        let na = cross(tangent(0), tangent(1));
        FacePoint {
            l: [1.0 - q.xi[0] - q.xi[1], q.xi[0], q.xi[1]],
            n,
            da: q.weight * dot(na, na).sqrt(),
            at: std::array::from_fn(|c| (0..6).map(|i| n[i] * x[i][c]).sum()),
        }
    })
}

/// The area of a face: the flat triangle's on T4, the curved 6-node
/// face's on T10 (the area its rows' a_i share: Σ_i Φ_i = 1).
pub fn face_area(mesh: &Mesh3d, f: &Face) -> f64 {
    match f.mids {
        None => mesh.face_area_normal(f).0,
        Some(_) => t6_points(mesh, f).map(|p| p.da).sum(),
    }
}

/// A corner's row being integrated: a_i, ∫ Ψ_i d dA and ∫ Ψ_i N_j dA.
#[derive(Default)]
struct Acc {
    area: f64,
    gap: f64,
    terms: Vec<(usize, f64)>,
}

/// Dual mortar rows on the corners of 6-node faces (module doc).
fn mortar(
    mesh: &Mesh3d,
    set: &[Face],
    faces: &str,
    obstacle: Obstacle,
    extra: &dyn Fn([f64; 3]) -> f64,
) -> Result<ObstacleRows, CoreError> {
    let mut order: Vec<usize> = Vec::new();
    let mut acc: std::collections::HashMap<usize, Acc> = std::collections::HashMap::new();
    for f in set {
        let nodes: Vec<usize> = f.nodes().collect();
        for FacePoint { l, n, da, at } in t6_points(mesh, f) {
            let d = closest(&obstacle, at)?.0 + extra(at);
            for (k, &corner) in f.corners.iter().enumerate() {
                let psi = 4.0 * l[k] - 1.0;
                let a = acc.entry(corner).or_insert_with(|| {
                    order.push(corner);
                    Acc::default()
                });
                a.area += da * l[k];
                a.gap += da * psi * d;
                for (j, &node) in nodes.iter().enumerate() {
                    match a.terms.iter_mut().find(|t| t.0 == node) {
                        Some(t) => t.1 += da * psi * n[j],
                        None => a.terms.push((node, da * psi * n[j])),
                    }
                }
            }
        }
    }
    let mut out = ObstacleRows {
        obstacle,
        faces: faces.to_string(),
        nodes: Vec::with_capacity(order.len()),
        terms: Vec::with_capacity(order.len()),
        normal: Vec::with_capacity(order.len()),
        area: Vec::with_capacity(order.len()),
        gap: Vec::with_capacity(order.len()),
    };
    for corner in order {
        let a = &acc[&corner];
        out.nodes.push(corner);
        out.normal.push(closest(&out.obstacle, mesh.nodes[corner])?.1);
        out.terms.push(a.terms.iter().map(|&(n, c)| (n, c / a.area)).collect());
        out.gap.push(a.gap / a.area);
        out.area.push(a.area);
    }
    Ok(out)
}
