//! The 3D solid kernels (T4, T10 with the linear isotropic law), checked
//! against truths that need no reference solution:
//!
//! - an element stiffness is symmetric and positive semi-definite, and its
//!   null space is the six rigid motions (K r = 0, and exactly six
//!   eigenvalues at rounding level);
//! - the patch test: on an unstructured mesh of a cube, boundary nodes moved
//!   by a linear field u = A x + c, the interior nodes solve to the same
//!   field and every element's stress is C:ε of it (the elements reproduce
//!   linear fields exactly, so only rounding is left);
//! - a block in uniaxial stress: u_z prescribed on top, symmetry planes, free
//!   lateral faces: the reaction is E ε A and the lateral contraction ν ε.
//!
//! The meshes are Kuhn splits (six tetrahedra around each cell's main
//! diagonal) of a grid, with interior nodes moved off the grid so that no
//! two elements are alike; T10 midsides at the edge midpoints (straight edges,
//! affine elements). The systems are small and dense, solved by Cholesky.

use std::collections::HashMap;

use contact_core::fem::constitutive::{Constitutive, LinearIsotropic, Section};
use contact_core::fem::kernel::{self, Integration, Solid};
use contact_core::fem::reference::tetrahedron::T10_EDGES;
use contact_core::fem::reference::{ReferenceElement, T10, T4};
use contact_core::mesh3d::{Mesh3d, Order};

const LAW: (f64, f64) = (200.0, 0.3);

fn law() -> LinearIsotropic {
    LinearIsotropic::new(LAW.0, LAW.1, Section::Solid)
}

struct Mesh<const N: usize> {
    nodes: Vec<[f64; 3]>,
    elems: Vec<[usize; N]>,
}

fn signed_volume(x: [[f64; 3]; 4]) -> f64 {
    let d = |a: usize| [x[a][0] - x[0][0], x[a][1] - x[0][1], x[a][2] - x[0][2]];
    let (u, v, w) = (d(1), d(2), d(3));
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0
}

/// The Kuhn split of an n³ grid of the box [0, size], interior nodes moved by
/// up to `jitter` of a cell in each direction (a fixed pseudo-random pattern).
fn box_t4(n: usize, size: [f64; 3], jitter: f64) -> Mesh<4> {
    let id = |i: usize, j: usize, k: usize| i + (n + 1) * (j + (n + 1) * k);
    let mut nodes = vec![[0.0; 3]; (n + 1).pow(3)];
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let ijk = [i, j, k];
                let inside = ijk.iter().all(|&a| a > 0 && a < n);
                nodes[id(i, j, k)] = std::array::from_fn(|c| {
                    let h = size[c] / n as f64;
                    let s = ((id(i, j, k) * 3 + c) as f64 * 12.9898).sin() * 43_758.545_3;
                    let wobble = if inside {
                        jitter * h * (s - s.floor() - 0.5)
                    } else {
                        0.0
                    };
                    ijk[c] as f64 * h + wobble
                });
            }
        }
    }
    let mut elems = Vec::new();
    let unit = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                for p in [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]] {
                    let mut at = [i, j, k];
                    let mut tet = [id(i, j, k), 0, 0, 0];
                    for (s, &axis) in p.iter().enumerate() {
                        at = std::array::from_fn(|c| at[c] + unit[axis][c]);
                        tet[s + 1] = id(at[0], at[1], at[2]);
                    }
                    if signed_volume(tet.map(|a| nodes[a])) < 0.0 {
                        tet.swap(1, 2);
                    }
                    elems.push(tet);
                }
            }
        }
    }
    Mesh { nodes, elems }
}

/// The T10 mesh of a T4 mesh: one node at the midpoint of each edge, shared.
fn quadratic(m: &Mesh<4>) -> Mesh<10> {
    let mut nodes = m.nodes.clone();
    let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
    let elems = m
        .elems
        .iter()
        .map(|t| {
            std::array::from_fn(|i| {
                if i < 4 {
                    return t[i];
                }
                let [a, b] = T10_EDGES[i - 4].map(|c| t[c]);
                *mids.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    nodes.push(std::array::from_fn(|c| 0.5 * (nodes[a][c] + nodes[b][c])));
                    nodes.len() - 1
                })
            })
        })
        .collect();
    Mesh { nodes, elems }
}

fn element_stiffness<E: ReferenceElement<3, N>, const N: usize>(x: &[[f64; 3]; N]) -> Vec<f64> {
    let mut ke = vec![0.0; 9 * N * N];
    kernel::stiffness::<E, Solid, _, 3, N, 6>(x, &law(), Integration::Full, &mut ke);
    ke
}

