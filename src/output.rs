//! Writing output files so that a failure never leaves half a file behind:
//! the bytes go to a temporary file in the same directory, which is then
//! renamed over the destination.

use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` atomically.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut file = tempfile::Builder::new()
        .prefix(".lumlab-")
        .suffix(".partial")
        .tempfile_in(dir)
        .map_err(without_temporary_path)?;
    file.write_all(bytes)?;
    file.as_file().sync_all()?;
    file.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// tempfile's errors end with " at path <temporary file>"; the user only
/// knows the real destination, which the caller names.
fn without_temporary_path(e: std::io::Error) -> std::io::Error {
    let text = e.to_string();
    let cause = text.split(" at path ").next().unwrap_or(&text).to_owned();
    std::io::Error::new(e.kind(), cause)
}
