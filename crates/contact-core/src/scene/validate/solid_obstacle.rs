//! A solid's rigid obstacle from its wire form, nondimensional
//! (`scene::solid_obstacle`), refused at the field at fault.

use contact_proto::{SolidObstacleShape, SolidSpec};

use super::{finite, invalid, positive};
use crate::error::{CoreError, InvalidKind as K};
use crate::scene::solid::{Obstacle, Plane};
use crate::scene::solid_obstacle::HeightField;

/// The obstacle, its lengths over `length`; each field finite, radii
/// positive, directions nonzero, at their pointers.
pub(super) fn obstacle(spec: &SolidSpec, length: f64) -> Result<Obstacle, CoreError> {
    let p = "/solid/obstacle/shape";
    let point = |x: &[f64; 3], at: &str| -> Result<[f64; 3], CoreError> {
        for (c, v) in x.iter().enumerate() {
            finite(*v, &format!("{p}/{at}/{c}"), K::Geometry)?;
        }
        Ok(*x)
    };
    let radius = |r: f64, at: &str| positive(r, &format!("{p}/{at}"), K::Geometry, "a radius");
    let nonzero = |x: &[f64; 3], at: &str| -> Result<[f64; 3], CoreError> {
        point(x, at)?;
        if x.iter().all(|v| *v == 0.0) {
            return Err(invalid(
                K::Geometry,
                format!("{p}/{at}"),
                format!("must be nonzero, got {x:?}"),
            ));
        }
        // A direction divided by its largest component: its norm can then
        // neither overflow ([0, 0, 1e200]) nor underflow ([1e-170, 0, 0]).
        let largest = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        Ok(x.map(|v| v / largest))
    };
    let shape = match &spec.obstacle.shape {
        SolidObstacleShape::Plane { point: at, normal } => Obstacle::Plane(
            Plane::try_new(point(at, "plane/point")?, nonzero(normal, "plane/normal")?)
                .map_err(|e| invalid(K::Geometry, format!("{p}/plane/normal"), e.to_string()))?,
        ),
        SolidObstacleShape::Sphere { centre, radius: r } => Obstacle::Sphere {
            centre: point(centre, "sphere/centre")?,
            radius: radius(*r, "sphere/radius")?,
        },
        SolidObstacleShape::Cylinder {
            point: at,
            axis,
            radius: r,
        } => Obstacle::try_cylinder(
            point(at, "cylinder/point")?,
            nonzero(axis, "cylinder/axis")?,
            radius(*r, "cylinder/radius")?,
        )
        .map_err(|e| invalid(K::Geometry, format!("{p}/cylinder/axis"), e.to_string()))?,
        SolidObstacleShape::Paraboloid {
            apex,
            normal,
            axis,
            radii,
        } => {
            let (apex, normal) = (point(apex, "paraboloid/apex")?, nonzero(normal, "paraboloid/normal")?);
            let radii = [
                radius(radii[0], "paraboloid/radii/0")?,
                radius(radii[1], "paraboloid/radii/1")?,
            ];
            Obstacle::try_paraboloid(apex, normal, nonzero(axis, "paraboloid/axis")?, radii).map_err(|_| {
                invalid(
                    K::Geometry,
                    format!("{p}/paraboloid/axis"),
                    "must not lie along the normal",
                )
            })?
        }
        SolidObstacleShape::HeightField {
            origin,
            normal,
            axis,
            spacing,
            heights,
        } => height_field(
            p,
            point(origin, "height_field/origin")?,
            nonzero(normal, "height_field/normal")?,
            nonzero(axis, "height_field/axis")?,
            *spacing,
            heights,
        )?,
    };
    Ok(shape.scaled(length))
}

/// Most values a height field may hold: 4M (32 MB as numbers, about the
/// door's default request size in JSON text).
const HEIGHT_FIELD_VALUES: usize = 4_000_000;

/// A height field from its wire form, refused at the field at fault.
pub(super) fn height_field(
    p: &str,
    origin: [f64; 3],
    normal: [f64; 3],
    axis: [f64; 3],
    spacing: [f64; 2],
    heights: &[Vec<f64>],
) -> Result<Obstacle, CoreError> {
    let at = |f: &str| format!("{p}/height_field/{f}");
    let Some((normal, e1)) = Obstacle::frame(normal, axis) else {
        return Err(invalid(K::Geometry, at("axis"), "must not lie along the normal"));
    };
    for (k, d) in spacing.iter().enumerate() {
        if !(*d > 0.0 && d.is_finite()) {
            return Err(invalid(
                K::Geometry,
                at(&format!("spacing/{k}")),
                format!("must be positive, got {d}"),
            ));
        }
    }
    let n1 = heights.first().map_or(0, Vec::len);
    if heights.len() < 2 || n1 < 2 {
        return Err(invalid(
            K::Geometry,
            at("heights"),
            format!(
                "needs at least 2 rows of at least 2 heights, got {} rows of {n1}",
                heights.len()
            ),
        ));
    }
    if heights.len().saturating_mul(n1) > HEIGHT_FIELD_VALUES {
        return Err(CoreError::TooLarge {
            path: at("heights"),
            reason: format!(
                "{} rows of {n1} heights, past the {HEIGHT_FIELD_VALUES} a height field may hold: resample it",
                heights.len()
            ),
        });
    }
    let mut values = Vec::with_capacity(heights.len() * n1);
    for (j, row) in heights.iter().enumerate() {
        if row.len() != n1 {
            return Err(invalid(
                K::Geometry,
                at(&format!("heights/{j}")),
                format!("every row needs the first row's {n1} heights, got {}", row.len()),
            ));
        }
        if let Some(i) = row.iter().position(|h| !h.is_finite()) {
            return Err(invalid(K::Geometry, at(&format!("heights/{j}/{i}")), "must be finite"));
        }
        values.extend_from_slice(row);
    }
    Ok(Obstacle::HeightField(std::sync::Arc::new(HeightField {
        origin,
        normal,
        e1,
        spacing,
        counts: [n1, heights.len()],
        heights: values,
    })))
}
