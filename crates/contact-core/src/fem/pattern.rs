//! The sparse stiffness of any mesh with D displacement components per node:
//! its CSC pattern (lower triangle of K_ff) from the node graph, and the
//! scatter of element matrices into it and into K_fd.
//!
//! Global DOF D·node + c; `free[d]` is DOF d's free index or `FIXED`. Free
//! indices grow with the global DOF number, so each column's rows come out
//! sorted and an element entry finds its place by binary search: the pattern
//! is built once and the values are added in place (no triplet sort).

/// The free index of a prescribed DOF.
pub const FIXED: usize = usize::MAX;

/// CSC pattern of the lower triangle of K_ff: column of free DOF j holds the
/// free DOFs i ≥ j of the nodes sharing an element with j's node.
/// `each_element` calls its argument once per element with the element's
/// global node numbers (of `total_nodes`).
pub fn lower<const D: usize>(
    total_nodes: usize,
    free: &[usize],
    n_free: usize,
    each_element: impl FnOnce(&mut dyn FnMut(&[usize])),
) -> (Vec<usize>, Vec<usize>) {
    debug_assert_eq!(free.len(), D * total_nodes);
    // Neighbours b ≥ a of each node a (small, so linear insertion).
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); total_nodes];
    each_element(&mut |conn: &[usize]| {
        for &a in conn {
            for &c in conn {
                if c >= a && !adj[a].contains(&(c as u32)) {
                    adj[a].push(c as u32);
                }
            }
        }
    });
    let mut col_ptr = Vec::with_capacity(n_free + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for (a, nb) in adj.iter_mut().enumerate() {
        nb.sort_unstable();
        for ca in 0..D {
            if free[D * a + ca] == FIXED {
                continue;
            }
            for &bn in nb.iter() {
                let bn = bn as usize;
                for cb in 0..D {
                    let i = free[D * bn + cb];
                    if i != FIXED && (bn > a || cb >= ca) {
                        row_idx.push(i);
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
    }
    (col_ptr, row_idx)
}

/// The global matrices being assembled: K_ff's values on its pattern and K_fd.
pub struct Global<'a> {
    pub col_ptr: &'a [usize],
    pub row_idx: &'a [usize],
    pub vals: Vec<f64>,
    /// (free row, global prescribed DOF, value) of K_fd.
    pub k_fd: Vec<(usize, usize, f64)>,
}

impl<'a> Global<'a> {
    /// Zero values on the pattern `(col_ptr, row_idx)`.
    pub fn new(col_ptr: &'a [usize], row_idx: &'a [usize]) -> Self {
        Self {
            col_ptr,
            row_idx,
            vals: vec![0.0; row_idx.len()],
            k_fd: Vec::new(),
        }
    }

    /// Adds the element matrix `ke` (row-major, nd × nd with nd = `gd.len()`)
    /// of the element with global DOFs `gd`.
    pub fn add(&mut self, gd: &[usize], free: &[usize], ke: &[f64]) {
        let nd = gd.len();
        for a in 0..nd {
            let fa = free[gd[a]];
            if fa == FIXED {
                continue;
            }
            for c in 0..nd {
                let fc = free[gd[c]];
                let v = ke[a * nd + c];
                if fc == FIXED {
                    if v != 0.0 {
                        self.k_fd.push((fa, gd[c], v));
                    }
                } else if fc <= fa {
                    let col = &self.row_idx[self.col_ptr[fc]..self.col_ptr[fc + 1]];
                    let pos = col.binary_search(&fa).expect("pattern covers every element coupling");
                    self.vals[self.col_ptr[fc] + pos] += v;
                }
            }
        }
    }
}
