//! The Gmsh MSH 4.1 reader for tetrahedral bodies: a hand-written unit cube
//! of 6 tetrahedra with two physical surfaces and a physical volume, an
//! order-2 box written by the test and read back, and hostile inputs (each a
//! structured error, none a panic). Volumes and areas of the unit cube are
//! sums of a few exact binary fractions: 1e-15 leaves room for round-off only.

use contact_core::mesh3d::generate::box_mesh;
use contact_core::mesh3d::gmsh::try_parse;
use contact_core::mesh3d::{Mesh3d, Order, EDGES};

/// The unit cube: node b + 1 at (b & 1, b >> 1 & 1, b >> 2 & 1), cut into
/// the 6 Kuhn tetrahedra along the diagonal from node 1 to node 8. The
/// physical surface "bottom" (z = 0) lists its triangles with their normal
/// into the body, "top" (z = 1) outward; the physical volume is "block".
const CUBE: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
2 1 \"bottom\"
2 2 \"top\"
3 3 \"block\"
$EndPhysicalNames
$Entities
0 0 2 1
1 0 0 0 1 1 0 1 1 0
2 0 0 1 1 1 1 1 2 0
1 0 0 0 1 1 1 1 3 2 1 2
$EndEntities
$Nodes
1 8 1 8
3 1 0 8
1
2
3
4
5
6
7
8
0 0 0
1 0 0
0 1 0
1 1 0
0 0 1
1 0 1
0 1 1
1 1 1
$EndNodes
$Elements
3 10 1 10
2 1 2 2
1 1 2 4
2 1 4 3
2 2 2 2
3 5 6 8
4 5 8 7
3 1 4 6
5 1 2 4 8
6 1 3 7 8
7 1 5 6 8
8 1 6 2 8
9 1 7 5 8
10 1 4 3 8
$EndElements
";

fn cube() -> Mesh3d {
    try_parse(CUBE, &[], "/m").unwrap().try_mesh(1.0, "/m").unwrap()
}

#[test]
fn the_cube_reads_with_its_volumes_and_outward_face_sets() {
    let m = cube();
    assert_eq!((m.order, m.nodes.len(), m.n_elems()), (Order::T4, 8, 6));
    let mut total = 0.0;
    for e in 0..6 {
        assert!((m.volume(e) - 1.0 / 6.0).abs() < 1e-15, "element {e}: {}", m.volume(e));
        total += m.volume(e);
    }
    assert!((total - 1.0).abs() < 1e-15);
    for (name, nz) in [("bottom", -1.0), ("top", 1.0)] {
        let faces = &m.face_sets[name];
        assert_eq!(faces.len(), 2);
        let mut area = 0.0;
        for f in faces {
            let (a, n) = m.face_area_normal(f);
            assert_eq!(n, [0.0, 0.0, nz], "{name}");
            area += a;
        }
        assert!((area - 1.0).abs() < 1e-15, "{name}: {area}");
    }
    // The named volume is the same body; an unknown one lists the known ones.
    let named = try_parse(CUBE, &["block".into()], "/m").unwrap();
    assert_eq!(named.elements.len(), 24);
    let e = try_parse(CUBE, &["ball".into()], "/m").unwrap_err();
    assert!(e.code() == "invalid_request" && e.to_string().contains("block"), "{e}");
}

