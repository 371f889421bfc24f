//! Files: the File menu, the Files panel and the file dialogs. A dialog is
//! `egui_file`'s, drawn by egui itself (so it works on any desktop, under
//! Xvfb and in the UI tests); what it picks becomes the same command a
//! dropped file or a recent entry emits, e.g. `Command::OpenScene(Some(path))`.
//! The Files panel's quick buttons act on the file of each kind used last.

use super::command::Command;
use super::recent::RecentFiles;
use super::state::Paths;
use crate::tr;
use std::path::{Path, PathBuf};

/// What a file dialog is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileAction {
    OpenScene,
    LoadSettings,
    SaveSettings,
    Screenshot,
    ExportExr,
}

impl FileAction {
    /// The kind's extensions, lower case; the first is added to a saved
    /// name that has none.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Self::OpenScene => &["glb", "gltf"],
            Self::LoadSettings | Self::SaveSettings => &["toml"],
            Self::Screenshot => &["png"],
            Self::ExportExr => &["exr"],
        }
    }

    fn title(self) -> String {
        match self {
            Self::OpenScene => tr!("dialog-open-scene"),
            Self::LoadSettings => tr!("dialog-load-settings"),
            Self::SaveSettings => tr!("dialog-save-settings"),
            Self::Screenshot => tr!("dialog-screenshot"),
            Self::ExportExr => tr!("dialog-export-exr"),
        }
    }

    /// The dialog writes a file (and asks before replacing one).
    pub fn saves(self) -> bool {
        matches!(self, Self::SaveSettings | Self::Screenshot | Self::ExportExr)
    }

    /// The command that does the action on `path`.
    pub fn command(self, path: PathBuf) -> Command {
        match self {
            Self::OpenScene => Command::OpenScene(Some(path)),
            Self::LoadSettings => Command::LoadSettings(Some(path)),
            Self::SaveSettings => Command::SaveSettings(Some(path)),
            Self::Screenshot => Command::Screenshot(Some(path)),
            Self::ExportExr => Command::ExportExr(Some(path)),
        }
    }

    /// The file of this kind used last.
    fn last_file(self, paths: &Paths) -> &str {
        match self {
            Self::OpenScene => &paths.scene_file,
            Self::LoadSettings | Self::SaveSettings => &paths.settings_file,
            Self::Screenshot => &paths.screenshot_file,
            Self::ExportExr => &paths.exr_file,
        }
    }

    fn matches(self, name: &str) -> bool {
        Path::new(name)
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| self.extensions().contains(&e.to_ascii_lowercase().as_str()))
    }

    /// `path` with the kind's extension when it has none of them.
    fn with_extension(self, path: PathBuf) -> PathBuf {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        match name {
            Some(n) if !self.matches(&n) => path.with_file_name(format!("{n}.{}", self.extensions()[0])),
            _ => path,
        }
    }
}

/// An open dialog and what its result is for.
struct Dialog {
    action: FileAction,
    dialog: egui_file::FileDialog,
}

/// The file dialog, and the question asked before a save replaces a file.
#[derive(Default)]
pub struct FilesPanel {
    dialog: Option<Dialog>,
    replace: Option<(FileAction, PathBuf)>,
}

