//! The 3D answer in the request's units: the report of `report`, scaled
//! back (`scene` module doc: positions and gaps times the length, pressures
//! times the modulus, forces times modulus · length², moments times
//! modulus · length³; areas times length²), with the solve's status and
//! sizes. No wire types: the `contact` crate writes it as the reply.

use super::report::SolidContactReport;
use super::two_level::Estimate;
use crate::mesh3d::Order;
use crate::observer::Timings;
use crate::outcome::{EstimateBasis, Note, Status};
use crate::scene::solid::SolidScene;
use crate::scene::Outputs;
use crate::solution::report::{Refinement, Warning};

#[derive(Debug, Clone)]
pub struct SolidAnswer {
    pub body: String,
    pub obstacle: String,
    pub faces: String,
    pub order: Order,
    pub status: Status,
    pub report: SolidContactReport,
    /// Largest penetration of a row, max(−gap, 0).
    pub max_penetration: f64,
    /// Free DOFs, rows, rows in contact.
    pub dofs: usize,
    pub candidates: usize,
    pub active: usize,
    /// Contact-force refinement steps on the final active set.
    pub refinements: usize,
    /// Bytes of the factor of K (`signorini::Operator::factor_bytes`): what
    /// the next refinement round's memory is predicted from.
    pub factor_bytes: f64,
    pub timings: Timings,
    pub client_id: Option<String>,
    /// What the request's `outputs` asked for.
    pub outputs: Outputs,
    /// The body's fields, when `outputs` asks for any of them.
    pub fields: Option<BodyFields>,
    /// One per load factor or load path step when the request lists
    /// `load_factors` or `load_path` (the rest of the answer is the last
    /// one's).
    pub steps: Option<Vec<SolidStep>>,
    /// The error estimate (`adapt::solid`), None where `settings.estimate`
    /// is false.
    pub accuracy: Option<SolidAccuracy>,
    /// With `settings.accuracy`: the rounds that led to this answer.
    pub refinement: Option<Refinement>,
    pub notes: Vec<Note>,
    pub warnings: Vec<Warning>,
}

/// The answer at one load factor, in the request's units.
#[derive(Debug, Clone)]
pub struct SolidStep {
    /// The load factor (1 for a load path step).
    pub factor: f64,
    /// A load path step's factors, as the request named them.
    pub loads: Option<std::collections::BTreeMap<String, f64>>,
    pub status: Status,
    pub report: SolidContactReport,
    pub max_penetration: f64,
}

/// A solid answer's error estimate: how it was made, and the estimated
/// relative errors (`solid::two_level::Estimate`; all None with
/// `EstimateBasis::NoEstimate`, the notes saying why).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidAccuracy {
    pub basis: EstimateBasis,
    pub estimate: Estimate,
}

impl SolidAccuracy {
    /// No estimate (a given mesh, or a companion that did not solve).
    pub fn none() -> Self {
        SolidAccuracy {
            basis: EstimateBasis::NoEstimate,
            estimate: Estimate {
                pressure_l2: None,
                peak: None,
                resultant: None,
                contact_area: None,
            },
        }
    }
}

/// The body as solved, in the request's units: what `outputs` (mesh,
/// displacement, stress, vtu) reads.
#[derive(Debug, Clone)]
pub struct BodyFields {
    pub nodes: Vec<[f64; 3]>,
    /// Connectivity, `order.nodes_per_element()` per element (Gmsh's order).
    pub elems: Vec<usize>,
    pub displacement: Vec<[f64; 3]>,
    /// Centroid stress per element, Voigt (xx, yy, zz, yz, xz, xy); empty
    /// unless `stress` or `vtu` is asked for.
    pub stress: Vec<[f64; 6]>,
}

impl BodyFields {
    /// Nondimensional fields scaled back: positions and displacements times
    /// the length, stresses times the modulus.
    pub fn dimensional(
        nodes: &[[f64; 3]],
        elems: &[usize],
        u: &[[f64; 3]],
        s: &[[f64; 6]],
        scene: &SolidScene,
    ) -> Self {
        let (l, e) = (scene.length, scene.modulus);
        BodyFields {
            nodes: nodes.iter().map(|x| x.map(|c| c * l)).collect(),
            elems: elems.to_vec(),
            displacement: u.iter().map(|x| x.map(|c| c * l)).collect(),
            stress: s.iter().map(|x| x.map(|c| c * e)).collect(),
        }
    }
}

/// The status of a solve: solved when it converged with a certificate
/// within the tolerance (the 2D rule for exact methods).
pub fn status(report: &SolidContactReport, tolerance: f64) -> Status {
    let worst = report.certificate.worst();
    if !worst.is_finite() {
        Status::NumericalError
    } else if !report.converged {
        Status::MaxIterations
    } else if worst > tolerance {
        Status::NumericalError
    } else {
        Status::Solved
    }
}

/// `report` in the request's units.
pub fn dimensional(mut report: SolidContactReport, scene: &SolidScene) -> SolidContactReport {
    let (l, e) = (scene.length, scene.modulus);
    let at = |x: [f64; 3]| x.map(|c| c * l);
    for p in &mut report.points {
        p.position = at(p.position);
        p.pressure *= e;
        p.gap *= l;
    }
    for p in &mut report.patches {
        p.area *= l * l;
        p.tributary_area *= l * l;
        p.force *= e * l * l;
        p.centre_of_pressure = at(p.centre_of_pressure);
        p.peak_pressure *= e;
        p.peak_at = at(p.peak_at);
        for ring in &mut p.outline {
            ring.iter_mut().for_each(|x| *x = at(*x));
        }
    }
    report.resultant.force = report.resultant.force.map(|f| f * e * l * l);
    report.resultant.moment = report.resultant.moment.map(|m| m * e * l * l * l);
    report
}
