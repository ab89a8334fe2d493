//! Frictional contact points whose slip the supports prescribe, found before
//! the solve.
//!
//! A frictional row's slip is the tangential displacement of its node
//! relative to the other surface, t · u(x) − t · u^b(y) (`contact::friction`).
//! Where the node's motion along t is held by a support and so is the facing
//! point's (the other body's nodes whose shape functions do not vanish at the
//! node's projection; a fixed obstacle; a punch whose motion along t is
//! prescribed), that slip is a datum of the scene, not an unknown: the node
//! slides by it whatever μ, and Coulomb's law gives it the friction force
//! μ λ. At a real μ that is the answer; but it grows with μ without bound,
//! and reaches the free nodes through the row's weights (a mortar row also
//! tests the next nodes), so such a scene has no stick limit as μ grows: the
//! press fit pushed by the shaft's bottom with the ring's bottom held, whose
//! push-out forces the doc of `scene::validate::pairs::MAX_FRICTION` gives.
//!
//! A warning, not a refusal: at the μ of real surfaces (0.05 to 0.4 on that
//! press fit, every step solved with the push-out force μ N to 1e-12) the
//! answer is Coulomb's and is used; what is wrong is reading a large μ as
//! "the surfaces stick". Where no free DOF moves along t the support takes
//! the friction force itself (`Tangents::new` leaves the row out, listing
//! the point in `Tangents::held`), and the solve carries no μ λ there: such
//! a point is judged too, and the warning says its friction force is left
//! out of the reply. Where the supports leave the node one free direction
//! that its normal row moves too (`Tangents::tied`), the closed gap fixes
//! the slip: judged the same way (`closed`).
//! The points are found from the scene and its rows before the solve
//! (`find`); the step's answer reports those in contact (`warnings`): a point
//! that stays open carries no friction force. A slip prescribed to 0 (both
//! sides held still: the press fit's closing step, a symmetry plane held on
//! both bodies) is not reported: the point may stick, with a bounded force.
//!
//! A tied point can wedge. Closed and sliding by its datum s, its forces move
//! its gap by a (1 + r γ) λ (γ = μ sign(s) − ℓ, ℓ = n · t, a its own
//! compliance; `methods::friction::gauss_seidel`): where 1 + r γ ≤ 0, from
//! μ = (1 − r ℓ) / |r| on when r s < 0, its friction force pushes it into the
//! surface at least as hard as its normal force pushes it out (a node free
//! along y alone: μ |n_x| ≥ n_y). Pressed in by the rest, it then has no
//! Coulomb answer, closed or open. The Hertz block with its top held along x
//! against the cylinder (R 8, zone half-width 0.67, so |n_x| / n_y ≤ 0.084)
//! solves at μ = 0.3 and ran to its iteration cap at μ = 20 and 100, with
//! the zone shrunk to |x| < 0.39 and 0.07, where μ |x| / R < 1: a step that
//! does not settle names such points in its warning (`wedges_from`).

use std::collections::{BTreeMap, BTreeSet, HashMap};

use crate::contact::friction::Tangents;
use crate::mesh::Mesh2d;
use crate::model::Model;
use crate::outcome::WarningCode;
use crate::scene::scaling::shown;
use crate::scene::{Analysis, Control, Scene, Target};
use crate::solution::report::Warning;

/// A tangent component below this (of a unit tangent) does not move the
/// node along t: its DOF need not be held.
const ALONG: f64 = 1e-9;
/// A prescribed slip within this share of the motions it is the difference
/// of is 0 (round-off).
const SAME: f64 = 1e-12;
/// A projection this close (in the edge's parameter) to an end is at that
/// node: round-off of the nondimensional coordinates, not a position.
const AT_END: f64 = 1e-9;
/// Positions listed in a warning's message, at most.
const LISTED: usize = 4;

