//! The 3D solid's sections of the request (`analysis: "solid"`, the
//! request's `solid`) and of the reply (`solid`): one elastic body of
//! tetrahedra against one rigid obstacle, frictionless. Lengths, forces and
//! pressures are the caller's units (consistent, e.g. mm, N, MPa); forces
//! are totals, not per unit thickness.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{ElementLists, MaterialSpec};

/// A 3D contact problem: one body of tetrahedra whose face set `contact.faces`
/// may touch one rigid obstacle (a plane, a sphere, a cylinder or a
/// paraboloid), frictionless, small strain.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidSpec {
    pub body: SolidBodySpec,
    pub obstacle: SolidObstacleSpec,
    pub contact: SolidContactSpec,
}

/// The elastic body (isotropic, linear, small strain).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidBodySpec {
    /// Name used in the reply; defaults to "body0".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    pub material: MaterialSpec,
    pub mesh: SolidMeshSpec,
    /// Displacement constraints on named face sets (fixed supports, rollers,
    /// symmetry planes, prescribed motion).
    #[serde(default)]
    pub supports: Vec<SolidSupportSpec>,
    /// Surface loads on named face sets.
    #[serde(default)]
    pub tractions: Vec<SolidTractionSpec>,
    /// Body force per unit volume [force/length³], e.g. weight density.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body_force: Option<[f64; 3]>,
}

/// Tetrahedron order.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SolidElementKind {
    /// Linear 4-node tetrahedron.
    #[default]
    T4,
    /// Quadratic 10-node tetrahedron (isoparametric): corners, then the
    /// midsides of edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1 (Gmsh's order).
    T10,
}

/// A body's tetrahedral mesh: generated, given inline, or made with Gmsh.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SolidMeshSpec {
    /// The box [x0, x0+lx] × [y0, y0+ly] × [z0, z0+lz], each cell cut into six
    /// tetrahedra; face sets "x_min", "x_max", "y_min", "y_max", "z_min",
    /// "z_max". A quarter model of a body symmetric about two planes is the box
    /// with its focus on their common edge and rollers on their face sets.
    Box(BoxSpec),
    /// Explicit nodes, tetrahedra and named face sets.
    Inline(InlineSolidMeshSpec),
    /// A Gmsh MSH 4.1 ASCII mesh: tetrahedra (types 4, 11) make the body, the
    /// triangles (types 2, 9) of each physical surface group the face set of
    /// that name.
    Gmsh(GmshSolidMeshSpec),
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    /// The corner of least coordinates [x0, y0, z0].
    pub corner: [f64; 3],
    /// Side lengths [lx, ly, lz] [length], each positive.
    pub lengths: [f64; 3],
    /// Cell size away from the focus (uniform mesh without grading) [length].
    pub size: f64,
    #[serde(default)]
    pub element: SolidElementKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grading: Option<SolidGradingSpec>,
}

/// Refinement toward a focus point, axis by axis: cell sides `h_min` within
/// `extent` of the focus's coordinate, growing geometrically by `ratio` per
/// cell up to the mesh's `size` (cells far from the focus along one axis and
/// near it along another are slabs).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidGradingSpec {
    /// Point where the mesh is finest [x, y, z].
    pub focus: [f64; 3],
    /// Cell side at the focus [length].
    pub h_min: f64,
    /// Growth factor of neighbouring cell sides, 1 ≤ ratio ≤ 2.
    #[serde(default = "default_ratio")]
    pub ratio: f64,
    /// Half-width of the zone around the focus meshed uniformly at `h_min`
    /// (make it cover the expected contact patch) [length].
    #[serde(default)]
    pub extent: f64,
}

fn default_ratio() -> f64 {
    1.1
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InlineSolidMeshSpec {
    /// Node coordinates [[x, y, z], ...].
    pub nodes: Vec<[f64; 3]>,
    /// Tetrahedra as 0-based node indices, 4 per T4, 10 per T10 (corners,
    /// then the midsides of edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1), each of
    /// positive volume: corner 3 on the side of (p1 − p0) × (p2 − p0). All
    /// elements of one order.
    pub elements: ElementLists,
    /// Named boundary face sets: each face as its three corner node indices,
    /// in any order (each takes its element's outward orientation).
    pub face_sets: BTreeMap<String, Vec<[usize; 3]>>,
}

/// A 3D mesh made with Gmsh, as MSH 4.1 ASCII text.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GmshSolidMeshSpec {
    /// The content of a `.msh` file (format 4.1, ASCII).
    pub msh: String,
    /// Physical volume groups that make up the body (default: every
    /// tetrahedron in the file).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub volumes: Vec<String>,
}

/// Prescribed displacement components on a face set. A component set to 0
/// is a support (one: a roller or symmetry plane; three: fixed); a nonzero
/// value prescribes motion.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidSupportSpec {
    /// Name of the face set.
    pub faces: String,
    /// Prescribed x displacement [length]; absent = free.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ux: Option<f64>,
    /// Prescribed y displacement [length]; absent = free.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uy: Option<f64>,
    /// Prescribed z displacement [length]; absent = free.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uz: Option<f64>,
}

