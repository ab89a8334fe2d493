//! The solve request. Units are the caller's, but must be consistent
//! (e.g. mm, N, MPa); forces are per unit thickness.
//!
//! Length: the whole request in one file, so that its documentation (these doc
//! comments, which become the JSON Schema) reads in one place; type definitions only.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A contact problem: bodies, rigid obstacles, contact pairs, method and outputs.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = required_by_analysis)]
pub struct SolveRequest {
    /// Protocol version; must be "1".
    pub version: String,
    /// Free text describing the physical setup (echoed nowhere, for humans).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Optional caller id, returned unchanged in the reply for correlation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub client_id: Option<String>,
    /// Optional limit on the solve time in seconds; the service applies the smaller of this and its own limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_limit: Option<f64>,
    /// Plane strain (default), plane stress, axisymmetry, or a 3D solid.
    #[serde(default)]
    pub analysis: Analysis,
    /// Elastic bodies (at least one; none with `analysis: "solid"`, whose
    /// body is in `solid`).
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// Rigid obstacles the bodies may touch.
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
    /// Tensionless deformable foundations the bodies may rest on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub foundations: Vec<FoundationSpec>,
    /// Contact pairs: which boundary edges of which body may touch which
    /// obstacle, other body or foundation (at least one; none with
    /// `analysis: "solid"`).
    #[serde(default)]
    pub contacts: Vec<ContactSpec>,
    /// Constraint treatment.
    #[serde(default)]
    pub method: MethodName,
    /// Numerical settings; every field has a documented default.
    #[serde(default)]
    pub settings: SolverSettings,
    /// Optional fields of the reply, computed only when listed.
    #[serde(default)]
    pub outputs: Vec<OutputKind>,
    /// Solve once per factor, with every load and prescribed displacement
    /// multiplied by it (gaps unchanged), from one factorization. The reply's
    /// `steps` holds each answer.
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "crate::bounded::load_factors"
    )]
    pub load_factors: Vec<f64>,
    /// Solve step by step, each step scaling named loads and prescribed
    /// displacements separately (so that a normal load can be held while a
    /// tangential one grows); history-dependent contact (friction) carries
    /// its state from one step to the next. Not together with `load_factors`.
    /// The reply's `steps` holds each answer.
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "crate::bounded::load_path"
    )]
    pub load_path: Vec<LoadPathStep>,
    /// The names of the units the request's numbers are in, echoed in the
    /// reply for plots and files. Nothing is converted: the numbers must be
    /// consistent (e.g. mm, N, MPa) whatever the names say.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<Units>,
    /// The 3D problem, with `analysis: "solid"` only (then `bodies`,
    /// `obstacles`, `foundations` and `contacts` stay empty).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solid: Option<crate::solid::SolidSpec>,
}

/// A 2D request needs `bodies` and `contacts`, a 3D solid its `solid`: the
/// service refuses the others, and the schema is as strict (serde reads an
/// absent list as empty, so the types alone would not say it).
fn required_by_analysis(schema: &mut schemars::Schema) {
    let solid = serde_json::json!({"properties": {"analysis": {"const": "solid"}}, "required": ["analysis"]});
    schema.insert("if".into(), solid);
    schema.insert("then".into(), serde_json::json!({"required": ["solid"]}));
    schema.insert("else".into(), serde_json::json!({"required": ["bodies", "contacts"]}));
}

/// One step of a load path.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadPathStep {
    /// Factor of each named load or prescribed displacement at this step, by
    /// its JSON pointer in the request: `/bodies/0/tractions/1`,
    /// `/bodies/0/point_loads/0`, `/bodies/0/supports/2` (its prescribed
    /// values), `/bodies/0/body_force`, a coupling's component
    /// `/bodies/0/couplings/0/vertical` (`horizontal`, `rotation`), and a punch's motion
    /// `/obstacles/0/punch/horizontal` (`vertical`, `rotation`: its load or
    /// displacement); a 3D solid's `/solid/body/tractions/0`,
    /// `/solid/body/supports/1` (its prescribed values) and
    /// `/solid/body/body_force`. Those not named keep factor 1 (as
    /// given). To move one component of a support separately, give it its own
    /// support entry on the same edge (or face) set.
    #[serde(default)]
    pub loads: std::collections::BTreeMap<String, f64>,
}

/// Names of units (free text of at most 32 characters, e.g. "mm", "N", "MPa").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Units {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<String>,
    /// Force (per unit thickness where the reply says so).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force: Option<String>,
    /// Stress and pressure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stress: Option<String>,
}

