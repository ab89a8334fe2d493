//! `analysis: "solid"`: the request's `solid` section → `SolidScene`. Every
//! refusal names the JSON pointer of the field at fault. What needs the
//! tetrahedra is `solid::door`'s, right after this one, with the pointers
//! this one hands it: the checks of a given mesh (inverted or degenerate
//! tetrahedra, T10 maps that fold, face sets that are not boundary faces,
//! `mesh3d::quality`) and the face-set names. The size limit is judged
//! before any mesh is built: a box's node count is exact from its grid
//! lines (`box_nodes`), an inline mesh's is its own (a Gmsh text's is
//! judged once read).

use contact_proto::{self as proto, InitialGapSpec, OutputKind, SolidMeshSpec, SolveRequest};

use super::{finite, invalid, poisson, positive, settings as wire_settings, Limits};
use crate::error::{CoreError, InvalidKind as K};
use crate::mesh::generate::Grading;
use crate::scene::solid::{cells_bound, grid_nodes, FaceLoad, Obstacle, SolidMesh, SolidScene, Support};
use crate::scene::{Method, Settings};

/// The solid scene of `req`, whose `analysis` is `solid`.
pub fn solid_scene(req: &SolveRequest, limits: &Limits) -> Result<SolidScene, CoreError> {
    let time_limit = wire_settings::time_limit(req)?;
    super::version(req)?;
    let Some(spec) = &req.solid else {
        return Err(invalid(
            K::Request,
            "/solid",
            "`analysis: \"solid\"` needs the `solid` section",
        ));
    };
    not_2d(req)?;
    let method = wire_settings::method(req);
    if !matches!(method, Method::Auto | Method::ActiveSet) {
        return Err(invalid(
            K::Request,
            "/method",
            "a 3D solid is solved by the condensed active set only: give `auto` or `active_set`",
        ));
    }
    let settings = settings(req)?;
    wire_settings::units(req)?;
    let b = &spec.body;
    let bp = "/solid/body";
    let e = positive(
        b.material.youngs_modulus,
        &format!("{bp}/material/youngs_modulus"),
        K::Material,
        "Young's modulus",
    )?;
    let nu = poisson(b.material.poisson_ratio, &format!("{bp}/material/poisson_ratio"))?;
    let (length, estimated_nodes, mesh) = mesh(&b.mesh, limits, &format!("{bp}/mesh"))?;
    // Refined, the fields are the last round's: up to the rounds' budget.
    let answered_nodes = match &req.settings.accuracy {
        Some(a) => estimated_nodes.max(a.max_dofs.min(limits.max_dofs) as f64 / 3.0),
        None => estimated_nodes,
    };
    output_size(&req.outputs, answered_nodes, &mesh, limits)?;
    let mut supports = Vec::with_capacity(b.supports.len());
    for (k, s) in b.supports.iter().enumerate() {
        let sp = format!("{bp}/supports/{k}");
        let faces = s.faces.clone();
        let given = [("ux", s.ux), ("uy", s.uy), ("uz", s.uz)];
        if given.iter().all(|g| g.1.is_none()) {
            return Err(invalid(
                K::Request,
                sp,
                "a support must prescribe at least one of ux, uy, uz",
            ));
        }
        let mut fix = [None; 3];
        for (c, (name, v)) in given.into_iter().enumerate() {
            if let Some(v) = v {
                fix[c] = Some(finite(v, &format!("{sp}/{name}"), K::Request)? / length);
            }
        }
        supports.push(Support { faces, fix });
    }
    let mut loads = Vec::with_capacity(b.tractions.len());
    for (k, t) in b.tractions.iter().enumerate() {
        let tp = format!("{bp}/tractions/{k}");
        let faces = t.faces.clone();
        loads.push(match (t.traction, t.pressure) {
            (Some(v), None) => {
                for (c, x) in v.iter().enumerate() {
                    finite(*x, &format!("{tp}/traction/{c}"), K::Request)?;
                }
                FaceLoad::Traction {
                    faces,
                    t: v.map(|x| x / e),
                }
            }
            (None, Some(p)) => FaceLoad::Pressure {
                faces,
                p: finite(p, &format!("{tp}/pressure"), K::Request)? / e,
            },
            _ => return Err(invalid(K::Request, tp, "give one of `traction` and `pressure`")),
        });
    }
    let mut body_force = [0.0; 3];
    if let Some(f) = b.body_force {
        for (c, x) in f.iter().enumerate() {
            // A force per volume times a length is a stress.
            body_force[c] = finite(*x, &format!("{bp}/body_force/{c}"), K::Request)? * length / e;
        }
    }
    let scales = crate::scene::Scales {
        length,
        modulus: e,
        axisymmetric: true,
    };
    // The largest nondimensional load or prescribed value of each entry, as
    // 2D judges them; a solid's forces are totals (force unit E·L², as a
    // body of revolution's).
    let sizes = super::solid_load_path::Sizes::of(&supports, &loads, body_force);
    // A path's steps are judged instead (`check_steps`): only they are solved.
    if req.load_factors.is_empty() && req.load_path.is_empty() {
        sizes.check_base(scales)?;
    } else {
        wire_settings::check_load_factors(&req.load_factors, sizes.largest(), scales, limits)?;
    }
    let load_path = super::solid_load_path::solid_load_path(req, b, limits)?;
    sizes.check_steps(&load_path, scales)?;
    let shape = super::solid_obstacle::obstacle(spec, length)?;
    // The face-set names are checked against the mesh by `solid::door`.
    let faces = spec.contact.faces.clone();
    let paraboloid = match &spec.contact.initial_gap {
        None => None,
        Some(_) if !matches!(shape, Obstacle::Plane(_)) => {
            return Err(invalid(
                K::Request,
                "/solid/contact/initial_gap",
                "an initial gap profile stands a flat face for a curved one against a plane: give the obstacle's \
                    own shape (sphere, cylinder, paraboloid, height field) instead",
            ));
        }
        Some(InitialGapSpec::Paraboloid { apex, radius }) => {
            let gp = "/solid/contact/initial_gap/paraboloid";
            for (c, x) in apex.iter().enumerate() {
                finite(*x, &format!("{gp}/apex/{c}"), K::Geometry)?;
            }
            let r = positive(*radius, &format!("{gp}/radius"), K::Geometry, "the paraboloid's radius")?;
            Some((apex.map(|x| x / length), r / length))
        }
    };
    Ok(SolidScene {
        length,
        modulus: e,
        body: b.name.clone().unwrap_or_else(|| "body0".into()),
        obstacle: spec.obstacle.name.clone().unwrap_or_else(|| "obstacle0".into()),
        mesh,
        poisson_ratio: nu,
        supports,
        loads,
        body_force,
        shape,
        faces,
        paraboloid,
        settings,
        outputs: wire_settings::outputs(req),
        client_id: req.client_id.clone(),
        time_limit,
        estimated_nodes,
        load_factors: req.load_factors.clone(),
        load_path,
    })
}

