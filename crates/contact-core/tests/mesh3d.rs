//! Tetrahedral meshes: the generated box (volume, orientation, face sets,
//! conformity, T10 midsides, grading) and the checks of user-given meshes.
//! Tolerances: sums of positive volumes and areas of O(10³) terms round to a
//! few 1e-16 relative, so 1e-12 leaves room for no error of method; exact
//! midpoints and copied coordinates compare to 1e-15 of the box's size.

use std::collections::{BTreeMap, HashMap, HashSet};

use contact_core::mesh::generate::Grading;
use contact_core::mesh::quality::Conn;
use contact_core::mesh3d::generate::{box_mesh, BOX_FACES};
use contact_core::mesh3d::{quality, signed_volume, Face, Mesh3d, Order, EDGES};

const LO: [f64; 3] = [0.0, -1.0, 1.0];
const HI: [f64; 3] = [2.0, 0.5, 4.0];

fn volume_of_box() -> f64 {
    (0..3).map(|a| HI[a] - LO[a]).product()
}

/// The mesh through the inline checks: its connectivity and face sets' corners.
fn revalidate(m: &Mesh3d) -> Mesh3d {
    let sets: BTreeMap<String, Vec<[usize; 3]>> = m
        .face_sets
        .iter()
        .map(|(k, v)| (k.clone(), v.iter().map(|f| f.corners).collect()))
        .collect();
    let conn = Conn::Flat {
        nodes: &m.elems,
        per: m.order.nodes_per_element(),
    };
    quality::try_inline(m.nodes.clone(), conn, &sets, "/mesh").unwrap()
}

#[test]
fn the_box_tets_fill_its_volume_all_positively_oriented() {
    for order in [Order::T4, Order::T10] {
        let m = box_mesh(LO, HI, 0.5, None, order);
        // 4 × 3 × 6 cells of 6 tetrahedra.
        assert_eq!(m.n_elems(), 6 * 4 * 3 * 6);
        let vols: Vec<f64> = (0..m.n_elems()).map(|e| m.volume(e)).collect();
        let sum: f64 = vols.iter().sum();
        let rel = (sum - volume_of_box()).abs() / volume_of_box();
        assert!(rel < 1e-12, "{order:?}: relative volume error {rel:e}");
        // Each Kuhn tetrahedron of a 0.5³ cell has volume 0.5³/6.
        let min = vols.iter().copied().fold(f64::INFINITY, f64::min);
        assert!((min - 0.125 / 6.0).abs() < 1e-15, "{min}");
        let checked = revalidate(&m);
        assert_eq!(
            checked.face_sets, m.face_sets,
            "the checks orient the faces as the generator does"
        );
    }
}

#[test]
fn the_box_face_sets_are_its_sides_with_outward_normals() {
    let m = box_mesh(LO, HI, 0.5, None, Order::T4);
    assert_eq!(m.face_sets.len(), 6);
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        let side_area = (HI[b] - LO[b]) * (HI[c] - LO[c]);
        for (s, name) in BOX_FACES[a].iter().enumerate() {
            let faces = &m.face_sets[*name];
            let mut area = 0.0;
            for f in faces {
                let (da, n) = m.face_area_normal(f);
                area += da;
                let mut want = [0.0; 3];
                want[a] = if s == 0 { -1.0 } else { 1.0 };
                assert!((0..3).all(|k| (n[k] - want[k]).abs() < 1e-15), "{name}: {n:?}");
                let plane = if s == 0 { LO[a] } else { HI[a] };
                assert!(f.corners.iter().all(|&p| m.nodes[p][a] == plane), "{name}");
            }
            let rel = (area - side_area).abs() / side_area;
            assert!(rel < 1e-12, "{name}: area {area} of {side_area}");
        }
    }
}

/// Sorted corners of every face of every element, and how many elements use it.
fn face_uses(m: &Mesh3d) -> HashMap<[usize; 3], usize> {
    let mut uses = HashMap::new();
    for e in 0..m.n_elems() {
        for k in 0..4 {
            *uses.entry(m.local_face(e, k).key()).or_insert(0) += 1;
        }
    }
    uses
}

