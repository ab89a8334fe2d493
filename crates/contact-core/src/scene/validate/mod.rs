//! Request → Scene: the one door every request passes. Each part of the
//! request has its module (`bodies`, `couplings`, `obstacles`, `foundations`, `pairs`,
//! `settings`); every failure names the JSON pointer of the offending field.
//! What can only be judged after meshing is `admit`'s.

mod bodies;
mod couplings;
mod foundations;
mod load_path;
mod obstacles;
mod pairs;
mod settings;
mod solid;
mod solid_load_path;
mod solid_obstacle;

pub use solid::solid_scene;

use contact_proto::{self as proto, SolveRequest};

use crate::error::{CoreError, InvalidKind};
use crate::scene::Scene;

/// Size limits of a deployment (the CLI and the service set them).
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Largest number of degrees of freedom (2 per node, before supports).
    pub max_dofs: usize,
    /// Largest number of contact candidates over all pairs. The condensed
    /// operator is dense: 16·m² bytes (W and its Gram product), so 4000
    /// candidates take 0.26 GB, beside the blocks of L⁻¹ P Bᵀ (82 kB per
    /// candidate at 1.2M DOF, growing with the depth of the elimination tree).
    pub max_candidates: usize,
    /// Longest `load_factors` list: each factor is a full contact solve and,
    /// with `outputs`, a full set of fields in the reply.
    pub max_load_steps: usize,
    /// Most numbers the requested `outputs` may put in one reply, over all load
    /// steps (estimated from the mesh size before meshing): a displacement
    /// field is 2 per node and step, stresses 4, VTU about 8.
    pub max_output_values: usize,
    /// Whether the error estimate's coarser companion may be solved on a
    /// second thread beside the answer (`adapt::overlap`).
    pub overlap: Overlap,
}

/// When the estimate's companion runs beside the answer's solve
/// (`adapt::overlap`); the reply is the same either way.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Overlap {
    /// When a core is free and the request is at most half the DOF limit.
    Auto,
    /// Never: the companion after the answer, on the solving thread.
    Off,
    /// Whenever the companion can be made from the scene alone (tests).
    Always,
}

/// Peak memory of a 2D solve per degree of freedom: 1.34–1.46 kB measured
/// (`/usr/bin/time`, maximum resident set) on the Hertz block at 138k, 428k
/// and 1.29M DOF, factor, condensation and estimate included. A service
/// bounded in memory sets `max_dofs` from it.
pub const BYTES_PER_DOF: usize = 1500;

impl Limits {
    /// The memory a request at the DOF limit is admitted for (`max_dofs` at
    /// 2D rates): what a 3D factor, which fills far more per DOF, must fit.
    pub fn memory_bytes(&self) -> f64 {
        self.max_dofs as f64 * BYTES_PER_DOF as f64
    }
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
            overlap: Overlap::Auto,
        }
    }
}

pub(super) fn invalid(kind: InvalidKind, path: impl Into<String>, reason: impl Into<String>) -> CoreError {
    CoreError::invalid(kind, path, reason)
}

pub(super) fn finite(v: f64, path: &str, kind: InvalidKind) -> Result<f64, CoreError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(kind, path, format!("value {v} is not a finite number")))
    }
}

/// Poisson's ratio of an isotropic elastic material: −1 < ν < 0.5.
pub(super) fn poisson(nu: f64, path: &str) -> Result<f64, CoreError> {
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

pub(super) fn positive(v: f64, path: &str, kind: InvalidKind, what: &str) -> Result<f64, CoreError> {
    finite(v, path, kind)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(kind, path, format!("{what} must be positive, got {v}")))
    }
}

/// The protocol version every request carries.
pub(super) fn version(req: &SolveRequest) -> Result<(), CoreError> {
    if req.version != proto::PROTOCOL_VERSION {
        return Err(invalid(
            InvalidKind::Version,
            "/version",
            format!(
                "version '{}' is not supported; this service speaks '{}'",
                req.version,
                proto::PROTOCOL_VERSION
            ),
        ));
    }
    Ok(())
}

impl Scene {
    /// Validates `req` against the deployment's `limits` and builds the scene
    /// in nondimensional form. The checks run in a fixed order, so the same
    /// request is always refused for the same first fault.
    pub fn try_new(req: &SolveRequest, limits: &Limits) -> Result<Scene, CoreError> {
        use InvalidKind as K;
        let time_limit = settings::time_limit(req)?;
        version(req)?;
        if req.analysis == proto::Analysis::Solid {
            return Err(invalid(
                K::Request,
                "/analysis",
                "a 3D solid is not a 2D scene: its door is `scene::validate::solid_scene`",
            ));
        }
        if req.solid.is_some() {
            return Err(invalid(
                K::Request,
                "/solid",
                "`solid` describes a 3D body: give it with `analysis: \"solid\"`",
            ));
        }
        if req.bodies.is_empty() {
            // At the request itself: an absent `bodies` reads as empty, and
            // its pointer would not resolve.
            return Err(invalid(
                K::Request,
                "",
                "at least one body is required in `bodies` (or, for a 3D solid, `analysis: \"solid\"`)",
            ));
        }
        let survey = bodies::survey(req, limits)?;
        let scales = survey.scales;
        let (names, bodies) = bodies::bodies(req, &survey)?;
        let (obstacle_names, obstacles) = obstacles::obstacles(req, scales)?;
        let (foundation_names, foundations) = foundations::foundations(req, scales)?;
        let names = pairs::Names {
            bodies: &names,
            obstacles: &obstacle_names,
            foundations: &foundation_names,
        };
        let (pairs, notes) = pairs::pairs(req, &survey, &names)?;
        couplings::against_pairs(&bodies, &pairs)?;
        let settings = settings::settings(req, scales, &bodies, survey.nodes.iter().sum(), limits)?;
        settings::units(req)?;
        let load_path = load_path::load_path(req, &bodies, limits)?;
        Ok(Scene {
            analysis: settings::analysis(req),
            scales,
            bodies,
            obstacles,
            foundations,
            pairs,
            method: settings::method(req),
            settings,
            outputs: settings::outputs(req),
            client_id: req.client_id.clone(),
            time_limit,
            estimated_nodes: survey.nodes.iter().sum(),
            notes,
            load_factors: req.load_factors.clone(),
            load_path,
        })
    }
}
