//! A guaranteed upper bound of the energy-norm error (Prager–Synge).
//!
//! For linear elasticity with frictionless contact against rigid obstacles,
//! any admissible displacement v (supports kept, no penetration anywhere on
//! the contact candidates) and any statically admissible stress τ (symmetric,
//! div τ + f = 0, τ n equal to the loads where they are given, and on the
//! candidates τ n = −p* ν with p* ≥ 0 along the row direction ν) bound the
//! error of the exact u by
//!
//! ```text
//! ‖u − v‖²_E ≤ ‖C ε(v) − τ‖²_C⁻¹ + 2 ∫_Γc p* (g − v · ν) ds,
//! ```
//!
//! from the duality of the potential and the complementary energy (the
//! Prager–Synge hypercircle, with the contact term of the Signorini problem;
//! Weiss & Wohlmuth, Math. Comp. 78, 2009 use the same split). It
//! needs no constant: its effectivity is ≥ 1 by construction.
//!
//! The answer u_h is made admissible by a correction w where a candidate side
//! penetrates between its nodes (v = u_h + w; the bound of u − u_h adds
//! ‖w‖_E). τ is the equilibrated stress of `equilibrate` (of `quadratic` on
//! T6), lowered patch by patch by Airy corrections (`patch`), for the answer
//! with
//! its nodal contact forces replaced by a pressure p* ≥ 0 whose traction
//! −p* ν is linear on each side and follows the obstacle's normal exactly:
//! p* linear through the nodal pressures λ_i / w_i where the obstacle is
//! straight, q |x − c| where it is a circle about c (`Form`); the answer's
//! change under that replacement is one solve with the factor at hand. A
//! side in contact where the normal turns otherwise is out of reach.
//!
//! The theorem asks nothing of p* but p* ≥ 0 and −p* ν(x) for the gap's own
//! ν(x) on every facing point, and nothing of v but v · ν ≤ g there; so:
//!
//! - ν = m(x)/|m(x)| with m affine along the side (a circle's x − c, or a
//!   finely tabulated curve's segment whose joints' normals the gap
//!   interpolates, `normal::Form::Fan`: the V-shaped floor of
//!   `signorini_inline_block_on_vee`) takes p* = q |m|, one q per side:
//!   −p* ν = −q m is linear.
//! - The given traction is per side, so p* may jump at a node (it does
//!   where a side past an obstacle's end takes p* = 0, below), and its loads
//!   differ from the nodal contact forces by what u_eq absorbs
//!   (K (u_eq − u_h) = f(p*) − f_c, whatever p* is). A node on the boundary
//!   of two pieces' regions where the normal is continuous (the V's apex,
//!   a gentle joint, under a node) leaves each side one piece's form. At a
//!   sharp corner on a node the node's normal is one piece's and the other
//!   side's interior the other's: that side reads `Kinked`, out of reach in
//!   contact (taking each side's own limit there is not done yet).
//! - Where the obstacle ends within a side (an open end: a flat punch's
//!   corner between two nodes), the side past the end is free, τ n = 0, and
//!   a p* linear along the side that vanishes there vanishes on all of it:
//!   p* = 0 on that side, and its admissibility is checked on the part the
//!   obstacle faces (`normal::facing_part`), which on a straight piece and a
//!   linear side is exact at the part's two ends (v · ν − g affine).
//! - An excess of v · ν over g below the rounding of the two, 8 ε
//!   (|v · ν| + |g|), is taken as contact: the flat punch's answer meets its
//!   face to 4e-19 of 2e-2, which no push can remove in floating point.
//!
//! A body's sides on a tensionless Winkler bed add the bed's term
//! 2 ∫ [½ k (w⁺)² + p*²/(2k) − p* w] dx (w the indentation) in place of the
//! obstacle's, with no admissibility correction (`foundation`, where the
//! bound is derived). A body the bed alone holds has its free rigid modes
//! held by virtual supports in the factor (`fem::rigid_modes`); p* is scaled
//! to balance its loads on those modes, so the forces u_eq moves by are
//! self-equilibrated and the virtual supports carry nothing: u_eq is then in
//! equilibrium at every node, the virtual supports' included. Pasternak's
//! shear layer and the elastic half-plane are not in the bound: their
//! complementary energies are those of a second (non-local) body, which the
//! pointwise Young inequality of `foundation` does not carry.
//!
//! On quadratic triangles (straight-sided, `quadratic`) p* is linear on
//! each half of a side through its three nodal pressures (one q on a
//! circle; on a side the obstacle faces in part, nonzero on a whole half it
//! faces alone, where it keeps the midside node's pressure and jumps to 0
//! at the middle: the four-split stress carries each half's traction
//! alone), its loads are the P2 functions' moments, and the admissibility
//! is checked along the quadratic displacement, each node that passes the
//! obstacle pushed out by its own excess first. A punch
//! scales the midside values with the corners' (`punch`); a bed's p* stays
//! linear along the side through its corners' rows (`foundation`). On the
//! P2–P0 element the rows are of the stress it integrates and the
//! correction's norm is the true energy's (K holds the mean dilatation's
//! alone, which is short of it).
//!
//! Length: about 1,050 lines, the bound's data from the scene (loads,
//! supports, the contact pressure on linear and quadratic sides, the
//! admissibility correction, the contact term) in one pass over the same
//! sides; the equilibration (linear and quadratic), the Airy stress, a
//! punch's balance and the beds' sides are modules of their own.

pub mod airy;
pub mod equilibrate;
#[cfg(test)]
mod fixtures;
mod foundation;
mod normal;
mod numbering;
mod patch;
mod pending;
mod punch;
pub mod quadratic;
pub mod split;

pub use pending::{Operator, Pending};

use std::collections::HashMap;

use faer::sparse::SparseColMat;

use crate::contact::free_motions::Motion;
use crate::contact::gap::closest;
use crate::contact::rows::punch_coefficients;
use crate::fem::assembly::{each_element, integration, DofMap, FIXED};
use crate::fem::constitutive::Constitutive;
use crate::fem::kernel::Integration;
use crate::fem::loads::clip;
use crate::linalg::sparse::sym_lower_matvec;
use crate::linalg::Cholesky;
use crate::mesh::{boundary::edge_normal, Mesh2d, Order};
use crate::model::Model;
use crate::scene::{Analysis, FoundationModel, GapMeasure, Scene, Target};
use equilibrate::Given;
use normal::{form_of, Form};

