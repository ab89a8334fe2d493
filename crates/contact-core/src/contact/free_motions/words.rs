//! The free motions in the request's terms: a motion's words, its load in
//! the request's units and range, and the JSON pointer of the load a
//! refusal names.

use super::{Motion, COMPONENT};
use crate::fem::rigid_modes::{self, Kind};
use crate::fem::DofMap;
use crate::scene::scaling::shown;
use crate::scene::Scene;

pub(super) fn owner(scene: &Scene, dofs: &DofMap, mo: Motion) -> String {
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
pub(super) fn load_value(scene: &Scene, mo: Motion, v: f64) -> f64 {
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
pub(super) fn unit_of(b: [f64; 3]) -> f64 {
    match rigid_modes::kind(b) {
        Kind::X(u) | Kind::Y(u) | Kind::Along(u) | Kind::Rotation(u) => u,
    }
}

/// [min, max] of a load in the request's units: a negative `unit_of`
/// reverses the range.
pub(super) fn load_range(scene: &Scene, mo: Motion, min: Option<f64>, max: Option<f64>) -> (Option<f64>, Option<f64>) {
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
pub(super) fn load_words(scene: &Scene, mo: Motion, v: f64) -> String {
    load_words_user(mo, load_value(scene, mo, v))
}

/// A load `x` already in the request's units, with what it is.
pub(super) fn load_words_user(mo: Motion, x: f64) -> String {
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
pub(super) fn outside(value: f64, min: Option<f64>, max: Option<f64>) -> f64 {
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
pub(super) fn motion_path(scene: &Scene, dofs: &DofMap, body_loads: &[Vec<(String, [f64; 3])>], mo: Motion) -> String {
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
pub(super) fn heaviest(loads: &[(String, [f64; 3])], dir: [f64; 3]) -> Option<String> {
    loads
        .iter()
        .map(|(path, r)| (path, (r[0] * dir[0] + r[1] * dir[1] + r[2] * dir[2]).abs()))
        .filter(|(_, w)| *w > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(path, _)| path.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How far a load lies outside its admissible range, relative to the
    /// nearer bound (0 inside; by the value itself for a bound of 0), and
    /// the load that works most on a motion (none when none works on it).
    #[test]
    fn the_offending_load_is_the_one_farthest_out_and_doing_most_work() {
        assert_eq!(outside(2.0, Some(0.0), Some(4.0)), 0.0);
        assert_eq!(outside(5.0, Some(0.0), Some(4.0)), 0.25);
        assert_eq!(outside(-2.0, Some(0.0), None), 1.0);
        let loads = vec![
            ("/a".to_string(), [1.0, 0.0, 0.0]),
            ("/b".to_string(), [0.0, -2.0, 0.0]),
            ("/c".to_string(), [0.0, 0.0, 0.0]),
        ];
        assert_eq!(heaviest(&loads, [1.0, 1.0, 0.0]).as_deref(), Some("/b"));
        assert_eq!(heaviest(&loads, [0.0, 0.0, 1.0]), None);
    }
}