/// The 2D sections stay empty, and what the 3D route does not do is
/// refused rather than ignored.
fn not_2d(req: &SolveRequest) -> Result<(), CoreError> {
    let unused = [
        ("/bodies", req.bodies.is_empty()),
        ("/obstacles", req.obstacles.is_empty()),
        ("/foundations", req.foundations.is_empty()),
        ("/contacts", req.contacts.is_empty()),
    ];
    if let Some((path, _)) = unused.iter().find(|u| !u.1) {
        return Err(invalid(
            K::Request,
            *path,
            "a 3D solid is described in `solid` alone: leave the 2D sections (bodies, obstacles, foundations, \
                contacts) out",
        ));
    }
    if req.settings.formulation == proto::Formulation::Full {
        return Err(invalid(
            K::Request,
            "/settings/formulation",
            "a 3D solid is solved on the condensed formulation only",
        ));
    }
    Ok(())
}

/// The settings the 3D route reads: tolerance and iteration cap, checked as
/// in 2D.
/// The outputs of a solid against the numbers a reply may carry
/// (`max_output_values`, as 2D's `check_output_size`): per node its
/// coordinates and displacement, per tetrahedron its nodes, stress tensor and
/// the VTU's cell arrays. A linear tetrahedral mesh has about 5.5 tetrahedra
/// per node (Euler's relation for a mesh of good quality), a quadratic one
/// about 0.75 (each tetrahedron adds its six edges' midsides, shared by about
/// five); an inline mesh counts its own.
fn output_size(outputs: &[OutputKind], nodes: f64, mesh: &SolidMesh, limits: &Limits) -> Result<(), CoreError> {
    if outputs.is_empty() {
        return Ok(());
    }
    let (tets, k) = match mesh {
        SolidMesh::Box { t10: true, .. } => (0.75 * nodes, 10.0),
        // Refined in rounds (`settings.accuracy`), the mesh keeps its
        // tetrahedra per node: eight times the tetrahedra, about as many
        // times the nodes.
        SolidMesh::Inline {
            ends,
            elements,
            nodes: given,
            ..
        } if !ends.is_empty() => (
            ends.len() as f64 * nodes / given.len().max(1) as f64,
            elements.len() as f64 / ends.len() as f64,
        ),
        _ => (5.5 * nodes, 4.0),
    };
    let values: f64 = outputs
        .iter()
        .map(|o| match o {
            OutputKind::Displacement => 3.0 * nodes,
            OutputKind::Mesh => 3.0 * nodes + k * tets,
            OutputKind::Stress => 6.0 * tets,
            // Points, displacement, pressure; connectivity, offsets, types,
            // the tensor, von Mises and the principal stresses.
            OutputKind::Vtu => 7.0 * nodes + (k + 12.0) * tets,
        })
        .sum();
    wire_settings::within_output_limit(values, "", "", limits)
}

