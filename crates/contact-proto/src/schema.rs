//! JSON Schema export of the wire types (checked in under `proto/`).

use schemars::schema_for;

use crate::progress::ProgressMessage;
use crate::{ErrorReply, SolveReply, SolveRequest};

/// (file name, pretty JSON) of every schema, in a stable order.
pub fn schemas() -> Vec<(&'static str, String)> {
    let pretty = |v: schemars::Schema| serde_json::to_string_pretty(&v).expect("schema serializes") + "\n";
    vec![
        ("request.schema.json", pretty(schema_for!(SolveRequest))),
        ("reply.schema.json", pretty(schema_for!(SolveReply))),
        ("error.schema.json", pretty(schema_for!(ErrorReply))),
        ("progress.schema.json", pretty(schema_for!(ProgressMessage))),
    ]
}
