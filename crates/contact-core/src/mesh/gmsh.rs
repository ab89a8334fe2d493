//! Gmsh MSH 4.1 ASCII text → a body mesh (no file I/O: the text comes in the request).
//!
//! What is read: `$MeshFormat` (4.1, ASCII only), `$PhysicalNames`, `$Entities`
//! (which physical groups each entity belongs to), `$Nodes` and `$Elements`;
//! other sections are skipped. The body is made of the 3-node (type 2) and
//! 6-node (type 9) triangles of the surface entities, or only of those in the
//! physical surface groups the request names. Line elements (type 1, and type 8
//! of quadratic meshes) of every physical curve group become the edge set named
//! after the group (a group without a name is named by its tag). Gmsh's 6-node
//! triangle lists the corners, then the midsides of edges 0-1, 1-2, 2-0: our T6
//! order, so connectivity is taken as it is. Triangles Gmsh wrote clockwise (a
//! surface whose normal is −z) are renumbered counter-clockwise, which changes
//! no geometry. The result goes through the same checks as an inline mesh
//! (`quality::try_build`), whose errors then name the Gmsh element tag and entity.
//!
//! Binary MSH is refused with a hint: no maintained Rust crate reads MSH 4.1 (mshio
//! has had no release since 2020) and a JSON request carries text anyway.
//!
//! Counts read from the file reserve memory only up to what the section's text
//! can hold (`msh::Tokens::at_most`): a hostile count fails on the missing data.
//! Triangles are kept flat, `per_element` indices each: reading a 58 MB file of
//! 1.1M triangles costs 4.4 times its size (peak resident memory of the
//! service), where a list per triangle and growing vectors cost 8.8 times.
//!
//! The sections, their tokens, the physical groups and the nodes are read by
//! `msh`, which the tetrahedral reader (`mesh3d::gmsh`) shares.

use std::collections::BTreeMap;

use super::msh::{self, bad, Tokens};
use super::{quality, signed_area, Mesh2d};
use crate::error::CoreError;

/// A parsed MSH file restricted to one body, in the file's units.
#[derive(Debug, Clone)]
pub struct Parsed {
    pub nodes: Vec<[f64; 2]>,
    /// Counter-clockwise triangles, `per_element` (3 or 6) local node indices
    /// each, one after the other.
    pub elements: Vec<usize>,
    pub per_element: usize,
    /// Physical curve group name → boundary edges as corner node pairs.
    pub edge_sets: BTreeMap<String, Vec<[usize; 2]>>,
    /// Gmsh (element tag, entity tag) of every element, for error messages.
    element_tags: Vec<(u64, i64)>,
    /// Gmsh line element tags of every edge set, in edge order.
    edge_tags: BTreeMap<String, Vec<u64>>,
}

impl Parsed {
    /// The checked mesh with coordinates divided by `length`; `path` is the
    /// JSON pointer of the MSH text (errors point there and name the Gmsh tags).
    pub fn try_mesh(&self, length: f64, path: &str) -> Result<Mesh2d, CoreError> {
        let scaled: Vec<[f64; 2]> = self.nodes.iter().map(|p| [p[0] / length, p[1] / length]).collect();
        let locate = msh::locate(path, &self.element_tags, &self.edge_tags, WORDS);
        let elements = quality::Conn::Flat {
            nodes: &self.elements,
            per: self.per_element,
        };
        quality::try_build(scaled, elements, &self.edge_sets, &locate)
    }
}

/// The words of this reader's messages.
const WORDS: msh::Words = msh::Words {
    entity: "surface",
    group: "curve",
    member: "line element",
    elements: "triangles",
    body_types: "a 2D body is made of 3-node (type 2) or 6-node (type 9) triangles",
    set_types: "its edge sets of 2-node (type 1) or 3-node (type 8) lines",
};

