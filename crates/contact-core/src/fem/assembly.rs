//! Global assembly: per-body stiffness and loads, Dirichlet elimination.
//!
//! Global DOF 2·(node + node_offset[body]) + c. Prescribed DOFs are eliminated:
//! K_ff u_f = f_f − K_fd u_d. Only the lower triangle of K_ff is stored.

use faer::sparse::SparseColMat;

use super::constitutive::{law_of, Constitutive, Law};
use super::kernel::{self, Integration, Plane, Ring};
use super::reference::{T3, T6};
use super::rigid_modes::{self, free_modes, mode_row, virtual_supports, RigidModes};
use crate::error::{CoreError, InvalidKind};
use crate::mesh::Mesh2d;
use crate::scene::scaling::shown;
use crate::scene::{Analysis, Scene};

pub use super::pattern::FIXED;
use super::pattern::{self, Global};

/// Poisson's ratio from which T6 in plane strain switches to selective reduced
/// integration (the volumetric stiffness is then over ten times the shear one).
pub const NEARLY_INCOMPRESSIBLE: f64 = 0.45;

/// Numbering of degrees of freedom over all bodies.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// First global node index of each body.
    pub node_offset: Vec<usize>,
    /// Free index of each global DOF, or FIXED.
    pub free: Vec<usize>,
    /// Prescribed value of each global DOF (0 where free).
    pub prescribed: Vec<f64>,
    pub n_free: usize,
    /// Free rigid modes of bodies held (partly) by contact, with their virtual supports.
    pub rigid: Vec<RigidModes>,
}

impl DofMap {
    pub fn dof(&self, body: usize, node: usize, c: usize) -> usize {
        2 * (self.node_offset[body] + node) + c
    }
}

/// The load-independent part: K_ff (lower triangle) and the coupling K_fd of
/// free rows to prescribed DOFs, so that a new set of prescribed values costs a
/// sparse product, not a reassembly.
pub struct Stiffness {
    pub k: SparseColMat<usize, f64>,
    /// (free row, global prescribed DOF, value) of K_fd.
    pub k_fd: Vec<(usize, usize, f64)>,
}

/// Builds the DOF map from the supports. Rigid motions the supports leave free
/// are allowed for bodies that take part in a contact pair (contact may hold
/// them): they get virtual supports (`rigid_modes`) and become free rigid
/// motions of the contact problem. A body with free modes and no contact is rejected.
pub fn dof_map(scene: &Scene, meshes: &[Mesh2d]) -> Result<DofMap, CoreError> {
    let mut node_offset = Vec::with_capacity(meshes.len());
    let mut total = 0;
    for m in meshes {
        node_offset.push(total);
        total += m.nodes.len();
    }
    let mut fixed = vec![false; 2 * total];
    let mut prescribed = vec![0.0; 2 * total];
    let mut rigid = Vec::new();
    for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
        let mut rows: Vec<[f64; 3]> = Vec::new();
        let c0 = centroid(mesh);
        for (k, s) in body.supports.iter().enumerate() {
            for node in mesh.edge_set_nodes(&s.edges) {
                for (c, v) in [(0, s.ux), (1, s.uy)] {
                    if let Some(v) = v {
                        let d = 2 * (node_offset[b] + node) + c;
                        if fixed[d] && prescribed[d] != v {
                            return Err(CoreError::invalid(
                                InvalidKind::Request,
                                format!("{}/supports/{k}", body.path),
                                format!(
                                    "conflicting prescribed displacements at node {node} (component {})",
                                    ["x", "y"][c]
                                ),
                            ));
                        }
                        fixed[d] = true;
                        prescribed[d] = v;
                        let p = mesh.nodes[node];
                        rows.push(mode_row(c, p[0] - c0[0], p[1] - c0[1]));
                    }
                }
            }
        }
        if scene.analysis == Analysis::Axisymmetric {
            axis_conditions(body, mesh, &scene.scales, node_offset[b], &mut fixed, &mut prescribed)?;
            // A body of revolution has one rigid motion, along the axis: a
            // radial "translation" or a rotation of the section strains the hoops.
            rows.push([1.0, 0.0, 0.0]);
            rows.push([0.0, 0.0, 1.0]);
        }
        if let Some(cp) = body.couplings.first() {
            if let Some(modes) = super::coupling::held(b, cp, mesh, node_offset[b], &mut fixed, &mut prescribed)? {
                rigid.push(modes);
            }
            continue;
        }
        let basis = free_modes(&rows);
        if basis.is_empty() {
            continue;
        }
        let in_contact = scene
            .pairs
            .iter()
            .any(|p| p.body == b || matches!(p.target, crate::scene::Target::Body { body, .. } if body == b));
        if !in_contact {
            let modes: Vec<String> = basis
                .iter()
                .map(|m| rigid_modes::describe(*m, c0, scene.scales.length(1.0)))
                .collect();
            return Err(CoreError::invalid(
                InvalidKind::NoSupport,
                body.supports_path(),
                format!(
                    "the supports of body '{}' leave its {} free and no contact pair involves the body to hold it",
                    body.name,
                    modes.join(" and ")
                ),
            ));
        }
        let off = node_offset[b];
        // Away from the contact edges if possible: a row whose node is held by a
        // virtual support sees the body only through its rigid modes.
        let mut contact_nodes = std::collections::HashSet::new();
        for p in &scene.pairs {
            if p.body == b {
                contact_nodes.extend(mesh.edge_set_nodes(&p.edges));
            }
            if let crate::scene::Target::Body { body, edges, .. } = &p.target {
                if *body == b {
                    contact_nodes.extend(mesh.edge_set_nodes(edges));
                }
            }
        }
        let away = virtual_supports(&mesh.nodes, c0, &basis, |n, c| {
            fixed[2 * (off + n) + c] || contact_nodes.contains(&n)
        });
        let chosen = if away.len() == basis.len() {
            away
        } else {
            virtual_supports(&mesh.nodes, c0, &basis, |n, c| fixed[2 * (off + n) + c])
        };
        let virtual_dofs: Vec<usize> = chosen.into_iter().map(|(n, c)| 2 * (off + n) + c).collect();
        for &d in &virtual_dofs {
            fixed[d] = true;
        }
        rigid.push(RigidModes {
            body: b,
            center: c0,
            basis,
            virtual_dofs,
        });
    }
    let mut free = vec![FIXED; 2 * total];
    let mut n_free = 0;
    for d in 0..2 * total {
        if !fixed[d] {
            free[d] = n_free;
            n_free += 1;
        }
    }
    Ok(DofMap {
        node_offset,
        free,
        prescribed,
        n_free,
        rigid,
    })
}

