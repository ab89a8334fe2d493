//! What reading a mesh costs at the door, counted by this binary's allocator
//! (its own binary: the allocator counts every thread's allocations).
//!
//! A structured grid of 200 × 200 nodes (79k triangles), as a Gmsh payload
//! and as an inline one, is read and validated (`validate_bytes`, what the
//! service does before a request may queue). The peak of bytes allocated
//! during that, over those allocated before, is held to 5.5 times the payload
//! (a reallocation counted as a new block plus the old one). Counted so: 2.80
//! for the Gmsh payload (3.8 MB) and 2.37 for the inline one (3.1 MB), where a
//! list per element, growing vectors and a hash of every element edge cost
//! 9.13 and 10.18. docs/howto/service.md states the service's peak resident memory on
//! 58 MB payloads: 4.4 and 3.5 times (8.8 and 12.1 before).

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

use serde_json::{json, Value};

struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(bytes: usize) {
    let now = NOW.fetch_add(bytes, Relaxed) + bytes;
    PEAK.fetch_max(now, Relaxed);
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(l) };
        if !p.is_null() {
            grew(l.size());
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) };
        NOW.fetch_sub(l.size(), Relaxed);
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, l, new) };
        if !q.is_null() {
            grew(new);
            NOW.fetch_sub(l.size(), Relaxed);
        }
        q
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

const N: usize = 200;

/// Node k of the grid on [-20, 20] × [-20, 0], row after row.
fn node(k: usize) -> [f64; 2] {
    let step = |n: usize, span: f64| span * n as f64 / (N - 1) as f64;
    [-20.0 + step(k % N, 40.0), -20.0 + step(k / N, 20.0)]
}

fn triangles() -> Vec<[usize; 3]> {
    let id = |i: usize, j: usize| j * N + i;
    (0..N - 1)
        .flat_map(|j| (0..N - 1).map(move |i| (i, j)))
        .flat_map(|(i, j)| {
            [
                [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
            ]
        })
        .collect()
}

fn edges() -> [(&'static str, Vec<[usize; 2]>); 4] {
    let id = |i: usize, j: usize| j * N + i;
    [
        ("bottom", (0..N - 1).map(|i| [id(i, 0), id(i + 1, 0)]).collect()),
        ("right", (0..N - 1).map(|j| [id(N - 1, j), id(N - 1, j + 1)]).collect()),
        ("top", (0..N - 1).map(|i| [id(i + 1, N - 1), id(i, N - 1)]).collect()),
        ("left", (0..N - 1).map(|j| [id(0, j + 1), id(0, j)]).collect()),
    ]
}

fn msh() -> String {
    use std::fmt::Write;
    let mut s = String::from(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n1 1 \"bottom\"\n1 2 \"right\"\n1 3 \"top\"\n\
         1 4 \"left\"\n2 5 \"block\"\n$EndPhysicalNames\n$Entities\n0 4 1 0\n",
    );
    for k in 1..=4 {
        writeln!(s, "{k} -20 -20 0 20 0 0 1 {k} 0").unwrap();
    }
    s += "1 -20 -20 0 20 0 0 1 5 4 1 2 3 4\n$EndEntities\n";
    let nn = N * N;
    writeln!(s, "$Nodes\n1 {nn} 1 {nn}\n2 1 0 {nn}").unwrap();
    (1..=nn).for_each(|k| writeln!(s, "{k}").unwrap());
    (0..nn).for_each(|k| writeln!(s, "{:?} {:?} 0", node(k)[0], node(k)[1]).unwrap());
    let (tris, edges) = (triangles(), edges());
    let ne = tris.len() + edges.iter().map(|(_, e)| e.len()).sum::<usize>();
    writeln!(s, "$EndNodes\n$Elements\n5 {ne} 1 {ne}").unwrap();
    let mut tag = 0;
    for (k, (_, es)) in edges.iter().enumerate() {
        writeln!(s, "1 {} 1 {}", k + 1, es.len()).unwrap();
        for [a, b] in es {
            tag += 1;
            writeln!(s, "{tag} {} {}", a + 1, b + 1).unwrap();
        }
    }
    writeln!(s, "2 1 2 {}", tris.len()).unwrap();
    for [a, b, c] in tris {
        tag += 1;
        writeln!(s, "{tag} {} {} {}", a + 1, b + 1, c + 1).unwrap();
    }
    s + "$EndElements\n"
}

/// Peak bytes allocated while `payload` is validated, over those before, per payload byte.
fn cost_of_reading(payload: &[u8]) -> f64 {
    let before = NOW.load(Relaxed);
    PEAK.store(before, Relaxed);
    let validated = contact::validate_bytes(payload, &Default::default());
    let peak = PEAK.load(Relaxed);
    assert!(validated.is_ok(), "{:?}", validated.err());
    (peak - before) as f64 / payload.len() as f64
}

#[test]
fn reading_a_mesh_costs_a_bounded_multiple_of_its_payload() {
    let mut req: Value = common::example("signorini_hertz_cylinder_gmsh.json");
    req["bodies"][0]["mesh"]["gmsh"]["msh"] = json!(msh());
    let gmsh = serde_json::to_vec(&req).unwrap();
    let sets: serde_json::Map<String, Value> = edges().into_iter().map(|(k, e)| (k.to_string(), json!(e))).collect();
    req["bodies"][0]["mesh"] = json!({"inline": {
        "nodes": (0..N * N).map(node).collect::<Vec<_>>(),
        "elements": triangles(),
        "edge_sets": sets,
    }});
    let inline = serde_json::to_vec(&req).unwrap();
    drop(req);
    let (g, i) = (cost_of_reading(&gmsh), cost_of_reading(&inline));
    eprintln!(
        "Gmsh {:.1} MB: {g:.2}x; inline {:.1} MB: {i:.2}x",
        gmsh.len() as f64 / 1e6,
        inline.len() as f64 / 1e6
    );
    assert!(g < 5.5 && i < 5.5, "Gmsh {g:.2}x, inline {i:.2}x the payload");
}
