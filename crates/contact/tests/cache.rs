//! The operator cache: a repeated scene reuses the factorization and gives the
//! identical answer; a change of loads or prescribed motion reuses it too (and
//! the answer follows the physics); a change of material or of the contact
//! rows does not reuse it, but reuses its ordering and symbolic analysis.

mod common;
use common::*;
use contact::cache::OperatorCache;
use contact::proto::CacheState;
use serde_json::json;

fn solve_with(cache: &OperatorCache, req: &serde_json::Value) -> contact::proto::SolveReply {
    let bytes = serde_json::to_vec(req).unwrap();
    contact::solve_bytes_cached(&bytes, &Default::default(), Some(cache)).unwrap()
}

#[test]
fn repeated_and_reloaded_scenes_hit_the_cache() {
    let cache = OperatorCache::new(1 << 30);
    let req = example("signorini_roller_on_flat.json");
    let first = solve_with(&cache, &req);
    assert_eq!(first.cache, CacheState::Miss);
    let again = solve_with(&cache, &req);
    assert_eq!(again.cache, CacheState::Hit);
    assert_eq!(again.timings.factorization, 0.0);
    for (a, b) in first.pairs[0].points.iter().zip(&again.pairs[0].points) {
        assert_eq!(
            a.pressure, b.pressure,
            "a cached operator must give the very same answer"
        );
    }
    // Deeper indentation: same K, same candidates, new prescribed values → hit,
    // and the uncached solve agrees to round-off.
    let mut deeper = req.clone();
    deeper["bodies"][0]["supports"][0]["uy"] = json!(-0.08);
    let cached = solve_with(&cache, &deeper);
    assert_eq!(cached.cache, CacheState::Hit);
    let fresh = solved(&deeper);
    assert_eq!(fresh.cache, CacheState::Off);
    let peak = peak_pressure(&fresh);
    for (a, b) in cached.pairs[0].points.iter().zip(&fresh.pairs[0].points) {
        assert!((a.pressure - b.pressure).abs() <= 1e-10 * peak);
    }
    assert!(
        cached.resultant.fy > first.resultant.fy,
        "a deeper push carries more load"
    );
    // The core works in units of the largest modulus, so halving E is the same
    // nondimensional operator: a hit, with every pressure exactly halved.
    let mut softer = req.clone();
    softer["bodies"][0]["material"]["youngs_modulus"] = json!(100.0);
    let soft = solve_with(&cache, &softer);
    assert_eq!(soft.cache, CacheState::Hit);
    for (a, b) in first.pairs[0].points.iter().zip(&soft.pairs[0].points) {
        assert!((0.5 * a.pressure - b.pressure).abs() <= 1e-12 * peak);
    }
    // Another Poisson ratio is another operator, but the same sparsity
    // pattern: the numeric factorization is redone on the kept ordering and
    // symbolic analysis, and the answer is the uncached one to round-off.
    let mut other = req.clone();
    other["bodies"][0]["material"]["poisson_ratio"] = json!(0.25);
    let hits = cache.symbolic_hits();
    let reused = solve_with(&cache, &other);
    assert_eq!(reused.cache, CacheState::Miss);
    assert_eq!(cache.len(), 2);
    assert_eq!(cache.symbolic_hits(), hits + 1, "the symbolic analysis is reused");
    let fresh = solved(&other);
    let peak = peak_pressure(&fresh);
    assert!(max_pressure_diff(&reused, &fresh) <= 1e-12 * peak);
    // Other contact rows on the same K (far candidates pruned): another
    // operator, but the factor's analysis depends on K's pattern alone.
    let mut fewer = other.clone();
    fewer["settings"] = json!({ "prune_gap_ratio": 0.01 });
    let hits = cache.symbolic_hits();
    let pruned = solve_with(&cache, &fewer);
    assert_eq!(pruned.cache, CacheState::Miss);
    assert!(pruned.size.candidates < reused.size.candidates, "rows were pruned");
    assert_eq!(cache.symbolic_hits(), hits + 1, "the symbolic analysis is reused");
    assert!(max_pressure_diff(&pruned, &solved(&fewer)) <= 1e-12 * peak);
}

#[test]
fn cache_respects_its_memory_bound() {
    let cache = OperatorCache::new(1); // nothing fits
    let req = example("signorini_inline_block_on_vee.json");
    assert_eq!(solve_with(&cache, &req).cache, CacheState::Miss);
    assert_eq!(solve_with(&cache, &req).cache, CacheState::Miss);
    assert!(cache.is_empty());
}
