//! Typed request constructors over the wire structs: the Rust twin of the
//! Python client's `contact_client.request`, so that the benches, suites and
//! tests put their scenes together from the same parts instead of spelling
//! whole JSON documents.
//!
//! ```
//! use contact_verify::build::*;
//! let req = request(
//!     vec![body("block", 200.0, 0.3, rectangle([-20.0, -20.0], 40.0, 20.0, 1.0, "t3"))
//!         .fixed("bottom")],
//!     vec![pair("block", "top").obstacle("cylinder")],
//! )
//! .with_obstacle(obstacle("cylinder", circle([0.0, 7.88], 8.0)));
//! assert_eq!(req.bodies.len(), 1);
//! ```

use contact_proto::{
    Analysis, BodyRef, BodySpec, ContactSpec, Discretization, ElementKind, ElementLists, Facing, FoundationModel,
    FoundationSpec, FrictionSpec, GradingSpec, HalfDiskSpec, InlineMeshSpec, MaterialSpec, MeshSpec, MethodName,
    ObstacleShape, ObstacleSpec, OutputKind, PointLoadSpec, RectangleSpec, SolveRequest, SolverSettings, SupportSpec,
    SurfaceSpec, TractionSpec, PROTOCOL_VERSION,
};

/// A request with the service's defaults for everything not given.
pub fn request(bodies: Vec<BodySpec>, contacts: Vec<ContactSpec>) -> SolveRequest {
    SolveRequest {
        version: PROTOCOL_VERSION.to_string(),
        description: None,
        client_id: None,
        time_limit: None,
        analysis: Default::default(),
        bodies,
        obstacles: Vec::new(),
        foundations: Vec::new(),
        contacts,
        method: MethodName::Auto,
        settings: SolverSettings::default(),
        outputs: Vec::new(),
        load_factors: Vec::new(),
        load_path: Vec::new(),
        units: None,
        solid: None,
    }
}

/// Additions to a request, chained.
pub trait RequestExt {
    fn with_obstacle(self, o: ObstacleSpec) -> Self;
    fn with_foundation(self, f: FoundationSpec) -> Self;
    fn with_method(self, m: MethodName) -> Self;
    fn with_description(self, d: &str) -> Self;
    fn with_analysis(self, a: Analysis) -> Self;
    /// The fields the reply carries besides the contact answer.
    fn with_outputs(self, o: &[OutputKind]) -> Self;
    /// The request as the JSON document the service reads.
    fn to_value(&self) -> serde_json::Value;
}

impl RequestExt for SolveRequest {
    fn with_obstacle(mut self, o: ObstacleSpec) -> Self {
        self.obstacles.push(o);
        self
    }
    fn with_foundation(mut self, f: FoundationSpec) -> Self {
        self.foundations.push(f);
        self
    }
    fn with_method(mut self, m: MethodName) -> Self {
        self.method = m;
        self
    }
    fn with_description(mut self, d: &str) -> Self {
        self.description = Some(d.to_string());
        self
    }
    fn with_analysis(mut self, a: Analysis) -> Self {
        self.analysis = a;
        self
    }
    fn with_outputs(mut self, o: &[OutputKind]) -> Self {
        self.outputs = o.to_vec();
        self
    }
    fn to_value(&self) -> serde_json::Value {
        wire(self)
    }
}

/// Any part of a request as the JSON the service reads: for a test that
/// changes one part of a checked-in example.
pub fn wire(part: &impl serde::Serialize) -> serde_json::Value {
    serde_json::to_value(part).expect("a request's part serializes")
}

/// `"t3"` or `"t6"` (anything else is T3's default).
pub fn element_kind(name: &str) -> ElementKind {
    match name {
        "t6" => ElementKind::T6,
        _ => ElementKind::T3,
    }
}

/// A method by its wire name (`"auto"`, `"active_set"`, …).
pub fn method_name(name: &str) -> MethodName {
    serde_json::from_value(serde_json::Value::String(name.to_string())).expect("a method name of the protocol")
}

/// A pair's discretization by its wire name (`"mortar"`, `"node_to_segment"`).
pub fn discretization(name: &str) -> Discretization {
    serde_json::from_value(serde_json::Value::String(name.to_string())).expect("a discretization of the protocol")
}

