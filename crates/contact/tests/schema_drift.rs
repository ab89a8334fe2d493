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
