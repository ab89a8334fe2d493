//! How well each reply's error estimate (`pairs[].accuracy`) matches its true
//! error, on the convergence suite's kinds of scene: the disk and the ball on
//! a flat, a rigid cylinder into a block, the flat punch of revolution, two
//! elastic cylinders, a footing on Winkler springs and a flat punch under an
//! eccentric load (a moment).
//!
//! Each scene is solved at three levels (the generated meshes' `h_min` and
//! `size` 8, 4 and 2 times the scene's own, the size at most a quarter of the
//! body), T3
//! and T6 (T6 elements twice as long: the same node spacing), and compared
//! with its own overkill: T6 with every element half the scene's own (4×
//! finer than the finest level), or, for the disk, the ball and the block,
//! with their stored overkill tables (`overkill`). The true error is the
//! nodal relative L2 error of the first pair's pressure at the level's
//! candidates (the reference interpolated along the surface), outside the
//! bands the reply's estimate leaves out around an unbounded pressure
//! (`contact_core::solution::corners`), and each zone end's distance to the
//! reference's edge.

use contact_core::scene::Limits;
use contact_core::solution::accuracy::{along_polyline, described, described_at, described_l2, field};
use contact_core::solution::corners::in_band;
use contact_core::solution::report::Report;
use serde_json::{json, Value};

/// Level factors on the scene's element sizes, coarse to fine, and the
/// reference's.
pub const LEVELS: [f64; 3] = [8.0, 4.0, 2.0];
pub const REFERENCE: f64 = 0.5;

/// A scene: its name and its request at the scene's own element sizes.
pub struct Scene {
    pub name: &'static str,
    pub request: fn() -> Value,
}

