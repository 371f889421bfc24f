//! What the app remembers between runs (eframe storage), apart from every
//! GPU object: the settings, the split comparison, panel visibility and
//! the paths last used, the folder the file dialog was last in, the
//! recent files and the language picked. Unknown or invalid stored state falls back to the
//! defaults.

use super::recent::RecentFiles;
use crate::i18n::Language;
use crate::presets::Comparison;
use crate::settings::Settings;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The key under which the state is stored.
pub const STORAGE_KEY: &str = "lumlab.state";

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct State {
    pub settings: Settings,
    pub split: SplitState,
    pub panels: PanelState,
    pub paths: Paths,
    pub recent: RecentFiles,
    /// The language picked in the Language menu (None: the system's).
    pub language: Option<Language>,
}

/// How the split view shows A and B.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum SplitLayout {
    /// One image, A left of a divider the user drags, B right of it.
    #[default]
    Wipe,
    /// Two whole images of the same view side by side, cameras linked: the
    /// lecture's figure ("left: without normalization, right: with").
    SideBySide,
}

/// The split view: B differs from A by the comparison's setting.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SplitState {
    pub enabled: bool,
    pub comparison: Comparison,
    /// Where A ends and B begins, as a fraction of the image width.
    pub wipe: f32,
    pub layout: SplitLayout,
}

impl Default for SplitState {
    fn default() -> Self {
        Self {
            enabled: false,
            comparison: Comparison::default(),
            wipe: 0.5,
            layout: SplitLayout::Wipe,
        }
    }
}

/// Which panels are shown.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PanelState {
    /// The settings panel on the left.
    pub settings: bool,
    /// The analysis panel on the right (probe, energy, reference, timings).
    pub analysis: bool,
    /// The Lecture panel (the guided tour) under the image.
    pub lecture: bool,
}

impl Default for PanelState {
    fn default() -> Self {
        Self {
            settings: true,
            analysis: true,
            lecture: false,
        }
    }
}

/// The file of each kind used last (the Files panel's quick actions work
/// on them) and the folder the file dialog was last in.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Paths {
    pub settings_file: String,
    pub scene_file: String,
    pub screenshot_file: String,
    pub exr_file: String,
    /// Where the next file dialog starts (None: the working directory).
    pub last_folder: Option<PathBuf>,
}

impl Default for Paths {
    fn default() -> Self {
        Self {
            settings_file: "lumlab-settings.toml".into(),
            scene_file: String::new(),
            screenshot_file: "lumlab-screenshot.png".into(),
            exr_file: "lumlab-radiance.exr".into(),
            last_folder: None,
        }
    }
}

impl State {
    /// The stored state, when it parses and its settings are valid.
    pub fn restore(storage: Option<&dyn eframe::Storage>) -> Option<Self> {
        let state: Self = eframe::get_value(storage?, STORAGE_KEY)?;
        state.settings.validate().ok()?;
        Some(state)
    }

    pub fn store(&self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, STORAGE_KEY, self);
    }
}

/// eframe's storage kept in memory: what a test stores the state in to
/// restore it as the next start would.
#[derive(Default)]
pub struct MemoryStorage(std::collections::HashMap<String, String>);

impl eframe::Storage for MemoryStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.into(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn state_round_trips() {
        let mut state = State::default();
        state.settings.light.power_w = 42.0;
        state.split.enabled = true;
        state.language = Some(Language::Fr);
        let text = serde_json::to_string(&state).unwrap();
        let back: State = serde_json::from_str(&text).unwrap();
        assert_eq!(back, state);
    }

    #[test]
    fn state_stored_before_recent_files_and_folders_still_loads() {
        let old = r#"{"settings":{},"paths":{"settings_file":"a.toml","scene_file":"b.glb"}}"#;
        let state: State = serde_json::from_str(old).unwrap();
        assert_eq!(state.paths.settings_file, "a.toml");
        assert_eq!(state.paths.last_folder, None);
        assert_eq!(state.recent, RecentFiles::default());
        assert_eq!(state.language, None);
    }

    #[test]
    fn invalid_stored_settings_are_dropped() {
        use eframe::Storage;
        let mut mem = MemoryStorage::default();
        let mut state = State::default();
        state.settings.light.power_w = 7.0;
        state.store(&mut mem);
        assert_eq!(State::restore(Some(&mem)).unwrap().settings.light.power_w, 7.0);
        state.settings.material.k = 3.0;
        state.store(&mut mem);
        assert!(State::restore(Some(&mem)).is_none());
        mem.set_string(STORAGE_KEY, "garbage".into());
        assert!(State::restore(Some(&mem)).is_none());
    }
}
