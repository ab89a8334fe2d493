//! The layout rules of the workspace, checked on its sources:
//!
//! - in every crate's library (`contact-core`, `contact-proto`, `contact`,
//!   `contact-verify`, `contact-py`) the top-level modules depend on each other
//!   without a cycle, and so do the files under every folder (issue 38.4; the
//!   core's `contact`, whose target kinds once imported each other in a circle,
//!   and `methods`, whose frictional Newton iteration and its Gauss–Seidel
//!   fallback did, are checked by name as well);
//! - only the scene boundary (`scene::validate` and its modules,
//!   `scene::size_limit`) reads wire types;
//! - a source file of any crate over 500 lines says why in its module doc (a
//!   line starting `//! Length:`).
//!
//! Dependencies are read from `crate::a::b` paths and `super::` imports
//! (test modules excluded); a file that declares a folder of modules
//! (`mod.rs`, or `a.rs` beside `a/`) is not a node of its folder's graph (it
//! declares the files and re-exports; `methods/mod.rs` also holds the types
//! the methods share and the dispatch to them). A binary's sources (`main.rs`,
//! `bin/`) are crates of their own and read the library by name, so they are
//! left out.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The library sources of every crate of the workspace: (crate, its src/),
/// each folder of `crates/` with a `src/lib.rs`, so a new crate is checked
/// without being listed here.
fn crate_srcs() -> Vec<(String, PathBuf)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out: Vec<(String, PathBuf)> = std::fs::read_dir(&root)
        .expect("the crates folder")
        .map(|e| e.expect("a crates entry").path())
        .filter(|p| p.join("src").join("lib.rs").is_file())
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), p.join("src")))
        .collect();
    out.sort();
    assert!(out.len() >= 5, "{out:?}");
    out
}

/// The library source folder of the crate `name`.
fn src_of(name: &str) -> PathBuf {
    crate_srcs()
        .into_iter()
        .find(|(k, _)| k == name)
        .unwrap_or_else(|| panic!("no crate {name}"))
        .1
}

/// Module path of a source file under `src`: `contact/targets/body.rs` →
/// ["contact", "targets", "body"].
fn module_in(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|s| s.to_string_lossy().into_owned()).collect();
    if parts.last().is_some_and(|l| l == "mod" || l == "lib") {
        parts.pop();
    }
    parts
}

/// Module path of a source file of the core.
fn module_of(file: &Path) -> Vec<String> {
    module_in(&src(), file)
}

/// The code of a file without its test module and comments.
fn code(file: &Path) -> String {
    let text = std::fs::read_to_string(file).unwrap();
    let text = text.split("#[cfg(test)]").next().unwrap();
    text.lines()
        .map(|l| l.split("//").next().unwrap())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Identifiers following `prefix` (`crate::`, `super::`), and those listed in
/// `prefix{a, b::c}` groups (first segment of each).
fn paths_after(text: &str, prefix: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for (i, _) in text.match_indices(prefix) {
        let rest = &text[i + prefix.len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // Top-level items of the group, nested groups skipped over.
            let (mut depth, mut item) = (0, String::new());
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        out.push(item.split("::").map(|s| s.trim().to_string()).collect());
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                item.push(c);
            }
            out.push(item.split("::").map(|s| s.trim().to_string()).collect());
            out.retain(|segs: &Vec<String>| !segs[0].is_empty());
        } else {
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(rest.len());
            out.push(
                rest[..end]
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(String::from)
                    .collect(),
            );
        }
    }
    out
}

fn has_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        match state.get(n) {
            Some(1) => {
                let k = stack.iter().position(|s| s == n).unwrap();
                let mut cycle = stack[k..].to_vec();
                cycle.push(n.to_string());
                return Some(cycle);
            }
            Some(2) => return None,
            _ => {}
        }
        state.insert(n.to_string(), 1);
        stack.push(n.to_string());
        for m in g.get(n).into_iter().flatten() {
            if let Some(c) = visit(m, g, state, stack) {
                return Some(c);
            }
        }
        stack.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if let Some(c) = visit(n, graph, &mut state, &mut Vec::new()) {
            return Some(c);
        }
    }
    None
}

