//! The one place that knows the order of the stages:
//! request → scene → meshes → assembly → constraints → method → certificate → reply.

use std::time::Instant;

use std::sync::Arc;

use crate::cache::{self, OperatorCache};
use crate::contact::{
    self,
    foundation::Foundations,
    free_motions::{self, FreeMotions, Motion},
};
use crate::error::{CoreError, InvalidKind};
use crate::fem::{self, element, material::d_matrix};
use crate::mesh::{generate, Mesh2d};
use crate::methods::{self, Problem};
use crate::proto::{
    self, BodyOutput, CacheState, ErrorReply, Formulation, LoadStep, MethodName, ProblemSize, PunchResult, SolveReply,
    SolveStatus, Timings,
};
use crate::scene::{parse::parse_request, Limits, MeshSource, Scene};
use crate::solution::{certificate::certify, post, validity};

/// Bytes in, reply or structured error out: what the service and the CLI call.
pub fn solve_bytes(bytes: &[u8], limits: &Limits) -> Result<SolveReply, ErrorReply> {
    solve_bytes_cached(bytes, limits, None)
}

/// As `solve_bytes`, reusing prepared operators from `cache` when given.
pub fn solve_bytes_cached(
    bytes: &[u8],
    limits: &Limits,
    cache: Option<&OperatorCache>,
) -> Result<SolveReply, ErrorReply> {
    let run = || -> Result<SolveReply, CoreError> {
        let req = parse_request(bytes)?;
        let _limit = crate::cancel::request_limit(req.time_limit, "/time_limit")?;
        let scene = Scene::try_new(&req, limits)?;
        solve(&scene, limits, cache)
    };
    run().map_err(|e| ErrorReply::from(&e).with_client_id_of(bytes))
}

/// The checks of `solve_bytes` that come before any numerics: parse, the time
/// limit, validation (with its size estimates). Cheap and bounded by the
/// payload, so the service runs it on arrival and only valid work queues.
pub fn check_bytes(bytes: &[u8], limits: &Limits) -> Result<(), ErrorReply> {
    let run = || -> Result<(), CoreError> {
        let req = parse_request(bytes)?;
        crate::cancel::validate_time_limit(req.time_limit, "/time_limit")?;
        Scene::try_new(&req, limits).map(|_| ())
    };
    run().map_err(|e| ErrorReply::from(&e).with_client_id_of(bytes))
}

/// The bodies' meshes in nondimensional coordinates: generated in the
/// request's units, then scaled. A generator that cannot mesh its region (a
/// geometry its refinement does not handle) is an `invalid_mesh` at the body's
/// mesh, not a panic.
pub fn build_meshes(scene: &Scene) -> Result<Vec<Mesh2d>, CoreError> {
    let length = scene.scales.length;
    let scaled = |mut m: Mesh2d| {
        for p in m.nodes.iter_mut() {
            *p = [p[0] / length, p[1] / length];
        }
        m
    };
    scene
        .bodies
        .iter()
        .map(|b| {
            let generated = match &b.mesh {
                MeshSource::Rectangle {
                    corner,
                    width,
                    height,
                    size,
                    grading,
                    order,
                } => generate::rectangle(*corner, *width, *height, *size, *grading, *order),
                MeshSource::Disk {
                    center,
                    radius,
                    down,
                    part,
                    size,
                    grading,
                    order,
                } => generate::disk(*center, *radius, *down, *part, *size, *grading, *order),
                MeshSource::Inline(m) => return Ok(m.clone()),
            };
            generated.map(scaled).map_err(|e| {
                CoreError::invalid(
                    crate::error::InvalidKind::Mesh,
                    format!("{}/mesh", b.path),
                    format!("the mesh generator could not mesh this body: {}", e.0),
                )
            })
        })
        .collect()
}

