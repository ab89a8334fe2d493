//! A measurement for issue 40's 300k-DOF T10 target, not a solver of the
//! product: the linear system of a graded T10 box (the unit cube under a
//! uniform pressure on a roller base, rollers on its sides, as
//! `solid3d_timing` builds it) solved by conjugate gradients preconditioned
//! by a two-level p-multigrid cycle, against the supernodal Cholesky in the
//! nested-dissection order the 3D solves use.
//!
//! The cycle: a Chebyshev smoother of degree `DEGREE` on D⁻¹K (D the
//! diagonal), the residual restricted to the T4 box on the same vertices
//! (P interpolates the linear tetrahedra's functions at the T10 nodes:
//! identity at a vertex, the mean of its edge's two vertices at a midside
//! node; on straight tetrahedra P1 ⊂ P2, so Pᵀ K P is the T4 stiffness
//! exactly, which is assembled and factored directly), and the same
//! smoother after it, so the cycle is symmetric and CG applies. Prints, per
//! size, the setup and the iterations and seconds to a relative residual of
//! 1e-10, and the direct solve's seconds where it fits in memory.
//!
//! `cargo run --release -p contact-core --example solid_pcg [-- n ...]` (cells a side, default 11 16 22).

use contact_core::fem::pattern::FIXED;
use contact_core::linalg::cholesky::{Cholesky, SymbolicFactor};
use contact_core::linalg::sparse::sym_lower_matvec;
use contact_core::mesh::generate::{graded_points, Grading};
use contact_core::mesh3d::generate::{grid, uniform};
use contact_core::mesh3d::{Mesh3d, Order, EDGES};
use contact_core::solid::dofs::{dof_map, SolidDofs};
use contact_core::solid::{loads, ordering, stiffness, FaceLoad, SolidBody, Support};
use std::sync::Arc;
use std::time::Instant;

const DEGREE: usize = 3;
const TOL: f64 = 1e-10;

fn lines(n: usize) -> [Vec<f64>; 3] {
    let h = 1.0 / n as f64;
    let g = Grading {
        h_min: 0.25 * h,
        ratio: 1.3,
        extent: h,
    };
    [
        uniform(0.0, 1.0, n),
        uniform(0.0, 1.0, n),
        graded_points(0.0, 1.0, 0.0, g, h),
    ]
}

fn body(mesh: &Mesh3d) -> SolidBody<'_> {
    SolidBody {
        mesh,
        youngs_modulus: 1.0,
        poisson_ratio: 0.3,
        supports: vec![
            Support::roller("x_min", 0),
            Support::roller("x_max", 0),
            Support::roller("y_min", 1),
            Support::roller("y_max", 1),
            Support::roller("z_min", 2),
        ],
        loads: vec![FaceLoad::Pressure {
            faces: "z_max".into(),
            p: 1e-3,
        }],
        body_force: [0.0; 3],
    }
}

/// P as (coarse free index, weight) lists per fine free DOF.
fn prolongation(fine: &Mesh3d, fd: &SolidDofs, cd: &SolidDofs, n_vertices: usize) -> Vec<Vec<(usize, f64)>> {
    let mut ends = vec![[usize::MAX; 2]; fine.nodes.len()];
    for e in 0..fine.n_elems() {
        let el = fine.elem(e);
        for (k, &[i, j]) in EDGES.iter().enumerate() {
            ends[el[4 + k]] = [el[i], el[j]];
        }
    }
    let mut p = vec![Vec::new(); fd.n_free];
    for (node, edge) in ends.iter().enumerate() {
        for c in 0..3 {
            let i = fd.free[3 * node + c];
            if i == FIXED {
                continue;
            }
            let coarse = |v: usize| cd.free[3 * v + c];
            if node < n_vertices {
                if coarse(node) != FIXED {
                    p[i].push((coarse(node), 1.0));
                }
            } else {
                for &v in edge {
                    if coarse(v) != FIXED {
                        p[i].push((coarse(v), 0.5));
                    }
                }
            }
        }
    }
    p
}

struct Cycle<'a> {
    k: &'a faer::sparse::SparseColMat<usize, f64>,
    inv_diag: Vec<f64>,
    lmax: f64,
    p: Vec<Vec<(usize, f64)>>,
    coarse: Cholesky,
    n_coarse: usize,
}

fn diag(k: &faer::sparse::SparseColMat<usize, f64>) -> Vec<f64> {
    let sym = k.symbolic();
    let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), k.val());
    (0..k.ncols())
        .map(|j| (cp[j]..cp[j + 1]).find(|&q| ri[q] == j).map(|q| v[q]).unwrap())
        .collect()
}

