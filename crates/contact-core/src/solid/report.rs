//! The contact answer of a solid as a report a reply can be written from:
//! its contact patches, every candidate point, the resultant, and the
//! certificate. Pure: the body, its rows and the `Contact` in, a
//! `SolidContactReport` out (no wire types).
//!
//! **In contact.** A row is in contact when its force λ_i > 0 (the LCP's
//! strict complementarity: an open row has λ_i = 0 exactly, a closed one a
//! positive force). A face of the contact face set is in contact when every
//! one of its rows is: its corners (T4 nodal rows sit at the corners; T10
//! dual mortar rows at the corners too). The pressure the rows describe is
//! Σ p_i Φ_i with Φ_i the corner hats (linear on a face; `obstacle`), so a
//! face with all corners pressed is pressed over all of it, and a face with
//! an open corner holds the patch's edge somewhere inside, which the rows
//! do not place more finely than one face. The faces in contact are thus
//! the inner bound of the patch: its area under-counts the true area by
//! about half a face's width along the outline; the rows' tributary area
//! Σ a_i is reported beside it (it counts a third of each face at an
//! edge node, on T4 exactly the area-weighted fraction of pressed corners).
//!
//! **Patches.** The rows in contact joined through the face set's edges
//! whose two corners are both in contact: a connected set of pressed rows,
//! and the faces in contact whose corners belong to it. Every row in
//! contact belongs to exactly one patch, so the patches' forces sum to the
//! total force. A patch may hold no whole face (a single pressed node, or a
//! line of them): its area is then 0 and its outline empty, the contact
//! being narrower than the mesh resolves. Two faces touching at a vertex
//! only belong to one patch (their shared row's force cannot be split).
//!
//! **Per patch.** Area: the sum of its faces' areas, the flat triangle's
//! on T4, the curved 6-node face's on T10 (`obstacle::face_area`: the area
//! the rows' a_i share). Force: Σ λ_i over its rows (each along its
//! row's normal: the plane's, or on a curved obstacle the normal at the
//! row's closest obstacle point). Centre of pressure: Σ λ_i x̄_i / Σ λ_i, with x̄_i = Σ_j c_ij x_j
//! the point where row i's force acts (the row's terms, summing to 1: the
//! node itself on T4 and, by biorthogonality, on flat T10 faces). Peak:
//! the largest pressure λ_i / a_i and its row's node. Outline: the edges
//! used by one face of the patch only, chained into closed polygons (with
//! the midside nodes on T10, so a curved edge is followed to second
//! order); each loop runs counter-clockwise seen from the obstacle (the faces'
//! outward orientation), so a hole's loop runs the other way. Where two
//! loops meet at one vertex the walk may join them into one.
//!
//! **Resultant.** F = Σ λ_i n_i and M = Σ x̄_i × λ_i n_i about the origin, in
//! the reference configuration (small strain): with the applied loads and
//! the support reactions, F and M balance to the certificate's equilibrium.
//!
//! Positions are the reference coordinates of the rows' nodes; gaps are
//! after deformation (`Contact::gap`).

use std::collections::HashMap;

use super::obstacle::{face_area, ObstacleRows};
use super::signorini::{Certificate, Contact};
use super::SolidBody;
use crate::error::CoreError;
use crate::mesh3d::{cross, Face};

/// A candidate row of the answer.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPoint {
    /// The row's node.
    pub node: usize,
    /// The node's reference position.
    pub position: [f64; 3],
    /// λ_i / a_i.
    pub pressure: f64,
    /// The gap after deformation.
    pub gap: f64,
    /// λ_i > 0.
    pub in_contact: bool,
}

