//! `contact`: the command-line shell (`contact::cli`).

fn main() -> std::process::ExitCode {
    std::process::ExitCode::from(contact::cli::main(std::env::args_os()))
}