/// Solves the scene, once per load factor (one factorization serves them all).
pub fn solve(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<SolveReply, CoreError> {
    if scene.load_factors.is_empty() {
        return solve_one(scene, limits, cache);
    }
    // Later factors find the operator the first one prepared.
    let local = OperatorCache::new(usize::MAX);
    let cache = cache.or(Some(&local));
    let mut steps = Vec::with_capacity(scene.load_factors.len());
    let mut replies: Vec<SolveReply> = Vec::with_capacity(scene.load_factors.len());
    for &k in &scene.load_factors {
        let r = solve_one(&scene.scaled(k), limits, cache)?;
        steps.push(LoadStep {
            factor: k,
            status: r.status,
            iterations: r.iterations,
            pairs: r.pairs.clone(),
            resultant: r.resultant,
            certificate: r.certificate,
        });
        replies.push(r);
    }
    let first_cache = replies[0].cache;
    let mut t = Timings::default();
    for r in &replies {
        let s = r.timings;
        t.mesh += s.mesh;
        t.assembly += s.assembly;
        t.factorization += s.factorization;
        t.condensation += s.condensation;
        t.contact_solve += s.contact_solve;
        t.post += s.post;
        t.total += s.total;
    }
    let mut last = replies.pop().expect("at least one factor");
    // The reply is only as good as its worst step.
    if let Some(bad) = steps.iter().find(|st| st.status != SolveStatus::Solved) {
        last.status = bad.status;
    }
    last.timings = t;
    last.cache = if local.is_empty() { first_cache } else { CacheState::Off };
    last.steps = Some(steps);
    Ok(last)
}

fn solve_one(scene: &Scene, limits: &Limits, cache: Option<&OperatorCache>) -> Result<SolveReply, CoreError> {
    let t_start = Instant::now();
    let mut timings = Timings::default();

    let t = Instant::now();
    crate::progress::stage("mesh");
    let meshes = build_meshes(scene)?;
    timings.mesh = t.elapsed().as_secs_f64();
    crate::cancel::check("mesh")?;
    let n_dofs: usize = meshes.iter().map(|m| 2 * m.nodes.len()).sum();
    if n_dofs > limits.max_dofs {
        return Err(CoreError::TooLarge {
            path: "/bodies".into(),
            reason: format!(
                "{n_dofs} degrees of freedom; this service accepts at most {}",
                limits.max_dofs
            ),
        });
    }

    let t = Instant::now();
    crate::progress::stage("assembly");
    let dofs = fem::assembly::dof_map(scene, &meshes)?;
    check_search_work(scene, &meshes)?;
    let cons = contact::build(scene, &meshes, &dofs);
    for (p, pair) in scene.pairs.iter().enumerate() {
        if !cons.candidates.iter().any(|c| c.pair == p) {
            return Err(CoreError::invalid(
                InvalidKind::NoContactCandidates,
                format!("{}/edges", pair.path),
                format!(
                    "no node of edge set '{}' can reach {} along its outward normal ({} pruned: the ray misses the obstacle or the gap exceeds prune_gap_ratio × body size)",
                    pair.edges, pair_target_name(scene, pair), cons.pruned[p]
                ),
            ));
        }
    }
    let external = fem::assembly::external_loads(scene, &meshes, &dofs);
    let free = FreeMotions::try_new(scene, &cons, &dofs, &meshes, &external)?;
    let foundations = Foundations::try_new(scene, &cons)?;
    if scene.settings.formulation == Formulation::Full {
        if !free.motions.is_empty() || !foundations.is_empty() {
            return Err(CoreError::invalid(
                InvalidKind::Request,
                "/settings/formulation",
                "load-controlled punches, bodies held only by contact and foundations are solved on the condensed formulation only",
            ));
        }
        if !cons.rows_are_nodal() {
            return Err(CoreError::invalid(
                InvalidKind::Request,
                "/settings/formulation",
                "the full formulation needs nodal contact rows (one node per row, as T3 and discretization 'nodal' give); mortar rows (the T6 default) and two-body rows are solved on the condensed formulation only",
            ));
        }
        return solve_full(scene, &meshes, dofs, cons, &free, &external, timings, t, t_start);
    }
    if scene.method == MethodName::Auto
        && free.motions.is_empty()
        && dofs.rigid.is_empty()
        && foundations.is_empty()
        && cons.rows_are_nodal()
        && full_is_cheaper(dofs.n_free, cons.len())
    {
        return solve_full(scene, &meshes, dofs, cons, &free, &external, timings, t, t_start);
    }
    // The condensed operator is dense in the candidates: bounded by the limit.
    if cons.len() > limits.max_candidates {
        return Err(CoreError::TooLarge {
            path: "/contacts".into(),
            reason: format!(
                "{} contact candidates; this service accepts at most {} on the condensed formulation",
                cons.len(),
                limits.max_candidates
            ),
        });
    }
    let key = cache::key(scene, &meshes, &dofs, &cons);
    timings.assembly = t.elapsed().as_secs_f64();
    let (op, cache_state) = match cache.and_then(|c| c.get(key)) {
        Some(op) => (op, CacheState::Hit),
        None => {
            let stiffness = Arc::new(fem::assembly::assemble_stiffness(scene, &meshes, &dofs)?);
            crate::cancel::check("assembly")?;
            timings.assembly = t.elapsed().as_secs_f64();
            crate::progress::stage("factorization");
            let op = Arc::new(methods::condensed::prepare(stiffness, &cons)?);
            timings.factorization = op.t_factorization;
            timings.condensation = op.t_condensation;
            if let Some(c) = cache {
                c.insert(key, op.clone());
            }
            (
                op,
                if cache.is_some() {
                    CacheState::Miss
                } else {
                    CacheState::Off
                },
            )
        }
    };
    crate::cancel::check("condensation")?;
    let t = Instant::now();
    let f = fem::assembly::assemble_loads(&external, &dofs, &op.stiffness);
    let compliance = (!foundations.is_empty()).then(|| foundations.compliance(&cons));
    timings.assembly += t.elapsed().as_secs_f64();

    let problem = Problem {
        op: &op,
        f: &f,
        cons: &cons,
        settings: &scene.settings,
        zeta: scene
            .settings
            .penalty
            .map(|z| z * scene.scales.modulus / scene.scales.length)
            .unwrap_or(1e-6),
        barrier: scene
            .settings
            .barrier
            .map(|z| z / (scene.scales.modulus * scene.scales.length))
            .unwrap_or(1e-8),
        punch: (!free.is_empty()).then_some(methods::PunchBlock {
            c: &free.c,
            rhs: &free.rhs,
        }),
        compliance: compliance.as_ref(),
    };
    crate::progress::stage("contact_solve");
    let sol = methods::solve(&problem, scene.method)?;
    crate::cancel::check("contact_solve")?;
    timings.contact_solve = sol.t_contact;
    let stage = Stage {
        meshes: &meshes,
        dofs: &dofs,
        cons: &cons,
        k: &op.stiffness.k,
        f: &f,
        free: Some(&free),
        pivot_ratio: Some(op.pivot_ratio),
        predicted: Some(op.chol.cost().predicted_secs()),
        foundations: Some((&foundations, compliance.as_ref())),
    };
    Ok(finish(scene, &stage, sol, timings, t_start, cache_state))
}

/// What post-processing needs of the solve.
struct Stage<'a> {
    meshes: &'a [Mesh2d],
    dofs: &'a fem::DofMap,
    cons: &'a contact::ConstraintSet,
    k: &'a faer::sparse::SparseColMat<usize, f64>,
    f: &'a [f64],
    free: Option<&'a FreeMotions>,
    /// `Cholesky::pivot_ratio` of the factor (condensed path).
    pivot_ratio: Option<f64>,
    /// `FactorCost::predicted_secs` of a factorization this solve ran.
    predicted: Option<f64>,
    /// The foundations and their compliance D F D (None when there are none).
    foundations: Option<(&'a Foundations, Option<&'a faer::Mat<f64>>)>,
}

