//! Checks of the model's own assumptions on a solution.
//!
//! The theory is small strain and small rotation, with the non-penetration
//! condition linearized about the reference configuration. A solution can
//! satisfy the discrete equations exactly and still lie outside that model (a
//! punch tipped by 37°, a cylinder pushed in to a/R = 0.67): these checks say
//! so with the measured value and the limit.
//!
//! Limits, each where a neglected term reaches about 1 % of what is kept (a
//! Hertz contact at a/R = 0.085 has 3 % strain and 0.08 rad of local surface
//! rotation at the zone edge and is well inside the theory's validity):
//! - strain 5e-2: Green's strain adds ½ε² ≈ 2.5 % of the linear strain;
//! - rotation 0.15 rad: a linearized rotation misplaces points by θ²/2 ≈ 1.1 %
//!   of their distance to the centre of rotation;
//! - displacement 5e-2 of the body's size: equilibrium is written on the
//!   undeformed shape;
//! - contact half-width 0.3 of a curved obstacle's radius: the Hertz-type gap
//!   x²/2R is off by (a/R)²/4 ≈ 2 % there;
//! - contact displacement 5e-2 of the obstacle's radius: the linearized
//!   distance d + ∇d·u errs by |u_t|²/2R.

use crate::contact::ConstraintSet;
use crate::fem::element;
use crate::mesh::Mesh2d;
use crate::scene::{Psi, Scene, Shape};
use crate::solution::report::Warning;

pub const MAX_STRAIN: f64 = 5e-2;
pub const MAX_ROTATION: f64 = 0.15;
pub const MAX_DISPLACEMENT: f64 = 5e-2;
pub const MAX_ZONE_OVER_RADIUS: f64 = 0.3;
pub const MAX_CONTACT_MOTION_OVER_RADIUS: f64 = 5e-2;

/// `disp[b][n]`: nodal displacements of body b (rigid motions included);
/// `punch_rotations`: (obstacle, θ) of every punch; `zones`: per pair, the
/// contact zones' x-intervals (nondimensional).
pub fn check(
    scene: &Scene,
    meshes: &[Mesh2d],
    disp: &[Vec<[f64; 2]>],
    cons: &ConstraintSet,
    punch_rotations: &[(usize, f64)],
    zones: &[Vec<[f64; 2]>],
) -> Vec<Warning> {
    let mut out = Vec::new();
    let mut warn = |code: &'static str, value: f64, limit: f64, location: String| {
        if value > limit {
            out.push(Warning {
                code,
                value,
                limit,
                location,
            });
        }
    };
    for (b, (mesh, u)) in meshes.iter().zip(disp).enumerate() {
        let (mut strain, mut rotation) = (0.0f64, 0.0f64);
        let mut x = Vec::with_capacity(6);
        let mut ue = Vec::with_capacity(12);
        for e in 0..mesh.n_elems() {
            x.clear();
            ue.clear();
            for &n in mesh.elem(e) {
                x.push(mesh.nodes[n]);
                ue.extend_from_slice(&u[n]);
            }
            let g = element::centroid_gradient(mesh.order, &x, &ue);
            // Principal strains of the symmetric part; the rotation is the skew part.
            let (exx, eyy, exy) = (g[0], g[3], 0.5 * (g[1] + g[2]));
            let (mean, radius) = (0.5 * (exx + eyy), (0.25 * (exx - eyy).powi(2) + exy * exy).sqrt());
            strain = strain.max((mean + radius).abs()).max((mean - radius).abs());
            rotation = rotation.max((0.5 * (g[2] - g[1])).abs());
        }
        let biggest = u.iter().map(|d| d[0].hypot(d[1])).fold(0.0, f64::max);
        let path = scene.bodies[b].path.clone();
        warn("large_strain", strain, MAX_STRAIN, path.clone());
        warn("large_rotation", rotation, MAX_ROTATION, path.clone());
        warn("large_displacement", biggest / mesh.size(), MAX_DISPLACEMENT, path);
    }
    for &(o, theta) in punch_rotations {
        warn("large_rotation", theta.abs(), MAX_ROTATION, format!("/obstacles/{o}"));
    }
    for (p, pair) in scene.pairs.iter().enumerate() {
        let crate::scene::Target::Obstacle(o) = pair.target else {
            continue;
        };
        let Some(radius) = curvature_radius(&scene.obstacles[o].shape) else {
            continue;
        };
        let half = zones[p].iter().map(|z| 0.5 * (z[1] - z[0])).fold(0.0, f64::max);
        warn(
            "large_contact_zone",
            half / radius,
            MAX_ZONE_OVER_RADIUS,
            pair.path.clone(),
        );
        let moved = cons
            .candidates
            .iter()
            .filter(|c| c.pair == p)
            .map(|c| disp[c.body][c.node])
            .map(|d| d[0].hypot(d[1]))
            .fold(0.0, f64::max);
        warn(
            "gap_linearization",
            moved / radius,
            MAX_CONTACT_MOTION_OVER_RADIUS,
            pair.path.clone(),
        );
    }
    out
}

/// The smallest radius of curvature of a curved obstacle (None: straight).
fn curvature_radius(shape: &Shape) -> Option<f64> {
    match shape {
        Shape::Circle { radius, .. } => Some(*radius),
        Shape::Profile { psi, .. } => match psi {
            Psi::Circle { radius } => Some(*radius),
            Psi::Flat { corner_radius, .. } if *corner_radius > 0.0 => Some(*corner_radius),
            _ => None,
        },
        Shape::Line { .. } | Shape::Polyline { .. } => None,
    }
}
