//! The report's folder: a new one, an empty one, or one that an earlier
//! report wrote, recognised by the marker file `.lumlab-report` that lists
//! the files it wrote. Anything else is refused untouched. In a folder of
//! its own the report replaces only the files its marker lists: whatever
//! else is there stays.
//!
//! The report is first written into a staging folder beside the destination
//! (`.NAME.XXXXXX.lumlab-report-partial`), removed on failure; a new folder
//! is then renamed into place whole, an existing one receives the files one
//! rename at a time.

use crate::output::{folder_of, resolve};
use std::os::unix::fs::PermissionsExt;
use std::path::{Component, Path, PathBuf};

/// The marker file: what the report wrote, one relative path a line.
pub const MARKER: &str = ".lumlab-report";
const MARKER_HEADER: &str =
    "# written by lumlab report: the files below are replaced by the next report here";
/// What a staging folder's name ends with.
pub const STAGING_SUFFIX: &str = ".lumlab-report-partial";

#[derive(Debug, thiserror::Error)]
pub enum FolderError {
    #[error("'{0}': the folder it would go in, '{1}', does not exist")]
    NoParent(PathBuf, PathBuf),
    #[error("'{0}': '{1}' is not a folder")]
    ParentNotFolder(PathBuf, PathBuf),
    #[error("'{0}': exists and is not a folder")]
    NotFolder(PathBuf),
    #[error(
        "'{0}': the folder is not empty and was not written by lumlab report (it has no {MARKER} marker); \
         give a new or empty folder"
    )]
    Foreign(PathBuf),
    #[error("'{0}': cannot write there: {1}")]
    NotWritable(PathBuf, std::io::Error),
    #[error("'{0}': {1}")]
    Io(PathBuf, std::io::Error),
}

/// Where a report goes and the staging folder it is written in first.
pub struct ReportFolder {
    staging: tempfile::TempDir,
    destination: PathBuf,
    /// The files an earlier report there wrote; None for a new folder.
    earlier: Option<Vec<PathBuf>>,
}

impl ReportFolder {
    /// Checks the destination (before any work) and makes the staging folder.
    pub fn prepare(destination: &Path) -> Result<Self, FolderError> {
        let shown = destination.to_owned();
        let resolved =
            resolve(destination).map_err(|e| FolderError::Io(shown.clone(), std::io::Error::other(e)))?;
        let parent = folder_of(&resolved);
        if !parent.exists() {
            return Err(FolderError::NoParent(shown, parent.to_owned()));
        }
        if !parent.is_dir() {
            return Err(FolderError::ParentNotFolder(shown, parent.to_owned()));
        }
        let earlier = match std::fs::symlink_metadata(&resolved) {
            Err(_) => None,
            Ok(m) if !m.is_dir() => return Err(FolderError::NotFolder(shown)),
            Ok(_) => Some(earlier_files(&resolved).map_err(|e| match e {
                Some(e) => FolderError::Io(shown.clone(), e),
                None => FolderError::Foreign(shown.clone()),
            })?),
        };
        if earlier.is_some() {
            // Files will be moved in: the folder itself must take them.
            tempfile::Builder::new()
                .suffix(STAGING_SUFFIX)
                .tempfile_in(&resolved)
                .map_err(|e| FolderError::NotWritable(shown.clone(), e))?;
        }
        let name = resolved
            .file_name()
            .map_or("report".into(), |n| n.to_string_lossy());
        let staging = tempfile::Builder::new()
            .prefix(&format!(".{name}."))
            .suffix(STAGING_SUFFIX)
            // Given to mkdir(2), so the umask applies, as for any new folder.
            .permissions(std::fs::Permissions::from_mode(0o777))
            .tempdir_in(parent)
            .map_err(|e| FolderError::NotWritable(shown, e))?;
        Ok(Self {
            staging,
            destination: resolved,
            earlier,
        })
    }

    /// Where the report's files are written first.
    pub fn staging(&self) -> &Path {
        self.staging.path()
    }