/// Whether `auto` should solve on the full system: the condensed path costs
/// about 1.2e-10 m³ s of dense work on this machine (W and the LCP, measured
/// 0.18 s at m = 1000 and 6.8 s at m = 4000), the full active set a few
/// factorizations of about 1.8e-7 n^1.2 s each (0.126 s at 75k DOF, 1.74 s at
/// 612k); the full path wins when the first exceeds about ten of the second
/// (strip of 1000 candidates on 5k DOF: 0.18 s condensed, 0.02 s full; the
/// Hertz scenes stay condensed).
fn full_is_cheaper(n_free: usize, m: usize) -> bool {
    (m as f64).powi(3) > 1.5e4 * (n_free as f64).powf(1.2)
}

/// Largest problem the full-system interior point accepts.
const FULL_IPM_MAX_DOFS: usize = 200_000;

/// Full-system exact methods: no condensation, no cache (they are the comparison).
#[allow(clippy::too_many_arguments)]
fn solve_full(
    scene: &Scene,
    meshes: &[Mesh2d],
    dofs: fem::DofMap,
    cons: contact::ConstraintSet,
    free: &FreeMotions,
    external: &[f64],
    mut timings: Timings,
    t: Instant,
    t_start: Instant,
) -> Result<SolveReply, CoreError> {
    let stiffness = fem::assembly::assemble_stiffness(scene, meshes, &dofs)?;
    let f = fem::assembly::assemble_loads(external, &dofs, &stiffness);
    timings.assembly = t.elapsed().as_secs_f64();
    crate::cancel::check("assembly")?;
    let g = cons.g();
    crate::progress::stage("contact_solve");
    let sol = match scene.method {
        MethodName::Auto | MethodName::ActiveSet => {
            methods::full::solve_active_set(&stiffness.k, &f, &cons, &g, &scene.settings)?
        }
        MethodName::InteriorPoint => {
            // Clarabel on the full QP needs ~4 GB and a minute at 1M DOF (measured in
            // ../shared/DEPENDENCIES.md); it is a comparison, not a production path.
            if dofs.n_free > FULL_IPM_MAX_DOFS {
                return Err(CoreError::TooLarge {
                    path: "/settings/formulation".into(),
                    reason: format!(
                        "interior_point on the full formulation is limited to {FULL_IPM_MAX_DOFS} DOFs ({} requested); use the condensed formulation",
                        dofs.n_free
                    ),
                });
            }
            methods::full::solve_interior_point(&stiffness.k, &f, &cons, &g, &scene.settings)?
        }
        other => {
            return Err(CoreError::invalid(
                InvalidKind::Request,
                "/settings/formulation",
                format!(
                "the full formulation is offered for the exact methods active_set and interior_point, not {other:?}"
            ),
            ))
        }
    };
    crate::cancel::check("contact_solve")?;
    timings.contact_solve = sol.t_contact;
    let stage = Stage {
        meshes,
        dofs: &dofs,
        cons: &cons,
        k: &stiffness.k,
        f: &f,
        // No free motion reaches here; its notes (undetermined modes) still do.
        free: Some(free),
        pivot_ratio: None,
        predicted: None,
        foundations: None,
    };
    Ok(finish(scene, &stage, sol, timings, t_start, CacheState::Off))
}