fn example(name: &str) -> Value {
    let path = format!("{}/../../proto/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("example JSON")
}

pub const SCENES: [Scene; 9] = [
    Scene {
        name: "disk_on_flat",
        request: || crate::convergence::disk_request(0.0011, "t3"),
    },
    Scene {
        name: "ball_on_flat",
        request: || crate::convergence::ball_request(0.0011, "t3"),
    },
    Scene {
        name: "hertz_block",
        request: || crate::bench::hertz_request(0.02, "t3", "auto"),
    },
    Scene {
        name: "punch_of_revolution",
        request: || example("axisymmetric_flat_punch.json"),
    },
    Scene {
        name: "two_cylinders",
        request: || example("two_bodies_cylinders.json"),
    },
    Scene {
        name: "winkler_footing",
        request: || {
            // Loaded off centre (4 on x in [0.4, 1] of the width [−1, 1], a
            // softer footing): it lifts off the tensionless springs near
            // x = 0.11. Centred, the example's pressure is uniform and exact.
            let mut req = example("foundation_winkler_footing.json");
            req["bodies"][0]["tractions"] = json!([{"edges": "top", "pressure": 4.0, "x_range": [0.4, 1.0]}]);
            req["bodies"][0]["material"]["youngs_modulus"] = json!(200.0);
            req
        },
    },
    // The disk and the block given inline, as a user's own mesher would send
    // them (`run::inlined` at each level): their estimate's companion is the
    // mesh bisected twice over, and their errors are read against the
    // generated scenes' overkill tables (`table_of`).
    Scene {
        name: "disk_on_flat_inline",
        request: || crate::convergence::disk_request(0.0011, "t3"),
    },
    Scene {
        name: "hertz_block_inline",
        request: || crate::bench::hertz_request(0.02, "t3", "auto"),
    },
    Scene {
        name: "punch_under_moment",
        request: || {
            let mut req = example("indentation_flat_punch.json");
            // M = 2 with P2 = −10: eccentric by 0.2 of the half-width 1.
            req["obstacles"][0]["punch"]["rotation"] = json!({ "load": 2.0 });
            req
        },
    },
];

/// The request with every generated mesh's `h_min` and `size` `factor` times
/// as large (T6: twice that, the same node spacing as T3) and of order
/// `element`.
pub fn scaled(req: &Value, factor: f64, element: &str) -> Value {
    let mut req = req.clone();
    let f = factor * if element == "t6" { 2.0 } else { 1.0 };
    if let Some(bodies) = req["bodies"].as_array_mut() {
        for b in bodies {
            for kind in ["rectangle", "half_disk", "quarter_disk"] {
                // (Indexing a missing key would insert it.)
                let Some(m) = b["mesh"].get_mut(kind) else { continue };
                {
                    // The far field no coarser than a quarter of the body (the
                    // generators refuse a size past a disk's radius).
                    let extent = m["radius"]
                        .as_f64()
                        .or_else(|| Some(m["width"].as_f64()?.min(m["height"].as_f64()?)))
                        .unwrap_or(f64::INFINITY);
                    let size = m["size"].as_f64().unwrap_or(1.0);
                    m["size"] = json!((size * f).min((0.25 * extent).max(size)));
                    m["element"] = json!(element);
                    // The grading's ratio stays: scaled by 8 it would reach 1.8
                    // and the estimate's coarser companion would clamp at 2.
                    if let Some(g) = m.get_mut("grading") {
                        g["h_min"] = json!(g["h_min"].as_f64().unwrap_or(1.0) * f);
                    }
                }
            }
        }
    }
    req
}

#[derive(Debug, Clone)]
pub struct Row {
    pub scene: &'static str,
    pub element: &'static str,
    pub factor: f64,
    pub dofs: usize,
    pub err_l2: f64,
    pub est_l2: Option<f64>,
    /// Largest measurable true error of a zone end, and its estimate.
    pub err_edge: Option<f64>,
    pub est_edge: f64,
    pub err_resultant: f64,
    pub est_resultant: Option<f64>,
    /// Relative error of the largest nodal pressure (outside the singular
    /// bands) against the reference's peak, and its estimate.
    pub err_peak: f64,
    pub est_peak: Option<f64>,
    /// Seconds of the estimate over seconds of the solve.
    pub cost: f64,
    /// Relative L2 error along the surface of the described field (the
    /// square-root facets to the fitted edges included,
    /// `accuracy::described`): what `est_l2` bounds.
    pub err_curve: f64,
    /// The outermost fitted edge's true error and its estimate.
    pub err_fit: Option<f64>,
    pub est_fit: Option<f64>,
}

impl Row {
    pub const HEADER: &'static str =
        "scene,element,factor,dofs,err_l2,est_l2,eff_l2,err_edge,est_edge,eff_edge,err_resultant,est_resultant,\
            eff_resultant,err_peak,est_peak,eff_peak,cost,err_curve,eff_curve,err_fit,est_fit,eff_fit";

    fn eff(est: Option<f64>, err: f64) -> Option<f64> {
        est.filter(|_| err > 0.0).map(|e| e / err)
    }
    pub fn eff_l2(&self) -> Option<f64> {
        Self::eff(self.est_l2, self.err_l2)
    }
    pub fn eff_edge(&self) -> Option<f64> {
        self.err_edge.and_then(|e| Self::eff(Some(self.est_edge), e))
    }
    pub fn eff_resultant(&self) -> Option<f64> {
        Self::eff(self.est_resultant, self.err_resultant)
    }
    pub fn eff_peak(&self) -> Option<f64> {
        Self::eff(self.est_peak, self.err_peak)
    }
    pub fn eff_curve(&self) -> Option<f64> {
        Self::eff(self.est_l2, self.err_curve)
    }
    pub fn eff_fit(&self) -> Option<f64> {
        self.err_fit.and_then(|e| Self::eff(self.est_fit, e))
    }

    pub fn csv(&self) -> String {
        let o = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.6e}"));
        format!(
            "{},{},{},{},{:.6e},{},{},{},{:.6e},{},{:.6e},{},{},{:.6e},{},{},{:.4},{:.6e},{},{},{},{}",
            self.scene,
            self.element,
            self.factor,
            self.dofs,
            self.err_l2,
            o(self.est_l2),
            o(self.eff_l2()),
            o(self.err_edge),
            self.est_edge,
            o(self.eff_edge()),
            self.err_resultant,
            o(self.est_resultant),
            o(self.eff_resultant()),
            self.err_peak,
            o(self.est_peak),
            o(self.eff_peak()),
            self.cost,
            self.err_curve,
            o(self.eff_curve()),
            o(self.err_fit),
            o(self.est_fit),
            o(self.eff_fit()),
        )
    }

    pub fn table_header() -> String {
        format!(
            "{:<20} {:<3} {:>4} {:>8} {:>8} {:>8} {:>6} {:>9} {:>9} {:>6} {:>8} {:>8} \
                {:>6} {:>8} {:>8} {:>6} {:>5} {:>8} {:>6} {:>9} {:>9} {:>6}",
            "scene",
            "el",
            "f",
            "dofs",
            "err_l2",
            "est_l2",
            "eff",
            "err_edge",
            "est_edge",
            "eff",
            "err_res",
            "est_res",
            "eff",
            "err_peak",
            "est_peak",
            "eff",
            "cost",
            "err_crv",
            "eff",
            "err_fit",
            "est_fit",
            "eff"
        )
    }

    pub fn table_line(&self) -> String {
        let pct = |v: Option<f64>| v.map_or("-".into(), |v| format!("{:.3}%", 100.0 * v));
        let e = |v: Option<f64>| v.map_or("-".into(), |v| format!("{v:.2}"));
        format!(
            "{:<20} {:<3} {:>4} {:>8} {:>8} {:>8} {:>6} {:>9} {:>9.2e} {:>6} {:>8} {:>8} \
                {:>6} {:>8} {:>8} {:>6} {:>5.2} {:>8} {:>6} {:>9} {:>9} {:>6}",
            self.scene,
            self.element,
            self.factor,
            self.dofs,
            pct(Some(self.err_l2)),
            pct(self.est_l2),
            e(self.eff_l2()),
            self.err_edge.map_or("-".into(), |v| format!("{v:.2e}")),
            self.est_edge,
            e(self.eff_edge()),
            pct(Some(self.err_resultant)),
            pct(self.est_resultant),
            e(self.eff_resultant()),
            pct(Some(self.err_peak)),
            pct(self.est_peak),
            e(self.eff_peak()),
            self.cost,
            pct(Some(self.err_curve)),
            e(self.eff_curve()),
            self.err_fit.map_or("-".into(), |v| format!("{v:.2e}")),
            self.est_fit.map_or("-".into(), |v| format!("{v:.2e}")),
            e(self.eff_fit()),
        )
    }
}

