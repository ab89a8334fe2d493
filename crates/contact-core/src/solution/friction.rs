//! Friction in the report: per point the tangential traction, the step's slip
//! and the state (`prescribed` where every DOF the slip reads is held: the
//! solve has no tangential row there, applies no friction force, and the
//! point slides by what the supports prescribe; its traction is then the
//! normal force's share along the tangent alone, 0 against an obstacle); per
//! pair the stick and slip zones and the tangential resultant (added to the
//! pair's and the total resultant, which are the whole contact force on the
//! bodies, and against another body to the force on that one); and the
//! Coulomb conditions' residuals in the certificate, which decide the status
//! like the others.

use std::collections::HashMap;

use crate::contact::friction::Tangents;
use crate::methods::friction::{self as fr, State};
use crate::model::Model;
use crate::scene::{Scene, Target};
use crate::solution::report::{
    FrictionResiduals, FrictionState, PairFriction, PointFriction, Report, Resultant, Status,
};

/// Adds the friction of the step `s` to `report` (composed from the normal
/// forces, with the friction forces among the loads for its equilibrium).
pub fn attach(report: &mut Report, scene: &Scene, model: &Model, t: &Tangents, s: &fr::Friction) {
    let sc = scene.scales;
    let axisymmetric = scene.analysis == crate::scene::Analysis::Axisymmetric;
    let cons = &model.cons;
    let (lambda, state) = (&s.lambda, &s.history.state);
    let residuals = residuals(t, lambda, &s.tau, &s.slip, s.u_scale);
    report.certificate.friction = Some(residuals);
    if report.status == Status::Solved && report.certificate.worst() > scene.settings.tolerance {
        report.status = Status::NumericalError;
    }
    let held: HashMap<usize, usize> = t.held.iter().enumerate().map(|(j, h)| (h.candidate, j)).collect();
    let mut total = Resultant::default();
    for (p, pair) in scene.pairs.iter().enumerate() {
        if pair.friction <= 0.0 {
            continue;
        }
        let by_node: HashMap<usize, usize> = (0..cons.len())
            .filter(|&i| cons.candidates[i].pair == p)
            .map(|i| (cons.candidates[i].node, i))
            .collect();
        let pr = &mut report.pairs[p];
        let points: Vec<PointFriction> = pr
            .points
            .iter()
            .map(|q| {
                let i = by_node[&q.node];
                // The whole contact force's tangential component, which the
                // Coulomb law bounds (the friction force alone but against
                // another body).
                let weight = cons.candidates[i].weight;
                let (traction, slip, tangent) = match (t.row_of[i], held.get(&i)) {
                    (Some(k), _) => (-t.along(k, s.lambda[i], s.tau[k]) / weight, s.slip[k], t.tangent[k]),
                    // No friction force: only the normal force's share.
                    (None, Some(&j)) => (
                        -t.held[j].lean * s.lambda[i] / weight,
                        s.held_slip[j],
                        t.held[j].tangent,
                    ),
                    (None, None) => (0.0, 0.0, [0.0; 2]),
                };
                let tangent =
                    matches!(pair.target, Target::Body { .. } if t.row_of[i].is_some() || held.contains_key(&i))
                        .then_some(tangent);
                let st = match state.get(&(p, q.node)) {
                    _ if !s.in_contact[i] => FrictionState::Open,
                    _ if held.contains_key(&i) => FrictionState::Prescribed,
                    Some(State::Slip(_)) => FrictionState::Slip,
                    _ => FrictionState::Stick,
                };
                PointFriction {
                    traction: sc.stress(traction),
                    tangent,
                    slip: sc.length(slip),
                    state: st,
                }
            })
            .collect();
        // Runs of consecutive points in one state, by their first and last
        // points (the points are in increasing x, then y).
        let runs = |which: FrictionState| -> Vec<[[f64; 2]; 2]> {
            let mut out: Vec<[[f64; 2]; 2]> = Vec::new();
            let mut open = false;
            for (q, f) in pr.points.iter().zip(&points) {
                if f.state == which {
                    match out.last_mut() {
                        Some(z) if open => z[1] = [q.x, q.y],
                        _ => out.push([[q.x, q.y], [q.x, q.y]]),
                    }
                    open = true;
                } else {
                    open = false;
                }
            }
            out
        };
        let xs = |r: &[[[f64; 2]; 2]]| r.iter().map(|z| [z[0][0], z[1][0]]).collect::<Vec<[f64; 2]>>();
        let (stick_runs, slip_runs) = (runs(FrictionState::Stick), runs(FrictionState::Slip));
        // Friction forces on the nodes: −τ times the turned coefficients, on
        // the pair's body (its resultant) and, against another body, on that
        // one (the other resultant: the rows' terms on it carry the opposite
        // force, so the two add up to zero).
        let on = |body: usize| {
            let mesh = &model.meshes[body];
            let mut r = Resultant::default();
            for (k, terms) in t.terms.iter().enumerate() {
                if cons.candidates[t.of[k]].pair != p {
                    continue;
                }
                for term in terms.iter().filter(|term| term.body == body) {
                    let f = [-s.tau[k] * term.coef[0], -s.tau[k] * term.coef[1]];
                    let x = mesh.nodes[term.node];
                    r.fx += f[0];
                    r.fy += f[1];
                    r.m += x[0] * f[1] - x[1] * f[0];
                }
            }
            // A body of revolution's radial forces and moments cancel
            // around each ring, as the normal forces' do (`post`).
            Resultant {
                fx: if axisymmetric { 0.0 } else { sc.force(r.fx) },
                fy: sc.force(r.fy),
                m: if axisymmetric { 0.0 } else { sc.moment(r.m) },
            }
        };
        let r = on(pair.body);
        pr.resultant.fx += r.fx;
        pr.resultant.fy += r.fy;
        pr.resultant.m += r.m;
        if let (Target::Body { body, .. }, Some(other)) = (&pair.target, pr.other_resultant.as_mut()) {
            let o = on(*body);
            other.fx += o.fx;
            other.fy += o.fy;
            other.m += o.m;
        }
        total.fx += r.fx;
        total.fy += r.fy;
        total.m += r.m;
        pr.friction = Some(PairFriction {
            coefficient: pair.friction,
            stick_zones: xs(&stick_runs),
            slip_zones: xs(&slip_runs),
            stick_runs,
            slip_runs,
            tangential_resultant: r,
            points,
        });
    }
    report.resultant.fx += total.fx;
    report.resultant.fy += total.fy;
    report.resultant.m += total.m;
    // The friction forces push the punches as well: P = −Σ (λ c + τ c_t),
    // the normal part already in the report (`punches` lists every punch in
    // the order of the obstacles).
    let punches = scene.obstacles.iter().enumerate().filter(|(_, ob)| ob.punch.is_some());
    for ((o, _), pr) in punches.zip(report.punches.iter_mut()) {
        let mut load = [0.0; 3];
        for (k, punch) in t.punch.iter().enumerate() {
            if let Some((po, ct)) = punch {
                if *po == o {
                    (0..3).for_each(|c| load[c] -= s.tau[k] * ct[c]);
                }
            }
        }
        pr.p1 += sc.force(load[0]);
        pr.p2 += sc.force(load[1]);
        pr.m += sc.moment(load[2]);
    }
}