/// Kinematic assumption: a 2D section, or a 3D solid.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Analysis {
    #[default]
    PlaneStrain,
    PlaneStress,
    /// A body of revolution under loads of revolution, computed on its r–z
    /// half-section: x is the radius r ≥ 0, y the axis z. Nodes on the axis
    /// (r = 0) have u_r = 0. Forces (resultants, point loads, punch loads,
    /// contact forces) are totals over the whole circumference; a point load
    /// at radius r is a ring load. Radial resultants and moments vanish by
    /// symmetry and are reported as 0; punches move along the axis only.
    Axisymmetric,
    /// A 3D body of tetrahedra (the request's `solid`): one body, one rigid
    /// plane, frictionless, method `auto` or `active_set`; no load factors,
    /// load path, outputs or error estimate yet.
    Solid,
}

/// One elastic body.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Name used in replies; defaults to "body<i>".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    pub material: MaterialSpec,
    pub mesh: MeshSpec,
    /// Displacement constraints on named edge sets (fixed supports, rollers, prescribed motion).
    #[serde(default)]
    pub supports: Vec<SupportSpec>,
    /// Surface loads on named edge sets (or on part of one, `x_range`).
    #[serde(default)]
    pub tractions: Vec<TractionSpec>,
    /// Concentrated forces at points of named edge sets.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub point_loads: Vec<PointLoadSpec>,
    /// Body force per unit volume [force/length³], e.g. weight density.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body_force: Option<[f64; 2]>,
    /// Rigid couplings of edge sets to a reference point (at most one per
    /// body; a body with one takes no `supports`): an axle pushed or held.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub couplings: Vec<CouplingSpec>,
}

/// An edge set tied rigidly to a reference point: every node of it moves as
/// u = (ux, uy) + θ e3 × (x − reference), with the reference point's three
/// motions each prescribed as a displacement or as a load, as for a punch
/// (the edge set is a rigid axle or hub; the body may still deform
/// elsewhere). Loads act on the reference point: forces in the global axes,
/// the moment about `reference`, counter-clockwise positive. A body pressed
/// down through its axle onto something below has a negative vertical load.
/// The body must take part in a contact pair when a component is a load
/// (contact holds it). In axisymmetry only `vertical` may be given: the
/// edge set moves along the axis.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CouplingSpec {
    /// Name of the edge set tied to the reference point; not also a contact
    /// surface: its nodes are no contact candidates, even at the ends it
    /// shares with one (a half-disk's flat and arc share two nodes).
    pub edges: String,
    /// The reference point [x, y] [length]: the axle's centre. At most 10⁴
    /// times the body's size (the largest side of its bounding box) away from
    /// that box: farther, the lever arms about it cost the solve its
    /// precision, and the request is refused (`invalid_request`).
    pub reference: [f64; 2],
    /// ux [length] or Fx [force]; default: displacement 0.
    #[serde(default)]
    pub horizontal: Control,
    /// uy [length] or Fy [force]; default: displacement 0.
    #[serde(default)]
    pub vertical: Control,
    /// θ [radian, small] or M [force × length] about `reference`; default:
    /// displacement 0 (rotation held). A load of 0 leaves the axle free to
    /// turn.
    #[serde(default)]
    pub rotation: Control,
}

/// A concentrated force [force per unit thickness] at a point of an edge set
/// (a node, or between nodes: shared by the edge's nodes as its shape
/// functions there say, the consistent nodal load of a point force).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointLoadSpec {
    /// Name of the edge set the point lies on.
    pub edges: String,
    /// The point [x, y] [length]; it must lie on the edge set (within 1e-6 of
    /// the body's size).
    pub at: [f64; 2],
    /// The force [fx, fy] [force per unit thickness].
    pub force: [f64; 2],
}

/// Isotropic linear elastic material.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Young's modulus E > 0 [force/length²].
    pub youngs_modulus: f64,
    /// Poisson's ratio, -1 < ν < 0.5.
    pub poisson_ratio: f64,
}

/// Triangle order for generated meshes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ElementKind {
    /// Linear 3-node triangle.
    #[default]
    T3,
    /// Quadratic 6-node triangle (corners, then midsides of edges 01, 12, 20).
    T6,
}