/// A given mesh's `settings.accuracy` refines it uniformly (`adapt::solid`),
/// a box's regrades it: both take the same target.
fn settings(req: &SolveRequest) -> Result<Settings, CoreError> {
    let (tolerance, max_iterations) = wire_settings::iteration(req)?;
    let accuracy = match &req.settings.accuracy {
        None => None,
        Some(t) if t.zone_edge.is_some() => {
            return Err(invalid(
                K::Request,
                "/settings/accuracy/zone_edge",
                "a 3D solid's patches have no zone ends: give pressure_l2",
            ));
        }
        Some(t) => Some(wire_settings::accuracy_target(t)?),
    };
    Ok(Settings {
        tolerance,
        max_iterations,
        estimate: req.settings.estimate,
        accuracy,
        ..Settings::default()
    })
}

/// The length scale, the predicted node count and the mesh (a box's
/// parameters, or a checked given mesh).
fn mesh(m: &SolidMeshSpec, limits: &Limits, path: &str) -> Result<(f64, f64, SolidMesh), CoreError> {
    let (length, nodes, mesh) = match m {
        SolidMeshSpec::Box(b) => {
            let p = format!("{path}/box");
            for c in 0..3 {
                finite(b.corner[c], &format!("{p}/corner/{c}"), K::Mesh)?;
                positive(b.lengths[c], &format!("{p}/lengths/{c}"), K::Mesh, "a side length")?;
            }
            let length = b.lengths.iter().fold(0.0f64, |a, &l| a.max(l));
            let size = positive(b.size, &format!("{p}/size"), K::Mesh, "size")?;
            let lo = b.corner.map(|x| x / length);
            let hi: [f64; 3] = std::array::from_fn(|c| (b.corner[c] + b.lengths[c]) / length);
            // A corner so far off that the scaled sides are not the given
            // ones in double precision would make flat cells, which the
            // checks of a given mesh never see.
            for c in 0..3 {
                let side = b.lengths[c] / length;
                if (hi[c] - lo[c] - side).abs() > 1e-9 * side {
                    return Err(invalid(
                        K::Mesh,
                        format!("{p}/corner/{c}"),
                        format!(
                            "the box's corner {} is so far from its sides' length {} that the sides are not distinct \
                             in double precision: move the origin near the body",
                            b.corner[c], b.lengths[c]
                        ),
                    ));
                }
            }
            let grading = match &b.grading {
                None => None,
                Some(g) => {
                    let gp = format!("{p}/grading");
                    super::bodies::check_grading_values(g.h_min, g.ratio, g.extent, size, &gp)?;
                    for (c, x) in g.focus.iter().enumerate() {
                        finite(*x, &format!("{gp}/focus/{c}"), K::Mesh)?;
                    }
                    let grading = Grading {
                        h_min: g.h_min / length,
                        ratio: g.ratio,
                        extent: g.extent / length,
                    };
                    Some((g.focus.map(|x| x / length), grading))
                }
            };
            let t10 = b.element == proto::SolidElementKind::T10;
            let nodes = box_nodes(lo, hi, size / length, grading, t10, limits, &p)?;
            // As for a 2D rectangle (`bodies::MIN_ASPECT`), after the size
            // limit, which a thin box of a sensible element size passes first:
            // a side too thin makes slivers.
            for c in 0..3 {
                if b.lengths[c] < super::bodies::MIN_ASPECT * length {
                    return Err(invalid(
                        K::Mesh,
                        format!("{p}/lengths/{c}"),
                        format!(
                            "the box is too thin to mesh: side {} is less than {:e} of its longest",
                            b.lengths[c],
                            super::bodies::MIN_ASPECT
                        ),
                    ));
                }
            }
            let mesh = SolidMesh::Box {
                lo,
                hi,
                size: size / length,
                grading,
                t10,
            };
            (length, nodes, mesh)
        }
        SolidMeshSpec::Inline(i) => {
            let p = format!("{path}/inline");
            for (k, n) in i.nodes.iter().enumerate() {
                for (c, x) in n.iter().enumerate() {
                    finite(*x, &format!("{p}/nodes/{k}/{c}"), K::Mesh)?;
                }
            }
            let length = crate::mesh::extent(&i.nodes);
            too_many(i.nodes.len() as f64, limits, &format!("{p}/nodes"))?;
            if !(length > 0.0 && length.is_finite()) {
                return Err(invalid(K::Mesh, format!("{p}/nodes"), "the mesh has no extent"));
            }
            let (elements, ends) = i.elements.as_parts();
            let mesh = SolidMesh::Inline {
                nodes: i.nodes.iter().map(|x| x.map(|c| c / length)).collect(),
                elements: elements.to_vec(),
                ends: ends.to_vec(),
                face_sets: i.face_sets.clone(),
                path: p,
            };
            (length, i.nodes.len() as f64, mesh)
        }
        SolidMeshSpec::Gmsh(g) => {
            // The scale and the size from the file's nodes (all of them);
            // its elements are read by `solid::door`.
            let p = format!("{path}/gmsh/msh");
            let nodes = crate::mesh::msh::try_nodes(&g.msh, &p)?.coords;
            too_many(nodes.len() as f64, limits, &p)?;
            let length = crate::mesh::extent(&nodes);
            if !(length > 0.0 && length.is_finite()) {
                return Err(invalid(K::Mesh, p, "the mesh has no extent"));
            }
            let mesh = SolidMesh::Gmsh {
                msh: g.msh.clone(),
                volumes: g.volumes.clone(),
                path: p,
            };
            (length, nodes.len() as f64, mesh)
        }
    };
    Ok((length, nodes, mesh))
}

