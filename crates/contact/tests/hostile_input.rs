//! Hostile input through the request parser and validator (and, when it gets
//! that far, the solve): every payload is answered, with an error reply when it
//! is not a valid request, without a panic and within its time limit.
//!
//! Three sources: the corpus kept in `fuzz/corpus/request/` (the examples, the
//! hand-written hostile seeds whose expected code is pinned below, and what the
//! cargo-fuzz target found worth keeping), payloads too big to keep as files
//! (generated here), and deterministic mutations: every leaf of every example
//! replaced by each hostile value, then seeded random byte edits.

use std::panic::AssertUnwindSafe;
use std::path::Path;
use std::time::{Duration, Instant};

use contact::proto::{ErrorCode, ErrorReply, SolveReply};
use contact::Limits;
use serde_json::{json, Value};

/// The guards of the fuzz target: small limits and a short deadline.
const LIMITS: Limits = Limits {
    max_dofs: 20_000,
    max_candidates: 400,
    max_load_steps: 10,
    max_output_values: 2_000_000,
    overlap: contact::scene::Overlap::Auto,
};
const DEADLINE: Duration = Duration::from_millis(250);
/// Deadline plus the longest stage that does not poll it, with room for a loaded machine.
const BOUND: Duration = Duration::from_secs(5);

fn answer(what: &str, bytes: &[u8]) -> Result<SolveReply, ErrorReply> {
    let start = Instant::now();
    let _deadline = contact::cancel::Deadline::install(DEADLINE);
    let out = std::panic::catch_unwind(AssertUnwindSafe(|| contact::solve_bytes(bytes, &LIMITS)))
        .unwrap_or_else(|_| panic!("{what}: the solve panicked"));
    assert!(start.elapsed() < BOUND, "{what}: took {:?}", start.elapsed());
    if let Ok(reply) = &out {
        serde_json::to_vec(reply).unwrap_or_else(|e| panic!("{what}: reply does not serialize: {e}"));
    }
    out
}

fn code(what: &str, bytes: &[u8]) -> ErrorCode {
    match answer(what, bytes) {
        Ok(r) => panic!("{what}: expected an error, got a reply with status {:?}", r.status),
        Err(e) => e.code,
    }
}

fn corpus() -> Vec<(String, Vec<u8>)> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("fuzz/corpus/request");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{dir:?}: {e}"))
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect()
}

#[test]
fn hostile_seeds_get_their_error() {
    use ErrorCode as C;
    let expected = [
        ("hostile_big_integer.json", C::InvalidRequest),
        ("hostile_degenerate_element.json", C::InvalidMesh),
        ("hostile_element_index.json", C::InvalidMesh),
        ("hostile_empty.json", C::MalformedJson),
        // 5000 load factors: cut at the limit while read, before validation
        // (which would find no body first).
        ("hostile_giant_array.json", C::TooLarge),
        ("hostile_grading_ratio.json", C::TooLarge),
        ("hostile_huge_number.json", C::MalformedJson),
        ("hostile_huge_width.json", C::TooLarge),
        ("hostile_infinity.json", C::MalformedJson),
        ("hostile_invalid_utf8.json", C::MalformedJson),
        ("hostile_nan.json", C::MalformedJson),
        ("hostile_nested_arrays.json", C::MalformedJson),
        ("hostile_nested_in_field.json", C::MalformedJson),
        ("hostile_nested_objects.json", C::MalformedJson),
        ("hostile_node_coordinates.json", C::InvalidMesh),
        // The first triangle listed twice: a stiffer block, not an answer.
        ("hostile_overlapping_element.json", C::InvalidMesh),
        ("hostile_time_limit.json", C::Timeout),
        ("hostile_tiny_mesh_size.json", C::InvalidMesh),
        ("hostile_truncated.json", C::MalformedJson),
    ];
    let files = corpus();
    let wrong: Vec<String> = expected
        .iter()
        .filter_map(|&(name, want)| {
            let bytes = &files
                .iter()
                .find(|f| f.0 == name)
                .unwrap_or_else(|| panic!("{name} missing"))
                .1;
            let got = code(name, bytes);
            (got != want).then(|| format!("{name}: {got:?}, expected {want:?}"))
        })
        .collect();
    assert!(wrong.is_empty(), "{wrong:#?}");
}

/// Load factors whose scaled loads overflow the solve's arithmetic (1e308)
/// are refused at their path (they were once answered `solved` with null
/// pressures); tiny and zero factors are legal, each step with its own status.
#[test]
fn extreme_load_factors_are_refused_or_answered_step_by_step() {
    let (name, bytes) = corpus()
        .into_iter()
        .find(|f| f.0 == "hostile_load_factors.json")
        .unwrap();
    let e = answer(&name, &bytes).expect_err("1e308 overflows");
    assert_eq!(
        (e.code, e.path.as_str()),
        (ErrorCode::InvalidRequest, "/load_factors/0")
    );
    let mut req: Value = serde_json::from_slice(&bytes).unwrap();
    req["load_factors"] = json!([0.0, 5e-324, -1.0, 1e3]);
    let reply = answer(&name, &serde_json::to_vec(&req).unwrap()).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    let steps = reply.steps.expect("steps");
    assert_eq!(steps.len(), 4);
    assert!(steps.iter().all(|s| {
        let c = s.certificate;
        [c.primal, c.dual, c.complementarity, c.equilibrium]
            .iter()
            .all(|v| v.is_finite())
    }));
}

#[test]
fn every_corpus_file_is_answered() {
    let files = corpus();
    assert!(files.len() >= 25, "the corpus lost files");
    for (name, bytes) in &files {
        let _ = answer(name, bytes);
    }
}