/// The bound of one answer, nondimensional.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyBound {
    /// Upper bound of ‖u − u_h‖_E.
    pub absolute: f64,
    /// ‖u_h‖_E.
    pub norm: f64,
    /// The admissibility correction's share ‖w‖_E (0 when u_h penetrates
    /// nowhere).
    pub correction: f64,
    /// 2 ∫ p* (g − v · ν): the contact term, with the beds'
    /// 2 ∫ [½ k (w⁺)² + p*²/(2k) − p* w] dx (`foundation`).
    pub contact: f64,
    /// ‖u_eq − u_h‖_E: how far the answer moves when its nodal contact
    /// forces become p*'s loads (in the stiffness the answer was solved
    /// with: on the P2–P0 element its discrete energy).
    pub shift: f64,
    /// The potential energy ½ a(u_h, u_h) − ℓ(u_h) plus the beds'
    /// ∫ ½ k (w⁺)² dx (the continuous springs' energy), the latter taken at
    /// the admissible v: J(u_h) wherever v = u_h (no obstacle side's
    /// correction moved a bed side's node), for checks:
    /// 2 (J(u_h) − J(u)) ≥ ‖u − u_h‖²_E when u_h is admissible.
    pub potential: f64,
}

impl EnergyBound {
    /// Relative to the answer's own energy norm: ‖u − u_h‖_E / ‖u_h‖_E is
    /// at most this (finite wherever the answer moves at all).
    pub fn relative(&self) -> f64 {
        if self.norm > 0.0 {
            self.absolute / self.norm
        } else {
            f64::INFINITY
        }
    }
}

/// Why a foundation is out of the bound's reach.
const BED_MODELS: &str =
    "only Winkler beds are in the bound (a Pasternak layer's or a half-plane's complementary energy is not)";

/// Why a side in contact is out of reach where its normal is of no
/// `normal::Form` with a linear traction.
const KINKED: &str =
    "the obstacle's normal turns within a side in contact across two of its pieces (a sharp corner, a joint)";

/// Sample points per candidate side where the admissibility of u_h is
/// checked (the gap is a smooth function of the point on each side).
const SAMPLES: usize = 9;

/// Why a scene has no bound (yet), or None when it is one the bound covers.
pub fn unsupported(scene: &Scene, model: &Model, factor: Option<&Cholesky>) -> Option<&'static str> {
    if scene.analysis == Analysis::Axisymmetric {
        return Some("the equilibrated stress is built for plane sections, not axisymmetry");
    }
    if let Some(why) = quadratic::unsupported(model) {
        return Some(why);
    }
    if scene.has_friction() {
        return Some("friction is not in the bound's complementary energy");
    }
    if scene.pairs.iter().any(|p| matches!(p.target, Target::Body { .. })) {
        return Some("contact between two deformable bodies is not in the bound yet");
    }
    if scene.pairs.iter().any(|p| match p.target {
        Target::Foundation(f) => !matches!(scene.foundations[f].model, FoundationModel::Winkler { .. }),
        _ => false,
    }) {
        return Some(BED_MODELS);
    }
    if scene.bodies.iter().any(|b| !b.couplings.is_empty()) {
        return Some("a coupling's rigid side is not in the bound yet");
    }
    if scene.bodies.iter().any(|b| !b.point_loads.is_empty()) {
        return Some("a point load has an unbounded energy, so its error's energy is too");
    }
    if scene.settings.gap != GapMeasure::SignedDistance {
        return Some("the bound is written for the signed-distance gap");
    }
    // A body with free rigid modes is in the bound where Winkler beds alone
    // hold it (`foundation::balance`).
    if model
        .dofs
        .rigid
        .iter()
        .any(|set| set.virtual_dofs.is_empty() || !foundation::only_on_beds(scene, set.body))
    {
        return Some("a body moved by the contact alone is not in the bound yet");
    }
    if factor.is_none() {
        return Some("the bound needs the stiffness factor of the condensed route");
    }
    None
}

/// A pair's candidate side: its ends, the pressure p* at each and the
/// obstacle's row direction ν there; the traction on the body −p* ν is
/// linear along the side, so that `airy` can carry it exactly.
struct ContactSide {
    body: usize,
    obstacle: usize,
    ends: [usize; 2],
    pressure: [f64; 2],
    dir: [[f64; 2]; 2],
    /// A quadratic side's midside node, p* and ν there: p* is linear on
    /// each half (on a circle q |x − c|, whose −p* ν is linear along the
    /// whole side).
    mid: Option<Mid>,
    form: Form,
    /// The part of the side the obstacle faces, in the side's parameter
    /// (all of it, [0, 1], but where the obstacle ends within the side).
    span: [f64; 2],
    /// The obstacle's curvature along the side (`form_of`), for the
    /// admissibility check's margin.
    curvature: f64,
}

#[derive(Debug, Clone, Copy)]
struct Mid {
    node: usize,
    /// p* at the middle as the first half reaches it and as the second
    /// does: equal but where a punch's corner sits on the midside node, and
    /// p* falls to 0 past it (`Given` carries the jump).
    pressure: [f64; 2],
    dir: [f64; 2],
}

/// Whether a side's nodal p* (its ends', and a quadratic side's midside
/// values) is anywhere nonzero: a midside value can press between two
/// corners at 0.
fn carries(ends: [f64; 2], mid: Option<[f64; 2]>) -> bool {
    ends != [0.0, 0.0] || mid.is_some_and(|m| m != [0.0, 0.0])
}

/// At parameter t of a side, the value linear between its ends' `ends`,
/// or on each half through the midside's `mid` (a quadratic side's p*,
/// each half its own value at the middle).
fn piecewise(ends: [f64; 2], mid: Option<[f64; 2]>, t: f64) -> f64 {
    match mid {
        Some(m) if t <= 0.5 => (1.0 - 2.0 * t) * ends[0] + 2.0 * t * m[0],
        Some(m) => (2.0 - 2.0 * t) * m[1] + (2.0 * t - 1.0) * ends[1],
        None => (1.0 - t) * ends[0] + t * ends[1],
    }
}

