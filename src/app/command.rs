//! The app's actions as data. Panels, keyboard shortcuts, drag and drop, the
//! scripted `--screenshot` run and the tests all *emit* a [`Command`]; one
//! place (`LabApp::apply`, in `apply.rs`) carries it out and records undo.
//! A new action is a new variant here, its handling in `apply.rs`, and, if
//! it has a key, a row in `shortcuts.rs`.

use super::files::FileAction;
use super::state::{PanelState, SplitState};
use crate::i18n::Language;
use crate::presets::Preset;
use crate::scene::framing::frame_all;
use crate::scene::{Aabb, Camera, SceneScale};
use crate::settings::{DebugView, Settings};
use glam::Vec3;
use std::path::PathBuf;

/// One thing the user (or a script) asks of the lab.
///
/// Paths are optional where a shortcut has none to give: `None` means the
/// file of that kind used last (shown in the Files panel).
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Replaces the settings: a panel's edit or a drag in the viewport.
    /// Continuous edits become one undo step once the pointer is released
    /// and the settings stay quiet (see `undo.rs`).
    SetSettings(Box<Settings>),
    /// Replaces the split view's state (on/off, comparison, wipe).
    SetSplit(SplitState),
    /// Shows or hides the side panels.
    SetPanels(PanelState),
    /// Sets a preset experiment's values: one undo step.
    ApplyPreset(Preset),
    /// Shows a debug view: one undo step.
    ShowView(DebugView),
    /// The next (+1) or previous (−1) debug view: one undo step.
    StepView(i8),
    /// The camera back to the scene's own view: one undo step.
    ResetView,
    /// The camera moved along its direction until the model fills the view.
    FrameAll,
    /// The camera of the scene file with this index (`--camera gltf:N`).
    UseSceneCamera(usize),
    /// The orbit turns around this point from now on (a double-click).
    SetPivot(Vec3),
    /// The exposure set from the image: a high percentile of the lit
    /// pixels' luminance is shown near white.
    AutoExposure,
    Undo,
    Redo,
    /// Shows the file dialog; the file chosen becomes the action's command
    /// (e.g. `OpenScene(Some(path))`, as a dropped file does).
    ChooseFile(FileAction),
    /// Loads a glTF/GLB on a thread; the current scene stays until it succeeds.
    OpenScene(Option<PathBuf>),
    /// Back to the built-in scene.
    BuiltInScene,
    LoadSettings(Option<PathBuf>),
    SaveSettings(Option<PathBuf>),
    /// A PNG of the whole window.
    Screenshot(Option<PathBuf>),
    /// The linear radiance of half A as EXR.
    ExportExr(Option<PathBuf>),
    /// Renders the CPU reference of half A on a thread.
    StartReference,
    /// Esc: cancels the reference if it runs, else closes the help.
    Cancel,
    ToggleSplit,
    ToggleHelp,
    /// Hides both side panels, or shows both.
    TogglePanels,
    /// Default settings, split and panels, the built-in scene (paths and
    /// language kept).
    ResetEverything,
    /// Goes to step i of the lecture tour: its scene, and its settings,
    /// camera and view as one undo step; its split view; its panel opened
    /// and highlighted.
    TourStep(usize),
    /// Shows the app's text in this language from the next frame on (persisted).
    SetLanguage(Language),
}

/// What a command needs to know of the scene shown.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneView {
    /// The scene's own view, where Reset view goes.
    pub home: Camera,
    /// How the lab's lengths map onto the scene.
    pub scale: SceneScale,
    /// The model's bounds (without an added ground), for Frame all.
    pub bounds: Aabb,
    /// The cameras the scene file defines.
    pub cameras: Vec<Camera>,
}

impl Command {
    /// The settings a command leaves, or None when it does more than change
    /// the settings. Pure, so that the tour and the tests can predict a
    /// command's effect.
    pub fn settings_after(&self, settings: &Settings, scene: &SceneView) -> Option<Settings> {
        let mut s = settings.clone();
        match self {
            Self::SetSettings(new) => return Some((**new).clone()),
            Self::ApplyPreset(preset) => {
                // On the built-in scene, presets start from its own view
                // (their light positions are tuned for it).
                if s.scene.is_none() {
                    s.camera = scene.home;
                }
                preset.apply(&mut s, scene.scale);
            }
            Self::ShowView(view) => s.view.mode = *view,
            Self::StepView(step) => {
                let all = DebugView::ALL;
                let i = all.iter().position(|v| *v == s.view.mode).unwrap_or(0) as i64;
                let n = all.len() as i64;
                s.view.mode = all[(i + *step as i64).rem_euclid(n) as usize];
            }
            Self::ResetView => s.camera = scene.home,
            Self::FrameAll => s.camera = frame_all(&s.camera, &scene.bounds),
            Self::UseSceneCamera(i) => s.camera = *scene.cameras.get(*i)?,
            Self::SetPivot(p) => {
                // Keep the eye; a pivot on the eye would leave no direction.
                if p.distance(s.camera.eye) > 1e-6 * (1.0 + p.length()) {
                    s.camera.target = *p;
                }
            }
            _ => return None,
        }
        Some(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn built_in() -> SceneView {
        SceneView {
            home: Camera::default(),
            scale: SceneScale::BUILT_IN,
            bounds: crate::scene::default_scene().model_bounds(),
            cameras: vec![Camera::default()],
        }
    }

    #[test]
    fn stepping_views_wraps_both_ways() {
        let s = Settings::default();
        let last = *DebugView::ALL.last().unwrap();
        let back = Command::StepView(-1).settings_after(&s, &built_in()).unwrap();
        assert_eq!(back.view.mode, last);
        let forth = Command::StepView(1).settings_after(&back, &built_in()).unwrap();
        assert_eq!(forth.view.mode, s.view.mode);
    }

    #[test]
    fn reset_view_restores_the_scenes_camera_only() {
        let mut s = Settings::default();
        s.camera.eye.x += 3.0;
        s.light.power_w = 7.0;
        let after = Command::ResetView.settings_after(&s, &built_in()).unwrap();
        assert_eq!(after.camera, Camera::default());
        assert_eq!(after.light.power_w, 7.0);
    }
}
