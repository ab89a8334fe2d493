//! Tolerance-driven refinement (`settings.accuracy`) and the error estimate
//! every reply carries (`pairs[].accuracy`).
//!
//! Length: about 750 lines, one test per scene or defect the error bar was
//! measured on, each stating the figures its tolerance rests on.

use contact::wire;
use contact_verify::convergence::disk_request;
use serde_json::{json, Value};

fn solve(req: &Value) -> contact_core::solution::report::Report {
    contact_verify::run::solve(req, &Default::default()).expect("solved")
}

fn example(name: &str) -> Value {
    let path = format!("{}/../../proto/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The disk on a flat from a coarse start (h_min = 0.02 R: 6 element edges
/// across the half-zone) asked for 0.5 %: each round shrinks the smallest
/// element by a step sized from the last estimate (¼ to ¾) until the estimate
/// is met, and the pressure the answer then describes is within 0.5 % of the
/// disk's overkill solution, its nodal values too.
#[test]
fn a_pressure_tolerance_refines_the_disk_until_met() {
    let mut req = disk_request(0.02, "t3");
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.005}});
    let r = solve(&req);
    let refinement = r.refinement.as_ref().expect("rounds reported");
    assert!(refinement.reached, "{refinement:?}");
    assert_eq!(refinement.stopped, "reached");
    let rounds = &refinement.rounds;
    assert!(rounds.len() >= 2, "{rounds:?}");
    for w in rounds.windows(2) {
        assert!(w[1].dofs > w[0].dofs, "{rounds:?}");
        let step = w[1].h_min / w[0].h_min;
        assert!((0.25 - 1e-12..=0.75 + 1e-12).contains(&step), "{rounds:?}");
    }
    let last = rounds.last().unwrap();
    assert!(last.pressure_l2.is_some_and(|p| p <= 0.005), "{last:?}");
    let acc = r.pairs[0].accuracy.as_ref().unwrap();
    assert_eq!((acc.basis.as_str(), acc.pressure_l2), ("two_level", last.pressure_l2));
    // The true error, against the disk's overkill table (its own L2
    // uncertainty 1.4e-5): the target itself (measured 0.20 % described,
    // 0.18 % at the nodes).
    let e = contact_verify::tolerance::described_error(&r);
    assert!(e <= 0.005, "described L2 error against the overkill reference {e:.4}");
    let e = contact_verify::tolerance::error(&r);
    assert!(e <= 0.005, "nodal L2 error against the overkill reference {e:.4}");
    assert!(r.warnings.iter().all(|w| w.code != "tolerance_not_reached"));
}

/// A round limit that stops the refinement short leaves the answer `solved`
/// with a `tolerance_not_reached` warning that says what was reached.
#[test]
fn a_round_limit_stops_short_with_a_warning() {
    let mut req = disk_request(0.02, "t3");
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.001, "max_rounds": 1}});
    let v = serde_json::to_value(wire::solve_bytes(&serde_json::to_vec(&req).unwrap(), &Default::default()).unwrap())
        .unwrap();
    assert_eq!(v["status"], "solved");
    assert_eq!(v["refinement"]["reached"], false);
    assert_eq!(v["refinement"]["stopped"], "max_rounds");
    assert_eq!(v["refinement"]["rounds"].as_array().unwrap().len(), 1);
    let w = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["code"] == "tolerance_not_reached")
        .expect("warned");
    assert_eq!(w["location"], "/settings/accuracy");
    assert_eq!(w["limit"], 0.001);
    assert!(w["value"].as_f64().unwrap() > 0.001);
    assert!(w["message"].as_str().unwrap().contains("max_rounds"), "{w}");
}

/// A given (inline) mesh is estimated against its region meshed again with
/// elements twice as large (`two_level`, `mesh::coarsen`), and with a target
/// it is refined by splitting every element in four round after round: the block on a
/// vee refined to a zone-end error of 0.02 keeps its edge sets (the same pair
/// solves on every round), each round has about four times the unknowns of
/// the one before, and each round's zone end lies within twice its
/// estimated error of the final round's (the estimate's effectivity bound).
#[test]
fn an_inline_mesh_is_refined_uniformly() {
    let base = example("signorini_inline_block_on_vee.json");
    let plain = solve(&base);
    let acc = plain.pairs[0].accuracy.as_ref().unwrap();
    assert_eq!(acc.basis, "two_level");
    assert!(
        acc.pressure_l2.is_some() && acc.peak.is_some() && acc.resultant.is_some(),
        "{acc:?}"
    );
    assert_eq!(acc.zone_edges.len(), plain.pairs[0].zones_along.len());
    let mut ends = Vec::new();
    let mut estimates = Vec::new();
    for rounds in 1..=5 {
        let mut req = base.clone();
        req["settings"] = json!({"accuracy": {"zone_edge": 0.02, "max_rounds": rounds}});
        let r = solve(&req);
        let z = r.pairs[0].zones_along[0];
        ends.push(z.end[0]);
        estimates.push(r.pairs[0].accuracy.as_ref().unwrap().zone_edges[0][1]);
        if rounds == 5 {
            let refinement = r.refinement.unwrap();
            assert!(refinement.reached, "{refinement:?}");
            // Met with the margin of `adapt::SAFETY` (0.6 of the target).
            assert!(estimates[4] <= 0.012);
            // Uniform refinement of a 2D mesh: every side halved, four times
            // the elements; the DOFs grow by 4 less the boundary's share.
            for w in refinement.rounds.windows(2) {
                let growth = w[1].dofs as f64 / w[0].dofs as f64;
                assert!((3.0..=4.5).contains(&growth), "{:?}", refinement.rounds);
            }
        }
    }
    let last = *ends.last().unwrap();
    for (k, (end, est)) in ends.iter().zip(&estimates).enumerate().take(4) {
        assert!(
            (end - last).abs() <= 2.0 * est,
            "round {}: end {end} vs final {last}, estimate {est}",
            k + 1
        );
    }
}

