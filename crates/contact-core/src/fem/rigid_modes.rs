//! Rigid motions a body's supports leave free, and the virtual supports that
//! take them out of the stiffness matrix.
//!
//! A body held (partly) by contact alone has a singular K: K R = 0 for its
//! free rigid modes R. Fixing as many well-placed DOFs S as there are free
//! modes (R_S nonsingular) makes the rest of K positive definite, and every
//! displacement splits as u = ũ + R β with ũ_S = 0. Since K R = 0 the energy
//! is ½ ũᵀK̃ũ − fᵀũ − (Rᵀf)ᵀβ and the contact rows read B ũ + (B R) β ≤ g:
//! the modes are free rigid motions exactly like a load-controlled punch (see
//! `contact::free_motions`), with loads P = Rᵀf and their equilibrium
//! (B R)ᵀλ = Rᵀf. At the solution the virtual supports carry no force.

use faer::Mat;

use crate::linalg::dense::sym_eigen_small;

/// The free rigid modes of one body: mode k moves point x by
/// (b0 − b2 (y − c_y), b1 + b2 (x − c_x)) with b = basis[k].
#[derive(Debug, Clone, PartialEq)]
pub struct RigidModes {
    pub body: usize,
    pub center: [f64; 2],
    pub basis: Vec<[f64; 3]>,
    /// Global DOFs fixed to zero in K̃ (one per mode; none for a coupling's
    /// modes, whose coupled nodes are real supports, `fem::coupling`).
    pub virtual_dofs: Vec<usize>,
}

impl RigidModes {
    /// Displacement of point x under unit amplitude of mode k.
    pub fn at(&self, k: usize, x: [f64; 2]) -> [f64; 2] {
        self.at_dir(self.basis[k], x)
    }

    /// Displacement of point x under the rigid motion `dir` = (ux, uy, rotation about the centre).
    pub fn at_dir(&self, dir: [f64; 3], x: [f64; 2]) -> [f64; 2] {
        let (dx, dy) = (x[0] - self.center[0], x[1] - self.center[1]);
        [dir[0] - dir[2] * dy, dir[1] + dir[2] * dx]
    }

    /// Words for the rigid motion `dir`, lengths times `length` (the caller's units).
    pub fn describe(&self, dir: [f64; 3], length: f64) -> String {
        describe(dir, self.center, length)
    }
}

/// What a rigid motion (ux, uy, rotation) is, components below 1e-9 of the
/// translation counting as round-off, with its amplitude per unit of the
/// quantity that names it: the signed ux or uy of an axis translation, the
/// length of any other, θ of a rotation (so that a load's work divided by it
/// is F_x, F_y, the force along the motion or the moment about its centre).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    X(f64),
    Y(f64),
    Along(f64),
    Rotation(f64),
}

pub fn kind(b: [f64; 3]) -> Kind {
    let t = b[0].hypot(b[1]);
    if b[2].abs() > 1e-9 * t {
        Kind::Rotation(b[2])
    } else if b[1].abs() <= 1e-9 * t {
        Kind::X(b[0])
    } else if b[0].abs() <= 1e-9 * t {
        Kind::Y(b[1])
    } else {
        Kind::Along(t)
    }
}

/// Words for the rigid motion (ux, uy, rotation about `center`): a translation
/// and its direction, or a rotation and the point it turns about.
pub fn describe(b: [f64; 3], center: [f64; 2], length: f64) -> String {
    let t = b[0].hypot(b[1]);
    if !matches!(kind(b), Kind::Rotation(_)) {
        match kind(b) {
            Kind::X(_) => "translation in x".into(),
            Kind::Y(_) => "translation in y".into(),
            _ => format!("translation along ({:.3}, {:.3})", b[0] / t, b[1] / t),
        }
    } else {
        // The fixed point of u(x) = (b0 − θ (y − c_y), b1 + θ (x − c_x)).
        let (px, py) = ((center[0] - b[1] / b[2]) * length, (center[1] + b[0] / b[2]) * length);
        let size = px.abs().max(py.abs());
        let short = |v: f64| {
            if v.abs() <= 1e-9 * size {
                "0".to_string()
            } else {
                crate::scene::scaling::shown(v)
            }
        };
        format!("rotation about ({}, {})", short(px), short(py))
    }
}