/// The dense global stiffness (3 DOFs per node, node-major).
fn assemble<E: ReferenceElement<3, N>, const N: usize>(m: &Mesh<N>) -> Vec<f64> {
    let nd = 3 * m.nodes.len();
    let mut k = vec![0.0; nd * nd];
    for e in &m.elems {
        let ke = element_stiffness::<E, N>(&e.map(|a| m.nodes[a]));
        for a in 0..3 * N {
            for b in 0..3 * N {
                k[(3 * e[a / 3] + a % 3) * nd + 3 * e[b / 3] + b % 3] += ke[a * 3 * N + b];
            }
        }
    }
    k
}

/// Solves K u = f with the DOFs of `fixed` prescribed (f = 0 elsewhere):
/// Cholesky of K_ff against −K_fp u_p. Returns u.
fn solve(k: &[f64], fixed: &[Option<f64>]) -> Vec<f64> {
    let nd = fixed.len();
    let free: Vec<usize> = (0..nd).filter(|&d| fixed[d].is_none()).collect();
    let mut u: Vec<f64> = fixed.iter().map(|v| v.unwrap_or(0.0)).collect();
    let nf = free.len();
    let mut l = vec![0.0; nf * nf];
    let mut rhs = vec![0.0; nf];
    for (i, &di) in free.iter().enumerate() {
        for (j, &dj) in free.iter().enumerate() {
            l[i * nf + j] = k[di * nd + dj];
        }
        rhs[i] = -(0..nd)
            .filter(|&d| fixed[d].is_some())
            .map(|d| k[di * nd + d] * u[d])
            .sum::<f64>();
    }
    for j in 0..nf {
        let s: f64 = (0..j).map(|p| l[j * nf + p] * l[j * nf + p]).sum();
        let djj = l[j * nf + j] - s;
        assert!(djj > 0.0, "K_ff is not positive definite at {j}");
        l[j * nf + j] = djj.sqrt();
        for i in j + 1..nf {
            let s: f64 = (0..j).map(|p| l[i * nf + p] * l[j * nf + p]).sum();
            l[i * nf + j] = (l[i * nf + j] - s) / l[j * nf + j];
        }
    }
    for i in 0..nf {
        let s: f64 = (0..i).map(|p| l[i * nf + p] * rhs[p]).sum();
        rhs[i] = (rhs[i] - s) / l[i * nf + i];
    }
    for i in (0..nf).rev() {
        let s: f64 = (i + 1..nf).map(|p| l[p * nf + i] * rhs[p]).sum();
        rhs[i] = (rhs[i] - s) / l[i * nf + i];
    }
    for (i, &d) in free.iter().enumerate() {
        u[d] = rhs[i];
    }
    u
}

/// Eigenvalues of the symmetric n × n matrix `a` (cyclic Jacobi), ascending.
fn eigenvalues(mut a: Vec<f64>, n: usize) -> Vec<f64> {
    let norm2: f64 = a.iter().map(|v| v * v).sum();
    for _ in 0..100 {
        let off: f64 = (0..n * n).filter(|i| i / n != i % n).map(|i| a[i] * a[i]).sum();
        if off < 1e-32 * norm2 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (kp, kq) = (a[k * n + p], a[k * n + q]);
                    a[k * n + p] = c * kp - s * kq;
                    a[k * n + q] = s * kp + c * kq;
                }
                for k in 0..n {
                    let (pk, qk) = (a[p * n + k], a[q * n + k]);
                    a[p * n + k] = c * pk - s * qk;
                    a[q * n + k] = s * pk + c * qk;
                }
            }
        }
    }
    let mut ev: Vec<f64> = (0..n).map(|i| a[i * n + i]).collect();
    ev.sort_by(f64::total_cmp);
    ev
}

/// The six rigid motions at the nodes `x`: translations, then rotations ω × x.
fn rigid_modes(x: &[[f64; 3]]) -> [Vec<f64>; 6] {
    std::array::from_fn(|m| {
        x.iter()
            .flat_map(|p| match m {
                0..=2 => std::array::from_fn(|c| if c == m { 1.0 } else { 0.0 }),
                3 => [0.0, -p[2], p[1]],
                4 => [p[2], 0.0, -p[0]],
                _ => [-p[1], p[0], 0.0],
            })
            .collect()
    })
}

