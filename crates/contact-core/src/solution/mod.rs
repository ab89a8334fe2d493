//! Solution → report: certificate, contact zones, pressures, resultants.

pub mod accuracy;
pub mod certificate;
pub mod compose;
pub mod corners;
pub mod couplings;
pub mod end_layer;
pub mod energy;
pub mod friction;
pub mod peak_fit;
pub mod post;
pub mod prescribed_slip;
pub mod report;
pub mod two_level;
pub mod validity;