/// A connected contact patch (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// Its rows, indices into `SolidContactReport::points`, ascending.
    pub rows: Vec<usize>,
    /// Its faces in contact (of the contact face set).
    pub faces: Vec<Face>,
    /// Σ of its faces' areas (curved on T10).
    pub area: f64,
    /// Σ a_i over its rows.
    pub tributary_area: f64,
    /// Σ λ_i over its rows: their normal forces' sum (against a plane,
    /// along its normal; against a curved obstacle, each along its row's
    /// normal, so a little more than the patch's resultant).
    pub force: f64,
    pub centre_of_pressure: [f64; 3],
    pub peak_pressure: f64,
    /// The node position of the row with the peak pressure.
    pub peak_at: [f64; 3],
    /// Closed polygons (the last point joins the first), one per boundary
    /// loop.
    pub outline: Vec<Vec<[f64; 3]>>,
}

/// The resultant of the contact forces on the body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resultant {
    pub force: [f64; 3],
    /// About the origin.
    pub moment: [f64; 3],
}

/// The contact answer of a solid on an obstacle (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct SolidContactReport {
    /// In the order of their first row.
    pub patches: Vec<Patch>,
    /// Every candidate row, in the rows' order.
    pub points: Vec<ContactPoint>,
    pub resultant: Resultant,
    pub certificate: Certificate,
    pub iterations: usize,
    pub converged: bool,
}

