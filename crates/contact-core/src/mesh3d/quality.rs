//! Checks and assembly of user-given tetrahedral meshes (inline or read from
//! a Gmsh file): finite coordinates, index ranges, element orientation and
//! shape, T10 maps that do not fold and midsides shared along each edge, face
//! sets that are boundary faces.
//!
//! Orientation: an element of negative volume is refused, not renumbered.
//! Gmsh's 3D meshers write every tetrahedron with positive volume (unlike
//! its triangles, which the 2D reader turns counter-clockwise because a
//! surface may face −z), so a negative one means the connectivity follows
//! another convention (a mirrored mesh, another program's node order) or a
//! typing error. Renumbering would accept such a mesh silently, with its T10
//! midsides possibly in the other program's order too.
//!
//! A T10's isoparametric map x(ξ) = Σ xₙ Nₙ(ξ) must stay invertible. Its
//! Jacobian determinant is a quadratic polynomial in ξ, so positivity at
//! sampled points is necessary, not sufficient; we sample the 4 corners
//! (where a midside pulled across the element folds it first) and the 4
//! points of the degree-2 rule that integrates the stiffness, where a
//! negative det J would enter K directly.

use std::collections::{BTreeMap, HashMap};

use super::{signed_volume, sub, Face, Mesh3d, Order, EDGES, FACES};
use crate::error::{CoreError, InvalidKind};
use crate::fem::reference::{physical_gradients, ReferenceElement, T10};
use crate::mesh::overlap;
pub use crate::mesh::quality::Item;
use crate::mesh::quality::{check_used_and_connected, index_fault, inline_locate, Conn};

/// Smallest admissible ratio of an element's volume (and of det J / 6 at the
/// sampled points of a T10) to its longest edge cubed; a regular
/// tetrahedron has 0.118. The 2D check uses the same 1e-8 for area over
/// longest edge squared: below it the element stiffness loses all accuracy.
const MIN_SHAPE_RATIO: f64 = 1e-8;

/// Builds a mesh from inline data; `path` is the JSON pointer of the inline mesh.
pub fn try_inline(
    nodes: Vec<[f64; 3]>,
    elements: Conn,
    face_sets: &BTreeMap<String, Vec<[usize; 3]>>,
    path: &str,
) -> Result<Mesh3d, CoreError> {
    let locate = inline_locate(path, "face_sets");
    try_build(nodes, elements, face_sets, &locate)
}

/// The checks of `try_inline` for a mesh from any source: `locate` turns a
/// failing item into the error's JSON pointer and a prefix of its message
/// (an imported file names its own element tags there). Face sets are given
/// by their corners in any order; each comes out oriented by its element.
pub fn try_build(
    nodes: Vec<[f64; 3]>,
    elements: Conn,
    face_sets: &BTreeMap<String, Vec<[usize; 3]>>,
    locate: &dyn Fn(Item) -> (String, String),
) -> Result<Mesh3d, CoreError> {
    let bad = |item: Item, r: String| {
        let (p, context) = locate(item);
        CoreError::invalid(InvalidKind::Mesh, p, format!("{context}{r}"))
    };
    if nodes.len() < 4 {
        return Err(bad(Item::Nodes, "a mesh needs at least 4 nodes".into()));
    }
    if let Some(k) = nodes.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        return Err(bad(
            Item::Node(k),
            format!("node {k} has a coordinate that is not a finite number"),
        ));
    }
    if elements.is_empty() {
        return Err(bad(Item::Elements, "a mesh needs at least one element".into()));
    }
    let npe = elements.get(0).len();
    let order = match npe {
        4 => Order::T4,
        10 => Order::T10,
        k => {
            return Err(bad(
                Item::Element(0),
                format!("element has {k} nodes; expected 4 (T4) or 10 (T10)"),
            ))
        }
    };
    let mut elems = Vec::with_capacity(elements.len() * npe);
    for (e, el) in elements.iter().enumerate() {
        if let Err((k, why)) = index_fault(el, npe, nodes.len()) {
            return Err(bad(k.map_or(Item::Element(e), |k| Item::ElementNode(e, k)), why));
        }
        let mut x = [[0.0; 3]; 10];
        for (k, &n) in el.iter().enumerate() {
            x[k] = nodes[n];
        }
        check_shape(&x[..npe]).map_err(|r| bad(Item::Element(e), r))?;
        elems.extend_from_slice(el);
    }
    check_used_and_connected(nodes.len(), elements, &bad)?;
    let faces = |e: usize| {
        let t = &elems[npe * e..];
        FACES.map(|[p, q, r]| overlap::side_key([t[p], t[q], t[r]]))
    };
    if let Some(key) = overlap::overlapped_side(elements.len(), nodes.len(), faces) {
        let users = overlap::users(elements.len(), key, faces);
        let at = users.last().map_or(Item::Elements, |&e| Item::Element(e));
        return Err(bad(at, overlap::why("face", key, &users)));
    }
    if order == Order::T10 {
        check_shared_midsides(&elems, &bad)?;
    }
    let mesh = Mesh3d {
        order,
        nodes,
        elems,
        face_sets: BTreeMap::new(),
    };
    let face_sets = match_faces(&mesh, face_sets, &bad)?;
    Ok(Mesh3d { face_sets, ..mesh })
}

