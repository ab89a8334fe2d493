//! Solution → reply: certificate, contact zones, pressures, resultants.

pub mod certificate;
pub mod post;
pub mod validity;
