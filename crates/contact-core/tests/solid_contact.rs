//! Frictionless Signorini contact of a body of tetrahedra with a rigid plane
//! (`contact_core::solid::signorini`), against truths that need no reference:
//!
//! - the contact patch test (T4 nodal rows, T10 dual mortar rows): a box
//!   resting on the plane, uniform pressure p
//!   on its top, rollers on its four sides (the box is held along the plane's
//!   normal by contact alone, a free motion of the mixed LCP): the exact
//!   solution is oedometric, in T4's space, so every node's contact pressure
//!   λ_i / a_i is p and Σ λ_i is p A;
//! - complementarity and no penetration, node by node and in the KKT
//!   certificate;
//! - an off-centre load on a block that may tilt: part of the base lifts
//!   off, and the contact forces balance the load's force and its moment
//!   about the base line the supports cannot load;
//! - the report of each answer (`solid::report`): the patch test's single
//!   patch is the base (area, force, centre of pressure, outline), the
//!   off-centre block's and the tilted plane's resultants balance the load
//!   with the reactions, the Hertz patch's area gives a, and a box over a
//!   groove rests on two patches;
//! - the nested dissection stops at a passed deadline.
//!
//! Tolerances: where the discrete solution is exact (the patch test), 1e-10
//! is the round-off of the factorization and of the dense W, ε · cond, with
//! cond(K) ~ 1e4 on these graded meshes; equilibrium of the contact forces
//! is an equation the mixed LCP solves (Dᵀλ = Rᵀf) and holds to 1e-12 of
//! the load, the round-off of its saddle-point solve; the certificate's
//! entries are relative round-off residuals, 1e-10 leaving two decades of
//! slack over the measured 1e-13 to 1e-12 (printed).
//!
//! Length: about 630 lines; the report's checks sit beside the solves of
//! the scenes they read (the Hertz solve alone takes 3.5 s) rather than
//! solving them again in a file of their own.

use contact_core::cancel::Deadline;
use contact_core::error::{CoreError, InvalidKind};
use contact_core::mesh::generate::Grading;
use contact_core::mesh3d::generate::box_mesh;
use contact_core::mesh3d::{Mesh3d, Order};
use contact_core::scene::Settings;
use contact_core::solid::dofs::dof_map;
use contact_core::solid::obstacle::{rows, Plane};
use contact_core::solid::ordering::nested_dissection;
use contact_core::solid::report::{report, SolidContactReport};
use contact_core::solid::signorini::{self, Contact};
use contact_core::solid::{FaceLoad, SolidBody, Support};

const E: f64 = 2.0;
const NU: f64 = 0.3;
const P: f64 = 0.01;

fn graded(order: Order) -> Mesh3d {
    let g = Grading {
        h_min: 0.04,
        ratio: 1.5,
        extent: 0.05,
    };
    // Graded toward an inner point, so spacings change on both sides of it.
    box_mesh([0.0; 3], [1.0; 3], 0.25, Some(([0.3, 0.6, 0.0], g)), order)
}

fn on_plane_body(mesh: &Mesh3d) -> SolidBody<'_> {
    SolidBody {
        mesh,
        youngs_modulus: E,
        poisson_ratio: NU,
        supports: vec![
            Support::roller("x_min", 0),
            Support::roller("x_max", 0),
            Support::roller("y_min", 1),
            Support::roller("y_max", 1),
        ],
        loads: vec![FaceLoad::Pressure {
            faces: "z_max".into(),
            p: P,
        }],
        body_force: [0.0; 3],
    }
}

