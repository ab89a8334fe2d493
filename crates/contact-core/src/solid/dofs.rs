//! Degrees of freedom of a body of tetrahedra: DOF 3·node + c, prescribed on
//! the supports' face sets, and the rigid motions the supports leave free.
//!
//! A rigid motion is u(x) = t + ω × (x − x₀): with d = (x − x₀)/L (L the
//! body's size, so that the six coordinates (t, Lω) weigh alike) component c
//! of node x is the row `mode_row(c, d)` times (t, Lω). The supports leave
//! free the null space of the rows of their DOFs (the Gram matrix's
//! eigenvectors of eigenvalue ≤ 1e-12 of the largest). A body that contact
//! may hold keeps them as free motions β (u = ũ + R β, R's columns the free
//! modes on every DOF), and one virtual support per mode (ũ = 0 there,
//! chosen by pivoted Gram–Schmidt for a well-conditioned R_S, away from the
//! contact nodes when it can) makes K_ff positive definite; a body nothing
//! else holds is refused.

use faer::Mat;

use super::SolidBody;
use crate::error::{CoreError, InvalidKind};
use crate::fem::pattern::FIXED;
use crate::linalg::dense::sym_eigen_small;

/// The numbering of a body's DOFs.
#[derive(Debug, Clone)]
pub struct SolidDofs {
    /// Free index of each DOF (3·node + c), or `FIXED`.
    pub free: Vec<usize>,
    /// Prescribed value of each DOF (0 where free or virtually supported).
    pub prescribed: Vec<f64>,
    /// Held by a support (not by a virtual one).
    pub supported: Vec<bool>,
    pub n_free: usize,
    /// The rigid motions the supports leave free (none: K is definite).
    pub modes: FreeModes,
}

/// Rigid motions left free by the supports, in (t, Lω) coordinates.
#[derive(Debug, Clone, Default)]
pub struct FreeModes {
    pub center: [f64; 3],
    /// L: the body's size.
    pub length: f64,
    /// Orthonormal basis of the free motions.
    pub basis: Vec<[f64; 6]>,
    /// The DOFs held at 0 by a virtual support, one per mode.
    pub virtual_dofs: Vec<usize>,
}

impl FreeModes {
    /// Component c of mode k at point x.
    pub fn at(&self, k: usize, x: [f64; 3], c: usize) -> f64 {
        let d = [0, 1, 2].map(|i| (x[i] - self.center[i]) / self.length);
        let row = mode_row(c, d);
        (0..6).map(|j| row[j] * self.basis[k][j]).sum()
    }

    /// Mode k on every DOF of a mesh with nodes `nodes`.
    pub fn field(&self, k: usize, nodes: &[[f64; 3]]) -> Vec<f64> {
        nodes
            .iter()
            .flat_map(|&x| (0..3).map(move |c| self.at(k, x, c)))
            .collect()
    }

    pub fn len(&self) -> usize {
        self.basis.len()
    }

    pub fn is_empty(&self) -> bool {
        self.basis.is_empty()
    }
}

/// Component c of the six rigid modes (tx, ty, tz, ωx, ωy, ωz) at offset d:
/// (ω × d)_c.
pub fn mode_row(c: usize, d: [f64; 3]) -> [f64; 6] {
    match c {
        0 => [1.0, 0.0, 0.0, 0.0, d[2], -d[1]],
        1 => [0.0, 1.0, 0.0, -d[2], 0.0, d[0]],
        _ => [0.0, 0.0, 1.0, d[1], -d[0], 0.0],
    }
}

/// The DOF map of `body`. `contact` lists the nodes contact may hold the
/// body by (None: no contact, so a rigid motion the supports leave free is
/// refused with `no_support`).
pub fn dof_map(body: &SolidBody, contact: Option<&[usize]>) -> Result<SolidDofs, CoreError> {
    body.check()?;
    let mesh = body.mesh;
    let n = 3 * mesh.nodes.len();
    let mut supported = vec![false; n];
    let mut prescribed = vec![0.0; n];
    for (k, s) in body.supports.iter().enumerate() {
        body.face_set(&s.faces, &format!("supports/{k}/faces"))?;
        for node in mesh.face_set_nodes(&s.faces) {
            for (c, v) in s.fix.iter().enumerate() {
                let Some(v) = *v else { continue };
                let d = 3 * node + c;
                if supported[d] && prescribed[d] != v {
                    return Err(CoreError::invalid(
                        InvalidKind::Request,
                        format!("supports/{k}"),
                        format!(
                            "conflicting prescribed displacements at node {node} (component {})",
                            ["x", "y", "z"][c]
                        ),
                    ));
                }
                supported[d] = true;
                prescribed[d] = v;
            }
        }
    }
    let center = centroid(&mesh.nodes);
    let length = mesh.size();
    let basis = free_modes(&mesh.nodes, center, length, &supported);
    let mut modes = FreeModes {
        center,
        length,
        basis,
        virtual_dofs: Vec::new(),
    };
    if !modes.is_empty() {
        let Some(contact) = contact else {
            let list: Vec<String> = modes.basis.iter().map(describe).collect();
            return Err(CoreError::invalid(
                InvalidKind::NoSupport,
                "supports",
                format!(
                    "the supports leave the rigid motion(s) {} free and no contact holds the body",
                    list.join(" and ")
                ),
            ));
        };
        let in_contact: std::collections::HashSet<usize> = contact.iter().copied().collect();
        let away = virtual_supports(&mesh.nodes, &modes, |d| supported[d] || in_contact.contains(&(d / 3)));
        modes.virtual_dofs = if away.len() == modes.len() {
            away
        } else {
            virtual_supports(&mesh.nodes, &modes, |d| supported[d])
        };
    }
    let mut free = vec![FIXED; n];
    let mut n_free = 0;
    for d in 0..n {
        if !supported[d] && !modes.virtual_dofs.contains(&d) {
            free[d] = n_free;
            n_free += 1;
        }
    }
    Ok(SolidDofs {
        free,
        prescribed,
        supported,
        n_free,
        modes,
    })
}

