//! The validated, nondimensional domain model built from a request.
//!
//! `Scene::try_new` (`validate`) refuses everything the request alone shows
//! to be wrong; what only the meshes and rows can show is `admit`'s, right
//! after meshing and assembly. All lengths are divided by `scales.length` and all
//! moduli and stresses by `scales.modulus`, so the numerics see O(1) numbers
//! whatever the caller's units.

pub mod height_field;
pub mod scaling;
pub mod settings;
mod size_limit;
pub mod solid;
pub mod solid_obstacle;
pub mod validate;

pub use scaling::Scales;
pub use settings::{
    AccuracyTarget, Analysis, Control, Discretization, Formulation, GapMeasure, Method, Settings, T6Multipliers,
};
pub use validate::{Limits, Overlap, BYTES_PER_DOF};

use crate::mesh::{generate::Grading, Mesh2d, Order};

#[derive(Debug, Clone)]
pub struct Scene {
    pub analysis: Analysis,
    pub scales: Scales,
    pub bodies: Vec<Body>,
    pub obstacles: Vec<Obstacle>,
    pub foundations: Vec<Foundation>,
    pub pairs: Vec<Pair>,
    pub method: Method,
    pub settings: Settings,
    pub outputs: Outputs,
    pub client_id: Option<String>,
    /// Seconds the solve may take (the request's `time_limit`), if limited.
    pub time_limit: Option<f64>,
    /// Nodes of all meshes as estimated before meshing (progress plans with it).
    pub estimated_nodes: f64,
    /// What validation decided that the user should know (echoed in the reply's notes).
    pub notes: Vec<crate::outcome::Note>,
    /// Load multipliers to solve for (empty: the loads as given).
    pub load_factors: Vec<f64>,
    /// Load path steps (empty: none): each scales named loads separately.
    pub load_path: Vec<PathStep>,
}

/// One load path step: the factor of each named load (the others keep 1),
/// and the names as the request gave them (echoed in the reply).
#[derive(Debug, Clone, Default)]
pub struct PathStep {
    pub factors: Vec<(LoadRef, f64)>,
    pub given: std::collections::BTreeMap<String, f64>,
}

/// A load or prescribed displacement of a body that a load path scales.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadRef {
    Traction {
        body: usize,
        index: usize,
    },
    PointLoad {
        body: usize,
        index: usize,
    },
    Support {
        body: usize,
        index: usize,
    },
    BodyForce {
        body: usize,
    },
    /// Component (0: horizontal, 1: vertical, 2: rotation) of a punch's
    /// control, load or displacement.
    Punch {
        obstacle: usize,
        component: usize,
    },
    /// Component of a body's coupling, as for a punch.
    Coupling {
        body: usize,
        index: usize,
        component: usize,
    },
}

impl Scene {
    /// The scene of the last load step (a stepped solve's report answers
    /// it), or None for a scene without steps.
    pub fn last_step(&self) -> Option<Scene> {
        match self.load_path.last() {
            Some(st) => Some(self.at_step(st)),
            None => self.load_factors.last().map(|&k| self.scaled(k)),
        }
    }

    /// The same scene with every load and prescribed displacement times `k`.
    pub fn scaled(&self, k: f64) -> Scene {
        let mut s = self.clone();
        s.load_factors.clear();
        s.load_path.clear();
        for b in &mut s.bodies {
            b.body_force = [k * b.body_force[0], k * b.body_force[1]];
            for sup in &mut b.supports {
                sup.ux = sup.ux.map(|v| k * v);
                sup.uy = sup.uy.map(|v| k * v);
            }
            for t in &mut b.tractions {
                match t {
                    Traction::Vector { t, .. } => *t = [k * t[0], k * t[1]],
                    Traction::Pressure { p, .. } => *p *= k,
                }
            }
            for pl in &mut b.point_loads {
                pl.force = [k * pl.force[0], k * pl.force[1]];
            }
            for cp in &mut b.couplings {
                for c in &mut cp.controls {
                    c.scale(k);
                }
            }
        }
        // A punch's load or motion is one of the scene's loads.
        for pu in s.obstacles.iter_mut().filter_map(|o| o.punch.as_mut()) {
            for c in &mut pu.controls {
                c.scale(k);
            }
        }
        s
    }
}

impl Scene {
    /// The scene of a load path step: each named load times its factor.
    pub fn at_step(&self, step: &PathStep) -> Scene {
        let mut s = self.clone();
        s.load_factors.clear();
        s.load_path.clear();
        for &(r, k) in &step.factors {
            match r {
                LoadRef::Traction { body, index } => match &mut s.bodies[body].tractions[index] {
                    Traction::Vector { t, .. } => *t = [k * t[0], k * t[1]],
                    Traction::Pressure { p, .. } => *p *= k,
                },
                LoadRef::PointLoad { body, index } => {
                    let f = &mut s.bodies[body].point_loads[index].force;
                    *f = [k * f[0], k * f[1]];
                }
                LoadRef::Support { body, index } => {
                    let sup = &mut s.bodies[body].supports[index];
                    sup.ux = sup.ux.map(|v| k * v);
                    sup.uy = sup.uy.map(|v| k * v);
                }
                LoadRef::BodyForce { body } => {
                    let b = &mut s.bodies[body].body_force;
                    *b = [k * b[0], k * b[1]];
                }
                LoadRef::Punch { obstacle, component } => {
                    if let Some(pu) = &mut s.obstacles[obstacle].punch {
                        pu.controls[component].scale(k);
                    }
                }
                LoadRef::Coupling { body, index, component } => {
                    s.bodies[body].couplings[index].controls[component].scale(k);
                }
            }
        }
        s
    }

