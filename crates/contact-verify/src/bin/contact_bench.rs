//! `contact-bench`: the benchmark, convergence and stability suites of
//! `contact-verify` run from the command line, their tables printed and
//! written as CSV (`cargo run --release -p contact-verify --bin contact-bench
//! -- --quick`).
//!
//! It was `contact bench` until 0.2.0 (issue 38.4): a binary of its own here,
//! so that the service binary and the Python extension no longer link the
//! verification crate. Measured at 0.2.0, release build: the `contact` binary
//! went from 127.8 MB to 123.8 MB (22.5 MB to 21.5 MB stripped) by this move alone;
//! with the regex-syntax features that `contact` now asks for (its Cargo.toml), 124.7 MB
//! (22.2 MB stripped); the extension from 130.7 MB to 127.6 MB (22.9 to 22.6 MB stripped).

use std::path::{Path, PathBuf};

use anyhow::Context;

/// Where the bench's CSV goes unless told (the convergence and stability
/// suites' defaults sit beside it).
const DEFAULT_BENCH_CSV: &str = "bench_out/bench.csv";

/// Time-against-error benchmark (Hertz, T3/T6, every method): table on
/// stdout, CSV file; with --convergence, --stability or --solid the other
/// suites.
#[derive(clap::Parser)]
#[command(name = "contact-bench", version)]
pub struct Bench {
    /// Meshes up to ~100k DOF only (for CI).
    #[arg(long)]
    quick: bool,
    /// `auto` alone against the floor, T3, at about 75k, 612k and 1.19M DOF.
    #[arg(long, conflicts_with = "quick")]
    floor: bool,
    /// Threads of the sparse factorization and sweeps, for the solve and
    /// the floor alike (default 1).
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// CSV output path.
    #[arg(long, default_value = DEFAULT_BENCH_CSV)]
    csv: PathBuf,
    /// Runs per row; the median is reported.
    #[arg(long, default_value_t = 1)]
    repeat: usize,
    /// The numerical stress suite instead (one row per scene and axis value;
    /// CSV to --csv, default bench_out/stability.csv).
    #[arg(long)]
    stability: bool,
    /// Convergence under refinement against Hertz instead (elastic disk on a
    /// rigid flat and rigid cylinder into a block, six levels, T3 and T6;
    /// the disk, the ball and the block also against overkill references;
    /// CSV to --csv, default bench_out/convergence.csv), then the time to a
    /// tolerance (tolerance.csv), the error estimate's effectivity on
    /// nine scenes, two of them given inline (effectivity.csv) and the frictional stick zone against
    /// Cattaneo–Mindlin, three levels, T3 and T6 (friction_convergence.csv)
    /// beside it.
    #[arg(long, conflicts_with = "stability")]
    convergence: bool,
    /// The 3D rows instead: Hertz's ball on a flat (the example's quarter
    /// model), T4 and T10 at four sizes each (`--quick`: two), stage times
    /// and the errors of a and p0; CSV to --csv, default bench_out/solid.csv.
    #[arg(long, conflicts_with_all = ["stability", "convergence", "floor"])]
    solid: bool,
}

/// Writes a CSV table (header, then one line per row) and says so.
fn write_csv(path: &Path, header: &str, rows: impl IntoIterator<Item = String>) -> anyhow::Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let mut text = format!("{header}\n");
    for r in rows {
        text.push_str(&r);
        text.push('\n');
    }
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

