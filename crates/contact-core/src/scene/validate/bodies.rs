//! `bodies`: materials, meshes (generated, inline, Gmsh), supports, tractions
//! and body forces. The first pass reads what sets the scales (the largest
//! modulus and extent) and the size estimate; the second builds the bodies
//! in nondimensional form.

use std::collections::BTreeSet;

use contact_proto::{self as proto, ElementKind, MeshSpec, SolveRequest};

use super::{finite, invalid, poisson, positive, Limits};
use crate::error::{CoreError, InvalidKind, InvalidKind as K};
use crate::mesh::generate::{DiskPart, Grading};
use crate::mesh::{gmsh, quality, Order};
use crate::scene::{Body, MeshSource, PointLoad, Scales, Support, Traction};

/// What the first pass learns: the scales, each body's estimated node count
/// and bounding box (in the request's units), and the Gmsh files it parsed.
pub struct Survey {
    pub scales: Scales,
    pub nodes: Vec<f64>,
    pub boxes: Vec<([f64; 2], [f64; 2])>,
    pub parsed: Vec<Option<gmsh::Parsed>>,
}

/// The first pass: raw numbers, to choose the scales and estimate the size.
pub fn survey(req: &SolveRequest, limits: &Limits) -> Result<Survey, CoreError> {
    // First pass: raw numbers, to choose the scales.
    let mut length: f64 = 0.0;
    let mut modulus: f64 = 0.0;
    let mut nodes = Vec::with_capacity(req.bodies.len());
    let mut boxes = Vec::with_capacity(req.bodies.len());
    let mut parsed = Vec::with_capacity(req.bodies.len());
    for (i, b) in req.bodies.iter().enumerate() {
        let p = format!("/bodies/{i}/material");
        let e = positive(
            b.material.youngs_modulus,
            &format!("{p}/youngs_modulus"),
            K::Material,
            "Young's modulus",
        )?;
        poisson(b.material.poisson_ratio, &format!("{p}/poisson_ratio"))?;
        modulus = modulus.max(e);
        check_mesh_spec(&b.mesh, &format!("/bodies/{i}/mesh"))?;
        let file = match &b.mesh {
            MeshSpec::Gmsh(g) => Some(gmsh::try_parse(
                g.msh.as_deref().unwrap_or_default(),
                &g.surfaces,
                &format!("/bodies/{i}/mesh/gmsh/msh"),
            )?),
            _ => None,
        };
        let ((lo, hi), n) = crate::scene::size_limit::box_and_nodes(&b.mesh, file.as_ref());
        let ext = crate::mesh::box_extent(lo, hi);
        boxes.push((lo, hi));
        parsed.push(file);
        length = length.max(ext);
        nodes.push(n);
    }
    if !(length > 0.0 && length.is_finite()) {
        return Err(invalid(K::Mesh, "/bodies", "bodies have no extent"));
    }
    if 2.0 * nodes.iter().sum::<f64>() > limits.max_dofs as f64 {
        let meshes: Vec<&MeshSpec> = req.bodies.iter().map(|b| &b.mesh).collect();
        return Err(crate::scene::size_limit::too_large(&meshes, &nodes, limits.max_dofs));
    }
    for (i, b) in req.bodies.iter().enumerate() {
        check_aspect(&b.mesh, &format!("/bodies/{i}/mesh"))?;
    }

    Ok(Survey {
        scales: Scales {
            length,
            modulus,
            axisymmetric: req.analysis == proto::Analysis::Axisymmetric,
        },
        nodes,
        boxes,
        parsed,
    })
}