/// `m` as MSH 4.1 text: one volume entity (physical "body"), one surface
/// entity per face set (physical group named after it), T10 as type 11
/// tetrahedra and type 9 triangles.
fn to_msh(m: &Mesh3d) -> String {
    let (tet, tri) = match m.order {
        Order::T4 => (4, 2),
        Order::T10 => (11, 9),
    };
    let sets: Vec<_> = m.face_sets.iter().collect();
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    s += &format!("{}\n", sets.len() + 1);
    for (k, (name, _)) in sets.iter().enumerate() {
        s += &format!("2 {} \"{name}\"\n", k + 1);
    }
    s += &format!(
        "3 {} \"body\"\n$EndPhysicalNames\n$Entities\n0 0 {} 1\n",
        sets.len() + 1,
        sets.len()
    );
    for k in 0..sets.len() {
        s += &format!("{} 0 0 0 1 1 1 1 {} 0\n", k + 1, k + 1);
    }
    s += &format!("1 0 0 0 1 1 1 1 {} 0\n$EndEntities\n", sets.len() + 1);
    let n = m.nodes.len();
    s += &format!("$Nodes\n1 {n} 1 {n}\n3 1 0 {n}\n");
    for i in 0..n {
        s += &format!("{}\n", i + 1);
    }
    for p in &m.nodes {
        s += &format!("{:e} {:e} {:e}\n", p[0], p[1], p[2]);
    }
    let faces: usize = sets.iter().map(|(_, f)| f.len()).sum();
    let total = faces + m.n_elems();
    s += &format!("$EndNodes\n$Elements\n{} {total} 1 {total}\n", sets.len() + 1);
    let mut tag = 0;
    for (k, (_, fs)) in sets.iter().enumerate() {
        s += &format!("2 {} {tri} {}\n", k + 1, fs.len());
        for f in fs.iter() {
            tag += 1;
            // Written inward (corners 1 and 2 swapped, midsides to match): the reader orients.
            let c = f.corners;
            let mut nodes = vec![c[0], c[2], c[1]];
            if let Some(md) = f.mids {
                nodes.extend([md[2], md[1], md[0]]);
            }
            s += &format!(
                "{tag} {}\n",
                nodes.iter().map(|v| (v + 1).to_string()).collect::<Vec<_>>().join(" ")
            );
        }
    }
    s += &format!("3 1 {tet} {}\n", m.n_elems());
    for e in 0..m.n_elems() {
        tag += 1;
        s += &format!(
            "{tag} {}\n",
            m.elem(e)
                .iter()
                .map(|v| (v + 1).to_string())
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    s + "$EndElements\n"
}

#[test]
fn an_order_2_box_reads_back_with_its_midsides_in_place() {
    let m = box_mesh([0.0; 3], [1.0, 2.0, 1.0], 0.5, None, Order::T10);
    let text = to_msh(&m);
    let back = try_parse(&text, &["body".into()], "/m")
        .unwrap()
        .try_mesh(1.0, "/m")
        .unwrap();
    assert_eq!(back.order, Order::T10);
    // Coordinates are exact binary fractions written with {:e}: they read back exactly.
    assert_eq!(back.nodes, m.nodes);
    assert_eq!(back.elems, m.elems);
    assert_eq!(
        back.face_sets, m.face_sets,
        "the inward triangles come out oriented outward"
    );
    for e in 0..back.n_elems() {
        let t = back.elem(e);
        for (k, &[i, j]) in EDGES.iter().enumerate() {
            let (a, b, mid) = (back.nodes[t[i]], back.nodes[t[j]], back.nodes[t[4 + k]]);
            assert!(
                (0..3).all(|c| (mid[c] - 0.5 * (a[c] + b[c])).abs() < 1e-15),
                "element {e}, edge {k}"
            );
        }
    }
}

/// VTK's order (midsides of 1-3 and 2-3 last) read as Gmsh's folds every element.
#[test]
fn a_t10_in_vtk_order_is_refused_as_folded() {
    let mut m = box_mesh([0.0; 3], [1.0; 3], 1.0, None, Order::T10);
    for t in m.elems.chunks_exact_mut(10) {
        t.swap(8, 9);
    }
    m.face_sets.clear();
    let e = try_parse(&to_msh(&m), &[], "/m")
        .unwrap()
        .try_mesh(1.0, "/m")
        .unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("Gmsh element") && msg.contains("folds"), "{msg}");
}

fn refusal(text: &str) -> String {
    let e = match try_parse(text, &[], "/m") {
        Ok(p) => p.try_mesh(1.0, "/m").unwrap_err(),
        Err(e) => e,
    };
    assert_eq!((e.code(), e.path()), ("invalid_mesh", "/m"), "{e}");
    e.to_string()
}

#[test]
fn hostile_files_are_refused_with_what_and_where() {
    let cases: Vec<(String, &[&str])> = vec![
        (CUBE.replace("$EndNodes\n", ""), &["$Nodes", "$EndNodes"]),
        (
            CUBE[..CUBE.find("7 1 5 6 8").unwrap()].to_string() + "$EndElements\n",
            &["ends early"],
        ),
        (
            CUBE.replace("3 1 0 8\n", "3 1 0 4000000000000000000\n"),
            &["ends early"],
        ),
        (
            CUBE.replace("3 1 4 6\n", "3 1 4 4000000000000000000\n"),
            &["ends early"],
        ),
        (
            CUBE.replace("3 1 4 6\n", "3 1 5 6\n"),
            &["type 5", "hexahedron", "volume entity 1"],
        ),
        (CUBE.replace("3 1 4 6\n", "3 1 99 6\n"), &["type 99", "not supported"]),
        (CUBE.replace("10 1 4 3 8", "10 1 4 3 9"), &["element 10", "node 9"]),
        (CUBE.replace("4.1 0 8", "4.1 1 8"), &["binary", "Mesh.Binary"]),
        (
            CUBE.replace("5 1 2 4 8", "5 1 4 2 8"),
            &["Gmsh element 5", "volume entity 1", "inverted"],
        ),
        (
            CUBE.replace("1 1 2 4\n", "1 1 4 8\n"),
            &["'bottom'", "triangle 1", "interior"],
        ),
        (CUBE.replace("0 1 1\n1 1 1", "0 1 1\n1 1 nan"), &["finite number"]),
        (
            CUBE.replace("1 0 0 0 1 1 1 1 3 2 1 2\n", ""),
            &["$Entities", "ends early"],
        ),
    ];
    for (text, words) in cases {
        let msg = refusal(&text);
        assert!(words.iter().all(|w| msg.contains(w)), "{words:?}: {msg}");
    }
}

/// Every truncation at a line end, and every token replaced by a negative,
/// a non-number, a huge number or zero, gives a result or a structured
/// error, never a panic.
#[test]
fn mutated_files_never_panic() {
    let mut tried = 0;
    let mut check = |text: &str| {
        tried += 1;
        let e = match try_parse(text, &[], "/m") {
            Ok(p) => match p.try_mesh(1.0, "/m") {
                Ok(_) => return,
                Err(e) => e,
            },
            Err(e) => e,
        };
        assert!(
            matches!(e.code(), "invalid_mesh" | "invalid_request") && e.path() == "/m",
            "{e}"
        );
    };
    for (i, _) in CUBE.match_indices('\n') {
        check(&CUBE[..i]);
    }
    let tokens: Vec<(usize, &str)> = CUBE
        .split_inclusive(char::is_whitespace)
        .scan(0, |at, t| {
            let start = *at;
            *at += t.len();
            Some((start, t.trim_end()))
        })
        .filter(|(_, t)| !t.is_empty())
        .collect();
    for &(at, tok) in &tokens {
        for with in ["-1", "x", "99999999999999999999", "0", "4000000000"] {
            check(&format!("{}{with}{}", &CUBE[..at], &CUBE[at + tok.len()..]));
        }
    }
    assert!(tried > 5 * tokens.len(), "{tried}");
}
