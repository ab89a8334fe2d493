//! Reuse of the expensive, load-independent part of a solve across requests.
//!
//! A `Prepared` operator holds K_ff and K_fd, the Cholesky factor of K_ff and
//! the condensed operator W = B K⁻¹ Bᵀ with the blocks of L⁻¹ P Bᵀ it came from. It depends
//! on the meshes, materials, analysis, which DOFs are prescribed (not their
//! values) and the contact rows B (not the gaps), so a request that changes only
//! loads, prescribed values or obstacle positions (with the same candidates)
//! reuses it. The key is a hash of exactly those inputs, computed from the
//! generated meshes, so equal meshes hit whatever way they were described.
//! The cache is owned by the caller (the service), bounded in bytes, LRU.
//!
//! Beside the operators it keeps the last few symbolic factorizations (the
//! AMD ordering and the supernodal structure), keyed by the sparsity pattern
//! of K only: a request that changes a material (E, ν) or the contact rows
//! misses the operator but reuses the ordering and redoes only the numeric
//! factorization.

use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

use crate::contact::ConstraintSet;
use crate::fem::assembly::{DofMap, Stiffness};
use crate::linalg::cholesky::SymbolicFactor;
use crate::linalg::schur::Condensed;
use crate::linalg::Cholesky;
use crate::mesh::Mesh2d;
use crate::scene::Scene;

pub struct Prepared {
    pub stiffness: Arc<Stiffness>,
    /// Shared by the condensations of a screened solve (`solve::screen`),
    /// each over the rows it holds.
    pub chol: Arc<Cholesky>,
    /// W and the blocks of X = L⁻¹ P Bᵀ: one forward and one backward sweep
    /// then make a whole solve.
    pub condensed: Condensed,
    /// The candidates W is over, by index, when a screened solve condensed
    /// only some (None: every candidate, in order).
    pub rows: Option<Vec<usize>>,
    /// `Cholesky::pivot_ratio` of the factor.
    pub pivot_ratio: f64,
    pub t_factorization: f64,
    pub t_condensation: f64,
}

impl Prepared {
    /// Approximate memory held, for the cache bound.
    pub fn bytes(&self) -> usize {
        let k = self.stiffness.k.val().len() * 16 + self.stiffness.k_fd.len() * 24;
        k + self.chol.nnz_factor() * 12 + self.condensed.stored_values() * 8
    }
}

/// Identity of the load-independent inputs of a solve.
pub fn key(scene: &Scene, meshes: &[Mesh2d], dofs: &DofMap, cons: &ConstraintSet) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    (scene.analysis as u8).hash(&mut h);
    for (body, mesh) in scene.bodies.iter().zip(meshes) {
        body.youngs_modulus.to_bits().hash(&mut h);
        body.poisson_ratio.to_bits().hash(&mut h);
        (mesh.order as u8).hash(&mut h);
        mesh.nodes.len().hash(&mut h);
        for p in &mesh.nodes {
            p[0].to_bits().hash(&mut h);
            p[1].to_bits().hash(&mut h);
        }
        mesh.elems.hash(&mut h);
    }
    dofs.free.hash(&mut h);
    cons.len().hash(&mut h);
    for c in &cons.candidates {
        for &(d, v) in &c.row {
            d.hash(&mut h);
            v.to_bits().hash(&mut h);
        }
        usize::MAX.hash(&mut h);
    }
    h.finish()
}

pub struct OperatorCache {
    entries: Mutex<Vec<(u64, Arc<Prepared>)>>,
    max_bytes: usize,
    /// Symbolic factorizations, most recently used last.
    symbolic: Mutex<Vec<Arc<SymbolicFactor>>>,
    symbolic_hits: std::sync::atomic::AtomicUsize,
}

/// Symbolic factorizations kept: their index arrays are a fraction of the
/// numeric factor's values, and a service sees few distinct meshes at a time.
const SYMBOLIC_KEPT: usize = 8;

impl OperatorCache {
    pub fn new(max_bytes: usize) -> Self {
        Self {
            entries: Mutex::new(Vec::new()),
            max_bytes,
            symbolic: Mutex::new(Vec::new()),
            symbolic_hits: Default::default(),
        }
    }

    /// The symbolic factorization for `pattern` (`cholesky::pattern_key`), if kept.
    pub fn get_symbolic(&self, pattern: u64) -> Option<Arc<SymbolicFactor>> {
        if self.max_bytes == 0 {
            return None;
        }
        let mut e = self.symbolic.lock().unwrap_or_else(|p| p.into_inner());
        let pos = e.iter().position(|s| s.key() == pattern)?;
        let entry = e.remove(pos);
        e.push(entry.clone());
        self.symbolic_hits.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Some(entry)
    }

    pub fn insert_symbolic(&self, s: Arc<SymbolicFactor>) {
        if self.max_bytes == 0 {
            return;
        }
        let mut e = self.symbolic.lock().unwrap_or_else(|p| p.into_inner());
        e.retain(|x| x.key() != s.key());
        e.push(s);
        if e.len() > SYMBOLIC_KEPT {
            e.remove(0);
        }
    }

    /// How many factorizations reused a kept symbolic analysis.
    pub fn symbolic_hits(&self) -> usize {
        self.symbolic_hits.load(std::sync::atomic::Ordering::Relaxed)
    }

    pub fn get(&self, key: u64) -> Option<Arc<Prepared>> {
        let mut e = self.entries.lock().unwrap_or_else(|p| p.into_inner());
        let pos = e.iter().position(|(k, _)| *k == key)?;
        let entry = e.remove(pos);
        let out = entry.1.clone();
        e.push(entry); // most recently used last
        Some(out)
    }

    pub fn insert(&self, key: u64, value: Arc<Prepared>) {
        let size = value.bytes();
        if size > self.max_bytes {
            return;
        }
        let mut e = self.entries.lock().unwrap_or_else(|p| p.into_inner());
        e.retain(|(k, _)| *k != key);
        e.push((key, value));
        while e.iter().map(|(_, v)| v.bytes()).sum::<usize>() > self.max_bytes {
            e.remove(0);
        }
    }

    pub fn len(&self) -> usize {
        self.entries.lock().map(|e| e.len()).unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn bytes(&self) -> usize {
        self.entries
            .lock()
            .map(|e| e.iter().map(|(_, v)| v.bytes()).sum())
            .unwrap_or(0)
    }
}
