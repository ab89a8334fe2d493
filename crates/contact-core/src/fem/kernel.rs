//! The element stiffness over the two seams, for every element and law:
//!
//!   K_e = Σ_q w_q det J_q B_qᵀ D_q B_q
//!
//! with D_q the law's tangent (`constitutive`) and B_q from the element's
//! physical gradients (`reference`), column by column: `Strains` maps one
//! DOF (node i, component c) to its S strains. Plane: (xx, yy, xy); a body of
//! revolution adds the hoop strain N_i / r and the measure 2πr; a solid has
//! (xx, yy, zz, yz, xz, xy) with engineering shear.
//!
//! The P2–P0 element (`Integration::MeanDilatation`, Nagtegaal, Parks & Rice 1974;
//! Hughes 1980) integrates D − λ m mᵀ with the full rule and the volumetric
//! part λ m mᵀ on the element's mean dilatation θ̄ = ∫ m·ε dV / V, m the
//! strains whose sum is the volume change: the mixed element with its
//! constant pressure condensed out, inf-sup stable in 2D, which neither locks
//! nor makes the contact pressure oscillate as ν → ½ (measured on Hertz at
//! ν = 0.4999: node-to-node oscillation 0.51 of the peak with full
//! integration).
//!
//! Everything is generic over the element (dimension D, N nodes), the strains
//! (S) and the law, so each combination compiles to fixed-size loops with no
//! allocation per element. DOF order in `ke` (row-major, (D N)², only its leading block is written): u0x,
//! u0y, (u0z,) u1x, ...

use super::constitutive::Constitutive;
use super::reference::{physical_gradients, ReferenceElement};

/// The strains of one DOF: component `c` of a node whose shape function has
/// the value `n` and physical gradient `grad` at a point of radius `r`.
pub trait Strains<const D: usize, const S: usize> {
    /// m: the strains whose sum is the volume change.
    const VOLUME: [f64; S];
    /// Whether the measure is 2πr dA (a body of revolution) or dV.
    const RING: bool;
    fn column(c: usize, n: f64, grad: &[f64; D], r: f64) -> [f64; S];
}

/// Plane strains (xx, yy, xy): u_x gives (∂x, 0, ∂y), u_y gives (0, ∂y, ∂x).
#[derive(Debug, Clone, Copy)]
pub struct Plane;

/// Strains of a body of revolution on its r–z section (rr, zz, rz, θθ),
/// ε_θθ = u_r / r (see `axisymmetric`).
#[derive(Debug, Clone, Copy)]
pub struct Ring;

/// Solid strains (xx, yy, zz, yz, xz, xy), engineering shear.
#[derive(Debug, Clone, Copy)]
pub struct Solid;

impl Strains<2, 3> for Plane {
    const VOLUME: [f64; 3] = [1.0, 1.0, 0.0];
    const RING: bool = false;
    #[inline(always)]
    fn column(c: usize, _n: f64, g: &[f64; 2], _r: f64) -> [f64; 3] {
        if c == 0 {
            [g[0], 0.0, g[1]]
        } else {
            [0.0, g[1], g[0]]
        }
    }
}

impl Strains<2, 4> for Ring {
    const VOLUME: [f64; 4] = [1.0, 1.0, 0.0, 1.0];
    const RING: bool = true;
    #[inline(always)]
    fn column(c: usize, n: f64, g: &[f64; 2], r: f64) -> [f64; 4] {
        if c == 0 {
            [g[0], 0.0, g[1], n / r]
        } else {
            [0.0, g[1], g[0], 0.0]
        }
    }
}

impl Strains<3, 6> for Solid {
    const VOLUME: [f64; 6] = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
    const RING: bool = false;
    #[inline(always)]
    fn column(c: usize, _n: f64, g: &[f64; 3], _r: f64) -> [f64; 6] {
        match c {
            0 => [g[0], 0.0, 0.0, 0.0, g[2], g[1]],
            1 => [0.0, g[1], 0.0, g[2], 0.0, g[0]],
            _ => [0.0, 0.0, g[2], g[1], g[0], 0.0],
        }
    }
}

/// One quadrature point of an element: its measure w det J (times 2πr on a
/// ring) and the strain columns of every DOF, B[i][c].
struct At<const D: usize, const N: usize, const S: usize> {
    w: f64,
    b: [[[f64; S]; D]; N],
}

#[inline(always)]
fn at<E, K, const D: usize, const N: usize, const S: usize>(
    x: &[[f64; D]; N],
    xi: &[f64; D],
    weight: f64,
) -> At<D, N, S>
where
    E: ReferenceElement<D, N>,
    K: Strains<D, S>,
{
    let (n, g) = E::evaluate(xi);
    let (det, grad) = physical_gradients(x, &g);
    let w = weight * det;
    let (w, r) = if K::RING {
        let r: f64 = (0..N).map(|i| n[i] * x[i][0]).sum();
        (w * std::f64::consts::TAU * r, r)
    } else {
        (w, 1.0)
    };
    At {
        w,
        b: std::array::from_fn(|i| std::array::from_fn(|c| K::column(c, n[i], &grad[i], r))),
    }
}

/// u · v summed from the first term on (the order the plane kernel always had).
#[inline(always)]
fn dot<const S: usize>(u: &[f64; S], v: &[f64; S]) -> f64 {
    let mut s = u[0] * v[0];
    for i in 1..S {
        s += u[i] * v[i];
    }
    s
}

