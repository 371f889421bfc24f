//! Writing output files so that a failure never leaves half a file behind:
//! the bytes go to a temporary file in the destination's folder, named
//! `.NAME.XXXXXX.lumlab-partial`, which is then renamed over the destination.
//!
//! The file gets the permissions any other program would give it: a new
//! file 0666 less the umask (0644 under umask 022), a replaced file keeps
//! its mode. A read-only destination is refused, and a symbolic link is
//! followed: its target is what gets written.

use std::io::Write;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// What a temporary file's name ends with, so that one left by a crash
/// says what it is.
pub const PARTIAL_SUFFIX: &str = ".lumlab-partial";

/// Links followed at most before giving up (as the kernel's ELOOP).
const MAX_LINKS: usize = 40;

/// Why an output path cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("'{path}': the folder '{folder}' does not exist")]
    NoFolder { path: PathBuf, folder: PathBuf },
    #[error("'{path}': is a folder, not a file")]
    IsFolder { path: PathBuf },
    #[error("'{path}': the file is read-only; make it writable or choose another name")]
    ReadOnly { path: PathBuf },
    #[error("'{path}': too many levels of symbolic links")]
    LinkLoop { path: PathBuf },
    #[error("'{path}': cannot write in '{folder}': {source}")]
    NotWritable {
        path: PathBuf,
        folder: PathBuf,
        source: std::io::Error,
    },
    #[error("'{path}': {source}")]
    Io { path: PathBuf, source: std::io::Error },
}

/// Set by the command line's signal handler; a write that sees it drops its
/// temporary file instead of putting it in place.
static INTERRUPT: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The flag a signal handler sets to stop the work.
pub fn interrupt_flag() -> Arc<AtomicBool> {
    Arc::clone(INTERRUPT.get_or_init(Arc::default))
}

/// True once an interrupt (SIGINT, SIGTERM, SIGHUP) asked the work to stop.
pub fn interrupted() -> bool {
    INTERRUPT.get().is_some_and(|flag| flag.load(Ordering::Relaxed))
}

/// The file a write to `path` changes: `path`, or the target of the
/// symbolic link(s) it names (which need not exist yet).
pub fn resolve(path: &Path) -> Result<PathBuf, OutputError> {
    let mut current = path.to_owned();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&current) {
            Ok(m) if m.file_type().is_symlink() => {
                let target = std::fs::read_link(&current).map_err(|source| OutputError::Io {
                    path: path.to_owned(),
                    source,
                })?;
                current = folder_of(&current).join(target);
            }
            _ => return Ok(current),
        }
    }
    Err(OutputError::LinkLoop {
        path: path.to_owned(),
    })
}

/// The folder a file is in ("." for a bare name).
pub fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Checks, before any work, that `path` can be written: its folder exists
/// and takes new files, and an existing file there is a writable file.
/// Returns the file that will be written (links followed).
pub fn check_writable(path: &Path) -> Result<PathBuf, OutputError> {
    let target = resolve(path)?;
    let folder = folder_of(&target);
    if !folder.is_dir() {
        return Err(OutputError::NoFolder {
            path: path.to_owned(),
            folder: folder.to_owned(),
        });
    }
    match std::fs::metadata(&target) {
        Ok(m) if m.is_dir() => {
            return Err(OutputError::IsFolder {
                path: path.to_owned(),
            });
        }
        Ok(m) if m.permissions().readonly() => {
            return Err(OutputError::ReadOnly {
                path: path.to_owned(),
            });
        }
        _ => {}
    }
    // The only sure test of a folder's write permission is to try; the
    // probe is removed at once.
    temporary_file(&target).map_err(|source| OutputError::NotWritable {
        path: path.to_owned(),
        folder: folder.to_owned(),
        source,
    })?;
    Ok(target)
}

/// A new temporary file beside `target`, removed when dropped.
fn temporary_file(target: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let name = target
        .file_name()
        .map_or("output".into(), |n| n.to_string_lossy());
    tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(PARTIAL_SUFFIX)
        // Given to open(2), so the umask applies, as for any new file.
        .permissions(std::fs::Permissions::from_mode(0o666))
        .tempfile_in(folder_of(target))
        .map_err(without_temporary_path)
}