/// Nodes of the box's grid, refused past the size limit: T4 nodes are the
/// grid's, T10 adds the midsides of every cell edge, face diagonal and main
/// diagonal, which are the points of the grid with each cell halved.
fn box_nodes(
    lo: [f64; 3],
    hi: [f64; 3],
    size: f64,
    grading: Option<([f64; 3], Grading)>,
    t10: bool,
    limits: &Limits,
    path: &str,
) -> Result<f64, CoreError> {
    let per_cell = if t10 { 2.0 } else { 1.0 };
    let nodes = |cells: [f64; 3]| -> f64 { cells.iter().map(|n| per_cell * n + 1.0).product() };
    // An upper bound first: the exact count (`grid_nodes`) builds the lines.
    let bound = cells_bound(lo, hi, size, grading);
    too_many(nodes(bound.map(|b| b.max(1.0))), limits, path).or_else(|e| {
        // Over by the bound: made, the lines tell; a bound past 1e7 cells on
        // one axis is over any limit this service is run with (4e7 nodes).
        if bound.iter().any(|&b| b > 1e7) {
            return Err(e);
        }
        Ok(())
    })?;
    let exact = grid_nodes(lo, hi, size, grading, t10);
    too_many(exact, limits, path)?;
    Ok(exact)
}

/// The size limit on 3 DOFs per node.
pub fn too_many(nodes: f64, limits: &Limits, path: &str) -> Result<(), CoreError> {
    if 3.0 * nodes > limits.max_dofs as f64 {
        return Err(CoreError::TooLarge {
            path: path.into(),
            reason: format!(
                "the mesh has about {nodes:.0} nodes, {:.0} degrees of freedom; this service solves at most {} \
                    (coarsen the mesh)",
                3.0 * nodes,
                limits.max_dofs
            ),
        });
    }
    Ok(())
}