impl ContactSide {
    /// p* at parameter t of the side.
    fn pressure_at(&self, mesh: &Mesh2d, t: f64) -> f64 {
        let (a, b) = (mesh.nodes[self.ends[0]], mesh.nodes[self.ends[1]]);
        match (self.form, self.mid) {
            (Form::Arc { center }, _) => {
                let x = [(1.0 - t) * a[0] + t * b[0], (1.0 - t) * a[1] + t * b[1]];
                let ra = (a[0] - center[0]).hypot(a[1] - center[1]);
                self.pressure[0] / ra * (x[0] - center[0]).hypot(x[1] - center[1])
            }
            (Form::Fan { .. }, _) => self.pressure[0] * self.form.scale(a, b, t).unwrap_or(1.0),
            (_, mid) => piecewise(self.pressure, mid.map(|m| m.pressure), t),
        }
    }

    /// The traction −p* ν on the body at the side's first end, its middle
    /// from the first half and from the second, and its second end (`Given`'s
    /// four values: linear on each half; the middle value is the mean of
    /// the ends' on a linear side).
    fn traction(&self) -> [[f64; 2]; 4] {
        let [a, b] = [0, 1].map(|e| self.dir[e].map(|d| -self.pressure[e] * d));
        let [m0, m1] = match self.mid {
            Some(m) => m.pressure.map(|p| m.dir.map(|d| -p * d)),
            None => [[(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]; 2],
        };
        [a, m0, m1, b]
    }

    /// The side's nodes in order along it (first end, midside, second end).
    fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        std::iter::once(self.ends[0])
            .chain(self.mid.map(|m| m.node))
            .chain(std::iter::once(self.ends[1]))
    }
}

