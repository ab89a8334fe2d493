//! Patch-wise Airy corrections that lower the equilibrated stress's
//! complementary energy (the patch minimisation of Braess & Schöberl, Math.
//! Comp. 77, 2008, and of Ern & Vohralík, written with Airy functions).
//!
//! Every C¹ function ψ of the HCT space of a triangle mesh (a cubic on each
//! third of every triangle, `airy`) has an Airy stress airy(ψ) that is
//! symmetric, divergence-free and linear on each third, with a traction
//! continuous across every side (ψ ∈ H²). Along a boundary side traversed
//! counter-clockwise its traction is the derivative of the rotated gradient
//! (t_x = d(ψ_,y)/ds, t_y = −d(ψ_,x)/ds), so it carries none where ∇ψ is
//! constant along the side. The functions supported on the elements around
//! one vertex i (ψ and ∇ψ at i, ψ's normal derivative at the midpoints of
//! the sides through i; zero at the patch's outer vertices and on its outer
//! sides) then carry no traction on the patch's outer sides; on a side of
//! the body with a given traction (a load, a free surface, the contact
//! pressure p*, a bed's p*) they must carry none either, which with ∇ψ = 0
//! at the side's other end asks ψ = ∇ψ = 0 at i and a zero normal
//! derivative at the side's midpoint. Where both displacement components
//! are prescribed the traction is a reaction and ψ is free there; a side
//! with one component prescribed (a roller) is kept as a given one, which
//! is safe (fewer corrections, never an inadmissible one). So σ* + airy(ψ)
//! stays statically admissible for every such ψ, and its energy
//! Σ_K ‖σ* + airy(ψ) − σ_h‖²_{C⁻¹,K} over the patch's free degrees of
//! freedom is a small positive semi-definite quadratic (at most 3 + k
//! unknowns, k the free sides at i; k alone where i is on a given side),
//! minimised exactly: each step can only lower the bound, and a
//! Gauss–Seidel sweep over the vertices moves σ* towards the least
//! complementary energy over the patches' span. That span is smaller than
//! all admissible piecewise-linear stresses on the split (the Johnson–Mercier
//! optimum): it leaves out a ψ whose gradient is a nonzero constant along a
//! given side between two held parts (the resultant moving between
//! supports) and every ψ on a roller's side.
//!
//! The mesh here is any triangle mesh whose every triangle is an HCT
//! macro-element: the linear triangles themselves (`equilibrate`), or each
//! quadratic triangle's four sub-triangles (`quadratic`, `split`).
//!
//! Length: about 540 lines, half of them the tests (a correction's zero
//! tractions, a patch removing its own correction, monotonicity); the
//! patch's degrees of freedom, its system and the residuals' update are one
//! step.

use super::airy;
use super::numbering::{factor_psd, solve_factored, Numbering, NONE};
use std::collections::HashSet;

/// The share of the vertices whose patches are relaxed: those holding the
/// most energy, largest first. The largest share whose whole estimate stays
/// under its mark of 30 % of the solve: at 10 % it measured 31 % on the
/// Hertz examples, at 5 % 19–26 % on the four 2D examples (the measured
/// effectivity against share and time is kept in one place, the
/// verification page's "The energy bound").
pub(super) const SHARE: f64 = 0.05;

/// σ* − σ_h of one triangle at the nine points of `airy::SubStress::at`
/// (three per third, (xx, yy, xy)): what the midpoint rule, exact for the
/// quadratic energy density of a linear difference, integrates.
pub(super) type Residual = [[[f64; 3]; 3]; 3];

/// One free degree of freedom of a vertex's patch.
#[derive(Clone, Copy, PartialEq)]
enum Dof {
    /// ψ (0) or ψ_,x (1) or ψ_,y (2) at the vertex.
    Vertex(usize),
    /// ψ's derivative along the side's normal at its midpoint.
    Side(usize),
}

