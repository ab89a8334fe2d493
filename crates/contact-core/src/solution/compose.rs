//! Solution → report: the certificate and the status it earns, contact zones
//! and pressures, punch motions and loads, foundation deflections, optional
//! fields, and the notes and warnings the user should read, all in the
//! request's units.

use faer::sparse::SparseColMat;
use faer::Mat;
use std::sync::Arc;

use crate::contact::{
    self,
    compliance::Foundations,
    free_motions::{self, FreeMotions, Motion},
};
use crate::fem::constitutive::Constitutive;
use crate::fem::kernel::Integration;
use crate::fem::{self, element};
use crate::mesh::Mesh2d;
use crate::methods;
use crate::model::Model;
use crate::observer::{Observer, Stage};
use crate::outcome::{Note, NoteKind};
use crate::scene::{Analysis, Scene};
use crate::solution::certificate::{certify, force_excess};
use crate::solution::report::{
    BodyFields, CacheState, Diagnostics, FoundationReport, ProblemSize, PunchReport, Report, Status,
};
use crate::solution::{energy, post, validity};

/// What the report needs of a solve besides its solution.
pub struct Solved<'a> {
    pub model: &'a Model,
    pub k: &'a SparseColMat<usize, f64>,
    pub f: &'a [f64],
    /// The external loads where `f` holds the friction forces too (the
    /// frictional route: f − B_Tᵀ τ); None: `f` is the loads.
    pub loads: Option<&'a [f64]>,
    /// `Cholesky::pivot_ratio` of the factor (condensed path).
    pub pivot_ratio: Option<f64>,
    /// `FactorCost::predicted_secs` of the factorization (condensed path).
    pub predicted: Option<f64>,
    /// The foundations' compliance D F D (condensed path, with foundations).
    pub compliance: Option<&'a Mat<f64>>,
    /// With friction, its share of the free motions' equilibrium
    /// (`FreeMotions::equilibrium`).
    pub friction: &'a [(f64, f64)],
    /// The model and the operator (condensed path), which the energy
    /// bound's pressure correction solves with (`energy::Pending`).
    pub operator: Option<(Arc<Model>, Arc<dyn energy::Operator>)>,
}

