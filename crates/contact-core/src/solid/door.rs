//! The solid room's part of the door, run right after
//! `scene::validate::solid_scene` and before any solve: a given mesh
//! (inline or Gmsh) is built and checked (`mesh3d::quality`: inverted or
//! degenerate tetrahedra, T10 maps that fold, face sets that are not
//! boundary faces, at the pointers the scene carries), and every face set
//! the request names must be the mesh's (a box's are `BOX_FACES`).

use crate::error::{CoreError, InvalidKind};
use crate::mesh::quality::Conn;
use crate::mesh3d::generate::BOX_FACES;
use crate::mesh3d::{gmsh, quality, Mesh3d};
use crate::scene::solid::{SolidMesh, SolidScene};

/// A 3D request that passed the door: its scene, and its mesh when given
/// (a box is generated in the route's mesh stage).
#[derive(Debug, Clone)]
pub struct SolidProblem {
    pub scene: SolidScene,
    pub mesh: Option<Mesh3d>,
}

impl SolidProblem {
    pub fn t10(&self) -> bool {
        match (&self.mesh, &self.scene.mesh) {
            (Some(m), _) => m.order == crate::mesh3d::Order::T10,
            (None, SolidMesh::Box { t10, .. }) => *t10,
            (None, _) => false,
        }
    }
}

/// The problem of `scene`: its given mesh built (the scene's copy of the
/// data moves into it) and its face-set names checked.
pub fn admit(mut scene: SolidScene) -> Result<SolidProblem, CoreError> {
    let length = scene.length;
    let mesh = match &mut scene.mesh {
        SolidMesh::Box { .. } => None,
        SolidMesh::Inline {
            nodes,
            elements,
            ends,
            face_sets,
            path,
        } => {
            let conn = Conn::Ragged { nodes: elements, ends };
            let mesh = quality::try_inline(std::mem::take(nodes), conn, face_sets, path)?;
            (*elements, *ends) = (Vec::new(), Vec::new());
            face_sets.clear();
            Some(mesh)
        }
        SolidMesh::Gmsh { msh, volumes, path } => {
            let mesh = gmsh::try_parse(msh, volumes, path)?.try_mesh(length, path)?;
            msh.clear();
            Some(mesh)
        }
    };
    let names: Vec<String> = match &mesh {
        None => BOX_FACES.iter().flatten().map(|s| s.to_string()).collect(),
        Some(m) => m.face_sets.keys().cloned().collect(),
    };
    let need = |name: &str, path: String| -> Result<(), CoreError> {
        if names.iter().any(|n| n == name) {
            return Ok(());
        }
        Err(CoreError::invalid(
            InvalidKind::Request,
            path,
            format!("no face set named '{name}' on this body (it has: {})", names.join(", ")),
        ))
    };
    for (k, s) in scene.supports.iter().enumerate() {
        need(&s.faces, format!("/solid/body/supports/{k}/faces"))?;
    }
    for (k, l) in scene.loads.iter().enumerate() {
        need(l.faces(), format!("/solid/body/tractions/{k}/faces"))?;
    }
    need(&scene.faces, "/solid/contact/faces".into())?;
    Ok(SolidProblem { scene, mesh })
}
