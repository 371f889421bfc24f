//! The files panel: settings files (the same TOML as `--settings`), scenes
//! (glTF/GLB, also by drag and drop), screenshots (PNG) and the linear
//! radiance (EXR). egui has no native dialog; a path field and a small
//! directory browser stand in for one.

use super::command::Command;
use super::state::Paths;
use std::path::{Path, PathBuf};

/// Which path field the browser fills.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Field {
    Settings,
    Scene,
    Screenshot,
    Exr,
}

impl Field {
    fn extensions(self) -> &'static [&'static str] {
        match self {
            Self::Settings => &["toml"],
            Self::Scene => &["gltf", "glb"],
            Self::Screenshot => &["png"],
            Self::Exr => &["exr"],
        }
    }

    fn path(self, paths: &mut Paths) -> &mut String {
        match self {
            Self::Settings => &mut paths.settings_file,
            Self::Scene => &mut paths.scene_file,
            Self::Screenshot => &mut paths.screenshot_file,
            Self::Exr => &mut paths.exr_file,
        }
    }
}

/// A directory listing to pick a file from.
struct Browser {
    field: Field,
    dir: PathBuf,
    entries: Vec<(String, bool)>,
    error: Option<String>,
}

impl Browser {
    fn open(field: Field, current: &str) -> Self {
        let start = Path::new(current)
            .parent()
            .filter(|p| p.is_dir())
            .map(Path::to_path_buf)
            .or_else(|| std::env::current_dir().ok())
            .unwrap_or_else(|| PathBuf::from("."));
        let mut browser = Self {
            field,
            dir: start,
            entries: Vec::new(),
            error: None,
        };
        browser.list();
        browser
    }

    /// Sub-directories, then the files with the field's extensions.
    fn list(&mut self) {
        self.entries.clear();
        self.error = None;
        let read = match std::fs::read_dir(&self.dir) {
            Ok(read) => read,
            Err(e) => {
                self.error = Some(format!("cannot list '{}': {e}", self.dir.display()));
                return;
            }
        };
        let extensions = self.field.extensions();
        for entry in read.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') {
                continue;
            }
            let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
            let matches = Path::new(&name)
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| extensions.contains(&e.to_ascii_lowercase().as_str()));
            if is_dir || matches {
                self.entries.push((name, is_dir));
            }
        }
        self.entries.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    }

    /// Shows the window; Some(path) when a file was picked, and whether it stays open.
    fn ui(&mut self, ctx: &egui::Context) -> (Option<PathBuf>, bool) {
        let mut open = true;
        let mut picked = None;
        let mut go_to = None;
        egui::Window::new(format!("Choose a .{} file", self.field.extensions().join(" / .")))
            .open(&mut open)
            .default_size([520.0, 420.0])
            .collapsible(false)
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    if ui.button("Up").on_hover_text("Parent directory").clicked() {
                        go_to = self.dir.parent().map(Path::to_path_buf);
                    }
                    ui.label(self.dir.display().to_string());
                });
                if let Some(e) = &self.error {
                    ui.label(egui::RichText::new(e).color(ui.visuals().warn_fg_color));
                }
                egui::ScrollArea::vertical().max_height(340.0).show(ui, |ui| {
                    for (name, is_dir) in &self.entries {
                        let text = if *is_dir { format!("{name}/") } else { name.clone() };
                        if ui
                            .selectable_label(false, text)
                            .on_hover_text(name.as_str())
                            .clicked()
                        {
                            let path = self.dir.join(name);
                            if *is_dir {
                                go_to = Some(path);
                            } else {
                                picked = Some(path);
                            }
                        }
                    }
                    if self.entries.is_empty() && self.error.is_none() {
                        ui.label("(no matching files here)");
                    }
                });
            });
        if let Some(dir) = go_to {
            self.dir = dir;
            self.list();
        }
        (picked.clone(), open && picked.is_none())
    }
}

#[derive(Default)]
pub struct FilesPanel {
    browser: Option<Browser>,
}

