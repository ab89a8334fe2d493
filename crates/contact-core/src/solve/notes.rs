//! Notes of a frictional solve that fell short: what its bodies held only by
//! contact and its load-controlled punches say of why.

use crate::methods;
use crate::model::Model;
use crate::scene::Scene;

/// What a frictional step that ran out of iterations says of the bodies
/// held only by contact. Their loads passed the check with the friction
/// cone before the solve, but that check sees loads, not the normal forces
/// a prescribed displacement makes (the LP may take any λ ≥ 0): a block
/// pressed down by a prescribed uy and pushed by Q = 1.46 μ P ran out of
/// iterations with a note that an equilibrium exists. So the step's own
/// normal forces are checked (`friction_shortfall`): where friction cannot
/// carry the load with them the body most likely slides; otherwise the
/// iteration, not the loads, fell short, and the remedies are more
/// iterations or smaller steps (each starts from the previous one's states,
/// so fewer points change state at once).
pub(crate) fn unsettled_bodies(
    scene: &Scene,
    model: &Model,
    iterations: usize,
    short: &[(usize, f64, String)],
) -> Vec<String> {
    let mut bodies: Vec<usize> = model.dofs.rigid.iter().map(|rm| rm.body).collect();
    bodies.sort_unstable();
    bodies.dedup();
    bodies
        .into_iter()
        .map(|b| {
            let name = &scene.bodies[b].name;
            let worst = short
                .iter()
                .filter(|s| s.0 == b)
                .max_by(|x, y| x.1.total_cmp(&y.1))
                .filter(|s| s.1 > 1.0 + SHORTFALL_SLACK);
            match worst {
                Some((_, ratio, motion)) => format!(
                    "body '{name}' is held only by contact and most likely slides: the frictional iteration did not \
                     settle \
                     in {iterations} iterations, and with the normal forces of its last iterate the load along the \
                     {motion} \
                     is {ratio:.4} times the most friction can carry (μ times those normal forces); the check of \
                     the loads \
                     with the friction cone before the solve sees loads only, not normal forces made by prescribed \
                     displacements: keep the load along that motion below μ times the normal force, or press harder"
                ),
                None => format!(
                    "body '{name}' is held only by contact: the frictional iteration did not settle its points' \
                     stick and \
                     slip states in {iterations} iterations; its loads pass the check with the friction cone, and the \
                     normal forces of the last iterate leave friction enough to carry them: raise \
                     settings.max_iterations \
                     ({}), or apply the loads in more steps (load_path)",
                    scene.settings.max_iterations
                ),
            }
        })
        .collect()
}

/// Round-off allowance of `friction_shortfall`'s ratio: the sums it compares
/// are of the step's forces, exact to a few ε of the largest.
const SHORTFALL_SLACK: f64 = 1e-9;

/// Per free rigid motion of a body held only by contact in the block:
/// (body, ratio, motion in words), the ratio of what friction must carry
/// along the motion once the normal forces λ have taken their share,
/// |rhs − C_Nᵀλ − C_Tᵀτ₀|, to the most the cone allows, Σ |C_T| μ λ, with τ₀
/// the centre of each point's cone (−λ n · t, 0 but against another body).
/// Above 1 no friction force in the cones balances the motion at these λ.
pub(crate) fn friction_shortfall(
    scene: &Scene,
    model: &Model,
    (block, keep): (&methods::FreeBlock, &[usize]),
    t: &crate::contact::friction::Tangents,
    lambda: &[f64],
) -> Vec<(usize, f64, String)> {
    use crate::contact::free_motions::Motion;
    let mut out = Vec::new();
    for (j, &m) in keep.iter().enumerate() {
        let Motion::Body { set, dir } = model.free.motions[m].0 else {
            continue;
        };
        let normal: f64 = (0..block.cn.nrows()).map(|i| block.cn[(i, j)] * lambda[i]).sum();
        let (mut centre, mut reach) = (0.0, 0.0);
        for k in 0..t.len() {
            let l = lambda[t.of[k]].max(0.0);
            centre -= block.ct[(k, j)] * t.along(k, l, 0.0);
            reach += block.ct[(k, j)].abs() * t.bound(k, l);
        }
        let need = (block.rhs[j] - normal - centre).abs();
        // What the normal forces balance exactly (a translation normal to a
        // flat floor, which no cone reaches) leaves round-off, not a load.
        let scale = block.rhs[j].abs() + normal.abs() + reach;
        let ratio = if need <= SHORTFALL_SLACK * scale {
            0.0
        } else {
            need / reach
        };
        let rm = &model.dofs.rigid[set];
        out.push((rm.body, ratio, rm.describe(dir, scene.scales.length(1.0))));
    }
    out
}

/// Why a frictional step with a load-controlled punch may not converge: a
/// horizontal load beyond μ times the vertical one. The frictional
/// compatibility check refuses it on a flat face and on a curved punch over
/// a flat block (each candidate's cone is taken about both normals,
/// `FreeMotions::check_with_friction`); where the punch's and the body's
/// normals are inclined together (a face and a surface both sloping) it can
/// admit it, and a step that then does not converge gets this note.
pub(crate) fn sliding_punches(scene: &Scene) -> Vec<String> {
    use crate::contact::friction_law::law_of;
    use crate::scene::{Control, Target};
    scene
        .obstacles
        .iter()
        .enumerate()
        .filter_map(|(o, ob)| {
            let punch = ob.punch.as_ref()?;
            let (Control::Load(q), Control::Load(p)) = (punch.controls[0], punch.controls[1]) else {
                return None;
            };
            let pairs = || {
                scene
                    .pairs
                    .iter()
                    .filter(move |pr| matches!(pr.target, Target::Obstacle(t) if t == o))
            };
            let mu = pairs().map(|pr| pr.friction).fold(0.0, f64::max);
            let most = pairs().map(|pr| law_of(pr).bound(p.abs())).fold(0.0, f64::max);
            (mu > 0.0 && q.abs() > most).then(|| {
                format!(
                    "punch '{}': its horizontal load is {:.4} times its vertical load, more than the friction \
                     coefficient {mu}: \
                     on a flat face it would slide; on this profile the compatibility check admitted it (inclined \
                     normals), \
                     and the frictional iteration did not converge; the punch most likely slides (keep |Q| below μ|P|)",
                    ob.name,
                    q.abs() / p.abs().max(f64::MIN_POSITIVE)
                )
            })
        })
        .collect()
}