/// Symmetric to 1e-15 of its largest entry, K r = 0 for the rigid modes to
/// 1e-12 of max|K| max|r|, and eigenvalues: six within 1e-12 λ_max of zero,
/// the rest positive. Returns (largest |K r|, λ_7 / λ_max) for the messages.
fn check_element<E: ReferenceElement<3, N>, const N: usize>(x: &[[f64; 3]; N]) -> (f64, f64) {
    let nd = 3 * N;
    let k = element_stiffness::<E, N>(x);
    let kmax = k.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for a in 0..nd {
        for b in 0..a {
            assert!((k[a * nd + b] - k[b * nd + a]).abs() <= 1e-15 * kmax);
        }
    }
    let mut worst = 0.0_f64;
    for r in rigid_modes(x) {
        let rmax = r.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for a in 0..nd {
            let kr: f64 = (0..nd).map(|b| k[a * nd + b] * r[b]).sum();
            worst = worst.max(kr.abs() / (kmax * rmax));
        }
    }
    assert!(worst < 1e-12, "K r = {worst:e} of max|K| max|r|");
    let ev = eigenvalues(k, nd);
    let top = ev[nd - 1];
    assert!(ev[..6].iter().all(|l| l.abs() < 1e-12 * top), "{:?}", &ev[..7]);
    assert!(ev[6] > 1e-6 * top, "a seventh zero eigenvalue: {:?}", &ev[..7]);
    (worst, ev[6] / top)
}

#[test]
fn element_stiffness_is_symmetric_semi_definite_with_the_rigid_null_space() {
    let corners = [[0.1, 0.0, 0.2], [1.3, 0.2, 0.1], [0.3, 1.1, 0.0], [0.4, 0.3, 0.9]];
    assert!(signed_volume(corners) > 0.0);
    let (r4, gap4) = check_element::<T4, 4>(&corners);
    let t10: [[f64; 3]; 10] = std::array::from_fn(|i| {
        if i < 4 {
            corners[i]
        } else {
            let [a, b] = T10_EDGES[i - 4];
            std::array::from_fn(|c| 0.5 * (corners[a][c] + corners[b][c]))
        }
    });
    let (r10, gap10) = check_element::<T10, 10>(&t10);
    eprintln!("T4: |K r| {r4:.1e}, λ7/λmax {gap4:.2e}; T10: |K r| {r10:.1e}, λ7/λmax {gap10:.2e}");
}

/// u = A x + c on the boundary (`on_boundary`) of the mesh, solved inside:
/// returns the largest nodal error over max |u| and the largest stress error
/// at the quadrature points over max |σ|.
fn patch<E: ReferenceElement<3, N>, const N: usize>(m: &Mesh<N>, size: [f64; 3]) -> (f64, f64) {
    let a = [[1e-3, 4e-4, -2e-4], [-3e-4, 2e-3, 5e-4], [6e-4, -1e-4, -1.5e-3]];
    let c = [0.01, -0.02, 0.005];
    let field =
        |p: &[f64; 3]| -> [f64; 3] { std::array::from_fn(|i| c[i] + (0..3).map(|j| a[i][j] * p[j]).sum::<f64>()) };
    let on_boundary = |p: &[f64; 3]| (0..3).any(|i| p[i].abs() < 1e-12 || (p[i] - size[i]).abs() < 1e-12);
    let fixed: Vec<Option<f64>> = m
        .nodes
        .iter()
        .flat_map(|p| {
            let u = field(p);
            let b = on_boundary(p);
            [0, 1, 2].map(|i| b.then_some(u[i]))
        })
        .collect();
    assert!(fixed.iter().any(Option::is_none), "the mesh has interior nodes");
    let u = solve(&assemble::<E, N>(m), &fixed);
    let umax = u.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
    let mut du = 0.0_f64;
    for (i, p) in m.nodes.iter().enumerate() {
        let want = field(p);
        for c in 0..3 {
            du = du.max((u[3 * i + c] - want[c]).abs() / umax);
        }
    }
    let eps = [
        a[0][0],
        a[1][1],
        a[2][2],
        a[1][2] + a[2][1],
        a[0][2] + a[2][0],
        a[0][1] + a[1][0],
    ];
    let law = law();
    let sigma = law.stress(&eps);
    let smax = sigma.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
    let mut ds = 0.0_f64;
    for e in &m.elems {
        let x = e.map(|n| m.nodes[n]);
        let ue = e.map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
        for q in E::RULE {
            let s = law.stress(&kernel::strain::<E, Solid, 3, N, 6>(&x, &q.xi, &ue));
            for i in 0..6 {
                ds = ds.max((s[i] - sigma[i]).abs() / smax);
            }
        }
    }
    (du, ds)
}

type Check<const N: usize> = fn(&Mesh<N>, [f64; 3]) -> (f64, f64);

/// Runs a check returning two relative errors on the T4 mesh of the box
/// [0, size] (3³ cells, interior nodes moved by up to 0.15 of a cell) and on
/// its T10 mesh; prints the errors after `what` and asserts each below `tol`.
fn on_both(size: [f64; 3], what: &str, tol: f64, t4: Check<4>, t10: Check<10>) {
    let m4 = box_t4(3, size, 0.3);
    let e4 = t4(&m4, size);
    let e10 = t10(&quadratic(&m4), size);
    eprintln!(
        "{what}: T4 {:.1e}, {:.1e}; T10 {:.1e}, {:.1e}",
        e4.0, e4.1, e10.0, e10.1
    );
    for v in [e4.0, e4.1, e10.0, e10.1] {
        assert!(v < tol, "{what}: {v:e}");
    }
}