/// The bound of a solved frictionless scene on rigid obstacles (see
/// `unsupported` for what it does not cover): `disp` the answer's nodal
/// displacements per body (the report's), `lambda` the candidates' forces, `punches` each punch's motion (α1, α2,
/// θ), prescribed or solved.
pub fn bound(
    scene: &Scene,
    model: &Model,
    k: &SparseColMat<usize, f64>,
    factor: &Cholesky,
    disp: &[Vec<[f64; 2]>],
    lambda: &[f64],
    punches: &[(usize, [f64; 3])],
) -> Result<EnergyBound, &'static str> {
    let (meshes, dofs) = (&model.meshes, &model.dofs);
    let u_h = disp;
    let mut given: Vec<HashMap<[usize; 2], Given>> = vec![HashMap::new(); meshes.len()];
    let key = |a: usize, b: usize| [a.min(b), a.max(b)];
    // Loads first, supports last (a held component's traction is sought
    // whatever else acts on the side).
    for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
        for t in &body.tractions {
            let (edges, vector, pressure, range) = match t {
                crate::scene::Traction::Vector { edges, t, x_range } => (edges, Some(*t), 0.0, *x_range),
                crate::scene::Traction::Pressure { edges, p, x_range } => (edges, None, *p, *x_range),
            };
            for e in mesh.edge_sets.get(edges).map(|v| v.as_slice()).unwrap_or(&[]) {
                // A range that ends at a node up to round-off (0.4 = −1 +
                // 28 × 0.05 reads 1e-15 inside the side) loads the whole
                // side: the load the bound carries then differs from the
                // model's by that much of one side's, far below the
                // equilibration's closure check (1e-8).
                const SNAP: f64 = 1e-9;
                match clip(mesh, e, range) {
                    None => continue,
                    Some((s0, s1)) if s1 + 1.0 <= SNAP || 1.0 - s0 <= SNAP => continue,
                    Some((s0, s1)) if s0 > -1.0 + SNAP || s1 < 1.0 - SNAP => {
                        return Err("a traction ends inside an element side, where the bound's traction is linear")
                    }
                    Some(_) => {}
                }
                let (n, _) = edge_normal(mesh, e);
                let tr = vector.unwrap_or([-pressure * n[0], -pressure * n[1]]);
                let g = given[b].entry(key(e.a, e.b)).or_insert(Given {
                    ends: [e.a, e.b],
                    traction: [Some([0.0; 4]); 2],
                });
                for (c, tc) in tr.iter().enumerate() {
                    if let Some(v) = g.traction[c].as_mut() {
                        v.iter_mut().for_each(|x| *x += tc);
                    }
                }
            }
        }
    }
    // The contact pressure p* ≥ 0: nodal pressures λ_i / w_i along each
    // row's direction, linear on each side of the pair's edge set.
    let mut nodal: HashMap<(usize, usize, usize), (f64, [f64; 2])> = HashMap::new();
    for (c, l) in model.cons.candidates.iter().zip(lambda) {
        let p = if c.weight > 0.0 { l.max(0.0) / c.weight } else { 0.0 };
        nodal.insert((c.pair, c.body, c.node), (p, c.normal));
    }
    let mut sides = Vec::new();
    for (p, pair) in scene.pairs.iter().enumerate() {
        let o = match pair.target {
            Target::Obstacle(o) => o,
            // A bed's sides are `foundation`'s.
            Target::Foundation(_) => continue,
            Target::Body { .. } => return Err("contact between two deformable bodies is not in the bound yet"),
        };
        let mesh = &meshes[pair.body];
        for e in mesh.edge_sets.get(&pair.edges).map(|v| v.as_slice()).unwrap_or(&[]) {
            let at = |n: usize| nodal.get(&(p, pair.body, n)).copied();
            let dir_of = |n: usize| {
                at(n)
                    .map(|x| x.1)
                    .or_else(|| closest(&scene.obstacles[o].shape, mesh.nodes[n]).map(|c| [-c.normal[0], -c.normal[1]]))
            };
            let shape = &scene.obstacles[o].shape;
            let (xa, xb) = (mesh.nodes[e.a], mesh.nodes[e.b]);
            // Where the obstacle ends within the side (an open end of a
            // polyline or profile, a flat punch's corner between two
            // nodes), the part of the side it faces.
            let point = |t: f64| [(1.0 - t) * xa[0] + t * xb[0], (1.0 - t) * xa[1] + t * xb[1]];
            let (span, found) = match form_of(shape, xa, xb) {
                Some(f) => ([0.0, 1.0], Some(f)),
                None => match normal::facing_part(shape, xa, xb) {
                    Some(part) => (part, form_of(shape, point(part[0]), point(part[1]))),
                    None => ([0.0, 1.0], None),
                },
            };
            let facing = closest(shape, point(0.5 * (span[0] + span[1]))).map(|c| [-c.normal[0], -c.normal[1]]);
            let (Some(da), Some(db)) = (dir_of(e.a).or(facing), dir_of(e.b).or(facing)) else {
                continue;
            };
            let mut pressure = [at(e.a).map_or(0.0, |x| x.0), at(e.b).map_or(0.0, |x| x.0)];
            // A quadratic side's midside p*: its own row's, or the ends'
            // mean where the multiplier lives on the corners alone.
            // (Each half's value at the middle: equal but at a punch's corner
            // on the midside node, below.)
            let mut mid_pressure = e
                .mid
                .map(|m| [at(m).map_or(0.5 * (pressure[0] + pressure[1]), |x| x.0); 2]);
            let Some((form, turn)) = found.map(|(f, t)| match f {
                // A punch's rigid motion b(y) enters g as b · ν, whose
                // second derivative along a fan the margin below does not
                // hold: a fan on a punch is left out of reach.
                Form::Fan { .. } if scene.obstacles[o].punch.is_some() => (Form::Kinked, t),
                _ => (f, t),
            }) else {
                // A quadratic side's midside row can press where its corners
                // do not (their values alternate near a zone's end).
                if carries(pressure, mid_pressure) {
                    return Err("a side in contact runs past an open end of its obstacle");
                }
                // A part the obstacle faces whose form is unknown, or pieces
                // of it apart, would go unchecked: v · ν ≤ g is not shown there.
                if span != [0.0, 1.0] || normal::faced_in_pieces(shape, xa, xb) {
                    return Err(
                        "an obstacle faces part of a candidate side in a way the admissibility check does not \
                        resolve (pieces of it apart within the side)",
                    );
                }
                continue;
            };
            // A quadratic side on a straight piece that faces all of one of
            // its halves (the obstacle ends on its midside node or past it:
            // `facing_part` reads a flat punch's corner on the node END_SLACK
            // of the piece past it, `contact::gap`): that half's end.
            let facing_half = match (e.mid, form) {
                (Some(_), Form::Straight) if span[0] == 0.0 && span[1] >= 0.5 => Some(0),
                (Some(_), Form::Straight) if span[1] == 1.0 && span[0] <= 0.5 => Some(1),
                _ => None,
            };
            if span != [0.0, 1.0] {
                // Past the obstacle's end the side is free (τ n = 0), and a
                // p* linear along the side that vanishes there vanishes on
                // all of it: the side's nodal forces go to u_eq's shift, and
                // its admissibility is checked on the facing part alone. On a
                // quadratic side p* is linear on each half: where the
                // obstacle faces a whole half, p* vanishes on the other, and
                // on that half runs from the facing end's pressure to the
                // midside node's, jumping to 0 at the middle (`Mid`): a flat
                // punch's corner on a midside node, where the answer's
                // pressure peaks. p* = 0 there overstated the T6 punch's
                // error by 3.5 or more; the node's own value, kept rather
                // than tuned (scaled by 0.75 or 1.25 it read within 1 % or
                // worse), brings it under 2 (docs/verification/accuracy.md).
                pressure = [0, 1].map(|end| if facing_half == Some(end) { pressure[end] } else { 0.0 });
                mid_pressure = mid_pressure.map(|m| [0, 1].map(|h| if facing_half == Some(h) { m[h] } else { 0.0 }));
            }
            // The traction at the ends follows the obstacle's own normal there
            // (a nodal row's direction is that normal at its node).
            let exact = |n: usize| closest(shape, mesh.nodes[n]).map(|c| [-c.normal[0], -c.normal[1]]);
            let (Some(da), Some(db)) = (exact(e.a).or(Some(da)), exact(e.b).or(Some(db))) else {
                continue;
            };
            match form {
                // No linear traction follows a normal that turns otherwise
                // (at a sharp corner the continuous model's normal is not even
                // defined), and the admissibility between samples has no
                // bound there: a side in contact there is out of reach.
                Form::Kinked if carries(pressure, mid_pressure) => return Err(KINKED),
                Form::Fan { .. } => {
                    // One q on the side, p* = q |m|, with the mean of the
                    // nodal pressures' integral as on an arc.
                    let (pa, pb) = (mesh.nodes[e.a], mesh.nodes[e.b]);
                    let r = |t: f64| form.scale(pa, pb, t).unwrap_or(1.0);
                    let q = match (e.mid, mid_pressure) {
                        (Some(_), Some(pm)) => {
                            (pressure[0] + 2.0 * (pm[0] + pm[1]) + pressure[1]) / (r(0.0) + 4.0 * r(0.5) + r(1.0))
                        }
                        _ => (pressure[0] + pressure[1]) / (r(0.0) + r(1.0)),
                    };
                    pressure = [q * r(0.0), q * r(1.0)];
                    mid_pressure = e.mid.map(|_| [q * r(0.5); 2]);
                }
                Form::Arc { center } => {
                    // One q on the side, p* = q |x − c|, with the mean of the
                    // nodal pressures' integral.
                    let r = |n: usize| (mesh.nodes[n][0] - center[0]).hypot(mesh.nodes[n][1] - center[1]);
                    // On a quadratic side the mean by Simpson's weights.
                    let q = match (e.mid, mid_pressure) {
                        (Some(m), Some(pm)) => {
                            (pressure[0] + 2.0 * (pm[0] + pm[1]) + pressure[1]) / (r(e.a) + 4.0 * r(m) + r(e.b))
                        }
                        _ => (pressure[0] + pressure[1]) / (r(e.a) + r(e.b)),
                    };
                    pressure = [q * r(e.a), q * r(e.b)];
                    mid_pressure = e.mid.map(|m| [q * r(m); 2]);
                }
                _ => {}
            }
            let mid = match (e.mid, mid_pressure) {
                (Some(node), Some(p)) => {
                    let Some(dir) = exact(node).or_else(|| dir_of(node)).or(facing) else {
                        continue;
                    };
                    Some(Mid { node, pressure: p, dir })
                }
                _ => None,
            };
            let side = ContactSide {
                body: pair.body,
                obstacle: o,
                ends: [e.a, e.b],
                pressure,
                dir: [da, db],
                mid,
                form,
                span,
                curvature: match form {
                    // 0 on a flat; 1/ρ over a gentle joint's wedge (`form_of`).
                    Form::Straight => turn,
                    Form::Arc { .. } | Form::Fan { .. } => turn,
                    // A side out of contact whose normal turns at a vertex
                    // (`form_of`'s bound).
                    Form::Kinked => turn,
                },
            };
            sides.push(side);
        }
    }
    for (o, _) in punches {
        punch::balance(scene, meshes, &model.free.motions, *o, &mut sides)?;
    }
    let mut beds = foundation::sides(scene, model, lambda)?;
    for set in &dofs.rigid {
        foundation::balance(model, set, &mut beds)?;
    }
    for side in &sides {
        add_traction(&mut given[side.body], side.ends, side.traction());
    }
    for side in &beds {
        let [a, b] = side.traction();
        let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        add_traction(&mut given[side.body], side.ends, [a, m, m, b]);
    }
    for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
        for s in &body.supports {
            for e in mesh.edge_sets.get(&s.edges).map(|v| v.as_slice()).unwrap_or(&[]) {
                let g = given[b].entry(key(e.a, e.b)).or_insert(Given {
                    ends: [e.a, e.b],
                    traction: [Some([0.0; 4]); 2],
                });
                if s.ux.is_some() {
                    g.traction[0] = None;
                }
                if s.uy.is_some() {
                    g.traction[1] = None;
                }
            }
        }
    }
    // u_eq: the answer with its nodal contact forces replaced by p*'s
    // consistent loads, K w = f(p*) − f_c (one solve with the factor).
    let mut d = vec![0.0; dofs.n_free];
    let mut add = |b: usize, n: usize, c: usize, v: f64| {
        let i = dofs.free[dofs.dof(b, n, c)];
        if i != FIXED {
            d[i] += v;
        }
    };
    let linear = sides
        .iter()
        .filter(|s| s.mid.is_none())
        .map(|s| (s.body, s.ends, [0, 1].map(|e| s.dir[e].map(|d| -s.pressure[e] * d))))
        .chain(
            beds.iter()
                .filter(|s| s.mid.is_none())
                .map(|s| (s.body, s.ends, s.traction())),
        );
    for (body, ends, t) in linear {
        let mesh = &meshes[body];
        let (pa, pb) = (mesh.nodes[ends[0]], mesh.nodes[ends[1]]);
        let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        for (c, (&ta, &tb)) in t[0].iter().zip(&t[1]).enumerate() {
            add(body, ends[0], c, l * (2.0 * ta + tb) / 6.0);
            add(body, ends[1], c, l * (ta + 2.0 * tb) / 6.0);
        }
    }
    // A quadratic side's consistent forces, a contact side's (p* linear on
    // each half, free to jump at the middle) or a bed's (p* linear along
    // it): the P2 functions' moments.
    let mut p2_loads = |body: usize, nodes: [usize; 3], t: [[f64; 2]; 4]| {
        let (pa, pb) = (meshes[body].nodes[nodes[0]], meshes[body].nodes[nodes[2]]);
        let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        for c in 0..2 {
            for (n, fc) in nodes.into_iter().zip(quadratic::half_moments(l, t.map(|v| v[c]))) {
                add(body, n, c, fc);
            }
        }
    };
    for s in &sides {
        if let Some(m) = s.mid {
            p2_loads(s.body, [s.ends[0], m.node, s.ends[1]], s.traction());
        }
    }
    for s in &beds {
        if let Some(mid) = s.mid {
            let [ta, tb] = s.traction();
            let tm = [0.5 * (ta[0] + tb[0]), 0.5 * (ta[1] + tb[1])];
            p2_loads(s.body, [s.ends[0], mid, s.ends[1]], [ta, tm, tm, tb]);
        }
    }
    for (cand, l) in model.cons.candidates.iter().zip(lambda) {
        for t in &cand.terms {
            for c in 0..2 {
                // The row's force on the node is −λ coef.
                add(t.body, t.node, c, l * t.coef[c]);
            }
        }
    }
    // d is zero but at the contact sides' nodes: its forward sweep works
    // the supernodes their DOFs reach alone.
    let y = factor.forward_sparse(&d);
    let w2 = factor.backward(&y);
    // ‖w‖²_E = wᵀ K w = wᵀ d, since K w = d: a dot product over the contact
    // sides' DOFs (where d lives) instead of a product with K (0.2–0.3 ms of
    // the bound's 22 ms on the Hertz example at 30k DOF).
    let shift = d.iter().zip(&w2).map(|(a, b)| a * b).sum::<f64>().max(0.0).sqrt();
    let moved = |b: usize, n: usize, c: usize, w: &[f64]| match dofs.free[dofs.dof(b, n, c)] {
        FIXED => 0.0,
        i => w[i],
    };
    let u_eq: Vec<Vec<[f64; 2]>> = u_h
        .iter()
        .enumerate()
        .map(|(b, nodes)| {
            (0..nodes.len())
                .map(|n| [nodes[n][0] + moved(b, n, 0, &w2), nodes[n][1] + moved(b, n, 1, &w2)])
                .collect()
        })
        .collect();
    // Admissibility: v · ν ≤ g along every candidate side, not only at its
    // nodes; where u_h passes the obstacle, v = u_h + w moves the side's
    // nodes back along their rows.
    let gap_at = |s: &ContactSide, x: [f64; 2]| -> Option<(f64, [f64; 2])> {
        let obstacle = &scene.obstacles[s.obstacle];
        let c = closest(&obstacle.shape, x)?;
        let dir = [-c.normal[0], -c.normal[1]];
        let mut g = c.distance;
        if let (Some(pu), Some((_, beta))) = (&obstacle.punch, punches.iter().find(|(o, _)| *o == s.obstacle)) {
            // The row n · u − c · β ≤ g with the punch's motion β.
            let co = punch_coefficients(c.point, pu.reference, dir);
            g += (0..3).map(|k| co[k] * beta[k]).sum::<f64>();
        }
        Some((g, dir))
    };
    // A punch's rigid motion at a side's sample: |b(y)| at the closest point
    // y, and |θ| R with R = |y − c| on a circular piece centred at c, |θ|
    // on any other (0 and 0 off punches).
    let motion_at = |s: &ContactSide, x: [f64; 2]| -> (f64, f64) {
        let obstacle = &scene.obstacles[s.obstacle];
        let (Some(pu), Some((_, beta))) = (&obstacle.punch, punches.iter().find(|(o, _)| *o == s.obstacle)) else {
            return (0.0, 0.0);
        };
        let Some(c) = closest(&obstacle.shape, x) else {
            return (0.0, 0.0);
        };
        let (dx, dy) = (c.point[0] - pu.reference[0], c.point[1] - pu.reference[1]);
        let b = (beta[0] - beta[2] * dy).hypot(beta[1] + beta[2] * dx);
        let r = match s.form {
            Form::Arc { center } => (c.point[0] - center[0]).hypot(c.point[1] - center[1]),
            _ => 1.0,
        };
        (b, beta[2].abs() * r)
    };
    let along = |s: &ContactSide, field: &[[f64; 2]], t: f64| -> ([f64; 2], [f64; 2]) {
        let mesh = &meshes[s.body];
        let (a, b) = (s.ends[0], s.ends[1]);
        let x = [
            (1.0 - t) * mesh.nodes[a][0] + t * mesh.nodes[b][0],
            (1.0 - t) * mesh.nodes[a][1] + t * mesh.nodes[b][1],
        ];
        let v = match s.mid {
            // The P2 functions along the side.
            Some(m) => {
                let w = quadratic::along_side(t);
                let vm = field[m.node];
                std::array::from_fn(|c| w[0] * field[a][c] + w[1] * vm[c] + w[2] * field[b][c])
            }
            None => [
                (1.0 - t) * field[a][0] + t * field[b][0],
                (1.0 - t) * field[a][1] + t * field[b][1],
            ],
        };
        (x, v)
    };
    // The largest of v · ν − g along a side: at its samples, plus what a
    // smooth function can gain between samples δ apart, δ²/8 max|f''|; with
    // ρ the distance to a circular piece's centre, |g''| ≤ 1/ρ and
    // |(v · ν)''| ≤ 2|v|/ρ² + 2|v'|/ρ. On a straight piece that is 0 for a
    // linear side; a quadratic side's own |v''| is added below. On a fan
    // (`normal::Form::Fan`) g is affine and, κ the bound of the normal's
    // turn, |ν'| ≤ κ and |ν''| ≤ 3κ² (ν = m/|m|, m affine): the arc's
    // margin below covers it. The third value is the rounding of v · ν − g
    // at the samples, 8 ε (|v · ν| + |g|): an excess below it is no
    // measurable penetration (the answer of a punch pressed flat meets its
    // face to 4e-19 of 2e-2, and a push that small leaves v unchanged in
    // floating point), and is taken as contact. On a punch g holds the
    // punch's motion, −b(y) · ν with b = (α1 − θ (y_y − r_y), α2 + θ (y_x −
    // r_x)) at the closest point y: on a circular piece of radius R,
    // |y'| ≤ R/ρ and |y''| ≤ 2R/ρ², so |(b · ν)''| ≤ (2|b| + 4|θ|R)/ρ²,
    // added to the margin as `moving`. On any other piece that turns (a
    // punch's fan or kink out of contact: in contact they are out of reach)
    // y moves along a facet at most at the side's speed (|y'| ≤ 1, y'' = 0)
    // or stays at a vertex, so 2|b'||ν'| ≤ 2|θ|κ joins 2|b|κ².
    // At parameter t of a side: the point, the obstacle's direction there,
    // v · ν − g and its rounding 8 ε (|v · ν| + |g|) (None where the
    // obstacle does not face it).
    let excess_at = |s: &ContactSide, field: &[[f64; 2]], t: f64| -> Option<([f64; 2], [f64; 2], f64, f64)> {
        let (x, v) = along(s, field, t);
        let (g, dir) = gap_at(s, x)?;
        let vn = v[0] * dir[0] + v[1] * dir[1];
        Some((x, dir, vn - g, 8.0 * f64::EPSILON * (vn.abs() + g.abs())))
    };
    let worst_of = |s: &ContactSide, field: &[[f64; 2]]| -> (f64, f64, f64) {
        let mesh = &meshes[s.body];
        let (mut worst, mut cos, mut slack) = (f64::NEG_INFINITY, 1.0_f64, 0.0_f64);
        let (mut bmax, mut turn_r) = (0.0_f64, 0.0_f64);
        let part = s.span[1] - s.span[0];
        for q in 0..SAMPLES {
            let t = s.span[0] + part * q as f64 / (SAMPLES - 1) as f64;
            let Some((x, dir, excess, rounding)) = excess_at(s, field, t) else {
                continue;
            };
            if s.curvature > 0.0 {
                let (b, tr) = motion_at(s, x);
                bmax = bmax.max(b);
                turn_r = turn_r.max(tr);
            }
            worst = worst.max(excess);
            slack = slack.max(rounding);
            for dn in &s.dir {
                cos = cos.min(dn[0] * dir[0] + dn[1] * dir[1]);
            }
        }
        let (a, b) = (mesh.nodes[s.ends[0]], mesh.nodes[s.ends[1]]);
        let l = (b[0] - a[0]).hypot(b[1] - a[1]);
        let curvature = s.curvature;
        let delta = l * part / (SAMPLES - 1) as f64;
        let moving = match s.form {
            Form::Arc { .. } => (2.0 * bmax + 4.0 * turn_r) * curvature * curvature,
            _ => 2.0 * bmax * curvature * curvature + 2.0 * turn_r * curvature,
        };
        if let Some(m) = s.mid {
            // A quadratic v: |v''| = 4 |v_a − 2 v_m + v_b| / l², |v'| at
            // most its ends' (v' is linear), |v| at most 1.25 of the nodes'
            // largest (Σ |φ_i| ≤ 1.25 along a side); on a straight piece f
            // is a quadratic and only |v''| counts.
            let (va, vm, vb) = (field[s.ends[0]], field[m.node], field[s.ends[1]]);
            let second = 4.0 * (va[0] - 2.0 * vm[0] + vb[0]).hypot(va[1] - 2.0 * vm[1] + vb[1]) / (l * l);
            let slope = [(-3.0, 4.0, -1.0), (1.0, -4.0, 3.0)]
                .iter()
                .map(|(x, y, z)| (x * va[0] + y * vm[0] + z * vb[0]).hypot(x * va[1] + y * vm[1] + z * vb[1]) / l)
                .fold(0.0, f64::max);
            let vmax = 1.25 * [va, vm, vb].iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
            // Twice the estimate of |f''|, as below.
            worst += delta * delta / 4.0
                * (second + curvature + 2.0 * vmax * curvature * curvature + 2.0 * slope * curvature + moving);
        } else if curvature > 0.0 {
            let (va, vb) = (field[s.ends[0]], field[s.ends[1]]);
            let vmax = va[0].hypot(va[1]).max(vb[0].hypot(vb[1]));
            let slope = (vb[0] - va[0]).hypot(vb[1] - va[1]) / l;
            // Twice the estimate of |f''|: a margin on the bound of a unit
            // vector's turn along a line.
            worst += delta * delta / 4.0
                * (curvature + 2.0 * vmax * curvature * curvature + 2.0 * slope * curvature + moving);
        }
        (worst, cos, slack)
    };
    let mut dir_at: HashMap<(usize, usize), [f64; 2]> = HashMap::new();
    for s in &sides {
        let mid = s.mid.map(|m| (m.node, m.dir));
        for (n, dn) in [(s.ends[0], s.dir[0]), (s.ends[1], s.dir[1])].into_iter().chain(mid) {
            let d = *dir_at.entry((s.body, n)).or_insert(dn);
            // A node facing two obstacles in different directions would be
            // pushed into one of them.
            if (d[0] - dn[0]).abs() + (d[1] - dn[1]).abs() > 1e-9 {
                return Err("a node faces two obstacles in different directions");
            }
        }
    }
    // A linear side's hats are ≥ 0, so pushing its ends by its worst moves
    // every point of it at least as far: one round, then the check. A
    // quadratic side's corner functions are negative on its far half, so a
    // corner pushed further by its other side pulls that half back: its
    // midside node takes the larger of its ends' pushes (the added push is
    // then concave along the side, so at least its smaller end's), and what
    // the margin's change leaves is pushed again, in a few more rounds.
    let quadratic_sides = sides.iter().any(|s| s.mid.is_some());
    let rounds = if quadratic_sides { 4 } else { 1 };
    // The bodies that run the P2–P0 element.
    let p2p0: Vec<bool> = scene
        .bodies
        .iter()
        .zip(meshes)
        .map(|(body, mesh)| integration(body, mesh.order, scene.analysis) == Integration::MeanDilatation)
        .collect();
    let mut v = u_h.to_vec();
    let mut w = vec![0.0; dofs.n_free];
    // Moves each node of `push` by its push along its rows' direction, in v
    // and in the correction w.
    let apply = |push: &HashMap<(usize, usize), f64>, v: &mut Vec<Vec<[f64; 2]>>, w: &mut [f64]| {
        for (&(b, n), &delta) in push {
            let dn = dir_at[&(b, n)];
            for c in 0..2 {
                let step = -delta * dn[c];
                match dofs.free[dofs.dof(b, n, c)] {
                    FIXED if step.abs() > 1e-12 * delta.max(f64::MIN_POSITIVE) && dn[c].abs() > 1e-9 => {
                        return Err("a node whose displacement is prescribed passes the obstacle between its rows")
                    }
                    FIXED => {}
                    i => {
                        w[i] += step;
                        v[b][n][c] += step;
                    }
                }
            }
        }
        Ok(())
    };
    // Where any side is quadratic, each node (of every side, linear ones
    // included) that passes the obstacle itself is first pushed by its own
    // excess alone: the weak rows leave a punch's corner on a midside node
    // inside the punch by a fraction of its neighbours' excess, and the
    // side's worst given to all its nodes would lift the sides further in,
    // where p* is large (docs/verification/accuracy.md: the T6 punch's
    // effectivity with and without it). The rounds after it push each side
    // by what it still lacks.
    let mut pushed = false;
    if quadratic_sides {
        let mut push: HashMap<(usize, usize), f64> = HashMap::new();
        for s in &sides {
            let params = std::iter::once(0.0)
                .chain(s.mid.map(|_| 0.5))
                .chain(std::iter::once(1.0));
            for (n, t) in s.nodes().zip(params) {
                if t < s.span[0] || t > s.span[1] {
                    continue;
                }
                let Some((_, dir, excess, rounding)) = excess_at(s, &v[s.body], t) else {
                    continue;
                };
                let dn = dir_at[&(s.body, n)];
                let cos = dn[0] * dir[0] + dn[1] * dir[1];
                if excess > rounding && cos >= 0.5 {
                    let e = push.entry((s.body, n)).or_insert(0.0);
                    *e = e.max(1.01 * excess / cos);
                }
            }
        }
        pushed = !push.is_empty();
        apply(&push, &mut v, &mut w)?;
    }
    for _ in 0..rounds {
        let mut push: HashMap<(usize, usize), f64> = HashMap::new();
        for s in &sides {
            let (worst, cos, slack) = worst_of(s, &v[s.body]);
            // A side through an obstacle's vertex has no finite margin.
            if worst.is_nan() || worst == f64::INFINITY {
                return Err("the answer could not be made admissible along its candidate sides");
            }
            if worst > slack {
                if cos < 0.5 {
                    return Err("a candidate side turns too far from its rows' direction to be made admissible");
                }
                // Every node of the side moves: v · ν gains the push at
                // every point (the shape functions sum to 1).
                for n in s.nodes() {
                    let e = push.entry((s.body, n)).or_insert(0.0);
                    // 1 % over: the margin of the check moves with v a little.
                    *e = e.max(1.01 * worst / cos);
                }
            }
        }
        if push.is_empty() {
            break;
        }
        for s in &sides {
            if let Some(m) = s.mid {
                let ends = s.ends.map(|n| push.get(&(s.body, n)).copied().unwrap_or(0.0));
                let most = ends[0].max(ends[1]);
                if most > 0.0 {
                    let e = push.entry((s.body, m.node)).or_insert(0.0);
                    *e = e.max(most);
                }
            }
        }
        pushed = true;
        apply(&push, &mut v, &mut w)?;
    }
    // v must be admissible everywhere: checked again, margin included.
    if sides.iter().any(|s| {
        let (worst, _, slack) = worst_of(s, &v[s.body]);
        worst > slack
    }) {
        return Err("the answer could not be made admissible along its candidate sides");
    }
    let correction = if !pushed {
        0.0
    } else if p2p0.contains(&true) {
        // K of the P2–P0 element holds the mean dilatation's energy alone,
        // λ |K| θ̄² ≤ λ ∫_K (tr ε)² (Jensen): wᵀ K w would be short of the
        // true ‖w‖²_E the triangle inequality needs. The elements' full rule
        // is the true energy.
        full_energy(scene, meshes, &v, u_h).sqrt()
    } else {
        let kw = sym_lower_matvec(k, &w);
        w.iter().zip(&kw).map(|(a, b)| a * b).sum::<f64>().max(0.0).sqrt()
    };
    // 2 ∫ p* (g − v · ν), Gauss–Legendre with 4 points on each side.
    let mut contact = 0.0;
    for s in &sides {
        // Not only the corners: a midside p* can press between two corners
        // at 0, and its term must then be counted.
        if !carries(s.pressure, s.mid.map(|m| m.pressure)) {
            continue;
        }
        let mesh = &meshes[s.body];
        let (pa, pb) = (mesh.nodes[s.ends[0]], mesh.nodes[s.ends[1]]);
        let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        // A quadratic side's p* may kink or jump at its middle: each half
        // alone, so no point falls on it and each half's rule is exact.
        for &(start, len) in punch::halves(s) {
            for (t, wq) in punch::GAUSS4 {
                let t = start + len * t;
                let (x, vv) = along(s, &v[s.body], t);
                let Some((g, dir)) = gap_at(s, x) else {
                    continue;
                };
                let p = s.pressure_at(mesh, t);
                contact += 2.0 * wq * len * l * p * (g - vv[0] * dir[0] - vv[1] * dir[1]).max(0.0);
            }
        }
    }
    // The beds' term (v = u_h there: a bed takes no correction) and their
    // energy in the potential.
    let (bed_term, bed_energy) = foundation::terms(meshes, &beds, &v);
    contact += bed_term;
    // The equilibrated stress, body by body.
    let mut squared = 0.0;
    let mut norm2 = 0.0;
    for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
        let law = crate::fem::assembly::law(body, scene.analysis);
        let dm: [[f64; 3]; 3] = std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                let mut e = [0.0; 3];
                e[c] = 1.0;
                Constitutive::<3>::stress(&law, &e)[r]
            })
        });
        // The elements' nodes read in place rather than copied.
        let out = match mesh.order {
            Order::T3 => {
                let (elems, rest) = mesh.elems.as_chunks::<3>();
                debug_assert!(rest.is_empty() && elems.len() == mesh.n_elems());
                equilibrate::bound(&equilibrate::Input {
                    nodes: &mesh.nodes,
                    elems,
                    u_eq: &u_eq[b],
                    u_cmp: &v[b],
                    u_norm: &u_h[b],
                    d: dm,
                    body_force: body.body_force,
                    given: &given[b],
                    mean_dilatation: None,
                })
            }
            Order::T6 => {
                let (elems, rest) = mesh.elems.as_chunks::<6>();
                debug_assert!(rest.is_empty() && elems.len() == mesh.n_elems());
                quadratic::bound(&equilibrate::Input {
                    nodes: &mesh.nodes,
                    elems,
                    u_eq: &u_eq[b],
                    u_cmp: &v[b],
                    u_norm: &u_h[b],
                    d: dm,
                    body_force: body.body_force,
                    given: &given[b],
                    mean_dilatation: p2p0[b].then(|| Constitutive::<3>::volumetric_lambda(&law)),
                })
            }
        }
        .ok_or("a degenerate element")?;
        // Each element's tractions must balance for its Airy stress to carry
        // them all; round-off leaves 1e-13 or so (the patch test), a node
        // system that was not in equilibrium far more.
        if out.closure > 1e-8 {
            return Err("the equilibrated tractions do not balance an element");
        }
        squared += out.indicators.iter().sum::<f64>();
        norm2 += out.norm2;
    }
    let work: f64 = (0..dofs.free.len())
        .map(|g| {
            let (b, rest) = body_of(dofs, g);
            model.external[g] * u_h[b][rest / 2][rest % 2]
        })
        .sum();
    // The punches' loads work on their motion: J = ½ a(u, u) − ℓ(u) − P · β.
    let punch_work: f64 = model
        .free
        .motions
        .iter()
        .filter_map(|(m, load)| match *m {
            Motion::Punch { obstacle, component } => punches
                .iter()
                .find(|(o, _)| *o == obstacle)
                .map(|(_, beta)| load * beta[component]),
            Motion::Body { .. } => None,
        })
        .sum();
    Ok(EnergyBound {
        absolute: (squared + contact).sqrt() + correction,
        norm: norm2.sqrt(),
        correction,
        contact,
        potential: 0.5 * norm2 - work - punch_work + bed_energy,
        shift,
    })
}

