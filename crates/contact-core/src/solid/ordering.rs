//! A fill-reducing order of a body's free DOFs for the sparse Cholesky:
//! geometric nested dissection of the mesh's nodes.
//!
//! The nodes are split at the median of the longest side of their bounding
//! box; the nodes of the lower half next to the upper half are the
//! separator, numbered after both halves, each half ordered the same way
//! down to 64 nodes (George 1973). A node's free DOFs stay together. On the
//! graded T4 boxes of the `solid3d_timing` example the factor then costs
//! 3.6e10 multiply–adds instead of AMD's 9.8e10 at 47k DOF and 1.5e12
//! instead of 5.7e12 at 293k (nnz(L) 4.6e8 against 8.6e8); on a T10 box of
//! 49k DOF 7.5e10 against 1.8e11. AMD, local and greedy, does not find the
//! planes that cut a 3D mesh in two.
//!
//! The order keeps the request's clock: each step of the recursion polls
//! the deadline (`cancel::check`, stage `factorization`, which the order
//! belongs to) and a passed one ends it with the timeout every stage
//! returns. A step sorts its set's coordinates, O(m log m) for m nodes, so
//! the polls are at most that far apart (the whole top step at most, about
//! one sort of all the nodes), and they cost one clock read per step, about
//! n / 64 reads in all.

use super::dofs::SolidDofs;
use crate::cancel::{self, Timeout};
use crate::fem::pattern::FIXED;
use crate::mesh3d::Mesh3d;
use crate::outcome::ProgressStage;

/// Leaves of the dissection: sets of at most this many nodes keep their order.
const LEAF: usize = 64;

/// (fwd, inv): fwd[i] is the free DOF at position i of the factor; a
/// `Timeout` once this thread's deadline has passed (module doc).
pub fn nested_dissection(mesh: &Mesh3d, dofs: &SolidDofs) -> Result<(Vec<usize>, Vec<usize>), Timeout> {
    cancel::check(ProgressStage::Factorization)?;
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); mesh.nodes.len()];
    for e in 0..mesh.n_elems() {
        let conn = mesh.elem(e);
        for &a in conn {
            for &b in conn {
                if a != b && !adj[a].contains(&(b as u32)) {
                    adj[a].push(b as u32);
                }
            }
        }
    }
    let mut side = vec![0u8; mesh.nodes.len()];
    let mut order = Vec::with_capacity(mesh.nodes.len());
    dissect((0..mesh.nodes.len()).collect(), mesh, &adj, &mut side, &mut order)?;
    let fwd: Vec<usize> = order
        .iter()
        .flat_map(|&n| (0..3).map(move |c| dofs.free[3 * n + c]))
        .filter(|&f| f != FIXED)
        .collect();
    let mut inv = vec![0; fwd.len()];
    for (i, &f) in fwd.iter().enumerate() {
        inv[f] = i;
    }
    Ok((fwd, inv))
}

/// Appends the nodes of `set` to `order`: both halves (recursively), then
/// their separator. `side` is all 0 on entry and on return (also on a
/// timeout, which leaves `order` unfinished).
fn dissect(
    set: Vec<usize>,
    mesh: &Mesh3d,
    adj: &[Vec<u32>],
    side: &mut [u8],
    order: &mut Vec<usize>,
) -> Result<(), Timeout> {
    cancel::check(ProgressStage::Factorization)?;
    if set.len() <= LEAF {
        order.extend(set);
        return Ok(());
    }
    let (lo, hi) = set.iter().fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), &n| {
        let x = mesh.nodes[n];
        ([0, 1, 2].map(|c| lo[c].min(x[c])), [0, 1, 2].map(|c| hi[c].max(x[c])))
    });
    let axis = (0..3)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(0);
    let mut coords: Vec<f64> = set.iter().map(|&n| mesh.nodes[n][axis]).collect();
    coords.sort_by(f64::total_cmp);
    let median = coords[coords.len() / 2];
    for &n in &set {
        side[n] = if mesh.nodes[n][axis] < median { 1 } else { 2 };
    }
    let (mut low, mut high, mut separator) = (Vec::new(), Vec::new(), Vec::new());
    for &n in &set {
        if side[n] == 2 {
            high.push(n);
        } else if adj[n].iter().any(|&m| side[m as usize] == 2) {
            separator.push(n);
        } else {
            low.push(n);
        }
    }
    for &n in &set {
        side[n] = 0;
    }
    // All nodes on one side of the median (many at the same coordinate):
    // no cut along this axis helps; the set keeps its order.
    if low.is_empty() || high.is_empty() {
        order.extend(set);
        return Ok(());
    }
    dissect(low, mesh, adj, side, order)?;
    dissect(high, mesh, adj, side, order)?;
    order.extend(separator);
    Ok(())
}
