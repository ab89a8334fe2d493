//! The validated, nondimensional domain model built from a request.
//!
//! `Scene::try_new` is the only place that rejects request content; everything
//! downstream trusts it. All lengths are divided by `scales.length` and all
//! moduli and stresses by `scales.modulus`, so the numerics see O(1) numbers
//! whatever the caller's units.

pub mod parse;
pub mod scaling;
pub mod validate;

pub use scaling::Scales;
pub use validate::Limits;

use crate::mesh::{generate::Grading, Mesh2d, Order};
use crate::proto::{Analysis, MethodName, SolverSettings};

#[derive(Debug, Clone)]
pub struct Scene {
    pub analysis: Analysis,
    pub scales: Scales,
    pub bodies: Vec<Body>,
    pub obstacles: Vec<Obstacle>,
    pub pairs: Vec<Pair>,
    pub method: MethodName,
    pub settings: SolverSettings,
    pub outputs: Outputs,
    pub client_id: Option<String>,
    /// Load multipliers to solve for (empty: the loads as given).
    pub load_factors: Vec<f64>,
}

impl Scene {
    /// The same scene with every load and prescribed displacement times `k`.
    pub fn scaled(&self, k: f64) -> Scene {
        let mut s = self.clone();
        s.load_factors.clear();
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
        }
        s
    }
}

#[derive(Debug, Clone, Copy, Default)]
pub struct Outputs {
    pub displacement: bool,
    pub mesh: bool,
    pub stress: bool,
}

#[derive(Debug, Clone)]
pub struct Body {
    pub name: String,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub mesh: MeshSource,
    pub supports: Vec<Support>,
    pub tractions: Vec<Traction>,
    pub body_force: [f64; 2],
    /// JSON pointer of the body in the request.
    pub path: String,
}

/// How the body's mesh is obtained (generated lazily by the mesh stage).
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
    HalfDisk {
        center: [f64; 2],
        radius: f64,
        down: bool,
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

#[derive(Debug, Clone)]
pub enum Traction {
    Vector { edges: String, t: [f64; 2] },
    Pressure { edges: String, p: f64 },
}

#[derive(Debug, Clone)]
pub struct Obstacle {
    pub name: String,
    pub shape: Shape,
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
}

#[derive(Debug, Clone)]
pub struct Pair {
    pub body: usize,
    pub edges: String,
    pub obstacle: usize,
    pub path: String,
}
