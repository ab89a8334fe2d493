//! MSH 4.1 ASCII text, the parts the 2D and 3D readers share: sections and
//! their tokens, the header (`$MeshFormat`, `$PhysicalNames`, `$Entities`),
//! the nodes (`$Nodes`), the element blocks' headers and elements, the body's
//! elements kept flat, the named sets and the messages naming Gmsh's tags.
//! Which blocks make the body and which the sets is each reader's own
//! (`mesh::gmsh` for triangles, `mesh3d::gmsh` for tetrahedra).
//!
//! Counts read from the file reserve memory only up to what the section's text
//! can hold (`Tokens::at_most`): a hostile count fails on the missing data.
//!
//! Length: about 545 lines, all of the MSH reading that the 2D and 3D
//! readers share (listed above); each reader keeps only what its dimension
//! decides.

use std::collections::{BTreeMap, HashMap};

use super::quality::Item;
use crate::error::{CoreError, InvalidKind};

pub(crate) fn bad(path: &str, reason: impl Into<String>) -> CoreError {
    CoreError::invalid(InvalidKind::Mesh, path, reason.into())
}

/// Gmsh's name of an element type, for messages.
fn type_name(t: i64) -> &'static str {
    match t {
        1 => "2-node line",
        2 => "3-node triangle",
        3 => "4-node quadrangle",
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        8 => "3-node line",
        9 => "6-node triangle",
        10 => "9-node quadrangle",
        11 => "10-node tetrahedron",
        15 => "1-node point",
        16 => "8-node quadrangle",
        20 => "9-node incomplete triangle",
        21 => "10-node triangle",
        26 => "4-node line",
        _ => "element",
    }
}

/// Nodes per element of the types whose blocks we may meet; None: unknown type.
fn nodes_per_element(t: i64) -> Option<usize> {
    Some(match t {
        15 => 1,
        1 => 2,
        2 | 8 => 3,
        3 | 4 | 26 => 4,
        7 => 5,
        6 | 9 => 6,
        5 | 16 => 8,
        10 | 20 => 9,
        11 | 21 => 10,
        _ => return None,
    })
}

/// Whitespace-separated tokens of one section, with the section's name for errors.
pub(crate) struct Tokens<'a> {
    it: std::str::SplitAsciiWhitespace<'a>,
    section: &'static str,
    path: &'a str,
    /// Length of the section's text: what bounds any count read from it.
    len: usize,
}

impl<'a> Tokens<'a> {
    /// The tokens of the required section `$name` (`$Nodes`, `$Elements`) after its
    /// header `numEntityBlocks numItems minTag maxTag`, and the number of blocks.
    pub(crate) fn blocks(text: &'a str, name: &'static str, path: &'a str) -> Result<(Self, usize), CoreError> {
        let body = section(text, name, path)?.ok_or_else(|| bad(path, format!("MSH file has no ${name} section")))?;
        let mut t = Tokens {
            it: body.split_ascii_whitespace(),
            section: name,
            path,
            len: body.len(),
        };
        let blocks = t.count()?;
        t.count()?;
        t.int()?;
        t.int()?;
        Ok((t, blocks))
    }
    /// `count` items of `tokens` tokens each, but never more than the
    /// section's text can hold (a token and its separator take 2 bytes at
    /// least): what may be reserved for them. Reserving the real count
    /// spares the doubling of growing vectors, whose slack and copies were
    /// 130 MB of the 290 MB that reading a 58 MB Gmsh mesh took.
    pub(crate) fn at_most(&self, count: usize, tokens: usize) -> usize {
        count.min(self.len / (2 * tokens))
    }
    pub(crate) fn next_str(&mut self) -> Result<&'a str, CoreError> {
        self.it
            .next()
            .ok_or_else(|| bad(self.path, format!("MSH section ${} ends early", self.section)))
    }
    pub(crate) fn int(&mut self) -> Result<i64, CoreError> {
        let t = self.next_str()?;
        t.parse().map_err(|_| {
            bad(
                self.path,
                format!("MSH section ${}: expected an integer, got '{t}'", self.section),
            )
        })
    }
    pub(crate) fn count(&mut self) -> Result<usize, CoreError> {
        let v = self.int()?;
        usize::try_from(v).map_err(|_| bad(self.path, format!("MSH section ${}: negative count {v}", self.section)))
    }
    pub(crate) fn tag(&mut self) -> Result<u64, CoreError> {
        let v = self.int()?;
        u64::try_from(v).map_err(|_| bad(self.path, format!("MSH section ${}: negative tag {v}", self.section)))
    }
    pub(crate) fn real(&mut self) -> Result<f64, CoreError> {
        let t = self.next_str()?;
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(bad(
                self.path,
                format!("MSH section ${}: expected a finite number, got '{t}'", self.section),
            )),
        }
    }
}

