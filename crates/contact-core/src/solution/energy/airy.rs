//! A statically admissible stress on one triangle from tractions on its
//! sides: the Airy stress of a Hsieh–Clough–Tocher (HCT) function.
//!
//! In the plane every symmetric, divergence-free stress is σ = airy(φ):
//! σ_xx = φ_,yy, σ_yy = φ_,xx, σ_xy = −φ_,xy. Along a side traversed
//! counter-clockwise the traction t = σ n is the derivative of the rotated
//! gradient, d(φ_,y)/ds = t_x and d(φ_,x)/ds = −t_y, so φ and ∇φ on the
//! boundary follow from the tractions by integration; they close around the
//! triangle exactly when the tractions carry no net force and moment. An HCT
//! macro-element (a cubic on each of the three triangles made with the
//! centroid, C¹ across them) is fixed by φ and ∇φ at the corners and the
//! normal derivative at the side midpoints; with tractions linear on each
//! side those boundary values are a cubic (φ) and quadratics (∇φ), which the
//! HCT function reproduces, so its stress (linear on each sub-triangle: the
//! Johnson–Mercier element) carries exactly the given tractions and is in
//! equilibrium inside (Ciarlet, *The Finite Element Method for Elliptic
//! Problems*, §6.1; Johnson & Mercier, Numer. Math. 30, 1978).
//!
//! Length: about 570 lines, a third of them the tests that the stress
//! reproduces uniform and linear equilibrated fields and carries any
//! balanced tractions; the HCT element, its reference table and the Airy
//! walk are one construction.

/// Stress (xx, yy, xy) at the three side midpoints of each sub-triangle, and
/// the sub-triangle's area: what the midpoint rule (exact for quadratics)
/// needs to integrate the energy of σ − σ_h.
#[derive(Debug, Clone, Copy)]
pub struct SubStress {
    pub area: [f64; 3],
    pub at: [[[f64; 3]; 3]; 3],
    /// Mid-side points of each sub-triangle, where `at` is evaluated.
    pub points: [[[f64; 2]; 3]; 3],
    /// How far φ and ∇φ failed to close around the triangle, as a traction
    /// (|Δ∇φ| / h and |Δφ| / h², h the longest side; 0 for tractions in
    /// equilibrium).
    pub closure: f64,
    /// The largest traction given, the scale `closure` is read against.
    pub scale: f64,
}