/// An elastic body with no supports or loads yet.
pub fn body(name: &str, youngs_modulus: f64, poisson_ratio: f64, mesh: MeshSpec) -> BodySpec {
    BodySpec {
        name: Some(name.to_string()),
        material: MaterialSpec {
            youngs_modulus,
            poisson_ratio,
        },
        mesh,
        supports: Vec::new(),
        tractions: Vec::new(),
        point_loads: Vec::new(),
        body_force: None,
        couplings: Vec::new(),
    }
}

/// Supports and loads on a body's edge sets, chained.
pub trait BodyExt {
    /// Prescribed displacement components (None: free).
    fn support(self, edges: &str, ux: Option<f64>, uy: Option<f64>) -> Self;
    /// Both components held at 0.
    fn fixed(self, edges: &str) -> Self;
    /// Uniform pressure, positive pushing into the body.
    fn pressure(self, edges: &str, p: f64) -> Self;
    /// Uniform traction vector [tx, ty] (force per length).
    fn traction(self, edges: &str, t: [f64; 2]) -> Self;
    /// Uniform pressure on the part of the edge set with x in [x_min, x_max].
    fn pressure_on(self, edges: &str, p: f64, x_range: [f64; 2]) -> Self;
    /// A concentrated force at a point of the edge set.
    fn point_load(self, edges: &str, at: [f64; 2], force: [f64; 2]) -> Self;
    /// Body force per unit volume.
    fn body_force(self, f: [f64; 2]) -> Self;
}

impl BodyExt for BodySpec {
    fn support(mut self, edges: &str, ux: Option<f64>, uy: Option<f64>) -> Self {
        self.supports.push(SupportSpec {
            edges: edges.to_string(),
            ux,
            uy,
        });
        self
    }
    fn fixed(self, edges: &str) -> Self {
        self.support(edges, Some(0.0), Some(0.0))
    }
    fn pressure(mut self, edges: &str, p: f64) -> Self {
        self.tractions.push(TractionSpec {
            edges: edges.to_string(),
            traction: None,
            pressure: Some(p),
            x_range: None,
        });
        self
    }
    fn traction(mut self, edges: &str, t: [f64; 2]) -> Self {
        self.tractions.push(TractionSpec {
            edges: edges.to_string(),
            traction: Some(t),
            pressure: None,
            x_range: None,
        });
        self
    }
    fn pressure_on(mut self, edges: &str, p: f64, x_range: [f64; 2]) -> Self {
        self.tractions.push(TractionSpec {
            edges: edges.to_string(),
            traction: None,
            pressure: Some(p),
            x_range: Some(x_range),
        });
        self
    }
    fn point_load(mut self, edges: &str, at: [f64; 2], force: [f64; 2]) -> Self {
        self.point_loads.push(PointLoadSpec {
            edges: edges.to_string(),
            at,
            force,
        });
        self
    }
    fn body_force(mut self, f: [f64; 2]) -> Self {
        self.body_force = Some(f);
        self
    }
}

/// Generated rectangle from its lower-left corner; edge sets bottom, right, top, left.
pub fn rectangle(corner: [f64; 2], width: f64, height: f64, size: f64, element_name: &str) -> MeshSpec {
    MeshSpec::Rectangle(RectangleSpec {
        corner,
        width,
        height,
        size,
        element: element_kind(element_name),
        grading: None,
    })
}

/// A mesh given node by node: triangles as node indices (3 per T3, 6 per
/// T6), each edge set as its edges' corner nodes.
pub fn inline(nodes: &[[f64; 2]], elements: &[Vec<usize>], edge_sets: &[(&str, &[[usize; 2]])]) -> MeshSpec {
    MeshSpec::Inline(InlineMeshSpec {
        nodes: nodes.to_vec(),
        elements: elements.iter().collect::<ElementLists>(),
        edge_sets: edge_sets
            .iter()
            .map(|(name, edges)| (name.to_string(), edges.to_vec()))
            .collect(),
    })
}

