//! What each coupling did: its reference point's motion and the force and
//! moment it passed to its body, from the nodal displacements alone (so that
//! every route, frictionless or frictional, condensed or full, reports it
//! alike).
//!
//! The motion is the rigid motion of the coupled nodes (exact: they move
//! rigidly by construction). The force is the reaction of the coupled nodes,
//! r_i = (K u)_i − f_i with f the body's own loads there (the coupling's
//! share taken out), summed to a force and a moment about the reference
//! point: for a load-controlled component it reproduces the load given (to
//! the solve's round-off), for a prescribed one it is the reaction that holds
//! it.

use std::collections::HashMap;

use crate::fem::assembly::{each_element, integration, law, DofMap};
use crate::fem::loads::coupling_forces;
use crate::mesh::Mesh2d;
use crate::scene::{Analysis, Control, Scene};
use crate::solution::report::CouplingReport;

/// Every coupling's motion and transmitted loads, in the caller's units.
/// `disp`: the nodal displacements of every body (nondimensional);
/// `external`: the model's nodal loads on every global DOF.
pub fn couplings(
    scene: &Scene,
    meshes: &[Mesh2d],
    dofs: &DofMap,
    disp: &[Vec<[f64; 2]>],
    external: &[f64],
) -> Vec<CouplingReport> {
    let sc = scene.scales;
    let mut out = Vec::new();
    for (b, body) in scene.bodies.iter().enumerate() {
        for cp in &body.couplings {
            let mesh = &meshes[b];
            let nodes = mesh.edge_set_nodes(&cp.edges);
            let motion = rigid_fit(mesh, &nodes, &disp[b], cp.reference);
            let mut loads: HashMap<usize, [f64; 2]> = nodes
                .iter()
                .map(|&n| (n, [-external[dofs.dof(b, n, 0)], -external[dofs.dof(b, n, 1)]]))
                .collect();
            for (n, f) in (0..3).flat_map(|k| coupling_forces(cp, mesh, k)) {
                if let Some(r) = loads.get_mut(&n) {
                    r[0] += f[0];
                    r[1] += f[1];
                }
            }
            add_ku(scene, b, mesh, &disp[b], &mut loads);
            let mut load = [0.0; 3];
            for (&n, r) in &loads {
                let (dx, dy) = (mesh.nodes[n][0] - cp.reference[0], mesh.nodes[n][1] - cp.reference[1]);
                load[0] += r[0];
                load[1] += r[1];
                load[2] += dx * r[1] - dy * r[0];
            }
            let given = |k: usize, solved: f64| match cp.controls[k] {
                Control::Displacement(v) => v,
                Control::Load(_) => solved,
            };
            let axisymmetric = scene.analysis == Analysis::Axisymmetric;
            out.push(CouplingReport {
                path: cp.path.clone(),
                body: body.name.clone(),
                ux: sc.length(given(0, motion[0])),
                uy: sc.length(given(1, motion[1])),
                theta: given(2, motion[2]),
                // Ring forces cancel round the circumference in axisymmetry.
                fx: if axisymmetric { 0.0 } else { sc.force(load[0]) },
                fy: sc.force(load[1]),
                m: if axisymmetric { 0.0 } else { sc.moment(load[2]) },
            });
        }
    }
    out
}

/// The rigid motion (ux, uy at `reference`, θ) of the nodes: θ from their
/// displacements' moment about the centroid over the polar moment, exact for
/// a rigid motion of two distinct points or more.
fn rigid_fit(mesh: &Mesh2d, nodes: &[usize], u: &[[f64; 2]], reference: [f64; 2]) -> [f64; 3] {
    let n = nodes.len() as f64;
    let (mut c, mut uc) = ([0.0; 2], [0.0; 2]);
    for &i in nodes {
        for k in 0..2 {
            c[k] += mesh.nodes[i][k] / n;
            uc[k] += u[i][k] / n;
        }
    }
    let (mut turn, mut polar) = (0.0, 0.0);
    for &i in nodes {
        let (dx, dy) = (mesh.nodes[i][0] - c[0], mesh.nodes[i][1] - c[1]);
        turn += dx * u[i][1] - dy * u[i][0];
        polar += dx * dx + dy * dy;
    }
    let theta = if polar > 0.0 { turn / polar } else { 0.0 };
    [
        uc[0] - theta * (reference[1] - c[1]),
        uc[1] + theta * (reference[0] - c[0]),
        theta,
    ]
}

/// Adds (K u)_i of body `b`'s elements to every node i of `at`: the
/// elements touching one of them.
fn add_ku(scene: &Scene, b: usize, mesh: &Mesh2d, u: &[[f64; 2]], at: &mut HashMap<usize, [f64; 2]>) {
    let body = &scene.bodies[b];
    let law = law(body, scene.analysis);
    let how = integration(body, mesh.order, scene.analysis);
    let touching: Vec<usize> = (0..mesh.n_elems())
        .filter(|&e| mesh.elem(e).iter().any(|n| at.contains_key(n)))
        .collect();
    each_element(mesh, scene.analysis, &law, how, touching.into_iter(), |conn, ke| {
        let nd = 2 * conn.len();
        for (i, node) in conn.iter().enumerate() {
            let Some(r) = at.get_mut(node) else { continue };
            for c in 0..2 {
                let row = &ke[(2 * i + c) * nd..(2 * i + c + 1) * nd];
                r[c] += conn
                    .iter()
                    .enumerate()
                    .map(|(j, &m)| row[2 * j] * u[m][0] + row[2 * j + 1] * u[m][1])
                    .sum::<f64>();
            }
        }
    });
}
