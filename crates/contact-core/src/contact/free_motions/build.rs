//! The free motions of a scene: the load-controlled punch components and
//! the rigid modes of bodies held only by contact, their columns C over the
//! candidates and their loads, reduced to the motions contact determines
//! (the null space of C removed, `NULL_COMBINATION`; a body's motion whose
//! lever is only the discretization's treated as free, `WEAK_LEVER`).

use faer::Mat;

use super::columns::{rigid_column, RigidColumn};
use super::refusal::carried_body;
use super::words::{describe_motion, heaviest, load_value, load_words, motion_path};
use super::{FreeMotions, Motion};
use crate::contact::ConstraintSet;
use crate::error::{CoreError, InvalidKind, LoadBound};
use crate::fem::loads::{self, Located};
use crate::fem::rigid_modes::RigidModes;
use crate::fem::DofMap;
use crate::linalg::dense::sym_eigen_small;
use crate::mesh::Mesh2d;
use crate::outcome::{Note, NoteKind};
use crate::scene::Scene;

/// Relative Gram eigenvalue below which a combination of free motions moves no
/// candidate: a lever of 1e-6 of the motion, far above round-off (ε‖G‖) and far
/// below any real lever (a circular punch's horizontal shift has n_x ≈ x/R).
const NULL_COMBINATION: f64 = 1e-12;

impl FreeMotions {
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
        let (vecs, null) = null_space(&cols, &norms, &live);
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
                notes.push(Note::new(
                    NoteKind::UndeterminedMotion,
                    format!(
                        "the {} is not determined: no contact normal resists it and no load works on it; the \
                            displacements are reported with it at 0, any amount of it is also a solution",
                        parts.join(" combined with the ")
                    ),
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
}

/// The null space of the unit columns `live` of C: the eigenvectors of
/// their Gram (by ascending eigenvalue) and those whose eigenvalues are at
/// most NULL_COMBINATION of the largest, combinations that move no candidate.
fn null_space(cols: &[Vec<f64>], norms: &[f64], live: &[usize]) -> (Mat<f64>, Vec<usize>) {
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
    (vecs, null)
}

fn unit(n: usize, k: usize) -> Vec<f64> {
    (0..n).map(|i| if i == k { 1.0 } else { 0.0 }).collect()
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
        note: Note,
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
            // A coupled body takes no supports: its motions are held by the coupling.
            let hold = if body.couplings.is_empty() {
                "support it"
            } else {
                "hold that motion with a coupling displacement"
            };
            return Err(CoreError::invalid(
                InvalidKind::IncompatibleLoads,
                heaviest(loads, dir).unwrap_or_else(|| body.path.clone()),
                format!(
                    "contact does not resist the {words} of body '{}' (held only by contact): no contact normal moves \
                        with it (beyond the discretization's {:.0e} of its motion), so contact cannot carry the loads' \
                        work on it; balance the loads on the body or {hold}",
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
            note: Note::new(
                NoteKind::UndeterminedMotion,
                format!(
                    "the {words} of body '{}' is not determined: contact does not resist it and no load works on it; \
                        the displacements are reported with it at 0, any amount of it is also a solution",
                    body.name
                ),
            ),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The null space of the columns is the combinations that move no
    /// candidate: with columns a, b, a + 2b and c (a, b, c independent)
    /// exactly one eigenvalue of the unit columns' Gram falls below
    /// NULL_COMBINATION of the largest, and its eigenvector, applied to the
    /// unit columns, moves every candidate by less than 1e-14 (ε times the
    /// Gram's size, 4); without the dependent column there is none.
    #[test]
    fn the_null_combinations_move_no_candidate() {
        let (a, b, c) = (
            vec![1.0, 0.2, -0.4, 0.0],
            vec![0.0, 1.0, 0.3, 0.5],
            vec![0.7, 0.0, 0.0, -1.0],
        );
        let ab: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + 2.0 * y).collect();
        let norm = |v: &Vec<f64>| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for (cols, nulls) in [(vec![a.clone(), b.clone(), ab, c.clone()], 1), (vec![a, b, c], 0)] {
            let norms: Vec<f64> = cols.iter().map(norm).collect();
            let live: Vec<usize> = (0..cols.len()).collect();
            let (vecs, null) = null_space(&cols, &norms, &live);
            assert_eq!(null.len(), nulls);
            for &e in &null {
                for i in 0..cols[0].len() {
                    let moved: f64 = (0..cols.len()).map(|k| vecs[(k, e)] * cols[k][i] / norms[k]).sum();
                    assert!(moved.abs() <= 1e-14, "candidate {i}: {moved}");
                }
            }
        }
    }
}