/// Generated quarter-disk (edge sets arc, flat, axis), arc facing down when `down`.
pub fn quarter_disk(center: [f64; 2], radius: f64, down: bool, size: f64, element_name: &str) -> MeshSpec {
    MeshSpec::QuarterDisk(disk(center, radius, down, size, element_name))
}

/// Generated half-disk (edge sets arc, flat), arc facing down when `down`.
pub fn half_disk(center: [f64; 2], radius: f64, down: bool, size: f64, element_name: &str) -> MeshSpec {
    MeshSpec::HalfDisk(disk(center, radius, down, size, element_name))
}

fn disk(center: [f64; 2], radius: f64, down: bool, size: f64, element_name: &str) -> HalfDiskSpec {
    HalfDiskSpec {
        center,
        radius,
        facing: if down { Facing::Down } else { Facing::Up },
        size,
        element: element_kind(element_name),
        grading: None,
    }
}

/// Elements of `h_min` within `extent` of `focus` (a disk's apex when None),
/// growing by `ratio` per element beyond.
pub fn grading(h_min: f64, ratio: f64, extent: f64, focus: Option<[f64; 2]>) -> GradingSpec {
    GradingSpec {
        focus,
        h_min,
        ratio,
        extent,
    }
}

/// The mesh with a grading (generated meshes only; others unchanged).
pub fn graded(mesh: MeshSpec, g: GradingSpec) -> MeshSpec {
    match mesh {
        MeshSpec::Rectangle(r) => MeshSpec::Rectangle(RectangleSpec { grading: Some(g), ..r }),
        MeshSpec::HalfDisk(d) => MeshSpec::HalfDisk(HalfDiskSpec { grading: Some(g), ..d }),
        MeshSpec::QuarterDisk(d) => MeshSpec::QuarterDisk(HalfDiskSpec { grading: Some(g), ..d }),
        other => other,
    }
}

/// A fixed rigid obstacle.
pub fn obstacle(name: &str, shape: ObstacleShape) -> ObstacleSpec {
    ObstacleSpec {
        name: Some(name.to_string()),
        shape,
        punch: None,
    }
}

/// Rigid disk.
pub fn circle(center: [f64; 2], radius: f64) -> ObstacleShape {
    ObstacleShape::Circle { center, radius }
}

/// Rigid half-plane through `point`, `normal` pointing out of it.
pub fn line(point: [f64; 2], normal: [f64; 2]) -> ObstacleShape {
    ObstacleShape::Line { point, normal }
}

/// A tensionless foundation along y, x in [x_min, x_max].
pub fn foundation(name: &str, model: FoundationModel, x_min: f64, x_max: f64, y: f64) -> FoundationSpec {
    FoundationSpec {
        name: Some(name.to_string()),
        y,
        x_min,
        x_max,
        model,
    }
}

/// A contact pair of a body's edge set; name its target with [`PairExt`].
pub fn pair(body: &str, edges: &str) -> ContactSpec {
    ContactSpec {
        body: BodyRef::Name(body.to_string()),
        edges: edges.to_string(),
        obstacle: None,
        against: None,
        foundation: None,
        discretization: Discretization::default(),
        friction: None,
    }
}

/// The target of a pair.
pub trait PairExt {
    fn obstacle(self, name: &str) -> Self;
    fn against(self, body: &str, edges: &str, d: Discretization) -> Self;
    fn foundation(self, name: &str) -> Self;
    /// Coulomb friction of coefficient μ.
    fn friction(self, mu: f64) -> Self;
}

impl PairExt for ContactSpec {
    fn obstacle(mut self, name: &str) -> Self {
        self.obstacle = Some(BodyRef::Name(name.to_string()));
        self
    }
    fn against(mut self, body: &str, edges: &str, d: Discretization) -> Self {
        self.against = Some(SurfaceSpec {
            body: BodyRef::Name(body.to_string()),
            edges: edges.to_string(),
        });
        self.discretization = d;
        self
    }
    fn foundation(mut self, name: &str) -> Self {
        self.foundation = Some(BodyRef::Name(name.to_string()));
        self
    }
    fn friction(mut self, mu: f64) -> Self {
        self.friction = Some(FrictionSpec { coefficient: mu });
        self
    }
}