/// Node by node: λ ≥ 0, gap ≥ 0 and λ gap = 0 to round-off of the
/// displacement (`tol` of the largest |u|), and the certificate below 1e-10.
fn assert_kkt(c: &Contact, tol: f64) {
    let umax = c.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let lmax = c.lambda.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for (i, (&l, &g)) in c.lambda.iter().zip(&c.gap).enumerate() {
        assert!(l >= 0.0, "row {i}: λ = {l}");
        assert!(g >= -tol * umax, "row {i}: penetration {g}");
        assert!((l * g).abs() <= tol * lmax * umax, "row {i}: λ g = {}", l * g);
    }
    println!("certificate {:?}", c.certificate);
    assert!(c.converged);
    assert!(c.certificate.worst() < 1e-10, "{:?}", c.certificate);
}

/// The smallest gap d(x + u) over every node of face set `faces` (midsides
/// included), over the largest |u|: what a mortar row's weighted gap leaves
/// at the nodes.
fn nodal_gap(mesh: &Mesh3d, c: &Contact, plane: Plane, faces: &str) -> f64 {
    let umax = c.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let gap = |n: usize| plane.distance(std::array::from_fn(|k| mesh.nodes[n][k] + c.u[3 * n + k]));
    mesh.face_set_nodes(faces)
        .into_iter()
        .map(gap)
        .fold(f64::INFINITY, f64::min)
        / umax
}

#[test]
fn a_box_on_a_plane_under_uniform_pressure_presses_it_uniformly() {
    // T4 with nodal rows, T10 with dual mortar rows on the corners; the
    // plane touching the base, then 1e-3 below it: the box must first move
    // down by the gap (its free motion), then press as before.
    for (order, drop) in [
        (Order::T4, 0.0),
        (Order::T4, 1e-3),
        (Order::T10, 0.0),
        (Order::T10, 1e-3),
    ] {
        let mesh = graded(order);
        let body = on_plane_body(&mesh);
        let plane = Plane::try_new([0.0, 0.0, -drop], [0.0, 0.0, 1.0]).unwrap();
        let r = rows(&body, "z_min", plane).unwrap();
        let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
        let worst = c.pressure.iter().fold(0.0f64, |a, p| a.max((p - P).abs())) / P;
        let total: f64 = c.lambda.iter().sum();
        println!(
            "{order:?}, drop {drop}: {} rows, {} DOFs, pressure error {worst:.1e}, Σλ error {:.1e}, {} iterations, \
             {} refinements",
            r.len(),
            c.dofs.n_free,
            (total - P).abs() / P,
            c.iterations,
            c.refinements
        );
        assert!(worst < 1e-10, "pressure off p by {worst:e}");
        assert!((total - P).abs() < 1e-12 * P, "Σλ = {total}");
        // The oedometric field, moved down by the gap.
        let m = E * (1.0 - NU) / ((1.0 + NU) * (1.0 - 2.0 * NU));
        let umax = P / m;
        for (n, x) in mesh.nodes.iter().enumerate() {
            let want = [0.0, 0.0, -drop - P * x[2] / m];
            for (k, w) in want.iter().enumerate() {
                assert!(
                    (c.u[3 * n + k] - w).abs() < 1e-10 * umax,
                    "node {n}: {:?}",
                    &c.u[3 * n..3 * n + 3]
                );
            }
        }
        assert_kkt(&c, 1e-10);
        // The exact field touches the plane everywhere: no node penetrates.
        assert!(nodal_gap(&mesh, &c, plane, "z_min") > -1e-10);
        whole_base_patch(&report(&body, &r, &c).unwrap());
    }
}