/// The text between `$name` and `$Endname`, if the section is present.
pub(crate) fn section<'a>(text: &'a str, name: &str, path: &str) -> Result<Option<&'a str>, CoreError> {
    let open = format!("${name}");
    let close = format!("$End{name}");
    let mut start = None;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let l = line.trim();
        if start.is_none() && l == open {
            start = Some(offset + line.len());
        } else if let Some(s) = start {
            if l == close {
                return Ok(Some(&text[s..offset]));
            }
        }
        offset += line.len();
    }
    match start {
        Some(_) => Err(bad(path, format!("MSH section {open} has no {close}"))),
        None => Ok(None),
    }
}

/// The physical groups of a file: names and which groups each entity is in.
pub(crate) struct Header {
    /// Physical group (dim, tag) → name.
    names: HashMap<(i64, i64), String>,
    /// Entity (dim, tag) → its physical group tags.
    physicals: HashMap<(i64, i64), Vec<i64>>,
}

impl Header {
    /// The name of physical group (dim, tag); a group without a name is named by its tag.
    pub(crate) fn group_name(&self, dim: i64, tag: i64) -> String {
        self.names.get(&(dim, tag)).cloned().unwrap_or_else(|| tag.to_string())
    }

    /// The names of the physical groups entity (dim, tag) is in.
    pub(crate) fn groups_of(&self, dim: i64, entity: i64) -> Vec<String> {
        self.physicals
            .get(&(dim, entity))
            .map(|g| g.iter().map(|&p| self.group_name(dim, p)).collect())
            .unwrap_or_default()
    }

    /// Whether entity (dim, tag) belongs to the body made of the groups
    /// `wanted` (empty: every entity of that dimension).
    pub(crate) fn in_body(&self, dim: i64, entity: i64, wanted: &[String]) -> bool {
        wanted.is_empty() || self.groups_of(dim, entity).iter().any(|g| wanted.contains(g))
    }

