//! A punch's loads carried exactly by the bound's contact pressure p*.

use super::{equilibrate, ContactSide, Form};
use crate::contact::free_motions::Motion;
use crate::contact::gap::closest;
use crate::contact::rows::punch_coefficients;
use crate::mesh::Mesh2d;
use crate::scene::{Control, Scene};

/// Gauss–Legendre with 4 points on [0, 1].
pub(super) const GAUSS4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_7, 0.173_927_422_568_726_9),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
];

/// Scales p* on the sides facing punch `o` so that it carries exactly the
/// loads the punch's rows carry in each component the request loads
/// (the complementary energy's admissible set asks the punch's equilibrium
/// of p*, and p* = λ_i / w_i linear on each side matches its force but not
/// its moment): nodal pressures × (1 + a₀ + a₁ t + a₂ t²), t the node's
/// distance along x from the punch's reference, one term per loaded
/// component. Err where no such scaling keeps p* ≥ 0.
pub(super) fn balance(
    scene: &Scene,
    meshes: &[Mesh2d],
    motions: &[(Motion, f64)],
    o: usize,
    sides: &mut [ContactSide],
) -> Result<(), &'static str> {
    let Some(pu) = &scene.obstacles[o].punch else {
        return Ok(());
    };
    let loaded: Vec<usize> = (0..3).filter(|&k| matches!(pu.controls[k], Control::Load(_))).collect();
    if loaded.is_empty() {
        return Ok(());
    }
    // The requested loads, not the rows' own sum (which meets them only to
    // the solver's tolerance): the punch's equilibrium Σ λ c = −P.
    let mut target = [0.0; 3];
    for (m, load) in motions {
        if let Motion::Punch { obstacle, component } = *m {
            if obstacle == o {
                target[component] = -load;
            }
        }
    }
    let n = loaded.len();
    let basis = |x: f64, j: usize| (x - pu.reference[0]).powi(j as i32);
    // a[k][j]: component k of p*'s force when its nodal pressures are scaled
    // by basis j (j = n: unscaled).
    let mut a = [[0.0; 4]; 3];
    let mut scale = 0.0_f64;
    for s in sides.iter().filter(|s| s.obstacle == o && presses(s)) {
        let mesh = &meshes[s.body];
        let (pa, pb) = (mesh.nodes[s.ends[0]], mesh.nodes[s.ends[1]]);
        let l = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        let mid = 0.5 * (pa[0] + pb[0]);
        // A quadratic side's p* may kink or jump at its middle: each half alone
        // (on a straight face the integrand is then a quadratic on each, and
        // 4 points are exact).
        for &(start, len) in halves(s) {
            for (q, w) in GAUSS4 {
                let t = start + len * q;
                let x = [(1.0 - t) * pa[0] + t * pb[0], (1.0 - t) * pa[1] + t * pb[1]];
                let Some(c) = closest(&scene.obstacles[o].shape, x) else {
                    continue;
                };
                let co = punch_coefficients(c.point, pu.reference, [-c.normal[0], -c.normal[1]]);
                for j in 0..=n {
                    let factor = |x: f64| if j < n { basis(x, j) } else { 1.0 };
                    let p = match s.form {
                        // One q on an arc's side: scaled at its midpoint.
                        Form::Arc { .. } | Form::Fan { .. } => s.pressure_at(mesh, t) * factor(mid),
                        _ => nodal(s, mesh, t, factor),
                    };
                    for (row, ck) in a.iter_mut().zip(co) {
                        row[j] += w * len * l * p * ck;
                    }
                }
            }
        }
        for p in s.pressure.iter().chain(s.mid.iter().flat_map(|m| &m.pressure)) {
            scale = scale.max(p.abs());
        }
    }
    // A loaded component no pressure on these sides can push (a flat face's
    // horizontal) holds as it is; the others are solved for, with as many
    // basis functions as they number.
    let big = a
        .iter()
        .flat_map(|r| r[..=n].iter())
        .fold(0.0_f64, |x, y| x.max(y.abs()));
    let (pushed, idle): (Vec<usize>, Vec<usize>) = loaded
        .into_iter()
        .partition(|&k| a[k][..n].iter().any(|v| v.abs() > 1e-12 * big));
    if idle
        .iter()
        .any(|&k| (target[k] - a[k][n]).abs() > 1e-9 * big.max(f64::MIN_POSITIVE))
    {
        return Err("the contact pressure cannot balance a punch's loads with one sign");
    }
    let unscaled = n;
    let n = pushed.len();
    if n == 0 {
        return Ok(());
    }
    // Σ_j a[k][j] x_j = target[k] − a[k][unscaled] over the pushed k.
    let rows: Vec<[f64; 4]> = pushed.iter().map(|&k| a[k]).collect();
    let r: Vec<f64> = pushed.iter().map(|&k| target[k] - a[k][unscaled]).collect();
    let coef = least_norm(&rows, &r, big).ok_or("the contact pressure cannot balance a punch's loads with one sign")?;
    for s in sides.iter_mut().filter(|s| s.obstacle == o) {
        let mesh = &meshes[s.body];
        let mid = 0.5 * (mesh.nodes[s.ends[0]][0] + mesh.nodes[s.ends[1]][0]);
        let form = s.form;
        let at = |node: usize| match form {
            Form::Arc { .. } | Form::Fan { .. } => mid,
            _ => mesh.nodes[node][0],
        };
        let (xs, xm) = (s.ends.map(at), s.mid.map(|m| at(m.node)));
        let scaled = |p: &mut f64, x: f64| {
            *p *= 1.0 + (0..n).map(|j| coef[j] * basis(x, j)).sum::<f64>();
            if *p < -1e-12 * scale {
                return Err("the contact pressure cannot balance a punch's loads with one sign");
            }
            *p = p.max(0.0);
            Ok(())
        };
        for (p, x) in s.pressure.iter_mut().zip(xs) {
            scaled(p, x)?;
        }
        if let (Some(m), Some(x)) = (s.mid.as_mut(), xm) {
            for p in &mut m.pressure {
                scaled(p, x)?;
            }
        }
    }
    Ok(())
}