#[test]
fn the_box_is_conforming_and_its_boundary_is_the_six_sides() {
    let m = box_mesh(LO, HI, 0.5, None, Order::T4);
    let uses = face_uses(&m);
    assert!(
        uses.values().all(|&u| u == 1 || u == 2),
        "a face used by more than two tets"
    );
    let boundary: HashSet<[usize; 3]> = uses.iter().filter(|(_, &u)| u == 1).map(|(k, _)| *k).collect();
    let sets: HashSet<[usize; 3]> = m.face_sets.values().flatten().map(Face::key).collect();
    assert_eq!(boundary, sets);
    assert_eq!(
        sets.len(),
        m.face_sets.values().map(Vec::len).sum::<usize>(),
        "no face in two sets"
    );
    // Each side's cells cut in two: 2 (4·3 + 3·6 + 4·6) faces.
    assert_eq!(boundary.len(), 2 * 2 * (4 * 3 + 3 * 6 + 4 * 6));
    // A box is a ball: V − E + F − T = 1.
    let edges: HashSet<(usize, usize)> = m
        .elems
        .chunks_exact(4)
        .flat_map(|t| EDGES.map(|[i, j]| (t[i].min(t[j]), t[i].max(t[j]))))
        .collect();
    let euler = m.nodes.len() as i64 - edges.len() as i64 + uses.len() as i64 - m.n_elems() as i64;
    assert_eq!(euler, 1);
}

#[test]
fn t10_midsides_sit_at_shared_edge_midpoints() {
    let t4 = box_mesh(LO, HI, 0.5, None, Order::T4);
    let m = box_mesh(LO, HI, 0.5, None, Order::T10);
    let edges: HashSet<(usize, usize)> = t4
        .elems
        .chunks_exact(4)
        .flat_map(|t| EDGES.map(|[i, j]| (t[i].min(t[j]), t[i].max(t[j]))))
        .collect();
    // One node per vertex and per edge: the midsides are shared.
    assert_eq!(m.nodes.len(), t4.nodes.len() + edges.len());
    assert_eq!(&m.nodes[..t4.nodes.len()], &t4.nodes[..]);
    let tol = 1e-15 * m.size();
    let near = |p: [f64; 3], q: [f64; 3]| (0..3).all(|c| (p[c] - q[c]).abs() <= tol);
    for e in 0..m.n_elems() {
        let t = m.elem(e);
        assert_eq!(&t[..4], t4.elem(e));
        for (k, &[i, j]) in EDGES.iter().enumerate() {
            let (a, b) = (m.nodes[t[i]], m.nodes[t[j]]);
            assert!(
                near(m.nodes[t[4 + k]], [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))),
                "element {e}, edge {k}"
            );
        }
    }
    for f in m.face_sets.values().flatten() {
        for (k, &mid) in f.mids.unwrap().iter().enumerate() {
            let (a, b) = (m.nodes[f.corners[k]], m.nodes[f.corners[(k + 1) % 3]]);
            assert!(near(m.nodes[mid], [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))));
        }
    }
    revalidate(&m);
}

/// The distinct coordinates of the nodes along axis `a`, sorted.
fn lines(m: &Mesh3d, a: usize) -> Vec<f64> {
    let mut x: Vec<f64> = m.nodes.iter().map(|p| p[a]).collect();
    x.sort_by(f64::total_cmp);
    x.dedup();
    x
}

