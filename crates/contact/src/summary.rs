//! `contact solve --summary`: the reply as a short table a person reads
//! (status, method, sizes, loads, zones, peak pressures, certificate, times)
//! instead of the full JSON.

use std::fmt::Write;

use contact_proto::{ErrorReply, SolveReply, SolveStatus};

/// Six significant digits, no trailing noise.
fn num(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e6).contains(&v.abs()) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{v:.5e}")
    }
}

/// ` name` of a unit the request named, else nothing: the numbers are in
/// the request's units either way, and a name read beside them saves a
/// reader from looking the request up.
fn unit(name: Option<&String>) -> String {
    name.map_or(String::new(), |n| format!(" {n}"))
}

pub fn reply(r: &SolveReply) -> String {
    let mut o = String::new();
    let units = r.units.as_ref();
    let length = unit(units.and_then(|u| u.length.as_ref()));
    let force = unit(units.and_then(|u| u.force.as_ref()));
    let stress = unit(units.and_then(|u| u.stress.as_ref()));
    // A moment is a force times a length; named only when both are.
    let moment = match units.map(|u| (&u.force, &u.length)) {
        Some((Some(f), Some(l))) => format!(" {f}·{l}"),
        _ => String::new(),
    };
    let status = match r.status {
        SolveStatus::Solved => "solved",
        SolveStatus::MaxIterations => "NOT SOLVED: iteration cap reached (see the certificate)",
        SolveStatus::NumericalError => "NOT SOLVED: numerical error (do not use the numbers)",
    };
    let _ = writeln!(o, "status       {status}");
    let _ = writeln!(o, "method       {} ({} iterations)", r.method, r.iterations);
    let _ = writeln!(
        o,
        "size         {} DOFs, {} contact rows, {} in contact",
        r.size.dofs, r.size.candidates, r.size.active
    );
    let _ = writeln!(
        o,
        "contact load fx {}{force}, fy {}{force}, m {}{moment} (on the bodies, moment about the origin)",
        num(r.resultant.fx),
        num(r.resultant.fy),
        num(r.resultant.m)
    );
    if let Some(s) = &r.solid {
        solid(&mut o, s, [&length, &force, &stress, &moment]);
    }
    for (k, p) in r.pairs.iter().enumerate() {
        let target = p
            .obstacle
            .as_ref()
            .map(|o| format!("obstacle '{o}'"))
            .or_else(|| p.against.as_ref().map(|a| format!("body '{a}'")))
            .or_else(|| p.foundation.as_ref().map(|f| format!("foundation '{f}'")))
            .unwrap_or_default();
        let peak = p.points.iter().max_by(|a, b| a.pressure.total_cmp(&b.pressure));
        // x-intervals where the touching surface runs along x (its x-extent at
        // least 90 % of its length: slopes under 25°), else the zones along the
        // surface, which a vertical face needs.
        let flat = p
            .zones_along
            .iter()
            .all(|z| (z.end[0] - z.start[0]).abs() >= 0.9 * (z.s_end - z.s_start));
        let zones: Vec<String> = if flat {
            p.zones
                .iter()
                .map(|z| format!("[{}, {}]", num(z[0]), num(z[1])))
                .collect()
        } else {
            p.zones_along
                .iter()
                .map(|z| {
                    format!(
                        "s [{}, {}] from ({}, {}) to ({}, {})",
                        num(z.s_start),
                        num(z.s_end),
                        num(z.start[0]),
                        num(z.start[1]),
                        num(z.end[0]),
                        num(z.end[1])
                    )
                })
                .collect()
        };
        let _ = writeln!(
            o,
            "pair {k}       body '{}' against {target}: zones {}; peak pressure {}{}",
            p.body,
            if zones.is_empty() {
                "none".to_string()
            } else {
                format!("{}{length}", zones.join(" "))
            },
            peak.map_or("-".into(), |q| format!("{}{stress}", num(q.pressure))),
            peak.map_or(String::new(), |q| format!(" at x = {}{length}", num(q.x)))
        );
        let ends: Vec<String> = p
            .zones_along
            .iter()
            .filter(|z| z.uncertainty.iter().any(|u| *u > 0.0))
            .map(|z| {
                format!(
                    "({}, {}) ±{}, ({}, {}) ±{}{length}",
                    num(z.start[0]),
                    num(z.start[1]),
                    num(z.uncertainty[0]),
                    num(z.end[0]),
                    num(z.end[1]),
                    num(z.uncertainty[1])
                )
            })
            .collect();
        if !ends.is_empty() {
            let _ = writeln!(
                o,
                "  zone ends  {} (estimated error along the surface)",
                ends.join("; ")
            );
        }
        // The fitted smooth edges, with their own estimate where there is one.
        let fitted_est = |i: usize, k: usize| {
            p.accuracy
                .as_ref()
                .and_then(|a| a.fitted_edges.get(i).and_then(|e| e[k]))
                .map_or(String::new(), |e| format!(" ±{}", num(e)))
        };
        let fitted: Vec<String> = p
            .zones_along
            .iter()
            .enumerate()
            .flat_map(|(i, z)| {
                [0, 1].map(|k| z.fitted[k].map(|f| format!("({}, {}){}", num(f.x), num(f.y), fitted_est(i, k))))
            })
            .flatten()
            .collect();
        if !fitted.is_empty() {
            let _ = writeln!(
                o,
                "  fitted     {}{length} (smooth edges where the fit of p² places them)",
                fitted.join("; ")
            );
        }
        if let Some(a) = p.accuracy.as_ref().filter(|a| a.pressure_l2.is_some()) {
            let pct = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{:.2} %", 100.0 * v));
            let _ = writeln!(
                o,
                "  accuracy   pressure L2 ±{}, peak ±{}, resultant ±{} (estimated, {})",
                pct(a.pressure_l2),
                pct(a.peak),
                pct(a.resultant),
                a.basis.to_string().replace('_', "-")
            );
            if let Some(e) = a.energy {
                let _ = writeln!(
                    o,
                    "  energy     error ≤ {} of the answer's energy norm (guaranteed bound)",
                    pct(Some(e))
                );
            }
            if !a.singular_ends.is_empty() {
                let at: Vec<String> = a
                    .singular_ends
                    .iter()
                    .map(|e| format!("({}, {}) ±{}", num(e.at[0]), num(e.at[1]), num(e.band)))
                    .collect();
                let _ = writeln!(
                    o,
                    "  corners    pressure unbounded at {}: left out of the estimate",
                    at.join(", ")
                );
            }
        }
        if let Some(f) = &p.friction {
            // A run along x as its x-interval; one whose ends share their x
            // (a vertical bore) by its end points.
            let runs = |z: &[[[f64; 2]; 2]]| {
                if z.is_empty() {
                    "none".to_string()
                } else {
                    z.iter()
                        .map(|[a, b]| match a[0] == b[0] && a[1] != b[1] {
                            true => format!("({}, {})–({}, {})", num(a[0]), num(a[1]), num(b[0]), num(b[1])),
                            false => format!("[{}, {}]", num(a[0]), num(b[0])),
                        })
                        .collect::<Vec<_>>()
                        .join(" ")
                }
            };
            let r = &f.tangential_resultant;
            let _ = writeln!(
                o,
                "  friction   μ {}: stick {}; slip {}; friction force fx {}{force}, fy {}{force}",
                num(f.coefficient),
                runs(&f.stick_runs),
                runs(&f.slip_runs),
                num(r.fx),
                num(r.fy)
            );
            let shear = p
                .points
                .iter()
                .filter_map(|q| q.tangential_traction.map(|t| (t, q)))
                .max_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));
            if let Some((t, q)) = shear {
                // Where the peak sits says whether it is at a slip zone's
                // edge (as Cattaneo–Mindlin's is) or inside the stick zone;
                // μp beside it says how close to slipping it is.
                let state = q.state.map_or(String::new(), |s| {
                    format!(
                        ", {}",
                        serde_json::to_value(s)
                            .ok()
                            .and_then(|v| v.as_str().map(String::from))
                            .unwrap_or_default()
                    )
                });
                let at = if flat {
                    format!("x = {}{length}", num(q.x))
                } else {
                    format!("({}, {}){length}", num(q.x), num(q.y))
                };
                let _ = writeln!(
                    o,
                    "  shear      peak |t| {}{stress} at {at} (t {}, μp {}{state})",
                    num(t.abs()),
                    num(t),
                    num(f.coefficient * q.pressure)
                );
            }
        }
    }
    if let Some(rf) = &r.refinement {
        let rounds: Vec<String> = rf.rounds.iter().map(|k| k.dofs.to_string()).collect();
        let _ = writeln!(
            o,
            "refinement   {} round(s), DOFs {}: {}",
            rf.rounds.len(),
            rounds.join(" → "),
            if rf.reached {
                "target reached".to_string()
            } else {
                format!("target NOT reached ({})", rf.stopped)
            }
        );
    }
    for pu in &r.punches {
        let _ = writeln!(
            o,
            "punch        '{}': alpha1 {}{length}, alpha2 {}{length}, theta {} rad; loads p1 {}{force}, p2 {}{force}, \
                m {}{moment}",
            pu.name,
            num(pu.alpha1),
            num(pu.alpha2),
            num(pu.theta),
            num(pu.p1),
            num(pu.p2),
            num(pu.m)
        );
    }
    for c in &r.couplings {
        let _ = writeln!(
            o,
            "coupling     {} of '{}': ux {}{length}, uy {}{length}, theta {} rad; on the body fx {}{force}, \
                fy {}{force}, m {}{moment}",
            c.path,
            c.body,
            num(c.ux),
            num(c.uy),
            num(c.theta),
            num(c.fx),
            num(c.fy),
            num(c.m)
        );
    }
    for f in &r.foundations {
        let w = f.w.iter().fold(0.0f64, |a, v| a.max(*v));
        let _ = writeln!(
            o,
            "foundation   '{}' ({}): load {}{force}, largest deflection {}{length}",
            f.name,
            f.model,
            num(f.load),
            num(w)
        );
    }
    let c = &r.certificate;
    let _ = writeln!(
        o,
        "certificate  primal {:.1e}, dual {:.1e}, complementarity {:.1e}, equilibrium {:.1e}",
        c.primal, c.dual, c.complementarity, c.equilibrium
    );
    if let Some(f) = &c.friction {
        let _ = writeln!(
            o,
            "  friction   cone {:.1e}, dissipation {:.1e}, stick {:.1e}",
            f.cone, f.dissipation, f.stick
        );
    }
    let t = &r.timings;
    let _ = writeln!(
        o,
        "time         {:.3} s (mesh {:.3}, assembly {:.3}, factorization {:.3}, condensation {:.3}, contact {:.3}, \
            post {:.3}, estimate {:.3})",
        t.total, t.mesh, t.assembly, t.factorization, t.condensation, t.contact_solve, t.post, t.estimate
    );
    if let Some(steps) = &r.steps {
        let _ = writeln!(o, "load steps   {} (the lines above are the last)", steps.len());
    }
    for w in &r.warnings {
        let _ = writeln!(o, "WARNING      {} at {}: {}", w.code, w.location, w.message);
    }
    for n in &r.notes {
        let _ = writeln!(o, "note         {n}");
    }
    o.trim_end().to_string()
}