/// A surface load on a face set: a traction vector, or a normal pressure, not both.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidTractionSpec {
    pub faces: String,
    /// Traction vector [tx, ty, tz] [force/length²].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traction: Option<[f64; 3]>,
    /// Normal pressure, positive pushing into the body [force/length²].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<f64>,
}

/// The rigid obstacle (fixed).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidObstacleSpec {
    /// Name used in the reply; defaults to "obstacle0".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    pub shape: SolidObstacleShape,
}

/// The obstacle's shape. The gap of a contact point is its distance to the
/// closest point of the obstacle, and the point is pushed along the
/// obstacle's normal there; a body point inside the obstacle at the start is
/// the obstacle pressed in by that depth (a prescribed interference).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SolidObstacleShape {
    /// The plane through `point`; the rigid half-space lies on the side
    /// opposite to `normal` (the normal points out of the obstacle, toward
    /// the body; any nonzero length).
    Plane { point: [f64; 3], normal: [f64; 3] },
    /// A rigid ball; the body lies outside it.
    Sphere {
        /// Its centre [x, y, z].
        centre: [f64; 3],
        /// Its radius [length], positive.
        radius: f64,
    },
    /// An infinitely long rigid cylinder; the body lies outside it.
    Cylinder {
        /// A point of its axis [x, y, z].
        point: [f64; 3],
        /// The axis's direction (any nonzero length).
        axis: [f64; 3],
        /// Its radius [length], positive.
        radius: f64,
    },
    /// A rigid body whose surface near its apex is the paraboloid of two
    /// principal radii (Hertz's local shape of a body of two curvatures):
    /// at distances ξ along `axis` and η across it from the apex, the
    /// surface lies ξ²/2R₁ + η²/2R₂ behind the apex's tangent plane, away
    /// from the body. The gap is the surface's height over the point
    /// divided by the length of its gradient: the distance to first order,
    /// exact on the surface.
    Paraboloid {
        /// The point of the obstacle nearest the body [x, y, z].
        apex: [f64; 3],
        /// The normal at the apex, out of the obstacle toward the body (any
        /// nonzero length).
        normal: [f64; 3],
        /// The direction of the principal section of radius `radii[0]`
        /// (its part across `normal` is used; not along `normal`).
        axis: [f64; 3],
        /// Principal radii [R₁, R₂] [length], each positive.
        radii: [f64; 2],
    },
    /// A rigid surface given as a table of heights over a regular grid (a
    /// measured or worn surface, a crowned roller, a groove): the height
    /// `heights[j][i]` above the reference plane through `origin` (along
    /// `normal`) at i·spacing[0] along `axis` and j·spacing[1] along
    /// normal × axis, interpolated by C¹ bicubic pieces (Catmull–Rom,
    /// exact on quadratics). The obstacle lies below the surface; every
    /// contact point must lie over the grid. The gap is the height over the
    /// point divided by the length of its gradient, as the paraboloid's.
    HeightField {
        /// The grid's point (0, 0) on the reference plane [x, y, z].
        origin: [f64; 3],
        /// The reference plane's normal, out of the obstacle toward the
        /// body (any nonzero length).
        normal: [f64; 3],
        /// The direction of the table's rows (its part across `normal` is
        /// used; not along `normal`).
        axis: [f64; 3],
        /// Grid spacing [along `axis`, across it] [length], each positive.
        spacing: [f64; 2],
        /// Rows of heights [length], each row along `axis`, the rows across
        /// it: at least 2 rows of at least 2 values, every row the same
        /// length.
        heights: Vec<Vec<f64>>,
    },
}

/// Which face set of the body may touch the obstacle.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidContactSpec {
    /// Name of the body's face set whose points are contact candidates: one
    /// row per node on T4 faces, one dual mortar row per corner on T10 faces.
    pub faces: String,
    /// A shape added to the gap of the flat face set, so that a flat-faced
    /// body stands for a curved one (absent: the gap is the distance to the
    /// obstacle). With a plane obstacle only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_gap: Option<InitialGapSpec>,
}

/// An initial gap profile added to the distance to the obstacle.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum InitialGapSpec {
    /// Hertz's gap of a sphere of radius `radius` touching at `apex`: each
    /// point of the face set is r² / (2 radius) farther from the obstacle,
    /// r its distance from `apex` across the plane's normal. The
    /// flat-faced body then stands for a ball pressed on the plane, within
    /// Hertz's own assumptions (contact radius small against the radius and
    /// the body; the body's far field that of a half-space).
    Paraboloid { apex: [f64; 3], radius: f64 },
}

