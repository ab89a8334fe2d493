//! A body's coupling on the degrees of freedom: its edge set's nodes held
//! at the prescribed part of the reference point's motion, its loaded
//! components the body's free rigid modes (`RigidModes`).

use super::rigid_modes::RigidModes;
use crate::error::{CoreError, InvalidKind};
use crate::mesh::Mesh2d;
use crate::scene::{Control, Coupling};

/// A body's coupling as supports and rigid modes. The coupled nodes are held
/// at the motion of the coupling's displacement-controlled components, and
/// its load-controlled components are the body's free rigid modes about the
/// reference point: u = ũ + R β with ũ = that motion on the coupled nodes.
/// Since the coupling is then the body's only support (`validate::couplings`),
/// K R = 0 and this is exactly the master–slave elimination of the coupled
/// DOFs in favour of the reference point's, with K̃ (the coupled nodes held)
/// positive definite: the loaded components are free motions like a body's
/// held only by contact, their loads the coupling's (carried by the coupled
/// nodes' nodal forces, `fem::loads`). The coupled nodes are no contact
/// candidates: like a supported node's, a row with no free DOF is dropped
/// (`contact::constraints::moves_rigidly` sees no virtual support), since its
/// tangential row would have no compliance at all and a sticking point there
/// made the frictional Newton system singular (measured: the T3 roller of
/// `signorini_roller_on_flat.json` pressed through its axle in one step with
/// friction ended at the iteration cap with nothing in contact, through the
/// two arc ends its axle shares; without their rows it solved in 14
/// iterations). `None` when every component is prescribed.
pub fn held(
    body: usize,
    cp: &Coupling,
    mesh: &Mesh2d,
    off: usize,
    fixed: &mut [bool],
    prescribed: &mut [f64],
) -> Result<Option<RigidModes>, CoreError> {
    for node in mesh.edge_set_nodes(&cp.edges) {
        let v = cp.prescribed_at(mesh.nodes[node]);
        for c in 0..2 {
            let d = 2 * (off + node) + c;
            if fixed[d] && prescribed[d] != v[c] {
                return Err(CoreError::invalid(
                    InvalidKind::Request,
                    cp.path.clone(),
                    format!(
                        "node {node} of the coupled edge set is also held by another condition with a different {} \
                            displacement",
                        ["x", "y"][c]
                    ),
                ));
            }
            fixed[d] = true;
            prescribed[d] = v[c];
        }
    }
    let basis: Vec<[f64; 3]> = (0..3)
        .filter(|&k| matches!(cp.controls[k], Control::Load(_)))
        .map(|k| {
            let mut e = [0.0; 3];
            e[k] = 1.0;
            e
        })
        .collect();
    Ok((!basis.is_empty()).then(|| RigidModes {
        body,
        center: cp.reference,
        basis,
        virtual_dofs: Vec::new(),
    }))
}
