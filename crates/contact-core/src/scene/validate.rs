//! Request → Scene: every check of the request lives here, each failure with
//! the JSON pointer of the offending field.

use std::collections::BTreeSet;

use super::*;
use crate::error::{CoreError, InvalidKind};
use crate::mesh::generate::DiskPart;
use crate::mesh::{generate::Grading, gmsh, quality};
use crate::scene::{Psi, Punch};
use contact_proto::{self as proto, BodyRef, ElementKind, MeshSpec, ObstacleShape, OutputKind, SolveRequest};

/// Size limits of a deployment (the CLI and the service set them).
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Largest number of degrees of freedom (2 per node, before supports).
    pub max_dofs: usize,
    /// Largest number of contact candidates over all pairs. The condensed
    /// operator is dense: about 56·m² bytes (W, the trailing factor and Bᵀ), so
    /// 4000 candidates take about 0.9 GB.
    pub max_candidates: usize,
    /// Longest `load_factors` list: each factor is a full contact solve and,
    /// with `outputs`, a full set of fields in the reply.
    pub max_load_steps: usize,
    /// Most numbers the requested `outputs` may put in one reply, over all load
    /// steps (estimated from the mesh size before meshing): a displacement
    /// field is 2 per node and step, stresses 4, VTU about 8.
    pub max_output_values: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_dofs: 2_500_000,
            max_candidates: 4_000,
            max_load_steps: 100,
            // 2e7 numbers are about 400 MB of JSON: ten full-field steps of
            // a 500k-node mesh.
            max_output_values: 20_000_000,
        }
    }
}

/// Largest |factor| × (largest nondimensional load or prescribed motion): the
/// solve forms products of loads (W λ · λ, energies), which must stay finite,
/// and a strain of 1e150 is meaningless long before.
const MAX_SCALED_LOAD: f64 = 1e150;

/// The requested fields over all load steps, against `max_output_values`
/// (`nodes`: the estimated node count of all bodies).
fn check_output_size(outputs: &[OutputKind], steps: usize, nodes: f64, limits: &Limits) -> Result<(), CoreError> {
    let per_node: f64 = outputs
        .iter()
        .map(|o| match o {
            OutputKind::Displacement => 2.0,
            OutputKind::Stress => 4.0,
            OutputKind::Mesh => 0.0,
            OutputKind::Vtu => 8.0,
        })
        .sum();
    // The mesh is written once, not per step: 2 coordinates and about 3
    // element indices per node.
    let once = if outputs.contains(&OutputKind::Mesh) {
        5.0 * nodes
    } else {
        0.0
    };
    let values = per_node * nodes * steps.max(1) as f64 + once;
    if values <= limits.max_output_values as f64 {
        return Ok(());
    }
    Err(CoreError::TooLarge {
        path: "/outputs".into(),
        reason: format!(
            "the requested outputs over {} load step(s) come to about {:.3e} numbers; this service returns at most {} per reply (fewer load steps or outputs, or a coarser mesh)",
            steps.max(1),
            values,
            limits.max_output_values
        ),
    })
}

/// `load_factors`: a bounded list of finite factors whose scaled loads stay
/// representable. `size`: the largest nondimensional load or prescribed motion.
fn check_load_factors(factors: &[f64], size: f64, limits: &Limits) -> Result<(), CoreError> {
    if factors.len() > limits.max_load_steps {
        return Err(CoreError::TooLarge {
            path: "/load_factors".into(),
            reason: format!(
                "{} load factors; this service solves at most {} load steps per request (split the list)",
                factors.len(),
                limits.max_load_steps
            ),
        });
    }
    for (k, &f) in factors.iter().enumerate() {
        let path = format!("/load_factors/{k}");
        finite(f, &path, InvalidKind::Request)?;
        if f.abs() * size > MAX_SCALED_LOAD {
            return Err(invalid(
                InvalidKind::Request,
                path,
                format!(
                    "load factor {f:e} scales the loads beyond what the solve can represent (|factor| × load must stay below {MAX_SCALED_LOAD:e} in units of E·L)"
                ),
            ));
        }
    }
    Ok(())
}

fn invalid(kind: InvalidKind, path: impl Into<String>, reason: impl Into<String>) -> CoreError {
    CoreError::invalid(kind, path, reason)
}

fn finite(v: f64, path: &str, kind: InvalidKind) -> Result<f64, CoreError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(kind, path, format!("value {v} is not a finite number")))
    }
}

