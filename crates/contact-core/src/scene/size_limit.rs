//! The size limit, checked before any mesh is built: each body's node count
//! predicted from its mesh parameters (`mesh::estimate`), and a refusal that
//! names the field to change and the value that would be accepted.

use crate::error::CoreError;
use crate::mesh::estimate::{self, Shape};
use crate::mesh::generate::Grading;
use crate::mesh::gmsh;
use contact_proto::{ElementKind, GradingSpec, MeshSpec};

/// The mesh parameter a refusal asks to coarsen.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Knob {
    /// `grading/h_min`, up to `size`.
    HMin,
    /// `size`, with `grading/h_min` scaled alike.
    Size,
}

/// A box that holds a body's mesh, in the request's units (a disk's whole
/// square for a half or quarter disk: at most its radius too far, which the
/// coupling's bound, 10⁴ times the body's size, does not notice), and the
/// mesh's predicted node count (`parsed`: the body's Gmsh file, read once by
/// the caller). The box's largest side is the body's nominal extent.
pub(super) fn box_and_nodes(m: &MeshSpec, parsed: Option<&gmsh::Parsed>) -> (([f64; 2], [f64; 2]), f64) {
    match m {
        MeshSpec::Rectangle(r) => (
            (r.corner, [r.corner[0] + r.width, r.corner[1] + r.height]),
            count(m, Knob::Size, 1.0),
        ),
        MeshSpec::HalfDisk(d) | MeshSpec::QuarterDisk(d) => (
            (
                [d.center[0] - d.radius, d.center[1] - d.radius],
                [d.center[0] + d.radius, d.center[1] + d.radius],
            ),
            count(m, Knob::Size, 1.0),
        ),
        MeshSpec::Inline(i) => (crate::mesh::bounds(&i.nodes), i.nodes.len() as f64),
        MeshSpec::Gmsh(_) => parsed.map_or((([0.0; 2], [0.0; 2]), 0.0), |p| {
            (crate::mesh::bounds(&p.nodes), p.nodes.len() as f64)
        }),
    }
}

/// Predicted nodes of a generated mesh with `knob` multiplied by `factor`
/// (None for given meshes, whose count is what it is).
fn generated(m: &MeshSpec, knob: Knob, factor: f64) -> Option<f64> {
    let scaled = |size: f64, g: Option<&GradingSpec>| {
        let size_f = if knob == Knob::Size { size * factor } else { size };
        let g = g.map(|g| Grading {
            h_min: (g.h_min * factor).min(size_f),
            ratio: g.ratio,
            extent: g.extent,
        });
        (size_f, g)
    };
    let t6 = |e: ElementKind| e == ElementKind::T6;
    match m {
        MeshSpec::Rectangle(r) => {
            let (size, g) = scaled(r.size, r.grading.as_ref());
            let focus = r
                .grading
                .as_ref()
                .and_then(|g| g.focus)
                .map_or([0.5 * r.width, r.height], |f| [f[0] - r.corner[0], f[1] - r.corner[1]]);
            let shape = Shape::Rectangle {
                w: r.width,
                h: r.height,
            };
            Some(estimate::nodes(shape, size, g.map(|g| (focus, g)), t6(r.element)))
        }
        MeshSpec::HalfDisk(d) | MeshSpec::QuarterDisk(d) => {
            let (size, g) = scaled(d.size, d.grading.as_ref());
            let shape = Shape::Disk {
                r: d.radius,
                quarter: matches!(m, MeshSpec::QuarterDisk(_)),
            };
            Some(estimate::nodes(
                shape,
                size,
                g.map(|g| ([0.0, -d.radius], g)),
                t6(d.element),
            ))
        }
        MeshSpec::Inline(_) | MeshSpec::Gmsh(_) => None,
    }
}

