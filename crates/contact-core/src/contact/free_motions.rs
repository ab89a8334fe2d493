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
//! Length: the free motions, their null space and the refusal of loads that
//! contact cannot carry share one set of private fields (the basis V, C, the
//! right-hand side); split into files, each would reach into the others.

use faer::Mat;

use super::{fichera, ConstraintSet, Term};
use crate::error::LoadBound;
use crate::error::{CoreError, InvalidKind};
use crate::fem::loads::{self, Located};
use crate::fem::rigid_modes::{self, Kind, RigidModes};
use crate::fem::DofMap;
use crate::linalg::dense::sym_eigen_small;
use crate::mesh::Mesh2d;
use crate::scene::scaling::shown;
use crate::scene::Control;
use crate::scene::Scene;

pub const COMPONENT: [&str; 3] = ["horizontal", "vertical", "rotation"];

/// Fraction of the largest free motion's terms below which a motion's
/// equilibrium residual is judged against this much of the largest instead
/// of its own terms. Round-off of the λ solve is a few ε of the largest
/// terms, so it then reads at most about 1e-12; a motion whose terms are
/// above it keeps its own scale. (At 1e-8 the roller below read 4.1e-9, at
/// E × 1e4 1.1e-8: round-off at the tolerance.)
const FLOOR: f64 = 1e-4;

