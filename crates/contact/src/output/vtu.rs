//! The solve as a VTK XML unstructured grid (`.vtu`, what ParaView opens), as bytes.
//!
//! One piece holds every body: points (z = 0), the triangles (VTK type 5 for
//! T3, 22 for T6, whose node order — corners, then midsides of edges 01, 12,
//! 20 — is ours), point data `displacement` (ux, uy, 0) and `contact_pressure`
//! (0 off the contact candidates; a node in several pairs gets their sum),
//! with friction `contact_tangential_traction` (the tangential traction as a
//! vector (tx, ty, 0) on the body, 0 off the candidates of frictional pairs), cell
//! data at the element centroids: `stress` (σxx, σyy, σxy), `stress_tensor`
//! (the symmetric tensor in ParaView's order XX, YY, ZZ, XY, YZ, XZ, with σzz
//! of plane strain), `von_mises`, `principal_stress` (σ1 ≥ σ2 ≥ σ3) and `body`
//! (the body's index in the request), so ParaView shows them without a
//! calculator. Arrays are inline `binary` (base64 of a UInt64 byte count and
//! the little-endian values), which ParaView and meshio read, at a third more
//! than raw size rather than the ~2.5× of decimal text.
//!
//! vtkio (the Rust VTK crate) was not used: its last stable release is from
//! 2021, and this file is a page of XML.

use base64::Engine;

use crate::proto::SolveReply;

/// VTK cell types.
const VTK_TRIANGLE: u8 = 5;
const VTK_QUADRATIC_TRIANGLE: u8 = 22;

/// The von Mises stress of a symmetric tensor (XX, YY, ZZ, XY, YZ, XZ).
pub(super) fn von_mises(t: &[f64; 6]) -> f64 {
    let [xx, yy, zz, xy, yz, xz] = *t;
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) + 3.0 * (xy * xy + yz * yz + xz * xz)).sqrt()
}

/// The symmetric tensor (XX, YY, ZZ, XY, YZ, XZ), the von Mises stress and
/// the principal stresses (descending) of an in-plane stress with its σzz.
fn invariants(s: [f64; 3], zz: f64) -> ([f64; 6], f64, [f64; 3]) {
    let [xx, yy, xy] = s;
    let tensor = [xx, yy, zz, xy, 0.0, 0.0];
    let (c, r) = (0.5 * (xx + yy), (0.25 * (xx - yy).powi(2) + xy * xy).sqrt());
    let mut p = [c + r, c - r, zz];
    p.sort_by(|a, b| b.total_cmp(a));
    (tensor, von_mises(&tensor), p)
}