fn centroid(m: &Mesh2d) -> [f64; 2] {
    let n = m.nodes.len() as f64;
    let s = m.nodes.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
    [s[0] / n, s[1] / n]
}

/// CSC pattern of the lower triangle of K_ff from the node graph of all bodies.
fn pattern(meshes: &[Mesh2d], dofs: &DofMap) -> (Vec<usize>, Vec<usize>) {
    let total: usize = meshes.iter().map(|m| m.nodes.len()).sum();
    pattern::lower::<2>(total, &dofs.free, dofs.n_free, |add| {
        let mut global = Vec::with_capacity(6);
        for (b, mesh) in meshes.iter().enumerate() {
            let off = dofs.node_offset[b];
            for e in 0..mesh.n_elems() {
                global.clear();
                global.extend(mesh.elem(e).iter().map(|&p| off + p));
                add(&global);
            }
        }
    })
}

/// Axisymmetry: no node may lie at r < 0, and a node on the axis (r = 0 to
/// 1e-9 of the body's size) has u_r = 0.
fn axis_conditions(
    body: &crate::scene::Body,
    mesh: &Mesh2d,
    scales: &crate::scene::scaling::Scales,
    offset: usize,
    fixed: &mut [bool],
    prescribed: &mut [f64],
) -> Result<(), CoreError> {
    let tol = mesh.axis_tolerance();
    for (node, p) in mesh.nodes.iter().enumerate() {
        if p[0] < -tol {
            return Err(CoreError::invalid(
                InvalidKind::Geometry,
                format!("{}/mesh", body.path),
                format!(
                    "body '{}' has node {node} at x = {} < 0: in axisymmetry x is the radius, and the section must lie \
                        at x ≥ 0",
                    body.name,
                    shown(scales.length(p[0]))
                ),
            ));
        }
        if p[0] <= tol {
            let d = 2 * (offset + node);
            if fixed[d] && prescribed[d] != 0.0 {
                return Err(CoreError::invalid(
                    InvalidKind::Request,
                    format!("{}/supports", body.path),
                    format!(
                        "body '{}' prescribes u_x = {} at node {node} on the axis, where the radial displacement of a \
                            body of revolution is 0",
                        body.name,
                        shown(scales.length(prescribed[d]))
                    ),
                ));
            }
            fixed[d] = true;
            prescribed[d] = 0.0;
        }
    }
    Ok(())
}

/// The law of a body in the scene's analysis (`constitutive::law_of`).
pub fn law(body: &crate::scene::Body, analysis: Analysis) -> Law {
    law_of(body.youngs_modulus, body.poisson_ratio, analysis.into())
}

/// How a body's elements integrate: the P2–P0 element for nearly
/// incompressible plane strain or axisymmetry on T6 (see
/// `kernel::Integration`), the full rule otherwise.
pub fn integration(body: &crate::scene::Body, order: crate::mesh::Order, analysis: Analysis) -> Integration {
    let nu = body.poisson_ratio;
    if order == crate::mesh::Order::T6 && analysis != Analysis::PlaneStress && nu >= NEARLY_INCOMPRESSIBLE {
        Integration::MeanDilatation
    } else {
        Integration::Full
    }
}