/// Row of the rigid-mode matrix for DOF c of a node at offset (dx, dy) from the centre.
pub fn mode_row(c: usize, dx: f64, dy: f64) -> [f64; 3] {
    if c == 0 {
        [1.0, 0.0, -dy]
    } else {
        [0.0, 1.0, dx]
    }
}

/// Orthonormal basis (in (tx, ty, θ) coordinates) of the rigid motions that the
/// constrained DOFs (`rows`, from `mode_row`) leave free.
pub fn free_modes(rows: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let g = Mat::<f64>::from_fn(3, 3, |i, j| rows.iter().map(|r| r[i] * r[j]).sum());
    let (vals, vecs) = sym_eigen_small(&g);
    // Lengths are O(1) after scaling, so the Gram matrix is well scaled; a mode
    // is free when the supports barely resist it.
    let scale = vals[2].max(1.0);
    (0..3)
        .filter(|&k| vals[k] <= 1e-12 * scale)
        .map(|k| {
            let mut b = [vecs[(0, k)], vecs[(1, k)], vecs[(2, k)]];
            // Canonical sign and zeros, so that messages and cache keys are stable.
            let lead = b
                .iter()
                .copied()
                .fold(0.0f64, |a, v| if v.abs() > a.abs() { v } else { a });
            for v in &mut b {
                *v *= lead.signum();
                if v.abs() < 1e-14 {
                    *v = 0.0;
                }
            }
            b
        })
        .collect()
}

/// Picks one (node, component) per free mode so that the modes restricted to
/// them are as well conditioned as possible: greedy pivoted Gram–Schmidt over
/// the rows R_d N of the unconstrained DOFs.
pub fn virtual_supports(
    nodes: &[[f64; 2]],
    center: [f64; 2],
    basis: &[[f64; 3]],
    is_fixed: impl Fn(usize, usize) -> bool,
) -> Vec<(usize, usize)> {
    let r = basis.len();
    let mut chosen: Vec<(usize, usize)> = Vec::with_capacity(r);
    let mut dirs: Vec<Vec<f64>> = Vec::with_capacity(r);
    for _ in 0..r {
        let mut best: Option<((usize, usize), Vec<f64>, f64)> = None;
        for (n, p) in nodes.iter().enumerate() {
            for c in 0..2 {
                if is_fixed(n, c) || chosen.contains(&(n, c)) {
                    continue;
                }
                let row = mode_row(c, p[0] - center[0], p[1] - center[1]);
                let mut v: Vec<f64> = basis
                    .iter()
                    .map(|b| row[0] * b[0] + row[1] * b[1] + row[2] * b[2])
                    .collect();
                for d in &dirs {
                    let dot: f64 = v.iter().zip(d).map(|(a, b)| a * b).sum();
                    v.iter_mut().zip(d).for_each(|(a, b)| *a -= dot * b);
                }
                let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
                if best.as_ref().is_none_or(|b| norm > b.2) {
                    best = Some(((n, c), v, norm));
                }
            }
        }
        let Some((dof, v, norm)) = best else { break };
        chosen.push(dof);
        dirs.push(v.into_iter().map(|a| a / norm).collect());
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horizontal_line_of_vertical_supports_leaves_the_x_translation() {
        let rows: Vec<[f64; 3]> = (0..5).map(|i| mode_row(1, i as f64 - 2.0, -0.5)).collect();
        let free = free_modes(&rows);
        assert_eq!(free, vec![[1.0, 0.0, 0.0]]);
    }

    #[test]
    fn no_supports_leave_three_modes_and_three_independent_virtual_supports() {
        let free = free_modes(&[]);
        assert_eq!(free.len(), 3);
        let nodes: Vec<[f64; 2]> = (0..9).map(|i| [(i % 3) as f64, (i / 3) as f64]).collect();
        let s = virtual_supports(&nodes, [1.0, 1.0], &free, |_, _| false);
        assert_eq!(s.len(), 3);
        // R_S nonsingular: its determinant is well away from zero.
        let m: Vec<Vec<f64>> = s
            .iter()
            .map(|&(n, c)| {
                let row = mode_row(c, nodes[n][0] - 1.0, nodes[n][1] - 1.0);
                free.iter()
                    .map(|b| row[0] * b[0] + row[1] * b[1] + row[2] * b[2])
                    .collect()
            })
            .collect();
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        assert!(det.abs() > 0.5, "det = {det}");
    }
}
