use contact_core::Limits;
use contact_verify::effectivity::{level, table_of, SCENES};
fn main() {
    let limits = Limits {
        max_dofs: 5_000_000,
        ..Limits::default()
    };
    for name in ["disk_on_flat", "hertz_block", "ball_on_flat"] {
        let sc = SCENES.iter().find(|s| s.name == name).unwrap();
        let base = (sc.request)();
        for el in ["t6", "t3"] {
            for f in [4.0, 2.0, 1.0, 0.5] {
                let mut req = level(sc, &base, f, el);
                req["settings"]["estimate"] = serde_json::json!(false);
                let r = contact_verify::run::solve(&req, &limits).unwrap();
                let e = contact_verify::overkill::reference_error(table_of(name), &r).unwrap();
                let dofs = r.size.dofs;
                println!(
                    "{name} {el} f={f} dofs {dofs} res_err {:+.3e} l2 {:.3e}",
                    e.resultant, e.l2
                );
            }
        }
    }
}