/// Poisson's ratio of an isotropic elastic material: −1 < ν < 0.5.
fn poisson(nu: f64, path: &str) -> Result<f64, CoreError> {
    finite(nu, path, InvalidKind::Material)?;
    if nu > -1.0 && nu < 0.5 {
        Ok(nu)
    } else {
        Err(invalid(
            InvalidKind::Material,
            path,
            format!("Poisson's ratio must satisfy -1 < nu < 0.5, got {nu}"),
        ))
    }
}

fn positive(v: f64, path: &str, kind: InvalidKind, what: &str) -> Result<f64, CoreError> {
    finite(v, path, kind)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(kind, path, format!("{what} must be positive, got {v}")))
    }
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

fn edge_names(m: &MeshSpec, parsed: Option<&gmsh::Parsed>) -> BTreeSet<String> {
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

fn resolve(r: &BodyRef, names: &[String], path: &str, what: &str) -> Result<usize, CoreError> {
    match r {
        BodyRef::Index(i) if *i < names.len() => Ok(*i),
        BodyRef::Index(i) => Err(invalid(
            InvalidKind::Request,
            path,
            format!("{what} index {i} out of range ({} given)", names.len()),
        )),
        BodyRef::Name(n) => names
            .iter()
            .position(|x| x == n)
            .ok_or_else(|| invalid(InvalidKind::Request, path, format!("no {what} named '{n}'"))),
    }
}

impl Scene {
    pub fn try_new(req: &SolveRequest, limits: &Limits) -> Result<Scene, CoreError> {
        use InvalidKind as K;
        if let Some(s) = req.time_limit.filter(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(invalid(
                K::Request,
                "/time_limit",
                format!("time_limit must be a positive number of seconds, got {s}"),
            ));
        }
        if req.version != proto::PROTOCOL_VERSION {
            return Err(invalid(
                K::Version,
                "/version",
                format!(
                    "version '{}' is not supported; this service speaks '{}'",
                    req.version,
                    proto::PROTOCOL_VERSION
                ),
            ));
        }
        if req.bodies.is_empty() {
            return Err(invalid(K::Request, "/bodies", "at least one body is required"));
        }
        // First pass: raw numbers, to choose the scales.
        let mut length: f64 = 0.0;
        let mut modulus: f64 = 0.0;
        let mut nodes = Vec::with_capacity(req.bodies.len());
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
            self::check_mesh_spec(&b.mesh, &format!("/bodies/{i}/mesh"))?;
            let file = match &b.mesh {
                MeshSpec::Gmsh(g) => Some(gmsh::try_parse(
                    g.msh.as_deref().unwrap_or_default(),
                    &g.surfaces,
                    &format!("/bodies/{i}/mesh/gmsh/msh"),
                )?),
                _ => None,
            };
            let (ext, n) = super::size_limit::extent_and_nodes(&b.mesh, file.as_ref());
            parsed.push(file);
            length = length.max(ext);
            nodes.push(n);
        }
        if !(length > 0.0 && length.is_finite()) {
            return Err(invalid(K::Mesh, "/bodies", "bodies have no extent"));
        }
        if 2.0 * nodes.iter().sum::<f64>() > limits.max_dofs as f64 {
            let meshes: Vec<&MeshSpec> = req.bodies.iter().map(|b| &b.mesh).collect();
            return Err(super::size_limit::too_large(&meshes, &nodes, limits.max_dofs));
        }
        for (i, b) in req.bodies.iter().enumerate() {
            check_aspect(&b.mesh, &format!("/bodies/{i}/mesh"))?;
        }
        let scales = Scales { length, modulus };
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
                    MeshSource::Inline(quality::try_inline(
                        &scaled,
                        &m.elements,
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
                match (t.traction, t.pressure) {
                    (Some(v), None) => {
                        finite(v[0], &format!("{tp}/traction/0"), K::Request)?;
                        finite(v[1], &format!("{tp}/traction/1"), K::Request)?;
                        tractions.push(Traction::Vector {
                            edges: t.edges.clone(),
                            t: [v[0] / modulus, v[1] / modulus],
                        });
                    }
                    (None, Some(p)) => {
                        finite(p, &format!("{tp}/pressure"), K::Request)?;
                        tractions.push(Traction::Pressure {
                            edges: t.edges.clone(),
                            p: p / modulus,
                        });
                    }
                    _ => return Err(invalid(K::Request, tp, "give exactly one of 'traction' and 'pressure'")),
                }
            }
            let bf = b.body_force.unwrap_or([0.0, 0.0]);
            finite(bf[0], &format!("{bp}/body_force/0"), K::Request)?;
            finite(bf[1], &format!("{bp}/body_force/1"), K::Request)?;
            bodies.push(Body {
                name,
                youngs_modulus: b.material.youngs_modulus / modulus,
                poisson_ratio: b.material.poisson_ratio,
                mesh,
                supports,
                tractions,
                body_force: [bf[0] * length / modulus, bf[1] * length / modulus],
                path: bp,
            });
        }

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
                    let scale = |c: proto::Control, k: usize, name: &str| -> Result<Control, CoreError> {
                        let (v, is_load) = match c {
                            proto::Control::Displacement(v) => (v, false),
                            proto::Control::Load(v) => (v, true),
                        };
                        let kind = if is_load { "load" } else { "displacement" };
                        finite(v, &format!("{pth}/{name}/{kind}"), K::Request)?;
                        Ok(match (is_load, k) {
                            (false, 2) => Control::Displacement(v),
                            (false, _) => Control::Displacement(v / length),
                            (true, 2) => Control::Load(v / (modulus * length * length)),
                            (true, _) => Control::Load(v / (modulus * length)),
                        })
                    };
                    Some(Punch {
                        reference: lp(pp.reference),
                        controls: [
                            scale(pp.horizontal, 0, "horizontal")?,
                            scale(pp.vertical, 1, "vertical")?,
                            scale(pp.rotation, 2, "rotation")?,
                        ],
                    })
                }
            };
            obstacles.push(Obstacle { name, shape, punch });
        }

        let mut foundation_names = Vec::new();
        let mut foundations = Vec::new();
        for (i, f) in req.foundations.iter().enumerate() {
            let fp = format!("/foundations/{i}");
            let name = f.name.clone().unwrap_or_else(|| format!("foundation{i}"));
            if foundation_names.contains(&name) {
                return Err(invalid(
                    K::Request,
                    format!("{fp}/name"),
                    format!("duplicate foundation name '{name}'"),
                ));
            }
            foundation_names.push(name.clone());
            let y = finite(f.y, &format!("{fp}/y"), K::Geometry)?;
            let x_min = finite(f.x_min, &format!("{fp}/x_min"), K::Geometry)?;
            let x_max = finite(f.x_max, &format!("{fp}/x_max"), K::Geometry)?;
            if x_max <= x_min {
                return Err(invalid(
                    K::Geometry,
                    format!("{fp}/x_max"),
                    format!("the foundation must have x_max > x_min, got [{x_min}, {x_max}]"),
                ));
            }
            let mp = format!("{fp}/model");
            let model = match &f.model {
                proto::FoundationModel::Winkler { stiffness } => FoundationModel::Winkler {
                    k: positive(
                        *stiffness,
                        &format!("{mp}/winkler/stiffness"),
                        K::Material,
                        "the Winkler stiffness",
                    )? * length
                        / modulus,
                },
                proto::FoundationModel::Pasternak { stiffness, shear } => {
                    let k = positive(
                        *stiffness,
                        &format!("{mp}/pasternak/stiffness"),
                        K::Material,
                        "the Pasternak stiffness",
                    )?;
                    let mu = finite(*shear, &format!("{mp}/pasternak/shear"), K::Material)?;
                    if mu < 0.0 {
                        return Err(invalid(
                            K::Material,
                            format!("{mp}/pasternak/shear"),
                            format!("the shear layer's μ must be ≥ 0, got {mu}"),
                        ));
                    }
                    FoundationModel::Pasternak {
                        k: k * length / modulus,
                        mu: mu / (modulus * length),
                    }
                }
                proto::FoundationModel::HalfPlane {
                    youngs_modulus,
                    poisson_ratio,
                    reference_distance,
                } => {
                    let hp = format!("{mp}/half_plane");
                    let e = positive(
                        *youngs_modulus,
                        &format!("{hp}/youngs_modulus"),
                        K::Material,
                        "Young's modulus",
                    )?;
                    let nu = poisson(*poisson_ratio, &format!("{hp}/poisson_ratio"))?;
                    let d = positive(
                        *reference_distance,
                        &format!("{hp}/reference_distance"),
                        K::Geometry,
                        "the reference distance",
                    )?;
                    FoundationModel::HalfPlane {
                        e_star: e / (1.0 - nu * nu) / modulus,
                        d: d / length,
                    }
                }
            };
            foundations.push(Foundation {
                name,
                y: y / length,
                x_min: x_min / length,
                x_max: x_max / length,
                model,
            });
        }

        if req.contacts.is_empty() {
            return Err(invalid(
                K::NoContactCandidates,
                "/contacts",
                "at least one contact pair is required",
            ));
        }
        let mut pairs = Vec::new();
        let mut notes = Vec::new();
        for (k, c) in req.contacts.iter().enumerate() {
            let cp = format!("/contacts/{k}");
            let body = resolve(&c.body, &names, &format!("{cp}/body"), "body")?;
            let has_edges = |b: usize, edges: &str, path: String| {
                if edge_names(&req.bodies[b].mesh, parsed[b].as_ref())
                    .iter()
                    .any(|e| e == edges)
                {
                    Ok(())
                } else {
                    Err(invalid(
                        K::Request,
                        path,
                        format!("body '{}' has no edge set named '{}'", names[b], edges),
                    ))
                }
            };
            has_edges(body, &c.edges, format!("{cp}/edges"))?;
            let target = match (&c.obstacle, &c.against, &c.foundation) {
                (Some(o), None, None) => {
                    Target::Obstacle(resolve(o, &obstacle_names, &format!("{cp}/obstacle"), "obstacle")?)
                }
                (None, None, Some(f)) => {
                    Target::Foundation(resolve(f, &foundation_names, &format!("{cp}/foundation"), "foundation")?)
                }
                (None, Some(a), None) => {
                    let other = resolve(&a.body, &names, &format!("{cp}/against/body"), "body")?;
                    if other == body {
                        return Err(invalid(
                            K::Request,
                            format!("{cp}/against/body"),
                            "a body cannot be in contact with itself (self-contact is not supported)",
                        ));
                    }
                    has_edges(other, &a.edges, format!("{cp}/against/edges"))?;
                    Target::Body {
                        body: other,
                        edges: a.edges.clone(),
                        discretization: discretization(c.discretization),
                    }
                }
                _ => {
                    return Err(invalid(
                        K::Request,
                        cp.clone(),
                        "a contact pair names exactly one of 'obstacle' (rigid), 'against' (another body's edge set) or 'foundation'",
                    ))
                }
            };
            // The side that carries the pressure (slave) must be the softer one:
            // a stiff slave's pressure oscillates from node to node (measured 80 %
            // at a stiffness ratio of 1e6, against 2 % the other way round).
            let stiffness = |b: usize| {
                let m = &req.bodies[b].material;
                match req.analysis {
                    proto::Analysis::PlaneStrain => m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio),
                    proto::Analysis::PlaneStress => m.youngs_modulus,
                }
            };
            let (body, edges, target) = match target {
                Target::Body {
                    body: other,
                    edges: other_edges,
                    discretization,
                } if stiffness(body) > SWAP_STIFFNESS_RATIO * stiffness(other) => {
                    notes.push(format!(
                        "contact pair {k}: body '{}' is {:.1e} times stiffer than '{}', so '{}' carries the pressure (its edge set '{}' is the slave side) and the pair is reported that way round",
                        names[body],
                        stiffness(body) / stiffness(other),
                        names[other],
                        names[other],
                        other_edges
                    ));
                    (
                        other,
                        other_edges,
                        Target::Body {
                            body,
                            edges: c.edges.clone(),
                            discretization,
                        },
                    )
                }
                t => (body, c.edges.clone(), t),
            };
            pairs.push(Pair {
                body,
                edges,
                target,
                path: cp,
            });
        }

        let s = &req.settings;
        let tol = positive(s.tolerance, "/settings/tolerance", K::Request, "tolerance")?;
        if tol >= 1e-2 {
            return Err(invalid(
                K::Request,
                "/settings/tolerance",
                "tolerance must be below 1e-2",
            ));
        }
        if s.max_iterations == 0 || s.max_iterations > 100_000 {
            return Err(invalid(
                K::Request,
                "/settings/max_iterations",
                "max_iterations must be between 1 and 100000",
            ));
        }
        positive(
            s.prune_gap_ratio,
            "/settings/prune_gap_ratio",
            K::Request,
            "prune_gap_ratio",
        )?;

        let load_size = bodies
            .iter()
            .flat_map(|b| {
                let supports = b.supports.iter().flat_map(|s| [s.ux, s.uy]).flatten();
                let tractions = b.tractions.iter().flat_map(|t| match t {
                    Traction::Vector { t, .. } => vec![t[0], t[1]],
                    Traction::Pressure { p, .. } => vec![*p],
                });
                supports.chain(tractions).chain(b.body_force).collect::<Vec<f64>>()
            })
            .fold(0.0f64, |a, v| a.max(v.abs()));
        check_load_factors(&req.load_factors, load_size, limits)?;
        check_output_size(&req.outputs, req.load_factors.len(), nodes.iter().sum(), limits)?;

        let settings = Settings {
            tolerance: tol,
            max_iterations: s.max_iterations,
            prune_gap_ratio: s.prune_gap_ratio,
            formulation: match s.formulation {
                proto::Formulation::Condensed => Formulation::Condensed,
                proto::Formulation::Full => Formulation::Full,
            },
            gap: match s.gap {
                proto::GapMeasure::SignedDistance => GapMeasure::SignedDistance,
                proto::GapMeasure::BodyNormal => GapMeasure::BodyNormal,
            },
            // ζ is a compliance [length / pressure], the barrier a pressure × length.
            penalty: match s.penalty {
                Some(z) => positive(z, "/settings/penalty", K::Request, "penalty")? * scales.modulus / scales.length,
                None => Settings::default().penalty,
            },
            barrier: match s.barrier {
                Some(z) => positive(z, "/settings/barrier", K::Request, "barrier")? / (scales.modulus * scales.length),
                None => Settings::default().barrier,
            },
        };
        Ok(Scene {
            analysis: match req.analysis {
                proto::Analysis::PlaneStrain => Analysis::PlaneStrain,
                proto::Analysis::PlaneStress => Analysis::PlaneStress,
            },
            scales,
            bodies,
            obstacles,
            foundations,
            pairs,
            method: match req.method {
                proto::MethodName::Auto => Method::Auto,
                proto::MethodName::ActiveSet => Method::ActiveSet,
                proto::MethodName::InteriorPoint => Method::InteriorPoint,
                proto::MethodName::Penalty => Method::Penalty,
                proto::MethodName::AugmentedLagrangian => Method::AugmentedLagrangian,
                proto::MethodName::Barrier => Method::Barrier,
            },
            settings,
            outputs: Outputs {
                displacement: req.outputs.contains(&OutputKind::Displacement),
                mesh: req.outputs.contains(&OutputKind::Mesh),
                stress: req.outputs.contains(&OutputKind::Stress),
                vtu: req.outputs.contains(&OutputKind::Vtu),
            },
            client_id: req.client_id.clone(),
            time_limit: req.time_limit,
            notes,
            load_factors: req.load_factors.clone(),
        })
    }
}