/// Certificate, status, contact zones, optional fields: the reply.
fn finish(
    scene: &Scene,
    st: &Stage,
    sol: methods::Solution,
    mut timings: Timings,
    t_start: Instant,
    cache: CacheState,
) -> SolveReply {
    let t = Instant::now();
    crate::progress::stage("post");
    let free = st.free.filter(|p| !p.motions.is_empty());
    let beta = free.map(|p| p.motion(&sol.beta)).unwrap_or_default();
    let mut shift = free.filter(|p| !p.is_empty()).map(|p| p.shift(&sol.beta));
    // The foundations' deflection opens the gaps: D F D λ joins the shift.
    if let Some((_, Some(wf))) = st.foundations {
        let opened = crate::linalg::dense::matvec(wf, &sol.lambda);
        let s = shift.get_or_insert_with(|| vec![0.0; opened.len()]);
        s.iter_mut().zip(&opened).for_each(|(a, b)| *a += b);
    }
    let (mut certificate, gaps) = certify(st.k, st.f, st.cons, &sol.u, &sol.lambda, shift.as_deref());
    if let Some(p) = st.free {
        certificate.equilibrium = certificate.equilibrium.max(p.equilibrium(&sol.lambda));
    }
    let punches = free
        .map(|p| punch_results(scene, st.cons, p, &beta, &sol.lambda))
        .unwrap_or_default();
    let mut notes = scene.notes.clone();
    for (body, mesh) in scene.bodies.iter().zip(st.meshes) {
        if mesh.order == crate::mesh::Order::T3
            && scene.analysis == proto::Analysis::PlaneStrain
            && body.poisson_ratio >= fem::assembly::NEARLY_INCOMPRESSIBLE
        {
            notes.push(format!(
                "body '{}' is nearly incompressible (ν = {}) on linear triangles, which lock in plane strain: its pressures may be too stiff and oscillate (measured 31 % L2 error on Hertz at ν = 0.4999); use T6 elements, which switch to selective reduced integration from ν = {}",
                body.name,
                body.poisson_ratio,
                fem::assembly::NEARLY_INCOMPRESSIBLE
            ));
        }
    }
    notes.extend(st.free.map(|p| p.notes.clone()).unwrap_or_default());
    notes.extend(sol.fallback.clone());
    let foundations = st
        .foundations
        .map(|(f, _)| foundation_results(scene, st.cons, f, &sol.lambda))
        .unwrap_or_default();
    let (pairs, resultant, n_active) = post::pairs(scene, st.meshes, st.cons, &sol.lambda, &sol.in_contact, &gaps);
    let status = if !certificate.is_finite() || (!sol.converged && sol.breakdown) {
        SolveStatus::NumericalError
    } else if !sol.converged {
        SolveStatus::MaxIterations
    } else if certificate.worst() > scene.settings.tolerance && sol.exact {
        SolveStatus::NumericalError
    } else if !sol.exact && certificate.dual.max(certificate.equilibrium) > scene.settings.tolerance {
        // Penalty answers violate primal feasibility and complementarity by design;
        // their own equations (equilibrium, λ ≥ 0) must still hold.
        SolveStatus::NumericalError
    } else {
        SolveStatus::Solved
    };
    let disp = nodal_displacements(st.meshes, st.dofs, &sol.u, free.map(|p| (p, beta.as_slice())));
    let punch_rotations: Vec<(usize, f64)> = match st.free {
        Some(fm) => (0..scene.obstacles.len())
            .filter(|&o| scene.obstacles[o].punch.is_some())
            .map(|o| (o, free_motions::punch_motion(scene, fm, &beta, o)[2]))
            .collect(),
        None => Vec::new(),
    };
    let zones: Vec<Vec<[f64; 2]>> = pairs
        .iter()
        .map(|pr| {
            pr.zones
                .iter()
                .map(|z| [z[0] / scene.scales.length, z[1] / scene.scales.length])
                .collect()
        })
        .collect();
    let warnings = validity::check(scene, st.meshes, &disp, st.cons, &punch_rotations, &zones);
    let bodies = body_outputs(scene, st.meshes, &disp);
    timings.post = t.elapsed().as_secs_f64();
    timings.total = t_start.elapsed().as_secs_f64();
    let mut reply = SolveReply {
        version: proto::PROTOCOL_VERSION.to_string(),
        client_id: scene.client_id.clone(),
        request_id: None,
        status,
        method: sol.method.to_string(),
        iterations: sol.iterations,
        pairs,
        resultant,
        certificate,
        size: ProblemSize {
            dofs: st.dofs.n_free,
            candidates: st.cons.len(),
            active: n_active,
        },
        diagnostics: proto::Diagnostics {
            condition_estimate: st.pivot_ratio,
            refinements: sol.refinements,
            factorization_predicted: st.predicted,
        },
        timings,
        cache,
        steps: None,
        punches,
        bodies,
        foundations,
        notes,
        warnings,
        vtu: None,
    };
    crate::output::attach_vtu(&mut reply, scene.outputs);
    reply
}