/// A frictional contact candidate whose slip the supports prescribe.
#[derive(Debug, Clone)]
pub struct Held {
    /// Its candidate (normal row).
    candidate: usize,
    pair: usize,
    x: [f64; 2],
    /// What holds it: supports (JSON pointer and body), a fixed obstacle, a
    /// punch's prescribed motion, the axis.
    by: BTreeSet<String>,
    /// The slip they prescribe (nondimensional).
    slip: f64,
    /// Without a tangential row: the supports take its friction force, which
    /// the reply's friction leaves out.
    carried: bool,
    /// A tied point: the μ from which it wedges (module docs), if any.
    wedges_from: Option<f64>,
    /// Carried, against a punch (whose reported load leaves its friction out).
    on_punch: bool,
}

/// The frictional candidates whose slip the supports prescribe, from the
/// scene and its rows alone (before the solve).
pub fn find(scene: &Scene, model: &Model, tangents: &Tangents) -> Vec<Held> {
    let holders = Holders::new(scene, &model.meshes);
    let mut found = Vec::new();
    for (k, &i) in tangents.of.iter().enumerate() {
        let c = &model.cons.candidates[i];
        let t = tangents.tangent[k];
        let Some(own) = holders.along(c.body, c.node, t) else {
            found.extend(closed(scene, model, tangents, &holders, k));
            continue;
        };
        let mut held: BTreeSet<String> = own.into_iter().collect();
        let mut slip = prescribed_along(model, c.body, c.node, t);
        // What the slip is a difference of, for its round-off.
        let mut scale = slip.abs();
        match &scene.pairs[c.pair].target {
            Target::Obstacle(o) => match (&scene.obstacles[*o].punch, c.punch_tangent()) {
                (None, _) => {
                    held.insert(format!("the fixed obstacle '{}'", scene.obstacles[*o].name));
                }
                (Some(p), Some((_, ct))) => {
                    // A load-controlled motion along the tangent leaves the slip free.
                    let Some(moved) =
                        p.controls
                            .iter()
                            .zip(ct.iter())
                            .try_fold(0.0, |m, (control, &w)| match control {
                                _ if w.abs() <= ALONG => Some(m),
                                Control::Displacement(v) => Some(m + w * v),
                                Control::Load(_) => None,
                            })
                    else {
                        continue;
                    };
                    held.insert(format!("punch '{}''s prescribed motion", scene.obstacles[*o].name));
                    slip -= moved;
                    scale += moved.abs();
                }
                (Some(_), None) => continue,
            },
            Target::Body { body, edges, .. } => {
                let Some(facing) = facing_nodes(&model.meshes[*body], edges, c.x) else {
                    continue;
                };
                let mut all = true;
                for &(n, w) in &facing {
                    match holders.along(*body, n, t) {
                        Some(h) => held.extend(h),
                        None => all = false,
                    }
                    let other = w * prescribed_along(model, *body, n, t);
                    slip -= other;
                    scale += other.abs();
                }
                if !all {
                    continue;
                }
            }
            Target::Foundation(_) => continue,
        }
        // A slip prescribed to 0 (both sides held still, a symmetry plane
        // held on both bodies) lets the point stick with a bounded force.
        if slip.abs() <= SAME * scale {
            continue;
        }
        found.push(Held {
            candidate: i,
            pair: c.pair,
            x: c.x,
            by: held,
            slip,
            carried: false,
            wedges_from: None,
            on_punch: false,
        });
    }
    found.extend(
        tangents
            .held
            .iter()
            .filter_map(|h| carried(scene, model, &holders, h.candidate, h.prescribed)),
    );
    found
}