/// A curved inline T6 mesh keeps its arc through refinement: the quarter
/// disk on a flat (h_min = 0.02 R, arc midsides on the circle) given inline
/// and solved in three rounds (the given mesh, then twice refined) has every contact node within the original arc's
/// interpolation
/// error R θ⁴/32 of the circle (θ the largest half angle of an original arc
/// edge; measured 1.1e-9 R, was 1.5e-3 R when bisection put midsides on
/// chords), and its pressure's L2 error against the overkill table is under
/// half the unrefined mesh's (measured 0.37 % from 1.37 %; chord midsides
/// made it 10.5 %: the sagitta read as a gap bump).
#[test]
fn a_curved_inline_t6_mesh_keeps_its_arc_when_refined() {
    use contact_core::mesh::generate::{disk, DiskPart, Grading};
    let h_min = 0.02;
    let grading = Grading {
        h_min,
        ratio: 1.1,
        extent: 0.105,
    };
    // The convergence scene's own mesh (`disk_request`), given inline.
    let (center, radius) = ([0.0, 1.0], 1.0);
    let m = disk(
        center,
        radius,
        true,
        DiskPart::Quarter,
        0.125,
        Some(grading),
        contact_core::mesh::Order::T6,
    )
    .unwrap();
    let sets: serde_json::Map<String, Value> = m
        .edge_sets
        .iter()
        .map(|(k, v)| (k.clone(), json!(v.iter().map(|e| [e.a, e.b]).collect::<Vec<_>>())))
        .collect();
    let elements: Vec<Vec<usize>> = m.elems.chunks(6).map(<[usize]>::to_vec).collect();
    let mut req = disk_request(h_min, "t6");
    req["bodies"][0]["mesh"] = json!({"inline": {"nodes": m.nodes, "elements": elements, "edge_sets": sets}});
    let theta = m.edge_sets["arc"]
        .iter()
        .map(|e| {
            let (a, b) = (m.nodes[e.a], m.nodes[e.b]);
            ((a[0] - b[0]).hypot(a[1] - b[1]) / (2.0 * radius)).asin()
        })
        .fold(0.0, f64::max);
    let plain = solve(&req);
    req["settings"] = json!({"accuracy": {"pressure_l2": 1e-5, "max_rounds": 3}});
    let refined = solve(&req);
    let rounds = &refined.refinement.as_ref().expect("rounds reported").rounds;
    assert_eq!(rounds.len(), 3, "{rounds:?}");
    assert!(refined.pairs[0].points.len() > plain.pairs[0].points.len());
    let off = refined.pairs[0]
        .points
        .iter()
        .map(|p| ((p.x - center[0]).hypot(p.y - center[1]) - radius).abs())
        .fold(0.0, f64::max);
    assert!(
        off <= radius * theta.powi(4) / 32.0,
        "{off} off the circle, θ = {theta}"
    );
    let (e0, e2) = (
        contact_verify::tolerance::error(&plain),
        contact_verify::tolerance::error(&refined),
    );
    assert!(e2 < 0.5 * e0, "L2 error {e0:.4} unrefined, {e2:.4} refined");
}

/// `estimate: false` skips the coarser solve; the targets are validated.
#[test]
fn the_estimate_is_optional_and_the_targets_are_checked() {
    let mut req = disk_request(0.0088, "t3");
    req["settings"] = json!({"estimate": false});
    let r = solve(&req);
    assert!(r.pairs[0].accuracy.is_none());
    assert_eq!(r.timings.estimate, 0.0);
    for (accuracy, path) in [
        (json!({}), "/settings/accuracy"),
        (json!({"pressure_l2": 2.0}), "/settings/accuracy/pressure_l2"),
        (json!({"zone_edge": -1.0}), "/settings/accuracy/zone_edge"),
        (
            json!({"pressure_l2": 0.01, "max_rounds": 0}),
            "/settings/accuracy/max_rounds",
        ),
    ] {
        req["settings"] = json!({ "accuracy": accuracy });
        let e = wire::solve_bytes(&serde_json::to_vec(&req).unwrap(), &Default::default()).unwrap_err();
        let v = serde_json::to_value(&e).unwrap();
        assert_eq!(v["code"], "invalid_request", "{v}");
        assert_eq!(v["path"], path, "{v}");
    }
}