/// Parses MSH 4.1 ASCII text; `surfaces` names the physical surface groups that
/// make up the body (empty: every triangle). `path`: JSON pointer of the text.
pub fn try_parse(text: &str, surfaces: &[String], path: &str) -> Result<Parsed, CoreError> {
    let header = msh::try_header(text, path)?;
    header.check_named(2, surfaces, "surface", path)?;
    let in_body = |entity: i64| header.in_body(2, entity, surfaces);

    // Nodes in file order.
    let file_nodes = msh::try_nodes(text, path)?;
    let (node_tags, coords) = (&file_nodes.tags, &file_nodes.coords);

    // Elements: triangles of the body, lines of the physical curves.
    let (mut t, blocks) = Tokens::blocks(text, "Elements", path)?;
    let mut tris = msh::Body::default();
    let mut lines: BTreeMap<String, Vec<(u64, [usize; 2])>> = BTreeMap::new();
    let node_of = |tag: u64, element: u64| file_nodes.index(tag, element, path);
    for _ in 0..blocks {
        let block = t.block(WORDS)?;
        let msh::Block {
            dim,
            entity,
            etype,
            n,
            npe,
        } = block;
        let unsupported = |on: &str| block.unsupported(on, WORDS, path);
        let curve_groups: Vec<String> = match dim {
            1 => header.groups_of(1, entity),
            _ => Vec::new(),
        };
        match (dim, etype) {
            (0, _) => {}
            (1, 1 | 8) => {}
            (1, _) if curve_groups.is_empty() => {}
            (1, _) => return Err(unsupported("curve")),
            (2, 2 | 9) => {}
            (2, _) if !in_body(entity) => {}
            (2, _) => return Err(unsupported("surface")),
            (3, _) => return Err(unsupported("volume")),
            _ => {
                return Err(bad(
                    path,
                    format!("Gmsh element block of dimension {dim} (entity {entity})"),
                ))
            }
        }
        let body = dim == 2 && in_body(entity);
        if body {
            tris.reserve(&t, n, npe);
        }
        let mut conn = [0; 10];
        for _ in 0..n {
            let conn = &mut conn[..npe];
            let tag = t.element(conn)?;
            if body {
                tris.push((tag, entity), conn, &file_nodes, WORDS, path)?;
            } else if dim == 1 {
                for g in &curve_groups {
                    let ends = [node_of(conn[0], tag)?, node_of(conn[1], tag)?];
                    lines.entry(g.clone()).or_default().push((tag, ends));
                }
            }
        }
    }
    if tris.tags.is_empty() {
        return Err(bad(
            path,
            if surfaces.is_empty() {
                "the MSH file has no triangles (types 2 or 9): mesh a surface (gmsh: generate(2))".to_string()
            } else {
                format!("the physical surface groups {surfaces:?} hold no triangles")
            },
        ));
    }

    // Keep the nodes the triangles use, in file order.
    let local = tris.keep_used(node_tags.len());
    let used = |i: usize| local[i] != usize::MAX;
    let mut nodes = Vec::with_capacity(local.iter().filter(|&&l| l != usize::MAX).count());
    nodes.extend(
        coords
            .iter()
            .enumerate()
            .filter(|(i, _)| used(*i))
            .map(|(_, c)| [c[0], c[1]]),
    );
    let size = super::extent(&nodes);
    for (i, c) in coords.iter().enumerate().filter(|(i, _)| used(*i)) {
        // z is written with ~16 digits: anything beyond round-off of the size is a 3D node.
        if c[2].abs() > 1e-9 * size {
            return Err(bad(
                path,
                format!(
                    "Gmsh node {} has z = {}: a 2D body lies in the plane z = 0",
                    node_tags[i], c[2]
                ),
            ));
        }
    }
    let msh::Body {
        nodes: mut elements,
        tags: element_tags,
        per,
    } = tris;
    for e in elements.chunks_exact_mut(per) {
        if signed_area(nodes[e[0]], nodes[e[1]], nodes[e[2]]) < 0.0 {
            // Clockwise: swap corners 1 and 2; midsides (01, 12, 20) become (02, 21, 10).
            e.swap(1, 2);
            if e.len() == 6 {
                e.swap(3, 5);
            }
        }
    }
    let (edge_sets, edge_tags) = msh::try_sets(lines, &local, WORDS, path)?;
    Ok(Parsed {
        nodes,
        elements,
        per_element: per,
        edge_sets,
        element_tags,
        edge_tags,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit square of two triangles, bottom edge a physical curve "bottom",
    /// the surface the physical group "plate". `tri` replaces the triangle block.
    fn square(tri: &str) -> String {
        format!(
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"bottom\"\n2 2 \
                \"plate\"\n$EndPhysicalNames\n\
$Entities\n0 1 1 0\n1 0 0 0 1 0 0 1 1 0\n1 0 0 0 1 1 0 1 2 0\n$EndEntities\n\
$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
$Elements\n2 3 1 3\n1 1 1 1\n1 1 2\n{tri}$EndElements\n"
        )
    }

    #[test]
    fn a_square_reads_with_its_named_edge_set_oriented_body_on_the_left() {
        let p = try_parse(&square("2 1 2 2\n2 1 2 3\n3 1 3 4\n"), &[], "/m").unwrap();
        assert_eq!(p.nodes.len(), 4);
        assert_eq!(
            (p.elements.as_slice(), p.per_element),
            ([0, 1, 2, 0, 2, 3].as_slice(), 3)
        );
        let m = p.try_mesh(1.0, "/m").unwrap();
        let e = m.edge_sets["bottom"][0];
        // Outward normal of a→b is (dy, −dx): the bottom edge must point down.
        let (a, b) = (m.nodes[e.a], m.nodes[e.b]);
        assert_eq!((b[1] - a[1], -(b[0] - a[0])), (0.0, -1.0));
    }

    #[test]
    fn clockwise_triangles_are_renumbered_with_the_same_area() {
        let p = try_parse(&square("2 1 2 2\n2 1 3 2\n3 1 4 3\n"), &[], "/m").unwrap();
        let m = p.try_mesh(1.0, "/m").unwrap();
        let area: f64 = (0..m.n_elems())
            .map(|e| {
                let c = m.elem(e);
                signed_area(m.nodes[c[0]], m.nodes[c[1]], m.nodes[c[2]])
            })
            .sum();
        assert!((area - 1.0).abs() < 1e-15, "{area}");
    }

    #[test]
    fn quads_are_refused_naming_the_type_and_entity() {
        let e = try_parse(&square("2 1 3 1\n2 1 2 3 4\n"), &[], "/m").unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("type 3") && msg.contains("entity 1") && msg.contains("quadrangle"),
            "{msg}"
        );
        assert_eq!(e.path(), "/m");
    }

    #[test]
    fn binary_and_old_versions_are_refused_with_the_option_to_set() {
        let bin = square("2 1 2 2\n2 1 2 3\n3 1 3 4\n").replace("4.1 0 8", "4.1 1 8");
        assert!(try_parse(&bin, &[], "/m")
            .unwrap_err()
            .to_string()
            .contains("Mesh.Binary"));
        let old = square("2 1 2 2\n2 1 2 3\n3 1 3 4\n").replace("4.1 0 8", "2.2 0 8");
        assert!(try_parse(&old, &[], "/m").unwrap_err().to_string().contains("4.1"));
    }

    #[test]
    fn a_node_off_the_plane_is_refused() {
        let text = square("2 1 2 2\n2 1 2 3\n3 1 3 4\n").replace("1 1 0\n0 1 0", "1 1 0.5\n0 1 0");
        let msg = try_parse(&text, &[], "/m").unwrap_err().to_string();
        assert!(msg.contains("node 3") && msg.contains("z = 0.5"), "{msg}");
    }

    #[test]
    fn a_degenerate_triangle_names_its_gmsh_tag() {
        // Element 3 repeats the collinear nodes 1, 2 and a node on their line.
        let text = square("2 1 2 2\n2 1 2 3\n3 1 3 4\n").replace("0 1 0\n$EndNodes", "0.5 0 0\n$EndNodes");
        let text = text.replace("3 1 3 4\n", "7 1 2 4\n");
        let msg = try_parse(&text, &[], "/m")
            .unwrap()
            .try_mesh(1.0, "/m")
            .unwrap_err()
            .to_string();
        assert!(msg.contains("Gmsh element 7"), "{msg}");
    }

    #[test]
    fn an_unknown_surface_group_lists_the_known_ones() {
        let msg = try_parse(&square("2 1 2 2\n2 1 2 3\n3 1 3 4\n"), &["body".into()], "/m")
            .unwrap_err()
            .to_string();
        assert!(msg.contains("'body'") && msg.contains("plate"), "{msg}");
        assert!(try_parse(&square("2 1 2 2\n2 1 2 3\n3 1 3 4\n"), &["plate".into()], "/m").is_ok());
    }

    #[test]
    fn hostile_counts_fail_without_allocating() {
        let text = square("2 1 2 2\n2 1 2 3\n3 1 3 4\n").replace("2 1 0 4\n", "2 1 0 4000000000000000000\n");
        assert!(try_parse(&text, &[], "/m").is_err());
    }
}