/// A frictional candidate left without a tangential row (`Tangents::held`:
/// every DOF its slip reads is prescribed), if that slip is not 0: it
/// slides by it, and its friction force μ λ goes to the supports, outside
/// the solve and the reply's friction (the roller of the Cattaneo–Mindlin
/// example with its arc also held along x: every point slid by the
/// prescribed 0.001 and the reply read "stick", friction 0). A punch moved by
/// a load along the slip leaves it free; one moved by a prescribed motion
/// there takes their friction through the supports, which its reported load
/// leaves out (a flat punch over a top held along x, moved sideways: load 0,
/// where sliding takes μ P).
fn carried(scene: &Scene, model: &Model, holders: &Holders, i: usize, slip: f64) -> Option<Held> {
    let c = &model.cons.candidates[i];
    let mut by = holders.any(c.body, c.node);
    let mut ob_punch = false;
    match &scene.pairs[c.pair].target {
        Target::Obstacle(o) => {
            let ob = &scene.obstacles[*o];
            // A load-controlled component along which the slip moves leaves
            // it free (a flat punch's vertical load does not: its tangent is x).
            let along = c.punch_tangent().map_or([0.0; 3], |(_, ct)| ct);
            let loaded = |(k, c): (usize, &Control)| matches!(c, Control::Load(_)) && along[k].abs() > ALONG;
            match &ob.punch {
                Some(p) if p.controls.iter().enumerate().any(loaded) => return None,
                Some(_) => {
                    ob_punch = true;
                    by.insert(format!("punch '{}''s prescribed motion", ob.name))
                }
                None => by.insert(format!("the fixed obstacle '{}'", ob.name)),
            };
        }
        Target::Body { body, .. } => {
            by.insert(format!("the supports of body '{}'", scene.bodies[*body].name));
        }
        Target::Foundation(_) => return None,
    }
    // The prescribed motions the slip is a difference of (the row's
    // coefficients turned keep their length).
    let scale = c.terms.iter().fold(0.0f64, |m, t| {
        let d = |k: usize| model.dofs.prescribed[model.dofs.dof(t.body, t.node, k)];
        m + t.coef[0].hypot(t.coef[1]) * d(0).hypot(d(1))
    });
    (slip.abs() > SAME * scale).then_some(Held {
        candidate: i,
        pair: c.pair,
        x: c.x,
        by,
        slip,
        carried: true,
        wedges_from: None,
        on_punch: ob_punch,
    })
}

/// The candidate of tangential row k if its supports leave it one free
/// direction, which its normal row moves (`Tangents::tied`): closed, its
/// slip r g + the prescribed part is fixed too, whatever the tangential
/// force (a contact edge held along x against a curved obstacle, whose
/// normal has an x-component: its stick state's equations were one, and the
/// frictional iteration ran to its cap with forces of 1e20). A punch moved
/// by a load leaves the slip free.
fn closed(scene: &Scene, model: &Model, tangents: &Tangents, holders: &Holders, k: usize) -> Option<Held> {
    let r = tangents.tied(k)?;
    let i = tangents.of[k];
    let c = &model.cons.candidates[i];
    let target = match &scene.pairs[c.pair].target {
        Target::Obstacle(o) => {
            let ob = &scene.obstacles[*o];
            let loaded = ob
                .punch
                .as_ref()
                .is_some_and(|p| p.controls.iter().any(|c| matches!(c, Control::Load(_))));
            if loaded {
                return None;
            }
            format!(
                "its contact with '{}', which fixes the direction they leave free",
                ob.name
            )
        }
        Target::Body { body, .. } => format!(
            "its contact with body '{}', which fixes the direction they leave free",
            scene.bodies[*body].name
        ),
        Target::Foundation(_) => return None,
    };
    let (a, b) = (r * c.g, tangents.prescribed[k]);
    let slip = a + b;
    if slip.abs() <= SAME * (a.abs() + c.g.abs() + b.abs()) {
        return None;
    }
    let mut by = holders.any(c.body, c.node);
    by.insert(target);
    let lean = tangents.lean.get(k).copied().unwrap_or(0.0);
    Some(Held {
        candidate: i,
        pair: c.pair,
        x: c.x,
        by,
        slip,
        carried: false,
        wedges_from: (r * slip < 0.0).then(|| ((1.0 - r * lean) / r.abs()).max(0.0)),
        on_punch: false,
    })
}

