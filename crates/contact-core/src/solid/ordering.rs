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
//!
//! faer's symbolic analysis after it does not poll: `analysed` predicts
//! both stages from the free DOFs (`predicted_secs`) and starts neither
//! when they cannot end in the time left, as 2D's AMD order is admitted
//! (`linalg::symbolic`); a 149k-DOF T10 ball with a 1.5 s limit answered
//! `too_large`… after 2.0 s, 0.5 s past it, in the analysis.

use faer::sparse::SparseColMat;

use super::dofs::SolidDofs;
use crate::cancel::{self, Timeout};
use crate::error::CoreError;
use crate::fem::pattern::FIXED;
use crate::linalg::cholesky::SymbolicFactor;
use crate::mesh3d::{Mesh3d, Order};
use crate::outcome::ProgressStage;

/// Seconds per free DOF of the nested dissection: measured 0.42–0.52 µs on
/// graded T4 boxes of 47k and 293k DOF, 0.44–1.03 µs on T10 of 49k and
/// 134k (the `solid3d_timing` example, `--cost`, load average 5.5 on 2
/// cores); the largest, times `rate::scale()` as 2D's are.
const ORDERING_PER_DOF: f64 = 1.03e-6;

/// faer's supernodal symbolic analysis in that order costs about 3e-9 s per
/// stored value of L (0.106 s at nnz(L) = 3.5e7, 1.49 s at 4.6e8, the same
/// runs), and L fills faster than n: the analysis took 0.106 s at 47k and
/// 1.49 s at 293k DOF on the T4 boxes (n^1.45), 0.158 s at 49k and 0.97 s at
/// 134k on the T10 ones (n^1.80). So t = t_ref (n / n_ref)^p from the larger
/// of each, with its exponent: a c n^(4/3) law anchored there (first
/// built) read 1.9 times low for T10 at 500k DOF, and the analysis does not
/// poll (review).
const SYMBOLIC_T4: [f64; 3] = [1.49, 293e3, 1.45];
const SYMBOLIC_T10: [f64; 3] = [0.97, 134e3, 1.80];

/// Seconds the order and the symbolic analysis of `n_free` DOFs are
/// predicted to take on this machine (`ORDERING_PER_DOF`, `SYMBOLIC_T4`,
/// `SYMBOLIC_T10`).
pub fn predicted_secs(order: Order, n_free: usize) -> [f64; 2] {
    let n = n_free as f64;
    let [t_ref, n_ref, p] = match order {
        Order::T4 => SYMBOLIC_T4,
        Order::T10 => SYMBOLIC_T10,
    };
    let scale = crate::linalg::rate::scale();
    [ORDERING_PER_DOF * n * scale, t_ref * (n / n_ref).powf(p) * scale]
}

/// The supernodal symbolic factor of `k` (the stiffness on `dofs`'s free
/// DOFs) in nested-dissection order; neither stage is started when the
/// prediction says it cannot end in the time left (module doc): a
/// `Timeout` naming its prediction.
pub fn analysed(mesh: &Mesh3d, dofs: &SolidDofs, k: &SparseColMat<usize, f64>) -> Result<SymbolicFactor, CoreError> {
    let [ordering, symbolic] = predicted_secs(mesh.order, dofs.n_free);
    cancel::check_room(ProgressStage::Factorization, ordering + symbolic)?;
    let (fwd, inv) = nested_dissection(mesh, dofs)?;
    // The order polls; the analysis does not: judged again with what is left.
    cancel::check_room(ProgressStage::Factorization, symbolic)?;
    Ok(SymbolicFactor::try_new_ordered(k, &fwd, &inv)?)
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::generate::box_mesh;
    use crate::solid::{dofs::dof_map, stiffness, SolidBody, Support};

    /// An order and analysis predicted past the time left are not started
    /// (2D's `an_ordering_that_cannot_end_in_time_is_not_started`): a T10
    /// cube of 22³ cells (about 2.7e5 free DOFs, its order and analysis
    /// predicted at about 3 s) given half its prediction is refused
    /// with that prediction, not by a poll (which names none) once the
    /// deadline passed.
    #[test]
    fn an_order_that_cannot_end_in_time_is_not_started() {
        let mesh = box_mesh([0.0; 3], [1.0; 3], 1.0 / 22.0, None, Order::T10);
        let body = SolidBody {
            mesh: &mesh,
            youngs_modulus: 1.0,
            poisson_ratio: 0.3,
            supports: vec![
                Support::roller("z_min", 2),
                Support::roller("x_min", 0),
                Support::roller("y_min", 1),
            ],
            loads: Vec::new(),
            body_force: [0.0; 3],
        };
        let dofs = dof_map(&body, None).expect("held");
        let k = stiffness::assemble(&body, &dofs).expect("no deadline yet");
        let [ordering, symbolic] = predicted_secs(Order::T10, dofs.n_free);
        let predicted = ordering + symbolic;
        assert!(predicted > 1.0, "{predicted} s: a prediction a poll could not overtake");
        let _deadline = cancel::Deadline::install(std::time::Duration::from_secs_f64(0.5 * predicted));
        match analysed(&mesh, &dofs, &k.k) {
            Err(CoreError::Timeout {
                predicted: Some((work, left)),
                ..
            }) => assert!(work > left, "{work} s predicted, {left} s left"),
            other => panic!("not refused by its prediction: {:?}", other.map(|s| s.cost())),
        }
    }
}