    /// Puts the staged report in place. Not interruptible: it is a few
    /// renames, and stopping half-way would mix two reports.
    pub fn commit(self) -> Result<(), FolderError> {
        let io = |e: std::io::Error| FolderError::Io(self.destination.clone(), e);
        let written = files_under(self.staging.path()).map_err(io)?;
        let Some(earlier) = &self.earlier else {
            write_marker(self.staging.path(), &written).map_err(io)?;
            let staged = self.staging.keep();
            return std::fs::rename(&staged, &self.destination).map_err(|e| {
                let _ = std::fs::remove_dir_all(&staged);
                io(e)
            });
        };
        // The marker first names both reports' files, so that a crash half-way
        // leaves every file of ours recognised as ours.
        let mut both = earlier.clone();
        both.extend(written.iter().filter(|f| !earlier.contains(f)).cloned());
        write_marker(&self.destination, &both).map_err(io)?;
        for file in &written {
            let to = self.destination.join(file);
            std::fs::create_dir_all(folder_of(&to)).map_err(io)?;
            std::fs::rename(self.staging.path().join(file), &to).map_err(io)?;
        }
        for file in earlier.iter().filter(|f| !written.contains(f)) {
            let path = self.destination.join(file);
            if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
                std::fs::remove_file(&path).map_err(io)?;
                // Folders the report made go when empty; remove_dir keeps any other.
                for folder in path.ancestors().skip(1).take_while(|a| *a != self.destination) {
                    if std::fs::remove_dir(folder).is_err() {
                        break;
                    }
                }
            }
        }
        write_marker(&self.destination, &written).map_err(io)
    }
}

/// The files an earlier report listed in its marker; `Err(None)` when the
/// folder is neither empty nor marked.
fn earlier_files(folder: &Path) -> Result<Vec<PathBuf>, Option<std::io::Error>> {
    let marker = folder.join(MARKER);
    if !std::fs::symlink_metadata(&marker).is_ok_and(|m| m.is_file()) {
        let empty = std::fs::read_dir(folder).map_err(Some)?.next().is_none();
        return if empty { Ok(Vec::new()) } else { Err(None) };
    }
    let text = crate::input::read_text_bounded(&marker, 1 << 20, "a report marker").map_err(Some)?;
    Ok(text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(PathBuf::from)
        // Only plain relative paths: a marker cannot point outside its folder.
        .filter(|p| p.components().all(|c| matches!(c, Component::Normal(_))))
        .collect())
}

fn write_marker(folder: &Path, files: &[PathBuf]) -> std::io::Result<()> {
    let mut text = format!("{MARKER_HEADER}\n");
    for file in files {
        text += &format!("{}\n", file.display());
    }
    crate::output::write_atomically_to_finish(&folder.join(MARKER), text.as_bytes())
}

/// Every regular file under `root`, as paths relative to it, sorted.
fn files_under(root: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    let mut folders = vec![PathBuf::new()];
    while let Some(relative) = folders.pop() {
        for entry in std::fs::read_dir(root.join(&relative))? {
            let entry = entry?;
            let path = relative.join(entry.file_name());
            if entry.file_type()?.is_dir() {
                folders.push(path);
            } else {
                files.push(path);
            }
        }
    }
    files.sort();
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report_into(destination: &Path, files: &[&str]) {
        let folder = ReportFolder::prepare(destination).unwrap();
        for file in files {
            let path = folder.staging().join(file);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, "new").unwrap();
        }
        folder.commit().unwrap();
    }

    #[test]
    fn a_new_folder_gets_the_report_and_its_marker() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("r");
        report_into(&out, &["report.csv", "images/a.png"]);
        let marker = std::fs::read_to_string(out.join(MARKER)).unwrap();
        assert!(marker.contains("report.csv\nimages/a.png") || marker.contains("images/a.png\nreport.csv"));
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no staging left"
        );
    }

    #[test]
    fn a_second_report_replaces_only_its_own_files() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("r");
        report_into(&out, &["report.csv", "images/old.png"]);
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        std::fs::write(out.join("images/photo.jpg"), "mine").unwrap();
        report_into(&out, &["report.csv", "images/new.png"]);
        assert_eq!(std::fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");
        assert!(out.join("images/photo.jpg").exists() && out.join("images/new.png").exists());
        assert!(!out.join("images/old.png").exists());
    }

    #[test]
    fn a_folder_without_the_marker_is_refused_even_with_a_report_csv() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("report.csv"), "someone's").unwrap();
        assert!(matches!(
            ReportFolder::prepare(dir.path()),
            Err(FolderError::Foreign(_))
        ));
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_marker_cannot_point_outside_its_folder() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("r");
        std::fs::create_dir(&out).unwrap();
        std::fs::write(dir.path().join("precious"), "keep").unwrap();
        std::fs::write(out.join(MARKER), "../precious\n/etc/passwd\nreport.csv\n").unwrap();
        report_into(&out, &["index.html"]);
        assert!(dir.path().join("precious").exists());
    }
}
