//! What a rigid motion of one body does to a set of rows over nodes (the
//! normal rows or the tangential ones): the compatibility LP's columns, the
//! reach of a motion left unresisted, and the frictional block's tangential
//! columns are all this one computation.

use crate::contact::Term;
use crate::fem::rigid_modes::RigidModes;
use crate::mesh::Mesh2d;

/// What a rigid motion of one body does to a set of rows (normal or
/// tangential, over nodes).
pub struct RigidColumn {
    /// Per row, −Σ coef · R(x) over the row's terms on the body: the row
    /// reads B u, and a rigid motion R β of its own points enters the rows
    /// as −C β, so its column of C is −B R.
    pub col: Vec<f64>,
    /// Per row, the largest |R(x)| among its points on the body: how far
    /// the row moves with the motion (0 off the body).
    pub reach: Vec<f64>,
}

/// The column and reach over `rows` of the rigid motion `dir` = (ux, uy,
/// rotation about the centre) of the body of `rm` (`RigidModes::at_dir`).
pub fn rigid_column<'a>(
    rows: impl IntoIterator<Item = &'a [Term]>,
    rm: &RigidModes,
    mesh: &Mesh2d,
    dir: [f64; 3],
) -> RigidColumn {
    let (mut col, mut reach) = (Vec::new(), Vec::new());
    for terms in rows {
        let on_body = || {
            terms
                .iter()
                .filter(|t| t.body == rm.body)
                .map(|t| (t, rm.at_dir(dir, mesh.nodes[t.node])))
        };
        col.push(on_body().map(|(t, d)| -(t.coef[0] * d[0] + t.coef[1] * d[1])).sum());
        reach.push(on_body().map(|(_, d)| d[0].hypot(d[1])).fold(0.0, f64::max));
    }
    RigidColumn { col, reach }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Order;

    /// A rigid column is the derivative of the gap under that motion. Nodes
    /// facing a circular obstacle (centre c, radius ρ) have the nodal rows
    /// n · u ≤ g, n = (c − x)/|c − x|, g = |c − x| − ρ; moved by ε R(x) the
    /// gap is |c − x − ε R(x)| − ρ, whose derivative at ε = 0 is −n · R(x),
    /// the column. A central difference at ε = 1e-6 errs by about
    /// ε² |R|³/|c − x|² ≈ 1e-12 and by the round-off ε_mach |g|/ε ≈ 1e-10:
    /// the tolerance is 1e-9. The reach is |R(x)|; a row on another body
    /// does not move (column and reach 0).
    #[test]
    fn a_rigid_column_is_the_derivative_of_the_gap() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.2], [-0.5, 0.4], [2.0, -0.3]];
        let mesh = Mesh2d {
            order: Order::T3,
            nodes: nodes.clone(),
            elems: Vec::new(),
            edge_sets: Default::default(),
        };
        let rm = RigidModes {
            body: 0,
            center: [0.3, -0.1],
            basis: Vec::new(),
            virtual_dofs: Vec::new(),
        };
        let (c, rho) = ([0.4, 3.0], 1.5);
        let gap = |x: [f64; 2]| (c[0] - x[0]).hypot(c[1] - x[1]) - rho;
        let mut rows: Vec<Vec<Term>> = nodes
            .iter()
            .enumerate()
            .map(|(node, x)| {
                let d = (c[0] - x[0]).hypot(c[1] - x[1]);
                let coef = [(c[0] - x[0]) / d, (c[1] - x[1]) / d];
                vec![Term { body: 0, node, coef }]
            })
            .collect();
        rows.push(vec![Term {
            body: 1,
            node: 0,
            coef: [1.0, 0.0],
        }]);
        for dir in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.3, -0.7, 0.4]] {
            let rc = rigid_column(rows.iter().map(Vec::as_slice), &rm, &mesh, dir);
            let eps = 1e-6;
            for (k, x) in nodes.iter().enumerate() {
                let r = rm.at_dir(dir, *x);
                let moved = |e: f64| gap([x[0] + e * r[0], x[1] + e * r[1]]);
                let fd = (moved(eps) - moved(-eps)) / (2.0 * eps);
                assert!(
                    (rc.col[k] - fd).abs() <= 1e-9,
                    "{dir:?}, node {k}: {} against {fd}",
                    rc.col[k]
                );
                assert_eq!(rc.reach[k], r[0].hypot(r[1]));
            }
            assert_eq!((rc.col[nodes.len()], rc.reach[nodes.len()]), (0.0, 0.0));
        }
    }
}