#[test]
fn payloads_too_big_to_keep_are_refused() {
    let deep = |open: &str, close: &str, n: usize| format!("{}{}", open.repeat(n), close.repeat(n)).into_bytes();
    assert_eq!(
        code("1M nested arrays", &deep("[", "]", 1 << 20)),
        ErrorCode::MalformedJson
    );
    assert_eq!(
        code("1M nested objects", &deep("{\"a\":", "}", 1 << 20)),
        ErrorCode::MalformedJson
    );
    let digits = format!(r#"{{"version": "1", "time_limit": 1{}}}"#, "0".repeat(100_000));
    assert_eq!(code("100k-digit number", digits.as_bytes()), ErrorCode::MalformedJson);
    // 10⁶ nodes with no element: read (bounded by the payload), then refused.
    let mut vee = example_without_description("signorini_inline_block_on_vee.json");
    vee["bodies"][0]["mesh"]["inline"]["nodes"] = json!(vec![[0.0, 0.0]; 1_000_000]);
    let e = answer("1M nodes", &serde_json::to_vec(&vee).unwrap()).unwrap_err();
    assert!(matches!(e.code, ErrorCode::InvalidMesh | ErrorCode::TooLarge), "{e:?}");
    let mut hertz = example_without_description("signorini_hertz_cylinder.json");
    hertz["load_factors"] = json!(vec![1.0; 1_000_000]);
    assert_eq!(
        code("1M load factors", &serde_json::to_vec(&hertz).unwrap()),
        ErrorCode::TooLarge
    );
    let mut s = vec![0xffu8; 1 << 20];
    s[0] = b'"';
    assert_eq!(code("1 MB of invalid UTF-8", &s), ErrorCode::MalformedJson);
}

fn example_without_description(name: &str) -> Value {
    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("proto/examples")
        .join(name);
    let mut v: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    v.as_object_mut().unwrap().remove("description");
    v
}

/// JSON pointers of every leaf (and every container, which is replaced whole too).
fn pointers(v: &Value, at: String, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => m.iter().for_each(|(k, c)| pointers(c, format!("{at}/{k}"), out)),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, c)| pointers(c, format!("{at}/{i}"), out)),
        _ => {}
    }
    out.push(at);
}

#[test]
fn every_field_of_every_example_survives_hostile_values() {
    let hostile = [
        json!(0),
        json!(-1),
        json!(0.5),
        json!(1e308),
        json!(-1e308),
        json!(5e-324),
        json!(u64::MAX),
        json!(i64::MIN),
        json!(""),
        json!("\u{0}\u{ffff}"),
        json!(null),
        json!(true),
        json!([]),
        json!({}),
    ];
    let mut runs = 0;
    for name in [
        "signorini_inline_block_on_vee.json",
        "signorini_hertz_cylinder.json",
        "indentation_flat_punch.json",
        "indentation_circular_punch.json",
        "signorini_roller_on_flat.json",
    ] {
        let base = example_without_description(name);
        let mut at = Vec::new();
        pointers(&base, String::new(), &mut at);
        for p in at.iter().filter(|p| !p.is_empty()) {
            for h in &hostile {
                let mut v = base.clone();
                *v.pointer_mut(p).unwrap() = h.clone();
                let _ = answer(&format!("{name}{p} = {h}"), &serde_json::to_vec(&v).unwrap());
                runs += 1;
            }
        }
    }
    assert!(runs > 2000, "{runs} runs");
}

/// xorshift64*: reproducible without a dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

#[test]
fn seeded_byte_mutations_of_the_corpus_are_answered() {
    const TOKENS: [&[u8]; 12] = [
        b"{", b"}", b"[", b"]", b",", b"\"", b"NaN", b"1e999", b"-0", b"null", b"\xff", b"\\u0000",
    ];
    let seeds = corpus();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for run in 0..3000 {
        let (name, seed) = &seeds[rng.below(seeds.len())];
        let mut b = seed.clone();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(b.len() + 1);
            match rng.below(5) {
                0 if !b.is_empty() => {
                    let i = at.min(b.len() - 1);
                    b[i] ^= 1 << rng.below(8);
                }
                1 => b.truncate(at),
                2 => {
                    let end = (at + rng.below(64)).min(b.len());
                    b.drain(at..end);
                }
                3 => {
                    let t = TOKENS[rng.below(TOKENS.len())];
                    b.splice(at..at, t.iter().copied());
                }
                _ => {
                    let end = (at + rng.below(256)).min(b.len());
                    let piece = b[at..end].to_vec();
                    b.splice(at..at, piece);
                }
            }
        }
        let _ = answer(&format!("mutation {run} of {name}"), &b);
    }
}

/// A refusal quotes at most a few hundred bytes of what it was sent: a
/// `load_path` key of a megabyte (it names no load) came back whole in both
/// the message and the path; now the message is cut (saying how much) and
/// the path is the pointer's ancestor that fits, which still resolves in
/// the request.
#[test]
fn a_huge_quoted_key_is_cut_from_the_refusal() {
    let mut req = example_without_description("signorini_hertz_cylinder.json");
    let key = format!("/bodies/0/{}", "x".repeat(1 << 20));
    req["load_path"] = json!([{ "loads": { key: 1.0 } }]);
    let e = contact::solve_bytes(&serde_json::to_vec(&req).unwrap(), &Limits::default()).expect_err("refused");
    assert_eq!(e.code, ErrorCode::InvalidRequest);
    assert!(
        e.message.len() < 2100 && e.message.contains("bytes cut"),
        "{} bytes",
        e.message.len()
    );
    assert_eq!(e.path, "/load_path/0/loads");
    assert!(req.pointer(&e.path).is_some());
}
