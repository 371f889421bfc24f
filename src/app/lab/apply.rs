//! The one place where commands change the app: settings (with undo),
//! scenes, files, the reference job, the split view and the panels.

use super::super::command::Command;
use super::super::files::FileAction;
use super::super::names::preset_title;
use super::super::state::State;
use super::super::viewport::Viewport;
use super::desktop::file_error;
use super::{LabApp, ShownScene, adopt_scene, chosen};
use crate::presets::Half;
use crate::scene::Scene;
use crate::scene::framing::with_ground;
use crate::settings::Settings;
use crate::tr;
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl LabApp {
    /// Carries out `command`.
    pub(super) fn apply(&mut self, command: Command, ctx: &egui::Context) {
        ctx.request_repaint();
        match command {
            Command::SetSettings(_)
            | Command::ApplyPreset(_)
            | Command::ShowView(_)
            | Command::StepView(_)
            | Command::ResetView
            | Command::FrameAll
            | Command::UseSceneCamera(_)
            | Command::SetPivot(_) => {
                let scene = self.scene_view();
                if let Some(after) = command.settings_after(&self.state.settings, &scene) {
                    self.change_settings(&command, after);
                }
            }
            Command::SetSplit(split) => self.state.split = split,
            Command::SetPanels(panels) => self.state.panels = panels,
            Command::Undo => {
                self.undo.undo(&mut self.state.settings);
            }
            Command::Redo => {
                self.undo.redo(&mut self.state.settings);
            }
            Command::ChooseFile(action) => self.files.choose(action, &self.state.paths),
            Command::OpenScene(path) => {
                let path = chosen(path, &mut self.state.paths.scene_file);
                if path.as_os_str().is_empty() {
                    // No scene file used yet: ask for one.
                    self.files.choose(FileAction::OpenScene, &self.state.paths);
                } else {
                    self.open_scene(path, ctx);
                }
            }
            Command::BuiltInScene => self.use_scene(None, crate::scene::default_scene()),
            Command::LoadSettings(path) => {
                let path = chosen(path, &mut self.state.paths.settings_file);
                self.load_settings(&path, ctx);
            }
            Command::SaveSettings(path) => {
                let path = chosen(path, &mut self.state.paths.settings_file);
                match self.state.settings.save(&path) {
                    Ok(()) => {
                        self.settings_match_file(&path);
                        let path = path.display().to_string();
                        self.say(tr!("status-settings-saved", path = path), false);
                    }
                    Err(e) => self.say(file_error(&path, e), true),
                }
            }
            Command::Screenshot(path) => {
                let path = chosen(path, &mut self.state.paths.screenshot_file);
                self.jobs.request_screenshot(path, ctx);
            }
            Command::ExportExr(path) => {
                let path = chosen(path, &mut self.state.paths.exr_file);
                match self.export_exr(&path) {
                    Ok(()) => {
                        let path = path.display().to_string();
                        self.say(tr!("status-exr-written", path = path), false)
                    }
                    Err(e) => self.say(file_error(&path, crate::cli::one_line(&e)), true),
                }
            }
            Command::AutoExposure => self.start_auto_exposure(),
            Command::StartReference => {
                if !self.reference.is_running() {
                    self.start_reference(ctx);
                }
            }
            Command::Cancel => {
                if self.reference.is_running() {
                    self.reference.cancel();
                } else {
                    self.help_open = false;
                }
            }
            Command::ToggleSplit => self.state.split.enabled = !self.state.split.enabled,
            Command::ToggleHelp => self.help_open = !self.help_open,
            Command::SetLanguage(language) => {
                self.state.language = Some(language);
                crate::i18n::set_current(language);
            }
            Command::TogglePanels => {
                let show = !(self.state.panels.settings || self.state.panels.analysis);
                self.state.panels.settings = show;
                self.state.panels.analysis = show;
            }
            Command::TourStep(index) => self.go_to_step(index),
            Command::ResetEverything => {
                self.undo.checkpoint(&self.state.settings);
                let paths = self.state.paths.clone();
                let recent = self.state.recent.clone();
                let language = self.state.language;
                self.state = State {
                    paths,
                    recent,
                    language,
                    ..State::default()
                };
                ctx.memory_mut(|m| *m = Default::default());
                self.use_scene(None, crate::scene::default_scene());
                self.undo.checkpoint(&self.state.settings);
                self.say(tr!("status-reset-everything"), false);
            }
        }
    }

    /// A command that only changes the settings. A continuous edit is left
    /// to the undo stack's quiet-time rule (one drag, one step); any other
    /// is one undo step of its own.
    fn change_settings(&mut self, command: &Command, after: Settings) {
        if matches!(command, Command::SetSettings(_)) {
            self.state.settings = after;
        } else {
            self.settings_in_one_step(|s| *s = after);
        }
        if let Command::ApplyPreset(preset) = command {
            // The split view compares without | with the remedy.
            if let Some(comparison) = preset.comparison() {
                self.state.split.comparison = comparison;
            }
            self.say(tr!("status-preset", preset = preset_title(*preset)), false);
        }
    }

    /// Changes the settings by `change` as one undo step of its own (a
    /// pending slider change before it is committed as another).
    pub(super) fn settings_in_one_step(&mut self, change: impl FnOnce(&mut Settings)) {
        self.undo.checkpoint(&self.state.settings);
        change(&mut self.state.settings);
        self.undo.checkpoint(&self.state.settings);
    }

    /// Loads a settings file; on any failure (its scene gone included) the
    /// settings and the scene stay as they were.
    fn load_settings(&mut self, path: &Path, ctx: &egui::Context) {
        let loaded = Settings::load(path)
            .map_err(|e| file_error(path, e))
            .and_then(|s| match &s.scene {
                Some(scene) if !scene.is_file() => Err(file_error(
                    path,
                    tr!(
                        "error-settings-scene-missing",
                        scene = scene.display().to_string()
                    ),
                )),
                _ => Ok(s),
            });
        match loaded {
            Ok(loaded) => {
                let scene_changes = loaded.scene != self.state.settings.scene;
                let scene = loaded.scene.clone();
                self.settings_in_one_step(|s| *s = loaded);
                self.settings_match_file(path);
                let shown = path.display().to_string();
                self.say(tr!("status-settings-loaded", path = shown), false);
                if scene_changes {
                    match scene {
                        Some(p) => self.open_scene(p, ctx),
                        None => self.use_scene(None, crate::scene::default_scene()),
                    }
                }
            }
            Err(e) => self.say(e, true),
        }
    }

    /// Shows `scene` (from `path`; None: built-in) from now on.
    pub(super) fn use_scene(&mut self, path: Option<PathBuf>, scene: Scene) {
        let shown = ShownScene::from_path(path.as_deref());
        let name = shown.name();
        let triangles = scene.triangle_count();
        let mut text = tr!("status-scene", name = name.as_str(), triangles = triangles);
        if !scene.warnings.is_empty() {
            text += &tr!(
                "status-scene-warnings",
                count = scene.warnings.len(),
                warnings = scene.warnings.join("; ")
            );
        }
        self.settings_in_one_step(|s| adopt_scene(s, path.as_deref(), &scene));
        if let Some(path) = &path {
            self.state.recent.add_scene(path);
        }
        self.file_scene = Arc::new(scene);
        self.shown = shown;
        self.redraw_scene();
        self.say(text, false);
    }

    /// Rebuilds the drawn scene when the ground settings changed.
    pub(super) fn sync_ground(&mut self) {
        if self.state.settings.ground != self.ground {
            self.redraw_scene();
        }
    }

    /// The drawn scene made anew from the file's and the ground settings;
    /// what was computed for the old one goes.
    pub(super) fn redraw_scene(&mut self) {
        self.ground = self.state.settings.ground;
        let scene = Arc::new(with_ground((*self.file_scene).clone(), &self.ground));
        if let Some(gpu) = &mut self.gpu {
            gpu.set_scene(&scene);
        }
        self.scene = scene;
        self.tracer = None;
        self.reference.clear();
        self.reference_generation += 1;
        self.probe = Default::default();
        self.jobs.pending_probe = None;
    }

    /// Loads a scene on a thread; the current one stays until it succeeds.
    fn open_scene(&mut self, path: PathBuf, ctx: &egui::Context) {
        match self.jobs.load_scene(path.clone(), ctx) {
            Ok(()) => self.say(tr!("status-loading", path = path.display().to_string()), false),
            Err(e) => {
                let reason = tr!("error-cannot-start-loading", message = e.to_string());
                self.say(file_error(&path, reason), true)
            }
        }
    }

    fn start_reference(&mut self, ctx: &egui::Context) {
        if self.viewport_size.0 == 0 {
            return;
        }
        let settings = Viewport::render_settings(
            &self.state.settings,
            &self.state.split,
            Half::A,
            self.viewport_size,
        );
        self.reference
            .start(Arc::clone(&self.scene), &settings, self.viewport_size, ctx);
    }

    fn export_exr(&self, path: &Path) -> anyhow::Result<()> {
        crate::image_io::ImageFormat::of_path(path)?;
        let half = self
            .gpu
            .as_ref()
            .and_then(|g| g.half(Half::A))
            .filter(|h| h.report.size != (0, 0))
            .ok_or_else(|| anyhow::anyhow!(tr!("error-no-image-to-export")))?;
        let renderer = half.renderer();
        let (w, h) = half.report.size;
        let texels = renderer.read_quantity();
        anyhow::ensure!(
            texels.len() == w as usize * h as usize,
            tr!("error-image-changed-size")
        );
        crate::image_io::write_exr_texels(path, (w, h), &texels)
    }
}