/// A quarter model: the focus on the edge x = x0, y = y1 at the top z = z1.
#[test]
fn a_graded_box_follows_its_grading_from_a_corner_focus() {
    let g = Grading {
        h_min: 0.05,
        ratio: 1.5,
        extent: 0.2,
    };
    let size = 0.5;
    let m = box_mesh(LO, HI, size, Some(([LO[0], HI[1], HI[2]], g)), Order::T4);
    let from_focus = [false, true, true];
    let mut cells = 1;
    for a in 0..3 {
        let mut x = lines(&m, a);
        assert_eq!((x[0], x[x.len() - 1]), (LO[a], HI[a]));
        if from_focus[a] {
            x.reverse();
        }
        let h: Vec<f64> = x.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
        cells *= h.len();
        let mut covered = 0.0;
        for (k, &hk) in h.iter().enumerate() {
            if covered < g.extent - 1e-12 {
                assert!((hk - g.h_min).abs() < 1e-12, "axis {a}, cell {k}: {hk}");
            } else if k + 1 < h.len() {
                // Growing by the ratio up to the size, the last cell adjusted to land on the end.
                assert!(
                    hk <= g.ratio * h[k - 1] * (1.0 + 1e-12) && hk <= size * (1.0 + 1e-12),
                    "axis {a}: {h:?}"
                );
                assert!(hk >= h[k - 1] * (1.0 - 1e-12), "axis {a}: {h:?}");
            } else {
                assert!(hk <= 1.5 * g.ratio * h[k - 1] && hk <= 1.5 * size, "axis {a}: {h:?}");
            }
            covered += hk;
        }
    }
    assert_eq!(m.n_elems(), 6 * cells);
    let sum: f64 = (0..m.n_elems()).map(|e| m.volume(e)).sum();
    assert!((sum - volume_of_box()).abs() < 1e-12 * volume_of_box());
    revalidate(&m);
}

/// The unit tetrahedron and a second one on its face x = 0 (sharing corners 0, 2, 3).
fn two_tets() -> (Vec<[f64; 3]>, Vec<usize>) {
    let nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
    ];
    (nodes, vec![0, 1, 2, 3, 0, 2, 4, 3])
}

fn inline_err(nodes: Vec<[f64; 3]>, elems: &[usize], sets: &[(&str, [usize; 3])]) -> (String, String) {
    let mut face_sets: BTreeMap<String, Vec<[usize; 3]>> = BTreeMap::new();
    for (k, f) in sets {
        face_sets.entry(k.to_string()).or_default().push(*f);
    }
    let conn = Conn::Flat { nodes: elems, per: 4 };
    let e = quality::try_inline(nodes, conn, &face_sets, "/m").unwrap_err();
    assert_eq!(e.code(), "invalid_mesh");
    (e.path().to_string(), e.to_string())
}

#[test]
fn two_tets_are_accepted_with_their_faces_oriented_outward() {
    let (nodes, elems) = two_tets();
    let sets = BTreeMap::from([("bottom".to_string(), vec![[0, 1, 2], [4, 0, 2]])]);
    let m = quality::try_inline(nodes, Conn::Flat { nodes: &elems, per: 4 }, &sets, "/m").unwrap();
    for f in &m.face_sets["bottom"] {
        let (_, n) = m.face_area_normal(f);
        assert_eq!(n, [0.0, 0.0, -1.0]);
    }
    assert!((m.volume(0) - 1.0 / 6.0).abs() < 1e-16 && (m.volume(1) - 1.0 / 6.0).abs() < 1e-16);
}