/// Relative Gram eigenvalue below which a combination of free motions moves no
/// candidate: a lever of 1e-6 of the motion, far above round-off (ε‖G‖) and far
/// below any real lever (a circular punch's horizontal shift has n_x ≈ x/R).
const NULL_COMBINATION: f64 = 1e-12;

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
    pub notes: Vec<String>,
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

    pub fn try_new(
        scene: &Scene,
        cons: &ConstraintSet,
        dofs: &DofMap,
        meshes: &[Mesh2d],
        points: &[Vec<Located>],
        external: &[f64],
    ) -> Result<Self, CoreError> {
        let (punch_free, c_punch) = cons.punch_block(scene);
        let body_loads: Vec<Vec<(String, [f64; 3])>> = dofs
            .rigid
            .iter()
            .map(|rm| {
                let body = &scene.bodies[rm.body];
                loads::resultants(scene, rm.body, &meshes[rm.body], &points[rm.body], rm.center)
                    .into_iter()
                    .map(|(src, r)| (src.path(body), r))
                    .collect()
            })
            .collect();
        if scene.has_friction() {
            return Ok(Self::frictional(
                &punch_free,
                c_punch,
                cons,
                dofs,
                meshes,
                external,
                body_loads,
            ));
        }
        let m = cons.len();
        let mut motions: Vec<(Motion, f64)> = punch_free
            .iter()
            .map(|&(o, k, load)| {
                (
                    Motion::Punch {
                        obstacle: o,
                        component: k,
                    },
                    load,
                )
            })
            .collect();
        // |work| of each load, the scale against which "zero load" is judged.
        let mut load_scale: Vec<f64> = punch_free.iter().map(|f| f.2.abs()).collect();
        let mut cols: Vec<Vec<f64>> = (0..punch_free.len())
            .map(|j| (0..m).map(|i| c_punch[(i, j)]).collect())
            .collect();
        let mut notes = Vec::new();
        let mut unresisted = Vec::new();
        for (set, rm) in dofs.rigid.iter().enumerate() {
            let resisted = body_directions(scene, cons, dofs, rm, &meshes[rm.body], external, &body_loads[set])?;
            for d in resisted {
                match d {
                    Direction::Resisted { dir, col, load, scale } => {
                        motions.push((Motion::Body { set, dir }, load));
                        load_scale.push(scale);
                        cols.push(col);
                    }
                    Direction::Free { col, reach, note } => {
                        unresisted.push((col, reach));
                        notes.push(note);
                    }
                }
            }
        }
        let n = motions.len();
        let norms: Vec<f64> = cols
            .iter()
            .map(|c| c.iter().map(|v| v * v).sum::<f64>().sqrt())
            .collect();
        let biggest = norms.iter().copied().fold(1.0, f64::max);
        let describe = |k: usize| describe_motion(scene, dofs, motions[k].0);
        let mut undetermined = Vec::new();
        let mut live = Vec::new();
        for k in 0..n {
            if norms[k] > 1e-12 * biggest {
                live.push(k);
                continue;
            }
            if motions[k].1.abs() > 1e-12 * load_scale[k] && motions[k].1 != 0.0 {
                let (mo, load) = motions[k];
                let bound = LoadBound {
                    path: motion_path(scene, dofs, &body_loads, mo),
                    value: load_value(scene, mo, load),
                    min: Some(0.0),
                    max: Some(0.0),
                };
                return Err(CoreError::invalid(
                    InvalidKind::IncompatibleLoads,
                    bound.path.clone(),
                    format!(
                        "no contact normal has a component along the {}, so contact cannot carry its load {}: it must \
                            be 0",
                        describe(k),
                        load_words(scene, mo, load)
                    ),
                )
                .with_loads(vec![bound]));
            }
            undetermined.push(unit(n, k));
        }
        // Combinations of resisted motions that together move no candidate
        // (e.g. a body and a punch moving as one): the null space of C on `live`.
        let l = live.len();
        let g = Mat::<f64>::from_fn(l, l, |a, b| {
            let (ca, cb) = (&cols[live[a]], &cols[live[b]]);
            ca.iter().zip(cb).map(|(x, y)| x * y).sum::<f64>() / (norms[live[a]] * norms[live[b]])
        });
        let (vals, vecs) = if l > 0 {
            sym_eigen_small(&g)
        } else {
            (Vec::new(), Mat::zeros(0, 0))
        };
        let top = vals.last().copied().unwrap_or(0.0);
        // The Gram of unit columns is computed to about ε ‖G‖, so an exact null
        // combination shows up as an eigenvalue of a few 1e-16, not 0: a
        // circular punch's rotation about its own centre is a horizontal shift
        // plus a rotation about its reference point, and the rows' radial
        // directions make those two columns parallel.
        let null: Vec<usize> = (0..l).filter(|&e| vals[e] <= NULL_COMBINATION * top).collect();
        let v = if null.is_empty() {
            Mat::<f64>::from_fn(n, l, |i, j| if i == live[j] { 1.0 } else { 0.0 })
        } else {
            // Each null combination, its loads' work and the scale of that work.
            let combos: Vec<(Vec<f64>, f64, f64)> = null
                .iter()
                .map(|&e| {
                    // The eigenvector is accurate to about ε / (eigenvalue gap):
                    // components at that level are round-off, not part of the motion.
                    let biggest = (0..l).map(|a| vecs[(a, e)].abs()).fold(0.0, f64::max);
                    let dir: Vec<f64> = (0..n)
                        .map(|i| live.iter().position(|&k| k == i).map_or(0.0, |a| vecs[(a, e)]))
                        .map(|v| if v.abs() <= 1e-9 * biggest { 0.0 } else { v })
                        .enumerate()
                        .map(|(i, v)| if v == 0.0 { 0.0 } else { v / norms[i] })
                        .collect();
                    let work: f64 = (0..n).map(|i| dir[i] * motions[i].1).sum();
                    let scale: f64 = (0..n).map(|i| (dir[i] * load_scale[i]).abs()).sum();
                    (dir, work, scale)
                })
                .collect();
            let loaded = |w: f64, scale: f64| w.abs() > 1e-12 * scale && w != 0.0;
            if combos.iter().any(|c| loaded(c.1, c.2)) {
                // The combination the loads push along, Σ work_e dir_e: the
                // eigenvectors are any basis of the null space (on a roller
                // over an unsupported plate, a turn of both about the contact),
                // this is the motion the loads make (the two sinking together).
                let pushed: Vec<f64> = (0..n).map(|i| combos.iter().map(|c| c.1 * c.0[i]).sum()).collect();
                if let Some(e) = carried_body(scene, dofs, meshes, &motions, &load_scale, &pushed) {
                    return Err(e);
                }
            }
            for (dir, work, scale) in combos {
                if loaded(work, scale) {
                    let names: Vec<String> = (0..n).filter(|&i| dir[i] != 0.0).map(describe).collect();
                    return Err(CoreError::invalid(
                        InvalidKind::IncompatibleLoads,
                        motion_path(scene, dofs, &body_loads, motions[live[0]].0),
                        format!(
                            "the {} can move together without moving any contact candidate along its normal, and their \
                                loads do work on that motion: contact cannot balance them",
                            names.join(" and ")
                        ),
                    ));
                }
                undetermined.push(dir);
            }
            let keep: Vec<usize> = (0..l).filter(|e| !null.contains(e)).collect();
            Mat::<f64>::from_fn(n, keep.len(), |i, j| {
                live.iter()
                    .position(|&k| k == i)
                    .map_or(0.0, |a| vecs[(a, keep[j])] / norms[i])
            })
        };
        let kept = v.ncols();
        let c = Mat::<f64>::from_fn(m, kept, |i, j| (0..n).map(|k| cols[k][i] * v[(k, j)]).sum());
        let rhs: Vec<f64> = (0..kept)
            .map(|j| (0..n).map(|k| -motions[k].1 * v[(k, j)]).sum())
            .collect();
        for dir in &undetermined {
            if dir
                .iter()
                .zip(&motions)
                .any(|(v, (mo, _))| v.abs() > 1e-12 && matches!(mo, Motion::Body { .. }))
            {
                let parts: Vec<String> = (0..n).filter(|&i| dir[i].abs() > 1e-12).map(describe).collect();
                notes.push(format!(
                    "the {} is not determined: no contact normal resists it and no load works on it; the displacements \
                        are reported with it at 0, any amount of it is also a solution",
                    parts.join(" combined with the ")
                ));
            }
        }
        let fm = Self {
            motions,
            v,
            c,
            rhs,
            undetermined,
            notes,
            unresisted,
            load_scale: Vec::new(),
            body_loads,
        };
        fm.check_compatibility(scene, dofs, false)?;
        fm.check_held(scene, dofs)?;
        Ok(fm)
    }

    /// The free motions of a frictional scene: every load-controlled punch
    /// component as given, then every free rigid mode of every body held
    /// only by contact (`fem::rigid_modes`, mode k of body set s as
    /// `Motion::Body` with its basis direction; its column −B_N R_k and load
    /// R_kᵀ f as in the frictionless case), all with V = I, unchecked here.
    /// Friction resists motions no normal does (a flat punch pushed sideways,
    /// a block pushed along a floor), so the null space and Fichera's test of
    /// the frictionless case do not apply; the frictional solve checks them
    /// with the tangential rows (`check_with_friction`).
    fn frictional(
        punch_free: &[(usize, usize, f64)],
        c_punch: Mat<f64>,
        cons: &ConstraintSet,
        dofs: &DofMap,
        meshes: &[Mesh2d],
        external: &[f64],
        body_loads: Vec<Vec<(String, [f64; 3])>>,
    ) -> Self {
        let mut motions: Vec<(Motion, f64)> = punch_free
            .iter()
            .map(|&(obstacle, component, load)| (Motion::Punch { obstacle, component }, load))
            .collect();
        let m = cons.len();
        let mut cols: Vec<Vec<f64>> = (0..punch_free.len())
            .map(|j| (0..m).map(|i| c_punch[(i, j)]).collect())
            .collect();
        let mut load_scale: Vec<f64> = punch_free.iter().map(|f| f.2.abs()).collect();
        for (set, rm) in dofs.rigid.iter().enumerate() {
            let mesh = &meshes[rm.body];
            for (k, &dir) in rm.basis.iter().enumerate() {
                let col = rigid_column(cons.candidates.iter().map(|c| c.terms.as_slice()), rm, mesh, dir).col;
                let (mut load, mut scale) = (0.0, 0.0);
                for (n, &x) in mesh.nodes.iter().enumerate() {
                    let d = rm.at(k, x);
                    let f = [external[dofs.dof(rm.body, n, 0)], external[dofs.dof(rm.body, n, 1)]];
                    load += f[0] * d[0] + f[1] * d[1];
                    scale += f[0].hypot(f[1]) * d[0].hypot(d[1]);
                }
                motions.push((Motion::Body { set, dir }, load));
                load_scale.push(scale);
                cols.push(col);
            }
        }
        let k = motions.len();
        Self {
            v: Mat::<f64>::from_fn(k, k, |i, j| if i == j { 1.0 } else { 0.0 }),
            c: Mat::<f64>::from_fn(m, k, |i, j| cols[j][i]),
            rhs: motions.iter().map(|f| -f.1).collect(),
            motions,
            undetermined: Vec::new(),
            notes: Vec::new(),
            unresisted: Vec::new(),
            load_scale,
            body_loads,
        }
    }

    /// Fichera's condition with friction: some contact force inside the
    /// friction cone on every candidate balances the punches' loads. In 2D
    /// the cone |τ| ≤ s λ is spanned by two rays, λ (n ± s t) (s = μ for
    /// Coulomb: `FrictionLaw::ray_slope`), so the
    /// forces are non-negative combinations of two columns per candidate and
    /// the frictionless LP decides (its ranges are then the frictional ones:
    /// a flat punch under P admits the horizontal loads [−μ|P|, μ|P|]).
    ///
    /// The cone is taken about both normals of a candidate, the punch's
    /// (its row direction n) and the body's, and a force must lie in both:
    /// the rays at angles [max(0, δ) − atan μ, min(0, δ) + atan μ] from n,
    /// δ the angle from n to the body's normal (`tilt`), none if that is
    /// empty. A force acts only where the two surfaces touch, and there, in
    /// the small-displacement model, they share their normal up to the
    /// surface's small rotation; a candidate whose two normals differ
    /// (beyond the zone of a curved punch on a flat block, where the punch's
    /// normal tilts by asin(x/R) and the block's stays vertical) would carry
    /// its force along the punch's tilted normal only after a large
    /// rotation of the surface. With the punch's normals alone, the LP let
    /// those candidates carry a horizontal load through their tilt (the
    /// wedge of a linearized gap, g(x − α1) ≈ g(x) − g′(x) α1, that a
    /// cylinder translated over a flat does not have) and admitted Q = 1.05 μP
    /// on the circular punch example, whose step then ran to the iteration
    /// cap. Rows without friction (`slope` 0) keep their one direction n.
    /// `ct`: each candidate's tangential punch coefficients (0 without a
    /// tangential row), `slope` its cone's. Returns the motions neither
    /// the normals nor friction resist and no load works on (a flat punch's
    /// horizontal motion on a frictionless pair): they are not determined,
    /// as in the frictionless case; with a load they fail the test.
    pub fn check_with_friction(
        &self,
        scene: &Scene,
        dofs: &DofMap,
        ct: &Mat<f64>,
        slope: &[f64],
        tilt: &[f64],
    ) -> Result<Vec<usize>, CoreError> {
        if self.is_empty() {
            return Ok(Vec::new());
        }
        let (m, k) = (self.c.nrows(), self.c.ncols());
        // tan of each candidate's two ray angles from n, None: no ray.
        let rays: Vec<Option<[f64; 2]>> = (0..m)
            .map(|i| {
                if slope[i] <= 0.0 {
                    return Some([0.0, 0.0]);
                }
                if tilt[i] == 0.0 {
                    return Some([slope[i], -slope[i]]);
                }
                let (half, d) = (slope[i].atan(), tilt[i]);
                let (hi, lo) = (d.min(0.0) + half, d.max(0.0) - half);
                (hi >= lo).then(|| [hi.tan(), lo.tan()])
            })
            .collect();
        let cone = Mat::<f64>::from_fn(2 * m, k, |r, j| {
            let i = r / 2;
            rays[i].map_or(0.0, |t| self.c[(i, j)] + t[r % 2] * ct[(i, j)])
        });
        let undetermined: Vec<usize> = (0..k)
            .filter(|&j| (0..2 * m).all(|r| cone[(r, j)] == 0.0) && self.rhs[j] == 0.0)
            .collect();
        let with_cone = Self {
            motions: self.motions.clone(),
            v: self.v.clone(),
            c: cone,
            rhs: self.rhs.clone(),
            undetermined: Vec::new(),
            notes: Vec::new(),
            unresisted: Vec::new(),
            load_scale: Vec::new(),
            body_loads: self.body_loads.clone(),
        };
        with_cone.check_compatibility(scene, dofs, true)?;
        Ok(undetermined)
    }

    /// Some free motion must not be able to leave every contact without the
    /// loads resisting it (`fichera::escape`): a body pressed from one side
    /// and held by nothing else, or left with no load by a forgotten support.
    fn check_held(&self, scene: &Scene, dofs: &DofMap) -> Result<(), CoreError> {
        if self.is_empty() {
            return Ok(());
        }
        let Some(gamma) = fichera::escape(&self.c, &self.rhs) else {
            return Ok(());
        };
        let beta = self.motion(&gamma);
        let biggest = beta.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let moving: Vec<usize> = (0..beta.len()).filter(|&k| beta[k].abs() > 1e-6 * biggest).collect();
        // Each body's share of the escape as one rigid motion, in words.
        let (mut parts, mut seen, mut path) = (Vec::new(), Vec::new(), None);
        for &k in &moving {
            match self.motions[k].0 {
                Motion::Punch { obstacle, component } => {
                    path.get_or_insert_with(|| format!("/obstacles/{obstacle}/punch/{}", COMPONENT[component]));
                    parts.push(format!(
                        "{} motion of punch '{}'",
                        COMPONENT[component], scene.obstacles[obstacle].name
                    ));
                }
                Motion::Body { set, .. } if !seen.contains(&set) => {
                    seen.push(set);
                    let mut dir = [0.0; 3];
                    for &j in &moving {
                        if let Motion::Body { set: other, dir: d } = self.motions[j].0 {
                            if other == set {
                                (0..3).for_each(|q| dir[q] += beta[j] * d[q]);
                            }
                        }
                    }
                    let body = &scene.bodies[dofs.rigid[set].body];
                    path.get_or_insert_with(|| body.supports_path());
                    parts.push(format!(
                        "{} of body '{}'",
                        dofs.rigid[set].describe(dir, scene.scales.length(1.0)),
                        body.name
                    ));
                }
                Motion::Body { .. } => {}
            }
        }
        Err(CoreError::invalid(
            InvalidKind::NoSupport,
            path.unwrap_or_default(),
            format!(
                "nothing holds the {}: it moves away from every contact and no load resists it, so contact, which can \
                    only push, carries nothing and the position is not determined; add a support that stops this \
                    motion (supports with ux and/or uy on an edge set), or load the body against its contact",
                parts.join(" together with the ")
            ),
        ))
    }

    /// Fichera's condition as an LP; on failure, the admissible range of each
    /// offending load with the others as given.
    /// With `friction`, the columns are the friction cone's rays.
    fn check_compatibility(&self, scene: &Scene, dofs: &DofMap, friction: bool) -> Result<(), CoreError> {
        if self.is_empty() {
            return Ok(());
        }
        let Err(bad) = fichera::check(&self.c, &self.rhs) else {
            return Ok(());
        };
        // With the identity basis each kept component is one motion and its range
        // is in that motion's units; a rotated basis only allows a general message.
        let original = |j: usize| {
            let nz: Vec<usize> = (0..self.v.nrows()).filter(|&k| self.v[(k, j)] != 0.0).collect();
            (nz.len() == 1 && self.v[(nz[0], j)] == 1.0).then(|| nz[0])
        };
        let mut bounds: Vec<(f64, LoadBound)> = Vec::new();
        let ranges: Vec<String> = bad
            .iter()
            .filter_map(|r| {
                let k = original(r.component)?;
                let (mo, load) = self.motions[k];
                let value = load_value(scene, mo, load);
                // A bound of 0 comes out of the LP (run to 1e-13) as a few 1e-10 of the load.
                let snap = |v: Option<f64>| v.map(|v| if v.abs() <= 1e-8 * value.abs() { 0.0 } else { v });
                let (min, max) = load_range(scene, mo, r.min, r.max);
                let (min, max) = (snap(min), snap(max));
                let b = LoadBound {
                    path: motion_path(scene, dofs, &self.body_loads, mo),
                    value,
                    min,
                    max,
                };
                bounds.push((outside(b.value, b.min, b.max), b));
                let fmt =
                    |v: Option<f64>, inf: &str| v.map(|x| load_words_user(mo, x)).unwrap_or_else(|| inf.to_string());
                let what = match mo {
                    Motion::Punch { obstacle, component } => format!(
                        "{} load {} on punch '{}'",
                        COMPONENT[component],
                        load_words(scene, mo, load),
                        scene.obstacles[obstacle].name
                    ),
                    Motion::Body { .. } => format!(
                        "load {} along the {}",
                        load_words(scene, mo, load),
                        describe_motion(scene, dofs, mo)
                    ),
                };
                Some(format!(
                    "the {what} must lie in [{}, {}]",
                    fmt(min, "-inf"),
                    fmt(max, "+inf")
                ))
            })
            .collect();
        let first = original(bad[0].component).unwrap_or(0);
        let path = bounds
            .iter()
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, b)| b.path.clone())
            .unwrap_or_else(|| motion_path(scene, dofs, &self.body_loads, self.motions[first].0));
        let what: Vec<String> =
            self.motions
                .iter()
                .map(|(mo, _)| owner(scene, dofs, *mo))
                .fold(Vec::new(), |mut acc, o| {
                    if !acc.contains(&o) {
                        acc.push(o);
                    }
                    acc
                });
        let loads = bounds.into_iter().map(|(_, b)| b).collect();
        let force = if friction {
            "contact force inside the friction cone (|t| ≤ μ p)"
        } else {
            "non-negative contact pressure"
        };
        let slides = if !friction {
            ""
        } else if self.motions.iter().any(|(mo, _)| matches!(mo, Motion::Body { .. })) {
            " (the body would slide or tip: no quasi-static equilibrium)"
        } else {
            " (the punch would slide: no quasi-static equilibrium)"
        };
        Err(CoreError::invalid(
            InvalidKind::IncompatibleLoads,
            path,
            if ranges.is_empty() {
                format!(
                    "no {force} on the candidate zone balances the loads on {}{slides}",
                    what.join(" and ")
                )
            } else {
                format!(
                    "no {force} on the candidate zone balances the loads on {}{slides}; with the other loads as given, \
                        {}",
                    what.join(" and "),
                    ranges.join("; or ")
                )
            },
        )
        .with_loads(loads))
    }
}

