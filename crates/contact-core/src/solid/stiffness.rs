//! K_ff and K_fd of a body of tetrahedra, and its internal forces K u.
//!
//! K = Σ_e K_e with K_e = `fem::kernel::stiffness` of the element (T4 or T10)
//! with the solid strains and the body's law in `Section::Solid`;
//! the P2–P0 element (mean dilatation) for T10 from ν ≥ 0.45, as in 2D. The
//! sparse pattern and scatter are `fem::pattern`'s with D = 3.

use super::dofs::SolidDofs;
use super::SolidBody;
use crate::fem::assembly::{Stiffness, NEARLY_INCOMPRESSIBLE};
use crate::fem::constitutive::{law_of, Law, Section};
use crate::fem::kernel::{self, Integration, Solid};
use crate::fem::pattern::{self, Global};
use crate::fem::reference::{T10, T4};
use crate::mesh3d::Order;

/// The body's law (`constitutive::law_of`).
pub fn law(body: &SolidBody) -> Law {
    law_of(body.youngs_modulus, body.poisson_ratio, Section::Solid)
}

/// The P2–P0 element for nearly incompressible T10, the full rule otherwise
/// (T4 has one point: mean dilatation would change nothing, and it locks).
pub fn integration(body: &SolidBody) -> Integration {
    if body.mesh.order == Order::T10 && body.poisson_ratio >= NEARLY_INCOMPRESSIBLE {
        Integration::MeanDilatation
    } else {
        Integration::Full
    }
}

/// Calls `each(conn, ke)` with every element's nodes and its stiffness
/// (row-major, (3 N)², DOFs u0x, u0y, u0z, u1x, ...).
pub fn each_element(body: &SolidBody, mut each: impl FnMut(&[usize], &[f64])) {
    let law = law(body);
    let how = integration(body);
    match body.mesh.order {
        Order::T4 => for_order::<4>(
            body,
            |x, ke| kernel::stiffness::<T4, Solid, _, 3, 4, 6>(x, &law, how, ke),
            &mut each,
        ),
        Order::T10 => for_order::<10>(
            body,
            |x, ke| kernel::stiffness::<T10, Solid, _, 3, 10, 6>(x, &law, how, ke),
            &mut each,
        ),
    }
}

fn for_order<const N: usize>(
    body: &SolidBody,
    element: impl Fn(&[[f64; 3]; N], &mut [f64]),
    each: &mut impl FnMut(&[usize], &[f64]),
) {
    let mesh = body.mesh;
    let nd = 3 * N;
    let mut ke = [0.0; 900];
    let mut x = [[0.0; 3]; N];
    for e in 0..mesh.n_elems() {
        let conn = mesh.elem(e);
        for (xi, &node) in x.iter_mut().zip(conn) {
            *xi = mesh.nodes[node];
        }
        element(&x, &mut ke);
        each(conn, &ke[..nd * nd]);
    }
}

/// K_ff (lower triangle) and K_fd: the pattern once from the node graph,
/// then the element matrices added in place.
pub fn assemble(body: &SolidBody, dofs: &SolidDofs) -> Stiffness {
    let mesh = body.mesh;
    let n = dofs.n_free;
    let (col_ptr, row_idx) = pattern::lower::<3>(mesh.nodes.len(), &dofs.free, n, |add| {
        for e in 0..mesh.n_elems() {
            add(mesh.elem(e));
        }
    });
    let mut global = Global::new(&col_ptr, &row_idx);
    let mut gd = Vec::with_capacity(30);
    each_element(body, |conn, ke| {
        gd.clear();
        gd.extend(conn.iter().flat_map(|&p| [3 * p, 3 * p + 1, 3 * p + 2]));
        global.add(&gd, &dofs.free, ke);
    });
    let Global { vals, k_fd, .. } = global;
    let sym = faer::sparse::SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Stiffness {
        k: faer::sparse::SparseColMat::new(sym, vals),
        k_fd,
    }
}

/// K u and |K| |u| on every DOF (supports included), element by element: the
/// reactions and the equilibrium residual read the first, the size of the
/// terms it sums (against which its round-off is judged) the second.
pub fn internal_forces(body: &SolidBody, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut ku = vec![0.0; u.len()];
    let mut abs = vec![0.0; u.len()];
    each_element(body, |conn, ke| {
        let nd = 3 * conn.len();
        let dof = |a: usize| 3 * conn[a / 3] + a % 3;
        for a in 0..nd {
            let (mut s, mut t) = (0.0, 0.0);
            for b in 0..nd {
                let v = ke[a * nd + b] * u[dof(b)];
                s += v;
                t += v.abs();
            }
            ku[dof(a)] += s;
            abs[dof(a)] += t;
        }
    });
    (ku, abs)
}