/// Why an element's shape is refused, or Ok: `x` are its nodes' coordinates.
fn check_shape(x: &[[f64; 3]]) -> Result<(), String> {
    let volume = signed_volume(x[0], x[1], x[2], x[3]);
    let longest = EDGES
        .iter()
        .map(|&[i, j]| {
            let d = sub(x[i], x[j]);
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
        .fold(0.0, f64::max);
    let floor = MIN_SHAPE_RATIO * longest.powi(3);
    // NaN (coordinates so large that differences overflow) is refused too.
    if volume.is_nan() || volume.abs() <= floor {
        // Ratios, not lengths: the coordinates here are nondimensional.
        return Err(format!(
            "degenerate element: its volume is {:.3e} of its longest edge cubed (at least {MIN_SHAPE_RATIO:.0e} is \
                needed)",
            volume.abs() / longest.powi(3).max(f64::MIN_POSITIVE)
        ));
    }
    if volume < 0.0 {
        return Err(
            "inverted element: its volume is negative; list the corners so that corner 3 lies on the side \
            of (p1 − p0) × (p2 − p0), as Gmsh writes them"
                .into(),
        );
    }
    if x.len() == 10 {
        let x: [[f64; 3]; 10] = std::array::from_fn(|i| x[i]);
        let corners = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let corners = corners
            .into_iter()
            .enumerate()
            .map(|(i, xi)| (format!("corner {i}"), xi));
        let rule = T10::RULE
            .iter()
            .enumerate()
            .map(|(i, q)| (format!("quadrature point {i}"), q.xi));
        for (at, xi) in corners.chain(rule) {
            let det = t10_det(&x, &xi) / 6.0;
            if det.is_nan() || det <= floor {
                return Err(format!(
                    "the element map folds: det J / 6 at its {at} is {:.3e} of its longest edge cubed (at least \
                        {MIN_SHAPE_RATIO:.0e} is needed); a midside node is too far from its edge's midpoint",
                    det / longest.powi(3)
                ));
            }
        }
    }
    Ok(())
}

/// det ∂x/∂ξ of a T10 at reference point `xi`: the element's own map
/// (`T10::evaluate`, `physical_gradients`).
fn t10_det(x: &[[f64; 3]; 10], xi: &[f64; 3]) -> f64 {
    let (_, g) = T10::evaluate(xi);
    physical_gradients(x, &g).0
}

/// Each edge has one midside node: two elements that share an edge but not
/// its midside leave a crack along it (their quadratic edges part).
fn check_shared_midsides(elems: &[usize], bad: &dyn Fn(Item, String) -> CoreError) -> Result<(), CoreError> {
    let mut mid: HashMap<(usize, usize), usize> = HashMap::with_capacity(elems.len() / 5);
    for (e, t) in elems.chunks_exact(10).enumerate() {
        for (k, &[i, j]) in EDGES.iter().enumerate() {
            let key = (t[i].min(t[j]), t[i].max(t[j]));
            let first = *mid.entry(key).or_insert(t[4 + k]);
            if first != t[4 + k] {
                return Err(bad(
                    Item::ElementNode(e, 4 + k),
                    format!(
                        "edge [{}, {}] has midside node {} here and {first} in an element before: the mesh is not \
                            conforming (share the midside node)",
                        key.0,
                        key.1,
                        t[4 + k]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The face sets as outward faces of their elements. Only the sets' faces are
/// looked up, so only they are kept: by sorted corners, the last element face
/// met and how many elements use it.
fn match_faces(
    mesh: &Mesh3d,
    face_sets: &BTreeMap<String, Vec<[usize; 3]>>,
    bad: &dyn Fn(Item, String) -> CoreError,
) -> Result<BTreeMap<String, Vec<Face>>, CoreError> {
    let key = |mut c: [usize; 3]| {
        c.sort_unstable();
        c
    };
    let mut wanted: HashMap<[usize; 3], (Option<Face>, usize)> =
        face_sets.values().flatten().map(|&c| (key(c), (None, 0))).collect();
    for e in 0..mesh.n_elems() {
        for k in 0..FACES.len() {
            let f = mesh.local_face(e, k);
            if let Some((owner, uses)) = wanted.get_mut(&f.key()) {
                *uses += 1;
                *owner = Some(f);
            }
        }
    }
    let mut sets = BTreeMap::new();
    for (name, faces) in face_sets {
        if faces.is_empty() {
            return Err(bad(Item::Set(name), "face set is empty".into()));
        }
        let mut out = Vec::with_capacity(faces.len());
        for (k, &c) in faces.iter().enumerate() {
            if let Some(&n) = c.iter().find(|&&n| n >= mesh.nodes.len()) {
                return Err(bad(
                    Item::Member(name, k),
                    format!("node {n} does not exist (the mesh has {} nodes)", mesh.nodes.len()),
                ));
            }
            match wanted.get(&key(c)) {
                Some(&(Some(face), 1)) => out.push(face),
                Some((Some(_), _)) => {
                    return Err(bad(
                        Item::Member(name, k),
                        format!("face {c:?} is interior (shared by two elements), not on the boundary"),
                    ))
                }
                _ => {
                    return Err(bad(
                        Item::Member(name, k),
                        format!("face {c:?} is not a face of any element"),
                    ))
                }
            }
        }
        sets.insert(name.clone(), out);
    }
    Ok(sets)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_t10(mid: [f64; 3]) -> [[f64; 3]; 10] {
        let c = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mut x: [[f64; 3]; 10] = std::array::from_fn(|i| {
            if i < 4 {
                c[i]
            } else {
                EDGES[i - 4]
                    .map(|j| c[j])
                    .into_iter()
                    .fold([0.0; 3], |a, p| [0, 1, 2].map(|k| a[k] + 0.5 * p[k]))
            }
        });
        x[4] = mid;
        x
    }

    /// A midside moved along its edge folds the map at the corner it moves
    /// toward once it passes the quarter point (where the quarter-point
    /// element's det J vanishes): with the midside of edge 0-1 at (t, 0, 0),
    /// det J at corner 0 is 4t − 1 (the 1D quadratic map's slope there).
    #[test]
    fn a_midside_past_the_quarter_point_folds_the_element() {
        assert!(check_shape(&unit_t10([0.5, 0.0, 0.0])).is_ok());
        assert!(check_shape(&unit_t10([0.3, 0.0, 0.0])).is_ok());
        assert!((t10_det(&unit_t10([0.3, 0.0, 0.0]), &[0.0; 3]) - 0.2).abs() < 1e-15);
        let msg = check_shape(&unit_t10([0.2, 0.0, 0.0])).unwrap_err();
        assert!(msg.contains("corner 0") && msg.contains("folds"), "{msg}");
        // Affine T10: det J = 6 V everywhere, so det J / 6 = 1/6.
        let x = unit_t10([0.5, 0.0, 0.0]);
        for xi in [[0.0; 3], T10::RULE[1].xi, [0.25; 3]] {
            assert!((t10_det(&x, &xi) - 1.0).abs() < 1e-15, "{xi:?}");
        }
    }
}
