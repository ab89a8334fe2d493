//! A trial law through the seam, defined here alone: what a second law
//! needs (`Constitutive<S>` for the three Voigt lengths, wrapped in a `Law`)
//! and two truths the assembly must keep for any law, the patch test and the
//! rigid motions in K's null space. Nothing outside this file knows the law.

use super::{Constitutive, Law};
use crate::fem::assembly::each_element;
use crate::fem::element;
use crate::fem::kernel::Integration;
use crate::mesh::Mesh2d;
use crate::mesh::{generate, Order};
use crate::scene::Analysis;
use std::collections::BTreeMap;

/// A trial law defined here alone, to show the seam: general linear
/// anisotropy, σ = C ε with C held as its 6 × 6 form and a law of S
/// components reading the leading S × S block (as `LinearIsotropic`).
#[derive(Debug)]
struct Anisotropic([[f64; 6]; 6]);

impl<const S: usize> Constitutive<S> for Anisotropic {
    fn stress(&self, e: &[f64; S]) -> [f64; S] {
        std::array::from_fn(|i| (0..S).map(|j| self.0[i][j] * e[j]).sum())
    }
    fn tangent(&self, _: &[f64; S]) -> [[f64; S]; S] {
        std::array::from_fn(|i| std::array::from_fn(|j| self.0[i][j]))
    }
    fn energy(&self, e: &[f64; S]) -> f64 {
        0.5 * self.stress(e).iter().zip(e).map(|(s, e)| s * e).sum::<f64>()
    }
    fn volumetric_lambda(&self) -> f64 {
        // The full rule alone runs here; the P2–P0 split is isotropy's.
        0.0
    }
}

/// An orthotropic plane law (stiffer along x, Poisson coupling, its own
/// shear modulus), symmetric positive definite, with a hoop row for the
/// ring: nothing an isotropic law could give.
fn trial() -> Law {
    let mut c = [[0.0; 6]; 6];
    c[0][..4].copy_from_slice(&[310.0, 42.0, 0.0, 35.0]);
    c[1][..4].copy_from_slice(&[42.0, 95.0, 0.0, 30.0]);
    c[2][2] = 27.0;
    c[3][..4].copy_from_slice(&[35.0, 30.0, 0.0, 120.0]);
    Law::new(Anisotropic(c))
}

/// A patch of 8 T3 on [0, 2]², its middle node moved off the grid so no
/// element is a right isosceles triangle.
fn patch(order: Order) -> Mesh2d {
    let mut nodes = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            nodes.push([i as f64, j as f64]);
        }
    }
    nodes[4] = [1.13, 0.91];
    let mut elems = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            let (a, b) = (3 * j + i, 3 * j + i + 1);
            let (c, d) = (a + 3, b + 3);
            elems.extend_from_slice(&[a, b, d, a, d, c]);
        }
    }
    let t3 = Mesh2d {
        order: Order::T3,
        nodes,
        elems,
        edge_sets: BTreeMap::new(),
    };
    match order {
        Order::T3 => t3,
        Order::T6 => generate::to_t6(t3),
    }
}

/// The dense K of every DOF (2 node + c) of `mesh` for `law`.
fn dense(mesh: &Mesh2d, analysis: Analysis, law: &Law) -> Vec<Vec<f64>> {
    let n = 2 * mesh.nodes.len();
    let mut k = vec![vec![0.0; n]; n];
    each_element(mesh, analysis, law, Integration::Full, 0..mesh.n_elems(), |conn, ke| {
        let nd = 2 * conn.len();
        let dof = |a: usize| 2 * conn[a / 2] + a % 2;
        for a in 0..nd {
            for b in 0..nd {
                k[dof(a)][dof(b)] += ke[a * nd + b];
            }
        }
    });
    k
}

/// Solves the small dense system a x = b by Gaussian elimination with
/// partial pivoting.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for p in 0..n {
        let r = (p..n).max_by(|&i, &j| a[i][p].abs().total_cmp(&a[j][p].abs())).unwrap();
        a.swap(p, r);
        b.swap(p, r);
        for i in p + 1..n {
            let f = a[i][p] / a[p][p];
            let (top, rest) = a.split_at_mut(i);
            for (x, y) in rest[0][p..].iter_mut().zip(&top[p][p..]) {
                *x -= f * y;
            }
            b[i] -= f * b[p];
        }
    }
    let mut x = vec![0.0; n];
    for p in (0..n).rev() {
        let s: f64 = (p + 1..n).map(|j| a[p][j] * x[j]).sum();
        x[p] = (b[p] - s) / a[p][p];
    }
    x
}