/// A body the loads of others push along with them: in a combination `dir`
/// of free motions that moves no candidate and that the loads work on, a
/// body held by nothing but contact whose own loads do no work on its part
/// (one without supports first), refused `no_support` with its part of the
/// motion and a support that stops it. A plate left unsupported under a
/// roller pressed onto it was refused `incompatible_loads` at the roller's
/// tractions, in a sentence of four motions that never said the plate had
/// no support.
fn carried_body(
    scene: &Scene,
    dofs: &DofMap,
    meshes: &[Mesh2d],
    motions: &[(Motion, f64)],
    load_scale: &[f64],
    dir: &[f64],
) -> Option<CoreError> {
    let mut sets: Vec<usize> = motions
        .iter()
        .zip(dir)
        .filter_map(|((mo, _), &c)| match mo {
            Motion::Body { set, .. } if c != 0.0 => Some(*set),
            _ => None,
        })
        .collect();
    sets.dedup();
    let part = |set: usize| {
        let (mut d, mut work, mut scale) = ([0.0; 3], 0.0, 0.0);
        for (i, (mo, load)) in motions.iter().enumerate() {
            if let Motion::Body { set: s, dir: b } = mo {
                if *s == set {
                    (0..3).for_each(|q| d[q] += dir[i] * b[q]);
                    work += dir[i] * load;
                    scale += (dir[i] * load_scale[i]).abs();
                }
            }
        }
        (d, work.abs() <= 1e-12 * scale)
    };
    let carried: Vec<(usize, [f64; 3])> = sets
        .iter()
        .map(|&s| (s, part(s)))
        .filter(|(_, (_, unloaded))| *unloaded)
        .map(|(s, (d, _))| (s, d))
        .collect();
    let &(set, d) = carried
        .iter()
        .find(|(s, _)| scene.bodies[dofs.rigid[*s].body].supports.is_empty())
        .or(carried.first())?;
    let rm = &dofs.rigid[set];
    let (b, body) = (rm.body, &scene.bodies[rm.body]);
    let words = rm.describe(d, scene.scales.length(1.0));
    let others: Vec<String> = sets
        .iter()
        .filter(|&&s| dofs.rigid[s].body != b)
        .map(|&s| format!("'{}'", scene.bodies[dofs.rigid[s].body].name))
        .collect();
    // An edge set away from the body's contacts to put the support on.
    let in_contact = |name: &str| {
        scene.pairs.iter().any(|p| {
            (p.body == b && p.edges == name)
                || matches!(&p.target, crate::scene::Target::Body { body, edges, .. } if *body == b && edges == name)
        })
    };
    let mut free_sets: Vec<&String> = meshes[b].edge_sets.keys().filter(|k| !in_contact(k)).collect();
    free_sets.sort();
    let components = match rigid_modes::kind(d) {
        Kind::X(_) => "\"ux\": 0",
        Kind::Y(_) => "\"uy\": 0",
        _ => "\"ux\": 0, \"uy\": 0",
    };
    let example = free_sets.first().map_or_else(
        || format!("{{{components}}} on one of its edge sets"),
        |e| format!("{{\"edges\": \"{e}\", {components}}}"),
    );
    Some(CoreError::invalid(
        InvalidKind::NoSupport,
        body.supports_path(),
        format!(
            "body '{}' is held by nothing but contact: its {words} moves together with body {} without opening or \
                closing any contact, and no load of its own works on it, so nothing balances the loads that push them; \
                add a support to body '{}' that stops its {words}, e.g. {example}",
            body.name,
            others.join(" and body "),
            body.name
        ),
    ))
}