/// Motion and loads of every punch, in the caller's units.
fn punch_results(
    scene: &Scene,
    cons: &contact::ConstraintSet,
    fm: &FreeMotions,
    beta: &[f64],
    lambda: &[f64],
) -> Vec<PunchResult> {
    let sc = scene.scales;
    let mut out = Vec::new();
    for (o, ob) in scene.obstacles.iter().enumerate() {
        if ob.punch.is_none() {
            continue;
        }
        let motion = free_motions::punch_motion(scene, fm, beta, o);
        // Loads on the punch balance the contact forces: P = −Σ λ_i c_i.
        let mut load = [0.0; 3];
        for (c, l) in cons.candidates.iter().zip(lambda) {
            if let Some((po, row)) = c.punch {
                if po == o {
                    for k in 0..3 {
                        load[k] -= l * row[k];
                    }
                }
            }
        }
        let undetermined: Vec<&str> = fm
            .motions
            .iter()
            .enumerate()
            .filter_map(|(k, (mo, _))| match *mo {
                Motion::Punch { obstacle, component } if obstacle == o && !fm.is_determined(k) => {
                    Some(free_motions::COMPONENT[component])
                }
                _ => None,
            })
            .collect();
        out.push(PunchResult {
            name: ob.name.clone(),
            alpha1: sc.length(motion[0]),
            alpha2: sc.length(motion[1]),
            theta: motion[2],
            p1: sc.force(load[0]),
            p2: sc.force(load[1]),
            m: sc.moment(load[2]),
            unique: undetermined.is_empty(),
            note: (!undetermined.is_empty()).then(|| {
                format!(
                    "the {} motion is not determined: no contact normal resists it and its load is 0; it is reported as 0, any value is a solution",
                    undetermined.join(" and ")
                )
            }),
        });
    }
    out
}

