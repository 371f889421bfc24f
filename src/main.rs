//! The `lumlab` binary: argument parsing only, then the library takes over.

/// The system allocator with large blocks in huge pages (see `allocator.rs`).
#[global_allocator]
static ALLOCATOR: lumlab::allocator::HugePages = lumlab::allocator::HugePages;

fn main() -> std::process::ExitCode {
    use lumlab::gpu::context::{MESA_EXTENSION_OVERRIDE, mesa_extension_override};
    let current = std::env::var(MESA_EXTENSION_OVERRIDE).ok();
    if let Some(value) = mesa_extension_override(current.as_deref()) {
        // SAFETY: the process has one thread here; nothing reads the
        // environment concurrently.
        unsafe { std::env::set_var(MESA_EXTENSION_OVERRIDE, value) };
    }
    lumlab::cli::main()
}