/// The estimates are the size of the true errors on every scene of the
/// effectivity table (`contact_verify::effectivity`), at its middle level
/// (every element 4× the scene's own), T3 and T6, against the stored overkill
/// tables (disk, ball, block, and the disk and the block given inline) or the
/// scene solved 4× finer (the others). Smooth-edged scenes: the pressure's
/// within [0.5, 3] (measured 0.92–2.71 here, 0.69–2.98 over all three
/// levels: the edge's placement term, `two_level::edge_placement`, errs on
/// the safe side where the edge happens to fall well, and lifted the lowest
/// row from 0.43), the zone ends' and the T3 resultant's within [0.5, 2]
/// (0.84–1.09 and 0.92–1.26). At a flat punch's corners the order
/// assumed is 1 (`two_level::two_level`), which errs on the safe side: the
/// punches' pressure reads 2.5–4.9 of the true error at this level, tested
/// within [0.5, 5]. The peak's within [0.5, 2] (0.82–1.83 here), the
/// punches' within [0.5, 3] (0.86–2.74: the largest value outside the
/// corner's band is where the pressure rises to it), except on the two
/// cylinders: their T3 peak at this level is 0.018 % off between levels
/// 0.48 % and 0.054 % off (a crossing no estimate can foresee), and their T6
/// peak, 0.043 % off, is estimated at 4.10× (its nodes next to the peak
/// alternate by more than that error, which both of the peak's estimates
/// see; `two_level::two_level`), tested within [0.5, 5]. The
/// T6 resultant, 0.002–0.24 % off, is estimated 0.65–42× (its own test
/// below, at the finest level). At
/// a flat punch's corners the pressure is unbounded: both the estimate and
/// the true error leave out the band the reply names there (`singular_ends`,
/// 5 % of the zone), which must sit at the corners x = ±1 (two on the plane
/// punch, the rim of the punch of revolution) and nowhere else.
#[test]
fn the_estimates_are_the_size_of_the_true_errors() {
    use contact_verify::effectivity::{compare, level, scaled, table_of, SCENES};
    for sc in &SCENES {
        let name = sc.name;
        let base = (sc.request)();
        let reference = contact_verify::overkill::reference(table_of(name))
            .is_none()
            .then(|| solve(&scaled(&base, 0.5, "t6")));
        for (element, label) in [("t3", "T3"), ("t6", "T6")] {
            let r = solve(&level(sc, &base, 4.0, element));
            let singular = &r.pairs[0].accuracy.as_ref().unwrap().singular_ends;
            if name.starts_with("punch") {
                // Both corners of the plane punch; the rim of the one of
                // revolution (its axis end is the edge set's).
                let corners = if name == "punch_under_moment" { 2 } else { 1 };
                assert_eq!(singular.len(), corners, "{name} {label}: {singular:?}");
                for e in singular {
                    assert!(
                        (e.at[0].abs() - 1.0).abs() < 0.05,
                        "{name} {label}: singular end at {:?}",
                        e.at
                    );
                }
            } else {
                assert!(singular.is_empty(), "{name} {label}: singular ends {singular:?}");
            }
            let row = compare(sc.name, label, 4.0, &r, reference.as_ref());
            // `pressure_l2` estimates the described field's error (p² linear
            // between nodes, the square-root facet to each fitted edge).
            let eff = row.eff_curve().unwrap();
            // Punches: the order 1 assumed next to a corner errs on the safe
            // side (2.9–4.1 measured).
            let most = if name.starts_with("punch") { 5.0 } else { 3.0 };
            assert!(
                (0.5..=most).contains(&eff),
                "{name} {label}: pressure effectivity {eff:.3}"
            );
            if let Some(eff) = row.eff_peak().filter(|_| !(name == "two_cylinders" && element == "t3")) {
                let most = match name {
                    "two_cylinders" => 5.0,
                    _ if name.starts_with("punch") => 3.0,
                    _ => 2.0,
                };
                assert!((0.5..=most).contains(&eff), "{name} {label}: peak effectivity {eff:.3}");
            }
            if let Some(eff) = row.eff_edge() {
                assert!(
                    (0.5..=2.0).contains(&eff),
                    "{name} {label}: zone end effectivity {eff:.3}"
                );
            }
            // Load-controlled scenes (the punches, the footing) have their
            // resultant exact to round-off: nothing to estimate.
            if let Some(eff) = row
                .eff_resultant()
                .filter(|_| element == "t3" && row.err_resultant > 1e-6)
            {
                assert!(
                    (0.5..=2.0).contains(&eff),
                    "{name} {label}: resultant effectivity {eff:.3}"
                );
            }
        }
    }
}

