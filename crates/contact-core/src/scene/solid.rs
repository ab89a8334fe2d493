//! A validated 3D request (`analysis: "solid"`), nondimensional: what the
//! door (`scene::validate::solid`) makes of the wire's `solid` section. Its
//! given mesh (inline or Gmsh) is built and checked by `solid::door`, in
//! the solid room (the scene knows no tetrahedra: `mesh3d` and `solid`
//! build on `fem`, which reads the scene); the route `solve::solid`
//! solves it. No wire types.
//!
//! Scales: lengths are divided by `length` (the body's size, the largest
//! side of its bounding box), moduli, pressures and tractions by `modulus`
//! (Young's modulus), so the numerics see E = 1 and a body of size 1 as the
//! 2D scene does. Forces come back times `modulus · length²` (totals: a
//! solid has no thickness), moments times `modulus · length³`.

use std::collections::BTreeMap;

use crate::mesh::generate::{graded_points, Grading};
use crate::scene::{Outputs, Settings};

pub use super::solid_obstacle::{Obstacle, Plane};

/// Where the body's mesh comes from: the door's data, in nondimensional
/// coordinates, with the JSON pointer its faults are reported at.
#[derive(Debug, Clone)]
pub enum SolidMesh {
    /// A generated box (`mesh3d::generate::box_mesh`), built in the route's
    /// mesh stage.
    Box {
        lo: [f64; 3],
        hi: [f64; 3],
        size: f64,
        grading: Option<([f64; 3], Grading)>,
        t10: bool,
    },
    /// Inline nodes, tetrahedra (`ends[e]` is where element e's nodes end in
    /// `elements`) and face sets.
    Inline {
        nodes: Vec<[f64; 3]>,
        elements: Vec<usize>,
        ends: Vec<usize>,
        face_sets: BTreeMap<String, Vec<[usize; 3]>>,
        path: String,
    },
    /// Gmsh MSH 4.1 text and the physical volumes of the body (its
    /// coordinates divided by `SolidScene::length` when read).
    Gmsh {
        msh: String,
        volumes: Vec<String>,
        path: String,
    },
}

/// Components held on a face set: `fix[c] = Some(v)` prescribes u_c = v on
/// every node of the set (a roller or symmetry plane fixes one component).
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    pub faces: String,
    pub fix: [Option<f64>; 3],
}

impl Support {
    /// A roller (or symmetry plane) on `faces`: u_c = 0, the other two
    /// components free.
    pub fn roller(faces: &str, c: usize) -> Self {
        let mut fix = [None; 3];
        fix[c] = Some(0.0);
        Self {
            faces: faces.into(),
            fix,
        }
    }
}

/// A load on a face set, per unit area of the deformed-free (reference)
/// surface.
#[derive(Debug, Clone, PartialEq)]
pub enum FaceLoad {
    /// Pressure p acting against the outward normal (p > 0 pushes in).
    Pressure { faces: String, p: f64 },
    /// A traction vector t.
    Traction { faces: String, t: [f64; 3] },
}

impl FaceLoad {
    pub fn faces(&self) -> &str {
        match self {
            FaceLoad::Pressure { faces, .. } | FaceLoad::Traction { faces, .. } => faces,
        }
    }
}

#[derive(Debug, Clone)]
pub struct SolidScene {
    pub length: f64,
    pub modulus: f64,
    pub body: String,
    pub obstacle: String,
    pub mesh: SolidMesh,
    pub poisson_ratio: f64,
    pub supports: Vec<Support>,
    pub loads: Vec<FaceLoad>,
    pub body_force: [f64; 3],
    /// The rigid obstacle (`scene::solid_obstacle`).
    pub shape: Obstacle,
    /// The contact face set.
    pub faces: String,
    /// Hertz's paraboloid (apex, radius) added to the gap, if given (with
    /// a plane only: the door refuses it on a curved obstacle).
    pub paraboloid: Option<([f64; 3], f64)>,
    pub settings: Settings,
    /// What the reply carries besides the contact answer (`stress` and
    /// `vtu` are computed on request only).
    pub outputs: Outputs,
    pub client_id: Option<String>,
    pub time_limit: Option<f64>,
    /// Nodes of the mesh, as counted at the door (for a Gmsh text, all of
    /// its nodes).
    pub estimated_nodes: f64,
    /// Load multipliers to solve for (empty: the loads as given): every
    /// load and prescribed motion times each, the gaps as given.
    pub load_factors: Vec<f64>,
    /// Load path steps (empty: none; never with `load_factors`): each
    /// scales the tractions, supports and body force separately.
    pub load_path: Vec<SolidPathStep>,
}