    /// Whether any pair has friction (μ > 0).
    pub fn has_friction(&self) -> bool {
        self.pairs.iter().any(|p| p.friction > 0.0)
    }
}

#[derive(Debug, Clone, Copy, Default)]
pub struct Outputs {
    pub displacement: bool,
    pub mesh: bool,
    pub stress: bool,
    /// The VTU file (needs all three of the above, computed for it).
    pub vtu: bool,
}

impl Body {
    /// Whether the body's elements are quadratic.
    pub fn is_t6(&self) -> bool {
        match &self.mesh {
            MeshSource::Rectangle { order, .. } | MeshSource::Disk { order, .. } => *order == Order::T6,
            MeshSource::Inline(m) => m.order == Order::T6,
        }
    }
}

#[derive(Debug, Clone)]
pub struct Body {
    pub name: String,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub mesh: MeshSource,
    pub supports: Vec<Support>,
    pub tractions: Vec<Traction>,
    pub point_loads: Vec<PointLoad>,
    pub body_force: [f64; 2],
    /// Edge sets tied rigidly to a reference point (at most one; then no supports).
    pub couplings: Vec<Coupling>,
    /// JSON pointer of the body in the request.
    pub path: String,
}

/// The names of a punch's or coupling's three motions, in the order of
/// their controls, as the request spells them.
pub const COMPONENTS: [&str; 3] = ["horizontal", "vertical", "rotation"];

/// An edge set tied rigidly to a reference point (nondimensional): its nodes
/// move as (ux, uy) + θ e3 × (x − reference), each of (ux, Fx), (uy, Fy),
/// (θ, M) prescribed on one side as for a punch.
#[derive(Debug, Clone)]
pub struct Coupling {
    pub edges: String,
    pub reference: [f64; 2],
    pub controls: [Control; 3],
    /// JSON pointer of the coupling.
    pub path: String,
}

impl Coupling {
    /// The prescribed part of the coupling's motion at point x: the
    /// displacement-controlled components only (the loaded ones are solved
    /// for as the body's free motions).
    pub fn prescribed_at(&self, x: [f64; 2]) -> [f64; 2] {
        let v = |k: usize| match self.controls[k] {
            Control::Displacement(v) => v,
            Control::Load(_) => 0.0,
        };
        let (dx, dy) = (x[0] - self.reference[0], x[1] - self.reference[1]);
        [v(0) - v(2) * dy, v(1) + v(2) * dx]
    }

    /// The load of component k (0 where it is a displacement).
    pub fn load(&self, k: usize) -> f64 {
        match self.controls[k] {
            Control::Load(v) => v,
            Control::Displacement(_) => 0.0,
        }
    }

    /// Whether some component is load-controlled (solved for by contact).
    pub fn has_load(&self) -> bool {
        self.controls.iter().any(|c| matches!(c, Control::Load(_)))
    }
}

impl Body {
    /// The JSON pointer of the body's supports, or of the body when it has
    /// none: the request may leave `supports` out, and a refusal's path must
    /// resolve in it.
    pub fn supports_path(&self) -> String {
        if self.supports.is_empty() {
            self.path.clone()
        } else {
            format!("{}/supports", self.path)
        }
    }
}

/// How the body's mesh is obtained (generated lazily by the mesh stage).
/// Generated meshes keep the request's units; `Inline` is nondimensional.
#[derive(Debug, Clone)]
pub enum MeshSource {
    Rectangle {
        corner: [f64; 2],
        width: f64,
        height: f64,
        size: f64,
        grading: Option<([f64; 2], Grading)>,
        order: Order,
    },
    Disk {
        center: [f64; 2],
        radius: f64,
        down: bool,
        part: crate::mesh::generate::DiskPart,
        size: f64,
        grading: Option<Grading>,
        order: Order,
    },
    Inline(Mesh2d),
}

#[derive(Debug, Clone)]
pub struct Support {
    pub edges: String,
    pub ux: Option<f64>,
    pub uy: Option<f64>,
}

/// A surface load on an edge set, or on its part with x in `x_range`.
#[derive(Debug, Clone)]
pub enum Traction {
    Vector {
        edges: String,
        t: [f64; 2],
        x_range: Option<[f64; 2]>,
    },
    Pressure {
        edges: String,
        p: f64,
        x_range: Option<[f64; 2]>,
    },
}

