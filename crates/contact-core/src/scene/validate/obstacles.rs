//! `obstacles`: rigid shapes (line, circle, polyline, punch profile) and the
//! rigid-motion controls of punches, nondimensional.

use contact_proto::{self as proto, ObstacleShape, SolveRequest};

use super::{finite, invalid, positive};
use crate::error::{CoreError, InvalidKind as K};
use crate::scene::{Control, Obstacle, Psi, Punch, Scales, Shape};

/// The obstacles and their names (for the pairs).
pub fn obstacles(req: &SolveRequest, scales: Scales) -> Result<(Vec<String>, Vec<Obstacle>), CoreError> {
    let Scales { length, .. } = scales;
    let l = |x: f64| x / length;
    let lp = |p: [f64; 2]| [p[0] / length, p[1] / length];
    let mut obstacle_names = Vec::new();
    let mut obstacles = Vec::new();
    for (i, o) in req.obstacles.iter().enumerate() {
        let op = format!("/obstacles/{i}/shape");
        let name = o.name.clone().unwrap_or_else(|| format!("obstacle{i}"));
        if obstacle_names.contains(&name) {
            return Err(invalid(
                K::Request,
                format!("/obstacles/{i}/name"),
                format!("duplicate obstacle name '{name}'"),
            ));
        }
        obstacle_names.push(name.clone());
        let shape = match &o.shape {
            ObstacleShape::Line { point, normal } => {
                for (k, v) in point.iter().chain(normal).enumerate() {
                    finite(
                        *v,
                        &format!("{op}/line/{}/{}", if k < 2 { "point" } else { "normal" }, k % 2),
                        K::Geometry,
                    )?;
                }
                let nn = (normal[0] * normal[0] + normal[1] * normal[1]).sqrt();
                if nn == 0.0 {
                    return Err(invalid(
                        K::Geometry,
                        format!("{op}/line/normal"),
                        "normal must be a nonzero vector",
                    ));
                }
                Shape::Line {
                    point: lp(*point),
                    normal: [normal[0] / nn, normal[1] / nn],
                }
            }
            ObstacleShape::Circle { center, radius } => {
                finite(center[0], &format!("{op}/circle/center/0"), K::Geometry)?;
                finite(center[1], &format!("{op}/circle/center/1"), K::Geometry)?;
                positive(*radius, &format!("{op}/circle/radius"), K::Geometry, "radius")?;
                Shape::Circle {
                    center: lp(*center),
                    radius: l(*radius),
                }
            }
            ObstacleShape::Profile { reference, psi } => {
                finite(reference[0], &format!("{op}/profile/reference/0"), K::Geometry)?;
                finite(reference[1], &format!("{op}/profile/reference/1"), K::Geometry)?;
                let pp = format!("{op}/profile/psi");
                let psi = match psi {
                    proto::ProfileSpec::Flat {
                        half_width,
                        corner_radius,
                    } => {
                        positive(*half_width, &format!("{pp}/flat/half_width"), K::Geometry, "half_width")?;
                        finite(*corner_radius, &format!("{pp}/flat/corner_radius"), K::Geometry)?;
                        if *corner_radius < 0.0 || *corner_radius > *half_width {
                            return Err(invalid(
                                K::Geometry,
                                format!("{pp}/flat/corner_radius"),
                                "corner_radius must lie in [0, half_width]",
                            ));
                        }
                        Psi::Flat {
                            half_width: l(*half_width),
                            corner_radius: l(*corner_radius),
                        }
                    }
                    proto::ProfileSpec::Circle { radius } => {
                        positive(*radius, &format!("{pp}/circle/radius"), K::Geometry, "radius")?;
                        Psi::Circle { radius: l(*radius) }
                    }
                    proto::ProfileSpec::Polyline { points } => {
                        Psi::Points(profile_points(points, &format!("{pp}/polyline/points"), length)?)
                    }
                    proto::ProfileSpec::Table { t, psi } => {
                        if t.len() != psi.len() {
                            return Err(invalid(
                                K::Geometry,
                                format!("{pp}/table/psi"),
                                format!("{} values of psi for {} values of t", psi.len(), t.len()),
                            ));
                        }
                        let pts: Vec<[f64; 2]> = t.iter().zip(psi).map(|(a, b)| [*a, *b]).collect();
                        Psi::Points(profile_points(&pts, &format!("{pp}/table/t"), length)?)
                    }
                };
                Shape::Profile {
                    reference: lp(*reference),
                    psi,
                }
            }
            ObstacleShape::Polyline { points } => {
                if points.len() < 2 {
                    return Err(invalid(
                        K::Geometry,
                        format!("{op}/polyline/points"),
                        "a polyline needs at least 2 points",
                    ));
                }
                for (k, p) in points.iter().enumerate() {
                    finite(p[0], &format!("{op}/polyline/points/{k}/0"), K::Geometry)?;
                    finite(p[1], &format!("{op}/polyline/points/{k}/1"), K::Geometry)?;
                    if k > 0 && points[k - 1] == *p {
                        return Err(invalid(
                            K::Geometry,
                            format!("{op}/polyline/points/{k}"),
                            "zero-length polyline segment",
                        ));
                    }
                }
                Shape::Polyline {
                    points: points.iter().map(|&p| lp(p)).collect(),
                }
            }
        };
        let punch = match &o.punch {
            None => None,
            Some(pp) => {
                let pth = format!("/obstacles/{i}/punch");
                finite(pp.reference[0], &format!("{pth}/reference/0"), K::Geometry)?;
                finite(pp.reference[1], &format!("{pth}/reference/1"), K::Geometry)?;
                let scale = |c: proto::Control, k: usize, name: &str| {
                    super::couplings::control(c, k, &format!("{pth}/{name}"), scales)
                };
                let mut controls = [
                    scale(pp.horizontal, 0, "horizontal")?,
                    scale(pp.vertical, 1, "vertical")?,
                    scale(pp.rotation, 2, "rotation")?,
                ];
                if req.analysis == proto::Analysis::Axisymmetric {
                    for (k, c, name) in [(0, pp.horizontal, "horizontal"), (2, pp.rotation, "rotation")] {
                        let (v, kind) = match c {
                            proto::Control::Displacement(v) => (v, "displacement"),
                            proto::Control::Load(v) => (v, "load"),
                        };
                        if v != 0.0 {
                            return Err(invalid(
                                K::Request,
                                format!("{pth}/{name}/{kind}"),
                                format!(
                                    "a punch of revolution moves along the axis only: its {name} {kind} must be 0 \
                                    (left out), got {v}"
                                ),
                            ));
                        }
                        // Held, not left free under a zero load: no row of a
                        // body of revolution resists it.
                        controls[k] = Control::Displacement(0.0);
                    }
                }
                Some(Punch {
                    reference: lp(pp.reference),
                    controls,
                })
            }
        };
        obstacles.push(Obstacle { name, shape, punch });
    }

    Ok((obstacle_names, obstacles))
}

/// Profile points (t, ψ): at least two, finite, t strictly increasing; scaled by 1/length.
fn profile_points(points: &[[f64; 2]], path: &str, length: f64) -> Result<Vec<[f64; 2]>, CoreError> {
    if points.len() < 2 {
        return Err(invalid(K::Geometry, path, "a profile needs at least 2 points"));
    }
    for (k, p) in points.iter().enumerate() {
        finite(p[0], &format!("{path}/{k}"), K::Geometry)?;
        finite(p[1], &format!("{path}/{k}"), K::Geometry)?;
        if k > 0 && p[0] <= points[k - 1][0] {
            return Err(invalid(
                K::Geometry,
                format!("{path}/{k}"),
                "profile abscissae must increase strictly",
            ));
        }
    }
    Ok(points.iter().map(|p| [p[0] / length, p[1] / length]).collect())
}
