//! A statically admissible stress on a straight-sided quadratic triangle K
//! from tractions linear on each half of its sides: K split in four at its
//! side midpoints (three corner sub-triangles and the middle one), each with
//! the `airy` stress of the tractions on its three sides.
//!
//! The six outer half-sides carry the tractions given. Each inner side
//! carries a linear traction (two components at two ends: four values),
//! which its corner sub-triangle's force and moment balance fix but for one:
//! a shear traction linear along the side with zero mean, α (s − ½) τ, which
//! carries no force and no moment. The middle sub-triangle is then balanced
//! when K is (its tractions are what the corner ones leave). The three α
//! (the count of the HCT interior normal derivatives a Johnson–Mercier
//! stress on K would have) are chosen to make the complementary energy
//! ∫_K (σ* − σ̄) : C⁻¹ (σ* − σ̄) least: σ* is affine in α (`airy` is linear
//! in its tractions), so the energy is a quadratic in α, made from the stress
//! with α = 0 and one per unit α, and minimised by a 3 × 3 solve. Any α gives
//! an admissible stress; the least one only tightens the bound.

use super::airy::{self, SubStress};
use super::patch::Residual;

/// The four sub-triangles' stresses with the least α, and its energy.
pub struct Split {
    /// The corner sub-triangles at p[0], p[1], p[2], then the middle one.
    pub subs: [SubStress; 4],
    /// ∫_K (σ* − σ̄) : C⁻¹ (σ* − σ̄).
    pub energy: f64,
    /// σ* − σ̄ at each sub-triangle's nine points (`patch`'s residual).
    pub residual: [Residual; 4],
    /// The largest of the sub-triangles' `closure` and `scale`.
    pub closure: f64,
    pub scale: f64,
}

/// A traction linear along a (sub-)side: its values at the side's two ends.
type Linear = [[f64; 2]; 2];

/// Each corner sub-triangle's vertices (counter-clockwise, as K's corners
/// `p` and midpoints `q`, q[j] on side j from p[j] to p[j+1]) and the slot
/// of its inner side; the middle sub-triangle is (q0, q1, q2), whose slot
/// for corner j's inner side is `MIDDLE_SLOT[j]`.
fn corner_sub(p: &[[f64; 2]; 3], q: &[[f64; 2]; 3], j: usize) -> ([[f64; 2]; 3], usize) {
    match j {
        0 => ([p[0], q[0], q[2]], 1),
        1 => ([q[0], p[1], q[1]], 2),
        _ => ([q[2], q[1], p[2]], 0),
    }
}
const MIDDLE_SLOT: [usize; 3] = [2, 0, 1];