/// A body's mesh: generated from a few parameters, or given inline.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum MeshSpec {
    /// Rectangle [x0, x0+width] × [y0, y0+height]; edge sets "bottom", "right", "top", "left".
    Rectangle(RectangleSpec),
    /// Half-disk; edge sets "flat" (the diameter) and "arc".
    HalfDisk(HalfDiskSpec),
    /// The half of a half-disk on the +x side of its centre, for models
    /// symmetric about the apex line; edge sets "flat", "arc" and "axis" (the
    /// symmetry line x = center[0], to be held with ux = 0).
    QuarterDisk(HalfDiskSpec),
    /// Explicit nodes, triangles and named edge sets.
    Inline(InlineMeshSpec),
    /// A Gmsh MSH 4.1 ASCII mesh: triangles (types 2, 9) make the body, the
    /// line elements of each physical curve group the edge set of that name.
    Gmsh(GmshMeshSpec),
}

/// A mesh made with Gmsh, as MSH 4.1 ASCII text (`msh`) or, for `contact solve
/// FILE` only, a file path relative to the request file (`file`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GmshMeshSpec {
    /// The content of a `.msh` file (format 4.1, ASCII).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub msh: Option<String>,
    /// Path of a `.msh` file next to the request; read by the command-line
    /// tool, refused by the service (send the text in `msh`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Physical surface groups that make up this body (default: every triangle in the file).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub surfaces: Vec<String>,
}

/// Local refinement toward a focus point: element size `h_min` within `extent`
/// of the focus, then growing geometrically by `ratio` per element up to the
/// mesh's `size`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GradingSpec {
    /// Point where the mesh is finest (for a half-disk: ignored, the apex of the arc is used).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus: Option<[f64; 2]>,
    /// Element size at the focus [length].
    pub h_min: f64,
    /// Growth factor of neighbouring element sizes, 1 ≤ ratio ≤ 2.
    #[serde(default = "default_ratio")]
    pub ratio: f64,
    /// Half-width of the zone around the focus meshed uniformly at `h_min`
    /// (make it cover the expected contact zone) [length].
    #[serde(default)]
    pub extent: f64,
}

fn default_ratio() -> f64 {
    1.1
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RectangleSpec {
    /// Lower-left corner [x0, y0].
    pub corner: [f64; 2],
    pub width: f64,
    pub height: f64,
    /// Element size away from the focus (uniform mesh without grading) [length].
    pub size: f64,
    #[serde(default)]
    pub element: ElementKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading: Option<GradingSpec>,
}

/// Which way the arc of a half-disk bulges.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Facing {
    /// Arc below the flat face (a roller resting on something below).
    #[default]
    Down,
    /// Arc above the flat face.
    Up,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HalfDiskSpec {
    /// Centre of the full disk (midpoint of the flat face).
    pub center: [f64; 2],
    pub radius: f64,
    #[serde(default)]
    pub facing: Facing,
    /// Element size away from the apex [length].
    pub size: f64,
    #[serde(default)]
    pub element: ElementKind,
    /// Refinement toward the apex of the arc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading: Option<GradingSpec>,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InlineMeshSpec {
    /// Node coordinates [[x, y], ...].
    pub nodes: Vec<[f64; 2]>,
    /// Triangles as 0-based node indices, counter-clockwise: 3 per T3, 6 per T6
    /// (corners, then midsides of edges 01, 12, 20). All elements of one order.
    pub elements: crate::ElementLists,
    /// Named boundary edge sets: each edge as its two corner node indices.
    pub edge_sets: std::collections::BTreeMap<String, Vec<[usize; 2]>>,
}

/// Prescribed displacement components on an edge set. A component set to 0 is a
/// support (both: fixed; one: roller); a nonzero value prescribes motion.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    /// Name of the edge set.
    pub edges: String,
    /// Prescribed x displacement [length]; absent = free.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ux: Option<f64>,
    /// Prescribed y displacement [length]; absent = free.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uy: Option<f64>,
}

/// A surface load on an edge set: a traction vector, or a normal pressure, not both.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    pub edges: String,
    /// Traction vector [tx, ty] [force/length²].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traction: Option<[f64; 2]>,
    /// Normal pressure, positive pushing into the body [force/length²].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<f64>,
    /// Load only the part of the edge set with x in [x_min, x_max] [length]
    /// (an edge crossing an end is loaded on its part inside).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x_range: Option<[f64; 2]>,
}

/// A rigid obstacle, fixed or (with `punch`) a rigid punch whose motion and loads
/// are partly prescribed.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    pub shape: ObstacleShape,
    /// Rigid-body motion of the obstacle: without it the obstacle is fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub punch: Option<PunchSpec>,
}