impl Cycle<'_> {
    /// x ← x + the Chebyshev polynomial of D⁻¹K on [lmax/10, 1.1 lmax]
    /// applied to r − K x (Saad, Iterative Methods §12.3).
    fn smooth(&self, r: &[f64], x: &mut [f64]) {
        let (a, b) = (self.lmax / 10.0, 1.1 * self.lmax);
        let (theta, delta) = ((b + a) / 2.0, (b - a) / 2.0);
        let sigma = theta / delta;
        let mut rho = 1.0 / sigma;
        let kx = sym_lower_matvec(self.k, x);
        let mut res: Vec<f64> = r.iter().zip(&kx).map(|(a, b)| a - b).collect();
        let mut d: Vec<f64> = res.iter().zip(&self.inv_diag).map(|(r, w)| r * w / theta).collect();
        for it in 0..DEGREE {
            for (xi, di) in x.iter_mut().zip(&d) {
                *xi += di;
            }
            if it + 1 == DEGREE {
                break;
            }
            let kd = sym_lower_matvec(self.k, &d);
            for (ri, kdi) in res.iter_mut().zip(&kd) {
                *ri -= kdi;
            }
            let rho_new = 1.0 / (2.0 * sigma - rho);
            for ((di, ri), w) in d.iter_mut().zip(&res).zip(&self.inv_diag) {
                *di = rho_new * rho * *di + 2.0 * rho_new / delta * ri * w;
            }
            rho = rho_new;
        }
    }

    fn apply(&self, r: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; r.len()];
        self.smooth(r, &mut x);
        let kx = sym_lower_matvec(self.k, &x);
        let mut rc = vec![0.0; self.n_coarse];
        for (i, row) in self.p.iter().enumerate() {
            let ri = r[i] - kx[i];
            for &(c, w) in row {
                rc[c] += w * ri;
            }
        }
        let ec = self.coarse.solve(&rc);
        for (xi, row) in x.iter_mut().zip(&self.p) {
            *xi += row.iter().map(|&(c, w)| w * ec[c]).sum::<f64>();
        }
        self.smooth(r, &mut x);
        x
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![11, 16, 22] } else { sizes };
    println!(
        "| cells | DOF | coarse DOF | setup [s] | iterations | PCG [s] | s per iteration | direct [s] | \
         |u_pcg − u_direct| / |u| |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for n in sizes {
        let l = lines(n);
        let t0 = Instant::now();
        let coarse_mesh = grid(&l, Order::T4);
        let fine_mesh = grid(&l, Order::T10);
        let (fb, cb) = (body(&fine_mesh), body(&coarse_mesh));
        let (fd, cd) = (dof_map(&fb, None).unwrap(), dof_map(&cb, None).unwrap());
        let k = stiffness::assemble(&fb, &fd).unwrap();
        let f = loads::free_rhs(&loads::external(&fb).unwrap(), &fd, &k);
        let kc = stiffness::assemble(&cb, &cd).unwrap();
        let (fwd, inv) = ordering::nested_dissection(&coarse_mesh, &cd).unwrap();
        let coarse = Cholesky::with_symbolic(
            Arc::new(SymbolicFactor::try_new_ordered(&kc.k, &fwd, &inv).unwrap()),
            &kc.k,
        )
        .unwrap();
        let inv_diag: Vec<f64> = diag(&k.k).iter().map(|d| 1.0 / d).collect();
        // λmax of D⁻¹K by 15 power steps (the smoother's interval is padded by 10 %).
        let mut v: Vec<f64> = (0..fd.n_free).map(|i| 1.0 + (i % 7) as f64).collect();
        let mut lmax = 0.0;
        for _ in 0..15 {
            let kv = sym_lower_matvec(&k.k, &v);
            let w: Vec<f64> = kv.iter().zip(&inv_diag).map(|(a, b)| a * b).collect();
            lmax = dot(&w, &v) / dot(&v, &v);
            let nw = dot(&w, &w).sqrt();
            v = w.iter().map(|x| x / nw).collect();
        }
        let cycle = Cycle {
            k: &k.k,
            inv_diag,
            lmax,
            p: prolongation(&fine_mesh, &fd, &cd, coarse_mesh.nodes.len()),
            coarse,
            n_coarse: cd.n_free,
        };
        let setup = t0.elapsed().as_secs_f64();
        let t1 = Instant::now();
        let mut x = vec![0.0; fd.n_free];
        let mut r = f.clone();
        let mut z = cycle.apply(&r);
        let mut p = z.clone();
        let mut rz = dot(&r, &z);
        let r0 = dot(&r, &r).sqrt();
        let mut its = 0;
        while dot(&r, &r).sqrt() > TOL * r0 && its < 500 {
            let kp = sym_lower_matvec(&k.k, &p);
            let alpha = rz / dot(&p, &kp);
            for i in 0..x.len() {
                x[i] += alpha * p[i];
                r[i] -= alpha * kp[i];
            }
            z = cycle.apply(&r);
            let rz_new = dot(&r, &z);
            for i in 0..p.len() {
                p[i] = z[i] + rz_new / rz * p[i];
            }
            rz = rz_new;
            its += 1;
        }
        let pcg = t1.elapsed().as_secs_f64();
        // The direct solve up to 130k DOF (the 126k T10 ball factored in about 60 s).
        let (direct, diff) = if fd.n_free <= 130_000 {
            let t2 = Instant::now();
            let (fw, iv) = ordering::nested_dissection(&fine_mesh, &fd).unwrap();
            let ch = Cholesky::with_symbolic(Arc::new(SymbolicFactor::try_new_ordered(&k.k, &fw, &iv).unwrap()), &k.k)
                .unwrap();
            let u = ch.solve(&f);
            let secs = t2.elapsed().as_secs_f64();
            let d: f64 = u.iter().zip(&x).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
            (format!("{secs:.2}"), format!("{:.1e}", d / dot(&u, &u).sqrt()))
        } else {
            ("—".into(), "—".into())
        };
        println!(
            "| {n} | {} | {} | {setup:.2} | {its} | {pcg:.2} | {:.3} | {direct} | {diff} |",
            fd.n_free,
            cd.n_free,
            pcg / its.max(1) as f64
        );
    }
}