/// The bodies, nondimensional, and their names (for the pairs).
pub fn bodies(req: &SolveRequest, survey: &Survey) -> Result<(Vec<String>, Vec<Body>), CoreError> {
    let Scales { length, modulus, .. } = survey.scales;
    let force_unit = survey.scales.force_unit();
    let parsed = &survey.parsed;
    let l = |x: f64| x / length;
    let lp = |p: [f64; 2]| [p[0] / length, p[1] / length];
    let mut names = Vec::new();
    let mut bodies = Vec::new();
    for (i, b) in req.bodies.iter().enumerate() {
        let bp = format!("/bodies/{i}");
        let name = b.name.clone().unwrap_or_else(|| format!("body{i}"));
        if names.contains(&name) {
            return Err(invalid(
                K::Request,
                format!("{bp}/name"),
                format!("duplicate body name '{name}'"),
            ));
        }
        names.push(name.clone());
        let mesh = match &b.mesh {
            // In the request's units: a generated mesh depends on its own
            // body's parameters only, not on the length scale that other
            // bodies set (refinement is not continuous in round-off).
            MeshSpec::Rectangle(r) => MeshSource::Rectangle {
                corner: r.corner,
                width: r.width,
                height: r.height,
                size: r.size,
                grading: r.grading.as_ref().map(|g| {
                    (
                        g.focus.unwrap_or([r.corner[0] + 0.5 * r.width, r.corner[1] + r.height]),
                        grading(g),
                    )
                }),
                order: order(r.element),
            },
            MeshSpec::HalfDisk(d) | MeshSpec::QuarterDisk(d) => MeshSource::Disk {
                center: d.center,
                radius: d.radius,
                down: d.facing == proto::Facing::Down,
                part: match &b.mesh {
                    MeshSpec::QuarterDisk(_) => DiskPart::Quarter,
                    _ => DiskPart::Half,
                },
                size: d.size,
                grading: d.grading.as_ref().map(grading),
                order: order(d.element),
            },
            MeshSpec::Inline(m) => {
                let scaled: Vec<[f64; 2]> = m.nodes.iter().map(|&p| lp(p)).collect();
                let (nodes, ends) = m.elements.as_parts();
                MeshSource::Inline(quality::try_inline(
                    scaled,
                    quality::Conn::Ragged { nodes, ends },
                    &m.edge_sets,
                    &format!("{bp}/mesh/inline"),
                )?)
            }
            MeshSpec::Gmsh(_) => match &parsed[i] {
                Some(p) => MeshSource::Inline(p.try_mesh(length, &format!("{bp}/mesh/gmsh/msh"))?),
                None => unreachable!("every Gmsh body was parsed in the first pass"),
            },
        };
        let edges = edge_names(&b.mesh, parsed[i].as_ref());
        let need_edges = |name: &str, path: String| -> Result<(), CoreError> {
            if edges.contains(name) {
                Ok(())
            } else {
                Err(invalid(
                    K::Request,
                    path,
                    format!(
                        "no edge set named '{name}' on this body (it has: {})",
                        edges.iter().cloned().collect::<Vec<_>>().join(", ")
                    ),
                ))
            }
        };
        let mut supports = Vec::new();
        for (k, s) in b.supports.iter().enumerate() {
            let sp = format!("{bp}/supports/{k}");
            need_edges(&s.edges, format!("{sp}/edges"))?;
            if s.ux.is_none() && s.uy.is_none() {
                return Err(invalid(K::Request, sp, "a support must prescribe ux, uy or both"));
            }
            if let Some(v) = s.ux {
                finite(v, &format!("{sp}/ux"), K::Request)?;
            }
            if let Some(v) = s.uy {
                finite(v, &format!("{sp}/uy"), K::Request)?;
            }
            supports.push(Support {
                edges: s.edges.clone(),
                ux: s.ux.map(l),
                uy: s.uy.map(l),
            });
        }
        let mut tractions = Vec::new();
        for (k, t) in b.tractions.iter().enumerate() {
            let tp = format!("{bp}/tractions/{k}");
            need_edges(&t.edges, format!("{tp}/edges"))?;
            let x_range = match t.x_range {
                None => None,
                Some([a, c]) => {
                    finite(a, &format!("{tp}/x_range/0"), K::Request)?;
                    finite(c, &format!("{tp}/x_range/1"), K::Request)?;
                    if c <= a {
                        return Err(invalid(
                            K::Request,
                            format!("{tp}/x_range"),
                            format!("x_range must be [x_min, x_max] with x_max > x_min, got [{a}, {c}]"),
                        ));
                    }
                    Some([l(a), l(c)])
                }
            };
            match (t.traction, t.pressure) {
                (Some(v), None) => {
                    finite(v[0], &format!("{tp}/traction/0"), K::Request)?;
                    finite(v[1], &format!("{tp}/traction/1"), K::Request)?;
                    tractions.push(Traction::Vector {
                        edges: t.edges.clone(),
                        t: [v[0] / modulus, v[1] / modulus],
                        x_range,
                    });
                }
                (None, Some(p)) => {
                    finite(p, &format!("{tp}/pressure"), K::Request)?;
                    tractions.push(Traction::Pressure {
                        edges: t.edges.clone(),
                        p: p / modulus,
                        x_range,
                    });
                }
                _ => return Err(invalid(K::Request, tp, "give exactly one of 'traction' and 'pressure'")),
            }
        }
        let mut point_loads = Vec::new();
        for (k, pl) in b.point_loads.iter().enumerate() {
            let pp = format!("{bp}/point_loads/{k}");
            need_edges(&pl.edges, format!("{pp}/edges"))?;
            for (name, v) in [("at", pl.at), ("force", pl.force)] {
                finite(v[0], &format!("{pp}/{name}/0"), K::Request)?;
                finite(v[1], &format!("{pp}/{name}/1"), K::Request)?;
            }
            point_loads.push(PointLoad {
                edges: pl.edges.clone(),
                at: lp(pl.at),
                force: [pl.force[0] / force_unit, pl.force[1] / force_unit],
                path: pp,
            });
        }
        let bf = b.body_force.unwrap_or([0.0, 0.0]);
        finite(bf[0], &format!("{bp}/body_force/0"), K::Request)?;
        finite(bf[1], &format!("{bp}/body_force/1"), K::Request)?;
        let couplings = super::couplings::couplings(
            b,
            &bp,
            &edges,
            survey.boxes[i],
            survey.scales,
            req.analysis == proto::Analysis::Axisymmetric,
        )?;
        bodies.push(Body {
            name,
            youngs_modulus: b.material.youngs_modulus / modulus,
            poisson_ratio: b.material.poisson_ratio,
            mesh,
            supports,
            tractions,
            point_loads,
            body_force: [bf[0] * length / modulus, bf[1] * length / modulus],
            couplings,
            path: bp,
        });
    }

    Ok((names, bodies))
}

