//! Bytes → `SolveRequest`, telling syntax errors (malformed JSON) from schema
//! errors (valid JSON that does not fit), the latter with a JSON pointer.
//!
//! The request is read straight into its types, with no intermediate
//! `serde_json::Value` (which costs 32 bytes and more per number: a 60 MB
//! payload of numbers took about 1.2 GB that way), and the lists the
//! deployment bounds (`load_factors`) stop at their limit while being read
//! (`contact_proto::bounded`). A schema error is reported only when the whole
//! text is JSON (checked then by a pass that builds nothing), so a truncated
//! document is "malformed", not "missing field".

use contact_core::error::{CoreError, InvalidKind};
use contact_core::Limits;
use contact_proto::bounded::ListLimits;
use contact_proto::SolveRequest;
use serde_json::error::Category;

pub fn parse_request(bytes: &[u8], limits: &Limits) -> Result<SolveRequest, CoreError> {
    let text = std::str::from_utf8(bytes).map_err(|e| CoreError::Malformed {
        message: format!("payload is not UTF-8: {e}"),
    })?;
    let first = text.trim_start_matches([' ', '\t', '\n', '\r']).chars().next();
    if first != Some('{') {
        syntax(text)?;
        let kind = match first {
            Some('[') => "an array",
            Some('"') => "a string",
            Some('t' | 'f') => "a boolean",
            Some('n') => "null",
            _ => "a number",
        };
        // Valid JSON of the wrong shape: an invalid request, not a malformed one.
        return Err(CoreError::invalid(
            InvalidKind::Request,
            "",
            format!("the request must be a JSON object {{\"version\": \"1\", \"bodies\": [...], ...}}, got {kind}"),
        ));
    }
    let bounds = ListLimits::install(limits.max_load_steps);
    let mut de = serde_json::Deserializer::from_str(text);
    let err = match serde_path_to_error::deserialize::<_, SolveRequest>(&mut de) {
        Ok(req) => {
            // Trailing characters after the object.
            de.end().map_err(|e| malformed(text, &e))?;
            return Ok(req);
        }
        Err(e) => e,
    };
    if let Some(over) = bounds.overflow() {
        // The text past the limit is not read: too large, whatever it holds.
        return Err(CoreError::TooLarge {
            path: over.path.into(),
            reason: format!(
                "more than {} {}; this service solves at most {} load steps per request (split the list)",
                over.limit,
                if over.path == "/load_path" {
                    "load path steps"
                } else {
                    "load factors"
                },
                over.limit
            ),
        });
    }
    let path = pointer(err.path());
    let inner = err.into_inner();
    match inner.classify() {
        Category::Data => {
            syntax(text)?;
            Err(CoreError::invalid(
                InvalidKind::Request,
                path,
                strip_position(&inner.to_string()),
            ))
        }
        Category::Syntax | Category::Eof | Category::Io => Err(malformed(text, &inner)),
    }
}

/// `Malformed` unless `text` is one JSON value, read without building it.
/// serde's `IgnoredAny` would skip nested values without serde_json's
/// recursion limit (128 levels); `Skip` recurses through `deserialize_any`, so
/// a document nested deeper is malformed here exactly as when it is read.
fn syntax(text: &str) -> Result<(), CoreError> {
    serde_json::from_str::<Skip>(text)
        .map(|_| ())
        .map_err(|e| malformed(text, &e))
}

struct Skip;

impl<'de> serde::Deserialize<'de> for Skip {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(Skip)
    }
}

