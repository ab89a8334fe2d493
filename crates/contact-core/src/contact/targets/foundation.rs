//! A tensionless foundation as a contact target: the rows of a body's edge
//! set resting on it (the foundation's compliance, which joins the condensed
//! operator, is `contact::compliance`).
//!
//! A body node x with outward normal n (facing down) may not pass the
//! deflected foundation surface y0 − w:
//!
//! ```text
//! n · u − (−n_y) w ≤ s,   s = (y0 − y) / n_y  (the gap along n)
//! ```
//!
//! with n = (0, −1) and s = y − y0 under the default signed distance (the
//! height above the flat foundation surface: exact), n the body's outward
//! normal under `settings.gap = body_normal`. The row's force projected on the
//! vertical, (−n_y) λ, loads the foundation over the row's panel (its node's
//! share of the edge set projected on x: the panels tile the footprint).

use std::collections::HashMap;

use crate::contact::constraints::{Candidate, FoundationRow, Link};
use crate::contact::rows::{self, Seen, Surface, T6Multiplier};
use crate::fem::DofMap;
use crate::mesh::{Edge, Mesh2d, Order};
use crate::scene::{GapMeasure, Scene};

/// Each multiplier node's share of an edge set projected on x, as [a, b] (the
/// panels tile the projection): halves of every edge, the support of the end
/// nodes' hats ∫ Φ_i ds (T6 midsides carry no multiplier, see `rows`).
fn node_panels(mesh: &Mesh2d, edges: &[Edge]) -> HashMap<usize, [f64; 2]> {
    let mut out: HashMap<usize, [f64; 2]> = HashMap::new();
    let mut put = |node: usize, a: f64, b: f64| {
        let (lo, hi) = (a.min(b), a.max(b));
        let e = out.entry(node).or_insert([lo, hi]);
        e[0] = e[0].min(lo);
        e[1] = e[1].max(hi);
    };
    for e in edges {
        let (xa, xb) = (mesh.nodes[e.a][0], mesh.nodes[e.b][0]);
        let m = 0.5 * (xa + xb);
        put(e.a, xa, m);
        put(e.b, m, xb);
    }
    out
}

/// Rows of pair `p` on foundation `f`; returns the number pruned (nodes off
/// the foundation's extent, not facing it, or too far above it). The rows are
/// those against a rigid obstacle (`rows`): one per node on T3 surfaces, the
/// corners' dual mortar rows on T6 ones, since nodal rows on quadratic faces
/// let the pressure alternate between corner and midside nodes (measured on
/// the half-plane roller, T6: 1.3 % of p0; T3 none). Each row loads the
/// foundation over its node's panel.
pub fn rows(scene: &Scene, p: usize, f: usize, meshes: &[Mesh2d], dofs: &DofMap, out: &mut Vec<Candidate>) -> usize {
    let pair = &scene.pairs[p];
    let fnd = &scene.foundations[f];
    let mesh = &meshes[pair.body];
    let surface = Surface {
        body: pair.body,
        mesh,
        edges: &mesh.edge_sets[&pair.edges],
        analysis: scene.analysis,
    };
    let panels = node_panels(mesh, surface.edges);
    let limit = scene.settings.prune_gap_ratio * mesh.size();
    let slack = 1e-9 * (fnd.x_max - fnd.x_min);
    let see = |x: [f64; 2], n: [f64; 2]| -> Option<Seen> {
        // Only a surface facing down, above the foundation's extent, can rest on it.
        if x[0] < fnd.x_min - slack || x[0] > fnd.x_max + slack || n[1] >= -1e-12 {
            return None;
        }
        // The foundation's surface is horizontal: its signed distance is the
        // height above it and the row is vertical (exact); the body-normal
        // form measures the gap along n instead.
        let (dir, gap) = match scene.settings.gap {
            GapMeasure::SignedDistance => ([0.0, -1.0], x[1] - fnd.y),
            GapMeasure::BodyNormal => (n, (fnd.y - x[1]) / n[1]),
        };
        Some(Seen {
            gap,
            dir,
            other: Vec::new(),
            punch: None,
        })
    };
    let rows = if mesh.order == Order::T6 {
        rows::mortar(&surface, T6Multiplier::Corners, &see, limit, &|_| vec![0.0, 0.5, 1.0])
    } else {
        rows::nodal(&surface, &see, limit)
    };
    let mut pruned = rows.pruned;
    for r in rows.rows {
        let panel = panels[&r.node];
        let clipped = [panel[0].max(fnd.x_min), panel[1].min(fnd.x_max)];
        let link = Link::Foundation(FoundationRow {
            foundation: f,
            panel: clipped,
            proj: -r.normal[1],
        });
        match Candidate::try_new(p, pair.body, mesh, r, dofs, link) {
            Some(c) if clipped[1] > clipped[0] => out.push(c),
            _ => pruned += 1,
        }
    }
    pruned
}