/// A concentrated force at a point of an edge set (nondimensional); where it
/// falls on the mesh is found after meshing (`admit::point_loads`).
#[derive(Debug, Clone)]
pub struct PointLoad {
    pub edges: String,
    pub at: [f64; 2],
    pub force: [f64; 2],
    /// JSON pointer of the load.
    pub path: String,
}

#[derive(Debug, Clone)]
pub struct Obstacle {
    pub name: String,
    pub shape: Shape,
    /// Rigid motion controls; None: fixed.
    pub punch: Option<Punch>,
}

/// A rigid punch: motion (α1, α2, θ) about `reference`, each component either
/// prescribed or paired with a prescribed load (P1, P2, M) on the punch.
#[derive(Debug, Clone)]
pub struct Punch {
    pub reference: [f64; 2],
    pub controls: [Control; 3],
}

/// Punch profile ψ(t), t = x − x_r.
#[derive(Debug, Clone)]
pub enum Psi {
    Flat {
        half_width: f64,
        corner_radius: f64,
    },
    Circle {
        radius: f64,
    },
    /// (t, ψ) with increasing t.
    Points(Vec<[f64; 2]>),
}

impl Psi {
    /// ψ(t), or None outside the profile's extent.
    pub fn eval(&self, t: f64) -> Option<f64> {
        // Nodes placed at a profile's end by a mesh generator land there only to
        // round-off: accept them.
        let (t0, t1) = self.extent();
        let slack = 1e-9 * (t1 - t0);
        let t = if t < t0 && t >= t0 - slack {
            t0
        } else if t > t1 && t <= t1 + slack {
            t1
        } else {
            t
        };
        match self {
            Psi::Flat {
                half_width,
                corner_radius,
            } => {
                let a = t.abs();
                let flat = half_width - corner_radius;
                if a <= flat {
                    Some(0.0)
                } else if a <= *half_width {
                    let d = a - flat;
                    Some(corner_radius - (corner_radius * corner_radius - d * d).max(0.0).sqrt())
                } else {
                    None
                }
            }
            Psi::Circle { radius } => (t.abs() < *radius).then(|| radius - (radius * radius - t * t).sqrt()),
            Psi::Points(p) => {
                let k = p.windows(2).position(|w| t >= w[0][0] && t <= w[1][0])?;
                let (a, b) = (p[k], p[k + 1]);
                Some(a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]))
            }
        }
    }

    /// Extent [t_min, t_max] of the profile.
    pub fn extent(&self) -> (f64, f64) {
        match self {
            Psi::Flat { half_width, .. } => (-half_width, *half_width),
            Psi::Circle { radius } => (-radius, *radius),
            Psi::Points(p) => (p[0][0], p[p.len() - 1][0]),
        }
    }
}

#[derive(Debug, Clone)]
pub enum Shape {
    /// Half-plane {(x − p)·n ≤ 0}; `n` unit, pointing out of the obstacle.
    Line {
        point: [f64; 2],
        normal: [f64; 2],
    },
    Circle {
        center: [f64; 2],
        radius: f64,
    },
    /// Rigid material to the right of the direction of travel.
    Polyline {
        points: Vec<[f64; 2]>,
    },
    /// Surface y = reference_y + ψ(x − reference_x), rigid above.
    Profile {
        reference: [f64; 2],
        psi: Psi,
    },
}

#[derive(Debug, Clone)]
pub struct Pair {
    pub body: usize,
    pub edges: String,
    pub target: Target,
    pub path: String,
    /// Coulomb coefficient μ (0: frictionless).
    pub friction: f64,
}

/// What the pair's edge set may touch.
#[derive(Debug, Clone)]
pub enum Target {
    Obstacle(usize),
    /// A foundation of `Scene::foundations`.
    Foundation(usize),
    /// An edge set of another deformable body.
    Body {
        body: usize,
        edges: String,
        discretization: Discretization,
    },
}

/// A tensionless foundation (nondimensional).
#[derive(Debug, Clone)]
pub struct Foundation {
    pub name: String,
    pub y: f64,
    pub x_min: f64,
    pub x_max: f64,
    pub model: FoundationModel,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FoundationModel {
    Winkler {
        k: f64,
    },
    Pasternak {
        k: f64,
        mu: f64,
    },
    /// E* = E / (1 − ν²) and the reference distance d.
    HalfPlane {
        e_star: f64,
        d: f64,
    },
}

impl FoundationModel {
    /// The model's name in the request and the report.
    pub fn name(&self) -> &'static str {
        match self {
            FoundationModel::Winkler { .. } => "winkler",
            FoundationModel::Pasternak { .. } => "pasternak",
            FoundationModel::HalfPlane { .. } => "half_plane",
        }
    }

    /// The distance at which a load's deflection is zero, where the model
    /// needs one to fix its rigid motion (nondimensional).
    pub fn reference_distance(&self) -> Option<f64> {
        match self {
            FoundationModel::HalfPlane { d, .. } => Some(*d),
            _ => None,
        }
    }
}