/// Assembles K_ff and K_fd of all bodies: the pattern once from the node graph,
/// then element matrices added in place (no triplet sort).
pub fn assemble_stiffness(scene: &Scene, meshes: &[Mesh2d], dofs: &DofMap) -> Result<Stiffness, CoreError> {
    let n = dofs.n_free;
    let (col_ptr, row_idx) = pattern(meshes, dofs);
    let mut global = Global::new(&col_ptr, &row_idx);
    let mut gd = [0usize; 12];
    for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
        let law = law(body, scene.analysis);
        let how = integration(body, mesh.order, scene.analysis);
        each_element(mesh, scene.analysis, &law, how, 0..mesh.n_elems(), |conn, ke| {
            for (i, &node) in conn.iter().enumerate() {
                gd[2 * i] = dofs.dof(b, node, 0);
                gd[2 * i + 1] = dofs.dof(b, node, 1);
            }
            global.add(&gd[..2 * conn.len()], &dofs.free, ke);
        });
    }
    let Global { vals, k_fd, .. } = global;
    // SAFETY-free construction: the checked constructor validates sortedness and bounds.
    let sym = faer::sparse::SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(Stiffness {
        k: SparseColMat::new(sym, vals),
        k_fd,
    })
}

/// Calls `each(conn, ke)` with the nodes and the stiffness (row-major,
/// (2K)², DOFs u0x, u0y, u1x, ...) of each element `elems` lists, for `law`
/// in `analysis`: the one place the plane and ring bodies meet the kernel.
/// Each (element, strains) pair runs its own monomorphised loop (`for_order`),
/// chosen once per call, not per element.
pub fn each_element<L: Constitutive<3> + Constitutive<4>>(
    mesh: &Mesh2d,
    analysis: Analysis,
    law: &L,
    how: Integration,
    elems: impl Iterator<Item = usize>,
    mut each: impl FnMut(&[usize], &[f64]),
) {
    use crate::mesh::Order;
    let each = &mut each;
    match (mesh.order, analysis == Analysis::Axisymmetric) {
        (Order::T3, false) => for_order(mesh, elems, each, |x, ke| {
            kernel::stiffness::<T3, Plane, _, 2, 3, 3>(x, law, how, ke)
        }),
        (Order::T3, true) => for_order(mesh, elems, each, |x, ke| {
            kernel::stiffness::<T3, Ring, _, 2, 3, 4>(x, law, how, ke)
        }),
        (Order::T6, false) => for_order(mesh, elems, each, |x, ke| {
            kernel::stiffness::<T6, Plane, _, 2, 6, 3>(x, law, how, ke)
        }),
        (Order::T6, true) => for_order(mesh, elems, each, |x, ke| {
            kernel::stiffness::<T6, Ring, _, 2, 6, 4>(x, law, how, ke)
        }),
    }
}

/// `each_element` for elements of K nodes, whose stiffness `element` writes
/// into a (2K)² row-major buffer.
fn for_order<const K: usize>(
    mesh: &Mesh2d,
    elems: impl Iterator<Item = usize>,
    each: &mut impl FnMut(&[usize], &[f64]),
    element: impl Fn(&[[f64; 2]; K], &mut [f64]),
) {
    let nd = 2 * K;
    let mut ke = [0.0; 144];
    let mut x = [[0.0; 2]; K];
    for e in elems {
        let conn = mesh.elem(e);
        for (xi, &node) in x.iter_mut().zip(conn) {
            *xi = mesh.nodes[node];
        }
        element(&x, &mut ke);
        each(conn, &ke[..nd * nd]);
    }
}

/// Right-hand side f_f − K_fd u_d from the external loads on every global DOF
/// (`external_loads`, computed once per solve: the rigid modes need them too)
/// and the prescribed displacements.
pub fn assemble_loads(external: &[f64], dofs: &DofMap, stiffness: &Stiffness) -> Vec<f64> {
    free_rhs(external, &dofs.free, &dofs.prescribed, dofs.n_free, stiffness)
}

/// f_f − K_fd u_d for any DOF map (`free`: each global DOF's free index or
/// FIXED; `prescribed`: its value where fixed), the plane's and the solid's.
pub fn free_rhs(
    external: &[f64],
    free: &[usize],
    prescribed: &[f64],
    n_free: usize,
    stiffness: &Stiffness,
) -> Vec<f64> {
    let mut f = vec![0.0; n_free];
    for (d, &v) in external.iter().enumerate() {
        if free[d] != FIXED {
            f[free[d]] += v;
        }
    }
    for &(row, d, v) in &stiffness.k_fd {
        f[row] -= v * prescribed[d];
    }
    f
}