/// How an element integrates the volumetric part of D.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integration {
    /// All of D with the element's rule.
    Full,
    /// The P2–P0 element (module doc): D − λ m mᵀ with the element's rule,
    /// λ V b̄ b̄ᵀ on the mean dilatation θ̄ = b̄·u_e.
    MeanDilatation,
}

/// K_e of the element with nodes `x` for `law` (its tangent at ε = 0).
pub fn stiffness<E, K, L, const D: usize, const N: usize, const S: usize>(
    x: &[[f64; D]; N],
    law: &L,
    integration: Integration,
    ke: &mut [f64],
) where
    E: ReferenceElement<D, N>,
    K: Strains<D, S>,
    L: Constitutive<S>,
{
    let nd = D * N;
    let ke = &mut ke[..nd * nd];
    ke.fill(0.0);
    let d = law.tangent(&[0.0; S]);
    match integration {
        Integration::Full => add_stiffness::<E, K, D, N, S>(x, &d, ke),
        Integration::MeanDilatation => {
            let lambda = law.volumetric_lambda();
            add_stiffness::<E, K, D, N, S>(x, &deviatoric(&d, lambda, K::VOLUME), ke);
            let (bbar, volume) = mean_dilatation::<E, K, D, N, S>(x);
            for a in 0..nd {
                for b in a..nd {
                    ke[a * nd + b] += lambda * volume * bbar[a / D][a % D] * bbar[b / D][b % D];
                }
            }
        }
    }
    symmetrize(nd, ke);
}

/// D − λ m mᵀ: the part of D the P2–P0 element integrates with the full rule.
pub fn deviatoric<const S: usize>(d: &[[f64; S]; S], lambda: f64, m: [f64; S]) -> [[f64; S]; S] {
    std::array::from_fn(|i| std::array::from_fn(|j| d[i][j] - lambda * m[i] * m[j]))
}

/// b̄ (θ̄ = Σ b̄[i][c] u[i][c], the L2 projection of m·ε onto constants: the
/// P0 pressure's constraint) and the volume V = ∫ dV, over the element's rule.
///
/// On a ring m·ε r = r ∂N/∂r + N (or r ∂N/∂z) is quadratic on an affine T6,
/// which the 3-point rule integrates exactly. div u at the centroid is not
/// θ̄ there: on an element touching the axis r varies by O(1) of itself, so
/// the error does not shrink under refinement (the ball on a flat of the
/// test `axisymmetric::nearly_incompressible_ball_matches_hertz_on_the_axis`,
/// whose doc gives both readings).
pub fn mean_dilatation<E, K, const D: usize, const N: usize, const S: usize>(x: &[[f64; D]; N]) -> ([[f64; D]; N], f64)
where
    E: ReferenceElement<D, N>,
    K: Strains<D, S>,
{
    let mut bbar = [[0.0; D]; N];
    let mut volume = 0.0;
    for q in E::RULE {
        let p = at::<E, K, D, N, S>(x, &q.xi, q.weight);
        volume += p.w;
        for (bi, pb) in bbar.iter_mut().zip(&p.b) {
            for (b, col) in bi.iter_mut().zip(pb) {
                *b += p.w * dot(&K::VOLUME, col);
            }
        }
    }
    for b in bbar.iter_mut().flatten() {
        *b /= volume;
    }
    (bbar, volume)
}

/// The strain ε = B u_e at the reference point `xi` (u_e[i][c]: node i's
/// displacement component c).
pub fn strain<E, K, const D: usize, const N: usize, const S: usize>(
    x: &[[f64; D]; N],
    xi: &[f64; D],
    ue: &[[f64; D]; N],
) -> [f64; S]
where
    E: ReferenceElement<D, N>,
    K: Strains<D, S>,
{
    let p = at::<E, K, D, N, S>(x, xi, 1.0);
    let mut eps = [0.0; S];
    for (pb, u) in p.b.iter().zip(ue) {
        for (col, uc) in pb.iter().zip(u) {
            for (e, b) in eps.iter_mut().zip(col) {
                *e += b * uc;
            }
        }
    }
    eps
}

fn symmetrize(nd: usize, ke: &mut [f64]) {
    for a in 0..nd {
        for b in 0..a {
            ke[a * nd + b] = ke[b * nd + a];
        }
    }
}

/// Adds Σ_q w_q det J_q B_qᵀ D B_q (times 2π r_q on a ring) over the
/// element's rule to the upper triangle of `ke`.
#[inline(always)]
fn add_stiffness<E, K, const D: usize, const N: usize, const S: usize>(
    x: &[[f64; D]; N],
    d: &[[f64; S]; S],
    ke: &mut [f64],
) where
    E: ReferenceElement<D, N>,
    K: Strains<D, S>,
{
    let nd = D * N;
    for q in E::RULE {
        let p = at::<E, K, D, N, S>(x, &q.xi, q.weight);
        for a in 0..nd {
            let ba = &p.b[a / D][a % D];
            let dba: [f64; S] = std::array::from_fn(|i| dot(&d[i], ba));
            for b in a..nd {
                ke[a * nd + b] += p.w * dot(&p.b[b / D][b % D], &dba);
            }
        }
    }
}