/// The 3D answer (`analysis: "solid"`), in the request's units.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidResult {
    pub body: String,
    pub obstacle: String,
    /// The contact face set.
    pub faces: String,
    pub element: SolidElementKind,
    /// The connected patches of contact, in the order of their first point.
    /// A point is in contact when its force is positive; a face is in
    /// contact when all its corners are, so a patch's faces are the inner
    /// bound of the contact (about half an element inside its edge).
    pub patches: Vec<ContactPatch>,
    /// Every candidate point, in the order of the rows.
    pub points: Vec<SolidContactPoint>,
    /// Total contact force on the body and its moment about the origin.
    pub resultant: SolidResultant,
    /// Largest penetration of a row (its gap below 0) [length].
    pub max_penetration: f64,
    /// With `outputs` listing `mesh`: the body's nodes [x, y, z] as meshed
    /// (a generated box's or a Gmsh file's, in the request's units).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nodes: Option<Vec<[f64; 3]>>,
    /// With `mesh`: the tetrahedra as 0-based indices into `nodes`, 4 per T4,
    /// 10 per T10 (corners, then the midsides of edges 0-1, 1-2, 2-0, 3-0,
    /// 3-2, 3-1: Gmsh's order, as in the request).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<Vec<Vec<usize>>>,
    /// With `displacement`: each node's [ux, uy, uz] [length].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub displacement: Option<Vec<[f64; 3]>>,
    /// With `stress`: each element's stress at its centroid [σxx, σyy, σzz,
    /// σxy, σyz, σxz] (ParaView's tensor order) [force/length²]. On
    /// nearly incompressible T10 (ν ≥ 0.45, the mean-dilatation element)
    /// its mean part is the element's constant pressure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stress: Option<Vec<[f64; 6]>>,
    /// The answer's error estimate (of the last load factor's or step's
    /// answer, with `load_factors` or `load_path`), absent with `settings.estimate: false` unless
    /// `settings.accuracy` asks for rounds, which are always estimated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<SolidAccuracy>,
}

/// A posteriori error estimate of a solid's contact answer, each a relative
/// error (null where not estimated).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidAccuracy {
    /// `two_level`: a generated box against the same scene with its grading's
    /// `h_min`, growth (ratio − 1) and far-field `size` doubled, every
    /// element about twice as large, Richardson-scaled (the 2D estimate's
    /// design), or with `settings.accuracy` a given mesh's refinement round
    /// against the round before (every tetrahedron split in eight); `none`:
    /// no estimate, for a given (inline or Gmsh) mesh without
    /// `settings.accuracy`, whose companion is not made (a finer one would
    /// cost several solves), or when the companion did not solve (the
    /// reply's notes say why).
    pub basis: crate::EstimateBasis,
    /// Estimated relative L2 error of the contact pressure over the contact
    /// face set: of the field the points describe, linear over each face
    /// between its corners' pressures.
    pub pressure_l2: Option<f64>,
    /// Estimated relative error of the largest point pressure.
    pub peak: Option<f64>,
    /// Estimated relative error of the contact force (`resultant.force`).
    pub resultant: Option<f64>,
    /// Estimated relative error of the contact area, the patches'
    /// `tributary_area` summed (an error of order h: the ring of faces the
    /// patch's edge crosses).
    pub contact_area: Option<f64>,
}

/// A 3D solid's answer at one load factor or load path step (a `steps`
/// entry's `solid`): its patches, points and resultant as in `SolidResult`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidStepResult {
    pub patches: Vec<ContactPatch>,
    pub points: Vec<SolidContactPoint>,
    pub resultant: SolidResultant,
    /// Largest penetration of a row [length].
    pub max_penetration: f64,
}

/// A connected region of contact.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactPatch {
    /// Area of its faces in contact (curved faces on T10) [length²].
    pub area: f64,
    /// Sum of its points' tributary areas [length²]: a third of each face at
    /// an edge point is counted, so this overestimates where `area`
    /// underestimates.
    pub tributary_area: f64,
    /// Sum of its points' normal contact forces [force] (against a curved
    /// obstacle each acts along the normal at its point: `resultant` is
    /// their vector sum).
    pub force: f64,
    /// Where the patch's force acts [x, y, z].
    pub centre_of_pressure: [f64; 3],
    /// Largest pressure of its points [force/length²].
    pub peak_pressure: f64,
    /// The point of the peak [x, y, z].
    pub peak_at: [f64; 3],
    /// The boundary of its faces, as closed polygons (the last point joins
    /// the first; T10 midsides included), counter-clockwise seen from the
    /// obstacle; a hole's loop runs the other way. Empty when the patch holds
    /// no whole face (contact narrower than the mesh resolves).
    pub outline: Vec<Vec<[f64; 3]>>,
}

/// A contact candidate: a node of the face set (T4) or a corner (T10).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidContactPoint {
    /// Reference position [x, y, z].
    pub at: [f64; 3],
    /// Contact pressure: the point's force over its tributary area
    /// [force/length²].
    pub pressure: f64,
    /// Gap after deformation (T10: its dual-weighted mean over the corner's
    /// faces) [length].
    pub gap: f64,
    pub in_contact: bool,
}

/// A force and its moment about the origin.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidResultant {
    /// [fx, fy, fz] [force].
    pub force: [f64; 3],
    /// [mx, my, mz] [force × length].
    pub moment: [f64; 3],
}