/// Whether a side carries any p* (a quadratic side's midside value can
/// press between two corners at 0).
fn presses(s: &ContactSide) -> bool {
    super::carries(s.pressure, s.mid.map(|m| m.pressure))
}

/// The pieces of [0, 1] on which a side's p* is linear: the whole side, or
/// a quadratic side's two halves (start, length).
pub(super) fn halves(s: &ContactSide) -> &'static [(f64, f64)] {
    if s.mid.is_some() {
        &[(0.0, 0.5), (0.5, 0.5)]
    } else {
        &[(0.0, 1.0)]
    }
}

/// p* at parameter t of a side whose nodal pressures are each scaled by
/// `factor` of the node's x: linear between the ends, or on each half
/// through the midside value.
fn nodal(s: &ContactSide, mesh: &Mesh2d, t: f64, factor: impl Fn(f64) -> f64) -> f64 {
    let at = |node: usize, p: f64| p * factor(mesh.nodes[node][0]);
    let ends = [0, 1].map(|e| at(s.ends[e], s.pressure[e]));
    super::piecewise(ends, s.mid.map(|m| m.pressure.map(|p| at(m.node, p))), t)
}

/// The least-norm x of Σ_{j < n} rows[p][j] x_j = r[p] (n = rows.len()),
/// or None where it does not hold to 1e-9 of `big`: x = Aᵀ y, A Aᵀ y = r (a
/// symmetric punch's horizontal and moment rows are both odd in x, so A may
/// be rank-deficient; the system is then consistent, or no scaling balances
/// the loads).
pub(super) fn least_norm(rows: &[[f64; 4]], r: &[f64], big: f64) -> Option<Vec<f64>> {
    let n = rows.len();
    let mut m = vec![0.0; n * n];
    for p in 0..n {
        for q in 0..n {
            m[p * n + q] = (0..n).map(|j| rows[p][j] * rows[q][j]).sum();
        }
    }
    let mut y = r.to_vec();
    let mut skip = Vec::new();
    equilibrate::factor_psd(&mut m, n, &mut skip);
    equilibrate::solve_factored(&m, &skip, &mut y, n);
    let coef: Vec<f64> = (0..n).map(|j| (0..n).map(|p| rows[p][j] * y[p]).sum()).collect();
    let holds = r.iter().enumerate().all(|(p, rp)| {
        let got: f64 = (0..n).map(|j| rows[p][j] * coef[j]).sum();
        (got - rp).abs() <= 1e-9 * big
    });
    holds.then_some(coef)
}