/// Writes `bytes` to `path` atomically (see the module's notes); after an
/// interrupt the temporary file is dropped and nothing changes.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write(path, bytes, true)
}

/// As [`write_atomically`], but completes after an interrupt: for the last
/// step of a change that must not stop half-way.
pub fn write_atomically_to_finish(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write(path, bytes, false)
}

/// The environment variable that lets the tests holding a generated asset
/// to its generator write the asset anew instead of failing.
#[cfg(test)]
const RENEW_ASSETS: &str = "LUMLAB_RENEW_ASSETS";

/// For a test that found the asset checked in at `path` (relative to the
/// crate) to differ from what its generator makes now, `fresh`: writes
/// `fresh` there when `LUMLAB_RENEW_ASSETS` is set (then commit it), and
/// fails otherwise, saying how to renew it. The assets' generators are the
/// library's own code (`scene::default_scene::build`, `app::icon::draw`);
/// every such test has `generated_asset` in its name.
#[cfg(test)]
pub(crate) fn renew_asset_or_fail(path: &str, fresh: &[u8]) {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    if std::env::var_os(RENEW_ASSETS).is_some() {
        write_atomically(&file, fresh).unwrap_or_else(|e| panic!("writing {}: {e}", file.display()));
        eprintln!("wrote {} ({} bytes): commit it", file.display(), fresh.len());
    } else {
        panic!("{path} is stale: run `{RENEW_ASSETS}=1 cargo test --lib generated_asset` and commit it");
    }
}

fn write(path: &Path, bytes: &[u8], interruptible: bool) -> std::io::Result<()> {
    let target = resolve(path).map_err(std::io::Error::other)?;
    let existing = std::fs::metadata(&target).ok();
    if existing.as_ref().is_some_and(|m| m.permissions().readonly()) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::PermissionDenied,
            "the file is read-only",
        ));
    }
    let mut file = temporary_file(&target)?;
    file.write_all(bytes)?;
    if let Some(existing) = existing {
        let mode = existing.permissions().mode() & 0o7777;
        file.as_file()
            .set_permissions(std::fs::Permissions::from_mode(mode))?;
    }
    file.as_file().sync_all()?;
    if interruptible && interrupted() {
        // Dropping the temporary file removes it: the folder stays as it was.
        return Err(std::io::Error::new(
            std::io::ErrorKind::Interrupted,
            "interrupted",
        ));
    }
    file.persist(&target).map_err(|e| e.error)?;
    Ok(())
}

/// tempfile's errors end with " at path <temporary file>"; the user only
/// knows the real destination, which the caller names.
fn without_temporary_path(e: std::io::Error) -> std::io::Error {
    let text = e.to_string();
    let cause = text.split(" at path ").next().unwrap_or(&text).to_owned();
    std::io::Error::new(e.kind(), cause)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(path: &Path) -> u32 {
        std::fs::metadata(path).unwrap().permissions().mode() & 0o777
    }

    #[test]
    fn an_existing_file_keeps_its_mode() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        std::fs::write(&path, "old").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o640)).unwrap();
        write_atomically(&path, b"new").unwrap();
        assert_eq!(mode(&path), 0o640);
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
    }

    #[test]
    fn a_read_only_file_is_refused_and_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        std::fs::write(&path, "keep").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o444)).unwrap();
        assert!(matches!(check_writable(&path), Err(OutputError::ReadOnly { .. })));
        assert!(write_atomically(&path, b"new").is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"keep");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_link_is_followed_to_its_target() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("real.txt");
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink("real.txt", &link).unwrap();
        assert_eq!(check_writable(&link).unwrap(), target);
        write_atomically(&link, b"through").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"through");
        let looped = dir.path().join("loop");
        std::os::unix::fs::symlink("loop", &looped).unwrap();
        assert!(matches!(
            check_writable(&looped),
            Err(OutputError::LinkLoop { .. })
        ));
    }

    #[test]
    fn bad_destinations_are_named_before_any_work() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("no/such/a.png");
        assert!(matches!(
            check_writable(&missing),
            Err(OutputError::NoFolder { .. })
        ));
        assert!(matches!(
            check_writable(dir.path()),
            Err(OutputError::IsFolder { .. })
        ));
        assert!(check_writable(&dir.path().join("new.png")).is_ok());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "the probe is removed"
        );
    }
}