fn discretization(d: proto::Discretization) -> Discretization {
    match d {
        proto::Discretization::Mortar => Discretization::Mortar,
        proto::Discretization::NodeToSegment => Discretization::NodeToSegment,
    }
}

/// A two-body pair whose named body is this many times stiffer than the other
/// is turned round, so that the softer body carries the pressure.
const SWAP_STIFFNESS_RATIO: f64 = 10.0;

fn check_grading(g: &proto::GradingSpec, size: f64, path: &str) -> Result<(), CoreError> {
    use InvalidKind as K;
    positive(g.h_min, &format!("{path}/h_min"), K::Mesh, "h_min")?;
    if g.h_min > size {
        return Err(invalid(
            K::Mesh,
            format!("{path}/h_min"),
            format!("h_min ({}) exceeds the element size ({size})", g.h_min),
        ));
    }
    finite(g.ratio, &format!("{path}/ratio"), K::Mesh)?;
    if !(g.ratio >= 1.0 && g.ratio <= 2.0) {
        return Err(invalid(
            K::Mesh,
            format!("{path}/ratio"),
            format!("ratio must be in [1, 2], got {}", g.ratio),
        ));
    }
    if !(g.extent.is_finite() && g.extent >= 0.0) {
        return Err(invalid(
            K::Mesh,
            format!("{path}/extent"),
            format!("extent must be a finite non-negative length, got {}", g.extent),
        ));
    }
    if let Some(f) = g.focus {
        finite(f[0], &format!("{path}/focus/0"), K::Mesh)?;
        finite(f[1], &format!("{path}/focus/1"), K::Mesh)?;
    }
    Ok(())
}

/// Smallest side ratio of a generated rectangle: beyond it the sides are not
/// distinct in double precision once scaled (the thin-strip tests run at
/// 1/500). Checked after the size limit, which a thin rectangle of a sensible
/// element size exceeds first.
const MIN_ASPECT: f64 = 1e-6;

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
    use InvalidKind as K;
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
                    "a Gmsh file reference is read only by `contact solve FILE` (relative to the request file); send the file's text in `msh`",
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

/// Profile points (t, ψ): at least two, finite, t strictly increasing; scaled by 1/length.
fn profile_points(points: &[[f64; 2]], path: &str, length: f64) -> Result<Vec<[f64; 2]>, CoreError> {
    use InvalidKind as K;
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
