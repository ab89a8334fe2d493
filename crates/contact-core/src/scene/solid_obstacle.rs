//! The rigid obstacle of a 3D solid, nondimensional: a plane, a sphere, a
//! cylinder, a paraboloid or a table of heights, each answering one question for a point x of
//! the body's contact surface: the signed distance d(x) to the obstacle
//! (positive outside it, where the body is) and the unit normal n(x) out of
//! the obstacle at the closest obstacle point, the direction along which
//! d(x + u) ≈ d(x) + n(x)·u is linearized (the 2D rigid obstacles'
//! `contact::targets` answer the same question with `Seen`).
//!
//! - **Plane** through p, unit normal n: d = (x − p)·n, n constant.
//! - **Sphere** of centre c and radius R, the body outside:
//!   d = |x − c| − R, n = (x − c)/|x − c|.
//! - **Cylinder** of axis through p along the unit a, radius R, the body
//!   outside: with r = (x − p) − ((x − p)·a) a the offset across the axis,
//!   d = |r| − R, n = r/|r|.
//! - **Paraboloid** with apex o, unit normal n₀ at the apex (toward the
//!   body) and principal radii R₁, R₂ along the unit e₁ ⊥ n₀ and
//!   e₂ = n₀ × e₁: the surface s = −(ξ²/2R₁ + η²/2R₂) in the frame
//!   (ξ, η, s) = ((x − o)·e₁, (x − o)·e₂, (x − o)·n₀), convex toward the
//!   body (Hertz's and Johnson's local shape of a body of two principal
//!   curvatures). Its exact distance needs a root of a quartic; the height
//!   φ = s + ξ²/2R₁ + η²/2R₂ over its gradient's length, d = φ/|∇φ|,
//!   n = ∇φ/|∇φ|, has the same zero set and, on it, the exact normal and
//!   unit slope, so the conditions d ≥ 0 and their linearization at contact
//!   are the exact ones; away from the surface it differs from the distance
//!   by O(φ² κ), below the rows' O(h²κ) sampling of the gap where it
//!   matters.
//! - **Height field**: a table of heights over a grid in a frame, the
//!   paraboloid's construction on a C¹ interpolant (`height_field`).
//!
//! The sphere's and the cylinder's normals are undefined at the centre and
//! on the axis, and a height field has none off its grid: a candidate there
//! is refused (`closest` gives None). A body
//! point inside the obstacle has d < 0: an initial penetration is the
//! obstacle pressed in by that depth (a prescribed interference, as a 2D
//! rigid obstacle placed into a body is), not an error.

use std::sync::Arc;

pub use super::height_field::HeightField;
use crate::error::{CoreError, InvalidKind};

/// A rigid plane: a point on it and its unit normal, out of the obstacle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub point: [f64; 3],
    pub normal: [f64; 3],
}

impl Plane {
    /// The plane through `point` with normal along `normal` (any length > 0).
    pub fn try_new(point: [f64; 3], normal: [f64; 3]) -> Result<Self, CoreError> {
        let l = norm(normal);
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
        (0..3).map(|c| (x[c] - self.point[c]) * self.normal[c]).sum()
    }
}

/// A rigid obstacle (module doc), in the scene's nondimensional lengths.
#[derive(Debug, Clone, PartialEq)]
pub enum Obstacle {
    Plane(Plane),
    Sphere {
        centre: [f64; 3],
        radius: f64,
    },
    /// `axis` of unit length.
    Cylinder {
        point: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
    /// `normal` and `e1` of unit length and orthogonal; `radii` along e₁
    /// and e₂ = normal × e₁.
    Paraboloid {
        apex: [f64; 3],
        normal: [f64; 3],
        e1: [f64; 3],
        radii: [f64; 2],
    },
    /// Shared: every candidate's row reads it.
    HeightField(Arc<HeightField>),
}

impl From<Plane> for Obstacle {
    fn from(p: Plane) -> Self {
        Obstacle::Plane(p)
    }
}

impl Obstacle {
    /// A cylinder with its axis along `axis` (any nonzero length).
    pub fn try_cylinder(point: [f64; 3], axis: [f64; 3], radius: f64) -> Result<Self, CoreError> {
        let l = norm(axis);
        if !(l > 0.0 && l.is_finite() && radius > 0.0 && radius.is_finite()) {
            return Err(CoreError::invalid(
                InvalidKind::Geometry,
                "obstacle",
                format!("a cylinder needs a nonzero axis and a positive radius, got {axis:?} and {radius}"),
            ));
        }
        Ok(Obstacle::Cylinder {
            point,
            axis: axis.map(|v| v / l),
            radius,
        })
    }

