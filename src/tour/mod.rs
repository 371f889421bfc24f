//! The lecture as a guided tour: steps in the lecture's order, each a short
//! text with its formula (in French and in English), the settings, camera,
//! view and split it sets, the panel it opens, a number to observe and a
//! question for the class.
//!
//! Steps are data (`assets/tour.toml`, built in; `lumlab --tour FILE` for a
//! teacher's own): a teacher reorders, edits or adds steps without code.
//! Loading checks everything a step could get wrong — unknown keys, wrong
//! types, settings out of range, missing text in either language — and says
//! so in one line naming the step and the key. No GUI here: the app drives
//! the tour with commands (`Command::TourStep`).

mod observe;

pub use observe::{Observe, format_number};

use crate::i18n::Language;
use crate::presets::{Comparison, ComparisonAxis, Preset};
use crate::scene::{Camera, SceneScale};
use crate::settings::Settings;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The tour built into the binary.
pub const BUILT_IN: &str = include_str!("../../assets/tour.toml");
/// The built-in tour's file, relative to the crate root.
pub const ASSET_PATH: &str = "assets/tour.toml";
/// A tour file larger than this is not read (bytes).
const LIMIT_BYTES: u64 = 4 << 20;

/// A tour file that cannot be used: one line naming the file, the step and the key.
#[derive(Debug, Error)]
pub enum TourError {
    #[error("cannot read tour file '{path}': {source}")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("tour file '{path}': {message}")]
    Invalid { path: PathBuf, message: String },
}

named_enum! {
    /// The scene a step shows.
    #[derive(Default)]
    pub enum TourScene {
        /// The lab's built-in scene (shadows, grazing panel, spheres).
        #[default]
        BuiltIn = "built-in",
        /// The lecture's figure: a row of spheres with m from 1 to 1000
        /// (`scene::lecture_scene`).
        Spheres = "spheres",
    }
}

impl TourScene {
    /// The view the scene opens with, where a step's camera starts from.
    pub fn home_camera(self) -> Camera {
        match self {
            Self::BuiltIn => Camera::default(),
            Self::Spheres => crate::scene::lecture_scene::HOME,
        }
    }

    /// Where the light starts from in the scene's steps (m).
    pub fn home_light(self) -> glam::Vec3 {
        match self {
            Self::BuiltIn => crate::settings::LightSettings::DEFAULT_POSITION,
            Self::Spheres => crate::scene::lecture_scene::LIGHT_POSITION,
        }
    }
}

named_enum! {
    /// A panel of the lab a step opens and highlights.
    pub enum Panel {
        Experiments = "experiments",
        Scene = "scene",
        Light = "light",
        Colour = "colour",
        Material = "material",
        Shadow = "shadow",
        View = "view",
        Files = "files",
        Probe = "probe",
        Energy = "energy",
        Reference = "reference",
        Timings = "timings",
    }
}

named_enum! {
    /// How a step shows the split view.
    #[derive(Default)]
    pub enum SplitChoice {
        /// One image.
        #[default]
        Off = "off",
        /// A | B in one image, a divider between.
        Wipe = "wipe",
        /// A and B as two whole images side by side (the lecture's figure).
        SideBySide = "side-by-side",
    }
}

/// A step's words in one language.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepText {
    pub title: String,
    /// A few sentences: what the lecture says here.
    pub text: String,
    /// The step's formula, as plain text.
    pub formula: String,
    /// What to look at, with `{value}` where the live number goes.
    pub observe: String,
    /// A question for the class.
    pub question: String,
}

impl StepText {
    /// The placeholder of the observed number.
    pub const VALUE: &'static str = "{value}";

    /// The observe sentence with the number in place.
    pub fn observe_with(&self, value: &str) -> String {
        self.observe.replace(Self::VALUE, value)
    }

    /// The first missing part, as its key.
    fn missing(&self) -> Option<&'static str> {
        let fields = [
            ("title", &self.title),
            ("text", &self.text),
            ("formula", &self.formula),
            ("observe", &self.observe),
            ("question", &self.question),
        ];
        fields
            .into_iter()
            .find(|(_, v)| v.trim().is_empty())
            .map(|(k, _)| k)
    }
}

/// One step of the tour, checked and ready to apply.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// A short name, unique in the tour (error messages, the step list).
    pub id: String,
    pub scene: TourScene,
    /// The preset the step starts from, if any (its comparison too).
    pub preset: Option<Preset>,
    /// Every setting the step leaves (the image size is the lab's own).
    pub settings: Settings,
    pub split: SplitChoice,
    /// The split view's comparison: the preset's, else the lecture's
    /// figure (without | with normalization); its axis the step's
    /// `compare` when written.
    pub comparison: Comparison,
    /// The panel opened and highlighted.
    pub panel: Panel,
    pub observe: Observe,
    fr: StepText,
    en: StepText,
}