/// Cubic monomials in (ξ, η) = (x − c) / h and their derivatives.
fn mono(q: [f64; 2]) -> [f64; 10] {
    let (x, y) = (q[0], q[1]);
    [
        1.0,
        x,
        y,
        x * x,
        x * y,
        y * y,
        x * x * x,
        x * x * y,
        x * y * y,
        y * y * y,
    ]
}
fn mono_x(q: [f64; 2]) -> [f64; 10] {
    let (x, y) = (q[0], q[1]);
    [0.0, 1.0, 0.0, 2.0 * x, y, 0.0, 3.0 * x * x, 2.0 * x * y, y * y, 0.0]
}
fn mono_y(q: [f64; 2]) -> [f64; 10] {
    let (x, y) = (q[0], q[1]);
    [0.0, 0.0, 1.0, 0.0, x, 2.0 * y, 0.0, x * x, 2.0 * x * y, 3.0 * y * y]
}
/// (φ_ξξ, φ_ηη, φ_ξη) rows.
fn mono_2(q: [f64; 2]) -> [[f64; 10]; 3] {
    let (x, y) = (q[0], q[1]);
    [
        [0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 6.0 * x, 2.0 * y, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 2.0 * x, 6.0 * y],
        [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 2.0 * x, 2.0 * y, 0.0],
    ]
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solves the 7 × 7 system `a` for `R` right-hand sides in place (partial
/// pivoting); false if singular.
fn solve7<const R: usize>(a: &mut [[f64; 7]; 7], b: &mut [[f64; R]; 7]) -> bool {
    for k in 0..7 {
        let p = (k..7)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap_or(k);
        if a[p][k].abs() < 1e-300 {
            return false;
        }
        a.swap(k, p);
        b.swap(k, p);
        let (pivot_row, pivot_rhs) = (a[k], b[k]);
        for (ai, bi) in a.iter_mut().zip(b.iter_mut()).skip(k + 1) {
            let f = ai[k] / pivot_row[k];
            if f == 0.0 {
                continue;
            }
            for (x, y) in ai.iter_mut().zip(&pivot_row).skip(k) {
                *x -= f * y;
            }
            for (x, y) in bi.iter_mut().zip(&pivot_rhs) {
                *x -= f * y;
            }
        }
    }
    for k in (0..7).rev() {
        let mut row = b[k];
        for (r, v) in row.iter_mut().enumerate() {
            let s: f64 = (k + 1..7).map(|j| a[k][j] * b[j][r]).sum();
            *v = (*v - s) / a[k][k];
        }
        b[k] = row;
    }
    true
}

pub(super) fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if det.abs() < 1e-300 {
        return None;
    }
    let col = |k: usize| {
        let mut m = a;
        for i in 0..3 {
            m[i][k] = b[i];
        }
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    Some([col(0) / det, col(1) / det, col(2) / det])
}

/// The cubics of the three sub-triangles (p[j], p[j+1], centroid), in the
/// monomials of (x − c) / h, of the HCT function with values `phi`,
/// gradients `grad` at the corners and normal derivatives `mid_dn` (along
/// each side's outward normal) at the side midpoints; h the longest side.
fn coefficients(p: &[[f64; 2]; 3], phi: [f64; 3], grad: [[f64; 2]; 3], mid_dn: [f64; 3]) -> Option<[[f64; 10]; 3]> {
    let c = [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0];
    let h = longest(p);
    let local = |x: [f64; 2]| [(x[0] - c[0]) / h, (x[1] - c[1]) / h];
    // Each sub-triangle j: coefficients a_j + Z_j z of its cubic, z = (φ,
    // h φ_x, h φ_y) at the centroid (the first three coefficients, since the
    // centroid is the local origin).
    let mut base = [[0.0; 10]; 3];
    let mut zcol = [[[0.0; 3]; 10]; 3];
    for j in 0..3 {
        let k = (j + 1) % 3;
        let (a, b) = (local(p[j]), local(p[k]));
        let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let l = (p[k][0] - p[j][0]).hypot(p[k][1] - p[j][1]);
        let n = [(p[k][1] - p[j][1]) / l, -(p[k][0] - p[j][0]) / l];
        let rows: [[f64; 10]; 7] = [
            mono(a),
            mono_x(a),
            mono_y(a),
            mono(b),
            mono_x(b),
            mono_y(b),
            std::array::from_fn(|q| n[0] * mono_x(m)[q] + n[1] * mono_y(m)[q]),
        ];
        let known = [
            phi[j],
            h * grad[j][0],
            h * grad[j][1],
            phi[k],
            h * grad[k][0],
            h * grad[k][1],
            h * mid_dn[j],
        ];
        let mut mat = [[0.0; 7]; 7];
        // Right-hand sides: the known data, then minus each z column.
        let mut rhs = [[0.0; 4]; 7];
        for i in 0..7 {
            mat[i].copy_from_slice(&rows[i][3..]);
            rhs[i][0] = known[i];
            for q in 0..3 {
                rhs[i][1 + q] = -rows[i][q];
            }
        }
        if !solve7(&mut mat, &mut rhs) {
            return None;
        }
        for q in 0..7 {
            base[j][3 + q] = rhs[q][0];
            for z in 0..3 {
                zcol[j][3 + q][z] = rhs[q][1 + z];
            }
        }
        for (z, row) in zcol[j].iter_mut().take(3).enumerate() {
            row[z] = 1.0;
        }
    }
    // C¹ across the inner side from p[j] to the centroid, shared by
    // sub-triangles j and j − 1: the normal derivative at its midpoint.
    let mut a3 = [[0.0; 3]; 3];
    let mut b3 = [0.0; 3];
    for j in 0..3 {
        let i = (j + 2) % 3;
        let q = local(p[j]);
        let mid = [q[0] / 2.0, q[1] / 2.0];
        let len = q[0].hypot(q[1]);
        let nu = [q[1] / len, -q[0] / len];
        let g: [f64; 10] = std::array::from_fn(|k| nu[0] * mono_x(mid)[k] + nu[1] * mono_y(mid)[k]);
        for z in 0..3 {
            a3[j][z] = (0..10).map(|k| g[k] * (zcol[j][k][z] - zcol[i][k][z])).sum();
        }
        b3[j] = -(dot(&g, &base[j]) - dot(&g, &base[i]));
    }
    let z = solve3(a3, b3)?;
    Some(std::array::from_fn(|j| {
        std::array::from_fn(|k| base[j][k] + (0..3).map(|w| zcol[j][k][w] * z[w]).sum::<f64>())
    }))
}

fn longest(p: &[[f64; 2]; 3]) -> f64 {
    (0..3)
        .map(|j| (p[(j + 1) % 3][0] - p[j][0]).hypot(p[(j + 1) % 3][1] - p[j][1]))
        .fold(0.0, f64::max)
}

const REFERENCE: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

/// The side midpoints of each sub-triangle of the reference triangle.
fn reference_points() -> [[[f64; 2]; 3]; 3] {
    let c = [1.0 / 3.0, 1.0 / 3.0];
    std::array::from_fn(|j| {
        let (a, b) = (REFERENCE[j], REFERENCE[(j + 1) % 3]);
        [
            [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0],
            [(b[0] + c[0]) / 2.0, (b[1] + c[1]) / 2.0],
            [(c[0] + a[0]) / 2.0, (c[1] + a[1]) / 2.0],
        ]
    })
}

/// Second derivatives (ξξ, ηη, ξη) of the twelve reference HCT basis
/// functions at the nine `reference_points`. An affine map carries the HCT
/// space of one triangle onto another's (cubics, the centroid split and C¹
/// all map), so every element reads its Hessians from this one table.
/// Degrees of freedom: φ, φ_ξ, φ_η at each corner, then the derivative
/// along each side's reference normal at its midpoint. Laid out by degree of
/// freedom, the 27 values of one (sub-triangle j, point q, component r at
/// 9 j + 3 q + r) in a row: `stress` sums the rows weighted by the degrees
/// of freedom, all 27 sums at once (independent, so they vectorise).
fn reference_table() -> &'static [[f64; 27]; 12] {
    static TABLE: std::sync::OnceLock<[[f64; 27]; 12]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let pts = reference_points();
        let h = longest(&REFERENCE);
        let c = [1.0 / 3.0, 1.0 / 3.0];
        let mut table = [[0.0; 27]; 12];
        for m in 0..12 {
            let mut phi = [0.0; 3];
            let mut grad = [[0.0; 2]; 3];
            let mut dn = [0.0; 3];
            match m {
                0..=8 => match m % 3 {
                    0 => phi[m / 3] = 1.0,
                    1 => grad[m / 3][0] = 1.0,
                    _ => grad[m / 3][1] = 1.0,
                },
                _ => dn[m - 9] = 1.0,
            }
            let coef = coefficients(&REFERENCE, phi, grad, dn).expect("the reference triangle");
            for j in 0..3 {
                for q in 0..3 {
                    let x = pts[j][q];
                    let d2 = mono_2([(x[0] - c[0]) / h, (x[1] - c[1]) / h]);
                    for r in 0..3 {
                        table[m][9 * j + 3 * q + r] = dot(&d2[r], &coef[j]) / (h * h);
                    }
                }
            }
        }
        table
    })
}