/// One warning per pair with points of `held` in contact (λ > 0; a point
/// that stays open carries no friction force, as the ends of the
/// Cattaneo–Mindlin roller's arc, held by its flat's supports, 8 above the
/// floor): value the number of such points, limit 0. A step that did not
/// settle (`settled` false) also names the pair's points that wedge at its μ.
pub fn warnings(scene: &Scene, held: &[Held], lambda: &[f64], settled: bool) -> Vec<Warning> {
    let mut found: BTreeMap<usize, Group> = BTreeMap::new();
    let mut wedged: BTreeMap<usize, (Vec<[f64; 2]>, f64)> = BTreeMap::new();
    for h in held.iter().filter(|_| !settled) {
        if let Some(from) = h.wedges_from.filter(|&m| m <= scene.pairs[h.pair].friction) {
            let w = wedged.entry(h.pair).or_insert((Vec::new(), f64::INFINITY));
            w.0.push(h.x);
            w.1 = w.1.min(from);
        }
    }
    for h in held
        .iter()
        .filter(|h| lambda.get(h.candidate).is_some_and(|l| *l > 0.0))
    {
        let group = found.entry(h.pair).or_default();
        group.at.push(h.x);
        group.by.extend(h.by.iter().cloned());
        group.slip = group.slip.max(h.slip.abs());
        group.carried += usize::from(h.carried);
        group.carried_punch |= h.on_punch;
    }
    found
        .into_iter()
        .map(|(p, mut g)| {
            g.at.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
            if let Some((mut at, from)) = wedged.remove(&p) {
                at.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
                g.wedged = at;
                g.wedges_from = from;
            }
            warning(scene, p, &g)
        })
        .collect()
}

/// A pair's points in contact whose slip is prescribed.
#[derive(Default)]
struct Group {
    /// Their positions (nondimensional).
    at: Vec<[f64; 2]>,
    /// What holds them.
    by: BTreeSet<String>,
    /// The largest slip prescribed (nondimensional).
    slip: f64,
    /// How many of them have no tangential row (`Held::carried`).
    carried: usize,
    /// Some of those against a punch (`Held::on_punch`).
    carried_punch: bool,
    /// The pair's points that wedge at its μ, in a step that did not settle,
    /// and the least μ from which one does.
    wedged: Vec<[f64; 2]>,
    wedges_from: f64,
}

fn warning(scene: &Scene, p: usize, g: &Group) -> Warning {
    let (at, held, slip) = (&g.at, &g.by, g.slip);
    let pair = &scene.pairs[p];
    let length = scene.scales.length;
    let places = listed(at, length);
    let (one, held_by) = (at.len() == 1, held.iter().cloned().collect::<Vec<_>>().join(", "));
    // Points without a tangential row: their friction force goes to the
    // supports, and the reply says `prescribed` there (see `solution::friction`).
    let carried = match g.carried {
        0 => String::new(),
        n => format!(
            ". The supports take the friction force of {n} of them (no free motion along the surface there): the \
                model applies none there, so the reply gives their state as `prescribed` with the prescribed slip, \
                and neither their tangential traction nor the pair's tangential resultant holds that force{}",
            if g.carried_punch {
                ", nor the punch's reported load (sliding, they take μ λ each from it)"
            } else {
                ""
            }
        ),
    };
    let wedged = match g.wedged.len() {
        0 => String::new(),
        n => format!(
            ". This step did not settle, and at μ = {}, {n} of the points whose slip the supports and the contact fix \
                wedge ({}): sliding by that slip, their friction force pushes them into the surface at least as \
                hard as their normal force pushes them out (from μ = {} on, μ |n_x| ≥ n_y for a node free along y \
                alone), so wherever the rest presses one in it has no Coulomb answer, closed or open. No answer \
                was found; whether one exists with them lifted off is not known, and the values of this reply are \
                the iteration's last, not an answer. Below μ = {} none of them wedges",
            pair.friction,
            listed(&g.wedged, length).join(", "),
            shown(g.wedges_from),
            shown(g.wedges_from),
        ),
    };
    Warning {
        code: WarningCode::PrescribedSlip,
        value: at.len() as f64,
        limit: 0.0,
        location: pair.path.clone(),
        message: format!(
            "the frictional contact {} of body '{}' at {} {} slip along the other surface prescribed by the \
                supports ({held_by}), by up to {}: {} by it whatever μ (here {}), with the friction \
                force μ λ. At a real μ that is Coulomb's answer, but it grows with μ without bound, so a large μ is \
                not the stick limit here. Release one of the supports at {} (hold that \
                body at its other end), or move the body by its far end{carried}{wedged}",
            if one { "node" } else { "nodes" },
            scene.bodies[pair.body].name,
            places.join(", "),
            if one { "has its" } else { "have their" },
            shown(slip * length),
            if one { "it slides" } else { "they slide" },
            pair.friction,
            if one { "that node" } else { "those nodes" },
        ),
    }
}