#[test]
fn bad_meshes_are_refused_naming_the_item() {
    let (nodes, elems) = two_tets();
    // (nodes, connectivity, face sets, where the error points, what it says)
    type Case<'a> = (Vec<[f64; 3]>, Vec<usize>, Vec<(&'a str, [usize; 3])>, &'a str, &'a str);
    let cases: Vec<Case> = vec![
        {
            let mut n = nodes.clone();
            n[3][2] = f64::NAN;
            (n, elems.clone(), vec![], "/m/nodes/3", "finite")
        },
        (
            nodes.clone(),
            vec![0, 1, 2, 3, 0, 2, 5, 3],
            vec![],
            "/m/elements/1/2",
            "out of range",
        ),
        (
            nodes.clone(),
            vec![0, 1, 2, 3, 0, 2, 2, 3],
            vec![],
            "/m/elements/1",
            "repeats a node",
        ),
        (
            nodes.clone(),
            vec![0, 1, 2, 3, 0, 4, 2, 3],
            vec![],
            "/m/elements/1",
            "inverted",
        ),
        {
            let mut n = nodes.clone();
            n[4] = [0.0, 0.3, 0.3];
            (n, elems.clone(), vec![], "/m/elements/1", "degenerate")
        },
        {
            let mut n = nodes.clone();
            n.push([5.0, 5.0, 5.0]);
            (n, elems.clone(), vec![], "/m/nodes/5", "used by no element")
        },
        // The first tetrahedron listed again (its corners rotated): every
        // face of it is used twice on the same side.
        (
            nodes.clone(),
            vec![0, 1, 2, 3, 0, 2, 4, 3, 1, 2, 0, 3],
            vec![],
            "/m/elements/2",
            "same side",
        ),
        // A third tetrahedron on the shared face 0-2-3, on the second's side.
        {
            let mut n = nodes.clone();
            n.push([-1.0, 0.5, 0.5]);
            (
                n,
                vec![0, 1, 2, 3, 0, 2, 4, 3, 0, 2, 5, 3],
                vec![],
                "/m/elements/2",
                "shared by elements 0, 1, 2",
            )
        },
        (
            nodes.clone(),
            elems.clone(),
            vec![("s", [0, 2, 3])],
            "/m/face_sets/s/0",
            "interior",
        ),
        (
            nodes.clone(),
            elems.clone(),
            vec![("s", [1, 2, 4])],
            "/m/face_sets/s/0",
            "not a face",
        ),
        (
            nodes.clone(),
            elems.clone(),
            vec![("s", [1, 2, 9])],
            "/m/face_sets/s/0",
            "does not exist",
        ),
    ];
    for (n, e, sets, path, what) in cases {
        let (p, msg) = inline_err(n, &e, &sets);
        assert_eq!(p, path, "{msg}");
        assert!(msg.contains(what), "{msg}");
    }
    // Two tetrahedra that share nothing are two bodies.
    let mut n = nodes.clone();
    n.extend([[5.0, 0.0, 0.0], [6.0, 0.0, 0.0], [5.0, 1.0, 0.0], [5.0, 0.0, 1.0]]);
    n.remove(4);
    let (p, msg) = inline_err(n, &[0, 1, 2, 3, 4, 5, 6, 7], &[]);
    assert!(p == "/m/nodes/4" && msg.contains("falls apart"), "{p}: {msg}");
}

#[test]
fn a_folded_t10_is_refused() {
    let m = box_mesh([0.0; 3], [1.0; 3], 1.0, None, Order::T10);
    let mut nodes = m.nodes.clone();
    // Pull element 0's midside of edge 0-1 to a tenth of the edge from corner 0.
    let t = m.elem(0);
    let (a, b) = (nodes[t[0]], nodes[t[1]]);
    nodes[t[4]] = [0, 1, 2].map(|c| 0.9 * a[c] + 0.1 * b[c]);
    let conn = Conn::Flat {
        nodes: &m.elems,
        per: 10,
    };
    let e = quality::try_inline(nodes, conn, &BTreeMap::new(), "/m").unwrap_err();
    assert!(e.path() == "/m/elements/0" && e.to_string().contains("folds"), "{e}");
    assert!(signed_volume(a, b, m.nodes[t[2]], m.nodes[t[3]]) > 0.0);
}

/// Two tetrahedra sharing an edge but not its midside node leave a crack.
#[test]
fn a_t10_edge_with_two_midsides_is_refused() {
    let m = box_mesh([0.0; 3], [1.0; 3], 1.0, None, Order::T10);
    let (mut nodes, mut elems) = (m.nodes.clone(), m.elems.clone());
    // Every Kuhn tetrahedron of the cell has the main diagonal as its edge 3-0
    // (local midside 7): element 1 gets a copy of that midside node.
    nodes.push(nodes[elems[10 + 7]]);
    elems[10 + 7] = nodes.len() - 1;
    let conn = Conn::Flat { nodes: &elems, per: 10 };
    let e = quality::try_inline(nodes, conn, &BTreeMap::new(), "/m").unwrap_err();
    assert!(
        e.path() == "/m/elements/1/7" && e.to_string().contains("not conforming"),
        "{e}"
    );
}
