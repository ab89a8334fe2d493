//! Overkill references: the convergence scenes solved far below their finest
//! level, stored as compact tables (`data/*.csv`), so that the convergence
//! suite measures errors below Hertz's model floor (a finite disk differs from
//! the half-plane formula by about 0.28 % in L2).
//!
//! A table holds the pressure at the overkill solution's surface nodes
//! (corners and midsides: T6 carries a multiplier on each) across
//! the zone up to `fit_from` (95 % of the zone), and beyond it the fit
//! p² = c0 + c1 x + c2 x² over the nodes of the zone's outer 5–20 %, whose
//! falling root is the zone's `edge`. Near a smooth edge p falls like a square
//! root, so p² is linear in the distance to the edge (exactly quadratic in x
//! for Hertz): the fit places the edge between nodes, where the nodal values
//! of the last few nodes depend on where the edge happens to fall (measured
//! at h_min = 0.0001375 R, each table's header: the nodes past fit_from off
//! the fit by up to 1.3e-3 p0 on the disk, 1.0e-3 on the ball, 4.9e-3 on the
//! block). The window stops short of those and starts where p² still
//! follows a quadratic (on the ball, with the corner-only multipliers of an
//! earlier table, a window at 60–80 % moved the edge by 5e-6 R, one at
//! 70–90 % left the nodes at 95 % 6e-5 p0 off). Inside, p² is interpolated by the cubic through the four nearest
//! stations.
//!
//! Measured uncertainty (each table's header: two levels, two far-field sizes,
//! two fit windows): disk 1.4e-5 in L2, 8.2e-7 in fy, 2.6e-7 R at the edge;
//! ball 1.7e-4, 8.3e-7, 2.3e-6 R; block (h_min 0.0025, far field 0.5, 1.4M
//! DOF) 3.3e-4, 1.0e-5, 8.9e-5 (1.2e-4 a). The L2 of the ball and the block
//! comes mostly from moving the fit's window inward, where p² departs from a
//! quadratic by the finite body's O(a/R) terms.
//! The ball's axis node reads 3e-6 below its neighbour (a local dip at
//! r = 0 whose ring weight is nil; left as computed).
//!
//! Tables are made by `cargo run --release -p contact-verify --example
//! overkill` (see that file), which states in each table's header how it was
//! made and its own measured uncertainty: the same evaluation from a solve
//! with h_min twice as large, one with the far-field size also doubled, and
//! the fit over two other windows.

use std::sync::OnceLock;

use contact_core::solution::accuracy::fit_quadratic;
use contact_core::solution::report::Report;

/// An overkill reference of one scene.
#[derive(Debug, Clone)]
pub struct Reference {
    pub scene: String,
    /// `#` lines of the table: how it was made.
    pub header: Vec<String>,
    /// Weights are ring areas (a body of revolution): the L2 measure is 2πx dx.
    pub axisymmetric: bool,
    /// Stations (surface nodes of the overkill mesh) up to `fit_from`.
    pub x: Vec<f64>,
    pub p: Vec<f64>,
    /// Past this x the pressure is sqrt(c0 + c1 x + c2 x²).
    pub fit_from: f64,
    pub fit: [f64; 3],
    /// The falling root of the fit: the zone's outer end.
    pub edge: f64,
    /// The model's resultant fy (as the scenes report it: on the modelled
    /// part, per unit thickness or over the circumference).
    pub fy: f64,
    /// Measured uncertainties (see the header): relative L2 of the pressure,
    /// relative resultant, and the edge (length).
    pub uncertainty_l2: f64,
    pub uncertainty_fy: f64,
    pub uncertainty_edge: f64,
}

/// Errors of a reply against an overkill reference.
#[derive(Debug, Clone, Copy)]
pub struct RefErrors {
    /// Nodal L2: sqrt(Σ w_i (p_i − p_ref(x_i))² / Σ w_i p_ref(x_i)²).
    pub l2: f64,
    /// (fy − fy_ref) / fy_ref, at the same prescribed approach.
    pub resultant: f64,
    /// The reply's zone end (its last node in contact at the larger x) minus
    /// the reference's edge.
    pub edge: f64,
}

/// Fraction of the zone past which the fit replaces the nodal values
/// (the last few nodes' values depend on where the edge falls between them).
pub const FIT_FROM: f64 = 0.95;
/// The fit's window starts at this fraction of the zone.
pub const FIT_WINDOW_START: f64 = 0.8;

impl Reference {
    /// The reference pressure at x (≥ 0; the scenes are symmetric about x = 0).
    pub fn pressure(&self, x: f64) -> f64 {
        let x = x.abs();
        if x > self.fit_from {
            return fit_pressure(self.fit, x);
        }
        // Cubic through the four nearest stations, on p² (smooth across the
        // zone: exactly quadratic for Hertz).
        let n = self.x.len();
        let i = self.x.partition_point(|&s| s <= x).clamp(2, n - 2);
        let (lo, hi) = (i - 2, i + 2);
        let mut y = 0.0;
        for j in lo..hi {
            let mut l = 1.0;
            for k in lo..hi {
                if k != j {
                    l *= (x - self.x[k]) / (self.x[j] - self.x[k]);
                }
            }
            y += l * self.p[j] * self.p[j];
        }
        y.max(0.0).sqrt()
    }