/// Certificate, status, contact zones, optional fields: the report.
pub fn report(scene: &Scene, st: &Solved, sol: methods::Solution, mut obs: Observer, cache: CacheState) -> Report {
    obs.enter(Stage::Post);
    let m = st.model;
    let free = Some(&m.free).filter(|p| !p.motions.is_empty());
    let beta = free.map(|p| p.motion(&sol.beta)).unwrap_or_default();
    let mut shift = free.filter(|p| !p.is_empty()).map(|p| p.shift(&sol.beta));
    // The foundations' deflection opens the gaps: D F D λ joins the shift.
    if let Some(wf) = st.compliance {
        let opened = crate::linalg::dense::matvec(wf, &sol.lambda);
        let s = shift.get_or_insert_with(|| vec![0.0; opened.len()]);
        s.iter_mut().zip(&opened).for_each(|(a, b)| *a += b);
    }
    let (mut certificate, gaps) = certify(st.k, st.f, &m.cons, &sol.u, &sol.lambda, shift.as_deref());
    let excess = {
        let loads = st.loads.unwrap_or(st.f);
        let friction: Vec<f64> = st
            .loads
            .map_or(Vec::new(), |l| st.f.iter().zip(l).map(|(a, b)| a - b).collect());
        force_excess(st.k, loads, &m.cons, &sol.u, &sol.lambda, &friction)
    };
    certificate.equilibrium = certificate
        .equilibrium
        .max(m.free.equilibrium(&sol.lambda, st.friction));
    let punches = free
        .map(|p| punch_results(scene, &m.cons, p, &beta, &sol.lambda))
        .unwrap_or_default();
    let mut notes = scene.notes.clone();
    for (body, mesh) in scene.bodies.iter().zip(&m.meshes) {
        if scene.analysis == Analysis::PlaneStress || body.poisson_ratio < fem::assembly::NEARLY_INCOMPRESSIBLE {
            continue;
        }
        if mesh.order == crate::mesh::Order::T3 {
            notes.push(Note::new(
                NoteKind::NearlyIncompressible,
                format!(
                    "body '{}' is nearly incompressible (ν = {}) on linear triangles, which lock in plane strain and \
                    axisymmetry: its pressures may be too stiff and oscillate (measured 31 % L2 error on Hertz at ν = \
                    0.4999 in plane strain, 19 % on a sphere into a block at ν = 0.499 in axisymmetry); use T6 \
                    elements, which switch to selective reduced integration from ν = {}",
                    body.name,
                    body.poisson_ratio,
                    fem::assembly::NEARLY_INCOMPRESSIBLE
                ),
            ));
        } else {
            notes.push(Note::new(
                NoteKind::P2P0Element,
                format!(
                "body '{}' ran the P2–P0 element (T6, the volume change constrained by its mean over each element: \
                    locking-free) since ν = {} ≥ {}",
                body.name,
                body.poisson_ratio,
                fem::assembly::NEARLY_INCOMPRESSIBLE
            ),
            ));
        }
    }
    notes.extend(m.free.notes.iter().cloned());
    notes.extend(sol.fallback.clone());
    let foundations = foundation_results(scene, &m.cons, &m.foundations, &sol.lambda);
    let (pairs, resultant, n_active) = post::pairs(scene, &m.meshes, &m.cons, &sol.lambda, &sol.in_contact, &gaps);
    let status = if !certificate.is_finite() || (!sol.converged && sol.breakdown) {
        Status::NumericalError
    } else if !sol.converged {
        Status::MaxIterations
    } else if certificate.worst() > scene.settings.tolerance && sol.exact {
        Status::NumericalError
    } else if !sol.exact && certificate.dual.max(certificate.equilibrium) > scene.settings.tolerance {
        // Penalty answers violate primal feasibility and complementarity by design;
        // their own equations (equilibrium, λ ≥ 0) must still hold.
        Status::NumericalError
    } else {
        Status::Solved
    };
    let disp = nodal_displacements(&m.meshes, &m.dofs, &sol.u, free.map(|p| (p, beta.as_slice())));
    let punch_motions: Vec<(usize, [f64; 3])> = (0..scene.obstacles.len())
        .filter(|&o| scene.obstacles[o].punch.is_some())
        .map(|o| (o, free_motions::punch_motion(scene, &m.free, &beta, o)))
        .collect();
    let turns = body_turns(&m.dofs, free.map(|p| (p, beta.as_slice())));
    let warnings = validity::check(scene, &m.meshes, &disp, &m.cons, &punch_motions, &turns, &pairs);
    let bodies = body_outputs(scene, &m.meshes, &disp);
    // The energy bound goes with the error estimate; it is made only for
    // the answer returned (`adapt`), from what is kept here.
    let pending_energy = st
        .operator
        .as_ref()
        .filter(|_| status == Status::Solved && (scene.settings.estimate || scene.settings.accuracy.is_some()))
        .filter(|(model, op)| energy::unsupported(scene, model, Some(op.factor())).is_none())
        .map(|(model, op)| {
            Arc::new(energy::Pending {
                model: model.clone(),
                operator: op.clone(),
                disp: disp.clone(),
                lambda: sol.lambda.clone(),
                punches: punch_motions.clone(),
            })
        });
    let couplings = crate::solution::couplings::couplings(scene, &m.meshes, &m.dofs, &disp, &m.external);
    // The post stage has no deadline check: its answer is ready.
    let _ = obs.leave(Stage::Post);
    let mut report = Report {
        client_id: scene.client_id.clone(),
        status,
        method: sol.method,
        iterations: sol.iterations,
        pairs,
        resultant,
        certificate,
        size: ProblemSize {
            dofs: m.dofs.n_free,
            candidates: m.cons.len(),
            active: n_active,
        },
        diagnostics: Diagnostics {
            condition_estimate: st.pivot_ratio,
            refinements: sol.refinements,
            factorization_predicted: st.predicted,
            condensed_rows: None,
        },
        timings: obs.finish(),
        cache,
        steps: None,
        refinement: None,
        punches,
        couplings,
        bodies,
        foundations,
        notes,
        warnings,
        outputs: scene.outputs,
        axisymmetric: scene.analysis == Analysis::Axisymmetric,
        energy: None,
        pending_energy,
    };
    if excess > UNBOUNDED {
        if report.status == Status::Solved {
            report.status = Status::NumericalError;
        }
        report.notes.push(Note::new(
            NoteKind::UnboundedForces,
            format!(
                "the contact forces are {excess:.1e} times what the loads and the deformation can balance: they \
                    cancel each other, and the pressures, friction forces and resultants must not be read"
            ),
        ));
    }
    if let Some(at) = report.first_non_finite() {
        report.status = Status::NumericalError;
        report.notes.push(Note::new(
            NoteKind::NonFinite,
            format!(
                "the answer holds a value that is not a finite number (first at {at}; JSON writes it as null): it must \
                    not be used"
            ),
        ));
    }
    report
}