/// The report of the box pressed uniformly: one patch, the whole base. Its
/// area is the unit square's as a sum of face areas (round-off, 1e-12: a
/// few hundred products of O(h) lengths), its force the load p·1 to the
/// certificate's 1e-10, its centre of pressure the base's centroid (λ_i = p
/// a_i, so Σ λ_i x_i / Σ λ_i = ∫ x dA / A exactly: 1e-10 of the size), and
/// its outline one loop on the base's perimeter, of length 4.
fn whole_base_patch(rep: &SolidContactReport) {
    assert_eq!(rep.patches.len(), 1, "one patch");
    let p = &rep.patches[0];
    let length: f64 = p.outline.iter().map(|l| perimeter(l)).sum();
    println!(
        "  one patch: area − 1 = {:.1e}, tributary − 1 = {:.1e}, force / P − 1 = {:.1e}, centre {:?}, {} loop(s) of \
         length {length}",
        p.area - 1.0,
        p.tributary_area - 1.0,
        p.force / P - 1.0,
        p.centre_of_pressure,
        p.outline.len()
    );
    assert!((p.area - 1.0).abs() < 1e-12, "area {}", p.area);
    assert!((p.tributary_area - 1.0).abs() < 1e-12, "Σ a_i {}", p.tributary_area);
    assert!((p.force - P).abs() < 1e-10 * P, "force {}", p.force);
    for (x, want) in p.centre_of_pressure.iter().zip([0.5, 0.5, 0.0]) {
        assert!((x - want).abs() < 1e-10, "centre {:?}", p.centre_of_pressure);
    }
    assert!((p.peak_pressure - P).abs() < 1e-10 * P, "peak {}", p.peak_pressure);
    assert_eq!(p.outline.len(), 1, "one loop");
    assert!((length - 4.0).abs() < 1e-12, "perimeter {length}");
    for x in &p.outline[0] {
        let off = x[0].min(1.0 - x[0]).min(x[1]).min(1.0 - x[1]).abs().max(x[2].abs());
        assert!(off < 1e-14, "{x:?} is not on the base's edge");
    }
    assert!(rep.points.iter().all(|q| q.in_contact), "every row pressed");
    assert_eq!(p.rows.len(), rep.points.len());
}

/// The length of a closed polygon.
fn perimeter(ring: &[[f64; 3]]) -> f64 {
    (0..ring.len())
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            ((0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>()).sqrt()
        })
        .sum()
}

/// A block [0, 1] × [0, ½] × [0, ½] (half of a block symmetric about y = 0),
/// pressed on the part x > ¾ of its top. The symmetry plane y = 0 holds u_y;
/// a peg at the middle of the base's edge (the base faces around
/// (½, 0, 0)) holds u_x; nothing else: the block may sink and tilt about the
/// base line x = ½, z = 0, held by the plane alone. With the load's
/// resultant at x = 7/8, far outside the base's middle third, the part of the
/// base near x = 0 lifts off.
#[test]
fn an_off_centre_load_lifts_part_of_the_base() {
    for order in [Order::T4, Order::T10] {
        off_centre(order);
    }
}