/// The three rigid motions of a punch, each prescribed as a displacement or as a
/// load (then the displacement is solved for). Loads act on the punch: forces in
/// the global axes, the moment about `reference`, counter-clockwise positive. A
/// punch pressed down onto a body below has a negative vertical load.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PunchSpec {
    /// Point about which the punch rotates and moments are taken.
    pub reference: [f64; 2],
    /// α1 [length] or P1 [force]; default: displacement 0.
    #[serde(default)]
    pub horizontal: Control,
    /// α2 [length] or P2 [force]; default: displacement 0.
    #[serde(default)]
    pub vertical: Control,
    /// θ [radian, small] or M [force × length]; default: displacement 0.
    #[serde(default)]
    pub rotation: Control,
}

/// One side of a (motion, load) pair.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Control {
    Displacement(f64),
    Load(f64),
}

/// Read by hand only to name the mistake of giving both sides: serde's
/// derived reader stops at the second key with a syntax error ("expected
/// value"), which the parser must call malformed JSON, without a path.
impl<'de> Deserialize<'de> for Control {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Sides;
        impl<'de> serde::de::Visitor<'de> for Sides {
            type Value = Control;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an object with one of `displacement` and `load`")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Control, A::Error> {
                use serde::de::Error;
                let mut out = None;
                while let Some(key) = map.next_key::<String>()? {
                    let side: fn(f64) -> Control = match key.as_str() {
                        "displacement" => Control::Displacement,
                        "load" => Control::Load,
                        other => return Err(A::Error::unknown_variant(other, &["displacement", "load"])),
                    };
                    let v: f64 = map.next_value()?;
                    if out.is_some() {
                        return Err(A::Error::custom(
                            "give one of `displacement` and `load`, not both: a motion is prescribed, or its load is",
                        ));
                    }
                    out = Some(side(v));
                }
                out.ok_or_else(|| A::Error::custom("give one of `displacement` and `load`"))
            }
        }
        d.deserialize_map(Sides)
    }
}

impl Default for Control {
    fn default() -> Self {
        Control::Displacement(0.0)
    }
}

/// Punch profile ψ(t): the rigid surface is y = y_r + ψ(x − x_r) with the rigid
/// material above it (a punch coming down onto a body).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ProfileSpec {
    /// Flat base |t| ≤ half_width, with corners rounded by `corner_radius` (0: sharp).
    Flat {
        half_width: f64,
        #[serde(default)]
        corner_radius: f64,
    },
    /// Circle of the given radius whose lowest point is at t = 0, ψ(0) = 0.
    Circle { radius: f64 },
    /// Points (t, ψ) with increasing t, linear in between.
    Polyline { points: Vec<[f64; 2]> },
    /// Tabulated ψ at increasing t, linear in between.
    Table { t: Vec<f64>, psi: Vec<f64> },
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ObstacleShape {
    /// Straight boundary through `point`; the rigid half-plane lies on the side
    /// opposite to `normal` (the normal points out of the obstacle, toward the body).
    Line { point: [f64; 2], normal: [f64; 2] },
    /// Rigid disk; bodies stay outside it.
    Circle { center: [f64; 2], radius: f64 },
    /// Polyline surface; the rigid material lies to the right of the direction
    /// of travel (a floor is given left to right). Extends no further than its ends.
    Polyline { points: Vec<[f64; 2]> },
    /// Punch profile: surface y = reference_y + ψ(x − reference_x), rigid above.
    Profile { reference: [f64; 2], psi: ProfileSpec },
}

/// A contact pair: an edge set of a body against exactly one of an obstacle
/// (`obstacle`), an edge set of another deformable body (`against`) or a
/// foundation (`foundation`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Body index (0-based) or name.
    pub body: BodyRef,
    /// Name of the body's edge set whose nodes are contact candidates (for two
    /// bodies: the non-mortar or "slave" side, where the pressure is discretized).
    pub edges: String,
    /// Rigid obstacle index (0-based) or name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<BodyRef>,
    /// The other deformable body's facing edge set (the mortar or "master" side).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub against: Option<SurfaceSpec>,
    /// Foundation index (0-based) or name: the edge set rests on it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub foundation: Option<BodyRef>,
    /// How the non-penetration condition between two bodies is discretized
    /// (ignored for rigid obstacles).
    #[serde(default)]
    pub discretization: Discretization,
    /// Coulomb friction on the pair (default: frictionless): against rigid
    /// obstacles, punches and other bodies, in plane strain, plane stress and
    /// axisymmetry, with the methods `auto` and `active_set`; not on or
    /// beside foundations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionSpec>,
}

