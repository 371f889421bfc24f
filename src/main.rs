//! The `lumlab` binary: argument parsing only, then the library takes over.

/// The system allocator with large blocks in huge pages (see `allocator.rs`).
#[global_allocator]
static ALLOCATOR: lumlab::allocator::HugePages = lumlab::allocator::HugePages;

fn main() -> std::process::ExitCode {
    lumlab::cli::main()
}
