//! Checks and assembly of user-given (inline) meshes: index ranges, element
//! orientation and shape, edge sets that are real boundary edges. The checks
//! that do not depend on the dimension (`Item`, `Conn`, `index_fault`,
//! `check_used_and_connected`) serve the tetrahedral meshes too
//! (`mesh3d::quality`).

use std::collections::{BTreeMap, HashMap};

use super::{overlap, signed_area, Edge, Mesh2d, Order};
use crate::error::{CoreError, InvalidKind};

/// Smallest admissible ratio of an element's area to its longest edge squared
/// (≈ 1.7e-6 corresponds to a minimum angle of about 2e-4 degrees): below it the
/// element stiffness loses all accuracy.
const MIN_SHAPE_RATIO: f64 = 1e-8;

/// A part of a user-given mesh, to say where a check failed.
#[derive(Debug, Clone, Copy)]
pub enum Item<'a> {
    Nodes,
    /// Node k.
    Node(usize),
    Elements,
    Element(usize),
    /// Local node `k` of element `e`.
    ElementNode(usize, usize),
    /// A named edge set (2D) or face set (3D).
    Set(&'a str),
    /// Edge or face `k` of the named set.
    Member(&'a str, usize),
}

/// Element connectivity as it was read, without a list per element (72 bytes
/// each): every element's nodes one after the other, `per` nodes each (a Gmsh
/// file) or ending at `ends` (inline JSON, where any length may come).
#[derive(Debug, Clone, Copy)]
pub enum Conn<'a> {
    Ragged { nodes: &'a [usize], ends: &'a [usize] },
    Flat { nodes: &'a [usize], per: usize },
}

impl<'a> Conn<'a> {
    pub fn len(&self) -> usize {
        match *self {
            Conn::Ragged { ends, .. } => ends.len(),
            Conn::Flat { nodes, per } => nodes.len() / per.max(1),
        }
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    pub fn get(&self, e: usize) -> &'a [usize] {
        match *self {
            Conn::Ragged { nodes, ends } => &nodes[if e == 0 { 0 } else { ends[e - 1] }..ends[e]],
            Conn::Flat { nodes, per } => &nodes[e * per..(e + 1) * per],
        }
    }
    pub fn iter(&self) -> impl Iterator<Item = &'a [usize]> + '_ {
        (0..self.len()).map(|e| self.get(e))
    }
}

/// Builds a mesh from inline data; `path` is the JSON pointer of the inline mesh.
pub fn try_inline(
    nodes: Vec<[f64; 2]>,
    elements: Conn,
    edge_sets: &BTreeMap<String, Vec<[usize; 2]>>,
    path: &str,
) -> Result<Mesh2d, CoreError> {
    let locate = inline_locate(path, "edge_sets");
    try_build(nodes, elements, edge_sets, &locate)
}

/// Where an item of the inline mesh at `path` is: its JSON pointer (`sets`:
/// the field of the named sets, `edge_sets` or `face_sets`), no message prefix.
pub fn inline_locate<'a>(path: &'a str, sets: &'a str) -> impl Fn(Item) -> (String, String) + 'a {
    move |item: Item| {
        let p = match item {
            Item::Nodes => format!("{path}/nodes"),
            Item::Node(k) => format!("{path}/nodes/{k}"),
            Item::Elements => format!("{path}/elements"),
            Item::Element(e) => format!("{path}/elements/{e}"),
            Item::ElementNode(e, k) => format!("{path}/elements/{e}/{k}"),
            Item::Set(name) => format!("{path}/{sets}/{name}"),
            Item::Member(name, k) => format!("{path}/{sets}/{name}/{k}"),
        };
        (p, String::new())
    }
}

/// What is wrong with the node indices of an element `el` of a mesh of
/// `n_nodes` nodes whose first element has `npe` (at most 10): the local
/// node at fault (None: the element as a whole) and why; Ok if nothing.
pub fn index_fault(el: &[usize], npe: usize, n_nodes: usize) -> Result<(), (Option<usize>, String)> {
    if el.len() != npe {
        return Err((
            None,
            format!(
                "element has {} nodes but element 0 has {npe}; mixed orders are not supported",
                el.len()
            ),
        ));
    }
    if let Some((k, &n)) = el.iter().enumerate().find(|(_, &n)| n >= n_nodes) {
        return Err((
            Some(k),
            format!("node index {n} out of range (mesh has {n_nodes} nodes)"),
        ));
    }
    let mut sorted = [0; 10];
    let sorted = &mut sorted[..npe];
    sorted.copy_from_slice(el);
    sorted.sort_unstable();
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Err((None, "element repeats a node".into()));
    }
    Ok(())
}

