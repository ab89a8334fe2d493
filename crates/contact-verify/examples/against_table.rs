//! A request file solved in process and its first pair read against a stored
//! overkill table (`contact_verify::overkill`) of the same scene: the
//! estimate beside the true error, and the refinement's rounds.
//! `cargo run --release -p contact-verify --example against_table --
//! disk_on_flat request.json`.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [table, path] = &args[..] else {
        eprintln!("usage: against_table TABLE REQUEST.json");
        std::process::exit(2);
    };
    let text = std::fs::read_to_string(path).expect("request file");
    let req: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let t = std::time::Instant::now();
    let r = contact_verify::run::solve(&req, &Default::default()).expect("solved");
    let seconds = t.elapsed().as_secs_f64();
    let e = contact_verify::overkill::reference_error(table, &r).expect("a stored table");
    let reference = contact_verify::overkill::reference(table).expect("a stored table");
    let peak = r.pairs[0].points.iter().map(|q| q.pressure).fold(0.0, f64::max);
    let acc = r.pairs[0].accuracy.as_ref();
    let pct = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{:.3} %", 100.0 * v));
    println!(
        "dofs {}  status {:?}  {seconds:.3} s (estimate {:.3} s)",
        r.size.dofs, r.status, r.timings.estimate
    );
    println!("basis {}", acc.map_or("-", |a| a.basis.as_str()));
    println!(
        "pressure_l2  estimate {:>9}  true {:>9}",
        pct(acc.and_then(|a| a.pressure_l2)),
        pct(Some(e.l2))
    );
    println!(
        "resultant    estimate {:>9}  true {:>9}",
        pct(acc.and_then(|a| a.resultant)),
        pct(Some(e.resultant.abs()))
    );
    println!(
        "peak         estimate {:>9}  true {:>9}",
        pct(acc.and_then(|a| a.peak)),
        pct(Some((peak / reference.pressure(0.0) - 1.0).abs()))
    );
    if let Some(f) = &r.refinement {
        println!("refinement: reached {} stopped {}", f.reached, f.stopped);
        for round in &f.rounds {
            println!("  {round:?}");
        }
    }
    for w in &r.warnings {
        println!("warning {}: {}", w.code, w.message);
    }
    for n in &r.notes {
        println!("note: {n}");
    }
}