    /// Every name in `wanted` is a physical group of dimension `dim`
    /// (`what`: "surface", "volume"); the refusal lists the groups there are.
    pub(crate) fn check_named(&self, dim: i64, wanted: &[String], what: &str, path: &str) -> Result<(), CoreError> {
        for s in wanted {
            if !self.names.iter().any(|(&(d, _), n)| d == dim && n == s) {
                let mut have: Vec<&str> = self
                    .names
                    .iter()
                    .filter(|((d, _), _)| *d == dim)
                    .map(|(_, n)| n.as_str())
                    .collect();
                have.sort_unstable();
                return Err(CoreError::invalid(
                    InvalidKind::Request,
                    path,
                    format!(
                        "no physical {what} group named '{s}' in the MSH file (it has: {})",
                        if have.is_empty() {
                            "none".to_string()
                        } else {
                            have.join(", ")
                        }
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Checks `$MeshFormat` (4.1, ASCII) and reads the physical groups.
pub(crate) fn try_header(text: &str, path: &str) -> Result<Header, CoreError> {
    let format =
        section(text, "MeshFormat", path)?.ok_or_else(|| bad(path, "not a Gmsh MSH file: no $MeshFormat section"))?;
    let mut f = format.split_ascii_whitespace();
    let (version, file_type) = (f.next().unwrap_or(""), f.next().unwrap_or(""));
    if version != "4.1" {
        return Err(bad(
            path,
            format!(
                "MSH version '{version}' is not read; save the mesh as MSH 4.1 (gmsh: -format msh41, or option \
                Mesh.MshFileVersion = 4.1)"
            ),
        ));
    }
    if file_type != "0" {
        return Err(bad(
            path,
            "binary MSH is not read; save the mesh as ASCII (gmsh: option Mesh.Binary = 0, the default)",
        ));
    }
    // Physical group (dim, tag) → name.
    let mut names: HashMap<(i64, i64), String> = HashMap::new();
    if let Some(s) = section(text, "PhysicalNames", path)? {
        for line in s.lines().skip(1) {
            let l = line.trim();
            if l.is_empty() {
                continue;
            }
            let mut parts = l.splitn(3, char::is_whitespace);
            let dim = parts.next().and_then(|v| v.parse::<i64>().ok());
            let tag = parts.next().and_then(|v| v.parse::<i64>().ok());
            let name = parts.next().map(|v| v.trim().trim_matches('"').to_string());
            match (dim, tag, name) {
                (Some(d), Some(t), Some(n)) => {
                    names.insert((d, t), n);
                }
                _ => return Err(bad(path, format!("MSH section $PhysicalNames: cannot read '{l}'"))),
            }
        }
    }

    // Entity (dim, tag) → its physical group tags.
    let mut physicals: HashMap<(i64, i64), Vec<i64>> = HashMap::new();
    if let Some(s) = section(text, "Entities", path)? {
        let mut t = Tokens {
            it: s.split_ascii_whitespace(),
            section: "Entities",
            path,
            len: s.len(),
        };
        let counts = [t.count()?, t.count()?, t.count()?, t.count()?];
        for (dim, &n) in counts.iter().enumerate() {
            for _ in 0..n {
                let tag = t.int()?;
                // A point has its coordinates, the others their bounding box.
                for _ in 0..if dim == 0 { 3 } else { 6 } {
                    t.real()?;
                }
                let np = t.count()?;
                let mut groups = Vec::new();
                for _ in 0..np {
                    groups.push(t.int()?);
                }
                if dim > 0 {
                    let nb = t.count()?;
                    for _ in 0..nb {
                        t.int()?;
                    }
                }
                physicals.insert((dim as i64, tag), groups);
            }
        }
    }
    Ok(Header { names, physicals })
}

/// The nodes of `$Nodes` in file order: their tags, coordinates and the
/// index of each tag.
pub(crate) struct Nodes {
    pub tags: Vec<u64>,
    pub coords: Vec<[f64; 3]>,
    pub index_of_tag: HashMap<u64, usize>,
}

impl Nodes {
    /// The index of node `tag`, which element `element` refers to.
    pub(crate) fn index(&self, tag: u64, element: u64, path: &str) -> Result<usize, CoreError> {
        self.index_of_tag.get(&tag).copied().ok_or_else(|| {
            bad(
                path,
                format!("Gmsh element {element} refers to node {tag}, which $Nodes does not list"),
            )
        })
    }
}

/// Reads `$Nodes`.
pub(crate) fn try_nodes(text: &str, path: &str) -> Result<Nodes, CoreError> {
    let (mut t, blocks) = Tokens::blocks(text, "Nodes", path)?;
    let mut node_tags: Vec<u64> = Vec::new();
    let mut coords: Vec<[f64; 3]> = Vec::new();
    for _ in 0..blocks {
        let dim = t.int()?;
        t.int()?;
        let parametric = t.int()? != 0;
        let n = t.count()?;
        node_tags.reserve_exact(t.at_most(n, 4));
        coords.reserve_exact(t.at_most(n, 4));
        for _ in 0..n {
            node_tags.push(t.tag()?);
        }
        for _ in 0..n {
            coords.push([t.real()?, t.real()?, t.real()?]);
            if parametric {
                for _ in 0..dim.clamp(0, 3) {
                    t.real()?;
                }
            }
        }
    }
    let mut index_of_tag: HashMap<u64, usize> = HashMap::with_capacity(node_tags.len());
    for (i, &tag) in node_tags.iter().enumerate() {
        if index_of_tag.insert(tag, i).is_some() {
            return Err(bad(path, format!("Gmsh node tag {tag} appears twice in $Nodes")));
        }
    }
    Ok(Nodes {
        tags: node_tags,
        coords,
        index_of_tag,
    })
}

/// The words of a reader's messages: the dimension of its body's entities
/// ("surface"), of its sets' physical groups ("curve"), what a member of a
/// set is ("line element"), what the body is made of ("triangles") and, in
/// full, which element types a body and its sets are made of.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Words {
    pub entity: &'static str,
    pub group: &'static str,
    pub member: &'static str,
    pub elements: &'static str,
    pub body_types: &'static str,
    pub set_types: &'static str,
}

/// The header of an element block: its entity (dim, tag), element type,
/// element count and nodes per element.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Block {
    pub dim: i64,
    pub entity: i64,
    pub etype: i64,
    pub n: usize,
    pub npe: usize,
}

impl Block {
    /// The refusal of this block's elements on an entity of the body or a set (`on`: its dimension's name).
    pub(crate) fn unsupported(&self, on: &str, words: Words, path: &str) -> CoreError {
        let Block { etype, entity, .. } = *self;
        bad(
            path,
            format!(
                "Gmsh {} elements (type {etype}) on {on} entity {entity} are not supported: {}, {}",
                type_name(etype),
                words.body_types,
                words.set_types
            ),
        )
    }
}

impl Tokens<'_> {
    /// The next element block's header; a type of unknown node count is refused.
    pub(crate) fn block(&mut self, words: Words) -> Result<Block, CoreError> {
        let (dim, entity, etype, n) = (self.int()?, self.int()?, self.int()?, self.count()?);
        let npe = nodes_per_element(etype).ok_or_else(|| {
            bad(
                self.path,
                format!(
                    "Gmsh element type {etype} (entity {entity} of dimension {dim}) is not supported: {}",
                    words.body_types
                ),
            )
        })?;
        Ok(Block {
            dim,
            entity,
            etype,
            n,
            npe,
        })
    }

    /// The next element of a block: its tag, and its nodes' tags into `conn`.
    pub(crate) fn element(&mut self, conn: &mut [u64]) -> Result<u64, CoreError> {
        let tag = self.tag()?;
        for c in conn.iter_mut() {
            *c = self.tag()?;
        }
        Ok(tag)
    }
}

/// Where an item of a mesh read from the MSH text at `path` is: the text's
/// JSON pointer, and a message prefix naming Gmsh's own tags (`element_tags`:
/// (element tag, entity tag) of each element; `member_tags`: the element tags
/// of each set's members, in order).
pub(crate) fn locate<'a>(
    path: &'a str,
    element_tags: &'a [(u64, i64)],
    member_tags: &'a BTreeMap<String, Vec<u64>>,
    words: Words,
) -> impl Fn(Item) -> (String, String) + 'a {
    move |item: Item| {
        let Words {
            entity, group, member, ..
        } = words;
        let context = match item {
            Item::Nodes | Item::Elements | Item::Node(_) => "Gmsh mesh: ".to_string(),
            Item::Element(e) | Item::ElementNode(e, _) => {
                let (tag, ent) = element_tags[e];
                format!("Gmsh element {tag} ({entity} entity {ent}): ")
            }
            Item::Set(name) => format!("Gmsh physical {group} group '{name}': "),
            Item::Member(name, k) => {
                let tag = member_tags.get(name).and_then(|t| t.get(k)).copied().unwrap_or(0);
                format!("Gmsh physical {group} group '{name}', {member} {tag}: ")
            }
        };
        (path.to_string(), context)
    }
}

/// The elements that make up a body, kept flat as they are read (a list per
/// element cost 70 bytes more each).
#[derive(Debug, Default)]
pub(crate) struct Body {
    /// File node indices, `per` each, one element after the other.
    pub nodes: Vec<usize>,
    /// (element tag, entity tag) of each element.
    pub tags: Vec<(u64, i64)>,
    /// Nodes per element (0 before the first).
    pub per: usize,
}

impl Body {
    /// Room for a block of `n` elements of `npe` nodes, as far as the section's text can hold them.
    pub(crate) fn reserve(&mut self, t: &Tokens, n: usize, npe: usize) {
        self.nodes.reserve_exact(t.at_most(n, 1 + npe) * npe);
        self.tags.reserve_exact(t.at_most(n, 1 + npe));
    }

    /// Adds element `tag` of `entity` (a `words.entity`) with its nodes' tags `conn`.
    pub(crate) fn push(
        &mut self,
        (tag, entity): (u64, i64),
        conn: &[u64],
        file: &Nodes,
        words: Words,
        path: &str,
    ) -> Result<(), CoreError> {
        if self.per == 0 {
            self.per = conn.len();
        } else if conn.len() != self.per {
            return Err(bad(
                path,
                format!(
                    "Gmsh element {tag} ({} entity {entity}): element has {} nodes but element 0 has {}; mixed \
                        orders are not supported",
                    words.entity,
                    conn.len(),
                    self.per
                ),
            ));
        }
        for &c in conn {
            self.nodes.push(file.index(c, tag, path)?);
        }
        self.tags.push((tag, entity));
        Ok(())
    }

    /// Keeps the file's nodes that the elements use, in file order, and
    /// renumbers the elements to them: for each of the file's `n` nodes, its
    /// index among the kept ones (usize::MAX: unused).
    pub(crate) fn keep_used(&mut self, n: usize) -> Vec<usize> {
        let mut local = vec![usize::MAX; n];
        for &k in &self.nodes {
            local[k] = 0;
        }
        for (kept, l) in local.iter_mut().filter(|l| **l == 0).enumerate() {
            *l = kept;
        }
        for k in self.nodes.iter_mut() {
            *k = local[*k];
        }
        local
    }
}

/// A reader's named sets (K corner nodes per member) and their members' element tags.
pub(crate) type Sets<const K: usize> = (BTreeMap<String, Vec<[usize; K]>>, BTreeMap<String, Vec<u64>>);

/// The named sets' members (K corner nodes as file node indices, with their
/// element tags) renumbered to the body's nodes (`local`, from
/// `Body::keep_used`), and the tags of each set's members apart.
pub(crate) fn try_sets<const K: usize>(
    members: BTreeMap<String, Vec<(u64, [usize; K])>>,
    local: &[usize],
    words: Words,
    path: &str,
) -> Result<Sets<K>, CoreError> {
    let (mut sets, mut tags) = (BTreeMap::new(), BTreeMap::new());
    for (name, ms) in members {
        let mut set = Vec::with_capacity(ms.len());
        let mut set_tags = Vec::with_capacity(ms.len());
        for (tag, c) in ms {
            if c.iter().any(|&n| local[n] == usize::MAX) {
                return Err(bad(
                    path,
                    format!(
                        "Gmsh physical {} group '{name}', {} {tag}: its nodes are not nodes of the body's {}",
                        words.group, words.member, words.elements
                    ),
                ));
            }
            set.push(c.map(|n| local[n]));
            set_tags.push(tag);
        }
        sets.insert(name.clone(), set);
        tags.insert(name, set_tags);
    }
    Ok((sets, tags))
}
