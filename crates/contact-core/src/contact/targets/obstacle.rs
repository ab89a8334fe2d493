//! A rigid obstacle as a contact target: fixed, or a punch whose rigid motion
//! (α1, α2, θ) is prescribed or left to the contact. What a surface point sees
//! is the obstacle's geometry (`contact::gap`): the signed distance to its
//! closest point and the row along the obstacle's normal there (the default),
//! or the gap along the body's own normal (`settings.gap = body_normal`).

use crate::contact::constraints::{Candidate, Link};
use crate::contact::gap::{closest, gap_along_normal};
use crate::contact::rows::{self, punch_coefficients, Seen, Surface, T6Multiplier};
use crate::fem::DofMap;
use crate::mesh::Order;
use crate::scene::{Control, GapMeasure, Scene};

/// Rows of the surface against obstacle `o` into `out`; returns how many were
/// pruned.
pub fn rows(
    scene: &Scene,
    p: usize,
    o: usize,
    slave: &Surface,
    limit: f64,
    dofs: &DofMap,
    out: &mut Vec<Candidate>,
) -> usize {
    let obstacle = &scene.obstacles[o];
    let signed = scene.settings.gap == GapMeasure::SignedDistance;
    let see = |x: [f64; 2], n_body: [f64; 2]| -> Option<Seen> {
        let (gap, dir, y) = if signed {
            let c = closest(&obstacle.shape, x)?;
            (c.distance, [-c.normal[0], -c.normal[1]], c.point)
        } else {
            (gap_along_normal(&obstacle.shape, x, n_body)?, n_body, x)
        };
        Some(Seen {
            gap,
            dir,
            other: Vec::new(),
            punch: obstacle
                .punch
                .as_ref()
                .map(|pu| punch_coefficients(y, pu.reference, dir)),
        })
    };
    let rows = if slave.mesh.order == Order::T6 {
        // Nodal rows on quadratic faces let the pressure alternate between
        // corners and midsides; dual mortar rows on each half of the edge do
        // not, and resolve the zone edge at the full node spacing (see
        // `rows::T6Multiplier`). Gauss points on each half of an edge: the
        // normals turn along the quadratic edge.
        rows::mortar(slave, T6Multiplier::Halves, &see, limit, &|_| vec![0.0, 0.5, 1.0])
    } else {
        rows::nodal(slave, &see, limit)
    };
    let mut pruned = rows.pruned;
    for r in rows.rows {
        let link = match (&obstacle.punch, r.punch) {
            (Some(_), Some(c)) => Link::Punch {
                obstacle: o,
                c: [c[0], c[1], c[2]],
                lever_t: c[3],
            },
            _ => Link::Fixed,
        };
        let Some(mut cand) = Candidate::try_new(p, slave.body, slave.mesh, r, dofs, link) else {
            pruned += 1;
            continue;
        };
        // A prescribed punch motion moves the obstacle: it opens the gap by c · β.
        if let (Some(pu), Link::Punch { c, .. }) = (&obstacle.punch, link) {
            for (k, ctl) in pu.controls.iter().enumerate() {
                if let Control::Displacement(v) = ctl {
                    cand.g += c[k] * v;
                }
            }
        }
        out.push(cand);
    }
    pruned
}