/// One load path step of a solid: the factor of each traction and support
/// (its prescribed values) and of the body force, 1 where the step does not
/// name it, and the names as the request gave them (echoed in the reply).
#[derive(Debug, Clone, PartialEq)]
pub struct SolidPathStep {
    pub tractions: Vec<f64>,
    pub supports: Vec<f64>,
    pub body_force: f64,
    pub given: BTreeMap<String, f64>,
}

/// A solid's supports, face loads and body force: the scene's, or a load
/// path step's (`SolidScene::at_step`).
#[derive(Debug, Clone, PartialEq)]
pub struct SolidLoads {
    pub supports: Vec<Support>,
    pub loads: Vec<FaceLoad>,
    pub body_force: [f64; 3],
}

/// Nodes of a generated box's grid (`mesh3d::generate::box_mesh`), exact
/// before it is meshed: T4 nodes are the grid's, T10 adds the midsides of
/// every cell edge, face diagonal and main diagonal, which are the points of
/// the grid with each cell halved.
pub fn grid_nodes(lo: [f64; 3], hi: [f64; 3], size: f64, grading: Option<([f64; 3], Grading)>, t10: bool) -> f64 {
    let per_cell = if t10 { 2.0 } else { 1.0 };
    let bound = cells_bound(lo, hi, size, grading);
    (0..3)
        .map(|a| {
            let cells = match grading {
                // Past a million cells on an axis no mesh is solvable: the
                // bound answers without making 1e9 lines (an h_min of 1e-8
                // of the box, a refinement round's window widened).
                Some(_) if bound[a] > AXIS_CELLS_MADE => bound[a],
                Some((focus, g)) => (graded_points(lo[a], hi[a], focus[a], g, size).len() - 1) as f64,
                None => ((hi[a] - lo[a]) / size).ceil().max(1.0),
            };
            per_cell * cells + 1.0
        })
        .product()
}

/// Cells per axis above which `grid_nodes` counts by `cells_bound`.
const AXIS_CELLS_MADE: f64 = 1e6;

/// An upper bound of each axis's cells, before any line is made (an h_min
/// of 5e-324 would ask for 1e323 lines): no cell is below h_min, and past
/// the uniform zone (2 extent wide) each side grows by `ratio` to `size`
/// within log(size / h_min) / log(ratio) + 1 cells.
pub fn cells_bound(lo: [f64; 3], hi: [f64; 3], size: f64, grading: Option<([f64; 3], Grading)>) -> [f64; 3] {
    std::array::from_fn(|a| {
        let length = hi[a] - lo[a];
        let cells = match grading {
            None => (length / size).ceil().max(1.0),
            Some((_, g)) => {
                let growing = if g.ratio > 1.0 {
                    (size / g.h_min).ln() / g.ratio.ln() + 2.0
                } else {
                    f64::INFINITY
                };
                (length / g.h_min)
                    .min(2.0 * (g.extent / g.h_min + 1.0) + 2.0 * growing + length / size + 2.0)
                    .ceil()
            }
        };
        cells.max(1.0)
    })
}

impl SolidScene {
    /// The supports, face loads and body force at load path step `step`:
    /// each as given times its factor (a support's prescribed values, not
    /// which components it holds).
    pub fn at_step(&self, step: &SolidPathStep) -> SolidLoads {
        let supports = self
            .supports
            .iter()
            .zip(&step.supports)
            .map(|(s, f)| Support {
                faces: s.faces.clone(),
                fix: s.fix.map(|v| v.map(|v| f * v)),
            })
            .collect();
        let loads = self
            .loads
            .iter()
            .zip(&step.tractions)
            .map(|(l, f)| match l {
                FaceLoad::Pressure { faces, p } => FaceLoad::Pressure {
                    faces: faces.clone(),
                    p: f * p,
                },
                FaceLoad::Traction { faces, t } => FaceLoad::Traction {
                    faces: faces.clone(),
                    t: t.map(|v| f * v),
                },
            })
            .collect();
        SolidLoads {
            supports,
            loads,
            body_force: self.body_force.map(|v| step.body_force * v),
        }
    }

    /// The initial gap profile added to the distance to the plane at x:
    /// r² / 2R with r the distance from the apex across the plane's normal.
    pub fn extra_gap(&self, x: [f64; 3]) -> f64 {
        let (Some((apex, radius)), Obstacle::Plane(plane)) = (self.paraboloid, &self.shape) else {
            return 0.0;
        };
        let d: [f64; 3] = std::array::from_fn(|c| x[c] - apex[c]);
        let along: f64 = (0..3).map(|c| d[c] * plane.normal[c]).sum();
        let r2 = (0..3).map(|c| d[c] * d[c]).sum::<f64>() - along * along;
        r2.max(0.0) / (2.0 * radius)
    }
}
