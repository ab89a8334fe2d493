//! The mesh stage: every body's mesh in nondimensional coordinates, built
//! here for every kind of mesh source.

use crate::error::{CoreError, InvalidKind};
use crate::mesh::{generate, Mesh2d};
use crate::scene::{MeshSource, Scene};

/// Generated meshes are made in the request's units, then scaled; inline and
/// Gmsh meshes were read and scaled by validation. A generator that cannot
/// mesh its region (a geometry its refinement does not handle) is an
/// `invalid_mesh` at the body's mesh, not a panic.
pub fn meshes(scene: &Scene) -> Result<Vec<Mesh2d>, CoreError> {
    let length = scene.scales.length;
    let scaled = |mut m: Mesh2d| {
        for p in m.nodes.iter_mut() {
            *p = [p[0] / length, p[1] / length];
        }
        m
    };
    scene
        .bodies
        .iter()
        .map(|b| {
            let generated = match &b.mesh {
                MeshSource::Rectangle {
                    corner,
                    width,
                    height,
                    size,
                    grading,
                    order,
                } => generate::rectangle(*corner, *width, *height, *size, *grading, *order),
                MeshSource::Disk {
                    center,
                    radius,
                    down,
                    part,
                    size,
                    grading,
                    order,
                } => generate::disk(*center, *radius, *down, *part, *size, *grading, *order),
                MeshSource::Inline(m) => return Ok(m.clone()),
            };
            generated.map(scaled).map_err(|e| {
                CoreError::invalid(
                    InvalidKind::Mesh,
                    format!("{}/mesh", b.path),
                    format!("the mesh generator could not mesh this body: {}", e.0),
                )
            })
        })
        .collect()
}
