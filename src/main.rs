//! The `lumlab` binary: argument parsing only, then the library takes over.

fn main() -> std::process::ExitCode {
    lumlab::cli::main()
}