    /// The table from a solved overkill reply (pair 0, the zone starting at
    /// x = 0); None if the zone has too few nodes for the fit.
    pub fn from_report(scene: &str, r: &Report, header: Vec<String>) -> Option<Self> {
        Self::from_report_window(scene, r, header, FIT_WINDOW_START, FIT_FROM)
    }

    /// `from_report` with the fit over the nodes in `lo`–`hi` of the zone and
    /// the fit used past `hi`.
    pub fn from_report_window(scene: &str, r: &Report, header: Vec<String>, lo: f64, hi: f64) -> Option<Self> {
        let mut pts: Vec<(f64, f64)> = r.pairs[0]
            .points
            .iter()
            .filter(|q| q.x >= 0.0)
            .map(|q| (q.x, q.pressure))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let end = pts.iter().filter(|q| q.1 > 0.0).map(|q| q.0).fold(0.0, f64::max);
        let window: Vec<(f64, f64)> = pts
            .iter()
            .filter(|q| q.1 > 0.0 && q.0 >= lo * end && q.0 <= hi * end)
            .map(|&(x, p)| (x, p * p))
            .collect();
        if window.len() < 4 {
            return None;
        }
        let fit = fit_quadratic(&window)?;
        let edge = falling_root(fit, end)?;
        let stations: Vec<(f64, f64)> = pts.iter().copied().filter(|q| q.0 <= hi * end).collect();
        Some(Reference {
            scene: scene.to_string(),
            header,
            axisymmetric: r.axisymmetric,
            fit_from: stations.last()?.0,
            x: stations.iter().map(|q| q.0).collect(),
            p: stations.iter().map(|q| q.1).collect(),
            fit,
            edge,
            fy: r.resultant.fy,
            uncertainty_l2: f64::NAN,
            uncertainty_fy: f64::NAN,
            uncertainty_edge: f64::NAN,
        })
    }

    /// The relative L2 difference of two references' pressures over [0, max
    /// edge] (measure dx, or 2πx dx for a body of revolution), integrated on a
    /// fine grid, relative to `self`.
    pub fn l2_difference(&self, other: &Reference) -> f64 {
        const N: usize = 20_000;
        let end = self.edge.max(other.edge);
        let (mut num, mut den) = (0.0, 0.0);
        for k in 0..N {
            let x = end * (k as f64 + 0.5) / N as f64;
            let w = if self.axisymmetric { x } else { 1.0 };
            let p = self.pressure(x);
            num += w * (p - other.pressure(x)).powi(2);
            den += w * p * p;
        }
        (num / den).sqrt()
    }

    /// The CSV table: `#` header lines, `key,value` rows, then `x,pressure`.
    pub fn to_csv(&self) -> String {
        let mut s = String::new();
        for h in &self.header {
            s.push_str("# ");
            s.push_str(h);
            s.push('\n');
        }
        let kv = |s: &mut String, k: &str, v: f64| s.push_str(&format!("{k},{v:.10e}\n"));
        s.push_str(&format!("scene,{}\n", self.scene));
        s.push_str(&format!("axisymmetric,{}\n", self.axisymmetric));
        kv(&mut s, "fy", self.fy);
        kv(&mut s, "edge", self.edge);
        kv(&mut s, "fit_from", self.fit_from);
        kv(&mut s, "fit_c0", self.fit[0]);
        kv(&mut s, "fit_c1", self.fit[1]);
        kv(&mut s, "fit_c2", self.fit[2]);
        kv(&mut s, "uncertainty_l2", self.uncertainty_l2);
        kv(&mut s, "uncertainty_fy", self.uncertainty_fy);
        kv(&mut s, "uncertainty_edge", self.uncertainty_edge);
        s.push_str("x,pressure\n");
        for (x, p) in self.x.iter().zip(&self.p) {
            s.push_str(&format!("{x:.8e},{p:.9e}\n"));
        }
        s
    }

