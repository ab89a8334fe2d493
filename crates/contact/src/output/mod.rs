//! Files made from a reply, as bytes or text (the shells write them): the VTU
//! grid for ParaView and the contact candidates as CSV.

pub mod csv;
pub mod vtu;
pub mod vtu_solid;

use base64::Engine;

use crate::proto::SolveReply;
use contact_core::scene::Outputs;

/// With `vtu` requested: sets the reply's `vtu` (base64 of the file) and drops
/// the per-body fields it needed that the request did not list. `stress_zz`:
/// each body's σzz per element (plane strain; the hoop stress in axisymmetry),
/// which the reply does not carry; `axisymmetric`: the file states the axis.
pub fn attach_vtu(reply: &mut SolveReply, asked: Outputs, stress_zz: &[Vec<f64>], axisymmetric: bool) {
    if !asked.vtu {
        return;
    }
    reply.vtu = Some(base64::engine::general_purpose::STANDARD.encode(vtu::vtu(reply, stress_zz, axisymmetric)));
    if !(asked.mesh || asked.displacement || asked.stress) {
        reply.bodies = None;
        return;
    }
    for b in reply.bodies.iter_mut().flatten() {
        if !asked.mesh {
            b.nodes = None;
            b.elements = None;
        }
        if !asked.displacement {
            b.displacement = None;
        }
        if !asked.stress {
            b.stress = None;
        }
    }
}
