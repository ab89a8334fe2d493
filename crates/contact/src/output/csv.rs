//! The contact candidates of a reply as CSV, one row per candidate:
//! `x,y,pair,body,gap,pressure,force,node` (pair: index in the request's
//! `contacts`; node: index in the body's mesh). Numbers are written in Rust's
//! shortest round-trip form, so the CSV holds exactly the reply's values.

use crate::proto::SolveReply;

pub const HEADER: &str = "x,y,pair,body,gap,pressure,force,node";

pub fn points_csv(reply: &SolveReply) -> String {
    let mut out = String::from(HEADER);
    out.push('\n');
    for (k, pair) in reply.pairs.iter().enumerate() {
        // Body names are free text: quote them as RFC 4180 says.
        let body = format!("\"{}\"", pair.body.replace('"', "\"\""));
        for p in &pair.points {
            out.push_str(&format!(
                "{},{},{k},{body},{},{},{},{}\n",
                p.x, p.y, p.gap, p.pressure, p.force, p.node
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_row_per_candidate_with_exact_values() {
        let reply: SolveReply = serde_json::from_str(include_str!("testdata/two_triangles_reply.json")).unwrap();
        let csv = points_csv(&reply);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], HEADER);
        assert_eq!(lines.len(), 1 + 2);
        assert_eq!(lines[1], "0,0,0,\"plate\",0,2,1,0");
        let force: f64 = lines[2].split(',').nth(6).unwrap().parse().unwrap();
        assert_eq!(force, 0.1 + 0.2, "shortest round-trip form keeps every bit");
    }
}