fn unit(n: usize, k: usize) -> Vec<f64> {
    (0..n).map(|i| if i == k { 1.0 } else { 0.0 }).collect()
}

fn owner(scene: &Scene, dofs: &DofMap, mo: Motion) -> String {
    match mo {
        Motion::Punch { obstacle, .. } => format!("punch '{}'", scene.obstacles[obstacle].name),
        Motion::Body { set, .. } => format!("body '{}'", scene.bodies[dofs.rigid[set].body].name),
    }
}

pub fn describe_motion(scene: &Scene, dofs: &DofMap, mo: Motion) -> String {
    match mo {
        Motion::Punch { obstacle, component } => format!(
            "{} motion of punch '{}'",
            COMPONENT[component], scene.obstacles[obstacle].name
        ),
        Motion::Body { set, dir } => format!(
            "{} of body '{}' (held only by contact)",
            dofs.rigid[set].describe(dir, scene.scales.length(1.0)),
            scene.bodies[dofs.rigid[set].body].name
        ),
    }
}

/// A load of a motion in the request's units: a force, or a moment. A body's
/// rigid motion (b0, b1, θ) with θ ≠ 0 is a rotation θ about its fixed point
/// (`rigid_modes::describe` names it), and the loads' work on it is θ times
/// their moment about that point; a translation (b0, b1) of length t does
/// work t times the force along it (along x or y: the signed component, so
/// that the value is F_x or F_y as `describe` names the motion).
fn load_value(scene: &Scene, mo: Motion, v: f64) -> f64 {
    let sc = scene.scales;
    match mo {
        Motion::Punch { component: 2, .. } => sc.moment(v),
        Motion::Punch { .. } => sc.force(v),
        Motion::Body { dir: b, .. } => match rigid_modes::kind(b) {
            Kind::Rotation(theta) => sc.moment(v / theta),
            _ => sc.force(v / unit_of(b)),
        },
    }
}