impl Step {
    /// The step's words in `language`.
    pub fn text(&self, language: Language) -> &StepText {
        match language {
            Language::Fr => &self.fr,
            Language::En => &self.en,
        }
    }

    /// The observed number, from `settings` (the step's, or as the teacher
    /// changed them since).
    pub fn observed(&self, settings: &Settings) -> f64 {
        self.observe.value(settings)
    }
}

/// The lecture's steps, in order.
#[derive(Clone, Debug, PartialEq)]
pub struct Tour {
    pub steps: Vec<Step>,
}

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TourFile {
    step: Vec<StepFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StepFile {
    id: String,
    #[serde(default)]
    scene: TourScene,
    #[serde(default)]
    preset: Option<Preset>,
    /// Checked here with the settings file's own rules; applied from the
    /// raw table so that only the keys written override the preset.
    #[serde(default, rename = "settings")]
    _settings: Settings,
    #[serde(default)]
    split: SplitChoice,
    /// The split's axis, over the preset's comparison (or the lecture's
    /// figure's): e.g. "visibility" for shadow map | ray traced.
    #[serde(default)]
    compare: Option<ComparisonAxis>,
    panel: Panel,
    observe: Observe,
    fr: StepText,
    en: StepText,
}

impl Tour {
    /// The tour built into the binary.
    pub fn built_in() -> Result<Self, TourError> {
        Self::parse(BUILT_IN, Path::new(ASSET_PATH))
    }

    /// Reads and checks a tour file.
    pub fn load(path: &Path) -> Result<Self, TourError> {
        let text = crate::input::read_text_bounded(path, LIMIT_BYTES, "a tour file").map_err(|source| {
            TourError::Read {
                path: path.to_owned(),
                source,
            }
        })?;
        Self::parse(&text, path)
    }

    /// Parses and checks the text of a tour file (`path` names it in errors).
    pub fn parse(text: &str, path: &Path) -> Result<Self, TourError> {
        let invalid = |message: String| TourError::Invalid {
            path: path.to_owned(),
            message,
        };
        let file: TourFile = toml::from_str(text).map_err(|e| invalid(describe_error(text, &e)))?;
        let raw: toml::Table = toml::from_str(text).map_err(|e| invalid(e.message().to_string()))?;
        let raw_steps = raw.get("step").and_then(toml::Value::as_array);
        if file.step.is_empty() {
            return Err(invalid("no [[step]]: a tour needs at least one step".into()));
        }
        let mut steps: Vec<Step> = Vec::with_capacity(file.step.len());
        for (i, step) in file.step.into_iter().enumerate() {
            let name = format!("step {} ('{}')", i + 1, step.id);
            if step.id.trim().is_empty() {
                return Err(invalid(format!("step {}: id is empty", i + 1)));
            }
            if let Some(first) = steps.iter().position(|s| s.id == step.id) {
                return Err(invalid(format!(
                    "{name}: id is already used by step {}",
                    first + 1
                )));
            }
            let overrides = raw_steps
                .and_then(|s| s.get(i))
                .and_then(|s| s.get("settings"))
                .and_then(toml::Value::as_table)
                .cloned()
                .unwrap_or_default();
            let settings = step_settings(step.scene, step.preset, &overrides)
                .map_err(|e| invalid(format!("{name}: settings.{e}")))?;
            step.observe
                .check()
                .map_err(|e| invalid(format!("{name}: {e}")))?;
            for (code, text) in [("fr", &step.fr), ("en", &step.en)] {
                if let Some(key) = text.missing() {
                    return Err(invalid(format!("{name}: {code}.{key} is empty")));
                }
                if !text.observe.contains(StepText::VALUE) {
                    return Err(invalid(format!(
                        "{name}: {code}.observe has no {} where the number goes",
                        StepText::VALUE
                    )));
                }
            }
            steps.push(Step {
                comparison: comparison(step.preset, step.compare),
                id: step.id,
                scene: step.scene,
                preset: step.preset,
                settings,
                split: step.split,
                panel: step.panel,
                observe: step.observe,
                fr: step.fr,
                en: step.en,
            });
        }
        Ok(Self { steps })
    }
}

/// A step's comparison: the preset's, else the lecture's figure (without |
/// with normalization), on the axis the step names if it names one.
fn comparison(preset: Option<Preset>, axis: Option<ComparisonAxis>) -> Comparison {
    let base = preset.and_then(Preset::comparison).unwrap_or_default();
    Comparison {
        axis: axis.unwrap_or(base.axis),
        ..base
    }
}

/// The settings of a step: the defaults seen from the scene's home view
/// and lit from its home light,
/// then the preset, then the keys the step writes. The error is
/// "key…: problem" (the caller prefixes `settings.`).
fn step_settings(
    scene: TourScene,
    preset: Option<Preset>,
    overrides: &toml::Table,
) -> Result<Settings, String> {
    if overrides.contains_key("scene") {
        return Err("scene: a step shows the built-in scene or the spheres (scene = \"built-in\" | \"spheres\" beside settings)".into());
    }
    let mut settings = Settings {
        camera: scene.home_camera(),
        ..Settings::default()
    };
    settings.light.position = scene.home_light();
    if let Some(preset) = preset {
        preset.apply(&mut settings, SceneScale::BUILT_IN);
    }
    let mut table = toml::Table::try_from(&settings).map_err(|e| e.to_string())?;
    merge(&mut table, overrides);
    let settings: Settings = table
        .try_into()
        .map_err(|e: toml::de::Error| e.message().to_string())?;
    settings.validate().map_err(|e| {
        // "material.k = 1.5 is out of range …": the key first, as elsewhere.
        e.to_string()
    })?;
    Ok(settings)
}

/// `from`'s keys written over `into`'s, tables merged key by key.
fn merge(into: &mut toml::Table, from: &toml::Table) {
    for (key, value) in from {
        match (into.get_mut(key), value) {
            (Some(toml::Value::Table(a)), toml::Value::Table(b)) => merge(a, b),
            _ => {
                into.insert(key.clone(), value.clone());
            }
        }
    }
}

/// A parse error in one line: the step it is in (number and id), then the
/// line and key path, then what is wrong.
fn describe_error(text: &str, error: &toml::de::Error) -> String {
    let detail = crate::settings::describe_toml_error(text, error);
    let Some(span) = error.span() else {
        return detail;
    };
    let before = &text[..span.start.min(text.len())];
    // Where each step's table begins: a `[[step]]` line (not a comment).
    let starts: Vec<usize> = text
        .match_indices("[[step]]")
        .map(|(at, _)| at)
        .filter(|&at| text[..at].ends_with('\n') || at == 0)
        .collect();
    let headers: Vec<usize> = starts.iter().copied().filter(|&at| at < before.len()).collect();
    let Some(&start) = headers.last() else {
        return detail;
    };
    let end = starts.get(headers.len()).copied().unwrap_or(text.len());
    let id = text[start..end].lines().find_map(|line| {
        let (key, value) = line.split_once('=')?;
        (key.trim() == "id").then(|| value.trim().trim_matches('"').to_string())
    });
    match id {
        Some(id) => format!("step {} ('{id}'), {detail}", headers.len()),
        None => format!("step {}, {detail}", headers.len()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Tour, String> {
        Tour::parse(text, Path::new("t.toml")).map_err(|e| e.to_string())
    }

    const STEP: &str = r#"
[[step]]
id = "one"
panel = "light"
observe = { quantity = "intensity" }
[step.fr]
title = "Flux"
text = "Le flux."
formula = "I = Φ / 4π"
observe = "I = {value}"
question = "Pourquoi ?"
[step.en]
title = "Flux"
text = "The flux."
formula = "I = Φ / 4π"
observe = "I = {value}"
question = "Why?"
"#;

    #[test]
    fn the_built_in_tour_loads() {
        let tour = Tour::built_in().unwrap();
        assert!(tour.steps.len() >= 16, "{}", tour.steps.len());
    }

    #[test]
    fn a_minimal_step_has_the_default_settings() {
        let tour = parse(STEP).unwrap();
        assert_eq!(tour.steps[0].settings, Settings::default());
        assert_eq!(tour.steps[0].text(Language::Fr).title, "Flux");
    }

    #[test]
    fn settings_override_the_preset_key_by_key() {
        let text = STEP.replace(
            "panel = \"light\"",
            "panel = \"shadow\"\npreset = \"aliasing\"\nsettings = { shadow = { filter = \"pcf\" } }",
        );
        let step = &parse(&text).unwrap().steps[0];
        assert_eq!(step.settings.shadow.resolution, 256, "from the preset");
        assert_eq!(step.settings.shadow.filter, crate::settings::Filter::Pcf);
        assert_eq!(step.comparison.axis, crate::presets::ComparisonAxis::Resolution);
    }
}