fn files() -> Vec<PathBuf> {
    lib_files(&src())
}

/// The library's source files under `src`: not a binary's (`main.rs`, `bin/`).
fn lib_files(src: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    sources(src, &mut files);
    files.retain(|f| {
        let rel = f.strip_prefix(src).unwrap();
        rel != Path::new("main.rs") && !rel.starts_with("bin")
    });
    files.sort();
    files
}

/// The graph of `src`'s top-level modules (the first segment of every
/// `crate::` path of a file outside the module).
fn top_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let files = lib_files(src);
    let tops: BTreeSet<String> = files
        .iter()
        .filter_map(|f| module_in(src, f).first().cloned())
        .collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let Some(me) = module_in(src, f).first().cloned() else {
            continue;
        };
        graph.entry(me.clone()).or_default();
        for p in paths_after(&code(f), "crate::") {
            if let Some(t) = p.first().filter(|t| tops.contains(*t) && **t != me) {
                graph.entry(me.clone()).or_default().insert(t.clone());
            }
        }
    }
    graph
}

#[test]
fn top_level_modules_form_no_cycle() {
    let graph = top_graph(&src());
    assert!(graph.len() > 5, "the scan found the modules: {graph:?}");
    assert_eq!(has_cycle(&graph), None, "{graph:#?}");
}

/// Whether `file` declares a folder of modules: `mod.rs`, `lib.rs`, or
/// `a.rs` beside a folder `a/`.
fn declares_folder(file: &Path) -> bool {
    file.file_name().is_some_and(|n| n == "mod.rs" || n == "lib.rs") || file.with_extension("").is_dir()
}

/// The dependencies between the files under the top-level module `top` of
/// the core (see `folder_graph`).
fn file_graph(top: &str) -> BTreeMap<String, BTreeSet<String>> {
    folder_graph(&src(), &[top.to_string()])
}

/// The dependencies between the files under the module folder `folder` of
/// `src` (the files that declare folders only declare and re-export, so
/// they are not nodes).
fn folder_graph(src: &Path, folder: &[String]) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let files: BTreeMap<Vec<String>, PathBuf> = lib_files(src)
        .into_iter()
        .filter(|f| !declares_folder(f))
        .map(|f| (module_in(src, &f), f))
        .filter(|(m, _)| m.len() > folder.len() && m.starts_with(folder))
        .collect();
    let nodes: BTreeSet<Vec<String>> = files.keys().cloned().collect();
    for (me, file) in &files {
        let text = code(file);
        let parent = &me[..me.len() - 1];
        let mut targets: Vec<Vec<String>> = paths_after(&text, "crate::");
        for p in paths_after(&text, "super::") {
            targets.push(parent.iter().cloned().chain(p).collect());
        }
        for t in targets {
            // The longest prefix of the path that is a file of `top`.
            if let Some(dep) = (1..=t.len()).rev().map(|k| t[..k].to_vec()).find(|k| nodes.contains(k)) {
                if &dep != me {
                    graph.entry(me.join("::")).or_default().insert(dep.join("::"));
                }
            }
        }
    }
    graph
}

#[test]
fn contact_files_form_no_cycle() {
    let graph = file_graph("contact");
    assert!(
        graph
            .get("contact::targets::body")
            .is_some_and(|d| d.contains("contact::rows")),
        "the scan sees the targets' imports: {graph:#?}"
    );
    assert_eq!(has_cycle(&graph), None, "{graph:#?}");
}

/// The methods' files, the frictional ones among them (whose Newton
/// iteration and Gauss–Seidel fallback once imported each other).
#[test]
fn methods_files_form_no_cycle() {
    let graph = file_graph("methods");
    assert!(
        graph
            .get("methods::friction::condensed")
            .is_some_and(|d| d.contains("methods::friction::newton") && d.contains("methods::friction::gauss_seidel")),
        "the scan sees the frictional files' imports: {graph:#?}"
    );
    assert_eq!(has_cycle(&graph), None, "{graph:#?}");
}

