//! The 3D rows of `contact-bench --solid` (`solid_bench`), at `--quick`'s
//! sizes: every row is the example's ball, solved and certified, and its
//! errors against Hertz shrink as the mesh is refined. Timings are printed,
//! never asserted.
//!
//! Tolerances: the certificate is the solve's round-off (1.9e-15 the
//! largest measured on these rows): 1e-12. Halving h_min at the apex (0.4 to
//! 0.2 mm on T4, 0.8 to 0.4 on T10, a = 1 mm) moved the fitted a from
//! −5.9 % to +1.4 % (T4) and from +10.1 % to −1.4 % (T10), the peak from
//! −3.8 % to +1.0 % and from −26 % to −6.5 %: the finer row's errors are
//! asked to be smaller than the coarser's.

use contact_verify::solid_ball::request;
use contact_verify::solid_bench::run;

#[test]
fn the_quick_rows_are_certified_and_converge() {
    let rows = run(true, 1, |r| println!("{}", r.table_line()));
    assert_eq!(rows.len(), 4, "two sizes of T4 and of T10");
    for r in &rows {
        assert_eq!(r.status, "solved", "{r:?}");
        assert!(r.certificate < 1e-12, "{r:?}");
        assert!(r.dofs > 0 && r.active > 0 && r.active <= r.candidates, "{r:?}");
    }
    for pair in rows.chunks(2) {
        let (coarse, fine) = (&pair[0], &pair[1]);
        assert_eq!(coarse.element, fine.element);
        assert!(fine.h_min < coarse.h_min && fine.dofs > coarse.dofs);
        assert!(fine.err_a.abs() < coarse.err_a.abs(), "{coarse:?} then {fine:?}");
        assert!(fine.err_p0.abs() < coarse.err_p0.abs(), "{coarse:?} then {fine:?}");
    }
}

/// The bench's request is the example with only the element and h_min
/// changed.
#[test]
fn the_bench_solves_the_example() {
    let example: serde_json::Value =
        serde_json::from_str(include_str!("../../../proto/examples/solid_ball_on_flat.json")).unwrap();
    let req = request("t10", 0.2);
    assert_eq!(req, example, "the example is T10 at h_min 0.2");
}
