//! `foundations`: tensionless Winkler, Pasternak and half-plane foundations,
//! nondimensional.

use contact_proto::{self as proto, SolveRequest};

use super::{finite, invalid, poisson, positive};
use crate::error::{CoreError, InvalidKind as K};
use crate::scene::{Foundation, FoundationModel, Scales};

/// The foundations and their names (for the pairs).
pub fn foundations(req: &SolveRequest, scales: Scales) -> Result<(Vec<String>, Vec<Foundation>), CoreError> {
    let Scales { length, modulus, .. } = scales;
    let mut foundation_names = Vec::new();
    let mut foundations = Vec::new();
    for (i, f) in req.foundations.iter().enumerate() {
        let fp = format!("/foundations/{i}");
        let name = f.name.clone().unwrap_or_else(|| format!("foundation{i}"));
        if foundation_names.contains(&name) {
            return Err(invalid(
                K::Request,
                format!("{fp}/name"),
                format!("duplicate foundation name '{name}'"),
            ));
        }
        foundation_names.push(name.clone());
        let y = finite(f.y, &format!("{fp}/y"), K::Geometry)?;
        let x_min = finite(f.x_min, &format!("{fp}/x_min"), K::Geometry)?;
        let x_max = finite(f.x_max, &format!("{fp}/x_max"), K::Geometry)?;
        if x_max <= x_min {
            return Err(invalid(
                K::Geometry,
                format!("{fp}/x_max"),
                format!("the foundation must have x_max > x_min, got [{x_min}, {x_max}]"),
            ));
        }
        let mp = format!("{fp}/model");
        if req.analysis == proto::Analysis::Axisymmetric {
            if let proto::FoundationModel::HalfPlane { .. } = &f.model {
                return Err(invalid(
                    K::Request,
                    mp,
                    "the elastic half-plane is not available in axisymmetry (a body of revolution rests on a \
                        half-space, whose ring-load kernel is not built yet); Winkler and Pasternak foundations are",
                ));
            }
            if x_min < 0.0 {
                return Err(invalid(
                    K::Geometry,
                    format!("{fp}/x_min"),
                    format!("in axisymmetry x is the radius: the foundation must start at x_min ≥ 0, got {x_min}"),
                ));
            }
        }
        let model = match &f.model {
            proto::FoundationModel::Winkler { stiffness } => FoundationModel::Winkler {
                k: positive(
                    *stiffness,
                    &format!("{mp}/winkler/stiffness"),
                    K::Material,
                    "the Winkler stiffness",
                )? * length
                    / modulus,
            },
            proto::FoundationModel::Pasternak { stiffness, shear } => {
                let k = positive(
                    *stiffness,
                    &format!("{mp}/pasternak/stiffness"),
                    K::Material,
                    "the Pasternak stiffness",
                )?;
                let mu = finite(*shear, &format!("{mp}/pasternak/shear"), K::Material)?;
                if mu < 0.0 {
                    return Err(invalid(
                        K::Material,
                        format!("{mp}/pasternak/shear"),
                        format!("the shear layer's μ must be ≥ 0, got {mu}"),
                    ));
                }
                FoundationModel::Pasternak {
                    k: k * length / modulus,
                    mu: mu / (modulus * length),
                }
            }
            proto::FoundationModel::HalfPlane {
                youngs_modulus,
                poisson_ratio,
                reference_distance,
            } => {
                let hp = format!("{mp}/half_plane");
                let e = positive(
                    *youngs_modulus,
                    &format!("{hp}/youngs_modulus"),
                    K::Material,
                    "Young's modulus",
                )?;
                let nu = poisson(*poisson_ratio, &format!("{hp}/poisson_ratio"))?;
                let d = positive(
                    *reference_distance,
                    &format!("{hp}/reference_distance"),
                    K::Geometry,
                    "the reference distance",
                )?;
                FoundationModel::HalfPlane {
                    e_star: e / (1.0 - nu * nu) / modulus,
                    d: d / length,
                }
            }
        };
        foundations.push(Foundation {
            name,
            y: y / length,
            x_min: x_min / length,
            x_max: x_max / length,
            model,
        });
    }

    Ok((foundation_names, foundations))
}
