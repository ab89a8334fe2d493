//! Contact rows of a face set against a rigid plane: nodal on T4 faces,
//! dual mortar on T10 faces.
//!
//! The plane through p with unit normal n (pointing out of the obstacle,
//! toward the body) has signed distance d(x) = (x − p)·n, and
//! non-penetration d(x + u) ≥ 0 is, exactly for a plane,
//!
//! ```text
//! −n·u_i ≤ d(x_i)      (one row per node of the face set)
//! ```
//!
//! whose multiplier λ_i ≥ 0 is the node's contact force (+λ_i n on the
//! body), on T4 faces. Its tributary area a_i = ∫ N_i dA over the face set
//! gives the nodal pressure λ_i / a_i, exact for a uniform pressure (the
//! consistent load of a uniform p is p a_i).
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
//! −n · Σ_j (∫ Ψ_i N_j dA / a_i) u_j ≤ ∫ Ψ_i d dA / a_i,   a_i = ∫ Φ_i dA,
//! ```
//!
//! the weighted mean of the gap over the corner's faces, with N_j the face's
//! quadratic shape functions. Since Σ_i Ψ_i = 1, λ_i = p a_i puts the
//! consistent load p ∫ N_j dA on every node: a uniform pressure is
//! transmitted exactly, and p_i = λ_i / a_i is the pressure at corner i.
//! Non-penetration then holds in this weighted mean, not at every node.
//! Integrated with Dunavant's degree-4 rule (Ψ N d is of degree 4 on a flat
//! face: exact there).

use super::SolidBody;
use crate::error::{CoreError, InvalidKind};
use crate::fem::reference::{triangle::RULE6, ReferenceElement, T6};
use crate::mesh3d::{cross, dot, Face, Mesh3d, Order};
pub use crate::scene::solid::Plane;

/// The candidate rows: one per node of the contact face set (T4), one per
/// corner (T10).
#[derive(Debug, Clone)]
pub struct PlaneRows {
    pub plane: Plane,
    /// The contact face set the rows were made from (`report` reads its
    /// faces).
    pub faces: String,
    /// The multiplier node of each row.
    pub nodes: Vec<usize>,
    /// Each row's nodal terms (node, c): the row reads −n · Σ c u_node ≤ gap
    /// (T4: its own node, c = 1).
    pub terms: Vec<Vec<(usize, f64)>>,
    /// The row's area a_i = ∫ Φ_i dA (pressure = λ_i / a_i).
    pub area: Vec<f64>,
    /// The gap before deformation (T4: d(x_i); T10: its dual-weighted mean).
    pub gap: Vec<f64>,
}

impl PlaneRows {
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The rows' gaps after the displacement `u` (every DOF, 3·node + c).
    pub fn gaps_after(&self, u: &[f64]) -> Vec<f64> {
        let n = self.plane.normal;
        let moved = |&(node, c): &(usize, f64)| c * (0..3).map(|k| n[k] * u[3 * node + k]).sum::<f64>();
        self.terms
            .iter()
            .zip(&self.gap)
            .map(|(t, g)| g + t.iter().map(moved).sum::<f64>())
            .collect()
    }
}

/// The rows of face set `faces` against `plane`.
pub fn rows(body: &SolidBody, faces: &str, plane: Plane) -> Result<PlaneRows, CoreError> {
    rows_with(body, faces, plane, &|_| 0.0)
}

/// The rows with `extra(x)` added to the distance d(x) before it is
/// weighted: a flat face set standing for a curved one (Hertz's paraboloid
/// r²/2R, `scene::SolidScene::extra_gap`). Integrated as d is on T10
/// faces (a quadratic `extra` exactly on a flat face).
pub fn rows_with(
    body: &SolidBody,
    faces: &str,
    plane: Plane,
    extra: &dyn Fn([f64; 3]) -> f64,
) -> Result<PlaneRows, CoreError> {
    let mesh = body.mesh;
    let set = body.face_set(faces, "contact/faces")?;
    if set.is_empty() {
        return Err(CoreError::invalid(
            InvalidKind::NoContactCandidates,
            "contact/faces",
            format!("face set '{faces}' is empty: there is nothing to touch the plane"),
        ));
    }
    Ok(match mesh.order {
        Order::T4 => nodal(mesh, set, faces, plane, extra),
        Order::T10 => mortar(mesh, set, faces, plane, extra),
    })
}

fn nodal(mesh: &Mesh3d, set: &[Face], faces: &str, plane: Plane, extra: &dyn Fn([f64; 3]) -> f64) -> PlaneRows {
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
    PlaneRows {
        plane,
        faces: faces.to_string(),
        terms: nodes.iter().map(|&n| vec![(n, 1.0)]).collect(),
        gap: nodes
            .iter()
            .map(|&n| plane.distance(mesh.nodes[n]) + extra(mesh.nodes[n]))
            .collect(),
        nodes,
        area,
    }
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
fn mortar(mesh: &Mesh3d, set: &[Face], faces: &str, plane: Plane, extra: &dyn Fn([f64; 3]) -> f64) -> PlaneRows {
    let mut order: Vec<usize> = Vec::new();
    let mut acc: std::collections::HashMap<usize, Acc> = std::collections::HashMap::new();
    for f in set {
        let nodes: Vec<usize> = f.nodes().collect();
        for FacePoint { l, n, da, at } in t6_points(mesh, f) {
            let d = plane.distance(at) + extra(at);
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
    let mut out = PlaneRows {
        plane,
        faces: faces.to_string(),
        nodes: Vec::with_capacity(order.len()),
        terms: Vec::with_capacity(order.len()),
        area: Vec::with_capacity(order.len()),
        gap: Vec::with_capacity(order.len()),
    };
    for corner in order {
        let a = &acc[&corner];
        out.nodes.push(corner);
        out.terms.push(a.terms.iter().map(|&(n, c)| (n, c / a.area)).collect());
        out.gap.push(a.gap / a.area);
        out.area.push(a.area);
    }
    out
}
