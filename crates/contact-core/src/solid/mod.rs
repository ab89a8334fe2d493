//! The 3D solid: linear elasticity of a tetrahedral body (`mesh3d`, T4 or
//! T10) and its frictionless contact with a rigid obstacle (a plane, a
//! sphere, a cylinder, a paraboloid), with the answer's
//! contact patches. A request reaches it with `analysis: "solid"`: the
//! door makes a `scene::solid::SolidScene`, `door` builds and checks its
//! given mesh, the route `solve::solid` solves it.
//!
//! The dimension lives in the element and mesh rooms: the element stiffness
//! is `fem::kernel::stiffness` over `fem::reference::{T4, T10}` with the
//! `Solid` strains and `fem::constitutive`'s law in `Section::Solid`; the
//! sparse pattern and scatter are `fem::pattern`'s (the 2D assembly's, with
//! D = 3); the factorization, the condensed operator W = B K⁻¹ Bᵀ and the
//! LCP are `linalg::{cholesky, schur}` and `methods::{condensed,
//! active_set}`, which never knew the dimension. What is here is what a
//! body of tetrahedra adds: 3 DOFs per node (`dofs`, DOF 3·node + c), its
//! assembly and loads on face sets (`stiffness`, `loads`), a linear solve
//! (`linear`), rows against the obstacle (`obstacle`), the Signorini solve with
//! its KKT certificate (`signorini`), the loads of a load path's steps
//! (`path`), the answer as contact patches (area,
//! force, centre of pressure, peak, outline polygons), points and the
//! resultant (`report`), the displacement and stress `outputs` asks for
//! (`fields`), and a nested-dissection order of the DOFs for the
//! factorization (`ordering`: AMD fills 3D factors 2–4 times more; it polls
//! the request's deadline as the other stages do).
//!
//! Lengths, moduli and loads are nondimensional (the caller's scales), as
//! everywhere below the scene.

pub mod answer;
pub mod dofs;
pub mod door;
pub mod fields;
pub mod linear;
pub mod loads;
pub mod obstacle;
pub mod ordering;
pub mod path;
pub mod report;
pub mod signorini;
pub mod stiffness;
pub mod two_level;
pub mod validity;

use crate::error::{CoreError, InvalidKind};
use crate::mesh3d::Mesh3d;

pub use crate::scene::solid::{FaceLoad, Support};

/// An elastic body of tetrahedra with its material, supports and loads.
#[derive(Debug, Clone)]
pub struct SolidBody<'a> {
    pub mesh: &'a Mesh3d,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub supports: Vec<Support>,
    pub loads: Vec<FaceLoad>,
    /// Force per unit volume.
    pub body_force: [f64; 3],
}

impl SolidBody<'_> {
    /// The checks a request's door would make: a positive modulus, ν in
    /// (−1, ½), and every named face set present. The path of a failure is
    /// the field's (`supports/k/faces`, `loads/k/faces`).
    pub fn check(&self) -> Result<(), CoreError> {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        if !(e > 0.0 && e.is_finite()) {
            return Err(CoreError::invalid(
                InvalidKind::Material,
                "youngs_modulus",
                format!("Young's modulus must be positive and finite, got {e}"),
            ));
        }
        if !(nu > -1.0 && nu < 0.5) {
            return Err(CoreError::invalid(
                InvalidKind::Material,
                "poisson_ratio",
                format!("Poisson's ratio must lie in (-1, 0.5), got {nu}"),
            ));
        }
        for (k, s) in self.supports.iter().enumerate() {
            self.face_set(&s.faces, &format!("supports/{k}/faces"))?;
        }
        for (k, l) in self.loads.iter().enumerate() {
            self.face_set(l.faces(), &format!("loads/{k}/faces"))?;
        }
        Ok(())
    }

    /// The faces of set `name`, or an `invalid_mesh` error at `path`.
    pub fn face_set(&self, name: &str, path: &str) -> Result<&[crate::mesh3d::Face], CoreError> {
        self.mesh.face_sets.get(name).map(|v| v.as_slice()).ok_or_else(|| {
            let known: Vec<&str> = self.mesh.face_sets.keys().map(|k| k.as_str()).collect();
            CoreError::invalid(
                InvalidKind::Mesh,
                path,
                format!("the mesh has no face set '{name}' (it has: {})", known.join(", ")),
            )
        })
    }
}