impl<'de> serde::de::Visitor<'de> for Skip {
    type Value = Skip;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("any JSON value")
    }
    fn visit_bool<E>(self, _: bool) -> Result<Skip, E> {
        Ok(Skip)
    }
    fn visit_i64<E>(self, _: i64) -> Result<Skip, E> {
        Ok(Skip)
    }
    fn visit_u64<E>(self, _: u64) -> Result<Skip, E> {
        Ok(Skip)
    }
    fn visit_f64<E>(self, _: f64) -> Result<Skip, E> {
        Ok(Skip)
    }
    fn visit_str<E>(self, _: &str) -> Result<Skip, E> {
        Ok(Skip)
    }
    fn visit_unit<E>(self) -> Result<Skip, E> {
        Ok(Skip)
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Skip, A::Error> {
        while seq.next_element::<Skip>()?.is_some() {}
        Ok(Skip)
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Skip, A::Error> {
        while map.next_entry::<serde::de::IgnoredAny, Skip>()?.is_some() {}
        Ok(Skip)
    }
}

fn malformed(text: &str, e: &serde_json::Error) -> CoreError {
    CoreError::Malformed {
        message: non_finite_literal(text, e).unwrap_or_else(|| e.to_string()),
    }
}

fn strip_position(s: &str) -> String {
    match s.find(" at line ") {
        Some(k) => s[..k].to_string(),
        None => s.to_string(),
    }
}

/// serde_path_to_error's path → RFC 6901 JSON pointer.
fn pointer(path: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let mut out = String::new();
    for seg in path.iter() {
        match seg {
            Segment::Seq { index } => out.push_str(&format!("/{index}")),
            Segment::Map { key } => out.push_str(&format!("/{}", key.replace('~', "~0").replace('/', "~1"))),
            Segment::Enum { variant } => out.push_str(&format!("/{variant}")),
            Segment::Unknown => {}
        }
    }
    out
}

/// A syntax error at a NaN or Infinity literal (which JavaScript and Python's
/// json module write, but JSON has no such values), said so, with the field.
fn non_finite_literal(text: &str, e: &serde_json::Error) -> Option<String> {
    let line = text.lines().nth(e.line().checked_sub(1)?)?;
    // serde_json reports the column just past the first offending character.
    let start = e.column().saturating_sub(2);
    let rest = line.get(start.min(line.len())..)?;
    let rest = rest.trim_start_matches(['-', '+']);
    let literal = ["NaN", "Infinity", "nan", "inf"].into_iter().find(|l| {
        rest.starts_with(l)
            || line
                .get(e.column().saturating_sub(1)..)
                .is_some_and(|r| r.starts_with(l))
    })?;
    let before = &line[..start.min(line.len())];
    let field = before
        .rfind("\":")
        .or_else(|| before.rfind("\" :"))
        .and_then(|end| before[..end].rfind('"').map(|b| &before[b + 1..end]));
    Some(format!(
        "JSON has no {literal}: {} holds {literal} (line {}, column {}); send a finite number",
        field.map_or("a value".to_string(), |f| format!("field '{f}'")),
        e.line(),
        e.column()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(text: &str) -> String {
        match parse_request(text.as_bytes(), &Limits::default()) {
            Err(CoreError::Malformed { message }) => message,
            other => panic!("expected malformed, got {other:?}"),
        }
    }

    #[test]
    fn nan_and_infinity_are_named_with_their_field() {
        let m = message(r#"{"version": "1", "bodies": [{"material": {"youngs_modulus": NaN}}]}"#);
        assert!(m.contains("JSON has no NaN") && m.contains("'youngs_modulus'"), "{m}");
        let m = message(r#"{"version": "1", "time_limit": -Infinity}"#);
        assert!(m.contains("Infinity") && m.contains("'time_limit'"), "{m}");
    }

    #[test]
    fn a_payload_that_is_not_an_object_is_said_so() {
        for (text, kind) in [("[1, 2]", "got an array"), ("42", "got a number")] {
            let e = crate::wire::error_reply(&parse_request(text.as_bytes(), &Limits::default()).unwrap_err());
            assert_eq!(e.code, crate::proto::ErrorCode::InvalidRequest);
            assert!(
                e.message.contains("must be a JSON object") && e.message.contains(kind),
                "{}",
                e.message
            );
        }
    }

    /// A list past its limit is refused `too_large` as soon as the first
    /// entry past the limit is read: what follows (here text that is not
    /// JSON) is never looked at, so reading costs the limit, not the payload.
    #[test]
    fn a_list_past_its_limit_is_too_large_unread() {
        let limits = Limits {
            max_load_steps: 3,
            ..Limits::default()
        };
        let text = r#"{"version": "1", "load_factors": [1, 2, 3, 4, 5 garbage"#;
        match parse_request(text.as_bytes(), &limits) {
            Err(CoreError::TooLarge { path, reason }) => {
                assert_eq!(path, "/load_factors");
                assert!(reason.contains("more than 3 load factors"), "{reason}");
            }
            other => panic!("expected too_large, got {other:?}"),
        }
        let ok = r#"{"version": "1", "bodies": [], "contacts": [], "load_factors": [1, 2, 3]}"#;
        assert_eq!(
            parse_request(ok.as_bytes(), &limits).unwrap().load_factors,
            [1.0, 2.0, 3.0]
        );
    }

    /// The request is read straight into its types, yet a document that is
    /// not JSON is "malformed" even when a field before its fault has the
    /// wrong type, and trailing text after the object is malformed too.
    #[test]
    fn syntax_errors_win_over_schema_errors() {
        assert!(message(r#"{"version": 1, "bodies": ["#).contains("EOF"));
        assert!(message(r#"{"version": "1", "bodies": [], "contacts": []} x"#).contains("trailing"));
        match parse_request(br#"{"version": 1, "bodies": [], "contacts": []}"#, &Limits::default()) {
            Err(CoreError::Invalid { path, .. }) => assert_eq!(path, "/version"),
            other => panic!("expected invalid, got {other:?}"),
        }
    }
}
