//! File references in a request, resolved for the command-line tool.
//!
//! A body's mesh may be `{"gmsh": {"file": "hertz.msh"}}`: `contact solve FILE`
//! reads it relative to the request file's directory and sends the text on as
//! `{"gmsh": {"msh": "..."}}`. The service never reads files (a request naming
//! one is refused in validation). The reading is the caller's `read`, so this
//! module does no I/O.

use crate::proto::{ErrorCode, ErrorReply};

/// The request with every Gmsh `file` replaced by the file's text (`msh`).
/// Bytes that are not a JSON object, or name no file, come back unchanged.
pub fn resolve_gmsh_files(bytes: &[u8], read: impl Fn(&str) -> Result<String, String>) -> Result<Vec<u8>, ErrorReply> {
    // A JSON value costs 32 bytes and more a number: 0.29 GB of the 0.56 GB
    // that `contact solve` took for a 70 MB inline mesh, which names no file.
    // (A key spelled with escapes, "\u0066ile", is not looked for.)
    if !bytes.windows(6).any(|w| w == b"\"file\"") {
        return Ok(bytes.to_vec());
    }
    let Ok(mut value) = serde_json::from_slice::<serde_json::Value>(bytes) else {
        return Ok(bytes.to_vec());
    };
    let mut changed = false;
    let bodies = value.get_mut("bodies").and_then(|b| b.as_array_mut());
    for (i, body) in bodies.into_iter().flatten().enumerate() {
        let Some(g) = body.pointer_mut("/mesh/gmsh").and_then(|g| g.as_object_mut()) else {
            continue;
        };
        let Some(file) = g.get("file").and_then(|f| f.as_str()).map(str::to_string) else {
            continue;
        };
        let path = format!("/bodies/{i}/mesh/gmsh/file");
        if g.contains_key("msh") {
            return Err(ErrorReply::new(
                ErrorCode::InvalidRequest,
                "give the Gmsh mesh as `file` or as `msh`, not both",
                path,
            ));
        }
        let text = read(&file)
            .map_err(|e| ErrorReply::new(ErrorCode::InvalidRequest, format!("cannot read '{file}': {e}"), path))?;
        g.remove("file");
        g.insert("msh".into(), serde_json::Value::String(text));
        changed = true;
    }
    if !changed {
        return Ok(bytes.to_vec());
    }
    Ok(serde_json::to_vec(&value).expect("a JSON value serializes"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_reference_becomes_the_files_text() {
        let req = br#"{"bodies": [{"mesh": {"gmsh": {"file": "m.msh", "surfaces": ["s"]}}}]}"#;
        let out = resolve_gmsh_files(req, |f| Ok(format!("text of {f}"))).unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v.pointer("/bodies/0/mesh/gmsh/msh").unwrap(), "text of m.msh");
        assert!(v.pointer("/bodies/0/mesh/gmsh/file").is_none());
        assert_eq!(v.pointer("/bodies/0/mesh/gmsh/surfaces/0").unwrap(), "s");
    }

    #[test]
    fn an_unreadable_file_names_the_field_and_other_requests_pass_unchanged() {
        let req = br#"{"bodies": [{"mesh": {"rectangle": {}}}, {"mesh": {"gmsh": {"file": "no.msh"}}}]}"#;
        let err = resolve_gmsh_files(req, |_| Err("not found".into())).unwrap_err();
        assert_eq!(err.path, "/bodies/1/mesh/gmsh/file");
        assert!(err.message.contains("no.msh"));
        let plain = br#"{"bodies": [{"mesh": {"rectangle": {}}}]} "#;
        assert_eq!(resolve_gmsh_files(plain, |_| unreachable!()).unwrap(), plain.to_vec());
        assert_eq!(
            resolve_gmsh_files(b"not json", |_| unreachable!()).unwrap(),
            b"not json".to_vec()
        );
    }
}