/// The outer half-sides of corner sub-triangle j in its slots, from K's
/// tractions `t[side][half]` (half 0 from p[side] to q[side]).
fn outer(t: &[[Linear; 2]; 3], j: usize) -> [Option<Linear>; 3] {
    match j {
        0 => [Some(t[0][0]), None, Some(t[2][1])],
        1 => [Some(t[0][1]), Some(t[1][0]), None],
        _ => [None, Some(t[1][1]), Some(t[2][0])],
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The stress of K (corners `p` counter-clockwise) under the tractions
/// `t[j][h]` on half h of side j (acting on K, linear on each half), closest
/// in complementary energy to the linear stress σ̄ given at the corners
/// (`target`), with the compliance C⁻¹. None for a degenerate triangle.
pub fn stress(
    p: &[[f64; 2]; 3],
    t: &[[Linear; 2]; 3],
    target: &[[f64; 3]; 3],
    compliance: &[[f64; 3]; 3],
) -> Option<Split> {
    let q: [[f64; 2]; 3] =
        std::array::from_fn(|j| [(p[j][0] + p[(j + 1) % 3][0]) / 2.0, (p[j][1] + p[(j + 1) % 3][1]) / 2.0]);
    let zero: Linear = [[0.0; 2]; 2];
    let mut middle = [zero; 3];
    let mut base: Vec<SubStress> = Vec::with_capacity(4);
    // Each corner sub-triangle's stress for a unit α on its inner side, and
    // the middle one's.
    let mut unit_corner: Vec<SubStress> = Vec::with_capacity(3);
    let mut unit_middle: Vec<SubStress> = Vec::with_capacity(3);
    for j in 0..3 {
        let (v, slot) = corner_sub(p, &q, j);
        let known = outer(t, j);
        let (a, b) = (v[slot], v[(slot + 1) % 3]);
        let c = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        // Force and moment about the inner side's midpoint of the outer
        // halves (Simpson's rule: exact for a linear traction along a line).
        let (mut force, mut moment) = ([0.0; 2], 0.0);
        for (k, tk) in known.iter().enumerate() {
            let Some(tk) = tk else { continue };
            let (xa, xb) = (v[k], v[(k + 1) % 3]);
            let l = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
            let tm = [(tk[0][0] + tk[1][0]) / 2.0, (tk[0][1] + tk[1][1]) / 2.0];
            let xm = [(xa[0] + xb[0]) / 2.0, (xa[1] + xb[1]) / 2.0];
            let r = |x: [f64; 2]| [x[0] - c[0], x[1] - c[1]];
            for i in 0..2 {
                force[i] += l * tm[i];
            }
            moment += l / 6.0 * (cross(r(xa), tk[0]) + 4.0 * cross(r(xm), tm) + cross(r(xb), tk[1]));
        }
        let l = (b[0] - a[0]).hypot(b[1] - a[1]);
        if l <= 0.0 {
            return None;
        }
        let tau = [(b[0] - a[0]) / l, (b[1] - a[1]) / l];
        let nu = [-tau[1], tau[0]];
        // t(s) = t̄ + (s − ½) d on the inner side: its force l t̄ and its
        // moment about c, l²/12 τ × d, cancel the outer halves'.
        let mean = [-force[0] / l, -force[1] / l];
        let gamma = -12.0 * moment / (l * l);
        let inner: Linear = [
            [mean[0] - gamma * nu[0] / 2.0, mean[1] - gamma * nu[1] / 2.0],
            [mean[0] + gamma * nu[0] / 2.0, mean[1] + gamma * nu[1] / 2.0],
        ];
        let mode: Linear = [[-tau[0] / 2.0, -tau[1] / 2.0], [tau[0] / 2.0, tau[1] / 2.0]];
        let with = |inner: Linear, outer: bool| -> [Linear; 3] {
            std::array::from_fn(|k| {
                if k == slot {
                    inner
                } else if outer {
                    known[k].unwrap_or(zero)
                } else {
                    zero
                }
            })
        };
        base.push(airy::stress(&v, &with(inner, true))?);
        unit_corner.push(airy::stress(&v, &with(mode, false))?);
        // The middle sub-triangle runs the side the other way, and its
        // traction is the opposite one (action and reaction).
        let opposite = |x: Linear| [[-x[1][0], -x[1][1]], [-x[0][0], -x[0][1]]];
        middle[MIDDLE_SLOT[j]] = opposite(inner);
        let mut m = [zero; 3];
        m[MIDDLE_SLOT[j]] = opposite(mode);
        unit_middle.push(airy::stress(&q, &m)?);
    }
    base.push(airy::stress(&q, &middle)?);
    // σ̄ at a point of K, from its barycentric coordinates.
    let det = cross(
        [p[1][0] - p[0][0], p[1][1] - p[0][1]],
        [p[2][0] - p[0][0], p[2][1] - p[0][1]],
    );
    let target_at = |x: [f64; 2]| -> [f64; 3] {
        let l1 = cross([x[0] - p[0][0], x[1] - p[0][1]], [p[2][0] - p[0][0], p[2][1] - p[0][1]]) / det;
        let l2 = cross([p[1][0] - p[0][0], p[1][1] - p[0][1]], [x[0] - p[0][0], x[1] - p[0][1]]) / det;
        let l0 = 1.0 - l1 - l2;
        std::array::from_fn(|r| l0 * target[0][r] + l1 * target[1][r] + l2 * target[2][r])
    };
    let energy_of = |a: [f64; 3], b: [f64; 3]| -> f64 {
        (0..3)
            .map(|r| a[r] * (0..3).map(|c| compliance[r][c] * b[c]).sum::<f64>())
            .sum()
    };
    // The modes at each point of sub-triangle s (0–2 the corners, 3 the
    // middle): corner j feels α_j alone, the middle one all three.
    let mode_at = |s: usize, i: usize, k: usize, pt: usize| -> [f64; 3] {
        match s {
            3 => unit_middle[i].at[k][pt],
            _ if s == i => unit_corner[i].at[k][pt],
            _ => [0.0; 3],
        }
    };
    let (mut h, mut g) = ([[0.0; 3]; 3], [0.0; 3]);
    for (s, sub) in base.iter().enumerate() {
        for k in 0..3 {
            let w = sub.area[k] / 3.0;
            for pt in 0..3 {
                let tg = target_at(sub.points[k][pt]);
                let diff: [f64; 3] = std::array::from_fn(|r| sub.at[k][pt][r] - tg[r]);
                for i in 0..3 {
                    let mi = mode_at(s, i, k, pt);
                    g[i] += w * energy_of(mi, diff);
                    for (j, hij) in h[i].iter_mut().enumerate() {
                        *hij += w * energy_of(mi, mode_at(s, j, k, pt));
                    }
                }
            }
        }
    }
    let alpha = airy::solve3(h, [-g[0], -g[1], -g[2]]).unwrap_or([0.0; 3]);
    let mut subs: [SubStress; 4] = [base[0], base[1], base[2], base[3]];
    let (mut energy, mut closure, mut scale) = (0.0, 0.0_f64, 0.0_f64);
    let mut residual = [[[[0.0; 3]; 3]; 3]; 4];
    for (s, (sub, res)) in subs.iter_mut().zip(residual.iter_mut()).enumerate() {
        closure = closure.max(sub.closure);
        scale = scale.max(sub.scale);
        for (k, res_k) in res.iter_mut().enumerate() {
            let w = sub.area[k] / 3.0;
            for (pt, res_pt) in res_k.iter_mut().enumerate() {
                for (i, a) in alpha.iter().enumerate() {
                    let mi = mode_at(s, i, k, pt);
                    for (v, m) in sub.at[k][pt].iter_mut().zip(mi) {
                        *v += a * m;
                    }
                }
                let tg = target_at(sub.points[k][pt]);
                let diff: [f64; 3] = std::array::from_fn(|r| sub.at[k][pt][r] - tg[r]);
                energy += w * energy_of(diff, diff);
                *res_pt = diff;
            }
        }
    }
    Some(Split {
        subs,
        energy,
        residual,
        closure,
        scale,
    })
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::compliance;
    use super::*;

    const TRIANGLE: [[f64; 2]; 3] = [[0.3, -0.2], [2.1, 0.4], [0.7, 1.9]];

    /// σ n on each half of each side of `p`, at the half's ends.
    fn halves(p: &[[f64; 2]; 3], sigma: &dyn Fn([f64; 2]) -> [f64; 3]) -> [[Linear; 2]; 3] {
        std::array::from_fn(|j| {
            let (a, b) = (p[j], p[(j + 1) % 3]);
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            let n = [(b[1] - a[1]) / l, -(b[0] - a[0]) / l];
            let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            let t = |x: [f64; 2]| {
                let s = sigma(x);
                [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
            };
            [[t(a), t(m)], [t(m), t(b)]]
        })
    }

    /// A uniform and a linear equilibrated stress (the Airy stresses of a
    /// quadratic and a cubic: both in every sub-triangle's HCT space, and
    /// their inner sides' tractions linear, so one α reproduces them) are
    /// reproduced at every point, and their energy against themselves is 0
    /// to round-off.
    #[test]
    fn uniform_and_linear_equilibrated_stresses_are_reproduced() {
        let uniform = |_: [f64; 2]| [1.3, -0.7, 0.45];
        // φ = x³ − 2 x²y + 0.5 xy² + 3y³ + x² − y²
        let linear = |x: [f64; 2]| {
            let (a, b) = (x[0], x[1]);
            [a + 18.0 * b - 2.0, 6.0 * a - 4.0 * b + 2.0, 4.0 * a - b]
        };
        let fields: [&dyn Fn([f64; 2]) -> [f64; 3]; 2] = [&uniform, &linear];
        for sigma in fields {
            let t = halves(&TRIANGLE, sigma);
            let target = TRIANGLE.map(sigma);
            let out = stress(&TRIANGLE, &t, &target, &compliance()).expect("triangle");
            assert!(out.closure < 1e-12 * out.scale, "closure {}", out.closure);
            for sub in &out.subs {
                for (s, x) in sub.at.iter().flatten().zip(sub.points.iter().flatten()) {
                    let e = sigma(*x);
                    for k in 0..3 {
                        assert!((s[k] - e[k]).abs() < 1e-11, "{s:?} against {e:?} at {x:?}");
                    }
                }
            }
            let scale: f64 = target.iter().flatten().map(|v| v * v).sum();
            assert!(out.energy < 1e-24 * scale, "energy {}", out.energy);
        }
    }

    /// Tractions linear on each half-side, each half its own (not the trace
    /// of one field), balanced by the last half's: the stress carries every
    /// half's traction exactly, read at the half's midpoint in the corner
    /// sub-triangle that touches it (point 0 of its sub-triangle along that
    /// side).
    #[test]
    fn balanced_half_side_tractions_are_carried_exactly() {
        let p = TRIANGLE;
        let q: [[f64; 2]; 3] = std::array::from_fn(|j| [0, 1].map(|c| (p[j][c] + p[(j + 1) % 3][c]) / 2.0));
        let mut t: [[Linear; 2]; 3] = [
            [[[0.5, -1.0], [0.1, 0.3]], [[-0.2, 0.6], [0.8, -0.4]]],
            [[[-0.4, 0.9], [0.7, 0.2]], [[0.3, 0.3], [-0.6, 1.1]]],
            [[[0.2, -0.5], [0.9, 0.1]], [[0.0; 2]; 2]],
        ];
        // Force and moment about the origin of a linear traction from x0 to x1
        // (Simpson: exact for a quadratic integrand).
        let load = |x0: [f64; 2], x1: [f64; 2], tt: Linear| -> [f64; 3] {
            let l = (x1[0] - x0[0]).hypot(x1[1] - x0[1]);
            let mut out = [0.0; 3];
            for (s, w) in [(0.0, 1.0), (0.5, 4.0), (1.0, 1.0)] {
                let x = [0, 1].map(|c| x0[c] + s * (x1[c] - x0[c]));
                let v = [0, 1].map(|c| tt[0][c] * (1.0 - s) + tt[1][c] * s);
                out[0] += l * w / 6.0 * v[0];
                out[1] += l * w / 6.0 * v[1];
                out[2] += l * w / 6.0 * cross(x, v);
            }
            out
        };
        let ends = |j: usize, h: usize| if h == 0 { (p[j], q[j]) } else { (q[j], p[(j + 1) % 3]) };
        let mut total = [0.0; 3];
        for (j, h) in [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0)] {
            let (a, b) = ends(j, h);
            let f = load(a, b, t[j][h]);
            (0..3).for_each(|k| total[k] += f[k]);
        }
        // The last half: the load of unit values, one at a time (linear),
        // its fourth value set to 0.3, the other three solved for.
        let (a, b) = ends(2, 1);
        let unit = |k: usize| {
            let mut tt = [[0.0; 2]; 2];
            tt[k / 2][k % 2] = 1.0;
            load(a, b, tt)
        };
        let cols = [unit(0), unit(1), unit(2)];
        let fourth = unit(3);
        let m = std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r]));
        let rhs = std::array::from_fn(|r| -total[r] - 0.3 * fourth[r]);
        let x = airy::solve3(m, rhs).expect("a non-degenerate half");
        t[2][1] = [[x[0], x[1]], [x[2], 0.3]];
        let target = [[0.2, -0.1, 0.05], [0.4, 0.3, -0.2], [-0.3, 0.6, 0.1]];
        let out = stress(&p, &t, &target, &compliance()).expect("triangle");
        assert!(out.closure < 1e-12 * out.scale, "closure {}", out.closure);
        // (corner sub-triangle, its slot) of each half.
        let touching = [[(0, 0), (1, 0)], [(1, 1), (2, 1)], [(2, 2), (0, 2)]];
        for j in 0..3 {
            for h in 0..2 {
                let (a, b) = ends(j, h);
                let l = (b[0] - a[0]).hypot(b[1] - a[1]);
                let n = [(b[1] - a[1]) / l, -(b[0] - a[0]) / l];
                let (sub, slot) = touching[j][h];
                let s = out.subs[sub].at[slot][0];
                let tn = [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]];
                let want = [0, 1].map(|c| (t[j][h][0][c] + t[j][h][1][c]) / 2.0);
                for k in 0..2 {
                    assert!((tn[k] - want[k]).abs() < 1e-11, "half {j}.{h}: {tn:?} against {want:?}");
                }
            }
        }
        assert!(out.energy > 0.0);
    }
}