/// Up to `LISTED` positions as the request gives them, and how many more.
fn listed(at: &[[f64; 2]], length: f64) -> Vec<String> {
    let mut places: Vec<String> = at
        .iter()
        .take(LISTED)
        .map(|x| format!("({}, {})", shown(x[0] * length), shown(x[1] * length)))
        .collect();
    if at.len() > LISTED {
        places.push(format!("and {} more", at.len() - LISTED));
    }
    places
}

/// The prescribed displacement of a node along t (nondimensional).
fn prescribed_along(model: &Model, body: usize, node: usize, t: [f64; 2]) -> f64 {
    let d = |c: usize| model.dofs.prescribed[model.dofs.dof(body, node, c)];
    t[0] * d(0) + t[1] * d(1)
}

/// The other body's nodes whose shape functions do not vanish at the
/// projection of `x` onto its edge set, with their values there.
fn facing_nodes(mesh: &Mesh2d, edges: &str, x: [f64; 2]) -> Option<Vec<(usize, f64)>> {
    let set = mesh.edge_sets.get(edges)?;
    let mut best: Option<(f64, f64, &crate::mesh::Edge)> = None;
    for e in set {
        let (a, b) = (mesh.nodes[e.a], mesh.nodes[e.b]);
        let s = crate::mesh::segment_param(x, a, b);
        let dist = (a[0] + s * (b[0] - a[0]) - x[0]).hypot(a[1] + s * (b[1] - a[1]) - x[1]);
        if best.is_none_or(|(bd, _, _)| dist < bd) {
            best = Some((dist, s, e));
        }
    }
    let (_, s, e) = best?;
    let s = if s < AT_END {
        0.0
    } else if s > 1.0 - AT_END {
        1.0
    } else {
        s
    };
    let values = match e.mid {
        None => vec![(e.a, 1.0 - s), (e.b, s)],
        Some(m) => vec![
            (e.a, (1.0 - s) * (1.0 - 2.0 * s)),
            (m, 4.0 * s * (1.0 - s)),
            (e.b, s * (2.0 * s - 1.0)),
        ],
    };
    Some(values.into_iter().filter(|(_, w)| *w != 0.0).collect())
}

/// Which support holds each node's components: the request's supports (by
/// JSON pointer) and, in axisymmetry, the axis (u_r = 0); the virtual
/// supports that fix a free body's rigid motions are not supports. Not read
/// from `DofMap`: it knows which DOFs are fixed, not by which support (the
/// warning names it), and it fixes the virtual supports too.
struct Holders(HashMap<(usize, usize, usize), String>);

impl Holders {
    fn new(scene: &Scene, meshes: &[Mesh2d]) -> Self {
        let mut held = HashMap::new();
        for (b, (body, mesh)) in scene.bodies.iter().zip(meshes).enumerate() {
            for (k, s) in body.supports.iter().enumerate() {
                for node in mesh.edge_set_nodes(&s.edges) {
                    for (c, v) in [(0, s.ux), (1, s.uy)] {
                        if v.is_some() {
                            held.entry((b, node, c))
                                .or_insert_with(|| format!("{}/supports/{k} of '{}'", body.path, body.name));
                        }
                    }
                }
            }
            if scene.analysis == Analysis::Axisymmetric {
                let tol = mesh.axis_tolerance();
                for (node, p) in mesh.nodes.iter().enumerate() {
                    if p[0] <= tol {
                        held.entry((b, node, 0)).or_insert_with(|| "the axis".to_string());
                    }
                }
            }
        }
        Holders(held)
    }

    /// The supports holding any of the node's components.
    fn any(&self, body: usize, node: usize) -> BTreeSet<String> {
        (0..2).filter_map(|c| self.0.get(&(body, node, c)).cloned()).collect()
    }

    /// The supports holding the node's motion along t, or None if some
    /// component moving it along t is free.
    fn along(&self, body: usize, node: usize, t: [f64; 2]) -> Option<Vec<String>> {
        (0..2)
            .filter(|&c| t[c].abs() > ALONG)
            .map(|c| self.0.get(&(body, node, c)).cloned())
            .collect()
    }
}
