//! The free rigid motions of a contact problem and their compatibility check.
//!
//! Two kinds of motion are held only by contact: the load-controlled components
//! of a rigid punch, and the rigid modes a body's supports leave free
//! (`fem::rigid_modes`). Both enter the rows as −C β and bring an equilibrium
//! equation Cᵀλ = −P (P their loads), so they are one block of the mixed LCP.
//!
//! Before solving, the block is reduced to the motions contact can resist:
//! a motion (or combination) that moves no candidate along its normal is
//! undetermined — harmless if its load is zero (it is reported as such and set
//! to 0), `incompatible_loads` otherwise. The rest must pass Fichera's LP test
//! (`fichera::check`): some λ ≥ 0 on the candidates balances the loads.
//!
//! The files by job: `build`, the motions, their columns and the null space
//! that leaves the block the motions contact determines; `refusal`, the
//! refusal of loads contact cannot carry (Fichera's LP, with the friction
//! cone's rays, and the escape test); `words`, the motions and their loads
//! in the request's terms; `columns`, what a body's rigid motion does to a
//! set of rows; `tangential`, the motions with friction (their tangential
//! columns and cones). Here: the block the solvers and the report read.

use faer::Mat;

use crate::scene::{Control, Scene};

mod build;
mod columns;
mod refusal;
mod tangential;
mod words;

pub use columns::{rigid_column, RigidColumn};
pub use words::describe_motion;

pub const COMPONENT: [&str; 3] = crate::scene::COMPONENTS;

/// Fraction of the largest free motion's terms below which a motion's
/// equilibrium residual is judged against this much of the largest instead
/// of its own terms. Round-off of the λ solve is a few ε of the largest
/// terms, so it then reads at most about 1e-12; a motion whose terms are
/// above it keeps its own scale. (At 1e-8 the roller below read 4.1e-9, at
/// E × 1e4 1.1e-8: round-off at the tolerance.)
const FLOOR: f64 = 1e-4;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Component (0: horizontal, 1: vertical, 2: rotation) of a punch.
    Punch { obstacle: usize, component: usize },
    /// Rigid motion `dir` = (ux, uy, rotation about the centre) of the body of
    /// `dofs.rigid[set]`, a combination of its free modes.
    Body { set: usize, dir: [f64; 3] },
}

pub struct FreeMotions {
    /// Every free motion with its (nondimensional) load P.
    pub motions: Vec<(Motion, f64)>,
    /// Basis of the motions contact determines: β = V γ (motions × kept).
    pub v: Mat<f64>,
    /// C V (candidates × kept) and the equilibrium right-hand side −Vᵀ P.
    pub c: Mat<f64>,
    pub rhs: Vec<f64>,
    /// Motions (or combinations) nothing resists and nothing loads: fixed at 0.
    pub undetermined: Vec<Vec<f64>>,
    /// The same, said in words, for rigid motions of bodies.
    pub notes: Vec<crate::outcome::Note>,
    /// Rigid motions of bodies treated as unresisted (held at 0 by the virtual
    /// supports): their columns of C and each candidate's motion with them. A
    /// solution must put no net generalized force on them (`unbalanced`).
    pub unresisted: Vec<(Vec<f64>, Vec<f64>)>,
    /// With friction, the size of each motion's loads, Σ |f_n| |R_k(x_n)|
    /// over a body's nodes (|P| for a punch): a scale of its equilibrium
    /// beside the contact forces (empty without friction).
    pub load_scale: Vec<f64>,
    /// Per rigid set (`dofs.rigid`), each load of its body with its
    /// resultant (Fx, Fy, M about the set's centre): a refusal names the one
    /// doing most work on the motion, a load the request has (`body_force`
    /// alone left `/tractions` pointing at nothing).
    pub body_loads: Vec<Vec<(String, [f64; 3])>>,
}

impl FreeMotions {
    pub fn is_empty(&self) -> bool {
        self.c.ncols() == 0
    }

    /// (C V) γ per candidate: the rows' share of the free motions.
    pub fn shift(&self, gamma: &[f64]) -> Vec<f64> {
        (0..self.c.nrows())
            .map(|i| (0..gamma.len()).map(|j| self.c[(i, j)] * gamma[j]).sum())
            .collect()
    }

    /// β = V γ: the amplitude of every free motion.
    pub fn motion(&self, gamma: &[f64]) -> Vec<f64> {
        (0..self.v.nrows())
            .map(|i| (0..gamma.len()).map(|j| self.v[(i, j)] * gamma[j]).sum())
            .collect()
    }