fn off_centre(order: Order) {
    let mut mesh = box_mesh([0.0; 3], [1.0, 0.5, 0.5], 1.0 / 16.0, None, order);
    let peg_node = mesh
        .nodes
        .iter()
        .position(|x| (x[0] - 0.5).abs() < 1e-12 && x[1] == 0.0 && x[2] == 0.0)
        .unwrap();
    let peg: Vec<_> = mesh.face_sets["z_min"]
        .iter()
        .filter(|f| f.corners.contains(&peg_node))
        .copied()
        .collect();
    let load: Vec<_> = mesh.face_sets["z_max"]
        .iter()
        .filter(|f| f.corners.iter().all(|&n| mesh.nodes[n][0] >= 0.75 - 1e-12))
        .copied()
        .collect();
    mesh.face_sets.insert("peg".into(), peg);
    mesh.face_sets.insert("load".into(), load);
    let body = SolidBody {
        mesh: &mesh,
        youngs_modulus: E,
        poisson_ratio: NU,
        supports: vec![Support::roller("y_min", 1), Support::roller("peg", 0)],
        loads: vec![FaceLoad::Pressure {
            faces: "load".into(),
            p: P,
        }],
        body_force: [0.0; 3],
    };
    let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let r = rows(&body, "z_min", plane).unwrap();
    let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
    assert_eq!(c.dofs.modes.len(), 2, "free: sinking and tilting");
    assert_kkt(&c, 1e-10);
    // Vertical forces and their moment about the base line x = ½, z = 0
    // (the peg's and the symmetry plane's reactions have neither: they act
    // along x at z = 0 and along y).
    let force = P * 0.25 * 0.5;
    let load_moment = -force * (0.875 - 0.5);
    let total: f64 = c.lambda.iter().sum();
    // A row's force reaches the nodes of its terms (a mortar row's several).
    let arm = |t: &Vec<(usize, f64)>| t.iter().map(|&(n, w)| w * (mesh.nodes[n][0] - 0.5)).sum::<f64>();
    let moment: f64 = r.terms.iter().zip(&c.lambda).map(|(t, l)| l * arm(t)).sum();
    println!(
        "{order:?}: Σλ − P = {:.1e} P, moment residual {:.1e} P L, {} iterations",
        (total - force) / force,
        (moment + load_moment) / force,
        c.iterations
    );
    assert!((total - force).abs() < 1e-12 * force, "Σλ = {total}, load {force}");
    assert!(
        (moment + load_moment).abs() < 1e-12 * force,
        "moments {moment} and {load_moment}"
    );
    // Lifted where the load is not: the rows near x = 0 carry nothing and
    // open by far more than round-off; those under the load are pressed.
    let umax = c.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let (mut lifted, mut pressed) = (0, 0);
    for (i, &n) in r.nodes.iter().enumerate() {
        let x = mesh.nodes[n][0];
        if x < 0.2 {
            assert!(
                c.lambda[i] == 0.0 && c.gap[i] > 1e-3 * umax,
                "x = {x}: λ {} gap {}",
                c.lambda[i],
                c.gap[i]
            );
            lifted += 1;
        }
        if x > 0.8 {
            assert!(c.lambda[i] > 0.0, "x = {x}: λ {}", c.lambda[i]);
            pressed += 1;
        }
    }
    let open = c.lambda.iter().filter(|&&l| l == 0.0).count();
    // Rows hold d(x + u) ≥ 0 at the nodes (T4) or in the dual mean over a
    // corner's faces (T10, the midsides free between): reported, not bound.
    let worst = nodal_gap(&mesh, &c, plane, "z_min");
    println!(
        "{open} of {} rows open; smallest nodal gap {worst:.1e} of max |u|",
        r.len()
    );
    if order == Order::T4 {
        assert!(worst > -1e-10, "{worst:e}");
    }
    assert!(lifted > 0 && pressed > 0);
    // The pressure p on the part [¾, 1] × [0, ½] of the top z = ½: the
    // force (0, 0, −pA) at its centroid (7/8, ¼, ½).
    let rep = report(&body, &r, &c).unwrap();
    balance(&mesh, &c, &rep, [0.875, 0.25, 0.5], [0.0, 0.0, -force]);
}

