//! K_ff and K_fd of a body of tetrahedra, and its internal forces K u.
//!
//! K = Σ_e K_e with K_e = `fem::kernel::stiffness` of the element (T4 or T10)
//! with the solid strains and the body's law in `Section::Solid`;
//! the P2–P0 element (mean dilatation) for T10 from ν ≥ 0.45, as in 2D. The
//! sparse pattern and scatter are `fem::pattern`'s with D = 3.

use super::dofs::SolidDofs;
use super::SolidBody;
use crate::cancel::{self, Timeout};
use crate::fem::assembly::{Stiffness, NEARLY_INCOMPRESSIBLE};
use crate::fem::constitutive::{law_of, Law, Section};
use crate::fem::kernel::{self, Integration, Solid};
use crate::fem::pattern::{self, Global};
use crate::fem::reference::{T10, T4};
use crate::mesh3d::Order;
use crate::outcome::ProgressStage;

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

/// Elements between looks at the request's clock. A T10's stiffness and its
/// scatter took about 40 µs here (35k DOF assembled in 0.3 s), so 1024 are
/// about 40 ms of work, 0.2 s on a machine loaded 5 times over: a 150k-DOF
/// T10 body, whose assembly did not look at the clock, answered a 1.5 s
/// time limit after 6.2–7.9 s (load 8–9), its first look the ordering's.
const ELEMENTS_BETWEEN_CHECKS: usize = 1024;

/// Calls `each(conn, ke)` with every element's nodes and its stiffness
/// (row-major, (3 N)², DOFs u0x, u0y, u0z, u1x, ...); a `Timeout` at
/// `stage` once the request's deadline has passed.
pub fn each_element(
    body: &SolidBody,
    stage: ProgressStage,
    mut each: impl FnMut(&[usize], &[f64]),
) -> Result<(), Timeout> {
    let law = law(body);
    let how = integration(body);
    match body.mesh.order {
        Order::T4 => for_order::<4>(
            body,
            stage,
            |x, ke| kernel::stiffness::<T4, Solid, _, 3, 4, 6>(x, &law, how, ke),
            &mut each,
        ),
        Order::T10 => for_order::<10>(
            body,
            stage,
            |x, ke| kernel::stiffness::<T10, Solid, _, 3, 10, 6>(x, &law, how, ke),
            &mut each,
        ),
    }
}

fn for_order<const N: usize>(
    body: &SolidBody,
    stage: ProgressStage,
    element: impl Fn(&[[f64; 3]; N], &mut [f64]),
    each: &mut impl FnMut(&[usize], &[f64]),
) -> Result<(), Timeout> {
    let mesh = body.mesh;
    let nd = 3 * N;
    let mut ke = [0.0; 900];
    let mut x = [[0.0; 3]; N];
    for e in 0..mesh.n_elems() {
        if e % ELEMENTS_BETWEEN_CHECKS == 0 {
            cancel::check(stage)?;
        }
        let conn = mesh.elem(e);
        for (xi, &node) in x.iter_mut().zip(conn) {
            *xi = mesh.nodes[node];
        }
        element(&x, &mut ke);
        each(conn, &ke[..nd * nd]);
    }
    Ok(())
}

/// K_ff (lower triangle) and K_fd: the pattern once from the node graph,
/// then the element matrices added in place.
pub fn assemble(body: &SolidBody, dofs: &SolidDofs) -> Result<Stiffness, Timeout> {
    let mesh = body.mesh;
    let n = dofs.n_free;
    let (col_ptr, row_idx) = pattern::lower::<3>(mesh.nodes.len(), &dofs.free, n, |add| {
        for e in 0..mesh.n_elems() {
            add(mesh.elem(e));
        }
    });
    let mut global = Global::new(&col_ptr, &row_idx);
    let mut gd = Vec::with_capacity(30);
    each_element(body, ProgressStage::Assembly, |conn, ke| {
        gd.clear();
        gd.extend(conn.iter().flat_map(|&p| [3 * p, 3 * p + 1, 3 * p + 2]));
        global.add(&gd, &dofs.free, ke);
    })?;
    let Global { vals, k_fd, .. } = global;
    let sym = faer::sparse::SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(Stiffness {
        k: faer::sparse::SparseColMat::new(sym, vals),
        k_fd,
    })
}

/// K u and |K| |u| on every DOF (supports included), element by element: the
/// reactions and the equilibrium residual read the first, the size of the
/// terms it sums (against which its round-off is judged) the second.
pub fn internal_forces(body: &SolidBody, u: &[f64], stage: ProgressStage) -> Result<(Vec<f64>, Vec<f64>), Timeout> {
    let mut ku = vec![0.0; u.len()];
    let mut abs = vec![0.0; u.len()];
    each_element(body, stage, |conn, ke| {
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
    })?;
    Ok((ku, abs))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::generate::box_mesh;

    /// An assembly under way when the request's deadline passes stops at its
    /// next look at the clock (here the first: the deadline has passed
    /// already) with the assembly's timeout, as the factorization does; with
    /// no deadline it runs to the end, its K u of a rigid translation zero.
    #[test]
    fn an_assembly_past_its_deadline_is_stopped() {
        let mesh = box_mesh([0.0; 3], [1.0, 0.5, 0.7], 0.35, None, Order::T10);
        let body = SolidBody {
            mesh: &mesh,
            youngs_modulus: 1.0,
            poisson_ratio: 0.3,
            supports: vec![],
            loads: vec![],
            body_force: [0.0; 3],
        };
        let u: Vec<f64> = mesh.nodes.iter().flat_map(|_| [1.0, 0.0, 0.0]).collect();
        let (ku, abs) = internal_forces(&body, &u, ProgressStage::Post).expect("no deadline");
        let scale = abs.iter().fold(0.0f64, |a, &b| a.max(b));
        assert!(
            ku.iter().all(|f| f.abs() <= 1e-12 * scale),
            "a translation strains nothing"
        );
        let _d = cancel::Deadline::install(std::time::Duration::ZERO);
        match internal_forces(&body, &u, ProgressStage::Assembly) {
            Err(t) => assert_eq!(t.stage, ProgressStage::Assembly),
            Ok(_) => panic!("expected a stop at the deadline"),
        }
    }
}