/// Coulomb friction: the tangential traction |t| ≤ μ p, sliding where it
/// reaches μ p, sticking where it is below.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    /// 0 ≤ μ ≤ 1e6 (0: frictionless); beyond 1e6 the request is refused
    /// (`invalid_request`): the friction a normal force at round-off carries,
    /// μ ε, would no longer be round-off. A large μ sticks wherever the
    /// surfaces press, which 1e6 already gives.
    pub coefficient: f64,
}

/// A tensionless foundation under the bodies: its surface is the horizontal
/// segment y = `y`, x_min ≤ x ≤ x_max, with the foundation below it. It pushes
/// up where a body presses on it and never pulls.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FoundationSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Height of the unloaded surface [length].
    pub y: f64,
    /// Extent of the foundation along x [length]: body nodes outside it find no
    /// foundation; a Pasternak layer ends there (free ends).
    pub x_min: f64,
    pub x_max: f64,
    pub model: FoundationModel,
}

/// The foundation's response to the pressure p(x) it carries (deflection w,
/// positive downward).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum FoundationModel {
    /// p = k w: independent springs of stiffness `stiffness` [pressure / length].
    Winkler { stiffness: f64 },
    /// p = k w − (μ w')': springs `stiffness` k [pressure / length] coupled by a
    /// shear layer `shear` μ [force per unit thickness]; outside the loaded zone
    /// the surface decays over √(μ/k).
    Pasternak { stiffness: f64, shear: f64 },
    /// An elastic half-plane (plane strain), w = T[p] with the Flamant kernel
    /// (2 / (π E*)) ln(d / |x − t|), E* = E / (1 − ν²). The surface displacement of
    /// a 2D half-plane is defined only up to a rigid motion: w = 0 at the
    /// distance `reference_distance` d from a point load; d must exceed a quarter
    /// of the loaded length.
    HalfPlane {
        youngs_modulus: f64,
        poisson_ratio: f64,
        reference_distance: f64,
    },
}

/// An edge set of a body.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SurfaceSpec {
    /// Body index (0-based) or name.
    pub body: BodyRef,
    /// Name of the body's edge set.
    pub edges: String,
}

/// Discretization of the two-body contact condition.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Discretization {
    /// Segment-to-segment (mortar): the gap is weighted by the non-mortar shape
    /// functions and integrated over the overlap of the two surfaces; passes the
    /// contact patch test (transmits a uniform pressure exactly).
    #[default]
    Mortar,
    /// Node-to-segment: each non-mortar node is projected along its normal onto
    /// the other body's surface; cheaper, fails the patch test on non-matching meshes.
    NodeToSegment,
}

/// Reference to a body or obstacle by index or by name.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum BodyRef {
    Index(usize),
    Name(String),
}

/// Constraint treatment.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MethodName {
    /// Fastest exact method for the scene (currently the condensed active set).
    #[default]
    Auto,
    /// Primal-dual active set (semismooth Newton) on the condensed contact problem,
    /// with a monotone active-set fallback if it cycles.
    ActiveSet,
    /// Interior point (Clarabel) on the condensed contact problem.
    InteriorPoint,
    /// Exterior penalty: pressure = penetration / ζ (`settings.penalty`); not exact,
    /// the reply's max_penetration and certificate show by how much.
    Penalty,
    /// Augmented Lagrangian (Uzawa) on the penalty: exact for any fixed ζ.
    AugmentedLagrangian,
    /// Interior penalty (log barrier): pressure = ζ / gap (`settings.barrier`),
    /// driven down to ζ by continuation from a strictly feasible start; never
    /// penetrates, not exact (open candidates carry ζ/gap).
    Barrier,
}

