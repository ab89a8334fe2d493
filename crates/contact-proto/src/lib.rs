//! Wire types: what goes over zenoh and through `contact solve`.
//!
//! Only serde/schemars types live here, no numerics. The JSON Schema files in the
//! top-level `proto/` directory are generated from these types (`contact schema`)
//! and a test fails when they drift. Every message carries `version`.

pub mod bounded;
pub mod elements;
pub mod error;
pub mod progress;
pub mod reply;
pub mod request;
pub mod schema;
pub mod solid;

pub use elements::ElementLists;
pub use error::{ErrorCode, ErrorDetails, ErrorReply, LoadBound};
pub use reply::*;
pub use request::*;
pub use solid::*;

/// Protocol version carried by every message; bumped on incompatible changes.
pub const PROTOCOL_VERSION: &str = "1";