/// A T6 resultant converges fast and its error changes sign from level to
/// level, so two levels can agree by chance: on the finest level of the
/// effectivity table (h_min and size × 2) the two-level estimate read 0.10,
/// 0.02 and 0.10 of the true error on the disk, the ball and the block
/// (against their overkill tables, whose resultant uncertainty is 8e-7 to
/// 1e-5 relative, far below the 2.6e-5–1.5e-4 errors measured). Floored at
/// what two levels can resolve (`two_level::RESULTANT_FLOOR`, 1e-4), it reads
/// 3.89, 1.23 and 0.65: asserted within [0.5, 5], the effectivity band's lower
/// end and the disk's measured reading with a margin.
#[test]
fn a_t6_resultant_is_not_estimated_below_what_two_levels_resolve() {
    use contact_verify::effectivity::{level, SCENES};
    for name in ["disk_on_flat", "ball_on_flat", "hertz_block"] {
        let sc = SCENES.iter().find(|s| s.name == name).unwrap();
        let r = solve(&level(sc, &(sc.request)(), 2.0, "t6"));
        let est = r.pairs[0].accuracy.as_ref().unwrap().resultant.unwrap();
        let err = contact_verify::overkill::reference_error(name, &r)
            .unwrap()
            .resultant
            .abs();
        assert!(
            (0.5..=5.0).contains(&(est / err)),
            "{name}: resultant estimate {est:.3e}, true {err:.3e}"
        );
    }
}

/// A user's own graded mesh of the disk on a flat (given inline, h_min
/// 0.0015 R, far field R/8: 10.7k DOF, as a user's mesher made it) carries a
/// full estimate, and it sees the far field's error: against the disk's
/// overkill table (its own L2 uncertainty 1.4e-5) the pressure's and the
/// resultant's estimates are within [0.5, 2] of their true errors, the
/// estimate's effectivity band (measured 0.473 % against 0.560 % for the
/// described field, whose nodes are 0.325 % off; 0.234 % against 0.221 % for
/// the resultant, the far field's stiffness, which a companion refined only
/// around the zone does not see; the companion, the region meshed again with
/// elements twice as large, took half the solve's time). Asked for 0.3 %, the rounds stop with the
/// true error below it (measured at 169k DOF: 0.090 % estimated, the
/// described field 0.050 % and the nodes 0.085 % off).
#[test]
fn a_users_graded_mesh_has_its_far_field_error_estimated() {
    let req = contact_verify::run::inlined(&disk_request(0.0015, "t3"));
    let r = solve(&req);
    let acc = r.pairs[0].accuracy.as_ref().unwrap();
    assert_eq!(acc.basis, "two_level");
    let e = contact_verify::overkill::reference_error("disk_on_flat", &r).unwrap();
    let row = contact_verify::effectivity::compare("disk_on_flat_inline", "T3", 1.0, &r, None);
    for (what, est, err) in [
        ("pressure", acc.pressure_l2.unwrap(), row.err_curve),
        ("resultant", acc.resultant.unwrap(), e.resultant.abs()),
    ] {
        assert!(
            (0.5..=2.0).contains(&(est / err)),
            "{what}: estimate {est:.3e}, true {err:.3e}"
        );
    }
    let mut refined = req.clone();
    refined["settings"] = json!({"accuracy": {"pressure_l2": 0.003}});
    let r = solve(&refined);
    assert!(r.refinement.as_ref().unwrap().reached, "{:?}", r.refinement);
    let e = contact_verify::overkill::reference_error("disk_on_flat", &r).unwrap();
    assert!(e.l2 <= 0.003, "true error {:.3e} above the target reached", e.l2);
}