/// The Coulomb conditions' residuals (see `FrictionResiduals`), relative to
/// the largest normal force and the displacement scale (‖u‖∞, or the largest
/// slip if larger); the stick condition's product (μλ − |t|) |Δs| relative to
/// the largest cone bound μλ where that is larger (μ > 1), the size of its
/// first factor: against λ alone a sticking point's round-off slip ε read as
/// μ ε (1.9e-9 at μ = 1e6 on the roller, 2.4e-5 at 1e10).
pub fn residuals(t: &Tangents, lambda: &[f64], tau: &[f64], slip: &[f64], u_scale: f64) -> FrictionResiduals {
    let inf = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let lmax = inf(lambda);
    let cone_scale = (0..t.len())
        .map(|k| t.bound(k, lambda[t.of[k]].max(0.0)))
        .fold(lmax, f64::max);
    let d = u_scale.max(inf(slip));
    let ratio = |num: f64, den: f64| if num == 0.0 { 0.0 } else { num / den };
    let mut r = FrictionResiduals::default();
    for k in 0..t.len() {
        let l = lambda[t.of[k]];
        let bound = t.bound(k, l.max(0.0));
        let tk = t.along(k, l, tau[k]);
        r.cone = r.cone.max(ratio((tk.abs() - bound).max(0.0), lmax));
        // The friction force −τ along t may not work with the slip: −τ Δs ≤ 0.
        r.dissipation = r.dissipation.max(ratio((-tk * slip[k]).max(0.0), lmax * d));
        r.stick = r
            .stick
            .max(ratio((bound - tk.abs()).max(0.0) * slip[k].abs(), cone_scale * d));
    }
    r
}
