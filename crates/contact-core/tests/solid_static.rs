//! The 3D solid's assembly, loads and linear solve (`contact_core::solid`)
//! against closed forms the elements reproduce exactly, on graded meshes
//! (grid lines spaced 0.04 near a corner, growing by 1.5 per cell: no two
//! neighbouring cells alike):
//!
//! - uniaxial stress: a box under uniform pressure p on its top, symmetry
//!   rollers on x = 0, y = 0, z = 0, free sides: σ_zz = −p, u_z = −p z / E,
//!   u_x = ν p x / E, u_y = ν p y / E (a linear field, in T4's and T10's
//!   spaces, and the consistent load of a uniform pressure is exact);
//! - oedometric: the same box with rollers on all four sides: u_z = −p z / M,
//!   M = E (1 − ν) / ((1 + ν)(1 − 2ν));
//! - a bar under its own weight b, rollers on its sides and bottom: the 1D
//!   field u_z = −(b / M)(H z − z² / 2), quadratic, so T10 holds it exactly
//!   (and its consistent body force, ∫ N_i b dV, is exact on affine T10).
//!
//! The tolerance 1e-10 (relative to the largest displacement or stress) is
//! what is left when the discrete solution is the exact one: the round-off of
//! the sparse Cholesky, ε · cond(K) with cond(K) ~ 1e4 on these meshes
//! (measured errors are printed; they are 1e-14 to 1e-12).

use contact_core::error::{CoreError, InvalidKind};
use contact_core::fem::constitutive::Constitutive;
use contact_core::fem::kernel::{self, Solid};
use contact_core::fem::reference::{T10, T4};
use contact_core::mesh::generate::Grading;
use contact_core::mesh3d::generate::box_mesh;
use contact_core::mesh3d::{Mesh3d, Order};
use contact_core::solid::{linear, stiffness, FaceLoad, SolidBody, Support};

const E: f64 = 3.0;
const P: f64 = 0.02;

fn graded(hi: [f64; 3], order: Order) -> Mesh3d {
    let g = Grading {
        h_min: 0.04,
        ratio: 1.5,
        extent: 0.05,
    };
    box_mesh([0.0; 3], hi, 0.25, Some(([0.0; 3], g)), order)
}

fn body(mesh: &Mesh3d, nu: f64, supports: Vec<Support>, loads: Vec<FaceLoad>, b: [f64; 3]) -> SolidBody<'_> {
    SolidBody {
        mesh,
        youngs_modulus: E,
        poisson_ratio: nu,
        supports,
        loads,
        body_force: b,
    }
}

fn top_pressure() -> Vec<FaceLoad> {
    vec![FaceLoad::Pressure {
        faces: "z_max".into(),
        p: P,
    }]
}

/// Largest |u_h − u| over the nodes, over the largest |u|.
fn nodal_error(mesh: &Mesh3d, u: &[f64], exact: impl Fn([f64; 3]) -> [f64; 3]) -> f64 {
    let (mut err, mut size) = (0.0f64, 0.0f64);
    for (n, &x) in mesh.nodes.iter().enumerate() {
        let e = exact(x);
        for c in 0..3 {
            err = err.max((u[3 * n + c] - e[c]).abs());
            size = size.max(e[c].abs());
        }
    }
    err / size
}

/// Largest |σ_h − σ| at every element's quadrature-free centroid, over |σ|.
fn stress_error(b: &SolidBody, u: &[f64], exact: [f64; 6]) -> f64 {
    let law = stiffness::law(b);
    let scale = exact.iter().fold(0.0f64, |a, s| a.max(s.abs()));
    let mut err = 0.0f64;
    let mesh = b.mesh;
    for e in 0..mesh.n_elems() {
        let conn = mesh.elem(e);
        let xi = [0.25; 3];
        let strain: [f64; 6] = match mesh.order {
            Order::T4 => {
                let x = std::array::from_fn(|i| mesh.nodes[conn[i]]);
                let ue = std::array::from_fn(|i| std::array::from_fn(|c| u[3 * conn[i] + c]));
                kernel::strain::<T4, Solid, 3, 4, 6>(&x, &xi, &ue)
            }
            Order::T10 => {
                let x = std::array::from_fn(|i| mesh.nodes[conn[i]]);
                let ue = std::array::from_fn(|i| std::array::from_fn(|c| u[3 * conn[i] + c]));
                kernel::strain::<T10, Solid, 3, 10, 6>(&x, &xi, &ue)
            }
        };
        let s = law.stress(&strain);
        for c in 0..6 {
            err = err.max((s[c] - exact[c]).abs());
        }
    }
    err / scale
}

/// Σ of the reactions' component c over the DOFs.
fn reaction(r: &[f64], c: usize) -> f64 {
    r.iter().skip(c).step_by(3).sum()
}