    /// The unit normal and the unit e₁ across it along `axis` (any nonzero
    /// lengths, not parallel: within 1e-6 rad of the normal an axis has no
    /// reliable direction across it); None otherwise.
    pub fn frame(normal: [f64; 3], axis: [f64; 3]) -> Option<([f64; 3], [f64; 3])> {
        let ln = norm(normal);
        if !(ln > 0.0 && ln.is_finite()) {
            return None;
        }
        let n = normal.map(|v| v / ln);
        let along = dot(axis, n);
        let across: [f64; 3] = std::array::from_fn(|c| axis[c] - along * n[c]);
        let la = norm(across);
        (la > 1e-6 * norm(axis) && la.is_finite()).then(|| (n, across.map(|v| v / la)))
    }

    /// A paraboloid with apex normal along `normal` and radius `radii[0]`
    /// in the section along `axis` (its part across `normal` is used; any
    /// nonzero lengths, not parallel).
    pub fn try_paraboloid(
        apex: [f64; 3],
        normal: [f64; 3],
        axis: [f64; 3],
        radii: [f64; 2],
    ) -> Result<Self, CoreError> {
        let bad = |why: &str| Err(CoreError::invalid(InvalidKind::Geometry, "obstacle", why.to_string()));
        if !(norm(normal) > 0.0 && norm(normal).is_finite()) {
            return bad("a paraboloid needs a nonzero normal");
        }
        let Some((n, e1)) = Self::frame(normal, axis) else {
            return bad("a paraboloid's axis must be nonzero and not along its normal");
        };
        if !radii.iter().all(|r| *r > 0.0 && r.is_finite()) {
            return bad("a paraboloid's radii must be positive and finite");
        }
        Ok(Obstacle::Paraboloid {
            apex,
            normal: n,
            e1,
            radii,
        })
    }

    /// The signed distance to the obstacle at x and the unit normal out of
    /// it at the closest obstacle point (module doc); None where that
    /// normal is undefined (a sphere's centre, a cylinder's axis).
    pub fn closest(&self, x: [f64; 3]) -> Option<(f64, [f64; 3])> {
        match *self {
            Obstacle::HeightField(ref f) => {
                let d = sub(x, f.origin);
                let e2 = cross(f.normal, f.e1);
                let (h, h_xi, h_eta) = f.height(dot(d, f.e1), dot(d, e2))?;
                let grad: [f64; 3] = std::array::from_fn(|c| f.normal[c] - h_xi * f.e1[c] - h_eta * e2[c]);
                let g = norm(grad);
                Some(((dot(d, f.normal) - h) / g, grad.map(|v| v / g)))
            }
            Obstacle::Plane(p) => Some((p.distance(x), p.normal)),
            Obstacle::Sphere { centre, radius } => away(sub(x, centre), radius),
            Obstacle::Cylinder { point, axis, radius } => {
                let d = sub(x, point);
                let along = dot(d, axis);
                away(std::array::from_fn(|c| d[c] - along * axis[c]), radius)
            }
            Obstacle::Paraboloid {
                apex,
                normal,
                e1,
                radii,
            } => {
                let d = sub(x, apex);
                let e2 = cross(normal, e1);
                let (xi, eta) = (dot(d, e1), dot(d, e2));
                let phi = dot(d, normal) + xi * xi / (2.0 * radii[0]) + eta * eta / (2.0 * radii[1]);
                let grad: [f64; 3] =
                    std::array::from_fn(|c| normal[c] + xi / radii[0] * e1[c] + eta / radii[1] * e2[c]);
                let g = norm(grad);
                Some((phi / g, grad.map(|v| v / g)))
            }
        }
    }