/// The VTU file of a reply whose `bodies` carry nodes, elements, displacement
/// and stress (the core computes them when `outputs` lists `vtu`); `stress_zz`
/// holds each body's σzz per element (empty: 0).
pub fn vtu(reply: &SolveReply, stress_zz: &[Vec<f64>], axisymmetric: bool) -> Vec<u8> {
    let bodies = reply.bodies.as_deref().unwrap_or_default();
    let mut points = Vec::new();
    let mut disp = Vec::new();
    let mut conn: Vec<i64> = Vec::new();
    let mut offsets: Vec<i64> = Vec::new();
    let mut types = Vec::new();
    let mut stress = Vec::new();
    let (mut tensor, mut von_mises, mut principal) = (Vec::new(), Vec::new(), Vec::new());
    let mut body_id: Vec<i32> = Vec::new();
    // First point of every body in the concatenated point list.
    let mut first = Vec::with_capacity(bodies.len());
    for (b, body) in bodies.iter().enumerate() {
        let base = points.len() / 3;
        first.push(base);
        let nodes = body.nodes.as_deref().unwrap_or_default();
        let u = body.displacement.as_deref().unwrap_or_default();
        for (k, p) in nodes.iter().enumerate() {
            points.extend_from_slice(&[p[0], p[1], 0.0]);
            let d = u.get(k).copied().unwrap_or_default();
            disp.extend_from_slice(&[d[0], d[1], 0.0]);
        }
        let elems = body.elements.as_deref().unwrap_or_default();
        let s = body.stress.as_deref().unwrap_or_default();
        for (e, el) in elems.iter().enumerate() {
            conn.extend(el.iter().map(|&n| (base + n) as i64));
            offsets.push(conn.len() as i64);
            types.push(if el.len() == 6 {
                VTK_QUADRATIC_TRIANGLE
            } else {
                VTK_TRIANGLE
            });
            let se = s.get(e).copied().unwrap_or_default();
            stress.extend_from_slice(&se);
            let zz = stress_zz.get(b).and_then(|z| z.get(e)).copied().unwrap_or_default();
            let (t, vm, p) = invariants(se, zz);
            tensor.extend_from_slice(&t);
            von_mises.push(vm);
            principal.extend_from_slice(&p);
            body_id.push(b as i32);
        }
    }
    let mut pressure = vec![0.0; points.len() / 3];
    let index = |name: &str| bodies.iter().position(|b| b.name == name);
    for pair in &reply.pairs {
        if let Some(b) = index(&pair.body) {
            for p in &pair.points {
                pressure[first[b] + p.node] += p.pressure;
            }
        }
        if let (Some(other), Some(pts)) = (pair.against.as_deref().and_then(index), &pair.other_points) {
            for p in pts {
                pressure[first[other] + p.node] += p.pressure;
            }
        }
    }

    // With friction: the tangential traction along each point's tangent
    // (`tangent`, or (−n_y, n_x)), as a vector ParaView can draw as glyphs.
    let friction = reply.pairs.iter().any(|p| p.friction.is_some());
    let mut tangential = vec![0.0; points.len()];
    for pair in reply.pairs.iter().filter(|p| p.friction.is_some()) {
        if let Some(b) = index(&pair.body) {
            for p in &pair.points {
                let t = p.tangential_traction.unwrap_or(0.0);
                let k = 3 * (first[b] + p.node);
                let tan = p.tangent.unwrap_or([-p.normal[1], p.normal[0]]);
                tangential[k] += t * tan[0];
                tangential[k + 1] += t * tan[1];
            }
        }
    }

    let n_points = points.len() / 3;
    let n_cells = types.len();
    let mut x = header();
    if axisymmetric {
        // The section of a body of revolution: the axis is the y axis through
        // the origin (a point and a direction); zz of the tensors is the hoop.
        x.push_str(
            "<FieldData>\n<DataArray type=\"Float64\" Name=\"revolution_axis\" NumberOfComponents=\"3\" \
            NumberOfTuples=\"2\" format=\"ascii\">0 0 0 0 1 0</DataArray>\n</FieldData>\n",
        );
    }
    x.push_str(&format!(
        "<Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\">\n"
    ));
    x.push_str("<PointData>\n");
    array(&mut x, "Float64", "displacement", 3, &le(&disp));
    array(&mut x, "Float64", "contact_pressure", 1, &le(&pressure));
    if friction {
        array(&mut x, "Float64", "contact_tangential_traction", 3, &le(&tangential));
    }
    x.push_str("</PointData>\n<CellData>\n");
    array(&mut x, "Float64", "stress", 3, &le(&stress));
    array(&mut x, "Float64", "stress_tensor", 6, &le(&tensor));
    array(&mut x, "Float64", "von_mises", 1, &le(&von_mises));
    array(&mut x, "Float64", "principal_stress", 3, &le(&principal));
    array(&mut x, "Int32", "body", 1, &le(&body_id));
    geometry(x, &points, &conn, &offsets, &types)
}

/// The file's start, up to its piece.
pub(super) fn header() -> String {
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\"?>\n");
    x.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    x.push_str("<UnstructuredGrid>\n");
    x
}

