//! The checked-in JSON Schemas must match the Rust types; run `contact schema` after changing proto/.

#[test]
fn checked_in_schemas_match_the_types() {
    for (name, text) in contact::proto::schema::schemas() {
        let path = format!("{}/proto/{name}", concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            on_disk == text,
            "{name} is stale: run `cargo run --release --bin contact -- schema`"
        );
    }
}

/// Every example is a test: each solves and says what it is.
#[test]
fn every_example_solves() {
    let dir = format!("{}/proto/examples", concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(
            v["description"].as_str().is_some_and(|d| d.len() > 40),
            "{path:?} needs a description"
        );
        let r =
            contact::solve_bytes(text.as_bytes(), &Default::default()).unwrap_or_else(|e| panic!("{path:?}: {e:?}"));
        assert_eq!(r.status, contact::proto::SolveStatus::Solved, "{path:?}");
        n += 1;
    }
    assert!(n >= 3);
}

/// The reply's schema lists, as enums, every status, method, stop reason,
/// estimate basis, warning code and note kind the core can report, and nothing
/// else: a client generated from it can match on them exhaustively.
#[test]
fn the_reply_schema_lists_every_outcome_the_core_reports() {
    use contact_core::outcome::{EstimateBasis, MethodRan, NoteKind, Status, StopReason, WarningCode};
    let (_, text) = contact::proto::schema::schemas()
        .into_iter()
        .find(|(name, _)| *name == "reply.schema.json")
        .expect("a reply schema");
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let defs = &schema["$defs"];
    let values = |name: &str| {
        let mut v = schema_enum(defs, name);
        v.sort();
        v
    };
    let sorted = |names: Vec<&str>| {
        let mut v: Vec<String> = names.into_iter().map(String::from).collect();
        v.sort();
        v
    };
    assert_eq!(
        values("MethodRan"),
        sorted(MethodRan::ALL.iter().map(|m| m.as_str()).collect())
    );
    assert_eq!(
        values("StopReason"),
        sorted(StopReason::ALL.iter().map(|m| m.as_str()).collect())
    );
    assert_eq!(
        values("EstimateBasis"),
        sorted(EstimateBasis::ALL.iter().map(|m| m.as_str()).collect())
    );
    assert_eq!(
        values("WarningCode"),
        sorted(WarningCode::ALL.iter().map(|m| m.as_str()).collect())
    );
    assert_eq!(
        values("NoteKind"),
        sorted(NoteKind::ALL.iter().map(|m| m.as_str()).collect())
    );
    assert_eq!(
        values("SolveStatus"),
        sorted(Status::ALL.iter().map(|m| m.as_str()).collect())
    );
}

/// The progress schema lists every stage the core reports progress in
/// (`ProgressStage`), in the order a solve runs them, and nothing else.
#[test]
fn the_progress_schema_lists_every_stage_of_the_core() {
    use contact_core::outcome::ProgressStage;
    let (_, text) = contact::proto::schema::schemas()
        .into_iter()
        .find(|(name, _)| *name == "progress.schema.json")
        .expect("a progress schema");
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let listed = schema_enum(&schema["$defs"], "ProgressStage");
    let core: Vec<&str> = ProgressStage::ALL.iter().map(|s| s.as_str()).collect();
    assert_eq!(listed, core);
}

/// The values of the enum `name` among a schema's `defs`, in their order: a
/// unit enum with documented variants is a oneOf of consts (or of enums);
/// without, an enum.
fn schema_enum(defs: &serde_json::Value, name: &str) -> Vec<String> {
    let d = &defs[name];
    if let Some(e) = d["enum"].as_array() {
        return e.iter().map(|x| x.as_str().unwrap().to_string()).collect();
    }
    d["oneOf"]
        .as_array()
        .unwrap_or_else(|| panic!("{name} is not an enum in the schema: {d}"))
        .iter()
        .flat_map(|o| {
            o.get("const")
                .map(|c| vec![c.clone()])
                .or_else(|| o["enum"].as_array().cloned())
                .unwrap_or_default()
        })
        .map(|x| x.as_str().unwrap().to_string())
        .collect()
}