#[test]
fn uniaxial_stress_patch_test_is_exact_on_t4_and_t10() {
    // ν = 0.49 on T10 runs the P2–P0 element, which holds a uniform pressure too.
    for (order, nu) in [(Order::T4, 0.3), (Order::T10, 0.3), (Order::T10, 0.49)] {
        let mesh = graded([1.0, 0.8, 1.2], order);
        let supports = vec![
            Support::roller("x_min", 0),
            Support::roller("y_min", 1),
            Support::roller("z_min", 2),
        ];
        let b = body(&mesh, nu, supports, top_pressure(), [0.0; 3]);
        let s = linear::solve(&b).unwrap();
        let eu = nodal_error(&mesh, &s.u, |x| [nu * P * x[0] / E, nu * P * x[1] / E, -P * x[2] / E]);
        let es = stress_error(&b, &s.u, [0.0, 0.0, -P, 0.0, 0.0, 0.0]);
        println!(
            "{order:?} ν = {nu}: {} DOFs, u error {eu:.1e}, σ error {es:.1e}, residual {:.1e}",
            s.dofs.n_free, s.residual
        );
        assert!(eu < 1e-10 && es < 1e-10, "{order:?} ν = {nu}: {eu:e} {es:e}");
        // The base carries the load: Σ R_z = p A, to round-off of the sum.
        let area = 1.0 * 0.8;
        assert!((reaction(&s.reactions, 2) - P * area).abs() < 1e-12 * P * area);
        assert!(s.residual < 1e-12, "backward error {}", s.residual);
    }
}

#[test]
fn oedometric_patch_test_is_exact_on_t4_and_t10() {
    for order in [Order::T4, Order::T10] {
        let nu = 0.3;
        let m = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mesh = graded([1.0, 1.0, 1.0], order);
        let supports = vec![
            Support::roller("x_min", 0),
            Support::roller("x_max", 0),
            Support::roller("y_min", 1),
            Support::roller("y_max", 1),
            Support::roller("z_min", 2),
        ];
        let b = body(&mesh, nu, supports, top_pressure(), [0.0; 3]);
        let s = linear::solve(&b).unwrap();
        let eu = nodal_error(&mesh, &s.u, |x| [0.0, 0.0, -P * x[2] / m]);
        let lateral = -P * nu / (1.0 - nu);
        let es = stress_error(&b, &s.u, [lateral, lateral, -P, 0.0, 0.0, 0.0]);
        println!("{order:?}: u error {eu:.1e}, σ error {es:.1e}");
        assert!(eu < 1e-10 && es < 1e-10, "{order:?}: {eu:e} {es:e}");
    }
}

#[test]
fn t10_bar_under_its_own_weight_is_exact() {
    let (h, nu, g) = (1.0, 0.25, 0.1);
    let m = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mesh = graded([0.3, 0.3, h], Order::T10);
    let supports = vec![
        Support::roller("x_min", 0),
        Support::roller("x_max", 0),
        Support::roller("y_min", 1),
        Support::roller("y_max", 1),
        Support::roller("z_min", 2),
    ];
    let b = body(&mesh, nu, supports, Vec::new(), [0.0, 0.0, -g]);
    let s = linear::solve(&b).unwrap();
    let eu = nodal_error(&mesh, &s.u, |x| [0.0, 0.0, -(g / m) * (h * x[2] - 0.5 * x[2] * x[2])]);
    println!("T10 bar: {} DOFs, u error {eu:.1e}", s.dofs.n_free);
    assert!(eu < 1e-10, "{eu:e}");
    // The base carries the weight g V (the sides' rollers carry nothing vertical).
    let weight = g * 0.3 * 0.3 * h;
    assert!((reaction(&s.reactions, 2) - weight).abs() < 1e-12 * weight);
    // T4 cannot hold the quadratic field: its error is far above round-off
    // (the check that the comparison above can fail).
    let mesh4 = graded([0.3, 0.3, h], Order::T4);
    let b4 = SolidBody {
        mesh: &mesh4,
        ..b.clone()
    };
    let s4 = linear::solve(&b4).unwrap();
    let e4 = nodal_error(&mesh4, &s4.u, |x| [0.0, 0.0, -(g / m) * (h * x[2] - 0.5 * x[2] * x[2])]);
    println!("T4 bar: u error {e4:.1e}");
    assert!(e4 > 1e-6, "{e4:e}");
}

#[test]
fn a_traction_is_carried_by_the_supports() {
    // A uniform shear traction τ on the top of a block held at its base:
    // Σ R = −τ A in each component (global equilibrium, to round-off).
    for order in [Order::T4, Order::T10] {
        let mesh = graded([1.0, 0.5, 0.5], order);
        let fixed = Support {
            faces: "z_min".into(),
            fix: [Some(0.0); 3],
        };
        let t = [0.01, -0.02, 0.005];
        let loads = vec![FaceLoad::Traction {
            faces: "z_max".into(),
            t,
        }];
        let b = body(&mesh, 0.3, vec![fixed], loads, [0.0; 3]);
        let s = linear::solve(&b).unwrap();
        for (c, tc) in t.iter().enumerate() {
            let want = -tc * 0.5;
            assert!((reaction(&s.reactions, c) - want).abs() < 1e-12 * 0.01, "{order:?} {c}");
        }
    }
}

#[test]
fn supports_that_leave_a_rigid_motion_free_are_refused() {
    let mesh = graded([1.0, 1.0, 1.0], Order::T4);
    let b = body(&mesh, 0.3, vec![Support::roller("z_min", 2)], top_pressure(), [0.0; 3]);
    match linear::solve(&b) {
        Err(CoreError::Invalid {
            kind: InvalidKind::NoSupport,
            reason,
            ..
        }) => {
            // Rollers on the base leave x, y and the turn about z free.
            assert!(
                reason.contains("translation along x") && reason.contains("rotation about z"),
                "{reason}"
            );
        }
        other => panic!("expected no_support, got {:?}", other.map(|s| s.dofs.n_free)),
    }
    let b = body(&mesh, 0.3, vec![Support::roller("bottom", 2)], top_pressure(), [0.0; 3]);
    assert!(matches!(
        linear::solve(&b),
        Err(CoreError::Invalid {
            kind: InvalidKind::Mesh,
            ..
        })
    ));
}