fn solve(req: &Value) -> Report {
    match crate::run::solve(req, &Limits::default()) {
        Ok(r) => r,
        Err(e) => panic!("effectivity scene rejected: {e:?}"),
    }
}

/// The row of a level's reply against the stored overkill table of `scene`
/// where there is one (`overkill`), else against `reference` (the same scene
/// solved 4× finer). A zone end's true error against a solved reference is
/// only known to the reference's own end uncertainty (its end is a node): an
/// end within twice that of the reference's is not measured (`None`).
pub fn compare(scene: &'static str, element: &'static str, factor: f64, r: &Report, reference: Option<&Report>) -> Row {
    let p = &r.pairs[0];
    let acc = p.accuracy.as_ref();
    // The estimate of the zone end at the larger x (the overkill scenes are
    // symmetric halves or wholes with the zone about x = 0).
    let outer = p
        .zones_along
        .iter()
        .flat_map(|z| [(z.start[0], z.uncertainty[0]), (z.end[0], z.uncertainty[1])])
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let singular = acc.map_or(&[][..], |a| &a.singular_ends[..]);
    let top = |pts: &[contact_core::solution::report::ContactPoint],
               singular: &[contact_core::solution::report::SingularEnd]| {
        pts.iter()
            .filter(|c| !in_band(singular, c.x, c.y))
            .map(|c| c.pressure)
            .fold(0.0, f64::max)
    };
    let err_peak = match (crate::overkill::reference(table_of(scene)), reference) {
        (Some(t), _) => (top(&p.points, singular) / t.pressure(0.0) - 1.0).abs(),
        (None, Some(q)) => (top(&p.points, singular) / top(&q.pairs[0].points, singular) - 1.0).abs(),
        (None, None) => f64::NAN,
    };
    let (err_l2, err_edge, est_edge, err_resultant) = match crate::overkill::reference_error(table_of(scene), r) {
        Some(e) => (e.l2, Some(e.edge.abs()), outer.map_or(0.0, |o| o.1), e.resultant.abs()),
        None => {
            let q = &reference.expect("a solved reference where no table is stored").pairs[0];
            let rf = field(q);
            let (mut num, mut den) = (0.0, 0.0);
            // Not within the bands the estimate leaves out around an
            // unbounded pressure (`corners`), where the L2 error has no limit.
            for c in p.points.iter().filter(|c| !in_band(singular, c.x, c.y)) {
                let pr = along_polyline(&rf, c.x, c.y);
                num += c.weight * (c.pressure - pr).powi(2);
                den += c.weight * pr.powi(2);
            }
            let ref_ends: Vec<([f64; 2], f64)> = q
                .zones_along
                .iter()
                .flat_map(|z| [(z.start, z.uncertainty[0]), (z.end, z.uncertainty[1])])
                .collect();
            // The end farthest from the reference's, if measurable.
            let mut worst: Option<(f64, f64)> = None;
            for z in &p.zones_along {
                for (end, u) in [(z.start, z.uncertainty[0]), (z.end, z.uncertainty[1])] {
                    let nearest = ref_ends
                        .iter()
                        .map(|(e, ue)| ((e[0] - end[0]).hypot(e[1] - end[1]), *ue))
                        .min_by(|a, b| a.0.total_cmp(&b.0));
                    if let Some((d, _)) = nearest.filter(|(d, ue)| *d > 2.0 * ue) {
                        if worst.is_none_or(|w| d > w.0) {
                            worst = Some((d, u));
                        }
                    }
                }
            }
            let norm = |r: &contact_core::solution::report::Resultant| r.fx.hypot(r.fy);
            let dr = (p.resultant.fx - q.resultant.fx).hypot(p.resultant.fy - q.resultant.fy);
            (
                if den > 0.0 { (num / den).sqrt() } else { 0.0 },
                worst.map(|w| w.0),
                worst.map_or(0.0, |w| w.1),
                if norm(&q.resultant) > 0.0 {
                    dr / norm(&q.resultant)
                } else {
                    0.0
                },
            )
        }
    };
    // The described field against the reference's (the table's continuous
    // profile, or the solved reference's own described field), and the
    // outermost fitted edge against the reference's edge.
    let counted = |x: f64, y: f64| !in_band(singular, x, y);
    let fitted_outer = p
        .zones_along
        .iter()
        .enumerate()
        .flat_map(|(i, z)| {
            [0, 1].map(|k| {
                let est = acc.and_then(|a| a.fitted_edges.get(i).and_then(|e| e[k]));
                z.fitted[k].map(|f| (f.at, est))
            })
        })
        .flatten()
        .max_by(|a, b| a.0[0].total_cmp(&b.0[0]));
    let (err_curve, err_fit) = match crate::overkill::reference(table_of(scene)) {
        Some(t) => {
            let (num, _, den) = described_l2(p, &|x, _| t.pressure(x), &counted);
            let fit = fitted_outer.map(|(at, _)| (at[0].abs() - t.edge).abs());
            (if den > 0.0 { (num / den).sqrt() } else { 0.0 }, fit)
        }
        None => {
            let q = &reference.expect("a solved reference where no table is stored").pairs[0];
            let (pts, reach) = described(q);
            let (num, _, den) = described_l2(p, &|x, y| described_at(&pts, &reach, x, y), &counted);
            let ends: Vec<([f64; 2], f64)> = q
                .zones_along
                .iter()
                .flat_map(|z| [0, 1].map(|k| z.fitted[k].map(|f| (f.at, z.uncertainty[k]))))
                .flatten()
                .collect();
            // Measurable where it is well past the reference's own scatter
            // (a quarter of its end's uncertainty, itself ≥ a quarter of
            // its spacing).
            let fit = fitted_outer.and_then(|(at, _)| {
                ends.iter()
                    .map(|(e, u)| ((e[0] - at[0]).hypot(e[1] - at[1]), *u))
                    .min_by(|a, b| a.0.total_cmp(&b.0))
                    .filter(|(d, u)| *d > 0.25 * u)
                    .map(|(d, _)| d)
            });
            (if den > 0.0 { (num / den).sqrt() } else { 0.0 }, fit)
        }
    };
    Row {
        err_curve,
        err_fit,
        est_fit: fitted_outer.and_then(|f| f.1),
        scene,
        element,
        factor,
        dofs: r.size.dofs,
        err_l2,
        est_l2: acc.and_then(|a| a.pressure_l2),
        err_edge,
        est_edge,
        err_resultant,
        est_resultant: acc.and_then(|a| a.resultant),
        err_peak,
        est_peak: acc.and_then(|a| a.peak),
        cost: r.timings.estimate / (r.timings.total - r.timings.estimate).max(1e-12),
    }
}