impl FilesPanel {
    fn path_row(&mut self, ui: &mut egui::Ui, paths: &mut Paths, field: Field, label: &str, help: &str) {
        ui.horizontal(|ui| {
            ui.label(label).on_hover_text(help);
            let width = (ui.available_width() - 90.0).max(80.0);
            ui.add(egui::TextEdit::singleline(field.path(paths)).desired_width(width))
                .on_hover_text(help);
            if ui
                .button("Browse…")
                .on_hover_text("Pick a file in a directory listing")
                .clicked()
            {
                self.browser = Some(Browser::open(field, field.path(paths)));
            }
        });
    }

    /// The panel; returns the command its buttons emit.
    pub fn ui(&mut self, ui: &mut egui::Ui, paths: &mut Paths, scene_name: &str) -> Option<Command> {
        let mut action = None;
        let path = |p: &str| Some(PathBuf::from(p.trim()));

        ui.label(egui::RichText::new(format!("Scene: {scene_name}")).strong());
        self.path_row(
            ui,
            paths,
            Field::Scene,
            "glTF",
            "A .gltf or .glb file (or drop one on the window)",
        );
        ui.horizontal(|ui| {
            if ui
                .button("Open scene")
                .on_hover_text("Load the glTF/GLB file above (Ctrl+O)")
                .clicked()
            {
                action = Some(Command::OpenScene(path(&paths.scene_file)));
            }
            if ui
                .button("Built-in scene")
                .on_hover_text("Back to the lab's own scene")
                .clicked()
            {
                action = Some(Command::BuiltInScene);
            }
        });
        ui.separator();

        self.path_row(
            ui,
            paths,
            Field::Settings,
            "Settings",
            "A TOML settings file, the same as `lumlab render --settings FILE`",
        );
        ui.horizontal(|ui| {
            if ui
                .button("Save (Ctrl+S)")
                .on_hover_text("Write every setting to the file")
                .clicked()
            {
                action = Some(Command::SaveSettings(path(&paths.settings_file)));
            }
            if ui
                .button("Load")
                .on_hover_text("Read the settings from the file (undo with Ctrl+Z)")
                .clicked()
            {
                action = Some(Command::LoadSettings(path(&paths.settings_file)));
            }
        });
        ui.separator();

        self.path_row(
            ui,
            paths,
            Field::Screenshot,
            "PNG",
            "Screenshot of the whole window",
        );
        if ui
            .button("Save screenshot (F12)")
            .on_hover_text("The whole window, as displayed")
            .clicked()
        {
            action = Some(Command::Screenshot(path(&paths.screenshot_file)));
        }
        self.path_row(
            ui,
            paths,
            Field::Exr,
            "EXR",
            "Linear 32-bit values of half A's view: radiance L (W/m²/sr) for `shaded`",
        );
        if ui
            .button("Export EXR")
            .on_hover_text("Unscaled linear values, no exposure, no sRGB")
            .clicked()
        {
            action = Some(Command::ExportExr(path(&paths.exr_file)));
        }
        ui.separator();
        if ui
            .button("Reset everything")
            .on_hover_text("Every setting, the split view, the panels and the scene back to their defaults (Ctrl+Z undoes the settings)")
            .clicked()
        {
            action = Some(Command::ResetEverything);
        }

        if let Some(browser) = &mut self.browser {
            let (picked, keep) = browser.ui(ui.ctx());
            if let Some(p) = picked {
                *browser.field.path(paths) = p.display().to_string();
            }
            if !keep {
                self.browser = None;
            }
        }
        action
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_browser_lists_directories_and_matching_files() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        for name in ["a.glb", "b.GLTF", "c.txt", ".hidden.glb"] {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        let current = dir.path().join("x.glb").display().to_string();
        let browser = Browser::open(Field::Scene, &current);
        let names: Vec<&str> = browser.entries.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["sub", "a.glb", "b.GLTF"]);
    }
}
