//! The effectivity table (`contact_verify::effectivity`) for the scenes named
//! on the command line (all without): `cargo run --release -p contact-verify
//! --example effectivity -- disk_on_flat_inline punch_under_moment`.

fn main() {
    let names: Vec<String> = std::env::args().skip(1).collect();
    let only: Vec<&str> = names.iter().map(String::as_str).collect();
    println!("{}", contact_verify::effectivity::Row::table_header());
    contact_verify::effectivity::run(&only, |r| println!("{}", r.table_line()));
}
