//! The 3D solid as a VTK XML unstructured grid, in the 2D file's form
//! (`vtu`: inline base64 binary arrays): the tetrahedra as VTK_TETRA (10)
//! or VTK_QUADRATIC_TETRA (24), point data `displacement` (ux, uy, uz) and
//! `contact_pressure` (each contact point's pressure on its node, 0 off
//! the candidates; on T10, whose points are the corners, a midside between
//! two points gets their mean, so ParaView's quadratic interpolation does
//! not dip to 0 between corners), cell data `stress_tensor` (XX, YY, ZZ, XY, YZ, XZ, at
//! the centroid) and `von_mises`.

use contact_core::mesh3d::{Order, EDGES};
use contact_core::solid::answer::BodyFields;

use super::vtu::{array, geometry, header, le, von_mises};

const VTK_TETRA: u8 = 10;
const VTK_QUADRATIC_TETRA: u8 = 24;

/// VTK node k of a quadratic tetra is our (Gmsh's) node `T10_TO_VTK[k]`.
/// Gmsh's 10-node tetrahedron lists the midsides of edges 0-1, 1-2, 2-0,
/// 3-0, 3-2, 3-1 (`mesh3d` module doc); VTK's (vtkQuadraticTetra) lists
/// 0-1, 1-2, 2-0, 0-3, 1-3, 2-3: the same six edges, the last two swapped.
pub const T10_TO_VTK: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// Voigt (xx, yy, zz, yz, xz, xy) → ParaView's (XX, YY, ZZ, XY, YZ, XZ).
pub fn paraview_order(s: &[f64; 6]) -> [f64; 6] {
    [s[0], s[1], s[2], s[5], s[3], s[4]]
}

/// The file of a solved body; `pressure` holds (node, pressure) of each
/// contact point (a node listed twice gets the sum).
pub fn solid_vtu(f: &BodyFields, order: Order, pressure: &[(usize, f64)]) -> Vec<u8> {
    let (k, cell_type) = match order {
        Order::T4 => (4, VTK_TETRA),
        Order::T10 => (10, VTK_QUADRATIC_TETRA),
    };
    let points: Vec<f64> = f.nodes.iter().flatten().copied().collect();
    let disp: Vec<f64> = f.displacement.iter().flatten().copied().collect();
    let mut p = vec![0.0; f.nodes.len()];
    let mut point = vec![false; f.nodes.len()];
    for &(node, v) in pressure {
        p[node] += v;
        point[node] = true;
    }
    if order == Order::T10 {
        for el in f.elems.chunks_exact(10) {
            for (j, [a, b]) in EDGES.iter().enumerate() {
                let (a, b, m) = (el[*a], el[*b], el[4 + j]);
                if point[a] && point[b] && !point[m] {
                    p[m] = 0.5 * (p[a] + p[b]);
                }
            }
        }
    }
    let conn: Vec<i64> = f
        .elems
        .chunks_exact(k)
        .flat_map(|el| (0..k).map(move |j| el[if k == 10 { T10_TO_VTK[j] } else { j }] as i64))
        .collect();
    let n_cells = f.elems.len() / k;
    let offsets: Vec<i64> = (1..=n_cells).map(|c| (c * k) as i64).collect();
    let types = vec![cell_type; n_cells];
    let tensors: Vec<[f64; 6]> = f.stress.iter().map(paraview_order).collect();
    let mut x = header();
    x.push_str(&format!(
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{n_cells}\">\n<PointData>\n",
        f.nodes.len()
    ));
    array(&mut x, "Float64", "displacement", 3, &le(&disp));
    array(&mut x, "Float64", "contact_pressure", 1, &le(&p));
    x.push_str("</PointData>\n<CellData>\n");
    if !tensors.is_empty() {
        let flat: Vec<f64> = tensors.iter().flatten().copied().collect();
        let vm: Vec<f64> = tensors.iter().map(von_mises).collect();
        array(&mut x, "Float64", "stress_tensor", 6, &le(&flat));
        array(&mut x, "Float64", "von_mises", 1, &le(&vm));
    }
    geometry(x, &points, &conn, &offsets, &types)
}
