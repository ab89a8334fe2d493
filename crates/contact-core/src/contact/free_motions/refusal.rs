//! The refusal of loads contact cannot carry: Fichera's LP on the free
//! motions' columns (with friction, on the friction cone's rays), the test
//! that some motion cannot leave every contact unresisted (each refusal
//! in the request's terms: `words`).

use faer::Mat;

use super::words::{describe_motion, load_range, load_value, load_words, load_words_user, motion_path, outside, owner};
use super::{FreeMotions, Motion, COMPONENT};
use crate::contact::fichera;
use crate::error::{CoreError, InvalidKind, LoadBound};
use crate::fem::rigid_modes::{self, Kind};
use crate::fem::DofMap;
use crate::mesh::Mesh2d;
use crate::scene::Scene;

impl FreeMotions {
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
        let rays: Vec<Option<[f64; 2]>> = (0..m).map(|i| cone_rays(slope[i], tilt[i])).collect();
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
    pub(super) fn check_held(&self, scene: &Scene, dofs: &DofMap) -> Result<(), CoreError> {
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
    pub(super) fn check_compatibility(&self, scene: &Scene, dofs: &DofMap, friction: bool) -> Result<(), CoreError> {
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

/// tan of a candidate's two ray angles from its row direction n: the cone
/// of slope `slope` about n met with the same cone about the body's normal,
/// at the angle `tilt` from n (None where they do not meet); n alone
/// without friction.
fn cone_rays(slope: f64, tilt: f64) -> Option<[f64; 2]> {
    if slope <= 0.0 {
        return Some([0.0, 0.0]);
    }
    if tilt == 0.0 {
        return Some([slope, -slope]);
    }
    let (half, d) = (slope.atan(), tilt);
    let (hi, lo) = (d.min(0.0) + half, d.max(0.0) - half);
    (hi >= lo).then(|| [hi.tan(), lo.tan()])
}

/// A body the loads of others push along with them: in a combination `dir`
/// of free motions that moves no candidate and that the loads work on, a
/// body held by nothing but contact whose own loads do no work on its part
/// (one without supports first), refused `no_support` with its part of the
/// motion and a support that stops it. A plate left unsupported under a
/// roller pressed onto it was refused `incompatible_loads` at the roller's
/// tractions, in a sentence of four motions that never said the plate had
/// no support.
pub(super) fn carried_body(
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The rays span the intersection of the cone of slope s about the row
    /// direction n with the cone about the body's normal, tilted by δ: each
    /// ray's angle φ from n lies in both (|φ| ≤ atan s, |φ − δ| ≤ atan s, to
    /// the round-off of atan and tan, 1e-15), the upper one on the upper
    /// edge of the intersection, min(0, δ) + atan s, the lower one on its
    /// lower edge; the cones do not meet when |δ| > 2 atan s. Without
    /// friction the force is along n alone.
    #[test]
    fn the_cone_rays_lie_in_both_normals_cones() {
        assert_eq!(cone_rays(0.0, 0.3), Some([0.0, 0.0]));
        for s in [0.3, 1.0] {
            let half = f64::atan(s);
            for d in [-1.5, -0.5, -0.1, 0.0, 0.2, 0.6, 1.5] {
                let rays = cone_rays(s, d);
                assert_eq!(rays.is_none(), d.abs() > 2.0 * half, "s {s}, δ {d}");
                let Some([hi, lo]) = rays else { continue };
                for t in [hi, lo] {
                    let phi = t.atan();
                    assert!(
                        phi.abs() <= half + 1e-15 && (phi - d).abs() <= half + 1e-15,
                        "s {s}, δ {d}: φ {phi}"
                    );
                }
                assert!((hi.atan() - (d.min(0.0) + half)).abs() <= 1e-15);
                assert!((lo.atan() - (d.max(0.0) - half)).abs() <= 1e-15);
            }
        }
    }
}