/// A quarter disk on a flat meshed by another package and given inline
/// (`data/inline_disk_on_flat_graded_L3.json`, 7.7k DOF): its axis node reads
/// 2.3 % above the trend of its neighbours, an error its coarser companion
/// shares (4.4 %) and Richardson's scaling divided away: the peak's estimate
/// read 0.87 % for a true 2.50 % (0.35) on the mesh, 0.205 % for 0.600 %
/// refined to 0.3 %. With the axis node's own deviation (`peak_spike`) it
/// reads 2.22 % and 0.584 % (0.88 and 0.97), asserted within [0.5, 2], the
/// error bar's band, against the disk's overkill table.
#[test]
fn a_peak_standing_off_its_neighbours_at_an_axis_is_estimated() {
    let path = format!(
        "{}/tests/data/inline_disk_on_flat_graded_L3.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let req: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let table = contact_verify::overkill::reference("disk_on_flat").unwrap();
    let mut refined = req.clone();
    refined["settings"] = json!({"accuracy": {"pressure_l2": 0.003}});
    for (what, req) in [("own mesh", req), ("refined", refined)] {
        let r = solve(&req);
        let est = r.pairs[0].accuracy.as_ref().unwrap().peak.unwrap();
        let peak = r.pairs[0].points.iter().map(|q| q.pressure).fold(0.0, f64::max);
        let err = (peak / table.pressure(0.0) - 1.0).abs();
        assert!(
            (0.5..=2.0).contains(&(est / err)),
            "{what}: peak estimate {est:.3e}, true {err:.3e}"
        );
    }
}

/// The peak of a T3 mesh given inline, whose companion is its region meshed
/// again (`mesh::coarsen`): the companion's nodal pressures scatter by a few
/// % near the peak where the given mesh's are smooth, and the nodal
/// difference read that scatter as the answer's error (the disk's peak
/// estimated at 6.96× and 8.19× its true error at these two levels, the
/// block's at 2.56× and 0.60×). Against the companion's fitted peak
/// (`peak_fit`) they read 1.83, 0.94, 0.82 and 0.60 (the block's finest level
/// keeps the nodal difference, the smaller there), asserted within [0.5, 2],
/// the error bar's band, against the overkill tables of the generated scenes
/// (their own L2 uncertainty 1.4e-5 and 3.3e-4, under a tenth of these
/// true peak errors: 0.08–0.72 %).
#[test]
fn the_peak_of_a_given_t3_mesh_is_read_against_its_companions_fitted_peak() {
    use contact_verify::effectivity::{compare, level, SCENES};
    for sc in SCENES.iter().filter(|s| s.name.ends_with("_inline")) {
        let base = (sc.request)();
        for factor in [4.0, 2.0] {
            let r = solve(&level(sc, &base, factor, "t3"));
            let row = compare(sc.name, "T3", factor, &r, None);
            let eff = row.eff_peak().unwrap();
            assert!(
                (0.5..=2.0).contains(&eff),
                "{} at {factor}: peak estimate {:?}, true {:.3e}",
                sc.name,
                row.est_peak,
                row.err_peak
            );
        }
    }
}

/// The Gmsh example (the Hertz block meshed by Gmsh, 8.4k DOF) carries its
/// pressure's, peak's and resultant's estimates, each within [0.5, 2] of its
/// true error against the block's overkill table (measured 0.372 % against
/// 0.417 %, 0.382 % against 0.390 % (0.669 % before the fitted peaks,
/// `peak_fit`), 0.278 % against 0.298 %).
#[test]
fn the_gmsh_example_has_its_error_estimated() {
    let r = solve(&example("signorini_hertz_cylinder_gmsh.json"));
    let acc = r.pairs[0].accuracy.as_ref().unwrap();
    assert_eq!(acc.basis, "two_level");
    let table = contact_verify::overkill::reference("hertz_block").unwrap();
    let e = contact_verify::overkill::errors(table, &r);
    let peak = r.pairs[0].points.iter().map(|q| q.pressure).fold(0.0, f64::max);
    for (what, est, err) in [
        ("pressure", acc.pressure_l2.unwrap(), e.l2),
        ("resultant", acc.resultant.unwrap(), e.resultant.abs()),
        ("peak", acc.peak.unwrap(), (peak / table.pressure(0.0) - 1.0).abs()),
    ] {
        assert!(
            (0.5..=2.0).contains(&(est / err)),
            "{what}: estimate {est:.3e}, true {err:.3e}"
        );
    }
}

/// With nothing in contact there is no contact error to reduce: a target
/// stops after the first round, says so in a note, and warns of nothing
/// (it refined to 383k DOF before, with a warning whose value was 1.8e308).
#[test]
fn nothing_in_contact_stops_the_refinement_at_once() {
    let mut req = disk_request(0.02, "t3");
    // The flat pulled up: the disk is lifted clear of the floor.
    req["bodies"][0]["supports"][0]["uy"] = json!(0.0075);
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.001}});
    let r = solve(&req);
    assert!(r.pairs[0].zones_along.is_empty(), "{:?}", r.pairs[0].zones_along);
    let f = r.refinement.as_ref().unwrap();
    assert_eq!(
        (f.stopped.as_str(), f.reached, f.rounds.len()),
        ("no_contact", false, 1)
    );
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    let note = r.notes.iter().find(|n| n.text.contains("nothing is in contact"));
    assert_eq!(
        note.map(|n| n.kind),
        Some(contact_core::outcome::NoteKind::NotRefined),
        "{:?}",
        r.notes
    );
}

/// Refinement keeps the time limit by predicting each round before building
/// it: with a limit of twice the given mesh's own solve, the estimate's
/// coarser companion fits but the next round (about 5× the solve: four times
/// the unknowns, time growing like DOF^1.2) cannot, so it is left out at
/// once, and the warning says why (the limit is set from the solve measured
/// here, so a slower machine moves both alike).
#[test]
fn refinement_predicts_its_rounds_within_the_time_limit() {
    let mut req = contact_verify::run::inlined(&disk_request(0.0008, "t3"));
    let t = std::time::Instant::now();
    req["settings"] = json!({"estimate": false});
    solve(&req);
    let limit = 2.0 * t.elapsed().as_secs_f64() + 0.05;
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.001}});
    req["time_limit"] = json!(limit);
    let t = std::time::Instant::now();
    let r = solve(&req);
    let took = t.elapsed().as_secs_f64();
    let f = r.refinement.as_ref().unwrap();
    assert_eq!((f.stopped.as_str(), f.rounds.len()), ("time_limit", 1), "{f:?}");
    // Within the service's promise for a limit (10 % of it, or 0.2 s): the
    // limit is twice one solve measured just before, and on a machine whose
    // load changes between the two (2 cores, load 6) this answer once came
    // back past the bare limit.
    let slack = (0.1 * limit).max(0.2);
    assert!(took <= limit + slack, "answered after {took:.3} s, limit {limit:.3} s");
    assert_eq!(r.pairs[0].accuracy.as_ref().unwrap().basis, "two_level");
    let w = r
        .warnings
        .iter()
        .find(|w| w.code == "tolerance_not_reached")
        .expect("warned");
    assert!(w.message.contains("time limit"), "{}", w.message);
}