/// The amplitude of a body's motion per unit of what names its load
/// (`rigid_modes::kind`).
fn unit_of(b: [f64; 3]) -> f64 {
    match rigid_modes::kind(b) {
        Kind::X(u) | Kind::Y(u) | Kind::Along(u) | Kind::Rotation(u) => u,
    }
}

/// [min, max] of a load in the request's units: a negative `unit_of`
/// reverses the range.
fn load_range(scene: &Scene, mo: Motion, min: Option<f64>, max: Option<f64>) -> (Option<f64>, Option<f64>) {
    let (a, b) = (
        min.map(|v| load_value(scene, mo, v)),
        max.map(|v| load_value(scene, mo, v)),
    );
    match mo {
        Motion::Body { dir, .. } if unit_of(dir) < 0.0 => (b, a),
        _ => (a, b),
    }
}

/// A nondimensional load `v` on motion `mo`, in words and the request's units.
fn load_words(scene: &Scene, mo: Motion, v: f64) -> String {
    load_words_user(mo, load_value(scene, mo, v))
}

/// A load `x` already in the request's units, with what it is.
fn load_words_user(mo: Motion, x: f64) -> String {
    match mo {
        Motion::Body { dir: b, .. } if matches!(rigid_modes::kind(b), Kind::Rotation(_)) => {
            format!("{} (moment about the centre of that rotation)", shown(x))
        }
        _ => shown(x),
    }
}

