//! Contact zones, pressures and resultants in the caller's units.
//!
//! Pressure at a candidate p_i = λ_i / w_i (w_i its tributary length), positive
//! in compression. Which candidates are in contact is the method's verdict
//! (`methods::Solution::in_contact`); zones are the x1-extents of runs of
//! consecutive contact candidates ordered by x1. Forces on nodes come from the
//! rows' nodal terms (−λ · coef), so resultants hold for every discretization,
//! and for two bodies the other side's pressure is its nodal force over its
//! tributary length.

use std::collections::BTreeMap;

use crate::contact::ConstraintSet;
use crate::mesh::{boundary::boundary_nodes, Mesh2d};
use crate::scene::{Discretization, Scene, Target};
use crate::solution::report::{ContactPoint, CounterPoint, PairReport, PairTarget, Resultant};

/// Nodal contact forces of pair `p` on `body`: node → force.
fn nodal_forces(cons: &ConstraintSet, lambda: &[f64], p: usize, body: usize) -> BTreeMap<usize, [f64; 2]> {
    let mut out: BTreeMap<usize, [f64; 2]> = BTreeMap::new();
    for (c, &l) in cons.candidates.iter().zip(lambda) {
        if c.pair != p {
            continue;
        }
        for t in c.terms.iter().filter(|t| t.body == body) {
            let f = out.entry(t.node).or_insert([0.0; 2]);
            f[0] -= l * t.coef[0];
            f[1] -= l * t.coef[1];
        }
    }
    out
}

fn resultant_of(forces: &BTreeMap<usize, [f64; 2]>, mesh: &Mesh2d) -> Resultant {
    let mut r = Resultant::default();
    for (&n, f) in forces {
        let x = mesh.nodes[n];
        r.fx += f[0];
        r.fy += f[1];
        r.m += x[0] * f[1] - x[1] * f[0];
    }
    r
}

pub fn pairs(
    scene: &Scene,
    meshes: &[Mesh2d],
    cons: &ConstraintSet,
    lambda: &[f64],
    in_contact: &[bool],
    gaps: &[f64],
) -> (Vec<PairReport>, Resultant, usize) {
    let sc = scene.scales;
    let axisymmetric = scene.analysis == crate::scene::Analysis::Axisymmetric;
    let mut total = Resultant::default();
    let mut n_active = 0;
    let mut out = Vec::with_capacity(scene.pairs.len());
    for (p, pair) in scene.pairs.iter().enumerate() {
        let mut idx: Vec<usize> = (0..cons.len()).filter(|&i| cons.candidates[i].pair == p).collect();
        idx.sort_by(|&a, &b| {
            let (xa, xb) = (cons.candidates[a].x, cons.candidates[b].x);
            xa[0].total_cmp(&xb[0]).then(xa[1].total_cmp(&xb[1]))
        });
        let mut points = Vec::with_capacity(idx.len());
        let mut zones: Vec<[f64; 2]> = Vec::new();
        let mut open: Option<[f64; 2]> = None;
        let mut max_pen: f64 = 0.0;
        // The mortar pressure is the field Σ p_i N_i: it is positive up to the
        // neighbouring nodes of the active ones, so its zone reaches them.
        let field = matches!(
            pair.target,
            Target::Body {
                discretization: Discretization::Mortar,
                ..
            }
        );
        let mut prev: Option<f64> = None;
        for &i in &idx {
            let c = &cons.candidates[i];
            let l = lambda[i];
            max_pen = max_pen.max(-gaps[i]);
            let x = sc.length(c.x[0]);
            // A foundation's pressure is constant on each row's panel.
            let (lo, hi) = match c.foundation() {
                Some(fr) => (sc.length(fr.panel[0]), sc.length(fr.panel[1])),
                None => (x, x),
            };
            if in_contact[i] {
                n_active += 1;
                open = Some(match open {
                    Some(z) => [z[0], hi],
                    None => [if field { prev.unwrap_or(x) } else { lo }, hi],
                });
            } else if let Some(z) = open.take() {
                zones.push(if field { [z[0], x] } else { z });
            }
            prev = Some(x);
            points.push(ContactPoint {
                x,
                y: sc.length(c.x[1]),
                gap: sc.length(gaps[i]),
                pressure: sc.stress(l / c.weight),
                force: sc.force(l),
                weight: sc.weight(c.weight),
                node: c.node,
                normal: c.normal,
            });
        }
        if let Some(z) = open {
            zones.push(z);
        }
        // The radial forces of a body of revolution and their moments cancel
        // over the circumference.
        let to_user = |r: Resultant| Resultant {
            fx: if axisymmetric { 0.0 } else { sc.force(r.fx) },
            fy: sc.force(r.fy),
            m: if axisymmetric { 0.0 } else { sc.moment(r.m) },
        };
        let res = to_user(resultant_of(
            &nodal_forces(cons, lambda, p, pair.body),
            &meshes[pair.body],
        ));
        let other = match &pair.target {
            Target::Obstacle(_) | Target::Foundation(_) => None,
            Target::Body { body, edges, .. } => {
                let (mesh, forces) = (&meshes[*body], nodal_forces(cons, lambda, p, *body));
                let mut pts: Vec<CounterPoint> = boundary_nodes(mesh, &mesh.edge_sets[edges], axisymmetric)
                    .into_iter()
                    .map(|bn| {
                        let f = forces.get(&bn.node).copied().unwrap_or([0.0; 2]);
                        // Compression pushes against the outward normal.
                        let fn_ = -(f[0] * bn.normal[0] + f[1] * bn.normal[1]);
                        let x = mesh.nodes[bn.node];
                        CounterPoint {
                            x: sc.length(x[0]),
                            y: sc.length(x[1]),
                            // A T6 corner on the axis has no area of its own.
                            pressure: sc.stress(if bn.weight > 0.0 { fn_ / bn.weight } else { 0.0 }),
                            force: sc.force(fn_),
                            weight: sc.weight(bn.weight),
                            node: bn.node,
                        }
                    })
                    .collect();
                pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
                Some((pts, to_user(resultant_of(&forces, mesh))))
            }
        };
        total.fx += res.fx;
        total.fy += res.fy;
        total.m += res.m;
        let target = match &pair.target {
            Target::Obstacle(o) => PairTarget::Obstacle(scene.obstacles[*o].name.clone()),
            Target::Foundation(f) => PairTarget::Foundation(scene.foundations[*f].name.clone()),
            Target::Body {
                body, discretization, ..
            } => PairTarget::Body(scene.bodies[*body].name.clone(), *discretization),
        };
        let (other_points, other_resultant) = other.map_or((None, None), |(p, r)| (Some(p), Some(r)));
        out.push(PairReport {
            body: scene.bodies[pair.body].name.clone(),
            target,
            other_points,
            other_resultant,
            zones,
            points,
            resultant: res,
            max_penetration: sc.length(max_pen),
            pruned: cons.pruned[p],
        });
    }
    (out, total, n_active)
}