/// Adds a traction linear on each half (`Given`'s four values, from
/// `ends[0]` to `ends[1]`) to a side's given data.
fn add_traction(given: &mut HashMap<[usize; 2], Given>, ends: [usize; 2], t: [[f64; 2]; 4]) {
    let g = given
        .entry([ends[0].min(ends[1]), ends[0].max(ends[1])])
        .or_insert(Given {
            ends,
            traction: [Some([0.0; 4]); 2],
        });
    let flip = g.ends != ends;
    for (c, slot) in g.traction.iter_mut().enumerate() {
        if let Some(v) = slot.as_mut() {
            for (i, x) in v.iter_mut().enumerate() {
                *x += t[if flip { 3 - i } else { i }][c];
            }
        }
    }
}

/// Σ_b ‖v_b − u_b‖²_E in the true energy (every element's full rule, exact
/// for the polynomial strains of straight-sided elements), over the
/// elements v moved.
fn full_energy(scene: &Scene, meshes: &[Mesh2d], v: &[Vec<[f64; 2]>], u: &[Vec<[f64; 2]>]) -> f64 {
    let mut sum = 0.0;
    for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
        let w: Vec<[f64; 2]> = v[b]
            .iter()
            .zip(&u[b])
            .map(|(a, c)| [a[0] - c[0], a[1] - c[1]])
            .collect();
        let moved = (0..mesh.n_elems()).filter(|&e| mesh.elem(e).iter().any(|&n| w[n] != [0.0, 0.0]));
        let law = crate::fem::assembly::law(body, scene.analysis);
        each_element(mesh, scene.analysis, &law, Integration::Full, moved, |conn, ke| {
            let nd = 2 * conn.len();
            let we = |a: usize| w[conn[a / 2]][a % 2];
            for a in 0..nd {
                for c in 0..nd {
                    sum += we(a) * ke[a * nd + c] * we(c);
                }
            }
        });
    }
    sum.max(0.0)
}

/// The body of global DOF `g` and the DOF's index within the body.
fn body_of(dofs: &DofMap, g: usize) -> (usize, usize) {
    let node = g / 2;
    let b = dofs.node_offset.iter().rposition(|&o| o <= node).unwrap_or(0);
    (b, g - 2 * dofs.node_offset[b])
}
