//! The body's fields a request's `outputs` asks for: the nodal displacement
//! and the stress at each tetrahedron's centroid, from the solved u.
//!
//! The stress is σ = D ε(centroid) with the body's law in `Section::Solid`
//! (`fem::constitutive`), ε from `fem::kernel::strain` over the element's own
//! shape functions. On the P2–P0 element (nearly incompressible T10,
//! `stiffness::integration`) the stiffness carries the volumetric part on
//! the mean dilatation θ̄, so the stress does too: σ = D ε − λ (tr ε − θ̄) m,
//! the mixed element's constant pressure rather than the locked pointwise one.
//! On a straight-sided T10 the two agree (u quadratic, ε linear, whose mean
//! is its centroid value), so the term acts on curved (Gmsh order-2) elements
//! only; the test below checks the straight case, where it must vanish.

use super::stiffness::{integration, law};
use super::SolidBody;
use crate::fem::constitutive::Constitutive;
use crate::fem::kernel::{self, Integration, Solid, Strains};
use crate::fem::reference::{ReferenceElement, T10, T4};
use crate::mesh3d::Order;

/// The reference centroid of a tetrahedron.
const CENTROID: [f64; 3] = [0.25, 0.25, 0.25];

/// Node k's displacement (u of DOFs 3k, 3k+1, 3k+2).
pub fn displacement(u: &[f64]) -> Vec<[f64; 3]> {
    u.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

/// Each element's stress at its centroid, Voigt (xx, yy, zz, yz, xz, xy)
/// as `kernel::Solid` orders the strains.
pub fn stress(body: &SolidBody, u: &[f64]) -> Vec<[f64; 6]> {
    match body.mesh.order {
        Order::T4 => stress_of::<T4, 4>(body, u),
        Order::T10 => stress_of::<T10, 10>(body, u),
    }
}

fn stress_of<E: ReferenceElement<3, N>, const N: usize>(body: &SolidBody, u: &[f64]) -> Vec<[f64; 6]> {
    let (law, how, mesh) = (law(body), integration(body), body.mesh);
    let lambda = Constitutive::<6>::volumetric_lambda(&law);
    (0..mesh.n_elems())
        .map(|e| {
            let conn = mesh.elem(e);
            let x: [[f64; 3]; N] = std::array::from_fn(|i| mesh.nodes[conn[i]]);
            let ue: [[f64; 3]; N] = std::array::from_fn(|i| std::array::from_fn(|c| u[3 * conn[i] + c]));
            let eps = kernel::strain::<E, Solid, 3, N, 6>(&x, &CENTROID, &ue);
            let mut s = law.stress(&eps);
            if how == Integration::MeanDilatation {
                let (bbar, _) = kernel::mean_dilatation::<E, Solid, 3, N, 6>(&x);
                let theta: f64 = bbar.iter().flatten().zip(ue.iter().flatten()).map(|(b, v)| b * v).sum();
                let trace: f64 = (0..6).map(|k| Solid::VOLUME[k] * eps[k]).sum();
                for (sk, m) in s.iter_mut().zip(Solid::VOLUME) {
                    *sk -= lambda * (trace - theta) * m;
                }
            }
            s
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::generate::box_mesh;

    /// A linear field u = G x is reproduced exactly by T4 and T10, so every
    /// element's stress is D ε(G) to rounding (1e-12 on unit data: a few
    /// hundred flops of O(1) terms); for G = diag(a, 0, 0) in an isotropic
    /// law σxx = (λ + 2μ) a, σyy = σzz = λ a and no shear.
    #[test]
    fn a_uniform_strain_gives_the_laws_stress_in_every_element() {
        let (e, a) = (1.0, 1e-3);
        // ν = 0.49 takes the P2–P0 path on T10.
        for (order, nu) in [(Order::T4, 0.3), (Order::T10, 0.3), (Order::T10, 0.49)] {
            let (l, m) = (e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu)));
            let mesh = box_mesh([0.0; 3], [1.0, 0.5, 0.7], 0.35, None, order);
            let body = SolidBody {
                mesh: &mesh,
                youngs_modulus: e,
                poisson_ratio: nu,
                supports: vec![],
                loads: vec![],
                body_force: [0.0; 3],
            };
            let u: Vec<f64> = mesh.nodes.iter().flat_map(|x| [a * x[0], 0.0, 0.0]).collect();
            let want = [(l + 2.0 * m) * a, l * a, l * a, 0.0, 0.0, 0.0];
            for s in stress(&body, &u) {
                for k in 0..6 {
                    assert!((s[k] - want[k]).abs() < 1e-12, "{order:?} ν={nu}: {s:?} vs {want:?}");
                }
            }
            assert_eq!(displacement(&u)[1], [a * mesh.nodes[1][0], 0.0, 0.0]);
        }
    }
}