/// The estimator seam (`adapt::estimator`): an estimator defined here alone,
/// which needs no companion, makes every pair's accuracy with no companion
/// solve; the registered two-level estimator called through the seam gives
/// the default estimate exactly.
#[test]
fn a_trial_estimator_through_the_seam_needs_no_companion() {
    use contact_core::adapt::estimator::{Companion, Estimator, TwoLevel};
    use contact_core::outcome::EstimateBasis;
    use contact_core::solution::report::{PairAccuracy, PairReport, Report};
    use contact_core::{Limits, Scene};

    /// The zone ends' uncertainties doubled, and nothing else.
    struct Trial;
    impl Estimator for Trial {
        fn companion(&self, _: &Scene, _: &Report, _: usize) -> Result<Option<Companion>, String> {
            Ok(None)
        }
        fn pair(&self, answer: &PairReport, companion: Option<(&PairReport, f64)>) -> PairAccuracy {
            assert!(companion.is_none());
            PairAccuracy {
                basis: EstimateBasis::ZoneEdges,
                pressure_l2: None,
                peak: None,
                resultant: None,
                zone_edges: answer
                    .zones_along
                    .iter()
                    .map(|z| z.uncertainty.map(|u| 2.0 * u))
                    .collect(),
                fitted_edges: Vec::new(),
                singular_ends: Vec::new(),
                energy: None,
            }
        }
        fn share(&self, _: &Scene) -> f64 {
            0.0
        }
    }

    let mut req = disk_request(0.0088, "t3");
    let with_estimate = solve(&req);
    req["settings"] = json!({"estimate": false});
    let parsed: contact_proto::SolveRequest = serde_json::from_value(req).unwrap();
    let limits = Limits::default();
    let scene = Scene::try_new(&parsed, &limits).unwrap();
    let bare = contact_core::solve(&scene, &limits, None).unwrap();

    let mut report = bare.clone();
    let no_solve = |_: &Scene| -> Result<Report, contact_core::CoreError> { panic!("Trial needs no companion") };
    let next = contact_core::adapt::estimate_by(&Trial, &scene, &mut report, &no_solve, usize::MAX);
    assert!(next.is_none());
    let pair = &report.pairs[0];
    let acc = pair.accuracy.as_ref().expect("the trial's accuracy");
    assert_eq!(acc.basis, EstimateBasis::ZoneEdges);
    assert_eq!(acc.zone_edges.len(), pair.zones_along.len());
    for (e, z) in acc.zone_edges.iter().zip(&pair.zones_along) {
        assert_eq!(*e, z.uncertainty.map(|u| 2.0 * u));
    }

    // The two-level estimator through the seam: the default estimate, to the
    // bit. The energy bound is made apart (`Estimator::energy`, once for the
    // answer returned, by `adapt::estimate` and the rounds), from what an
    // estimated solve keeps: the bare answer keeps nothing and has none.
    let mut report = bare;
    let solver = |s: &Scene| contact_core::solve(s, &limits, None);
    contact_core::adapt::estimate_by(&TwoLevel, &scene, &mut report, &solver, usize::MAX);
    let mut default = with_estimate.pairs[0].accuracy.clone().expect("the default estimate");
    assert!(default.energy.is_some_and(|e| e > 0.0));
    default.energy = None;
    assert_eq!(report.pairs[0].accuracy, Some(default));
}