/// Closes the cell data and writes the points (x, y, z flat) and cells
/// after it, ending the file.
pub(super) fn geometry(mut x: String, points: &[f64], conn: &[i64], offsets: &[i64], types: &[u8]) -> Vec<u8> {
    x.push_str("</CellData>\n<Points>\n");
    array(&mut x, "Float64", "Points", 3, &le(points));
    x.push_str("</Points>\n<Cells>\n");
    array(&mut x, "Int64", "connectivity", 1, &le(conn));
    array(&mut x, "Int64", "offsets", 1, &le(offsets));
    array(&mut x, "UInt8", "types", 1, types);
    x.push_str("</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    x.into_bytes()
}

/// Little-endian bytes of numbers.
pub(super) fn le<T: Copy + ToLe>(v: &[T]) -> Vec<u8> {
    let mut out = Vec::with_capacity(std::mem::size_of_val(v));
    for a in v {
        a.put(&mut out);
    }
    out
}

pub(super) trait ToLe {
    fn put(self, out: &mut Vec<u8>);
}
impl ToLe for f64 {
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}
impl ToLe for i64 {
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}
impl ToLe for i32 {
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

/// One inline binary DataArray: base64 of (byte count as UInt64, data).
pub(super) fn array(x: &mut String, ty: &str, name: &str, components: usize, data: &[u8]) {
    let mut block = Vec::with_capacity(8 + data.len());
    block.extend_from_slice(&(data.len() as u64).to_le_bytes());
    block.extend_from_slice(data);
    x.push_str(&format!(
        "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{components}\" format=\"binary\">"
    ));
    x.push_str(&base64::engine::general_purpose::STANDARD.encode(&block));
    x.push_str("</DataArray>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(xml: &str, name: &str) -> Vec<u8> {
        let tag = format!("Name=\"{name}\"");
        let start = xml.find(&tag).unwrap();
        let body = &xml[start..];
        let (a, b) = (body.find('>').unwrap() + 1, body.find("</DataArray>").unwrap());
        let raw = base64::engine::general_purpose::STANDARD.decode(&body[a..b]).unwrap();
        let n = u64::from_le_bytes(raw[..8].try_into().unwrap()) as usize;
        assert_eq!(n, raw.len() - 8, "the header counts the data bytes");
        raw[8..].to_vec()
    }

    #[test]
    fn a_section_of_revolution_states_its_axis() {
        let reply: SolveReply = serde_json::from_str(include_str!("testdata/two_triangles_reply.json")).unwrap();
        let axi = String::from_utf8(vtu(&reply, &[], true)).unwrap();
        assert!(axi.contains(
            "Name=\"revolution_axis\" NumberOfComponents=\"3\" NumberOfTuples=\"2\" format=\"ascii\">0 0 0 0 1 0<"
        ));
        let plane = String::from_utf8(vtu(&reply, &[], false)).unwrap();
        assert!(!plane.contains("FieldData"));
    }

    #[test]
    fn arrays_round_trip_and_offsets_end_at_the_connectivity_length() {
        let reply: SolveReply = serde_json::from_str(include_str!("testdata/two_triangles_reply.json")).unwrap();
        let xml = String::from_utf8(vtu(&reply, &[], false)).unwrap();
        assert!(xml.contains("NumberOfPoints=\"4\" NumberOfCells=\"2\""));
        let f64s =
            |b: Vec<u8>| -> Vec<f64> { b.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect() };
        let p = f64s(decode(&xml, "contact_pressure"));
        // Nodes 0 and 1 are candidates with pressures 2 and 3; the others get 0.
        assert_eq!(p, vec![2.0, 3.0, 0.0, 0.0]);
        let off: Vec<i64> = decode(&xml, "offsets")
            .chunks(8)
            .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(off, vec![3, 6]);
        assert_eq!(decode(&xml, "types"), vec![VTK_TRIANGLE, VTK_TRIANGLE]);
        let d = f64s(decode(&xml, "displacement"));
        assert_eq!(&d[3..6], &[0.5, -1.0, 0.0], "node 1's (ux, uy, 0)");
    }

    /// A frictional pair adds the tangential traction as a vector along each
    /// point's tangent (−n_y, n_x); a frictionless reply has no such array.
    #[test]
    fn friction_adds_the_tangential_traction() {
        let mut reply: SolveReply = serde_json::from_str(include_str!("testdata/two_triangles_reply.json")).unwrap();
        let plain = String::from_utf8(vtu(&reply, &[], false)).unwrap();
        assert!(!plain.contains("contact_tangential_traction"));
        let pair = &mut reply.pairs[0];
        pair.friction = Some(crate::proto::PairFriction {
            coefficient: 0.5,
            stick_zones: vec![],
            slip_zones: vec![[0.0, 1.0]],
            stick_runs: vec![],
            slip_runs: vec![[[0.0, 0.0], [1.0, 0.0]]],
            tangential_resultant: Default::default(),
        });
        // Normal (0, −1): the tangent is (1, 0).
        pair.points[0].tangential_traction = Some(-1.0);
        pair.points[1].tangential_traction = Some(1.5);
        let xml = String::from_utf8(vtu(&reply, &[], false)).unwrap();
        let t: Vec<f64> = decode(&xml, "contact_tangential_traction")
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(t, vec![-1.0, 0.0, 0.0, 1.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    }

    /// Uniaxial stress: von Mises is its magnitude and the principals are
    /// (s, 0, 0); pure shear τ: von Mises √3 τ, principals (τ, 0, −τ).
    #[test]
    fn invariants_of_uniaxial_stress_and_pure_shear() {
        let (t, vm, p) = invariants([-3.0, 0.0, 0.0], 0.0);
        assert_eq!(t, [-3.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!((vm - 3.0).abs() < 1e-15);
        assert_eq!(p, [0.0, 0.0, -3.0]);
        let (_, vm, p) = invariants([0.0, 0.0, 2.0], 0.0);
        assert!((vm - 2.0 * 3f64.sqrt()).abs() < 1e-14);
        assert!((p[0] - 2.0).abs() < 1e-15 && p[1] == 0.0 && (p[2] + 2.0).abs() < 1e-15);
    }
}