/// Nodal displacements of every body (nondimensional): the solved free DOFs,
/// the prescribed ones, and the rigid motions of bodies held by contact
/// (`free`: the free motions and their amplitudes β, whose body modes add R β).
fn nodal_displacements(
    meshes: &[Mesh2d],
    dofs: &fem::DofMap,
    u: &[f64],
    free: Option<(&FreeMotions, &[f64])>,
) -> Vec<Vec<[f64; 2]>> {
    let rigid = |b: usize, x: [f64; 2]| {
        let mut r = [0.0; 2];
        if let Some((fm, beta)) = free {
            for ((mo, _), a) in fm.motions.iter().zip(beta) {
                if let Motion::Body { set, dir } = *mo {
                    let rm = &dofs.rigid[set];
                    if rm.body == b {
                        let d = rm.at_dir(dir, x);
                        r[0] += a * d[0];
                        r[1] += a * d[1];
                    }
                }
            }
        }
        r
    };
    let value = |d: usize| match dofs.free[d] {
        fem::assembly::FIXED => dofs.prescribed[d],
        k => u[k],
    };
    meshes
        .iter()
        .enumerate()
        .map(|(b, mesh)| {
            (0..mesh.nodes.len())
                .map(|n| {
                    let r = rigid(b, mesh.nodes[n]);
                    [value(dofs.dof(b, n, 0)) + r[0], value(dofs.dof(b, n, 1)) + r[1]]
                })
                .collect()
        })
        .collect()
}

/// Optional per-body fields, only when the request lists them.
fn body_outputs(scene: &Scene, meshes: &[Mesh2d], disp: &[Vec<[f64; 2]>]) -> Option<Vec<BodyOutput>> {
    let o = scene.outputs;
    if !(o.displacement || o.mesh || o.stress || o.vtu) {
        return None;
    }
    // The VTU file needs every field; `output::attach_vtu` drops those not asked for.
    let (o_mesh, o_displacement, o_stress) = (o.mesh || o.vtu, o.displacement || o.vtu, o.stress || o.vtu);
    let sc = scene.scales;
    Some(
        scene
            .bodies
            .iter()
            .zip(meshes)
            .zip(disp)
            .map(|((body, mesh), disp)| BodyOutput {
                name: body.name.clone(),
                nodes: o_mesh.then(|| mesh.nodes.iter().map(|p| [sc.length(p[0]), sc.length(p[1])]).collect()),
                elements: o_mesh.then(|| (0..mesh.n_elems()).map(|e| mesh.elem(e).to_vec()).collect()),
                displacement: o_displacement.then(|| disp.iter().map(|d| [sc.length(d[0]), sc.length(d[1])]).collect()),
                stress: o_stress.then(|| {
                    let dm = d_matrix(body.youngs_modulus, body.poisson_ratio, scene.analysis);
                    (0..mesh.n_elems())
                        .map(|e| {
                            let conn = mesh.elem(e);
                            let x: Vec<[f64; 2]> = conn.iter().map(|&n| mesh.nodes[n]).collect();
                            let ue: Vec<f64> = conn.iter().flat_map(|&n| disp[n]).collect();
                            let s = element::centroid_stress(mesh.order, &x, &dm, &ue);
                            [sc.stress(s[0]), sc.stress(s[1]), sc.stress(s[2])]
                        })
                        .collect()
                }),
            })
            .collect(),
    )
}