/// The report of `contact`, solved on `rows` for `body`; an error only if
/// the rows' face set is not the body's.
pub fn report(body: &SolidBody, rows: &ObstacleRows, contact: &Contact) -> Result<SolidContactReport, CoreError> {
    let mesh = body.mesh;
    let set = body.face_set(&rows.faces, "contact/faces")?;
    debug_assert_eq!(contact.lambda.len(), rows.len(), "the contact was solved on these rows");
    let row_of: HashMap<usize, usize> = rows.nodes.iter().enumerate().map(|(i, &v)| (v, i)).collect();
    let pressed = |i: usize| contact.lambda[i] > 0.0;
    let points: Vec<ContactPoint> = (0..rows.len())
        .map(|i| ContactPoint {
            node: rows.nodes[i],
            position: mesh.nodes[rows.nodes[i]],
            pressure: contact.pressure[i],
            gap: contact.gap[i],
            in_contact: pressed(i),
        })
        .collect();
    // Where each row's force acts: Σ_j c_ij x_j.
    let acts: Vec<[f64; 3]> = rows
        .terms
        .iter()
        .map(|t| std::array::from_fn(|c| t.iter().map(|&(v, w)| w * mesh.nodes[v][c]).sum()))
        .collect();
    let corner_rows = |f: &Face| f.corners.map(|v| row_of[&v]);
    // Connected pressed rows, through edges with both ends pressed.
    let mut parent: Vec<usize> = (0..rows.len()).collect();
    for f in set {
        let r = corner_rows(f);
        for k in 0..3 {
            let (a, b) = (r[k], r[(k + 1) % 3]);
            if pressed(a) && pressed(b) {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut patch_of_root: HashMap<usize, usize> = HashMap::new();
    let mut patches: Vec<Patch> = Vec::new();
    for i in (0..rows.len()).filter(|&i| pressed(i)) {
        let r = root(&mut parent, i);
        let p = *patch_of_root.entry(r).or_insert_with(|| {
            patches.push(empty_patch());
            patches.len() - 1
        });
        let patch = &mut patches[p];
        let l = contact.lambda[i];
        patch.rows.push(i);
        patch.force += l;
        patch.tributary_area += rows.area[i];
        (0..3).for_each(|c| patch.centre_of_pressure[c] += l * acts[i][c]);
        if contact.pressure[i] > patch.peak_pressure {
            patch.peak_pressure = contact.pressure[i];
            patch.peak_at = points[i].position;
        }
    }
    for f in set {
        let r = corner_rows(f);
        if r.iter().all(|&i| pressed(i)) {
            let p = patch_of_root[&root(&mut parent, r[0])];
            patches[p].area += face_area(mesh, f);
            patches[p].faces.push(*f);
        }
    }
    for patch in &mut patches {
        patch.centre_of_pressure = patch.centre_of_pressure.map(|v| v / patch.force);
        patch.outline = outline(&patch.faces, &mesh.nodes);
    }
    let force = (0..rows.len()).fold([0.0; 3], |f, i| {
        std::array::from_fn(|c| f[c] + contact.lambda[i] * rows.normal[i][c])
    });
    let moment = (0..rows.len()).fold([0.0; 3], |m, i| {
        let t = cross(acts[i], rows.normal[i].map(|c| contact.lambda[i] * c));
        [m[0] + t[0], m[1] + t[1], m[2] + t[2]]
    });
    Ok(SolidContactReport {
        patches,
        points,
        resultant: Resultant { force, moment },
        certificate: contact.certificate,
        iterations: contact.iterations,
        converged: contact.converged,
    })
}

fn empty_patch() -> Patch {
    Patch {
        rows: Vec::new(),
        faces: Vec::new(),
        area: 0.0,
        tributary_area: 0.0,
        force: 0.0,
        centre_of_pressure: [0.0; 3],
        peak_pressure: f64::NEG_INFINITY,
        peak_at: [0.0; 3],
        outline: Vec::new(),
    }
}

/// The representative of `i`'s set (union–find with path halving).
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// The boundary loops of a set of outward-oriented faces: each face's
/// edges p→q, q→r, r→p (with their midsides), those whose reverse no face
/// of the set uses, chained end to start.
fn outline(faces: &[Face], nodes: &[[f64; 3]]) -> Vec<Vec<[f64; 3]>> {
    let edges = |f: Face| (0..3).map(move |k| (f.corners[k], f.corners[(k + 1) % 3], f.mids.map(|m| m[k])));
    let mut inner: HashMap<(usize, usize), u32> = HashMap::new();
    for &f in faces {
        for (a, b, _) in edges(f) {
            *inner.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    // Boundary edges by their start; a start may have several at a pinch.
    let mut from: HashMap<usize, Vec<(usize, Option<usize>)>> = HashMap::new();
    let mut starts = Vec::new();
    for &f in faces {
        for (a, b, m) in edges(f) {
            if inner[&(a.min(b), a.max(b))] == 1 {
                from.entry(a).or_default().push((b, m));
                starts.push(a);
            }
        }
    }
    let mut loops = Vec::new();
    for s in starts {
        let mut at = s;
        let mut ring = Vec::new();
        while let Some((b, m)) = from.get_mut(&at).and_then(|out| out.pop()) {
            ring.push(nodes[at]);
            ring.extend(m.map(|m| nodes[m]));
            at = b;
            if at == s {
                break;
            }
        }
        if !ring.is_empty() {
            loops.push(ring);
        }
    }
    loops
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 square of unit cells, two triangles each, the middle cell
    /// left out: two loops, the outer of length 12 enclosing +9 (counter-
    /// clockwise seen from the faces' normal, +z), the hole's of length 4
    /// enclosing −1 (the other way round). Exact in binary.
    #[test]
    fn a_ring_of_faces_has_two_loops_of_opposite_senses() {
        let at = |i: usize, j: usize| 4 * j + i;
        let nodes: Vec<[f64; 3]> = (0..16).map(|n| [(n % 4) as f64, (n / 4) as f64, 0.0]).collect();
        let mut faces = Vec::new();
        for j in 0..3 {
            for i in (0..3).filter(|&i| (i, j) != (1, 1)) {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                for corners in [[a, b, c], [a, c, d]] {
                    faces.push(Face { corners, mids: None });
                }
            }
        }
        let mut loops: Vec<(f64, f64)> = outline(&faces, &nodes)
            .iter()
            .map(|ring| {
                let k = ring.len();
                let next = |i: usize| ring[(i + 1) % k];
                let length = (0..k).map(|i| (0..2).map(|c| (next(i)[c] - ring[i][c]).powi(2)).sum::<f64>().sqrt());
                let area = (0..k)
                    .map(|i| ring[i][0] * next(i)[1] - next(i)[0] * ring[i][1])
                    .sum::<f64>()
                    / 2.0;
                (length.sum(), area)
            })
            .collect();
        loops.sort_by(|a, b| b.0.total_cmp(&a.0));
        assert_eq!(loops, vec![(12.0, 9.0), (4.0, -1.0)]);
    }
}