/// The 3D answer: the whole resultant and each patch (`units`: length,
/// force, stress and moment names).
fn solid(o: &mut String, s: &contact_proto::SolidResult, units: [&String; 4]) {
    let [length, force, stress, moment] = units;
    let v = |x: [f64; 3]| format!("({}, {}, {})", num(x[0]), num(x[1]), num(x[2]));
    let _ = writeln!(
        o,
        "solid        body '{}' on obstacle '{}' (face set '{}'): force {}{force}, moment {}{moment} (on the body, \
         about the origin)",
        s.body,
        s.obstacle,
        s.faces,
        v(s.resultant.force),
        v(s.resultant.moment)
    );
    for (k, p) in s.patches.iter().enumerate() {
        let _ = writeln!(
            o,
            "  patch {k}    area {}{length}² (tributary {}), force {}{force}, centre {}, peak {}{stress} at {}",
            num(p.area),
            num(p.tributary_area),
            num(p.force),
            v(p.centre_of_pressure),
            num(p.peak_pressure),
            v(p.peak_at)
        );
    }
}

pub fn error(e: &ErrorReply) -> String {
    let code = serde_json::to_value(e.code)
        .ok()
        .and_then(|v| v.as_str().map(String::from))
        .unwrap_or_default();
    let at = if e.path.is_empty() {
        String::new()
    } else {
        format!(" at {}", e.path)
    };
    format!("refused      {code}{at}: {}", e.message)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_six_digits_without_noise() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(10.0), "10");
        assert_eq!(num(-0.6912345678), "-0.691235");
        assert_eq!(num(2.5e-7), "2.50000e-7");
    }
}