/// The patch test (Irons) through the seam and the assembly, for a law
/// defined in this test alone: with the boundary nodes moved as the
/// uniform strain ε₀ = (εxx, εyy, γxy) prescribes, the interior nodes
/// solve to the same linear field, every element's recovered stress is
/// the law's σ(ε₀) and the strain energy ½ uᵀ K u is W(ε₀) A; on T3 and
/// on T6 (whose midside nodes inside the patch are free). Tolerance 1e-12
/// relative: the 10 to 26 unknowns' dense solve on a patch of aspect
/// ratio below 3 loses a few digits to round-off alone.
#[test]
fn a_trial_law_passes_the_patch_test() {
    let law = trial();
    let eps = [2e-3, -7e-4, 1.1e-3];
    let field = |p: [f64; 2]| [eps[0] * p[0] + 0.5 * eps[2] * p[1], 0.5 * eps[2] * p[0] + eps[1] * p[1]];
    let sigma = Constitutive::<3>::stress(&law, &eps);
    for order in [Order::T3, Order::T6] {
        let mesh = patch(order);
        let k = dense(&mesh, Analysis::PlaneStrain, &law);
        let on_boundary = |p: [f64; 2]| p.iter().any(|&v| v == 0.0 || v == 2.0);
        let free: Vec<usize> = (0..2 * mesh.nodes.len())
            .filter(|&d| !on_boundary(mesh.nodes[d / 2]))
            .collect();
        let mut u: Vec<f64> = mesh.nodes.iter().flat_map(|&p| field(p)).collect();
        for &d in &free {
            u[d] = 0.0;
        }
        let a: Vec<Vec<f64>> = free.iter().map(|&r| free.iter().map(|&c| k[r][c]).collect()).collect();
        let b: Vec<f64> = free
            .iter()
            .map(|&r| -(0..u.len()).map(|c| k[r][c] * u[c]).sum::<f64>())
            .collect();
        for (&d, v) in free.iter().zip(solve(a, b)) {
            u[d] = v;
        }
        let scale = 2.0 * eps.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
        for (node, &p) in mesh.nodes.iter().enumerate() {
            let want = field(p);
            for c in 0..2 {
                let err = (u[2 * node + c] - want[c]).abs();
                assert!(err <= 1e-12 * scale, "{order:?} node {node}: {err:e}");
            }
        }
        let peak = sigma.iter().fold(0.0_f64, |m, s| m.max(s.abs()));
        for e in 0..mesh.n_elems() {
            let conn = mesh.elem(e);
            let x: Vec<[f64; 2]> = conn.iter().map(|&n| mesh.nodes[n]).collect();
            let ue: Vec<f64> = conn.iter().flat_map(|&n| [u[2 * n], u[2 * n + 1]]).collect();
            let s = element::centroid_stress(order, &x, &law, &ue);
            for (s, want) in s.iter().zip(&sigma) {
                assert!((s - want).abs() <= 1e-12 * peak, "{order:?} element {e}: {s} vs {want}");
            }
        }
        let energy: f64 = 0.5
            * (0..u.len())
                .map(|a| u[a] * (0..u.len()).map(|b| k[a][b] * u[b]).sum::<f64>())
                .sum::<f64>();
        let want = Constitutive::<3>::energy(&law, &eps) * 4.0;
        assert!((energy / want - 1.0).abs() <= 1e-12, "{order:?}: {energy} vs {want}");
    }
}

/// The rigid motions are K's null space, through the seam and the
/// assembly for the trial law: the plane's two translations and its
/// rotation, the ring's axial translation (u_z = 1; a radial motion
/// strains the hoops). |K r| ≤ 1e-13 |K| |r| (|·| the largest entry):
/// each entry of K r sums at most 12 terms of K, each rounded to 1e-16.
#[test]
fn a_trial_law_keeps_the_rigid_motions_free() {
    let law = trial();
    for order in [Order::T3, Order::T6] {
        let mut mesh = patch(order);
        for p in &mut mesh.nodes {
            p[0] += 0.5; // off the axis, for the ring
        }
        let modes = |analysis: Analysis| -> Vec<Vec<f64>> {
            let each = |f: &dyn Fn([f64; 2]) -> [f64; 2]| mesh.nodes.iter().flat_map(|&p| f(p)).collect();
            match analysis {
                Analysis::Axisymmetric => vec![each(&|_| [0.0, 1.0])],
                _ => vec![each(&|_| [1.0, 0.0]), each(&|_| [0.0, 1.0]), each(&|p| [-p[1], p[0]])],
            }
        };
        for analysis in [Analysis::PlaneStrain, Analysis::Axisymmetric] {
            let k = dense(&mesh, analysis, &law);
            let big = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
            for r in modes(analysis) {
                let rmax = r.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for (row, kr) in k.iter().enumerate() {
                    let v: f64 = kr.iter().zip(&r).map(|(a, b)| a * b).sum();
                    assert!(v.abs() <= 1e-13 * big * rmax, "{order:?} {analysis:?} row {row}: {v:e}");
                }
            }
        }
    }
}