/// Contact forces this many times what the loads and the deformation can
/// balance (`certificate::force_excess`) are not an answer: a right one is
/// within a few times (rows meeting on a node on opposite sides), the
/// singular frictional system of a contact edge held along x measured
/// 1.3e14; 1e6 is far from both.
const UNBOUNDED: f64 = 1e6;

/// Motion and loads of every punch, in the caller's units.
fn punch_results(
    scene: &Scene,
    cons: &contact::ConstraintSet,
    fm: &FreeMotions,
    beta: &[f64],
    lambda: &[f64],
) -> Vec<PunchReport> {
    let sc = scene.scales;
    let axisymmetric = scene.analysis == Analysis::Axisymmetric;
    let mut out = Vec::new();
    for (o, ob) in scene.obstacles.iter().enumerate() {
        if ob.punch.is_none() {
            continue;
        }
        let motion = free_motions::punch_motion(scene, fm, beta, o);
        // Loads on the punch balance the contact forces: P = −Σ λ_i c_i.
        let mut load = [0.0; 3];
        for (c, l) in cons.candidates.iter().zip(lambda) {
            if let Some((po, row)) = c.punch() {
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
        out.push(PunchReport {
            name: ob.name.clone(),
            alpha1: sc.length(motion[0]),
            alpha2: sc.length(motion[1]),
            theta: motion[2],
            // A punch of revolution feels no net radial force and no moment:
            // the ring forces cancel round the circumference (Σλ r is a
            // first moment of the rows, not a moment).
            p1: if axisymmetric { 0.0 } else { sc.force(load[0]) },
            p2: sc.force(load[1]),
            m: if axisymmetric { 0.0 } else { sc.moment(load[2]) },
            unique: undetermined.is_empty(),
            note: (!undetermined.is_empty()).then(|| {
                format!(
                    "the {} motion is not determined: no contact normal resists it and its load is 0; it is reported \
                        as 0, any value is a solution",
                    undetermined.join(" and ")
                )
            }),
        });
    }
    out
}

/// Every body held only by contact with its rigid rotation θ (the sum over
/// its free motions of β times their rotation).
fn body_turns(dofs: &fem::DofMap, free: Option<(&FreeMotions, &[f64])>) -> Vec<(usize, f64)> {
    let mut out: Vec<(usize, f64)> = Vec::new();
    let Some((fm, beta)) = free else { return out };
    for ((mo, _), a) in fm.motions.iter().zip(beta) {
        if let Motion::Body { set, dir } = *mo {
            let rm = &dofs.rigid[set];
            match out.iter_mut().find(|t| t.0 == rm.body) {
                Some(t) => t.1 += a * dir[2],
                None => out.push((rm.body, a * dir[2])),
            }
        }
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
fn body_outputs(scene: &Scene, meshes: &[Mesh2d], disp: &[Vec<[f64; 2]>]) -> Option<Vec<BodyFields>> {
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
            .map(|((body, mesh), disp)| {
                // (xx, yy, xy, zz): in plane strain ε_zz = 0; σ_zz = 0 in plane
                // stress; in axisymmetry (rr, zz, rz, θθ), the hoop stress from u_r / r.
                let stress4: Option<Vec<[f64; 4]>> = o_stress.then(|| {
                    let law = crate::fem::assembly::law(body, scene.analysis);
                    let how = crate::fem::assembly::integration(body, mesh.order, scene.analysis);
                    (0..mesh.n_elems())
                        .map(|e| {
                            let conn = mesh.elem(e);
                            let x: Vec<[f64; 2]> = conn.iter().map(|&n| mesh.nodes[n]).collect();
                            let ue: Vec<f64> = conn.iter().flat_map(|&n| disp[n]).collect();
                            let s = match scene.analysis {
                                Analysis::Axisymmetric => match how {
                                    Integration::MeanDilatation => {
                                        crate::fem::axisymmetric::centroid_stress_selective(mesh.order, &x, &law, &ue)
                                    }
                                    Integration::Full => {
                                        crate::fem::axisymmetric::centroid_stress(mesh.order, &x, &law, &ue)
                                    }
                                },
                                Analysis::PlaneStrain | Analysis::PlaneStress => {
                                    let s = element::centroid_stress(mesh.order, &x, &law, &ue);
                                    // σ_zz at ε_zz = 0, the fourth component of the law's
                                    // 4-form (`Constitutive`): ν (σ_xx + σ_yy) for isotropy in
                                    // plane strain, 0 in plane stress.
                                    let g = element::centroid_gradient(mesh.order, &x, &ue);
                                    let zz = Constitutive::<4>::stress(&law, &[g[0], g[3], g[1] + g[2], 0.0])[3];
                                    [s[0], s[1], s[2], zz]
                                }
                            };
                            s.map(|v| sc.stress(v))
                        })
                        .collect()
                });
                let stress: Option<Vec<[f64; 3]>> =
                    stress4.as_ref().map(|s| s.iter().map(|s| [s[0], s[1], s[2]]).collect());
                BodyFields {
                    name: body.name.clone(),
                    nodes: o_mesh.then(|| mesh.nodes.iter().map(|p| [sc.length(p[0]), sc.length(p[1])]).collect()),
                    elements: o_mesh.then(|| (0..mesh.n_elems()).map(|e| mesh.elem(e).to_vec()).collect()),
                    displacement: o_displacement
                        .then(|| disp.iter().map(|d| [sc.length(d[0]), sc.length(d[1])]).collect()),
                    // The VTU file's tensor reads it, and in axisymmetry the
                    // reply's `stress_hoop`.
                    stress_zz: stress4
                        .as_ref()
                        .filter(|_| o.vtu || (o.stress && scene.analysis == Analysis::Axisymmetric))
                        .map(|s| s.iter().map(|s| s[3]).collect()),
                    stress,
                }
            })
            .collect(),
    )
}

/// Deflection of every loaded foundation in the caller's units.
fn foundation_results(
    scene: &Scene,
    cons: &contact::ConstraintSet,
    f: &Foundations,
    lambda: &[f64],
) -> Vec<FoundationReport> {
    let sc = scene.scales;
    f.deflections(scene, cons, lambda)
        .into_iter()
        .map(|(k, x, w)| {
            let fnd = &scene.foundations[k];
            let load: f64 = cons
                .candidates
                .iter()
                .zip(lambda)
                .filter_map(|(c, l)| c.foundation().filter(|r| r.foundation == k).map(|r| r.proj * l))
                .sum();
            let (model, reference_distance) = (fnd.model.name(), fnd.model.reference_distance().map(|d| sc.length(d)));
            FoundationReport {
                name: fnd.name.clone(),
                model,
                x: x.into_iter().map(|v| sc.length(v)).collect(),
                w: w.into_iter().map(|v| sc.length(v)).collect(),
                reference_distance,
                load: sc.force(load),
            }
        })
        .collect()
}
