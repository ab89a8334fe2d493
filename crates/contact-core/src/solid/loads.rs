//! Nodal loads of a body of tetrahedra: face loads and the body force.
//!
//! A face of a face set is a triangle (T4: 3 nodes; T10: 6 nodes, Gmsh's
//! order, the reference T6's), mapped x(ξ) = Σ N_i(ξ) x_i from the reference
//! triangle, so n dA = (∂x/∂ξ × ∂x/∂η) dξ dη, outward for the face sets'
//! orientation. The consistent nodal force of a traction t is
//! ∫ N_i t |∂x/∂ξ × ∂x/∂η| dξ dη, of a pressure −p ∫ N_i (∂x/∂ξ × ∂x/∂η) dξ dη,
//! over the face element's rule (degree 1 for T3, 2 for T6: exact for
//! uniform loads on flat faces). The body force b gives ∫ N_i b dV over the
//! tetrahedron's rule (exact on affine T4 and T10: N_i is of degree ≤ 2).

use super::dofs::SolidDofs;
use super::{FaceLoad, SolidBody};
use crate::error::CoreError;
use crate::fem::assembly::Stiffness;
use crate::fem::pattern::FIXED;
use crate::fem::reference::{physical_gradients, ReferenceElement, T10, T3, T4, T6};
use crate::mesh3d::{cross, Order};

/// Nodal external forces on every DOF (3·node + c), supports included.
pub fn external(body: &SolidBody) -> Result<Vec<f64>, CoreError> {
    let mesh = body.mesh;
    let mut f = vec![0.0; 3 * mesh.nodes.len()];
    for (k, load) in body.loads.iter().enumerate() {
        for face in body.face_set(load.faces(), &format!("loads/{k}/faces"))? {
            let nodes: Vec<usize> = face.nodes().collect();
            let mut add = |i: usize, v: [f64; 3]| {
                for c in 0..3 {
                    f[3 * nodes[i] + c] += v[c];
                }
            };
            match mesh.order {
                Order::T4 => face_load::<T3, 3>(std::array::from_fn(|i| mesh.nodes[nodes[i]]), load, &mut add),
                Order::T10 => face_load::<T6, 6>(std::array::from_fn(|i| mesh.nodes[nodes[i]]), load, &mut add),
            }
        }
    }
    if body.body_force != [0.0; 3] {
        for e in 0..mesh.n_elems() {
            let conn = mesh.elem(e);
            let mut add = |i: usize, w: f64| {
                for c in 0..3 {
                    f[3 * conn[i] + c] += w * body.body_force[c];
                }
            };
            match mesh.order {
                Order::T4 => volume_shares::<T4, 4>(std::array::from_fn(|i| mesh.nodes[conn[i]]), &mut add),
                Order::T10 => volume_shares::<T10, 10>(std::array::from_fn(|i| mesh.nodes[conn[i]]), &mut add),
            }
        }
    }
    Ok(f)
}

/// The nodal forces of `load` on the face with nodes `x` (face order).
fn face_load<E: ReferenceElement<2, N>, const N: usize>(
    x: [[f64; 3]; N],
    load: &FaceLoad,
    add: &mut impl FnMut(usize, [f64; 3]),
) {
    for q in E::RULE {
        let (n, g) = E::evaluate(&q.xi);
        let tangent = |r: usize| -> [f64; 3] { std::array::from_fn(|c| (0..N).map(|i| g[i][r] * x[i][c]).sum()) };
        let na = cross(tangent(0), tangent(1));
        let t = match load {
            FaceLoad::Pressure { p, .. } => na.map(|v| -p * v),
            FaceLoad::Traction { t, .. } => {
                let area = (na[0] * na[0] + na[1] * na[1] + na[2] * na[2]).sqrt();
                t.map(|v| v * area)
            }
        };
        for (i, ni) in n.iter().enumerate() {
            add(i, t.map(|v| q.weight * ni * v));
        }
    }
}

/// ∫ N_i dV of each node of the element with nodes `x`.
fn volume_shares<E: ReferenceElement<3, N>, const N: usize>(x: [[f64; 3]; N], add: &mut impl FnMut(usize, f64)) {
    for q in E::RULE {
        let (n, g) = E::evaluate(&q.xi);
        let (det, _) = physical_gradients(&x, &g);
        for (i, ni) in n.iter().enumerate() {
            add(i, q.weight * det * ni);
        }
    }
}

/// f_f − K_fd u_d: the right-hand side on the free DOFs.
pub fn free_rhs(external: &[f64], dofs: &SolidDofs, stiffness: &Stiffness) -> Vec<f64> {
    crate::fem::assembly::free_rhs(external, &dofs.free, &dofs.prescribed, dofs.n_free, stiffness)
}

/// The displacement of every DOF from the free ones: prescribed values
/// elsewhere (0 at a virtual support).
pub fn full_field(dofs: &SolidDofs, u_free: &[f64]) -> Vec<f64> {
    dofs.free
        .iter()
        .zip(&dofs.prescribed)
        .map(|(&i, &p)| if i == FIXED { p } else { u_free[i] })
        .collect()
}
