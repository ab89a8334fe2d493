//! Lists whose length a deployment bounds, counted while they are read.
//!
//! A list of numbers costs 8 bytes per entry once read, from as little as 2
//! bytes of JSON ("1,"), and building it before checking its length let one
//! 60 MB request with a 30M-entry `load_factors` list cost about 1.2 GB
//! (through an intermediate `serde_json::Value`, 32 bytes per number and
//! more). The deserializer below stops at the limit instead: at most
//! `limit + 1` entries are ever read. The limit is the reader's (a thread-local
//! set with [`ListLimits::install`] around one parse, as the deployment's
//! limits are not known to the types); without it every list is unbounded.

use std::cell::Cell;

use serde::de::{Deserializer, Error, SeqAccess, Visitor};

thread_local! {
    static MAX_LOAD_FACTORS: Cell<usize> = const { Cell::new(usize::MAX) };
    static OVERFLOW: Cell<Option<Overflow>> = const { Cell::new(None) };
}

/// A list cut at its limit: the JSON pointer of the list and the limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Overflow {
    pub path: &'static str,
    pub limit: usize,
}

/// While alive, lists read on this thread stop at these lengths.
#[must_use = "the limits are lifted when the guard is dropped"]
pub struct ListLimits {
    previous: usize,
}

impl ListLimits {
    /// Bounds `load_factors` to `max_load_factors` entries and forgets any
    /// earlier overflow.
    pub fn install(max_load_factors: usize) -> Self {
        OVERFLOW.with(|o| o.set(None));
        Self {
            previous: MAX_LOAD_FACTORS.with(|m| m.replace(max_load_factors)),
        }
    }

    /// The list that stopped the last read on this thread, if one did.
    pub fn overflow(&self) -> Option<Overflow> {
        OVERFLOW.with(|o| o.get())
    }
}

impl Drop for ListLimits {
    fn drop(&mut self) {
        MAX_LOAD_FACTORS.with(|m| m.set(self.previous));
        OVERFLOW.with(|o| o.set(None));
    }
}

/// `load_factors`, stopped with an error at the first entry past the limit.
pub fn load_factors<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    bounded(d, "/load_factors")
}

/// `load_path`, bounded by the same limit (each step is a load step): a
/// payload of empty steps, 13 bytes each, would otherwise hold a step map
/// per 13 bytes before validation counts them. Generic over the step (the
/// field's type names it), so that this module reads no request type.
pub fn load_path<'de, D: Deserializer<'de>, T: serde::Deserialize<'de>>(d: D) -> Result<Vec<T>, D::Error> {
    bounded(d, "/load_path")
}

fn bounded<'de, D: Deserializer<'de>, T: serde::Deserialize<'de>>(
    d: D,
    path: &'static str,
) -> Result<Vec<T>, D::Error> {
    let limit = MAX_LOAD_FACTORS.with(|m| m.get());
    d.deserialize_seq(Bounded {
        limit,
        path,
        item: std::marker::PhantomData,
    })
}

struct Bounded<T> {
    limit: usize,
    path: &'static str,
    item: std::marker::PhantomData<T>,
}

impl<'de, T: serde::Deserialize<'de>> Visitor<'de> for Bounded<T> {
    type Value = Vec<T>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "a list of at most {} entries", self.limit)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
        // The size hint comes from the payload: trusted only up to the limit.
        let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(self.limit).min(1 << 16));
        while let Some(x) = seq.next_element::<T>()? {
            if out.len() == self.limit {
                OVERFLOW.with(|o| {
                    o.set(Some(Overflow {
                        path: self.path,
                        limit: self.limit,
                    }))
                });
                return Err(A::Error::custom(format!(
                    "more than {} entries at {}",
                    self.limit, self.path
                )));
            }
            out.push(x);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize, Debug)]
    struct Doc {
        #[serde(deserialize_with = "load_factors")]
        f: Vec<f64>,
    }

    /// The read stops at the first entry past the limit, before the rest of
    /// the list (here, a syntax error it never reaches) is looked at.
    #[test]
    fn a_list_stops_one_past_its_limit() {
        let guard = ListLimits::install(3);
        let ok: Doc = serde_json::from_str(r#"{"f": [1, 2, 3]}"#).unwrap();
        assert_eq!(ok.f, [1.0, 2.0, 3.0]);
        assert_eq!(guard.overflow(), None);
        let cut = serde_json::from_str::<Doc>(r#"{"f": [1, 2, 3, 4, this is never read"#);
        assert!(cut.unwrap_err().is_data());
        assert_eq!(
            guard.overflow(),
            Some(Overflow {
                path: "/load_factors",
                limit: 3
            })
        );
        drop(guard);
        let free: Doc = serde_json::from_str(r#"{"f": [1, 2, 3, 4, 5]}"#).unwrap();
        assert_eq!(free.f.len(), 5, "without limits a list is read whole");
    }
}