/// The report's resultant against the loads, one uniform pressure of
/// resultant `load` acting at `at` (its face set's centroid): the
/// consistent nodal loads reproduce that force and moment exactly (Σ N_j =
/// 1, Σ N_j x_j = x). With the support reactions (the residual K u − f −
/// Bᵀλ on the supported DOFs), the forces and moments on the body sum to
/// zero: K u annihilates the rigid motions, and off the supports the
/// residual is the certificate's equilibrium (1e-13 of the terms over a
/// few thousand DOFs): 1e-10 of |load| and |load|·L (L = 1). The patches'
/// forces sum to Σ λ_i, the resultant's size, to round-off.
fn balance(mesh: &Mesh3d, c: &Contact, rep: &SolidContactReport, at: [f64; 3], load: [f64; 3]) {
    let force = load.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut f = [0.0; 3];
    let mut m = [0.0; 3];
    let mut add = |x: [f64; 3], v: [f64; 3]| {
        let t = [
            x[1] * v[2] - x[2] * v[1],
            x[2] * v[0] - x[0] * v[2],
            x[0] * v[1] - x[1] * v[0],
        ];
        (0..3).for_each(|k| {
            f[k] += v[k];
            m[k] += t[k];
        });
    };
    add(at, load);
    for (n, x) in mesh.nodes.iter().enumerate() {
        add(*x, std::array::from_fn(|k| c.reactions[3 * n + k]));
    }
    let (rf, rm) = (rep.resultant.force, rep.resultant.moment);
    let (f, m): ([f64; 3], [f64; 3]) = (
        std::array::from_fn(|k| f[k] + rf[k]),
        std::array::from_fn(|k| m[k] + rm[k]),
    );
    let patches: f64 = rep.patches.iter().map(|p| p.force).sum();
    let total: f64 = c.lambda.iter().sum();
    println!(
        "  resultant {rf:?}, moment {rm:?}; unbalanced force {f:?}, moment {m:?} (of |load| = {force}); {} \
         patch(es), Σ forces − Σλ = {:.1e}",
        rep.patches.len(),
        patches - total
    );
    for k in 0..3 {
        assert!(f[k].abs() < 1e-10 * force, "force {f:?}");
        assert!(m[k].abs() < 1e-10 * force, "moment {m:?}");
    }
    assert!(
        (patches - total).abs() < 1e-12 * total,
        "patches carry {patches} of {total}"
    );
}

/// The box under uniform pressure on a plane tilted by 0.05 about the y
/// axis (normal (sin θ, 0, cos θ), through the origin): the base touches
/// along x = 0 first and the box, held sideways by its rollers, sinks until
/// a strip of it carries the load. The contact forces act along the tilted
/// normal, the x rollers take their x component; the resultant balances
/// the load (0, 0, −p) at (½, ½, 1) with the reactions (`balance`), and
/// Σ λ cos θ = p (the free sinking's equilibrium, round-off).
#[test]
fn a_tilted_plane_s_resultant_balances_the_load() {
    for order in [Order::T4, Order::T10] {
        let mesh = graded(order);
        let body = on_plane_body(&mesh);
        let theta: f64 = 0.05;
        let plane = Plane::try_new([0.0; 3], [theta.sin(), 0.0, theta.cos()]).unwrap();
        let r = rows(&body, "z_min", plane).unwrap();
        let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
        assert_kkt(&c, 1e-10);
        let rep = report(&body, &r, &c).unwrap();
        let open = rep.points.iter().filter(|q| !q.in_contact).count();
        println!(
            "{order:?}: {open} of {} rows open, patches' areas {:?}",
            rep.points.len(),
            rep.patches.iter().map(|p| p.area).collect::<Vec<_>>()
        );
        assert!(open > 0, "partial contact");
        let sinking = rep.resultant.force[2];
        assert!((sinking - P).abs() < 1e-12 * P, "Σλ cos θ = {sinking}");
        balance(&mesh, &c, &rep, [0.5, 0.5, 1.0], [0.0, 0.0, -P]);
    }
}

#[test]
fn a_motion_the_plane_cannot_resist_is_refused() {
    // Without the side rollers the box may slide along the plane, which a
    // frictionless plane cannot stop.
    let mesh = graded(Order::T4);
    let mut body = on_plane_body(&mesh);
    body.supports.truncate(2);
    let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let r = rows(&body, "z_min", plane).unwrap();
    match signorini::solve(&body, &r, &Settings::default()) {
        Err(CoreError::Invalid {
            kind: InvalidKind::NoSupport,
            reason,
            ..
        }) => assert!(reason.contains("translation along y"), "{reason}"),
        other => panic!("expected no_support, got {:?}", other.map(|c| c.converged)),
    }
    assert!(Plane::try_new([0.0; 3], [0.0; 3]).is_err());
}

