//! Bytes → `SolveRequest`, telling syntax errors (malformed JSON) from schema
//! errors (valid JSON that does not fit), the latter with a JSON pointer.

use crate::error::{CoreError, InvalidKind};
use crate::proto::SolveRequest;

pub fn parse_request(bytes: &[u8]) -> Result<SolveRequest, CoreError> {
    let text = std::str::from_utf8(bytes).map_err(|e| CoreError::Malformed {
        message: format!("payload is not UTF-8: {e}"),
    })?;
    // Syntax first, so a truncated document is "malformed", not "missing field".
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| CoreError::Malformed { message: e.to_string() })?;
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