/// The Airy stress of the triangle `p` (counter-clockwise) whose side j, from
/// p[j] to p[j+1], carries the traction (force per length, acting on the
/// triangle) linear from `t[j][0]` at p[j] to `t[j][1]` at p[j+1]. The
/// tractions must be in equilibrium (net force and moment zero); `closure`
/// says how far they were. None for a degenerate triangle.
pub fn stress(p: &[[f64; 2]; 3], t: &[[[f64; 2]; 2]; 3]) -> Option<SubStress> {
    // φ and ∇φ at the corners, walking the sides from p[0] (φ = 0, ∇φ = 0
    // there: the Airy function is defined up to a linear part), and ∇φ at
    // each side's midpoint.
    let mut phi = [0.0; 4];
    let mut grad = [[0.0; 2]; 4];
    let mut mid = [[0.0; 2]; 3];
    let mut scale = 0.0_f64;
    let mut h = 0.0_f64;
    for j in 0..3 {
        let (a, b) = (p[j], p[(j + 1) % 3]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let l2 = d[0] * d[0] + d[1] * d[1];
        if l2 <= 0.0 {
            return None;
        }
        h = h.max(l2.sqrt());
        let rot = |v: [f64; 2]| [-v[1], v[0]];
        let (ta, tb) = (t[j][0], t[j][1]);
        scale = scale
            .max(ta[0].abs())
            .max(ta[1].abs())
            .max(tb[0].abs())
            .max(tb[1].abs());
        let g0 = grad[j];
        // With the side vector d = l s, l ∫ R t ds-terms read as d-products.
        let l = l2.sqrt();
        let whole = rot([(ta[0] + tb[0]) / 2.0, (ta[1] + tb[1]) / 2.0]);
        let half = rot([(3.0 * ta[0] + tb[0]) / 8.0, (3.0 * ta[1] + tb[1]) / 8.0]);
        let third = rot([ta[0] / 3.0 + tb[0] / 6.0, ta[1] / 3.0 + tb[1] / 6.0]);
        mid[j] = [g0[0] + l * half[0], g0[1] + l * half[1]];
        phi[j + 1] = phi[j] + dot(&g0, &d) + l * dot(&third, &d);
        grad[j + 1] = [g0[0] + l * whole[0], g0[1] + l * whole[1]];
    }
    // A plain root, not hypot (whose guard against overflow is slow, once per
    // element): the gap is a round-off-sized traction, far from overflow.
    let (gx, gy) = (grad[3][0] - grad[0][0], grad[3][1] - grad[0][1]);
    let closure = ((gx * gx + gy * gy).sqrt() / h).max((phi[3] - phi[0]).abs() / (h * h));
    let corner_grad = [grad[0], grad[1], grad[2]];
    let at = from_dofs(p, [phi[0], phi[1], phi[2]], corner_grad, mid)?;
    let a = [
        [p[1][0] - p[0][0], p[2][0] - p[0][0]],
        [p[1][1] - p[0][1], p[2][1] - p[0][1]],
    ];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let rp = reference_points();
    Some(SubStress {
        area: [det / 6.0; 3],
        at,
        points: std::array::from_fn(|j| {
            std::array::from_fn(|q| {
                let x = rp[j][q];
                [
                    p[0][0] + a[0][0] * x[0] + a[0][1] * x[1],
                    p[0][1] + a[1][0] * x[0] + a[1][1] * x[1],
                ]
            })
        }),
        closure,
        scale,
    })
}

/// The gradients at the side midpoints of the HCT function on `p` with
/// values `phi` and gradients `grad` at the corners whose gradient's part
/// along side j's normal at its midpoint is `normal[j]` (a vector along that
/// normal): the tangential part is the cubic's along the side, fixed by its
/// ends (Hermite: φ'(½) = 3/2 (φ_b − φ_a)/l − ¼ (∂_τφ_a + ∂_τφ_b)), so two
/// elements that share a side's corner data and its normal part share the
/// whole gradient there, and their HCT functions are C¹ across it.
pub fn mid_gradients(p: &[[f64; 2]; 3], phi: [f64; 3], grad: [[f64; 2]; 3], normal: [[f64; 2]; 3]) -> [[f64; 2]; 3] {
    std::array::from_fn(|j| {
        let k = (j + 1) % 3;
        let d = [p[k][0] - p[j][0], p[k][1] - p[j][1]];
        let l2 = d[0] * d[0] + d[1] * d[1];
        // With τ = d / l: (3/2 (φ_b − φ_a) / l − ¼ (∇φ_a + ∇φ_b)·d / l) d / l.
        let s = 1.5 * (phi[k] - phi[j]) / l2 - 0.25 * (dot(&grad[j], &d) + dot(&grad[k], &d)) / l2;
        [normal[j][0] + s * d[0], normal[j][1] + s * d[1]]
    })
}

/// The Airy stress (xx, yy, xy), at the nine points of `SubStress::at`, of
/// the HCT function on the triangle `p` (counter-clockwise) with values
/// `phi`, gradients `grad` at the corners and gradients `mid` at the side
/// midpoints (side j from p[j] to p[j+1]; their tangential parts those of
/// `mid_gradients`). Linear in the data: the stress of the tractions
/// (`stress`) and the patches' corrections (`patch`) are both made here.
/// None for a degenerate triangle.
pub fn from_dofs(
    p: &[[f64; 2]; 3],
    phi: [f64; 3],
    grad: [[f64; 2]; 3],
    mid: [[f64; 2]; 3],
) -> Option<[[[f64; 3]; 3]; 3]> {
    // x = p0 + A ξ: reference gradients are Aᵀ ∇φ, the reference normal
    // derivative at a midpoint is Aᵀ ∇φ there along the reference normal.
    let a = [
        [p[1][0] - p[0][0], p[2][0] - p[0][0]],
        [p[1][1] - p[0][1], p[2][1] - p[0][1]],
    ];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    if det <= 0.0 {
        return None;
    }
    let at = |g: [f64; 2]| [a[0][0] * g[0] + a[1][0] * g[1], a[0][1] * g[0] + a[1][1] * g[1]];
    let normals = [
        [0.0, -1.0],
        [std::f64::consts::FRAC_1_SQRT_2, std::f64::consts::FRAC_1_SQRT_2],
        [-1.0, 0.0],
    ];
    let mut dofs = [0.0; 12];
    for k in 0..3 {
        let g = at(grad[k]);
        dofs[3 * k] = phi[k];
        dofs[3 * k + 1] = g[0];
        dofs[3 * k + 2] = g[1];
        let gm = at(mid[k]);
        dofs[9 + k] = gm[0] * normals[k][0] + gm[1] * normals[k][1];
    }
    // H = A⁻ᵀ Ĥ A⁻¹.
    let inv = [[a[1][1] / det, -a[0][1] / det], [-a[1][0] / det, a[0][0] / det]];
    let table = reference_table();
    // The reference Hessians at the nine points, summed in the order of the
    // degrees of freedom; those that are 0 (φ and ∇φ at p[0] for the
    // tractions' walk, most of them for a patch's corrections) would add
    // nothing.
    let mut hess = [0.0; 27];
    for (d, row) in dofs.iter().zip(table) {
        if *d == 0.0 {
            continue;
        }
        for (h, t) in hess.iter_mut().zip(row) {
            *h += d * t;
        }
    }
    // (A⁻ᵀ Ĥ A⁻¹)_rs = Σ inv[k][r] Ĥ_kl inv[l][s] with Ĥ = [[ξξ, ξη], [ξη, ηη]]:
    // the map from (ξξ, ηη, ξη) to (xx, yy, xy), once per element.
    let map: [[f64; 3]; 3] = std::array::from_fn(|o| {
        let (r, s) = [(0, 0), (1, 1), (0, 1)][o];
        [
            inv[0][r] * inv[0][s],
            inv[1][r] * inv[1][s],
            inv[0][r] * inv[1][s] + inv[1][r] * inv[0][s],
        ]
    });
    let mut out = [[[0.0; 3]; 3]; 3];
    for j in 0..3 {
        for q in 0..3 {
            let hh = &hess[9 * j + 3 * q..9 * j + 3 * q + 3];
            let [pxx, pyy, pxy]: [f64; 3] =
                std::array::from_fn(|o| map[o][0] * hh[0] + map[o][1] * hh[1] + map[o][2] * hh[2]);
            out[j][q] = [pyy, pxx, -pxy];
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tractions σ n of a stress field on the sides of `p`.
    fn tractions(p: &[[f64; 2]; 3], sigma: impl Fn([f64; 2]) -> [f64; 3]) -> [[[f64; 2]; 2]; 3] {
        std::array::from_fn(|j| {
            let (a, b) = (p[j], p[(j + 1) % 3]);
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            let n = [(b[1] - a[1]) / l, -(b[0] - a[0]) / l];
            let t = |x: [f64; 2]| {
                let s = sigma(x);
                [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
            };
            [t(a), t(b)]
        })
    }

    const TRIANGLE: [[f64; 2]; 3] = [[0.3, -0.2], [2.1, 0.4], [0.7, 1.9]];

    /// A uniform stress is the Airy stress of a quadratic, which every HCT
    /// function reproduces: σ* must equal it at every point, to round-off.
    #[test]
    fn a_uniform_stress_is_reproduced() {
        let s0 = [1.3, -0.7, 0.45];
        let t = tractions(&TRIANGLE, |_| s0);
        let out = stress(&TRIANGLE, &t).expect("triangle");
        assert!(out.closure < 1e-13 * out.scale, "closure {}", out.closure);
        for sub in &out.at {
            for s in sub {
                for k in 0..3 {
                    assert!((s[k] - s0[k]).abs() < 1e-12, "{s:?} against {s0:?}");
                }
            }
        }
        let area: f64 = out.area.iter().sum();
        assert!((area - 0.5 * (1.8 * 2.1 - 0.4 * 0.6)).abs() < 1e-12);
    }

    /// A linear equilibrated stress is the Airy stress of a cubic, which the
    /// HCT space contains: reproduced exactly.
    #[test]
    fn a_linear_equilibrated_stress_is_reproduced() {
        // φ = x³ − 2 x²y + 0.5 xy² + 3y³ + x² − y²
        let sigma = |x: [f64; 2]| {
            let (a, b) = (x[0], x[1]);
            let pxx = 6.0 * a - 4.0 * b + 2.0;
            let pyy = a + 18.0 * b - 2.0;
            let pxy = -4.0 * a + b;
            [pyy, pxx, -pxy]
        };
        let t = tractions(&TRIANGLE, sigma);
        let out = stress(&TRIANGLE, &t).expect("triangle");
        assert!(out.closure < 1e-12 * out.scale, "closure {}", out.closure);
        for (sub, pts) in out.at.iter().zip(&out.points) {
            for (s, x) in sub.iter().zip(pts) {
                let e = sigma(*x);
                for k in 0..3 {
                    assert!((s[k] - e[k]).abs() < 1e-11, "{s:?} against {e:?} at {x:?}");
                }
            }
        }
    }

    /// Tractions that are not the trace of one linear field (each side its own
    /// linear load, in equilibrium) still give a stress whose traction on
    /// every side is the one given: checked through σ n at the side
    /// midpoints of the outer sub-sides, where the stress of the sub-triangle
    /// touching that side is evaluated.
    #[test]
    fn the_stress_carries_the_tractions_given() {
        let p = TRIANGLE;
        // Two sides loaded freely; the third side's linear traction is chosen
        // so that force and moment balance (3 conditions on its 4 values,
        // the fourth set to 0.2).
        let mut t = [[[0.5, -1.0], [0.1, 0.3]], [[-0.4, 0.9], [0.7, 0.2]], [[0.0; 2]; 2]];
        let (a, b) = (p[2], p[0]);
        let l2 = (b[0] - a[0]).hypot(b[1] - a[1]);
        // Force and moment about the origin of sides 0 and 1.
        let (mut fx, mut fy, mut m) = (0.0, 0.0, 0.0);
        for (j, tj) in t.iter().enumerate().take(2) {
            let (xa, xb) = (p[j], p[j + 1]);
            let l = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
            // ∫ over the side of a linear traction, and of x × t (exact with
            // the two-point Simpson's weights of a quadratic: ends and middle).
            let at = |s: f64| {
                let x = [xa[0] + s * (xb[0] - xa[0]), xa[1] + s * (xb[1] - xa[1])];
                let tt = [tj[0][0] * (1.0 - s) + tj[1][0] * s, tj[0][1] * (1.0 - s) + tj[1][1] * s];
                (tt, x[0] * tt[1] - x[1] * tt[0])
            };
            for (s, w) in [(0.0, 1.0), (0.5, 4.0), (1.0, 1.0)] {
                let (tt, mm) = at(s);
                fx += l * w / 6.0 * tt[0];
                fy += l * w / 6.0 * tt[1];
                m += l * w / 6.0 * mm;
            }
        }
        // Side 2 from a to b: unknowns (ta_x, ta_y, tb_x, tb_y), tb_y = 0.2.
        // Force: l/2 (ta + tb) = −(fx, fy); moment: ∫ x × t.
        let tb_y = 0.2;
        let ta_y = -2.0 * fy / l2 - tb_y;
        // Moment of side 2 with ta_x, tb_x unknown: linear in them; solve with
        // the force condition ta_x + tb_x = −2 fx / l2.
        let mom = |tax: f64, tbx: f64| {
            let mut mm = 0.0;
            for (s, w) in [(0.0, 1.0), (0.5, 4.0), (1.0, 1.0)] {
                let x = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                let tt = [tax * (1.0 - s) + tbx * s, ta_y * (1.0 - s) + tb_y * s];
                mm += l2 * w / 6.0 * (x[0] * tt[1] - x[1] * tt[0]);
            }
            mm
        };
        let sum = -2.0 * fx / l2;
        let (m0, m1) = (mom(0.0, sum), mom(1.0, sum - 1.0));
        let tax = (-m - m0) / (m1 - m0);
        t[2] = [[tax, ta_y], [sum - tax, tb_y]];
        let out = stress(&p, &t).expect("triangle");
        assert!(out.closure < 1e-12 * out.scale, "closure {}", out.closure);
        for j in 0..3 {
            let (xa, xb) = (p[j], p[(j + 1) % 3]);
            let l = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
            let n = [(xb[1] - xa[1]) / l, -(xb[0] - xa[0]) / l];
            // Point 0 of sub-triangle j is its outer side's midpoint.
            let s = out.at[j][0];
            let tn = [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]];
            let want = [(t[j][0][0] + t[j][1][0]) / 2.0, (t[j][0][1] + t[j][1][1]) / 2.0];
            for k in 0..2 {
                assert!((tn[k] - want[k]).abs() < 1e-11, "side {j}: {tn:?} against {want:?}");
            }
        }
    }
}