/// The checks of `try_inline` for a mesh from any source: `locate` turns a
/// failing item into the error's JSON pointer and a prefix of its message
/// (an imported file names its own element tags there).
pub fn try_build(
    nodes: Vec<[f64; 2]>,
    elements: Conn,
    edge_sets: &BTreeMap<String, Vec<[usize; 2]>>,
    locate: &dyn Fn(Item) -> (String, String),
) -> Result<Mesh2d, CoreError> {
    let bad = |item: Item, r: String| {
        let (p, context) = locate(item);
        CoreError::invalid(InvalidKind::Mesh, p, format!("{context}{r}"))
    };
    if nodes.len() < 3 {
        return Err(bad(Item::Nodes, "a mesh needs at least 3 nodes".into()));
    }
    if elements.is_empty() {
        return Err(bad(Item::Elements, "a mesh needs at least one element".into()));
    }
    let npe = elements.get(0).len();
    let order = match npe {
        3 => Order::T3,
        6 => Order::T6,
        k => {
            return Err(bad(
                Item::Element(0),
                format!("element has {k} nodes; expected 3 (T3) or 6 (T6)"),
            ))
        }
    };
    let mut elems = Vec::with_capacity(elements.len() * npe);
    for (e, el) in elements.iter().enumerate() {
        if let Err((k, why)) = index_fault(el, npe, nodes.len()) {
            return Err(bad(k.map_or(Item::Element(e), |k| Item::ElementNode(e, k)), why));
        }
        let (p, q, r) = (nodes[el[0]], nodes[el[1]], nodes[el[2]]);
        let area = signed_area(p, q, r);
        let longest = [(p, q), (q, r), (r, p)]
            .iter()
            .map(|(a, b)| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2))
            .fold(0.0, f64::max);
        if area.abs() <= MIN_SHAPE_RATIO * longest {
            return Err(bad(
                Item::Element(e),
                // Ratios, not lengths: the coordinates here are nondimensional.
                format!(
                    "degenerate element: its area is {:.3e} of its longest edge squared (at least \
                        {MIN_SHAPE_RATIO:.0e} is needed)",
                    area.abs() / longest.max(f64::MIN_POSITIVE)
                ),
            ));
        }
        if area < 0.0 {
            return Err(bad(
                Item::Element(e),
                "inverted element: corners are clockwise (negative area); list them counter-clockwise".into(),
            ));
        }
        if order == Order::T6 {
            // Midside nodes must keep the isoparametric map invertible; we require
            // them within a quarter of the edge length of the midpoint, the usual
            // sufficient condition for a positive Jacobian.
            for (k, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                let (a, b, m) = (nodes[el[i]], nodes[el[j]], nodes[el[3 + k]]);
                let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                let off = ((m[0] - mid[0]).powi(2) + (m[1] - mid[1]).powi(2)).sqrt();
                let len = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
                if off > 0.25 * len {
                    return Err(bad(
                        Item::ElementNode(e, 3 + k),
                        format!(
                            "midside node is {:.3} edge lengths from the \
                        edge midpoint (at most 0.25); the element map would fold",
                            off / len
                        ),
                    ));
                }
            }
        }
        elems.extend_from_slice(el);
    }
    let edges = |e: usize| {
        let c = &elems[npe * e..];
        [(0, 1), (1, 2), (2, 0)].map(|(i, j)| overlap::side_key([c[i], c[j]]))
    };
    if let Some(key) = overlap::overlapped_side(elements.len(), nodes.len(), edges) {
        let users = overlap::users(elements.len(), key, edges);
        let at = users.last().map_or(Item::Elements, |&e| Item::Element(e));
        return Err(bad(at, overlap::why("edge", key, &users)));
    }
    check_nodes(&nodes, elements, &bad)?;
    // Only the edge sets' edges are looked up, so only they are kept: by
    // corner pair, the elements that use the edge and the last one's
    // orientation (with its midside node). Keeping every element edge cost
    // about 190 bytes per element in two hash maps: 310 MB of the 880 MB that
    // reading a 70 MB inline mesh of 1.6M triangles took.
    let mut wanted: HashMap<(usize, usize), (Option<Edge>, usize)> = edge_sets
        .values()
        .flatten()
        .map(|&[a, b]| ((a.min(b), a.max(b)), (None, 0)))
        .collect();
    for el in elements.iter() {
        for (k, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
            let (a, b) = (el[i], el[j]);
            if let Some((owner, uses)) = wanted.get_mut(&(a.min(b), a.max(b))) {
                *uses += 1;
                let mid = (order == Order::T6).then(|| el[3 + k]);
                *owner = Some(Edge { a, b, mid });
            }
        }
    }
    let mut sets = BTreeMap::new();
    for (name, edges) in edge_sets {
        if edges.is_empty() {
            return Err(bad(Item::Set(name), "edge set is empty".into()));
        }
        let mut out = Vec::with_capacity(edges.len());
        for (k, &[a, b]) in edges.iter().enumerate() {
            if let Some(&n) = [a, b].iter().find(|&&n| n >= nodes.len()) {
                return Err(bad(
                    Item::Member(name, k),
                    format!("node {n} does not exist (the mesh has {} nodes)", nodes.len()),
                ));
            }
            match wanted.get(&(a.min(b), a.max(b))) {
                Some(&(Some(edge), 1)) => out.push(edge),
                Some((Some(_), _)) => {
                    return Err(bad(
                        Item::Member(name, k),
                        format!("edge [{a}, {b}] is interior (shared by two elements), not on the boundary"),
                    ))
                }
                _ => {
                    return Err(bad(
                        Item::Member(name, k),
                        format!("edge [{a}, {b}] is not an edge of any element"),
                    ))
                }
            }
        }
        sets.insert(name.clone(), out);
    }
    Ok(Mesh2d {
        order,
        nodes,
        elems,
        edge_sets: sets,
    })
}