fn order(e: ElementKind) -> Order {
    match e {
        ElementKind::T3 => Order::T3,
        ElementKind::T6 => Order::T6,
    }
}

/// The request's grading, in the request's units (generated meshes are made
/// in them, see `MeshSource`).
fn grading(g: &proto::GradingSpec) -> Grading {
    Grading {
        h_min: g.h_min,
        ratio: g.ratio,
        extent: g.extent,
    }
}

pub fn edge_names(m: &MeshSpec, parsed: Option<&gmsh::Parsed>) -> BTreeSet<String> {
    let names: &[&str] = match m {
        MeshSpec::Gmsh(_) => {
            return parsed
                .map(|p| p.edge_sets.keys().cloned().collect())
                .unwrap_or_default()
        }
        MeshSpec::Rectangle(_) => &["bottom", "right", "top", "left"],
        MeshSpec::HalfDisk(_) => &["flat", "arc"],
        MeshSpec::QuarterDisk(_) => &["flat", "arc", "axis"],
        MeshSpec::Inline(i) => return i.edge_sets.keys().cloned().collect(),
    };
    names.iter().map(|s| s.to_string()).collect()
}

fn check_grading(g: &proto::GradingSpec, size: f64, path: &str) -> Result<(), CoreError> {
    check_grading_values(g.h_min, g.ratio, g.extent, size, path)?;
    if let Some(f) = g.focus {
        finite(f[0], &format!("{path}/focus/0"), K::Mesh)?;
        finite(f[1], &format!("{path}/focus/1"), K::Mesh)?;
    }
    Ok(())
}