/// Every crate's top-level modules form no cycle, and neither do the files
/// under any of its folders (issue 38.4).
#[test]
fn every_crate_and_folder_forms_no_cycle() {
    fn folders(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                out.push(p.clone());
                folders(&p, out);
            }
        }
    }
    let (mut checked, mut cycles) = (Vec::new(), Vec::new());
    for (krate, src) in crate_srcs() {
        let graph = top_graph(&src);
        cycles.extend(has_cycle(&graph).map(|c| format!("{krate}: {}", c.join(" → "))));
        checked.push(krate.to_string());
        let mut dirs = Vec::new();
        folders(&src, &mut dirs);
        for d in dirs {
            let folder: Vec<String> = d
                .strip_prefix(&src)
                .unwrap()
                .iter()
                .map(|s| s.to_string_lossy().into_owned())
                .collect();
            if folder[0] == "bin" {
                continue;
            }
            let graph = folder_graph(&src, &folder);
            cycles.extend(has_cycle(&graph).map(|c| format!("{krate} {}: {}", folder.join("::"), c.join(" → "))));
            checked.push(format!("{krate} {}", folder.join("::")));
        }
    }
    assert!(cycles.is_empty(), "cycles:\n{}", cycles.join("\n"));
    // The scan reads the shell's imports too.
    let shell = top_graph(&src_of("contact"));
    assert!(
        shell.get("service").is_some_and(|d| d.contains("wire")),
        "the scan sees contact's service using its wire layer: {shell:#?}"
    );
    assert!(checked.len() >= 20, "every crate and folder: {checked:?}");
}

#[test]
fn only_the_scene_boundary_reads_wire_types() {
    let boundary = [["scene", "validate"], ["scene", "size_limit"]];
    for f in files() {
        let m = module_of(&f);
        if boundary.iter().any(|b| m.len() >= 2 && m[..2] == b[..]) {
            continue;
        }
        let text = code(&f);
        assert!(
            !text.contains("contact_proto") && !text.contains("proto::"),
            "{} reads wire types below the scene boundary",
            f.display()
        );
    }
}

#[test]
fn long_files_say_why() {
    let mut all = Vec::new();
    for (_, src) in crate_srcs() {
        sources(&src, &mut all);
    }
    assert!(all.len() > 40);
    for f in all {
        let text = std::fs::read_to_string(&f).unwrap();
        if text.lines().count() > 500 {
            assert!(
                text.lines().any(|l| l.starts_with("//! Length:")),
                "{} has {} lines and no `//! Length:` line saying why",
                f.display(),
                text.lines().count()
            );
        }
    }
}

#[test]
fn the_cycle_search_finds_a_circle() {
    let g: BTreeMap<String, BTreeSet<String>> = [("a", "b"), ("b", "c"), ("c", "a")]
        .into_iter()
        .map(|(x, y)| (x.to_string(), BTreeSet::from([y.to_string()])))
        .collect();
    assert_eq!(has_cycle(&g).map(|c| c.len()), Some(4));
    let imports = paths_after("use super::{rows::{self, Seen}, gap};", "super::");
    assert_eq!(imports[0][0], "rows");
    assert_eq!(imports[1][0], "gap");
}

/// The style width: no line of the workspace's Rust sources passes 120
/// characters (rustfmt's `max_width` cannot fail on a long string or
/// comment; the client's Python has ruff's E501 for the same).
#[test]
fn no_rust_line_passes_120_columns() {
    fn walk(dir: &std::path::Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() && p.file_name().is_some_and(|n| n != "target") {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    let crates = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    walk(&crates, &mut files);
    assert!(files.len() > 50, "the scan found the sources: {}", files.len());
    let long: Vec<String> = files
        .iter()
        .flat_map(|f| {
            let text = std::fs::read_to_string(f).unwrap_or_default();
            text.lines()
                .enumerate()
                .filter(|(_, l)| l.chars().count() > 120)
                .map(|(i, l)| format!("{}:{} ({} characters)", f.display(), i + 1, l.chars().count()))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(long.is_empty(), "lines over 120 characters:\n{}", long.join("\n"));
}