/// How far a value lies outside [min, max], relative to the nearer bound
/// (0 inside): the measure by which the component most likely set wrong is
/// chosen (a flat punch's |M| = 1.1 P a: 0.1 for M against 0.09 for P).
fn outside(value: f64, min: Option<f64>, max: Option<f64>) -> f64 {
    // Relative to the bound; a bound of 0 (a load that must vanish) by the value.
    let rel = |d: f64, bound: f64| d / if bound != 0.0 { bound.abs() } else { value.abs() };
    match (min, max) {
        (Some(lo), _) if value < lo => rel(lo - value, lo),
        (_, Some(hi)) if value > hi => rel(value - hi, hi),
        _ => 0.0,
    }
}

/// The JSON pointer of a motion's load: a punch's load component, or the
/// load of the body doing most work on the motion (the body when none does).
fn motion_path(scene: &Scene, dofs: &DofMap, body_loads: &[Vec<(String, [f64; 3])>], mo: Motion) -> String {
    match mo {
        Motion::Punch { obstacle, component } => {
            format!("/obstacles/{obstacle}/punch/{}/load", COMPONENT[component])
        }
        Motion::Body { set, dir } => {
            heaviest(&body_loads[set], dir).unwrap_or_else(|| scene.bodies[dofs.rigid[set].body].path.clone())
        }
    }
}