/// A grading's `h_min` (at most the mesh's `size`), `ratio` and `extent`
/// (2D and 3D alike).
pub(super) fn check_grading_values(
    h_min: f64,
    ratio: f64,
    extent: f64,
    size: f64,
    path: &str,
) -> Result<(), CoreError> {
    positive(h_min, &format!("{path}/h_min"), K::Mesh, "h_min")?;
    if h_min > size {
        return Err(invalid(
            K::Mesh,
            format!("{path}/h_min"),
            format!("h_min ({h_min}) exceeds the element size ({size})"),
        ));
    }
    finite(ratio, &format!("{path}/ratio"), K::Mesh)?;
    if !(1.0..=2.0).contains(&ratio) {
        return Err(invalid(
            K::Mesh,
            format!("{path}/ratio"),
            format!("ratio must be in [1, 2], got {ratio}"),
        ));
    }
    if !(extent.is_finite() && extent >= 0.0) {
        return Err(invalid(
            K::Mesh,
            format!("{path}/extent"),
            format!("extent must be a finite non-negative length, got {extent}"),
        ));
    }
    Ok(())
}

/// Smallest side ratio of a generated rectangle: beyond it the sides are not
/// distinct in double precision once scaled (the thin-strip tests run at
/// 1/500). Checked after the size limit, which a thin rectangle of a sensible
/// element size exceeds first.
pub(super) const MIN_ASPECT: f64 = 1e-6;

fn check_aspect(m: &MeshSpec, path: &str) -> Result<(), CoreError> {
    let MeshSpec::Rectangle(r) = m else { return Ok(()) };
    let (thin, name) = if r.height < r.width {
        (r.height, "height")
    } else {
        (r.width, "width")
    };
    if thin < MIN_ASPECT * r.width.max(r.height) {
        return Err(invalid(
            InvalidKind::Mesh,
            format!("{path}/rectangle/{name}"),
            format!("the rectangle is too thin to mesh: {name} {thin} is less than {MIN_ASPECT:e} of its other side"),
        ));
    }
    Ok(())
}

fn check_mesh_spec(m: &MeshSpec, path: &str) -> Result<(), CoreError> {
    match m {
        MeshSpec::Rectangle(r) => {
            let p = format!("{path}/rectangle");
            finite(r.corner[0], &format!("{p}/corner/0"), K::Mesh)?;
            finite(r.corner[1], &format!("{p}/corner/1"), K::Mesh)?;
            positive(r.width, &format!("{p}/width"), K::Mesh, "width")?;
            positive(r.height, &format!("{p}/height"), K::Mesh, "height")?;
            positive(r.size, &format!("{p}/size"), K::Mesh, "size")?;
            if let Some(g) = &r.grading {
                check_grading(g, r.size, &format!("{p}/grading"))?;
            }
        }
        MeshSpec::HalfDisk(d) | MeshSpec::QuarterDisk(d) => {
            let kind = if matches!(m, MeshSpec::HalfDisk(_)) {
                "half_disk"
            } else {
                "quarter_disk"
            };
            let p = format!("{path}/{kind}");
            finite(d.center[0], &format!("{p}/center/0"), K::Mesh)?;
            finite(d.center[1], &format!("{p}/center/1"), K::Mesh)?;
            positive(d.radius, &format!("{p}/radius"), K::Mesh, "radius")?;
            positive(d.size, &format!("{p}/size"), K::Mesh, "size")?;
            if d.size > d.radius {
                return Err(invalid(K::Mesh, format!("{p}/size"), "size must not exceed the radius"));
            }
            if let Some(g) = &d.grading {
                check_grading(g, d.size, &format!("{p}/grading"))?;
            }
        }
        MeshSpec::Inline(m) => {
            let p = format!("{path}/inline");
            for (k, n) in m.nodes.iter().enumerate() {
                finite(n[0], &format!("{p}/nodes/{k}/0"), K::Mesh)?;
                finite(n[1], &format!("{p}/nodes/{k}/1"), K::Mesh)?;
            }
            if m.nodes.is_empty() {
                return Err(invalid(K::Mesh, format!("{p}/nodes"), "no nodes"));
            }
        }
        MeshSpec::Gmsh(g) => {
            let p = format!("{path}/gmsh");
            if g.file.is_some() {
                return Err(invalid(
                    K::Request,
                    format!("{p}/file"),
                    "a Gmsh file reference is read only by `contact solve FILE` (relative to the request file); send \
                        the file's text in `msh`",
                ));
            }
            if g.msh.is_none() {
                return Err(invalid(
                    K::Request,
                    p,
                    "a Gmsh mesh needs `msh`: the MSH 4.1 ASCII text",
                ));
            }
        }
    }
    Ok(())
}
