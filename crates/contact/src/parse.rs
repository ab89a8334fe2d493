//! Bytes → `SolveRequest`, telling syntax errors (malformed JSON) from schema
//! errors (valid JSON that does not fit), the latter with a JSON pointer.

use contact_core::error::{CoreError, InvalidKind};
use contact_proto::SolveRequest;

pub fn parse_request(bytes: &[u8]) -> Result<SolveRequest, CoreError> {
    let text = std::str::from_utf8(bytes).map_err(|e| CoreError::Malformed {
        message: format!("payload is not UTF-8: {e}"),
    })?;
    // Syntax first, so a truncated document is "malformed", not "missing field".
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| CoreError::Malformed {
        message: non_finite_literal(text, &e).unwrap_or_else(|| e.to_string()),
    })?;
    if !value.is_object() {
        let kind = match value {
            serde_json::Value::Array(_) => "an array",
            serde_json::Value::String(_) => "a string",
            serde_json::Value::Number(_) => "a number",
            serde_json::Value::Bool(_) => "a boolean",
            _ => "null",
        };
        // Valid JSON of the wrong shape: an invalid request, not a malformed one.
        return Err(CoreError::invalid(
            InvalidKind::Request,
            "",
            format!("the request must be a JSON object {{\"version\": \"1\", \"bodies\": [...], ...}}, got {kind}"),
        ));
    }
    let req: SolveRequest = serde_path_to_error::deserialize(value).map_err(|e| {
        let path = pointer(e.path());
        CoreError::invalid(InvalidKind::Request, path, strip_position(&e.into_inner().to_string()))
    })?;
    Ok(req)
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
        match parse_request(text.as_bytes()) {
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
            let e = crate::wire::error_reply(&parse_request(text.as_bytes()).unwrap_err());
            assert_eq!(e.code, crate::proto::ErrorCode::InvalidRequest);
            assert!(
                e.message.contains("must be a JSON object") && e.message.contains(kind),
                "{}",
                e.message
            );
        }
    }
}