/// A scene's request at a level: `scaled`, then given inline where the
/// scene's name says so.
pub fn level(sc: &Scene, base: &Value, factor: f64, element: &str) -> Value {
    let req = scaled(base, factor, element);
    if sc.name.ends_with("_inline") {
        crate::run::inlined(&req)
    } else {
        req
    }
}

/// The overkill table a scene is measured against: its own, or that of the
/// generated scene it gives inline (`_inline`) or through Gmsh (`_gmsh`).
pub fn table_of(scene: &str) -> &str {
    scene
        .strip_suffix("_inline")
        .or_else(|| scene.strip_suffix("_gmsh"))
        .unwrap_or(scene)
}

/// Every scene (or those named in `only`), T3 and T6, at every level.
pub fn run(only: &[&str], mut progress: impl FnMut(&Row)) -> Vec<Row> {
    let mut rows = Vec::new();
    for sc in SCENES.iter().filter(|s| only.is_empty() || only.contains(&s.name)) {
        let base = (sc.request)();
        let reference = crate::overkill::reference(table_of(sc.name)).is_none().then(|| {
            let mut req = scaled(&base, REFERENCE, "t6");
            req["settings"]["estimate"] = json!(false);
            solve(&req)
        });
        for element in ["t3", "t6"] {
            for factor in LEVELS {
                let r = solve(&level(sc, &base, factor, element));
                let row = compare(
                    sc.name,
                    if element == "t3" { "T3" } else { "T6" },
                    factor,
                    &r,
                    reference.as_ref(),
                );
                progress(&row);
                rows.push(row);
            }
        }
    }
    rows
}