/// The residuals of a mesh's triangles and what the patches' corrections
/// need to lower them.
pub(super) struct Patches<'a> {
    nodes: &'a [[f64; 2]],
    /// Each triangle's corners, counter-clockwise (the order its residual's
    /// points follow).
    tris: &'a [[u32; 3]],
    num: &'a Numbering,
    compliance: [[f64; 3]; 3],
    /// Whether ψ and ∇ψ may move at a vertex (no boundary side with a given
    /// traction touches it).
    vertex_free: Vec<bool>,
    /// Whether the normal derivative may move at a side's midpoint (inside,
    /// or on a boundary side whose both components are held).
    side_free: Vec<bool>,
    pub(super) residual: Vec<Residual>,
    // Reused buffers: the patch's columns, each triangle's stress of each
    // column (None where the column does not reach it), the system.
    dofs: Vec<Dof>,
    basis: Vec<Option<Residual>>,
    h: Vec<f64>,
    g: Vec<f64>,
    skip: Vec<bool>,
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl<'a> Patches<'a> {
    /// `held`: the boundary sides (by their sorted corners) whose both
    /// displacement components are prescribed.
    pub(super) fn new(
        nodes: &'a [[f64; 2]],
        tris: &'a [[u32; 3]],
        num: &'a Numbering,
        compliance: [[f64; 3]; 3],
        held: &HashSet<[usize; 2]>,
        residual: Vec<Residual>,
    ) -> Self {
        let mut vertex_free = vec![true; nodes.len()];
        let side_free: Vec<bool> = num
            .sides
            .iter()
            .map(|s| {
                if s.elems[1] != NONE {
                    return true;
                }
                let key = [s.ends[0].min(s.ends[1]), s.ends[0].max(s.ends[1])];
                let free = held.contains(&key);
                if !free {
                    vertex_free[s.ends[0]] = false;
                    vertex_free[s.ends[1]] = false;
                }
                free
            })
            .collect();
        Self {
            nodes,
            tris,
            num,
            compliance,
            vertex_free,
            side_free,
            residual,
            dofs: Vec::new(),
            basis: Vec::new(),
            h: Vec::new(),
            g: Vec::new(),
            skip: Vec::new(),
        }
    }

    fn corners(&self, k: usize) -> [[f64; 2]; 3] {
        self.tris[k].map(|n| self.nodes[n as usize])
    }

    /// ∫_K r : C⁻¹ r of triangle k's residual.
    pub(super) fn energy(&self, k: usize) -> f64 {
        let p = self.corners(k);
        let w = cross(
            [p[1][0] - p[0][0], p[1][1] - p[0][1]],
            [p[2][0] - p[0][0], p[2][1] - p[0][1]],
        ) / 18.0;
        let r = &self.residual[k];
        w * r.iter().flatten().map(|s| self.inner(s, s)).sum::<f64>()
    }

    fn inner(&self, a: &[f64; 3], b: &[f64; 3]) -> f64 {
        let c = &self.compliance;
        (0..3).map(|r| a[r] * (0..3).map(|s| c[r][s] * b[s]).sum::<f64>()).sum()
    }

    /// The stress of degree of freedom `dof` of vertex `v` on triangle k,
    /// None where it does not reach k.
    fn column(&self, k: usize, v: usize, dof: Dof) -> Option<Residual> {
        let p = self.corners(k);
        let a = self.tris[k].iter().position(|&n| n as usize == v)?;
        let (mut phi, mut grad, mut normal) = ([0.0; 3], [[0.0; 2]; 3], [[0.0; 2]; 3]);
        match dof {
            Dof::Vertex(0) => phi[a] = 1.0,
            Dof::Vertex(c) => grad[a][c - 1] = 1.0,
            Dof::Side(id) => {
                let j = self.num.elem_sides[k].iter().position(|&s| s == id)?;
                normal[j] = self.num.sides[id].normal;
            }
        }
        let mid = airy::mid_gradients(&p, phi, grad, normal);
        airy::from_dofs(&p, phi, grad, mid)
    }

    /// The free degrees of freedom of vertex v's patch.
    fn free_dofs(&self, v: usize, dofs: &mut Vec<Dof>) {
        dofs.clear();
        if self.vertex_free[v] {
            dofs.extend([Dof::Vertex(0), Dof::Vertex(1), Dof::Vertex(2)]);
        }
        for &k in self.num.elems_at(v) {
            for &id in &self.num.elem_sides[k as usize] {
                if self.side_free[id] && self.num.sides[id].ends.contains(&v) && !dofs.contains(&Dof::Side(id)) {
                    dofs.push(Dof::Side(id));
                }
            }
        }
    }

    /// Minimises the patch of vertex v's energy over its free corrections
    /// and adds the least one to its triangles' residuals; returns the
    /// energy's change (≤ 0).
    pub(super) fn relax(&mut self, v: usize) -> f64 {
        let num = self.num;
        let elems = num.elems_at(v);
        if elems.is_empty() {
            return 0.0;
        }
        let mut dofs = std::mem::take(&mut self.dofs);
        self.free_dofs(v, &mut dofs);
        let n = dofs.len();
        if n == 0 {
            self.dofs = dofs;
            return 0.0;
        }
        let mut basis = std::mem::take(&mut self.basis);
        basis.clear();
        let (mut h, mut g) = (std::mem::take(&mut self.h), std::mem::take(&mut self.g));
        h.clear();
        h.resize(n * n, 0.0);
        g.clear();
        g.resize(n, 0.0);
        for &k in elems {
            let k = k as usize;
            let p = self.corners(k);
            let w = cross(
                [p[1][0] - p[0][0], p[1][1] - p[0][1]],
                [p[2][0] - p[0][0], p[2][1] - p[0][1]],
            ) / 18.0;
            let start = basis.len();
            for &d in &dofs {
                basis.push(self.column(k, v, d));
            }
            let cols = &basis[start..];
            for (i, bi) in cols.iter().enumerate() {
                let Some(bi) = bi else { continue };
                let mut ci = [[0.0; 3]; 9];
                for (t, s) in ci.iter_mut().zip(bi.iter().flatten()) {
                    *t = std::array::from_fn(|r| (0..3).map(|c| self.compliance[r][c] * s[c]).sum());
                }
                let dot = |b: &Residual| -> f64 {
                    b.iter()
                        .flatten()
                        .zip(&ci)
                        .map(|(s, t)| s[0] * t[0] + s[1] * t[1] + s[2] * t[2])
                        .sum()
                };
                g[i] += w * dot(&self.residual[k]);
                for (j, bj) in cols.iter().enumerate().take(i + 1) {
                    if let Some(bj) = bj {
                        let v = w * dot(bj);
                        h[i * n + j] += v;
                        if j != i {
                            h[j * n + i] += v;
                        }
                    }
                }
            }
        }
        // The least energy: H x = −g (H only semi-definite where a patch's
        // functions include a linear one, which makes no stress).
        // Scaled to a unit diagonal first: ψ's and ∇ψ's columns differ by
        // powers of the element size, which the factor's relative pivot
        // test would otherwise read as null.
        let d: Vec<f64> = (0..n)
            .map(|i| {
                if h[i * n + i] > 0.0 {
                    1.0 / h[i * n + i].sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        let mut x: Vec<f64> = (0..n).map(|i| -g[i] * d[i]).collect();
        let mut m: Vec<f64> = (0..n * n).map(|ij| h[ij] * d[ij / n] * d[ij % n]).collect();
        factor_psd(&mut m, n, &mut self.skip);
        solve_factored(&m, &self.skip, &mut x, n);
        for (xi, di) in x.iter_mut().zip(&d) {
            *xi *= di;
        }
        // The change 2 gᵀx + xᵀ H x = gᵀx at the minimum; a step that would
        // not lower it (round-off on a patch already at its least) is left.
        let hx: f64 = (0..n)
            .map(|i| x[i] * (0..n).map(|j| h[i * n + j] * x[j]).sum::<f64>())
            .sum();
        let change = 2.0 * g.iter().zip(&x).map(|(a, b)| a * b).sum::<f64>() + hx;
        if change < 0.0 {
            for (e, &k) in elems.iter().enumerate() {
                let r = &mut self.residual[k as usize];
                for (col, xi) in basis[e * n..(e + 1) * n].iter().zip(&x) {
                    let Some(b) = col else { continue };
                    for (rs, bs) in r.iter_mut().flatten().zip(b.iter().flatten()) {
                        for c in 0..3 {
                            rs[c] += xi * bs[c];
                        }
                    }
                }
            }
        }
        self.dofs = dofs;
        self.basis = basis;
        self.h = h;
        self.g = g;
        change.min(0.0)
    }

    /// Relaxes the patches of the `share` of the vertices whose patches
    /// hold the most energy, the largest first (each once: a partial
    /// Gauss–Seidel sweep; `SHARE` says why not all).
    pub(super) fn relax_largest(&mut self, share: f64) {
        if share <= 0.0 {
            return;
        }
        let energy: Vec<f64> = (0..self.tris.len()).map(|k| self.energy(k)).collect();
        let num = self.num;
        let mut order: Vec<(f64, u32)> = (0..self.nodes.len())
            .filter_map(|v| {
                let elems = num.elems_at(v);
                (!elems.is_empty()).then(|| (elems.iter().map(|&k| energy[k as usize]).sum(), v as u32))
            })
            .collect();
        let n = ((share * order.len() as f64).ceil() as usize).min(order.len());
        if n == 0 {
            return;
        }
        let larger = |a: &(f64, u32), b: &(f64, u32)| b.0.total_cmp(&a.0);
        if n < order.len() {
            order.select_nth_unstable_by(n - 1, larger);
            order.truncate(n);
        }
        order.sort_unstable_by(larger);
        for (_, v) in order {
            self.relax(v as usize);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::compliance;
    use super::*;

    /// A square of eight triangles around an inner node (corners
    /// counter-clockwise); its left side (x = 0: sides 0–3 and 3–6) held.
    type Mesh = (Vec<[f64; 2]>, Vec<[u32; 3]>, HashSet<[usize; 2]>);

    fn square() -> Mesh {
        let nodes = super::super::fixtures::square_nodes();
        let tris = vec![
            [0, 1, 4],
            [0, 4, 3],
            [1, 2, 5],
            [1, 5, 4],
            [3, 4, 7],
            [3, 7, 6],
            [4, 5, 8],
            [4, 8, 7],
        ];
        (nodes, tris, HashSet::from([[0, 3], [3, 6]]))
    }

    /// The correction of vertex v with coefficients 0.3 + 0.17 i, 0.9 − 0.2 i
    /// (any combination of the patch's free functions), per triangle.
    fn correction(p: &Patches, v: usize) -> Vec<Residual> {
        let mut dofs = Vec::new();
        p.free_dofs(v, &mut dofs);
        (0..p.tris.len())
            .map(|k| {
                let mut r = [[[0.0; 3]; 3]; 3];
                for (i, &d) in dofs.iter().enumerate() {
                    let x = if i % 2 == 0 {
                        0.3 + 0.17 * i as f64
                    } else {
                        0.9 - 0.2 * i as f64
                    };
                    if let Some(b) = p.column(k, v, d) {
                        for (rs, bs) in r.iter_mut().flatten().zip(b.iter().flatten()) {
                            (0..3).for_each(|c| rs[c] += x * bs[c]);
                        }
                    }
                }
                r
            })
            .collect()
    }

    /// The traction of a residual on side j of triangle k at both its ends:
    /// third j of the HCT split touches the side, its stress is linear and
    /// known at its three side midpoints (m01, m12, m20 of p[j], p[j+1], the
    /// centroid), so at p[j] it is m01 + m20 − m12 and at p[j+1]
    /// m01 + m12 − m20.
    fn side_tractions(p: &Patches, r: &Residual, k: usize, j: usize) -> [[f64; 2]; 2] {
        let id = p.num.elem_sides[k][j];
        let sign = if p.num.sides[id].elems[0] == k { 1.0 } else { -1.0 };
        let n = p.num.sides[id].normal.map(|x| sign * x);
        let m = &r[j];
        let at = |a: usize, b: usize, c: usize| -> [f64; 2] {
            let s: [f64; 3] = std::array::from_fn(|i| m[a][i] + m[b][i] - m[c][i]);
            [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
        };
        [at(0, 2, 1), at(0, 1, 2)]
    }

    /// Every vertex's correction carries no traction on its patch's outer
    /// sides nor on any boundary side whose traction is given (pointwise, at
    /// both ends of the linear traction, to round-off of the stress's
    /// scale), so σ* + airy(ψ) stays admissible; on the held side its
    /// reaction is a self-equilibrated one (no net force or moment: the
    /// correction is divergence-free and carries nothing elsewhere), and at
    /// the held side's middle vertex it is not zero (the reactions do move).
    #[test]
    fn a_correction_carries_no_traction_where_it_is_given() {
        let (nodes, tris, held) = square();
        let num = Numbering::new(&nodes, &tris);
        let p = Patches::new(
            &nodes,
            &tris,
            &num,
            compliance(),
            &held,
            vec![[[[0.0; 3]; 3]; 3]; tris.len()],
        );
        for v in 0..nodes.len() {
            let r = correction(&p, v);
            let scale = r
                .iter()
                .flatten()
                .flatten()
                .flatten()
                .fold(0.0_f64, |m, x| m.max(x.abs()));
            // Corner 2 has one element, both its sides through 2 loaded: its
            // patch has no free function; every other vertex has some.
            assert_eq!(scale == 0.0, v == 2, "vertex {v}: {scale}");
            if v == 2 {
                continue;
            }
            let (mut force, mut moment, mut reaction) = ([0.0; 2], 0.0, 0.0_f64);
            for k in 0..tris.len() {
                for j in 0..3 {
                    let id = num.elem_sides[k][j];
                    let side = &num.sides[id];
                    let t = side_tractions(&p, &r[k], k, j);
                    let key = [side.ends[0].min(side.ends[1]), side.ends[0].max(side.ends[1])];
                    let outer = !tris[k].contains(&(v as u32));
                    let boundary = side.elems[1] == NONE;
                    if boundary && held.contains(&key) {
                        // ∫ t and ∫ x × t of a linear traction (Simpson).
                        let (a, b) = (nodes[tris[k][j] as usize], nodes[tris[k][(j + 1) % 3] as usize]);
                        let xm = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                        let tm = [(t[0][0] + t[1][0]) / 2.0, (t[0][1] + t[1][1]) / 2.0];
                        for c in 0..2 {
                            force[c] += side.len * tm[c];
                        }
                        moment += side.len / 6.0 * (cross(a, t[0]) + 4.0 * cross(xm, tm) + cross(b, t[1]));
                        reaction = reaction.max(t.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs())));
                    } else if outer || boundary {
                        for tt in t.iter().flatten() {
                            assert!(tt.abs() < 1e-11 * scale, "vertex {v}, element {k}, side {j}: {t:?}");
                        }
                    }
                }
            }
            for f in force.iter().chain([&moment]) {
                assert!(
                    f.abs() < 1e-11 * scale,
                    "vertex {v}: net force {force:?}, moment {moment}"
                );
            }
            if v == 3 {
                assert!(
                    reaction > 1e-3 * scale,
                    "the held side's middle vertex moves the reaction"
                );
            }
        }
    }

    /// A residual that is itself one patch's correction is removed by that
    /// patch's minimisation (its energy falls to round-off): the patch's
    /// quadratic is the energy's, solved exactly.
    #[test]
    fn a_patch_removes_its_own_correction() {
        let (nodes, tris, held) = square();
        let num = Numbering::new(&nodes, &tris);
        for v in [0, 3, 4, 5] {
            let zero = vec![[[[0.0; 3]; 3]; 3]; tris.len()];
            let r = correction(&Patches::new(&nodes, &tris, &num, compliance(), &held, zero), v);
            let mut p = Patches::new(&nodes, &tris, &num, compliance(), &held, r);
            let before: f64 = (0..tris.len()).map(|k| p.energy(k)).sum();
            let change = p.relax(v);
            let after: f64 = (0..tris.len()).map(|k| p.energy(k)).sum();
            assert!(
                before > 0.0 && after < 1e-20 * before,
                "vertex {v}: {before} to {after}"
            );
            assert!(
                (before + change - after).abs() < 1e-12 * before,
                "vertex {v}: change {change}"
            );
        }
    }

    /// Relaxing the vertices in turn (two sweeps) never raises the energy of
    /// an arbitrary residual, and each step's change is the one it reports
    /// (the quadratic's value at its minimum): every step keeps the bound a
    /// bound and can only tighten it.
    #[test]
    fn relaxing_never_raises_the_energy() {
        let (nodes, tris, held) = square();
        let num = Numbering::new(&nodes, &tris);
        let residual: Vec<Residual> = (0..tris.len())
            .map(|k| {
                std::array::from_fn(|a| {
                    std::array::from_fn(|b| std::array::from_fn(|c| ((k * 27 + a * 9 + b * 3 + c) as f64 * 1.7).sin()))
                })
            })
            .collect();
        let mut p = Patches::new(&nodes, &tris, &num, compliance(), &held, residual);
        let total = |p: &Patches| (0..tris.len()).map(|k| p.energy(k)).sum::<f64>();
        let start = total(&p);
        let mut last = start;
        for _ in 0..2 {
            for v in 0..nodes.len() {
                let change = p.relax(v);
                let now = total(&p);
                assert!(
                    change <= 0.0 && now <= last * (1.0 + 1e-14),
                    "vertex {v}: {last} to {now}"
                );
                assert!(
                    (last + change - now).abs() < 1e-12 * start,
                    "vertex {v}: change {change}"
                );
                last = now;
            }
        }
        // A residual of arbitrary values is mostly not divergence-free, which
        // no Airy correction removes: it falls by 8 % here.
        assert!(last < 0.95 * start, "the sweeps lower the energy: {start} to {last}");
    }
}
