//! Nodal contact rows of a face set against a rigid plane.
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
//! body). Its tributary area a_i = ∫ N_i dA over the face set gives the
//! nodal pressure λ_i / a_i, exact for a uniform pressure (the consistent
//! load of a uniform p is p a_i).
//!
//! Only T4 faces: on a 6-node face, ∫ N_i dA of a corner is 0 (its shape
//! function integrates to zero on a triangle), so nodal rows there cannot
//! carry a uniform pressure and alternate; the design's answer is dual
//! mortar rows (biorthogonal multipliers), not built yet, and a T10 contact
//! surface is refused rather than solved wrongly.

use super::SolidBody;
use crate::error::{CoreError, InvalidKind};
use crate::mesh3d::{dot, sub, Order};

/// A rigid plane: a point on it and its unit normal, out of the obstacle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub point: [f64; 3],
    pub normal: [f64; 3],
}

impl Plane {
    /// The plane through `point` with normal along `normal` (any length > 0).
    pub fn try_new(point: [f64; 3], normal: [f64; 3]) -> Result<Self, CoreError> {
        let l = dot(normal, normal).sqrt();
        if !(l > 0.0 && l.is_finite()) || point.iter().any(|v| !v.is_finite()) {
            return Err(CoreError::invalid(
                InvalidKind::Geometry,
                "obstacle",
                format!("a plane needs a finite point and a nonzero normal, got {point:?} and {normal:?}"),
            ));
        }
        Ok(Self {
            point,
            normal: normal.map(|v| v / l),
        })
    }

    /// d(x) = (x − p)·n.
    pub fn distance(&self, x: [f64; 3]) -> f64 {
        dot(sub(x, self.point), self.normal)
    }
}

/// The candidate rows: one per node of the contact face set.
#[derive(Debug, Clone)]
pub struct PlaneRows {
    pub plane: Plane,
    pub nodes: Vec<usize>,
    /// Tributary area ∫ N_i dA of each node.
    pub area: Vec<f64>,
    /// d(x_i): the gap before deformation.
    pub gap: Vec<f64>,
}

impl PlaneRows {
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// The rows of the nodes of face set `faces` against `plane`.
pub fn rows(body: &SolidBody, faces: &str, plane: Plane) -> Result<PlaneRows, CoreError> {
    let mesh = body.mesh;
    let set = body.face_set(faces, "contact/faces")?;
    if mesh.order == Order::T10 {
        return Err(CoreError::invalid(
            InvalidKind::Request,
            "contact",
            "contact on quadratic tetrahedra (T10) needs dual mortar rows, which are not implemented yet: nodal rows \
                on 6-node faces cannot carry a uniform pressure (the corners' shape functions integrate to 0); use \
                linear tetrahedra (T4) for contact",
        ));
    }
    if set.is_empty() {
        return Err(CoreError::invalid(
            InvalidKind::NoContactCandidates,
            "contact/faces",
            format!("face set '{faces}' is empty: there is nothing to touch the plane"),
        ));
    }
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
    let gap = nodes.iter().map(|&n| plane.distance(mesh.nodes[n])).collect();
    Ok(PlaneRows {
        plane,
        nodes,
        area,
        gap,
    })
}