/// Hertz: a paraboloid of radius R pressed on the flat by a force P touches
/// it over a disk of radius a = (3 P R / 4 E*)^(1/3), E* = E / (1 − ν²), with
/// the peak pressure p0 = 3 P / (2π a²). The quarter model: a block
/// [0, 1]² × [0, 1] with symmetry planes x = 0 and y = 0, its base's gap to
/// the plane r² / (2R) (the paraboloid of Hertz's theory on a flat-faced
/// body, added to the rows' gaps), the quarter load P/4 as a uniform
/// pressure on its top; a = 0.1 (a tenth of the block), the mesh graded to
/// h = a/10 within 1.3 a of the axis.
///
/// Honest tolerances: the contact area Σ a_i over the active rows resolves
/// the edge of the disk to about one element, h/a = 10 % of a, and the
/// block is not a half-space (depth and width 10 a: a few per cent of
/// compliance), so a_h = √(4 A / π) must lie within 15 % of a (measured:
/// 1.018, 0.985, 1.005 at h = a/5, a/7, a/10). The nodal pressure on the
/// axis, λ / a_i, is a weaker quantity: measured 0.886, 0.887, 0.902 of p0 at
/// the same h, converging slowly from below (nodal rows on linear faces; the
/// tributary average alone would cost 0.2 %). Its bound, 15 %, is read from
/// those measurements, not derived: it guards against a change for the
/// worse, not for accuracy. The vertical equilibrium Σλ = P/4 is exact to
/// round-off (1e-12).
#[test]
fn a_paraboloid_on_a_flat_matches_hertz_to_its_mesh_size() {
    let (big_r, a, nu) = (1.0, 0.1, 0.3);
    let e_star = E / (1.0 - NU * NU);
    assert_eq!(nu, NU);
    let force = 4.0 * e_star * a * a * a / (3.0 * big_r);
    let g = Grading {
        h_min: a / 10.0,
        ratio: 1.3,
        extent: 1.3 * a,
    };
    let mesh = box_mesh([0.0; 3], [1.0; 3], 0.2, Some(([0.0; 3], g)), Order::T4);
    let body = SolidBody {
        mesh: &mesh,
        youngs_modulus: E,
        poisson_ratio: NU,
        supports: vec![Support::roller("x_min", 0), Support::roller("y_min", 1)],
        loads: vec![FaceLoad::Pressure {
            faces: "z_max".into(),
            p: force / 4.0,
        }],
        body_force: [0.0; 3],
    };
    let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let mut r = rows(&body, "z_min", plane).unwrap();
    for (gap, &n) in r.gap.iter_mut().zip(&r.nodes) {
        let x = mesh.nodes[n];
        *gap += (x[0] * x[0] + x[1] * x[1]) / (2.0 * big_r);
    }
    let t = std::time::Instant::now();
    let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
    assert_kkt(&c, 1e-10);
    let total: f64 = c.lambda.iter().sum();
    assert!((total - force / 4.0).abs() < 1e-12 * force, "Σλ = {total}");
    let area: f64 = (0..r.len()).filter(|&i| c.lambda[i] > 0.0).map(|i| r.area[i]).sum();
    let a_h = (4.0 * area / std::f64::consts::PI).sqrt();
    let axis = r.nodes.iter().position(|&n| mesh.nodes[n] == [0.0; 3]).unwrap();
    let p0 = 3.0 * force / (2.0 * std::f64::consts::PI * a * a);
    println!(
        "{} DOFs, {} rows ({} active), {:.2} s: a_h / a = {:.4}, p(0) / p0 = {:.4}",
        c.dofs.n_free,
        r.len(),
        c.lambda.iter().filter(|&&l| l > 0.0).count(),
        t.elapsed().as_secs_f64(),
        a_h / a,
        c.pressure[axis] / p0
    );
    assert!((a_h / a - 1.0).abs() < 0.15, "a_h = {a_h}, a = {a}");
    // The report: one patch carrying P/4 (round-off, as Σλ), its faces'
    // area π a² / 4 within the same 15 % on a. The faces in contact are the
    // inner bound, about half an element inside the edge (h / 2a = 5 %):
    // measured 0.937 a, against 1.005 a from the rows' Σ a_i.
    let rep = report(&body, &r, &c).unwrap();
    assert_eq!(rep.patches.len(), 1);
    let patch = &rep.patches[0];
    let a_faces = (4.0 * patch.area / std::f64::consts::PI).sqrt();
    println!(
        "  report: a from the faces' area / a = {:.4}, from Σ a_i {:.4}; peak {:.4} p0 at {:?}; {} loop(s), {} faces",
        a_faces / a,
        (4.0 * patch.tributary_area / std::f64::consts::PI).sqrt() / a,
        patch.peak_pressure / p0,
        patch.peak_at,
        patch.outline.len(),
        patch.faces.len()
    );
    assert!((a_faces / a - 1.0).abs() < 0.15, "a from the faces {a_faces}");
    // The outline: one loop, the symmetry planes' edges and an arc; the
    // arc's vertices (off the planes) are pressed nodes next to open ones
    // (a face's diagonal apart, √2 h), so near the edge r = a: within 2h
    // inside and h outside (measured 0.860 a to 1.005 a).
    assert_eq!(patch.outline.len(), 1);
    let arc: Vec<f64> = patch.outline[0]
        .iter()
        .filter(|x| x[0] > 1e-12 && x[1] > 1e-12)
        .map(|x| x[0].hypot(x[1]))
        .collect();
    let (rmin, rmax) = arc
        .iter()
        .fold((f64::MAX, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    println!(
        "  outline arc: {} vertices, r / a in [{:.3}, {:.3}]",
        arc.len(),
        rmin / a,
        rmax / a
    );
    assert!(
        !arc.is_empty() && rmin > 0.8 * a && rmax < 1.1 * a,
        "arc r in [{rmin}, {rmax}]"
    );
    assert!((patch.force - force / 4.0).abs() < 1e-12 * force);
    assert!(a_faces <= a_h, "the faces in contact are inside the rows' area");
    assert!(
        (c.pressure[axis] / p0 - 1.0).abs() < 0.15,
        "p(0) = {}, p0 = {p0}",
        c.pressure[axis]
    );
}

/// Fichera's condition: a box on the plane pulled up by its top (p < 0) has
/// no non-negative contact force to balance it, and one with no load at all
/// may rise freely (nothing decides where it rests): both refused, not
/// solved.
#[test]
fn loads_no_contact_force_can_balance_are_refused() {
    let mesh = graded(Order::T4);
    let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    for (p, kind) in [(-P, InvalidKind::IncompatibleLoads), (0.0, InvalidKind::NoSupport)] {
        let mut body = on_plane_body(&mesh);
        body.loads = vec![FaceLoad::Pressure {
            faces: "z_max".into(),
            p,
        }];
        let r = rows(&body, "z_min", plane).unwrap();
        match signorini::solve(&body, &r, &Settings::default()) {
            Err(CoreError::Invalid { kind: k, reason, .. }) => assert_eq!(k, kind, "p = {p}: {reason}"),
            other => panic!("p = {p}: expected a refusal, got {:?}", other.map(|c| c.converged)),
        }
    }
}

/// A box pressed on a plane with a groove: the rows over the strip
/// 0.3 < x < 0.7 start 0.05 away (the plane's trench, added to their gaps
/// as Hertz's paraboloid is), twelve times the box's sinking p / M, so
/// they stay open; the box rests on two strips, two patches. Their forces
/// sum to the load (the free sinking's equilibrium, 1e-12 as above), and
/// on the uniform mesh of h = 1/8 each patch is the faces of its strip of
/// nodes, x ≤ ¼ or x ≥ ¾: area ¼ and an outline of length 2.5, to
/// round-off.
#[test]
fn a_box_over_a_groove_rests_on_two_patches() {
    for order in [Order::T4, Order::T10] {
        let mesh = box_mesh([0.0; 3], [1.0; 3], 0.125, None, order);
        let body = on_plane_body(&mesh);
        let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
        let mut r = rows(&body, "z_min", plane).unwrap();
        for (gap, &n) in r.gap.iter_mut().zip(&r.nodes) {
            if (mesh.nodes[n][0] - 0.5).abs() < 0.2 {
                *gap += 0.05;
            }
        }
        let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
        assert_kkt(&c, 1e-10);
        let rep = report(&body, &r, &c).unwrap();
        let forces: Vec<f64> = rep.patches.iter().map(|p| p.force).collect();
        let total: f64 = forces.iter().sum();
        println!(
            "{order:?}: {} patches, forces {forces:?} (Σ − P = {:.1e} P), areas {:?}, perimeters {:?}",
            rep.patches.len(),
            (total - P) / P,
            rep.patches.iter().map(|p| p.area).collect::<Vec<_>>(),
            rep.patches
                .iter()
                .map(|p| p.outline.iter().map(|l| perimeter(l)).sum::<f64>())
                .collect::<Vec<_>>()
        );
        assert_eq!(rep.patches.len(), 2);
        assert!((total - P).abs() < 1e-12 * P, "Σ = {total}");
        assert!((rep.resultant.force[2] - P).abs() < 1e-12 * P);
        for p in &rep.patches {
            assert!(p.force > 0.0);
            assert!((p.area - 0.25).abs() < 1e-12, "area {}", p.area);
            assert_eq!(p.outline.len(), 1);
            assert!((perimeter(&p.outline[0]) - 2.5).abs() < 1e-12);
            let side = p.centre_of_pressure[0] < 0.5;
            assert!(
                p.rows.iter().all(|&i| (rep.points[i].position[0] < 0.5) == side),
                "a patch on both sides of the groove"
            );
        }
        for q in &rep.points {
            let over = (q.position[0] - 0.5).abs() < 0.2;
            assert_eq!(q.in_contact, !over, "{:?}", q);
        }
    }
}

/// The 3D ordering keeps a request's clock: under a deadline already passed
/// (`Deadline::install(0)`, as the service installs a request's limit) the
/// nested dissection stops with the timeout of stage `factorization`, and
/// the contact solve that calls it stops at its assembly, rather than running the order
/// to its end; under a deadline an hour away the order is the one computed
/// without any, a permutation of the free DOFs.
#[test]
fn a_passed_deadline_stops_the_3d_ordering() {
    let mesh = graded(Order::T4);
    let body = on_plane_body(&mesh);
    let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let r = rows(&body, "z_min", plane).unwrap();
    let touching: Vec<usize> = r.nodes.clone();
    let dofs = dof_map(&body, Some(&touching)).unwrap();
    let free = nested_dissection(&mesh, &dofs).unwrap();
    {
        let _d = Deadline::install(std::time::Duration::from_secs(3600));
        assert_eq!(nested_dissection(&mesh, &dofs).unwrap(), free);
    }
    let mut seen = vec![false; dofs.n_free];
    free.0.iter().for_each(|&f| seen[f] = true);
    assert!(seen.iter().all(|&s| s) && free.0.len() == dofs.n_free);
    assert!((0..dofs.n_free).all(|i| free.1[free.0[i]] == i));
    let _d = Deadline::install(std::time::Duration::ZERO);
    let t = nested_dissection(&mesh, &dofs).unwrap_err();
    assert_eq!(
        (t.stage, t.limit_s),
        (contact_core::outcome::ProgressStage::Factorization, 0.0)
    );
    match signorini::solve(&body, &r, &Settings::default()) {
        // The solve looks at the clock first in its assembly, before the order.
        Err(CoreError::Timeout { stage, limit_s, .. }) => assert_eq!((stage, limit_s), ("assembly", 0.0)),
        other => panic!("expected a timeout, got {:?}", other.map(|c| c.converged)),
    }
}