fn pair_target_name(scene: &Scene, pair: &crate::scene::Pair) -> String {
    match &pair.target {
        crate::scene::Target::Obstacle(o) => format!("obstacle '{}'", scene.obstacles[*o].name),
        crate::scene::Target::Body { body, edges, .. } => {
            format!("edge set '{edges}' of body '{}'", scene.bodies[*body].name)
        }
        crate::scene::Target::Foundation(f) => format!("foundation '{}'", scene.foundations[*f].name),
    }
}

/// Deflection of every loaded foundation in the caller's units.
fn foundation_results(
    scene: &Scene,
    cons: &contact::ConstraintSet,
    f: &Foundations,
    lambda: &[f64],
) -> Vec<proto::FoundationResult> {
    let sc = scene.scales;
    f.deflections(scene, cons, lambda)
        .into_iter()
        .map(|(k, x, w)| {
            let fnd = &scene.foundations[k];
            let load: f64 = cons
                .candidates
                .iter()
                .zip(lambda)
                .filter_map(|(c, l)| c.foundation.filter(|r| r.foundation == k).map(|r| r.proj * l))
                .sum();
            let (model, reference_distance) = match fnd.model {
                crate::scene::FoundationModel::Winkler { .. } => ("winkler", None),
                crate::scene::FoundationModel::Pasternak { .. } => ("pasternak", None),
                crate::scene::FoundationModel::HalfPlane { d, .. } => ("half_plane", Some(sc.length(d))),
            };
            proto::FoundationResult {
                name: fnd.name.clone(),
                model: model.to_string(),
                x: x.into_iter().map(|v| sc.length(v)).collect(),
                w: w.into_iter().map(|v| sc.length(v)).collect(),
                reference_distance,
                load: sc.force(load),
            }
        })
        .collect()
}

/// Ray casts a two-body pair may cost (each slave point against each master
/// edge, about 20 flops): a request is refused before the search rather than
/// tying a worker up for minutes on a pair of huge edge sets.
const MAX_SEARCH_CASTS: f64 = 4e8;

fn check_search_work(scene: &Scene, meshes: &[Mesh2d]) -> Result<(), CoreError> {
    for pair in &scene.pairs {
        let crate::scene::Target::Body {
            body,
            edges,
            discretization,
        } = &pair.target
        else {
            continue;
        };
        let slave = meshes[pair.body].edge_sets.get(&pair.edges).map_or(0, |e| e.len()) as f64;
        let master = meshes[*body].edge_sets.get(edges).map_or(0, |e| e.len()) as f64;
        // Mortar: 4 Gauss points on each of about two sub-segments per slave edge.
        let points = match discretization {
            proto::Discretization::Mortar => 8.0 * slave,
            proto::Discretization::NodeToSegment => slave + 1.0,
        };
        if points * master > MAX_SEARCH_CASTS {
            return Err(CoreError::TooLarge {
                path: format!("{}/edges", pair.path),
                reason: format!(
                    "the contact search of this two-body pair would cast {:.1e} rays ({} slave edges against {} master edges); this service accepts at most {MAX_SEARCH_CASTS:.0e}: restrict the edge sets to the faces that can touch",
                    points * master,
                    slave,
                    master
                ),
            });
        }
    }
    Ok(())
}
