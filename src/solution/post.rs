//! Contact zones, pressures and resultants in the caller's units.
//!
//! Pressure at a candidate p_i = λ_i / w_i (w_i its tributary length), positive
//! in compression. Which candidates are in contact is the method's verdict
//! (`methods::Solution::in_contact`); zones are the x1-extents of runs of
//! consecutive contact candidates ordered by x1.

use crate::contact::ConstraintSet;
use crate::proto::{ContactPoint, PairResult, Resultant};
use crate::scene::Scene;

pub fn pairs(
    scene: &Scene,
    cons: &ConstraintSet,
    lambda: &[f64],
    in_contact: &[bool],
    gaps: &[f64],
) -> (Vec<PairResult>, Resultant, usize) {
    let sc = scene.scales;
    let mut total = Resultant::default();
    let mut n_active = 0;
    let mut out = Vec::with_capacity(scene.pairs.len());
    for (p, pair) in scene.pairs.iter().enumerate() {
        let mut idx: Vec<usize> = (0..cons.len()).filter(|&i| cons.candidates[i].pair == p).collect();
        idx.sort_by(|&a, &b| {
            let (xa, xb) = (cons.candidates[a].x, cons.candidates[b].x);
            xa[0].total_cmp(&xb[0]).then(xa[1].total_cmp(&xb[1]))
        });
        let mut res = Resultant::default();
        let mut points = Vec::with_capacity(idx.len());
        let mut zones: Vec<[f64; 2]> = Vec::new();
        let mut open: Option<[f64; 2]> = None;
        let mut max_pen: f64 = 0.0;
        for &i in &idx {
            let c = &cons.candidates[i];
            let l = lambda[i];
            // Contact force on the body: −λ n (the obstacle pushes against the outward normal).
            let (fx, fy) = (-l * c.normal[0], -l * c.normal[1]);
            res.fx += fx;
            res.fy += fy;
            res.m += c.x[0] * fy - c.x[1] * fx;
            max_pen = max_pen.max(-gaps[i]);
            let x = sc.length(c.x[0]);
            if in_contact[i] {
                n_active += 1;
                open = Some(match open {
                    Some(z) => [z[0], x],
                    None => [x, x],
                });
            } else if let Some(z) = open.take() {
                zones.push(z);
            }
            points.push(ContactPoint {
                x,
                y: sc.length(c.x[1]),
                gap: sc.length(gaps[i]),
                pressure: sc.stress(l / c.weight),
                force: sc.force(l),
                weight: sc.length(c.weight),
                node: c.node,
                normal: c.normal,
            });
        }
        if let Some(z) = open {
            zones.push(z);
        }
        let res = Resultant {
            fx: sc.force(res.fx),
            fy: sc.force(res.fy),
            m: sc.moment(res.m),
        };
        total.fx += res.fx;
        total.fy += res.fy;
        total.m += res.m;
        out.push(PairResult {
            body: scene.bodies[pair.body].name.clone(),
            obstacle: scene.obstacles[pair.obstacle].name.clone(),
            zones,
            points,
            resultant: res,
            max_penetration: sc.length(max_pen),
            pruned: cons.pruned[p],
        });
    }
    (out, total, n_active)
}
