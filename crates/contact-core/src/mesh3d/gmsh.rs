//! Gmsh MSH 4.1 ASCII text → a tetrahedral body mesh (no file I/O: the text
//! comes in the request).
//!
//! What is read: `$MeshFormat` (4.1, ASCII only), `$PhysicalNames`,
//! `$Entities`, `$Nodes` (all through `mesh::msh`, as the 2D reader) and
//! `$Elements`; other sections are skipped. The body is made of the 4-node
//! (type 4) and 10-node (type 11) tetrahedra of the volume entities, or only
//! of those in the physical volume groups the request names. Triangles
//! (type 2, and type 9 of order-2 meshes) of every physical surface group
//! become the face set named after the group (a group without a name is named
//! by its tag); each is matched by its corners to the tetrahedron it bounds
//! and takes that element's outward orientation (`quality::try_build`), so the
//! side Gmsh oriented a surface toward does not matter, and a T10's face
//! takes its midsides from its element.
//!
//! Node order: Gmsh's 10-node tetrahedron (the reference manual's "Node
//! ordering" section, its Tetrahedron10 figure) lists the corners, then the
//! midsides of edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1: our T10 order
//! (`mesh3d::EDGES`), so connectivity is taken as it is. VTK's 10-node tetra
//! puts the last two the other way round (1-3, then 2-3); a file in that
//! order is refused by the element checks (its map folds, see the tests).
//! Tetrahedra of negative volume are refused, not renumbered (`quality`).
//!
//! Memory: counts read from the file reserve only what the section's text
//! can hold (`msh::Tokens::at_most`), and tetrahedra are kept flat,
//! `per_element` indices each, as the 2D reader keeps its triangles.

use std::collections::BTreeMap;

use super::quality;
use super::Mesh3d;
use crate::error::CoreError;
use crate::mesh::msh::{self, bad, Tokens};
use crate::mesh::quality::Conn;

/// A parsed MSH file restricted to one body, in the file's units.
#[derive(Debug, Clone)]
pub struct Parsed {
    pub nodes: Vec<[f64; 3]>,
    /// Tetrahedra, `per_element` (4 or 10) local node indices each, one after the other.
    pub elements: Vec<usize>,
    pub per_element: usize,
    /// Physical surface group name → boundary triangles as corner node triples.
    pub face_sets: BTreeMap<String, Vec<[usize; 3]>>,
    /// Gmsh (element tag, entity tag) of every tetrahedron, for error messages.
    element_tags: Vec<(u64, i64)>,
    /// Gmsh triangle tags of every face set, in face order.
    face_tags: BTreeMap<String, Vec<u64>>,
}

impl Parsed {
    /// Largest side of the bounding box and the node count (for scales and limits).
    pub fn extent_and_nodes(&self) -> (f64, f64) {
        (crate::mesh::extent(&self.nodes), self.nodes.len() as f64)
    }

    /// The checked mesh with coordinates divided by `length`; `path` is the
    /// JSON pointer of the MSH text (errors point there and name the Gmsh tags).
    pub fn try_mesh(&self, length: f64, path: &str) -> Result<Mesh3d, CoreError> {
        let scaled: Vec<[f64; 3]> = self.nodes.iter().map(|p| p.map(|c| c / length)).collect();
        let locate = msh::locate(path, &self.element_tags, &self.face_tags, WORDS);
        let elements = Conn::Flat {
            nodes: &self.elements,
            per: self.per_element,
        };
        quality::try_build(scaled, elements, &self.face_sets, &locate)
    }
}

/// The words of this reader's messages.
const WORDS: msh::Words = msh::Words {
    entity: "volume",
    group: "surface",
    member: "triangle",
    elements: "tetrahedra",
    body_types: "a 3D body is made of 4-node (type 4) or 10-node (type 11) tetrahedra",
    set_types: "its face sets of 3-node (type 2) or 6-node (type 9) triangles",
};

/// Parses MSH 4.1 ASCII text; `volumes` names the physical volume groups that
/// make up the body (empty: every tetrahedron). `path`: JSON pointer of the text.
pub fn try_parse(text: &str, volumes: &[String], path: &str) -> Result<Parsed, CoreError> {
    let header = msh::try_header(text, path)?;
    header.check_named(3, volumes, "volume", path)?;
    let file_nodes = msh::try_nodes(text, path)?;

    // Elements: tetrahedra of the body, triangles of the physical surfaces.
    let (mut t, blocks) = Tokens::blocks(text, "Elements", path)?;
    let mut tets = msh::Body::default();
    let mut triangles: BTreeMap<String, Vec<(u64, [usize; 3])>> = BTreeMap::new();
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
        let surface_groups = match dim {
            2 => header.groups_of(2, entity),
            _ => Vec::new(),
        };
        let body = dim == 3 && header.in_body(3, entity, volumes);
        match (dim, etype) {
            (0 | 1, _) => {}
            (2, 2 | 9) => {}
            (2, _) if surface_groups.is_empty() => {}
            (2, _) => return Err(unsupported("surface")),
            (3, 4 | 11) => {}
            (3, _) if !body => {}
            (3, _) => return Err(unsupported("volume")),
            _ => {
                return Err(bad(
                    path,
                    format!("Gmsh element block of dimension {dim} (entity {entity})"),
                ))
            }
        }
        if body {
            tets.reserve(&t, n, npe);
        }
        let mut conn = [0; 10];
        for _ in 0..n {
            let conn = &mut conn[..npe];
            let tag = t.element(conn)?;
            if body {
                tets.push((tag, entity), conn, &file_nodes, WORDS, path)?;
            } else if !surface_groups.is_empty() {
                let corners = [node_of(conn[0], tag)?, node_of(conn[1], tag)?, node_of(conn[2], tag)?];
                for g in &surface_groups {
                    triangles.entry(g.clone()).or_default().push((tag, corners));
                }
            }
        }
    }
    if tets.tags.is_empty() {
        return Err(bad(
            path,
            if volumes.is_empty() {
                "the MSH file has no tetrahedra (types 4 or 11): mesh a volume (gmsh: generate(3))".to_string()
            } else {
                format!("the physical volume groups {volumes:?} hold no tetrahedra")
            },
        ));
    }

    // Keep the nodes the tetrahedra use, in file order.
    let local = tets.keep_used(file_nodes.tags.len());
    let mut nodes = Vec::with_capacity(local.iter().filter(|&&l| l != usize::MAX).count());
    nodes.extend(
        file_nodes
            .coords
            .iter()
            .zip(&local)
            .filter(|(_, &l)| l != usize::MAX)
            .map(|(c, _)| *c),
    );
    let (face_sets, face_tags) = msh::try_sets(triangles, &local, WORDS, path)?;
    Ok(Parsed {
        nodes,
        elements: tets.nodes,
        per_element: tets.per,
        face_sets,
        element_tags: tets.tags,
        face_tags,
    })
}