/// To 1e-12 (rounding: measured 5e-16 to 1.3e-13).
#[test]
fn patch_test_reproduces_a_linear_field_exactly() {
    on_both(
        [1.0; 3],
        "patch (nodal u, stress)",
        1e-12,
        patch::<T4, 4>,
        patch::<T10, 10>,
    );
}

/// The block [0, L]³ in uniaxial stress: returns the errors of the reaction
/// on the top over E ε A and of the lateral displacements at x = L, y = L
/// over −ν ε L, both relative.
fn uniaxial<E: ReferenceElement<3, N>, const N: usize>(m: &Mesh<N>, size: [f64; 3]) -> (f64, f64) {
    let (e, nu) = LAW;
    let strain = 1e-3;
    let top = strain * size[2];
    let near = |a: f64, b: f64| (a - b).abs() < 1e-12;
    let fixed: Vec<Option<f64>> = m
        .nodes
        .iter()
        .flat_map(|p| {
            [
                near(p[0], 0.0).then_some(0.0),
                near(p[1], 0.0).then_some(0.0),
                if near(p[2], 0.0) {
                    Some(0.0)
                } else {
                    near(p[2], size[2]).then_some(top)
                },
            ]
        })
        .collect();
    let k = assemble::<E, N>(m);
    let u = solve(&k, &fixed);
    let nd = fixed.len();
    let reaction: f64 = (0..m.nodes.len())
        .filter(|&i| near(m.nodes[i][2], size[2]))
        .map(|i| (0..nd).map(|b| k[(3 * i + 2) * nd + b] * u[b]).sum::<f64>())
        .sum();
    let want = e * strain * size[0] * size[1];
    let mut lateral = 0.0_f64;
    for (i, p) in m.nodes.iter().enumerate() {
        for c in 0..2 {
            if near(p[c], size[c]) {
                let w = -nu * strain * size[c];
                lateral = lateral.max((u[3 * i + c] / w - 1.0).abs());
            }
        }
    }
    ((reaction / want - 1.0).abs(), lateral)
}

/// To 1e-10 (measured 1.1e-14 at most).
#[test]
fn uniaxial_block_has_hookes_reaction_and_contraction() {
    let size = [1.0, 1.5, 2.0];
    on_both(
        size,
        "uniaxial (reaction, contraction)",
        1e-10,
        uniaxial::<T4, 4>,
        uniaxial::<T10, 10>,
    );
}

/// The boundary faces of the box's T4 and T10 meshes (`Mesh3d::boundary_faces`
/// over the elements' local faces) tile its surface: 2 · 3² triangles a side,
/// areas summing to 2(ab + bc + ca) to 1e-14, each normal (the right-hand rule
/// on the face's corners) pointing out of the box, and a T10 face's midsides
/// at its edges' midpoints (straight edges).
#[test]
fn boundary_faces_tile_the_surface_and_point_out() {
    fn check<const N: usize>(m: &Mesh<N>, order: Order, size: [f64; 3]) {
        let mesh = Mesh3d {
            order,
            nodes: m.nodes.clone(),
            elems: m.elems.iter().flatten().copied().collect(),
            face_sets: Default::default(),
        };
        let faces = mesh.boundary_faces();
        assert_eq!(faces.len(), 6 * 2 * 9);
        let centre = size.map(|s| 0.5 * s);
        let mut area = 0.0;
        for (f, face) in faces.iter().enumerate() {
            let nodes = face.nodes().map(|n| m.nodes[n]).collect::<Vec<_>>();
            assert_eq!(nodes.len(), if order == Order::T4 { 3 } else { 6 });
            let d = |a: usize| -> [f64; 3] { std::array::from_fn(|c| nodes[a][c] - nodes[0][c]) };
            let (u, v) = (d(1), d(2));
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let out: f64 = (0..3).map(|c| n[c] * (nodes[0][c] - centre[c])).sum();
            assert!(out > 0.0, "face {f} points in");
            area += 0.5 * n.iter().map(|x| x * x).sum::<f64>().sqrt();
            for (k, mid) in nodes.iter().enumerate().skip(3) {
                let (p, q) = (nodes[k - 3], nodes[(k - 2) % 3]);
                assert!((0..3).all(|c| (mid[c] - 0.5 * (p[c] + q[c])).abs() < 1e-15));
            }
        }
        let [a, b, c] = size;
        let want = 2.0 * (a * b + b * c + c * a);
        assert!((area / want - 1.0).abs() < 1e-14, "{area} vs {want}");
    }
    let size = [1.0, 1.5, 2.0];
    let t4 = box_t4(3, size, 0.3);
    check::<4>(&t4, Order::T4, size);
    check::<10>(&quadratic(&t4), Order::T10, size);
}
