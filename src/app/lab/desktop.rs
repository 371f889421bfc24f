//! The desktop around the lab: the window's title, the file dialogs and the
//! error toasts. The dialogs' results are queued as commands like any other.

use super::super::files::FilesPanel;
use super::LabApp;
use crate::app::command::Command;
use crate::i18n::Language;
use crate::tr;
use std::path::Path;

impl LabApp {
    /// `lumlab — <scene name>`, with ` •` while the settings differ from the
    /// file they were last loaded from or saved to.
    pub fn title(&self) -> String {
        let changed = self.saved.as_ref().is_some_and(|s| *s != self.state.settings);
        let mark = if changed { " •" } else { "" };
        format!("lumlab — {}{mark}", self.shown.name())
    }

    /// The error messages shown as toasts, oldest first.
    pub fn toasts(&self) -> &[String] {
        self.toasts.messages()
    }

    /// A file dialog (or its "Replace?" question) is showing.
    pub fn file_dialog_open(&self) -> bool {
        self.files.dialog_open()
    }

    /// The dialogs, the toasts and the window's title, once a frame.
    pub(super) fn desktop(&mut self, ctx: &egui::Context) {
        if let Some(command) = self.files.show_dialogs(ctx, &mut self.state.paths.last_folder) {
            self.emit(command);
        }
        self.toasts.show(ctx);
        let title = self.title();
        if self.title_sent.as_ref() != Some(&title) {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title_sent = Some(title);
        }
    }

    /// The File menu in the top bar.
    pub(super) fn file_menu(&mut self, ui: &mut egui::Ui) {
        ui.menu_button(tr!("menu-file"), |ui| {
            if let Some(command) = FilesPanel::menu(ui, &self.state.recent) {
                self.emit(command);
            }
        });
    }

    /// The Language menu in the top bar: each language by its own name.
    pub(super) fn language_menu(&mut self, ui: &mut egui::Ui) {
        let current = crate::i18n::current();
        ui.menu_button(format!("{} ({})", tr!("menu-language"), current.code()), |ui| {
            for language in Language::ALL {
                if ui.radio(language == current, language.native_name()).clicked() {
                    self.emit(Command::SetLanguage(language));
                    ui.close();
                }
            }
        })
        .response
        .on_hover_text(tr!("menu-language-tip"));
    }

    /// The settings now match the file at `path` (just loaded or saved).
    pub(super) fn settings_match_file(&mut self, path: &Path) {
        self.saved = Some(self.state.settings.clone());
        self.state.recent.add_settings(path);
    }
}

/// A failure on `path` as one line that names the file and the reason.
pub(super) fn file_error(path: &Path, reason: impl std::fmt::Display) -> String {
    let reason = reason.to_string();
    let shown = path.display().to_string();
    if reason.contains(&shown) {
        reason
    } else {
        format!("'{shown}': {reason}")
    }
}