/// Nodes that coincide to this fraction of the mesh's extent are one point
/// (coordinates typed by hand or exported at 1e-12 relative agree to it).
const COINCIDE: f64 = 1e-12;

/// Every node is used, no two nodes coincide, and the elements form one
/// connected piece: an unused node makes K singular, coinciding nodes split
/// the body along a crack it does not have, and separate pieces are separate
/// bodies (each needs its own supports or contact).
fn check_nodes(nodes: &[[f64; 2]], elements: Conn, bad: &dyn Fn(Item, String) -> CoreError) -> Result<(), CoreError> {
    let mut used = vec![false; nodes.len()];
    for el in elements.iter() {
        for &n in el {
            used[n] = true;
        }
    }
    // Coinciding nodes: in x order, runs of nodes whose x follow each other
    // within the tolerance (two nodes that coincide are in one run), each
    // swept in y order. A sweep in x order alone compared every pair of a
    // column of equal x: 13 s for a structured 828 × 828 grid.
    let tol = COINCIDE * super::extent(nodes);
    let mut order: Vec<usize> = (0..nodes.len()).collect();
    order.sort_by(|&a, &b| nodes[a][0].total_cmp(&nodes[b][0]).then(a.cmp(&b)));
    let mut start = 0;
    while start < order.len() {
        let mut end = start + 1;
        while end < order.len() && nodes[order[end]][0] - nodes[order[end - 1]][0] <= tol {
            end += 1;
        }
        let run = &mut order[start..end];
        start = end;
        run.sort_by(|&a, &b| nodes[a][1].total_cmp(&nodes[b][1]).then(a.cmp(&b)));
        for (k, &i) in run.iter().enumerate() {
            for &j in &run[k + 1..] {
                if nodes[j][1] - nodes[i][1] > tol {
                    break;
                }
                if (nodes[j][0] - nodes[i][0]).abs() > tol {
                    continue;
                }
                let (first, second) = (i.min(j), i.max(j));
                let unused = [first, second].into_iter().find(|&n| !used[n]);
                return Err(match unused {
                    Some(n) => bad(
                        Item::Node(n),
                        format!(
                            "node {n} is used by no element (it coincides with node {})",
                            if n == first { second } else { first }
                        ),
                    ),
                    None => bad(
                        Item::Node(second),
                        format!(
                            "nodes {first} and {second} coincide: the mesh is split there (merge them into one node)"
                        ),
                    ),
                });
            }
        }
    }
    check_used_and_connected(nodes.len(), elements, bad)
}

/// Every one of the `n` nodes is used and the elements form one connected
/// piece: an unused node makes K singular, and separate pieces are separate
/// bodies (each needs its own supports or contact).
pub fn check_used_and_connected(
    n: usize,
    elements: Conn,
    bad: &dyn Fn(Item, String) -> CoreError,
) -> Result<(), CoreError> {
    let mut used = vec![false; n];
    for el in elements.iter() {
        for &k in el {
            used[k] = true;
        }
    }
    if let Some(k) = used.iter().position(|u| !u) {
        return Err(bad(Item::Node(k), format!("node {k} is used by no element")));
    }
    // Connected pieces: union-find over the elements' nodes.
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut a: usize) -> usize {
        while parent[a] != a {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        a
    }
    for el in elements.iter() {
        for w in el.windows(2) {
            let (a, b) = (root(&mut parent, w[0]), root(&mut parent, w[1]));
            if a != b {
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let first = root(&mut parent, 0);
    if let Some(k) = (1..n).find(|&k| root(&mut parent, k) != first) {
        return Err(bad(
            Item::Node(k),
            format!(
                "the mesh falls apart: node {k} belongs to a piece not connected to node 0; give each piece its own \
                    body (with its own supports or contact)"
            ),
        ));
    }
    Ok(())
}