impl FilesPanel {
    /// Opens the dialog for `action`, in the folder used last (else the last
    /// file's folder, else the working directory).
    pub fn choose(&mut self, action: FileAction, paths: &Paths) {
        let last_file = Path::new(action.last_file(paths).trim());
        let folder = paths
            .last_folder
            .clone()
            .filter(|d| d.is_dir())
            .or_else(|| last_file.parent().filter(|d| d.is_dir()).map(Path::to_path_buf))
            .or_else(|| std::env::current_dir().ok());
        let mut dialog = if action.saves() {
            let name = last_file.file_name().map(|n| n.to_string_lossy().into_owned());
            egui_file::FileDialog::save_file()
                .default_filename(name.unwrap_or_default())
                .filename_filter(Box::new(|name: &str| !name.trim().is_empty()))
        } else {
            egui_file::FileDialog::open_file()
                .filename_filter(Box::new(move |name: &str| action.matches(name)))
        };
        dialog = dialog
            .title(&action.title())
            .id(Self::dialog_id())
            .show_files_filter(Box::new(move |path: &Path| {
                path.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| action.matches(n))
            }))
            .show_rename(false)
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
            .keep_on_top(true)
            .default_size([620.0, 460.0]);
        if let Some(folder) = folder {
            dialog = dialog.initial_path(folder);
        }
        dialog.open();
        self.replace = None;
        self.dialog = Some(Dialog { action, dialog });
    }

    fn dialog_id() -> egui::Id {
        egui::Id::unique("lumlab file dialog")
    }

    /// Names egui_file's two text fields for screen readers (the crate
    /// leaves them unnamed): the folder above the list, the file name below.
    fn name_text_fields(ctx: &egui::Context) {
        let layer = egui::LayerId::new(egui::Order::Middle, Self::dialog_id());
        let mut fields: Vec<(f32, egui::Id)> = ctx.viewport(|v| {
            v.this_pass
                .widgets
                .get_layer(layer)
                .map(|w| (w.rect.min.y, w.id))
                .collect()
        });
        fields.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut names = ["Folder", "File name"].into_iter();
        for (_, id) in fields {
            let is_text = ctx
                .accesskit_node_builder(id, |n| n.role() == egui::Role::TextInput && n.label().is_none())
                .unwrap_or(false);
            if let Some(name) = is_text.then(|| names.next()).flatten() {
                ctx.accesskit_node_builder(id, |n| n.set_label(name));
            }
        }
    }

    /// Whether a dialog (or its question) is showing.
    pub fn dialog_open(&self) -> bool {
        self.dialog.is_some() || self.replace.is_some()
    }

    /// Shows the dialog and the question; the command of a file chosen.
    /// The dialog's folder is remembered in `last_folder`.
    pub fn show_dialogs(
        &mut self,
        ctx: &egui::Context,
        last_folder: &mut Option<PathBuf>,
    ) -> Option<Command> {
        let mut command = None;
        if let Some(open) = &mut self.dialog {
            open.dialog.show(ctx);
            Self::name_text_fields(ctx);
            match open.dialog.state() {
                egui_file::State::Open => {}
                egui_file::State::Selected => {
                    *last_folder = Some(open.dialog.directory().to_path_buf());
                    let action = open.action;
                    if let Some(path) = open.dialog.path().map(Path::to_path_buf) {
                        let path = if action.saves() {
                            action.with_extension(path)
                        } else {
                            path
                        };
                        if action.saves() && path.exists() {
                            self.replace = Some((action, path));
                        } else {
                            command = Some(action.command(path));
                        }
                    }
                    self.dialog = None;
                }
                egui_file::State::Cancelled | egui_file::State::Closed => {
                    *last_folder = Some(open.dialog.directory().to_path_buf());
                    self.dialog = None;
                }
            }
        }
        command.or_else(|| self.ask_to_replace(ctx))
    }

    /// "Replace it?" before a save overwrites an existing file.
    fn ask_to_replace(&mut self, ctx: &egui::Context) -> Option<Command> {
        let (action, path) = self.replace.clone()?;
        let mut answer = None;
        let modal = egui::Modal::new(egui::Id::unique("lumlab replace file")).show(ctx, |ui| {
            ui.heading(tr!("replace-title"));
            ui.label(tr!("replace-exists", path = path.display().to_string()));
            ui.horizontal(|ui| {
                if ui.button(tr!("replace-replace")).clicked() {
                    answer = Some(true);
                }
                if ui.button(tr!("replace-cancel")).clicked() {
                    answer = Some(false);
                }
            });
        });
        if modal.should_close() && answer.is_none() {
            answer = Some(false);
        }
        let replace = answer?;
        self.replace = None;
        replace.then(|| action.command(path))
    }

    /// The File menu's entries; the command of the one clicked.
    pub fn menu(ui: &mut egui::Ui, recent: &RecentFiles) -> Option<Command> {
        let entries = [
            (
                tr!("files-open-scene-dialog"),
                tr!("files-open-scene-dialog-tip"),
                Command::ChooseFile(FileAction::OpenScene),
            ),
            (
                tr!("files-built-in"),
                tr!("files-built-in-tip"),
                Command::BuiltInScene,
            ),
            (
                tr!("files-load-settings-dialog"),
                tr!("files-load-settings-dialog-tip"),
                Command::ChooseFile(FileAction::LoadSettings),
            ),
            (
                tr!("files-save-settings"),
                tr!("files-save-settings-tip"),
                Command::SaveSettings(None),
            ),
            (
                tr!("files-save-settings-as"),
                tr!("files-save-settings-as-tip"),
                Command::ChooseFile(FileAction::SaveSettings),
            ),
            (
                tr!("files-screenshot-dialog"),
                tr!("files-screenshot-dialog-tip"),
                Command::ChooseFile(FileAction::Screenshot),
            ),
            (
                tr!("files-export-exr-dialog"),
                tr!("files-export-exr-dialog-tip"),
                Command::ChooseFile(FileAction::ExportExr),
            ),
        ];
        let mut chosen = None;
        for (text, help, command) in entries {
            if ui.button(text).on_hover_text(help).clicked() {
                chosen = Some(command);
            }
        }
        ui.separator();
        recent.menu(ui).or(chosen)
    }

    /// The panel: the file of each kind used last, the quick actions on it,
    /// and a dialog to choose another. Each row of buttons is data.
    pub fn ui(&mut self, ui: &mut egui::Ui, paths: &Paths, scene_name: &str) -> Option<Command> {
        let browse = Command::ChooseFile;
        type Row = Vec<(String, String, Command)>;
        let sections: [(String, &str, Vec<Row>); 4] = [
            (
                "glTF".into(),
                &paths.scene_file,
                vec![vec![
                    (
                        tr!("files-browse"),
                        tr!("files-browse-tip"),
                        browse(FileAction::OpenScene),
                    ),
                    (
                        tr!("files-open-scene"),
                        tr!("files-open-scene-tip"),
                        Command::OpenScene(None),
                    ),
                    (
                        tr!("files-built-in"),
                        tr!("files-built-in-tip"),
                        Command::BuiltInScene,
                    ),
                ]],
            ),
            (
                tr!("files-kind-settings"),
                &paths.settings_file,
                vec![
                    vec![
                        (
                            tr!("files-save"),
                            tr!("files-save-tip"),
                            Command::SaveSettings(None),
                        ),
                        (
                            tr!("files-load"),
                            tr!("files-load-tip"),
                            Command::LoadSettings(None),
                        ),
                    ],
                    vec![
                        (
                            tr!("files-save-as"),
                            tr!("files-save-as-tip"),
                            browse(FileAction::SaveSettings),
                        ),
                        (
                            tr!("files-load-dialog"),
                            tr!("files-load-dialog-tip"),
                            browse(FileAction::LoadSettings),
                        ),
                    ],
                ],
            ),
            (
                "PNG".into(),
                &paths.screenshot_file,
                vec![vec![
                    (
                        tr!("files-screenshot"),
                        tr!("files-screenshot-tip"),
                        Command::Screenshot(None),
                    ),
                    (
                        tr!("files-save-as"),
                        tr!("files-screenshot-as-tip"),
                        browse(FileAction::Screenshot),
                    ),
                ]],
            ),
            (
                "EXR".into(),
                &paths.exr_file,
                vec![vec![
                    (
                        tr!("files-export-exr"),
                        tr!("files-export-exr-tip"),
                        Command::ExportExr(None),
                    ),
                    (
                        tr!("files-export-as"),
                        tr!("files-export-as-tip"),
                        browse(FileAction::ExportExr),
                    ),
                ]],
            ),
        ];
        let mut action = None;
        ui.label(egui::RichText::new(tr!("files-scene", name = scene_name)).strong());
        for (kind, path, rows) in sections {
            file_row(ui, &kind, path);
            for row in rows {
                ui.horizontal(|ui| {
                    for (text, help, command) in row {
                        if ui.button(text).on_hover_text(help).clicked() {
                            action = Some(command);
                        }
                    }
                });
            }
            ui.separator();
        }
        if ui
            .button(tr!("files-reset-everything"))
            .on_hover_text(tr!("files-reset-everything-tip"))
            .clicked()
        {
            action = Some(Command::ResetEverything);
        }
        action
    }
}