    /// Relative residual of the free motions' equilibrium for the contact
    /// forces λ, for the certificate: (CV)ᵀλ = −VᵀP on the motions solved for,
    /// and no net force on the motions treated as unresisted (`unbalanced`).
    /// With friction, `friction` holds the friction forces' share C_Tᵀτ of
    /// each kept motion's equilibrium, C_Nᵀλ + C_Tᵀτ = −P, and its largest
    /// term max_k |C_T,kj τ_k|, the scale of that share (empty without).
    pub fn equilibrium(&self, lambda: &[f64], friction: &[(f64, f64)]) -> f64 {
        let worst = self.unbalanced(lambda);
        let mut residuals = Vec::with_capacity(self.c.ncols());
        for j in 0..self.c.ncols() {
            let (mut ct, mut scale) = (0.0, self.rhs[j].abs());
            for (i, l) in lambda.iter().enumerate() {
                ct += self.c[(i, j)] * l;
                scale = scale.max((self.c[(i, j)] * l).abs());
            }
            if let Some(&(fr, largest)) = friction.get(j) {
                ct += fr;
                scale = scale.max(largest);
            }
            residuals.push(((ct - self.rhs[j]).abs(), scale));
        }
        // Each motion's residual against its own terms, but never against
        // less than round-off of the largest motion's: a combination that
        // carries round-off alone (load 1e-27 beside 2.9e-12 on a roller
        // pressed at one node, E in Pa) read 0.12, round-off over round-off,
        // and a right answer was `numerical_error`.
        let floor = FLOOR * residuals.iter().fold(0.0f64, |a, r| a.max(r.1));
        residuals
            .iter()
            .filter(|r| r.1.max(floor) > 0.0)
            .fold(worst, |w, r| w.max(r.0 / r.1.max(floor)))
    }

    /// The largest net contact force on an unresisted motion, relative to the
    /// contact forces acting along it: what the virtual supports would have to
    /// carry (0 at a true solution).
    fn unbalanced(&self, lambda: &[f64]) -> f64 {
        self.unresisted
            .iter()
            .map(|(col, reach)| {
                let net: f64 = col.iter().zip(lambda).map(|(c, l)| c * l).sum();
                let scale: f64 = reach.iter().zip(lambda).map(|(r, l)| r * l.abs()).sum();
                if net == 0.0 {
                    0.0
                } else {
                    net.abs() / scale.max(f64::MIN_POSITIVE)
                }
            })
            .fold(0.0, f64::max)
    }

    /// Whether motion `k` is fully determined by contact.
    pub fn is_determined(&self, k: usize) -> bool {
        self.undetermined.iter().all(|u| u[k].abs() <= 1e-12)
    }
}

/// Prescribed or solved amplitude of every punch component: (α1, α2, θ).
pub fn punch_motion(scene: &Scene, fm: &FreeMotions, beta: &[f64], obstacle: usize) -> [f64; 3] {
    let mut motion = [0.0; 3];
    if let Some(pu) = &scene.obstacles[obstacle].punch {
        for (k, ctl) in pu.controls.iter().enumerate() {
            if let Control::Displacement(v) = ctl {
                motion[k] = *v;
            }
        }
    }
    for (j, (mo, _)) in fm.motions.iter().enumerate() {
        if let Motion::Punch { obstacle: o, component } = *mo {
            if o == obstacle {
                motion[component] = beta.get(j).copied().unwrap_or(0.0);
            }
        }
    }
    motion
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(rhs: Vec<f64>, unresisted: Vec<(Vec<f64>, Vec<f64>)>) -> FreeMotions {
        let c = [[1.0, 0.0], [0.5, 1.0], [0.0, 2.0]];
        FreeMotions {
            motions: Vec::new(),
            v: Mat::from_fn(2, 2, |i, j| f64::from(u8::from(i == j))),
            c: Mat::from_fn(3, 2, |i, j| c[i][j]),
            rhs,
            undetermined: Vec::new(),
            notes: Vec::new(),
            unresisted,
            load_scale: Vec::new(),
            body_loads: Vec::new(),
        }
    }

    /// The free motions' equilibrium for the certificate is the relative
    /// residual of Cᵀλ = rhs: zero to round-off (ε of the terms, 1e-15) at
    /// forces that balance the loads (Cᵀλ = (2, 3) for λ = (1, 2, 0.5)), the
    /// imbalance over the motion's largest term otherwise (0.2 / 2.2), closed
    /// again by a friction share C_Tᵀτ of 0.2; and on a motion treated as
    /// unresisted the net contact force over the forces along it (|1 − 2| /
    /// 3.5 at λ = (1, 2, 0.5), 0 where they cancel).
    #[test]
    fn the_equilibrium_residual_is_the_imbalance_over_its_terms() {
        let lambda = [1.0, 2.0, 0.5];
        assert!(block(vec![2.0, 3.0], Vec::new()).equilibrium(&lambda, &[]) <= 1e-15);
        let off = block(vec![2.2, 3.0], Vec::new());
        assert!((off.equilibrium(&lambda, &[]) - 0.2 / 2.2).abs() <= 1e-15);
        assert!(off.equilibrium(&lambda, &[(0.2, 0.2), (0.0, 0.0)]) <= 1e-15);
        let free = vec![(vec![1.0, -1.0, 0.0], vec![1.0, 1.0, 1.0])];
        let held = block(vec![2.0, 3.0], free.clone());
        assert!((held.equilibrium(&lambda, &[]) - 1.0 / 3.5).abs() <= 1e-15);
        let balanced = [1.0, 1.0, 0.5];
        let rhs = vec![1.5, 2.0];
        assert!(block(rhs, free).equilibrium(&balanced, &[]) <= 1e-15);
        assert!((held.unbalanced(&[2.0, 1.0, 0.0]) - 1.0 / 3.0).abs() <= 1e-15);
    }
}
