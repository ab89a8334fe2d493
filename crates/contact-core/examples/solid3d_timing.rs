//! Solve times of the 3D solid on graded T4 boxes of about 50k and 300k DOF (n = 23 and 44 cells a side)
//! (and a T10 box of about 50k): the unit cube on a rigid plane tilted by
//! 0.002 rad about the y axis (so the base touches along x = 0 first and the
//! active set has work to do), uniform pressure on its top, rollers on its
//! four sides; grid lines uniform in x and y, graded toward the base in z.
//! For each: the linear solve of the same box on a roller base, then the
//! contact solve, stage by stage (seconds), with the rows, active rows,
//! iterations and the certificate's worst entry. Timings only, nothing is
//! asserted; one thread (`linalg::threads`' default, the service's).
//!
//! Each factor's cost (from the symbolic analysis alone) in the AMD order
//! the 2D solve uses and in the nested-dissection order of
//! `solid::ordering`, which the 3D solves use.
//!
//! `cargo run --release -p contact-core --example solid3d_timing [-- --cost] [--small]` (`--cost`: the factors'
//! costs alone, no numeric factorization; `--small`: the 50k-DOF boxes only).

use std::sync::Arc;

use contact_core::linalg::cholesky::{Cholesky, FactorCost, SymbolicFactor};
use contact_core::mesh::generate::{graded_points, Grading};
use contact_core::mesh3d::generate::{grid, uniform};
use contact_core::mesh3d::{Mesh3d, Order};
use contact_core::scene::Settings;
use contact_core::solid::dofs::dof_map;
use contact_core::solid::obstacle::{rows, Plane};
use contact_core::solid::{linear, ordering, signorini, stiffness, FaceLoad, SolidBody, Support};

fn mesh(n: usize, order: Order) -> Mesh3d {
    let h = 1.0 / n as f64;
    let g = Grading {
        h_min: 0.25 * h,
        ratio: 1.3,
        extent: h,
    };
    let z = graded_points(0.0, 1.0, 0.0, g, h);
    grid(&[uniform(0.0, 1.0, n), uniform(0.0, 1.0, n), z], order)
}

fn main() {
    let cost_only = std::env::args().any(|a| a == "--cost");
    let small = std::env::args().any(|a| a == "--small");
    for (n, order) in [(23, Order::T4), (44, Order::T4), (11, Order::T10), (16, Order::T10)] {
        if small && (n == 44 || n == 16) {
            continue;
        }
        let t = std::time::Instant::now();
        let mesh = mesh(n, order);
        let t_mesh = t.elapsed().as_secs_f64();
        let sides = vec![
            Support::roller("x_min", 0),
            Support::roller("x_max", 0),
            Support::roller("y_min", 1),
            Support::roller("y_max", 1),
        ];
        let mut body = SolidBody {
            mesh: &mesh,
            youngs_modulus: 1.0,
            poisson_ratio: 0.3,
            supports: sides.clone(),
            loads: vec![FaceLoad::Pressure {
                faces: "z_max".into(),
                p: 1e-3,
            }],
            body_force: [0.0; 3],
        };
        body.supports.push(Support::roller("z_min", 2));
        let dofs = dof_map(&body, None).unwrap();
        println!(
            "{order:?} n = {n}: {} nodes, {} elements, {} free DOFs (mesh {t_mesh:.2} s)",
            mesh.nodes.len(),
            mesh.n_elems(),
            dofs.n_free
        );
        let k = stiffness::assemble(&body, &dofs).expect("no deadline here");
        let cost = FactorCost::predict(&k.k).unwrap();
        println!(
            "  factor (AMD): nnz(L) {:.3e}, {:.3e} multiply-adds",
            cost.nnz as f64, cost.flops
        );
        let t = std::time::Instant::now();
        let (fwd, inv) = ordering::nested_dissection(&mesh, &dofs).unwrap();
        let t_order = t.elapsed().as_secs_f64();
        let analysis = Arc::new(SymbolicFactor::try_new_ordered(&k.k, &fwd, &inv).unwrap());
        let t_symbolic = t.elapsed().as_secs_f64() - t_order;
        let nd = analysis.cost();
        let per = |s: f64| 1e6 * s / dofs.n_free as f64;
        println!(
            "  factor (nested dissection): nnz(L) {:.3e} ({:.0} B per DOF), {:.3e} multiply-adds (ordering \
             {t_order:.3} s, {:.2} µs per DOF; symbolic analysis {t_symbolic:.3} s, {:.2} µs per DOF)",
            nd.nnz as f64,
            8.0 * nd.nnz as f64 / dofs.n_free as f64,
            nd.flops,
            per(t_order),
            per(t_symbolic)
        );
        if cost_only {
            continue;
        }
        // The numeric factorization alone against the time model fitted on
        // 2D factors (`FactorCost::reference_secs`).
        let t = std::time::Instant::now();
        drop(Cholesky::with_symbolic(analysis, &k.k).unwrap());
        let real = t.elapsed().as_secs_f64();
        // This machine's scale, measured on a 2D grid just after: what the
        // 3D factor's ratio would be if the 2D model held for it.
        let scale = contact_core::linalg::calibrate::calibrate();
        println!(
            "  numeric factorization {real:.3} s; the 2D-fitted model predicts {:.3} s on its reference machine \
             (real / predicted {:.2}; a 2D grid's just after {scale:.2})",
            nd.reference_secs(),
            real / nd.reference_secs()
        );
        let s = linear::solve(&body).unwrap();
        let [a, f, so] = s.seconds;
        println!(
            "  linear:  assembly {a:.3} s, factorization {f:.3} s, solve {so:.3} s, total {:.3} s, backward error \
             {:.1e}",
            a + f + so,
            s.residual
        );
        if order == Order::T10 {
            continue;
        }
        body.supports = sides;
        let theta: f64 = 0.002;
        let plane = Plane::try_new([0.0; 3], [theta.sin(), 0.0, theta.cos()]).unwrap();
        let t = std::time::Instant::now();
        let r = rows(&body, "z_min", plane).unwrap();
        let t_rows = t.elapsed().as_secs_f64();
        let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
        let [a, f, so] = c.seconds;
        let active = c.lambda.iter().filter(|&&l| l > 0.0).count();
        println!(
            "  contact: rows {t_rows:.3} s, assembly {a:.3} s, factorization + W {f:.3} s, LCP + u {so:.3} s, total \
             {:.3} s; {} rows, {active} active, {} iterations, {} refinements, certificate {:.1e}, converged {}",
            t_rows + a + f + so,
            r.len(),
            c.iterations,
            c.refinements,
            c.certificate.worst(),
            c.converged
        );
    }
}