/// A kind's file used last, shortened to its name (the full path on hover).
fn file_row(ui: &mut egui::Ui, kind: &str, path: &str) {
    let name = Path::new(path)
        .file_name()
        .map_or_else(|| tr!("files-none"), |n| n.to_string_lossy().into_owned());
    ui.horizontal(|ui| {
        ui.label(egui::RichText::new(kind).weak());
        ui.label(name).on_hover_text(path);
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_filter_by_extension_in_any_case() {
        assert!(FileAction::OpenScene.matches("a.GLB"));
        assert!(FileAction::OpenScene.matches("b.gltf"));
        assert!(!FileAction::OpenScene.matches("c.toml"));
        assert!(FileAction::ExportExr.matches("l.exr"));
        assert!(!FileAction::Screenshot.matches("png"));
    }

    #[test]
    fn a_saved_name_gets_its_kinds_extension() {
        let s = FileAction::SaveSettings;
        assert_eq!(s.with_extension("/d/lab".into()), Path::new("/d/lab.toml"));
        assert_eq!(s.with_extension("/d/lab.TOML".into()), Path::new("/d/lab.TOML"));
        assert_eq!(
            FileAction::Screenshot.with_extension("/d/shot.v2".into()),
            Path::new("/d/shot.v2.png")
        );
    }

    #[test]
    fn the_dialog_starts_in_the_folder_used_last() {
        let dir = tempfile::tempdir().unwrap();
        let paths = Paths {
            last_folder: Some(dir.path().to_path_buf()),
            ..Paths::default()
        };
        let mut files = FilesPanel::default();
        files.choose(FileAction::OpenScene, &paths);
        let open = files.dialog.as_ref().unwrap();
        assert_eq!(open.dialog.directory(), dir.path());
        assert!(files.dialog_open());
    }
}