fn run(opts: Bench) -> anyhow::Result<()> {
    let Bench {
        quick,
        floor,
        threads,
        csv,
        repeat,
        stability,
        convergence,
        solid,
    } = opts;
    let (header, lines) = if solid {
        contact_core::linalg::set_threads(threads);
        println!("3D: Hertz's ball on a rigid flat (quarter model, R = 50 mm, P = 6154 N), {threads} thread(s):");
        println!("{}", contact_verify::solid_bench::SolidRow::table_header());
        let rows = contact_verify::solid_bench::run(quick, repeat, |r| println!("{}", r.table_line()));
        (
            contact_verify::solid_bench::SolidRow::HEADER,
            rows.iter().map(|r| r.csv()).collect::<Vec<_>>(),
        )
    } else if convergence {
        println!("{}", contact_verify::convergence::Row::table_header());
        let rows = contact_verify::convergence::run(quick, |r| println!("{}", r.table_line()));
        println!(
            "model floor of disk_on_flat (finite disk against the half-plane formula): about {:.1} % in L2, {:.2} % in \
                the moment half-width",
            100.0 * contact_verify::convergence::DISK_FLOOR_L2,
            100.0 * contact_verify::convergence::DISK_FLOOR_MOMENT
        );
        for line in contact_verify::overkill::summary() {
            println!("{line}");
        }
        // Time to a tolerance, over the levels the table above ran.
        let levels = if quick { 3 } else { contact_verify::convergence::LEVELS };
        println!("\ntime to a tolerance, disk on a flat (error against its overkill table):");
        println!("{}", contact_verify::tolerance::Row::table_header());
        let tol = contact_verify::tolerance::run(levels, |r| println!("{}", r.table_line()));
        // Beside the convergence CSV.
        write_csv(
            &csv.with_file_name("tolerance.csv"),
            contact_verify::tolerance::Row::HEADER,
            tol.iter().map(|r| r.csv()),
        )?;
        // The estimate against the true error on every kind of scene.
        println!("\nerror estimate against the true error (reference: T6, every element half the scene's own):");
        println!("{}", contact_verify::effectivity::Row::table_header());
        let eff = contact_verify::effectivity::run(&[], |r| println!("{}", r.table_line()));
        write_csv(
            &csv.with_file_name("effectivity.csv"),
            contact_verify::effectivity::Row::HEADER,
            eff.iter().map(|r| r.csv()),
        )?;
        // Friction: the stick zone against Cattaneo–Mindlin.
        println!(
            "\nfriction: stick half-width c of a roller (nu = 0.499) on a rigid floor, then of two identical cylinders \
                (nu = 0.3), mu = {}, pressed then shifted, against Cattaneo-Mindlin:",
            contact_verify::friction::MU
        );
        println!("{}", contact_verify::friction::Row::table_header());
        let fr = contact_verify::friction::run(|r| println!("{}", r.table_line()));
        write_csv(
            &csv.with_file_name("friction_convergence.csv"),
            contact_verify::friction::Row::HEADER,
            fr.iter().map(|r| r.csv()),
        )?;
        (
            contact_verify::convergence::Row::HEADER,
            rows.iter().map(|r| r.csv()).collect::<Vec<_>>(),
        )
    } else if stability {
        println!("{}", contact_verify::stability::Row::table_header());
        let rows = contact_verify::stability::run(quick, |r| println!("{}", r.table_line()));
        let unclear = rows.iter().filter(|r| !r.is_clear()).count();
        println!(
            "{} rows, {unclear} neither certified nor refused with a clear status",
            rows.len()
        );
        (
            contact_verify::stability::Row::HEADER,
            rows.iter().map(|r| r.csv()).collect::<Vec<_>>(),
        )
    } else {
        println!("{}", contact_verify::bench::Row::table_header());
        let mode = match (quick, floor) {
            (true, _) => contact_verify::bench::Mode::Quick,
            (_, true) => contact_verify::bench::Mode::Floor,
            _ => contact_verify::bench::Mode::Full,
        };
        contact_core::linalg::set_threads(threads);
        let rows = contact_verify::bench::run(mode, repeat, |r| println!("{}", r.table_line()));
        (
            contact_verify::bench::Row::HEADER,
            rows.iter().map(|r| r.csv()).collect(),
        )
    };
    let csv = match (stability, convergence, solid) {
        _ if csv != Path::new(DEFAULT_BENCH_CSV) => csv,
        (true, _, _) => PathBuf::from("bench_out/stability.csv"),
        (_, true, _) => PathBuf::from("bench_out/convergence.csv"),
        (_, _, true) => PathBuf::from("bench_out/solid.csv"),
        _ => csv,
    };
    write_csv(&csv, header, lines)
}

fn main() -> anyhow::Result<()> {
    run(clap::Parser::parse())
}
