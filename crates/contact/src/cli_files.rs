//! The files of `contact solve`: Gmsh meshes the request names by path (read
//! relative to the request file), and the `--vtu` / `--points-csv` outputs.

use std::path::{Path, PathBuf};

use anyhow::Context;
use base64::Engine;

use crate::proto::{ErrorReply, OutputKind, SolveReply};
use crate::scene::Limits;

/// A reply and the VTU file made with it.
pub struct Solved {
    /// What the service would have answered to the request as given.
    pub shown: SolveReply,
    vtu: Option<Vec<u8>>,
}

/// Solves the request read from `file` ("-": stdin, paths then relative to the
/// working directory); with `want_vtu`, also makes the VTU file.
pub fn solve(file: &str, bytes: &[u8], want_vtu: bool) -> Result<Solved, ErrorReply> {
    let dir = match file {
        "-" => PathBuf::from("."),
        f => Path::new(f).parent().map(Path::to_path_buf).unwrap_or_default(),
    };
    let bytes = crate::request_files::resolve_gmsh_files(bytes, |name| {
        std::fs::read_to_string(dir.join(name)).map_err(|e| e.to_string())
    })?;
    let (bytes, asked) = if want_vtu {
        with_vtu_output(&bytes)
    } else {
        (bytes, true)
    };
    let mut reply = crate::solve_bytes(&bytes, &Limits::default())?;
    let vtu = reply.vtu.as_deref().map(|b64| {
        base64::engine::general_purpose::STANDARD
            .decode(b64)
            .expect("the reply layer encodes valid base64")
    });
    if !asked {
        reply.vtu = None;
    }
    Ok(Solved { shown: reply, vtu })
}

/// The request with `vtu` in its `outputs`, and whether it was there already.
/// A request that is not a JSON object is left for the solve to refuse.
fn with_vtu_output(bytes: &[u8]) -> (Vec<u8>, bool) {
    let Ok(mut v) = serde_json::from_slice::<serde_json::Value>(bytes) else {
        return (bytes.to_vec(), true);
    };
    let Some(obj) = v.as_object_mut() else {
        return (bytes.to_vec(), true);
    };
    let vtu = serde_json::to_value(OutputKind::Vtu).expect("a unit variant serializes");
    let outputs = obj.entry("outputs").or_insert_with(|| serde_json::Value::Array(vec![]));
    let Some(list) = outputs.as_array_mut() else {
        return (bytes.to_vec(), true);
    };
    if list.contains(&vtu) {
        return (bytes.to_vec(), true);
    }
    list.push(vtu);
    (serde_json::to_vec(&v).expect("a JSON value serializes"), false)
}

/// Writes the files asked for on the command line.
pub fn write_outputs(s: &Solved, vtu: Option<&Path>, points_csv: Option<&Path>) -> anyhow::Result<()> {
    if let (Some(path), Some(bytes)) = (vtu, &s.vtu) {
        std::fs::write(path, bytes).with_context(|| format!("writing {}", path.display()))?;
    }
    if let Some(path) = points_csv {
        std::fs::write(path, crate::output::csv::points_csv(&s.shown))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}
