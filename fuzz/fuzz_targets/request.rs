//! Bytes → `solve_bytes` under the service's guards: small size limits and a
//! deadline. Any panic, an allocation past libFuzzer's limits or an answer
//! later than the deadline plus one stage is a finding.
#![no_main]

use std::time::{Duration, Instant};

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let limits = contact::Limits {
        max_dofs: 20_000,
        max_candidates: 400,
        max_load_steps: 10,
        max_output_values: 2_000_000,
        overlap: contact::scene::Overlap::Auto,
    };
    let start = Instant::now();
    let _deadline = contact::cancel::Deadline::install(Duration::from_millis(250));
    if let Ok(reply) = contact::solve_bytes(data, &limits) {
        serde_json::to_vec(&reply).expect("a reply serializes");
    }
    assert!(start.elapsed() < Duration::from_secs(5), "took {:?}", start.elapsed());
});