/// The path of the load with the largest |work| on the rigid motion `dir`
/// = (ux, uy, rotation about the centre its resultants are taken about):
/// Fx ux + Fy uy + M θ. None when no load works on it.
fn heaviest(loads: &[(String, [f64; 3])], dir: [f64; 3]) -> Option<String> {
    loads
        .iter()
        .map(|(path, r)| (path, (r[0] * dir[0] + r[1] * dir[1] + r[2] * dir[2]).abs()))
        .filter(|(_, w)| *w > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(path, _)| path.clone())
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

/// Below this, contact "resists" a rigid motion of a body only through the
/// discretization: the normals of its candidates move less than this fraction of
/// the candidates' own motion (a cylinder turning about its centre, whose
/// polygonal boundary is not quite round). Such a motion is treated as free: a
/// load on it is refused rather than balanced by absurd pressures, and without
/// load it is reported as undetermined.
const WEAK_LEVER: f64 = 1e-2;

enum Direction {
    Resisted {
        dir: [f64; 3],
        col: Vec<f64>,
        load: f64,
        scale: f64,
    },
    Free {
        col: Vec<f64>,
        reach: Vec<f64>,
        note: String,
    },
}

/// The rigid motions of one body held by contact, split into those contact
/// resists (a basis in which each moves the candidate nodes by 1 in the mean
/// square and their normals by √μ ≥ WEAK_LEVER) and those it does not (which
/// must carry no load).
fn body_directions(
    scene: &Scene,
    cons: &ConstraintSet,
    dofs: &DofMap,
    rm: &RigidModes,
    mesh: &Mesh2d,
    external: &[f64],
    loads: &[(String, [f64; 3])],
) -> Result<Vec<Direction>, CoreError> {
    let r = rm.basis.len();
    let m = cons.len();
    let rows = || cons.candidates.iter().map(|c| c.terms.as_slice());
    // C in the basis (m × r) and the motion Gram of the candidate nodes.
    let cols: Vec<Vec<f64>> = rm
        .basis
        .iter()
        .map(|&b| rigid_column(rows(), rm, mesh, b).col)
        .collect();
    let c = Mat::<f64>::from_fn(m, r, |i, k| cols[k][i]);
    let mut gr = Mat::<f64>::zeros(r, r);
    for cand in &cons.candidates {
        for t in cand.terms.iter().filter(|t| t.body == rm.body) {
            let ms: Vec<[f64; 2]> = (0..r).map(|k| rm.at(k, mesh.nodes[t.node])).collect();
            for k in 0..r {
                for l in 0..r {
                    gr[(k, l)] += ms[k][0] * ms[l][0] + ms[k][1] * ms[l][1];
                }
            }
        }
    }
    let (rho, w) = sym_eigen_small(&gr);
    let top = rho.last().copied().unwrap_or(0.0);
    // Directions that move candidate nodes, scaled to unit mean-square motion.
    let moving: Vec<usize> = (0..r).filter(|&j| rho[j] > 1e-12 * top && top > 0.0).collect();
    let u = Mat::<f64>::from_fn(r, moving.len(), |k, j| w[(k, moving[j])] / rho[moving[j]].sqrt());
    let cu = &c * &u;
    let gc = cu.transpose() * &cu;
    let (mu, z) = if moving.is_empty() {
        (Vec::new(), Mat::zeros(0, 0))
    } else {
        sym_eigen_small(&gc)
    };
    let mut dirs: Vec<(Vec<f64>, bool)> = Vec::new(); // (coefficients in the basis, resisted)
    for j in 0..r {
        if !moving.contains(&j) {
            dirs.push(((0..r).map(|k| w[(k, j)]).collect(), false));
        }
    }
    for (e, &mu_e) in mu.iter().enumerate() {
        let coef: Vec<f64> = (0..r)
            .map(|k| (0..moving.len()).map(|j| u[(k, j)] * z[(j, e)]).sum())
            .collect();
        dirs.push((coef, mu_e >= WEAK_LEVER * WEAK_LEVER));
    }
    let body = &scene.bodies[rm.body];
    let mut out = Vec::new();
    for (coef, resisted) in dirs {
        let mut dir = [0.0; 3];
        for (k, b) in rm.basis.iter().enumerate() {
            for q in 0..3 {
                dir[q] += coef[k] * b[q];
            }
        }
        let (mut load, mut scale) = (0.0, 0.0);
        // The work is judged against the loads' full size (‖f‖ ‖d‖ per node), so
        // that round-off in a load perpendicular to the motion counts as zero.
        for (n, x) in mesh.nodes.iter().enumerate() {
            let d = rm.at_dir(dir, *x);
            let f = [external[dofs.dof(rm.body, n, 0)], external[dofs.dof(rm.body, n, 1)]];
            load += f[0] * d[0] + f[1] * d[1];
            scale += f[0].hypot(f[1]) * d[0].hypot(d[1]);
        }
        if resisted {
            let col: Vec<f64> = (0..m).map(|i| (0..r).map(|k| c[(i, k)] * coef[k]).sum()).collect();
            out.push(Direction::Resisted { dir, col, load, scale });
            continue;
        }
        let words = rm.describe(dir, scene.scales.length(1.0));
        if load.abs() > 1e-12 * scale && load != 0.0 {
            return Err(CoreError::invalid(
                InvalidKind::IncompatibleLoads,
                heaviest(loads, dir).unwrap_or_else(|| body.path.clone()),
                format!(
                    "contact does not resist the {words} of body '{}' (held only by contact): no contact normal moves \
                        with it (beyond the discretization's {:.0e} of its motion), so contact cannot carry the loads' \
                        work on it; balance the loads on the body or support it",
                    body.name, WEAK_LEVER
                ),
            ));
        }
        // What contact does on this motion after all, per candidate, and how far
        // each candidate moves with it: checked against λ after the solve.
        let RigidColumn { col, reach } = rigid_column(rows(), rm, mesh, dir);
        out.push(Direction::Free {
            col,
            reach,
            note: format!(
                "the {words} of body '{}' is not determined: contact does not resist it and no load works on it; the \
                    displacements are reported with it at 0, any amount of it is also a solution",
                body.name
            ),
        });
    }
    Ok(out)
}

/// What a rigid motion of one body does to a set of rows (normal or
/// tangential, over nodes).
pub struct RigidColumn {
    /// Per row, −Σ coef · R(x) over the row's terms on the body: the row
    /// reads B u, and a rigid motion R β of its own points enters the rows
    /// as −C β, so its column of C is −B R.
    pub col: Vec<f64>,
    /// Per row, the largest |R(x)| among its points on the body: how far
    /// the row moves with the motion (0 off the body).
    pub reach: Vec<f64>,
}

/// The column and reach over `rows` of the rigid motion `dir` = (ux, uy,
/// rotation about the centre) of the body of `rm` (`RigidModes::at_dir`).
pub fn rigid_column<'a>(
    rows: impl IntoIterator<Item = &'a [Term]>,
    rm: &RigidModes,
    mesh: &Mesh2d,
    dir: [f64; 3],
) -> RigidColumn {
    let (mut col, mut reach) = (Vec::new(), Vec::new());
    for terms in rows {
        let on_body = || {
            terms
                .iter()
                .filter(|t| t.body == rm.body)
                .map(|t| (t, rm.at_dir(dir, mesh.nodes[t.node])))
        };
        col.push(on_body().map(|(t, d)| -(t.coef[0] * d[0] + t.coef[1] * d[1])).sum());
        reach.push(on_body().map(|(_, d)| d[0].hypot(d[1])).fold(0.0, f64::max));
    }
    RigidColumn { col, reach }
}