/// A given mesh whose region has a hole has two boundary loops, which
/// `mesh::coarsen` does not mesh again: its estimate falls back to the finer
/// companion (`two_level_finer`) and still carries every quantity.
#[test]
fn a_mesh_with_a_hole_is_estimated_against_its_finer_companion() {
    let mut req = contact_verify::run::inlined(&disk_request(0.0088, "t3"));
    let mesh = &mut req["bodies"][0]["mesh"]["inline"];
    let nodes: Vec<[f64; 2]> = serde_json::from_value(mesh["nodes"].clone()).unwrap();
    let elements: Vec<[usize; 3]> = serde_json::from_value(mesh["elements"].clone()).unwrap();
    // The quarter disk (centre (0, 1), radius 1) without the elements whose
    // centroid lies within 0.15 of (0.4, 0.6), far from the contact at (0, 0).
    let before = elements.len();
    let kept: Vec<[usize; 3]> = elements
        .into_iter()
        .filter(|e| {
            let c = [0, 1].map(|k| e.iter().map(|&n| nodes[n][k]).sum::<f64>() / 3.0);
            (c[0] - 0.4).hypot(c[1] - 0.6) > 0.15
        })
        .collect();
    assert!(kept.len() < before, "a hole was cut");
    let mut index = vec![usize::MAX; nodes.len()];
    let mut used = Vec::new();
    for e in &kept {
        for &n in e {
            if index[n] == usize::MAX {
                index[n] = used.len();
                used.push(nodes[n]);
            }
        }
    }
    let remap = |n: usize| index[n];
    mesh["nodes"] = json!(used);
    mesh["elements"] = json!(kept.iter().map(|e| e.map(remap)).collect::<Vec<_>>());
    let sets: serde_json::Map<String, Value> = mesh["edge_sets"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(name, edges)| {
            let edges: Vec<[usize; 2]> = serde_json::from_value(edges.clone()).unwrap();
            (
                name.clone(),
                json!(edges.iter().map(|e| e.map(remap)).collect::<Vec<_>>()),
            )
        })
        .collect();
    mesh["edge_sets"] = Value::Object(sets);
    let r = solve(&req);
    let acc = r.pairs[0].accuracy.as_ref().unwrap();
    assert_eq!(acc.basis, "two_level_finer");
    assert!(
        acc.pressure_l2.is_some() && acc.peak.is_some() && acc.resultant.is_some(),
        "{acc:?}"
    );
}

/// A user's T6 mesh whose surface spacing steps inside the contact zone:
/// the Hertz block given inline (h_min 0.16, zone half-width 0.69) bisected
/// twice over within |x| < 0.8 of its top, twice more within 0.5 < |x| < 0.8
/// and 0.6 < |x| < 0.78 (toward the zone ends) and within |x| < 0.2, so the
/// spacing changes two- to fourfold at |x| ≈ 0.2, 0.5 and 0.6 (26.8k DOF).
/// At each step a node's value is the pressure a third of the step away
/// (`two_level::grading_deviation`), which the two levels, graded alike, see
/// only in part. Against the block's overkill table (its L2 uncertainty
/// 3.3e-4) the estimate read 0.271 % for a true 0.269 % (1.01); without the
/// nodes' term 0.216 % (0.81), and 0.46–0.83 on meshes refined by marking
/// (the verification page), where `settings.accuracy` 0.003 reported
/// `reached` with a true 0.32 %. The lower bound 0.9 is that term's own
/// reading of such errors (0.92–0.97 of the nodal error on those meshes);
/// the upper is the error bar's [0.5, 2].
#[test]
fn steps_in_a_given_mesh_spacing_are_estimated() {
    let base = contact_verify::bench::hertz_request(0.16, "t6", "auto");
    let parsed: contact_proto::SolveRequest = serde_json::from_value(base.clone()).unwrap();
    let scene = contact_core::Scene::try_new(&parsed, &Default::default()).unwrap();
    let length = scene.scales.length;
    let mut mesh = contact_core::meshing::meshes(&scene).unwrap().remove(0);
    for (lo, hi) in [(0.0, 0.8), (0.5, 0.8), (0.6, 0.78), (0.0, 0.2)] {
        let (lo, hi, depth) = (lo / length, hi / length, 0.3 / length);
        mesh = contact_core::mesh::bisect::refine_where(&mesh, |p| (lo..hi).contains(&p[0].abs()) && p[1] > -depth, 2);
    }
    let r = solve(&contact_verify::run::with_meshes(&base, &[mesh], length));
    let table = contact_verify::overkill::reference("hertz_block").unwrap();
    let (num, _, den) =
        contact_core::solution::accuracy::described_l2(&r.pairs[0], &|x, _| table.pressure(x), &|_, _| true);
    let truth = (num / den).sqrt();
    let est = r.pairs[0].accuracy.as_ref().unwrap().pressure_l2.unwrap();
    assert!(
        (0.9..=2.0).contains(&(est / truth)),
        "estimate {est:.3e}, true {truth:.3e} at {} DOF",
        r.size.dofs
    );
}