    /// The obstacle with its lengths divided by `length`.
    pub fn scaled(self, length: f64) -> Self {
        let s = |x: [f64; 3]| x.map(|c| c / length);
        match self {
            Obstacle::HeightField(f) => Obstacle::HeightField(Arc::new(HeightField {
                origin: s(f.origin),
                spacing: f.spacing.map(|d| d / length),
                heights: f.heights.iter().map(|h| h / length).collect(),
                ..(*f).clone()
            })),
            Obstacle::Plane(p) => Obstacle::Plane(Plane {
                point: s(p.point),
                normal: p.normal,
            }),
            Obstacle::Sphere { centre, radius } => Obstacle::Sphere {
                centre: s(centre),
                radius: radius / length,
            },
            Obstacle::Cylinder { point, axis, radius } => Obstacle::Cylinder {
                point: s(point),
                axis,
                radius: radius / length,
            },
            Obstacle::Paraboloid {
                apex,
                normal,
                e1,
                radii,
            } => Obstacle::Paraboloid {
                apex: s(apex),
                normal,
                e1,
                radii: radii.map(|r| r / length),
            },
        }
    }
}

/// Distance and normal outside a round surface of radius `radius` whose
/// offset from its centre (or axis) to x is `r`.
fn away(r: [f64; 3], radius: f64) -> Option<(f64, [f64; 3])> {
    let l = norm(r);
    (l > 0.0).then(|| (l - radius, r.map(|v| v / l)))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|c| a[c] - b[c])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|c| a[c] * b[c]).sum()
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each shape's distance at a point whose closest obstacle point is
    /// known, and its normal there; exact up to the square roots' round-off.
    #[test]
    fn distances_and_normals_of_the_shapes() {
        let close = |a: (f64, [f64; 3]), b: (f64, [f64; 3])| {
            (a.0 - b.0).abs() < 1e-14 && (0..3).all(|c| (a.1[c] - b.1[c]).abs() < 1e-14)
        };
        let sphere = Obstacle::Sphere {
            centre: [1.0, 2.0, 3.0],
            radius: 2.0,
        };
        assert!(close(sphere.closest([1.0, 2.0, 8.0]).unwrap(), (3.0, [0.0, 0.0, 1.0])));
        assert!(close(
            sphere.closest([1.0, 1.0, 3.0]).unwrap(),
            (-1.0, [0.0, -1.0, 0.0])
        ));
        assert!(sphere.closest([1.0, 2.0, 3.0]).is_none(), "no normal at the centre");
        let cyl = Obstacle::try_cylinder([0.0, 1.0, 0.0], [0.0, 0.0, 5.0], 1.0).unwrap();
        assert!(close(cyl.closest([0.0, -0.5, 7.0]).unwrap(), (0.5, [0.0, -1.0, 0.0])));
        assert!(Obstacle::try_cylinder([0.0; 3], [0.0; 3], 1.0).is_err());
        // The paraboloid at its apex's normal line, and across it where its
        // height is φ = 1/2 + 0 + ... : along e₂ at η = 2 with R₂ = 4 the
        // surface sinks by ½, so φ = s + ½ and ∇φ = n₀ + (η/R₂) e₂.
        let par = Obstacle::try_paraboloid([0.0; 3], [0.0, 0.0, 2.0], [1.0, 0.0, 1.0], [1.0, 4.0]).unwrap();
        assert!(close(par.closest([0.0, 0.0, 0.25]).unwrap(), (0.25, [0.0, 0.0, 1.0])));
        let g = (1.0f64 + 0.25).sqrt();
        assert!(close(
            par.closest([0.0, 2.0, 0.0]).unwrap(),
            (0.5 / g, [0.0, 0.5 / g, 1.0 / g])
        ));
        assert!(Obstacle::try_paraboloid([0.0; 3], [0.0, 0.0, 1.0], [0.0, 0.0, 3.0], [1.0, 1.0]).is_err());
    }
}