    pub fn parse(text: &str) -> Result<Self, String> {
        let mut r = Reference {
            scene: String::new(),
            header: Vec::new(),
            axisymmetric: false,
            x: Vec::new(),
            p: Vec::new(),
            fit_from: f64::NAN,
            fit: [f64::NAN; 3],
            edge: f64::NAN,
            fy: f64::NAN,
            uncertainty_l2: f64::NAN,
            uncertainty_fy: f64::NAN,
            uncertainty_edge: f64::NAN,
        };
        let mut table = false;
        for (n, line) in text.lines().enumerate() {
            let bad = |what: &str| format!("line {}: {what}: {line}", n + 1);
            if let Some(h) = line.strip_prefix('#') {
                r.header.push(h.trim().to_string());
                continue;
            }
            if line.trim().is_empty() {
                continue;
            }
            let (k, v) = line.split_once(',').ok_or_else(|| bad("no comma"))?;
            if table {
                let num = |s: &str| s.trim().parse::<f64>().map_err(|_| bad("not a number"));
                r.x.push(num(k)?);
                r.p.push(num(v)?);
                continue;
            }
            let num = || v.trim().parse::<f64>().map_err(|_| bad("not a number"));
            match k {
                "scene" => r.scene = v.to_string(),
                "axisymmetric" => r.axisymmetric = v.trim() == "true",
                "fy" => r.fy = num()?,
                "edge" => r.edge = num()?,
                "fit_from" => r.fit_from = num()?,
                "fit_c0" => r.fit[0] = num()?,
                "fit_c1" => r.fit[1] = num()?,
                "fit_c2" => r.fit[2] = num()?,
                "uncertainty_l2" => r.uncertainty_l2 = num()?,
                "uncertainty_fy" => r.uncertainty_fy = num()?,
                "uncertainty_edge" => r.uncertainty_edge = num()?,
                "x" => table = true,
                _ => return Err(bad("unknown key")),
            }
        }
        let finite = [r.fy, r.edge, r.fit_from, r.fit[0], r.fit[1], r.fit[2]];
        if r.x.len() < 4 || finite.iter().any(|v| !v.is_finite()) || r.x.windows(2).any(|w| w[1] <= w[0]) {
            return Err("incomplete table (fewer than 4 stations, a missing key or unsorted x)".into());
        }
        Ok(r)
    }
}

/// Errors of a reply against a reference, at the reply's own nodes.
pub fn errors(reference: &Reference, r: &Report) -> RefErrors {
    let (mut num, mut den) = (0.0, 0.0);
    let mut end = 0.0f64;
    for q in &r.pairs[0].points {
        let pr = reference.pressure(q.x);
        num += q.weight * (q.pressure - pr).powi(2);
        den += q.weight * pr * pr;
        if q.pressure > 0.0 {
            end = end.max(q.x);
        }
    }
    RefErrors {
        l2: (num / den).sqrt(),
        resultant: r.resultant.fy / reference.fy - 1.0,
        edge: end - reference.edge,
    }
}

/// The convergence scenes with a stored reference.
pub const SCENES: [&str; 3] = ["disk_on_flat", "ball_on_flat", "hertz_block"];

/// The stored reference of a convergence scene, if it has one.
pub fn reference(scene: &str) -> Option<&'static Reference> {
    static DISK: OnceLock<Reference> = OnceLock::new();
    static BALL: OnceLock<Reference> = OnceLock::new();
    static BLOCK: OnceLock<Reference> = OnceLock::new();
    let (cell, text) = match scene {
        "disk_on_flat" => (&DISK, include_str!("../data/disk_on_flat.csv")),
        "ball_on_flat" => (&BALL, include_str!("../data/ball_on_flat.csv")),
        "hertz_block" => (&BLOCK, include_str!("../data/hertz_block.csv")),
        _ => return None,
    };
    Some(cell.get_or_init(|| {
        Reference::parse(text).unwrap_or_else(|e| panic!("stored reference {scene} does not parse: {e}"))
    }))
}

/// Errors of a reply of the convergence scene `scene` against its overkill
/// reference, where it has one. The reply must be of the same scene (the same
/// prescribed approach): the references are displacement-controlled.
pub fn reference_error(scene: &str, r: &Report) -> Option<RefErrors> {
    reference(scene).map(|reference| errors(reference, r))
}

/// One line per stored reference: what it is and its own uncertainty (the
/// convergence bench prints them under its table: `ref_*` values near these
/// measure the reference, not the level).
pub fn summary() -> Vec<String> {
    SCENES
        .into_iter()
        .filter_map(|scene| reference(scene).map(|r| (scene, r)))
        .map(|(scene, r)| {
            let made = r.header.iter().find_map(|h| h.strip_prefix("Solve: ")).unwrap_or("");
            format!(
                "overkill reference of {scene}: uncertainty {:.1e} in L2, {:.1e} in fy, {:.1e} at the edge ({made})",
                r.uncertainty_l2, r.uncertainty_fy, r.uncertainty_edge
            )
        })
        .collect()
}

fn fit_pressure(c: [f64; 3], x: f64) -> f64 {
    (c[0] + c[1] * x + c[2] * x * x).max(0.0).sqrt()
}

/// The root of c0 + c1 x + c2 x² where it falls through zero, nearest `near`.
fn falling_root(c: [f64; 3], near: f64) -> Option<f64> {
    let [c0, c1, c2] = c;
    let roots = if c2.abs() <= 1e-14 * (c1.abs() * near + c0.abs()) / (near * near) {
        vec![-c0 / c1]
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return None;
        }
        let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
        vec![q / c2, c0 / q]
    };
    roots
        .into_iter()
        .filter(|&x| c1 + 2.0 * c2 * x < 0.0)
        .min_by(|a, b| (a - near).abs().total_cmp(&(b - near).abs()))
}