/// With `settings.accuracy` the energy bound is made once, for the round
/// returned (`Estimator::energy`, counted here through the seam): the disk
/// from a coarse start takes at least two rounds, and the bound the reply
/// carries is the one a single estimated solve on the final round's mesh
/// gives. Both are the same computation on the same factor and fields, so
/// they agree to round-off (1e-12 relative; measured equal to the bit).
#[test]
fn refinement_bounds_the_energy_of_the_returned_round_alone() {
    use contact_core::adapt::estimator::{Companion, Estimator, TwoLevel};
    use contact_core::solution::energy::{EnergyBound, Pending};
    use contact_core::solution::report::{PairAccuracy, PairReport, Report};
    use contact_core::{Limits, Scene};
    use std::cell::RefCell;

    /// The two-level estimator, recording every bound it is asked for.
    struct Counting(RefCell<Vec<(Scene, usize)>>);
    impl Estimator for Counting {
        fn companion(&self, scene: &Scene, report: &Report, max: usize) -> Result<Option<Companion>, String> {
            TwoLevel.companion(scene, report, max)
        }
        fn pair(&self, answer: &PairReport, companion: Option<(&PairReport, f64)>) -> PairAccuracy {
            TwoLevel.pair(answer, companion)
        }
        fn share(&self, scene: &Scene) -> f64 {
            TwoLevel.share(scene)
        }
        fn energy(&self, scene: &Scene, answer: &Pending) -> Result<EnergyBound, &'static str> {
            self.0.borrow_mut().push((scene.clone(), answer.model.dofs.n_free));
            TwoLevel.energy(scene, answer)
        }
    }

    let mut req = disk_request(0.02, "t3");
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.005}});
    let parsed: contact_proto::SolveRequest = serde_json::from_value(req).unwrap();
    let limits = Limits::default();
    let scene = Scene::try_new(&parsed, &limits).unwrap();
    let target = scene.settings.accuracy.unwrap();
    let bare = |s: &Scene| contact_core::solve::solve_steps(s, &limits, None);
    let est = Counting(RefCell::new(Vec::new()));
    let r = contact_core::adapt::refine_by(&est, &scene, target, &bare, &limits).unwrap();
    let rounds = &r.refinement.as_ref().unwrap().rounds;
    assert!(rounds.len() >= 2, "{rounds:?}");
    let asked = est.0.into_inner();
    assert_eq!(asked.len(), 1, "one bound for {} rounds", rounds.len());
    let (last, dofs) = asked.into_iter().next().unwrap();
    assert_eq!(dofs, r.size.dofs);
    let bound = r.energy.expect("the returned round's bound");
    assert_eq!(r.pairs[0].accuracy.as_ref().unwrap().energy, Some(bound.relative()));

    let mut single = last;
    single.settings.accuracy = None;
    single.settings.estimate = true;
    let s = contact_core::solve(&single, &limits, None).unwrap();
    assert_eq!(s.size.dofs, r.size.dofs);
    let alone = s.energy.expect("a single solve's bound");
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    assert!(
        close(alone.absolute, bound.absolute) && close(alone.norm, bound.norm),
        "{alone:?} vs {bound:?}"
    );
}

/// A flat punch under a moment (M = 2, P = 10: the whole face pressed, both
/// corners singular) refined from its coarsest effectivity level to 1 %: the
/// rounds place a node on each corner (`adapt::sizing`), and the target
/// reported reached is true against the same scene solved by T6 4× finer
/// than the effectivity table's finest level (T6, which converges faster per
/// unknown than the T3 answer, at more unknowns). The tolerance is the target
/// itself: a reply that says `reached` claims it. Before, the corners fell
/// between nodes and 1 % was reported reached above it (the figures, against
/// a finer solve still, are in docs/verification/accuracy.md).
#[test]
fn a_punchs_corners_are_nodes_of_the_returned_round() {
    use contact_verify::effectivity::{compare, scaled, LEVELS, REFERENCE, SCENES};
    let sc = SCENES.iter().find(|s| s.name == "punch_under_moment").unwrap();
    let base = (sc.request)();
    let mut req = scaled(&base, REFERENCE, "t6");
    req["settings"] = json!({"estimate": false});
    let reference = solve(&req);
    let mut req = scaled(&base, LEVELS[0], "t3");
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.01}});
    let r = solve(&req);
    assert!(r.refinement.as_ref().unwrap().reached, "{:?}", r.refinement);
    // The corners x = ±1 to round-off of the generator's unit scaling.
    for corner in [-1.0, 1.0] {
        assert!(
            r.pairs[0].points.iter().any(|c| (c.x - corner).abs() < 1e-9),
            "no node at the corner x = {corner}"
        );
    }
    let row = compare(sc.name, "T3", LEVELS[0], &r, Some(&reference));
    assert!(
        row.err_curve <= 0.01,
        "reported reached at a true {:.3} %",
        100.0 * row.err_curve
    );
}

/// A target out of reach within `accuracy.max_dofs` ends on the largest round
/// the budget holds, not on the last round whose full step fitted: the disk
/// asked for 0.05 % within 60k DOF stops at `max_dofs` with its last round
/// between half the budget and the budget (aimed at 0.8 of it from the
/// rounds' growth), and every round within it.
#[test]
fn the_last_round_fills_the_budget_it_is_given() {
    const BUDGET: u64 = 60_000;
    let mut req = disk_request(0.02, "t3");
    req["settings"] = json!({"accuracy": {"pressure_l2": 0.0005, "max_dofs": BUDGET}});
    let r = solve(&req);
    let f = r.refinement.as_ref().unwrap();
    assert!(!f.reached, "{f:?}");
    assert_eq!(f.stopped.as_str(), "max_dofs", "{f:?}");
    let dofs: Vec<u64> = f.rounds.iter().map(|r| r.dofs as u64).collect();
    assert!(dofs.iter().all(|&d| d <= BUDGET), "{dofs:?}");
    assert!(*dofs.last().unwrap() >= BUDGET / 2, "{dofs:?}");
}