/// The refusal of a request whose bodies' predicted `nodes` exceed
/// `max_dofs`: it points at the field of the largest generated body that
/// brings the total under the limit (`grading/h_min` when raising it up to
/// `size` is enough, else `size`) and names the smallest accepted value.
pub(super) fn too_large(meshes: &[&MeshSpec], nodes: &[f64], max_dofs: usize) -> CoreError {
    let total: f64 = nodes.iter().sum();
    let requested = if total.is_finite() {
        format!(
            "about {:.0} degrees of freedom requested; this service accepts at most {max_dofs}",
            2.0 * total
        )
    } else {
        format!("more degrees of freedom requested than can be counted; this service accepts at most {max_dofs}")
    };
    let largest = (0..meshes.len())
        .filter(|&i| {
            matches!(
                meshes[i],
                MeshSpec::Rectangle(_) | MeshSpec::HalfDisk(_) | MeshSpec::QuarterDisk(_)
            )
        })
        .max_by(|&a, &b| nodes[a].total_cmp(&nodes[b]));
    let Some(i) = largest else {
        return CoreError::TooLarge {
            path: "/bodies".into(),
            reason: requested,
        };
    };
    let (kind, size, grading) = match meshes[i] {
        MeshSpec::Rectangle(r) => ("rectangle", r.size, r.grading.as_ref()),
        MeshSpec::HalfDisk(d) => ("half_disk", d.size, d.grading.as_ref()),
        MeshSpec::QuarterDisk(d) => ("quarter_disk", d.size, d.grading.as_ref()),
        _ => unreachable!("only generated meshes are coarsened"),
    };
    let path = format!("/bodies/{i}/mesh/{kind}");
    let allowed = 0.5 * max_dofs as f64 - (0..nodes.len()).filter(|&j| j != i).map(|j| nodes[j]).sum::<f64>();
    // NaN (an overflowing sum) counts as exceeded.
    let fits_at = |g: f64| g <= 0.0;
    if allowed.is_nan() || allowed <= 0.0 {
        return CoreError::TooLarge {
            path,
            reason: format!("{requested}; the other bodies alone exceed it"),
        };
    }
    let (knob, base, field) = match grading {
        Some(g) if count(meshes[i], Knob::HMin, size / g.h_min) <= allowed => (Knob::HMin, g.h_min, "grading/h_min"),
        _ => (Knob::Size, size, "size"),
    };
    // Smallest accepted factor: the count follows a power law in the knob
    // (h⁻² where the area dominates), so a secant in log-log space lands
    // within 0.5 % in a few estimates (each costs milliseconds; this runs on
    // the arrival path). The last step is taken up until the count fits.
    let target = allowed.ln();
    let uncountable = std::cell::Cell::new(0);
    let g = |x: f64| {
        let v = count(meshes[i], knob, x.exp()).ln() - target;
        if !v.is_finite() {
            uncountable.set(uncountable.get() + 1);
        }
        v
    };
    let (mut x0, mut g0) = (0.0, nodes[i].ln() - target);
    let mut x1 = if g0.is_finite() { 0.5 * g0.max(0.1) } else { 8.0 };
    let mut g1 = g(x1);
    // A count that stays uncountable (a focus 1e308 away) has no answer.
    let lost = || uncountable.get() >= 6;
    for _ in 0..12 {
        if g1.abs() < 0.005 || lost() {
            break;
        }
        let slope = (g1 - g0) / (x1 - x0);
        let next = if g1.is_finite() && g0.is_finite() && slope < -1e-3 {
            // Bounded steps: the law changes where the grading saturates.
            x1 - (g1 / slope).clamp(-2.0 * (x1 - x0).abs() - 1.0, 2.0 * (x1 - x0).abs() + 1.0)
        } else if g1.is_finite() {
            x1 + 1.0
        } else {
            x1 + 8.0
        };
        (x0, g0) = (x1, g1);
        x1 = next.max(0.0);
        g1 = g(x1);
    }
    let mut tries = 0;
    while !fits_at(g1) && tries < 40 && !lost() {
        x1 += if g1.is_finite() { g1.abs().max(0.002) } else { 8.0 };
        g1 = g(x1);
        tries += 1;
    }
    if !fits_at(g1) {
        return CoreError::TooLarge {
            path,
            reason: requested,
        };
    }
    let hi = x1.exp();
    let value = round_up(base * hi);
    let alike = if knob == Knob::Size && grading.is_some() {
        " with grading/h_min scaled alike"
    } else {
        ""
    };
    CoreError::TooLarge {
        path: format!("{path}/{field}"),
        reason: format!("{requested}; {field} {value} or more{alike} would be accepted (now {base})"),
    }
}

/// `generated`, with anything not countable (overflow) as infinite.
fn count(m: &MeshSpec, knob: Knob, factor: f64) -> f64 {
    match generated(m, knob, factor) {
        Some(n) if n.is_finite() => n,
        Some(_) => f64::INFINITY,
        None => 0.0,
    }
}

/// `x` rounded up to three significant digits, printed without float noise.
fn round_up(x: f64) -> String {
    let e = x.log10().floor() - 2.0;
    let unit = 10f64.powf(e);
    let v = (x / unit * (1.0 - 1e-12)).ceil() * unit;
    let decimals = (-e).max(0.0) as usize;
    format!("{v:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::round_up;

    #[test]
    fn rounding_up_keeps_three_digits() {
        assert_eq!(round_up(0.012_341), "0.0124");
        assert_eq!(round_up(0.0123), "0.0123");
        assert_eq!(round_up(12_341.0), "12400");
    }
}