/// Numerical settings. All tolerances are relative and dimensionless.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    /// Convergence tolerance on the relative KKT residuals.
    pub tolerance: f64,
    /// Iteration cap of the contact iteration.
    pub max_iterations: usize,
    /// Candidates whose initial gap exceeds this multiple of the pair's body size are
    /// dropped before the solve (they cannot close under small strain).
    pub prune_gap_ratio: f64,
    /// Penalty parameter ζ of `penalty` and `augmented_lagrangian`: the
    /// compliance of the contact springs [length / pressure]. Default: 1e-6 of
    /// the natural compliance L/E (largest body size over largest modulus).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty: Option<f64>,
    /// `condensed` (default: one factorization, the LCP on the contact
    /// candidates) or `full` (active set / interior point on the whole system,
    /// refactoring per iteration; for comparison, exact methods only). With
    /// friction, `full` is the frictional active set on the whole system
    /// (nodal rows only: T3 against obstacles and punches with prescribed
    /// motions), which also serves a frictional scene whose contact rows
    /// exceed the condensed formulation's limit.
    pub formulation: Formulation,
    /// Barrier parameter ζ of `barrier` [pressure × length]: the pressure at a
    /// candidate is ζ / gap. Default: 1e-8 of E·L (largest modulus × body size).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub barrier: Option<f64>,
    /// How the gap of a contact row is measured: `signed_distance` (default)
    /// or `body_normal`.
    pub gap: GapMeasure,
    /// Where the mortar rows of T6 surfaces (against rigid obstacles, punches
    /// and other bodies) carry their multipliers: `every_node` (default) or
    /// `corners`.
    pub t6_multipliers: T6Multipliers,
    /// Estimate every pair's pressure error by a second, coarser solve of the
    /// same scene (generated meshes only; default true). The zone ends'
    /// uncertainty is always given.
    pub estimate: bool,
    /// Accuracy to reach: the generated meshes are refined round by round
    /// until the estimates are below these targets or a limit is met.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<AccuracyTarget>,
}

/// Targets of tolerance-driven refinement: set at least one of `pressure_l2`
/// and `zone_edge`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AccuracyTarget {
    /// Estimated relative L2 error of every pair's pressure over its zone (e.g. 0.005).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure_l2: Option<f64>,
    /// Estimated error of every zone end's position [length].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zone_edge: Option<f64>,
    /// Most solves, the first included (default 6).
    #[serde(default = "default_rounds")]
    pub max_rounds: usize,
    /// Largest number of degrees of freedom a round may have (default 400000,
    /// within the service's own size limit).
    #[serde(default = "default_max_dofs")]
    pub max_dofs: usize,
}

fn default_rounds() -> usize {
    6
}

fn default_max_dofs() -> usize {
    400_000
}

/// The linearized non-penetration condition of a contact row.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GapMeasure {
    /// The signed distance to the closest point of the obstacle (or of the
    /// other body's surface, or the vertical distance to a foundation), the row
    /// along the normal there: the first-order linearization of d(x + u) ≥ 0,
    /// exact against a flat obstacle. On T6 surfaces the rows against rigid
    /// obstacles are mortar rows (see `t6_multipliers`).
    #[default]
    SignedDistance,
    /// The gap along the body's own outward normal, one row per node (the
    /// classical u·n ≤ s). It differs from `signed_distance` where the body's
    /// normal and the obstacle's differ (a curved body on a flat: the pressure
    /// error against Hertz then stalls near 2 %).
    BodyNormal,
}

/// Where the mortar rows of a T6 surface carry their Lagrange multipliers.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum T6Multipliers {
    /// On every surface node, corners and midsides (a linear hat and its dual
    /// on each half of an edge): the zone edge is resolved at the full node
    /// spacing, T6 beats T3 per DOF (disk on a flat, 0.23 % at 8.8k DOF
    /// against T3's 0.24 % at 18k), but next to the zone edge corner and
    /// midside values alternate (up to 1e-2 of the peak pressure on a zone
    /// 20 element edges wide, a few % on one under 10). Edges that are chords
    /// of a curve (midsides at the chords' midpoints) keep their multipliers
    /// on the corners.
    #[default]
    EveryNode,
    /// On the corners only (linear per edge): no alternation, but the zone
    /// edge is resolved only at the corner spacing (disk on a flat: 0.20 % at
    /// 8.8k DOF, 0.16 % at 252k).
    Corners,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-8,
            max_iterations: 200,
            prune_gap_ratio: 0.5,
            penalty: None,
            barrier: None,
            formulation: Formulation::Condensed,
            gap: GapMeasure::SignedDistance,
            t6_multipliers: T6Multipliers::EveryNode,
            estimate: true,
            accuracy: None,
        }
    }
}

/// Where the exact methods work.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Formulation {
    #[default]
    Condensed,
    Full,
}

/// Optional reply content.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OutputKind {
    /// Nodal displacement of every body.
    Displacement,
    /// Node coordinates and element connectivity of every body.
    Mesh,
    /// Element stresses (σxx, σyy, σxy) at element centroids.
    Stress,
    /// The reply's `vtu`: every body's mesh with displacement, stress and
    /// contact pressure as a VTK XML unstructured grid (ParaView), base64.
    Vtu,
}
