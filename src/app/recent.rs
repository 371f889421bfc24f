//! The scenes and settings files opened last, newest first, persisted with
//! the rest of the state. A file that has gone since is shown greyed with a
//! note; it is never an error at start-up.

use super::command::Command;
use crate::tr;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RecentFiles {
    /// glTF/GLB files, newest first.
    pub scenes: Vec<PathBuf>,
    /// TOML settings files, newest first.
    pub settings: Vec<PathBuf>,
}

impl RecentFiles {
    /// Entries kept in each list.
    pub const KEPT: usize = 8;

    pub fn add_scene(&mut self, path: &Path) {
        push(&mut self.scenes, path);
    }

    pub fn add_settings(&mut self, path: &Path) {
        push(&mut self.settings, path);
    }

    /// The two lists as menu entries; the command of the one clicked.
    pub fn menu(&self, ui: &mut egui::Ui) -> Option<Command> {
        let scenes = section(ui, &tr!("recent-scenes"), &self.scenes, |p| {
            Command::OpenScene(Some(p))
        });
        let settings = section(ui, &tr!("recent-settings"), &self.settings, |p| {
            Command::LoadSettings(Some(p))
        });
        scenes.or(settings)
    }
}

/// Moves `path` (made absolute, so that it survives a change of directory)
/// to the front of `list`.
fn push(list: &mut Vec<PathBuf>, path: &Path) {
    let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    list.retain(|p| *p != path);
    list.insert(0, path);
    list.truncate(RecentFiles::KEPT);
}

/// What a menu entry says: the file's name, and a note when it is gone.
pub fn entry_text(path: &Path) -> String {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    if path.exists() {
        name
    } else {
        tr!("recent-missing", name = name)
    }
}

fn section(
    ui: &mut egui::Ui,
    title: &str,
    paths: &[PathBuf],
    open: impl Fn(PathBuf) -> Command,
) -> Option<Command> {
    ui.label(egui::RichText::new(title).weak());
    if paths.is_empty() {
        ui.label(egui::RichText::new(tr!("recent-none")).weak().italics());
    }
    let mut chosen = None;
    for path in paths {
        let exists = path.exists();
        let response = ui
            .add_enabled(exists, egui::Button::new(entry_text(path)))
            .on_hover_text(path.display().to_string())
            .on_disabled_hover_text(format!("{}: this file no longer exists", path.display()));
        if response.clicked() {
            chosen = Some(open(path.clone()));
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_newest_comes_first_without_duplicates_and_the_list_is_bounded() {
        let mut recent = RecentFiles::default();
        for i in 0..10 {
            recent.add_scene(Path::new(&format!("/scenes/{i}.glb")));
        }
        recent.add_scene(Path::new("/scenes/5.glb"));
        assert_eq!(recent.scenes.len(), RecentFiles::KEPT);
        assert_eq!(recent.scenes[0], Path::new("/scenes/5.glb"));
        assert_eq!(recent.scenes.iter().filter(|p| p.ends_with("5.glb")).count(), 1);
        assert_eq!(recent.scenes[1], Path::new("/scenes/9.glb"));
    }

    #[test]
    fn a_relative_path_is_kept_absolute() {
        let mut recent = RecentFiles::default();
        recent.add_settings(Path::new("lab.toml"));
        assert!(recent.settings[0].is_absolute());
    }

    #[test]
    fn a_gone_file_is_marked_missing() {
        let dir = tempfile::tempdir().unwrap();
        let here = dir.path().join("here.glb");
        std::fs::write(&here, b"x").unwrap();
        assert_eq!(entry_text(&here), "here.glb");
        assert_eq!(entry_text(&dir.path().join("gone.glb")), "gone.glb (missing)");
    }
}
