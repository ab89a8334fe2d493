//! The elements of an inline mesh as read: every element's node indices one
//! after the other, and where each element ends.
//!
//! On the wire they are a list of lists (`[[0, 1, 2], ...]`, the schema of
//! `Vec<Vec<usize>>`); read into a `Vec` per element they cost about 72 bytes
//! each (a 24-byte header and a heap block of 4 indices), against the 20–25
//! bytes of their JSON text: 117 MB of the 880 MB that reading a 70 MB inline
//! mesh of 1.6M triangles took. Here a T3 element costs 32 bytes. Lists of any
//! length are kept as they are, so that validation still names an element of
//! the wrong length.

use std::borrow::Cow;

use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::de::{DeserializeSeed, Deserializer, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ElementLists {
    nodes: Vec<usize>,
    /// End of each element in `nodes` (exclusive).
    ends: Vec<usize>,
}

impl ElementLists {
    pub fn len(&self) -> usize {
        self.ends.len()
    }
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }
    /// Node indices of element `e`.
    pub fn get(&self, e: usize) -> &[usize] {
        let start = if e == 0 { 0 } else { self.ends[e - 1] };
        &self.nodes[start..self.ends[e]]
    }
    pub fn iter(&self) -> impl Iterator<Item = &[usize]> + '_ {
        (0..self.len()).map(|e| self.get(e))
    }
    /// Every node index, element after element, and the end of each element.
    pub fn as_parts(&self) -> (&[usize], &[usize]) {
        (&self.nodes, &self.ends)
    }
}

impl<L: AsRef<[usize]>> FromIterator<L> for ElementLists {
    fn from_iter<I: IntoIterator<Item = L>>(lists: I) -> Self {
        let mut out = Self::default();
        for l in lists {
            out.nodes.extend_from_slice(l.as_ref());
            out.ends.push(out.nodes.len());
        }
        out
    }
}

impl Serialize for ElementLists {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.len()))?;
        for e in self.iter() {
            seq.serialize_element(e)?;
        }
        seq.end()
    }
}

impl<'de> Deserialize<'de> for ElementLists {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_seq(Outer)
    }
}

struct Outer;

impl<'de> Visitor<'de> for Outer {
    type Value = ElementLists;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a list of elements, each a list of node indices")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ElementLists, A::Error> {
        let mut out = ElementLists::default();
        while seq.next_element_seed(Inner(&mut out.nodes))?.is_some() {
            out.ends.push(out.nodes.len());
        }
        Ok(out)
    }
}

/// One element's list, appended to the shared `nodes`.
struct Inner<'a>(&'a mut Vec<usize>);

impl<'de> DeserializeSeed<'de> for Inner<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Inner<'_> {
    type Value = ();

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a list of node indices")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        while let Some(n) = seq.next_element::<usize>()? {
            self.0.push(n);
        }
        Ok(())
    }
}

/// The schema of the list of lists it reads.
impl JsonSchema for ElementLists {
    fn inline_schema() -> bool {
        <Vec<Vec<usize>>>::inline_schema()
    }
    fn schema_name() -> Cow<'static, str> {
        <Vec<Vec<usize>>>::schema_name()
    }
    fn schema_id() -> Cow<'static, str> {
        <Vec<Vec<usize>>>::schema_id()
    }
    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        <Vec<Vec<usize>>>::json_schema(generator)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_of_any_length_read_and_write_as_they_were() {
        let text = "[[0,1,2],[2,1,3,4,5,6],[]]";
        let e: ElementLists = serde_json::from_str(text).unwrap();
        assert_eq!(
            (e.len(), e.get(0), e.get(1), e.get(2)),
            (3, &[0, 1, 2][..], &[2, 1, 3, 4, 5, 6][..], &[][..])
        );
        assert_eq!(serde_json::to_string(&e).unwrap(), text);
        assert_eq!(
            e,
            [[0, 1, 2].as_slice(), &[2, 1, 3, 4, 5, 6], &[]].into_iter().collect()
        );
        assert!(serde_json::from_str::<ElementLists>("[[0,-1]]").is_err());
        assert!(serde_json::from_str::<ElementLists>("[0]").is_err());
    }

    #[test]
    fn the_schema_is_that_of_a_list_of_lists() {
        let ours = schemars::schema_for!(ElementLists);
        let theirs = schemars::schema_for!(Vec<Vec<usize>>);
        assert_eq!(ours, theirs);
    }
}