fn centroid(nodes: &[[f64; 3]]) -> [f64; 3] {
    let s = nodes
        .iter()
        .fold([0.0; 3], |a, p| [a[0] + p[0], a[1] + p[1], a[2] + p[2]]);
    s.map(|v| v / nodes.len() as f64)
}

/// Orthonormal basis of the rigid motions that the supported DOFs leave free.
fn free_modes(nodes: &[[f64; 3]], center: [f64; 3], length: f64, supported: &[bool]) -> Vec<[f64; 6]> {
    let mut g = Mat::<f64>::zeros(6, 6);
    for (d, _) in supported.iter().enumerate().filter(|(_, &s)| s) {
        let x = nodes[d / 3];
        let row = mode_row(d % 3, [0, 1, 2].map(|i| (x[i] - center[i]) / length));
        for i in 0..6 {
            for j in 0..6 {
                g[(i, j)] += row[i] * row[j];
            }
        }
    }
    let (vals, vecs) = sym_eigen_small(&g);
    // Offsets are O(1) in units of L, so the Gram matrix is well scaled.
    let scale = vals[5].max(1.0);
    (0..6)
        .filter(|&k| vals[k] <= 1e-12 * scale)
        .map(|k| {
            let b: [f64; 6] = std::array::from_fn(|i| vecs[(i, k)]);
            // Canonical sign and zeros, so that messages are stable.
            let lead = b
                .iter()
                .copied()
                .fold(0.0f64, |a, v| if v.abs() > a.abs() { v } else { a });
            b.map(|v| {
                if (v * lead.signum()).abs() < 1e-14 {
                    0.0
                } else {
                    v * lead.signum()
                }
            })
        })
        .collect()
}

/// "translation along z", "rotation about y" or the combination's coordinates
/// (for a canonical `b`: a unit vector's other entries exactly 0).
pub fn describe(b: &[f64; 6]) -> String {
    let names = ["translation along x", "translation along y", "translation along z"];
    let turns = ["rotation about x", "rotation about y", "rotation about z"];
    let unit = |k: usize| {
        (0..6).all(|j| {
            if j == k {
                (b[j].abs() - 1.0).abs() < 1e-12
            } else {
                b[j] == 0.0
            }
        })
    };
    match (0..6).find(|&k| unit(k)) {
        Some(k) if k < 3 => names[k].to_string(),
        Some(k) => turns[k - 3].to_string(),
        None => format!("(t, Lω) ∝ {b:.3?}"),
    }
}

/// One DOF per free mode, so that the modes restricted to them are as well
/// conditioned as possible: greedy pivoted Gram–Schmidt over the DOFs that
/// `excluded` does not rule out.
fn virtual_supports(nodes: &[[f64; 3]], modes: &FreeModes, excluded: impl Fn(usize) -> bool) -> Vec<usize> {
    let r = modes.len();
    let mut chosen: Vec<usize> = Vec::with_capacity(r);
    let mut dirs: Vec<Vec<f64>> = Vec::with_capacity(r);
    for _ in 0..r {
        let mut best: Option<(usize, Vec<f64>, f64)> = None;
        for d in (0..3 * nodes.len()).filter(|&d| !excluded(d) && !chosen.contains(&d)) {
            let mut v: Vec<f64> = (0..r).map(|k| modes.at(k, nodes[d / 3], d % 3)).collect();
            for dir in &dirs {
                let dot: f64 = v.iter().zip(dir).map(|(a, b)| a * b).sum();
                v.iter_mut().zip(dir).for_each(|(a, b)| *a -= dot * b);
            }
            let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
            if best.as_ref().is_none_or(|b| norm > b.2) {
                best = Some((d, v, norm));
            }
        }
        let Some((d, v, norm)) = best else { break };
        if norm <= 1e-8 {
            break;
        }
        chosen.push(d);
        dirs.push(v.into_iter().map(|a| a / norm).collect());
    }
    chosen
}
