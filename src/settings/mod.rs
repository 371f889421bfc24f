//! Every user-settable value of the lab, in one struct shared by the app
//! (persisted between runs), the command line (`--settings FILE` and the
//! flags) and the tests. Saved as TOML; loading names the field and the
//! allowed range of any bad value.

use crate::physics::Normalization;
use crate::scene::{Camera, SceneScale};
use glam::Vec3;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

mod colour;
mod shadow;
mod validate;

pub use colour::ColourSettings;
pub use shadow::{BiasMode, BiasSettings, Filter, ShadowSettings, Visibility};

/// The settings file could not be read, parsed, validated or written.
#[derive(Debug, Error)]
pub enum SettingsError {
    #[error("cannot read settings file '{path}': {source}")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("settings file '{path}': {message}")]
    Parse { path: PathBuf, message: String },
    #[error("{field} = {value} is out of range (allowed: {allowed})")]
    OutOfRange {
        field: &'static str,
        value: String,
        allowed: String,
    },
    #[error("cannot write settings file '{path}': {source}")]
    Write { path: PathBuf, source: std::io::Error },
}

/// Everything a picture depends on.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// The glTF/GLB scene; none = the built-in default scene.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene: Option<PathBuf>,
    pub camera: Camera,
    pub image: ImageSettings,
    pub light: LightSettings,
    pub material: MaterialSettings,
    pub shadow: ShadowSettings,
    pub view: ViewSettings,
    pub ground: GroundSettings,
    /// RGB or spectral light (files without it load in RGB mode).
    pub colour: ColourSettings,
}

/// Size of the rendered image (pixels) for the command line and the report.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ImageSettings {
    pub width: u32,
    pub height: u32,
}

impl Default for ImageSettings {
    fn default() -> Self {
        Self {
            width: 960,
            height: 540,
        }
    }
}

/// The light: a point light, or a small sphere light when `radius_m` > 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LightSettings {
    /// Centre of the light (m).
    pub position: Vec3,
    /// Emitted power Φ (W); the intensity is I = Φ / 4π (W/sr).
    pub power_w: f32,
    /// Radius R of the sphere light (m); 0 is a point light.
    pub radius_m: f32,
    /// Linear RGB colour multiplying the power.
    pub color: Vec3,
}

impl LightSettings {
    pub const DEFAULT_POSITION: Vec3 = Vec3::new(2.5, 6.0, 2.0);
    pub const DEFAULT_POWER_W: f32 = 1000.0;

    /// Whether the light is a sphere (R > 0) rather than a point.
    pub fn is_sphere(&self) -> bool {
        self.radius_m > 0.0
    }
}

impl Default for LightSettings {
    fn default() -> Self {
        Self {
            position: Self::DEFAULT_POSITION,
            power_w: Self::DEFAULT_POWER_W,
            radius_m: 0.0,
            color: Vec3::ONE,
        }
    }
}

/// The BRDF f_r = c · (k/π + (1 − k) · N(m) · cos^m θ_h).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MaterialSettings {
    /// Diffuse/specular mix k ∈ [0, 1].
    pub k: f32,
    /// Blinn-Phong exponent m ∈ [0, 10^6].
    pub m: f32,
    /// Normalization N(m) of the lobe.
    pub norm: Normalization,
    /// Objects whose glTF material gives its own k and m keep them; when
    /// false every object uses `k` and `m` above.
    pub use_scene_materials: bool,
    /// Replaces every object's colour c (linear RGB) when set.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color_override: Option<Vec3>,
}

impl Default for MaterialSettings {
    fn default() -> Self {
        Self {
            k: 0.5,
            m: 32.0,
            norm: Normalization::Approx,
            use_scene_materials: true,
            color_override: None,
        }
    }
}

named_enum! {
    /// What the image shows.
    pub enum DebugView {
        /// Reflected radiance L (W/m²/sr), exposed and sRGB encoded.
        Shaded = "shaded",
        /// The light's depth map, normalized.
        Depth = "depth",
        /// Visibility V ∈ [0, 1] from the shadow map.
        Visibility = "visibility",
        /// cos θ = max(0, n·l).
        Ndotl = "ndotl",
        /// Irradiance E (W/m²), false colour.
        Irradiance = "irradiance",
        /// f_r (1/sr), false colour.
        Brdf = "brdf",
        /// The diffuse part of L alone.
        Diffuse = "diffuse",
        /// The specular part of L alone.
        Specular = "specular",
        /// Shadow-map texels per screen pixel, false colour.
        TexelDensity = "texel-density",
        /// The light's frustum drawn over the shaded image.
        Frustum = "frustum",
        /// The CPU reference's visibility.
        RefVisibility = "ref-visibility",
        /// Signed error of L against the CPU reference.
        Error = "error",
        /// ΔE2000 per pixel between the RGB approximation and the spectral
        /// result under the illuminant (`[colour]`), false colour 0 … 10.
        DeltaE = "delta-e",
    }
}

/// What is shown and how it is exposed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ViewSettings {
    pub mode: DebugView,
    /// Exposure (EV): displayed = L · 2^EV, then the sRGB transfer.
    pub exposure_ev: f32,
}

impl Default for ViewSettings {
    fn default() -> Self {
        Self {
            mode: DebugView::Shaded,
            exposure_ev: 0.0,
        }
    }
}

named_enum! {
    /// Whether the lab adds a shadow-receiving ground under a loaded model.
    pub enum GroundMode {
        /// Under a model that has none (the built-in scene has its own).
        Auto = "auto",
        /// Always.
        On = "on",
        /// Never: the file's own geometry only.
        Off = "off",
    }
}

/// The ground the lab adds under a model (see `scene::framing`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GroundSettings {
    pub mode: GroundMode,
    /// Its diffuse/specular mix k.
    pub k: f32,
    /// Its Blinn-Phong exponent m.
    pub m: f32,
}

impl Default for GroundSettings {
    /// Neutral and mostly diffuse, as the built-in scene's ground.
    fn default() -> Self {
        Self {
            mode: GroundMode::Auto,
            k: 0.9,
            m: 16.0,
        }
    }
}

impl Settings {
    /// Positions (m) are allowed within this of the origin: a far "sun"
    /// at 1.5·10¹¹ m included.
    pub const MAX_COORDINATE_M: f32 = 1e12;
    /// The largest light power (W): the Sun's 3.8·10²⁶ W included.
    pub const MAX_POWER_W: f32 = 1e32;

    /// The default settings moved to a scene of `scale`: the light, the
    /// camera and the bias where the built-in scene has them, scaled. The
    /// built-in scale gives [`Settings::default`] exactly.
    pub fn for_scale(scale: SceneScale) -> Self {
        let mut s = Self::default();
        s.camera.eye = scale.point(s.camera.eye);
        s.camera.target = scale.point(s.camera.target);
        s.light.position = scale.point(s.light.position);
        s.light.radius_m = scale.length(s.light.radius_m);
        s.light.power_w = scale.power(s.light.power_w);
        s.shadow.bias.depth_m = scale.length(s.shadow.bias.depth_m);
        s
    }

    /// Shadow rays per pixel and frame of ray-traced visibility:
    /// `rt_light_samples` directions in a sphere light's solid angle; one ray
    /// to a point light, which is exact.
    pub fn ray_traced_rays_per_frame(&self) -> u32 {
        if self.light.is_sphere() {
            self.shadow.rt_light_samples.max(1)
        } else {
            1
        }
    }

    /// Frames that ray-traced visibility accumulates before its image
    /// holds: `rt_max_frames` under a sphere light; one under a point
    /// light, whose single shadow ray per pixel is exact, so further
    /// frames would only repeat it.
    pub fn ray_traced_frames(&self) -> u32 {
        if self.light.is_sphere() {
            self.shadow.rt_max_frames.max(1)
        } else {
            1
        }
    }

    /// Reads, parses and validates a settings file.
    pub fn load(path: &Path) -> Result<Self, SettingsError> {
        let limit = crate::input::SETTINGS_LIMIT_BYTES;
        let text = crate::input::read_text_bounded(path, limit, "a settings file").map_err(|source| {
            SettingsError::Read {
                path: path.to_owned(),
                source,
            }
        })?;
        let settings = Self::from_toml(&text).map_err(|message| SettingsError::Parse {
            path: path.to_owned(),
            message,
        })?;
        settings.validate()?;
        Ok(settings)
    }

    /// Parses TOML; the error is one line naming the line and the key.
    pub fn from_toml(text: &str) -> Result<Self, String> {
        toml::from_str(text).map_err(|e| describe_toml_error(text, &e))
    }

    /// The TOML text of these settings.
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).expect("settings always serialize")
    }

    /// Writes the settings atomically (a temporary file, then a rename).
    pub fn save(&self, path: &Path) -> Result<(), SettingsError> {
        crate::output::write_atomically(path, self.to_toml().as_bytes()).map_err(|source| {
            SettingsError::Write {
                path: path.to_owned(),
                source,
            }
        })
    }
}

/// One line: where the error is (line and key path) and what it is.
pub(crate) fn describe_toml_error(text: &str, error: &toml::de::Error) -> String {
    let message = error.message().trim().replace('\n', " ");
    let Some(span) = error.span() else {
        return message;
    };
    let before = &text[..span.start.min(text.len())];
    let line_no = before.matches('\n').count() + 1;
    let line = text.lines().nth(line_no - 1).unwrap_or("").trim();
    let table = before
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('[') && l.ends_with(']'))
        .map(|l| l.trim_matches(|c| c == '[' || c == ']').to_string());
    let key = line
        .split('=')
        .next()
        .map(str::trim)
        .filter(|k| !k.is_empty() && !k.starts_with('['));
    let path = match (table, key) {
        (Some(t), Some(k)) => format!(" at {t}.{k}"),
        (None, Some(k)) => format!(" at {k}"),
        _ => String::new(),
    };
    format!("line {line_no}{path}: {message}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_round_trip() {
        let s = Settings::default();
        s.validate().unwrap();
        let text = s.to_toml();
        assert_eq!(Settings::from_toml(&text).unwrap(), s);
    }

    #[test]
    fn an_empty_file_is_the_defaults() {
        assert_eq!(Settings::from_toml("").unwrap(), Settings::default());
    }

    #[test]
    fn unknown_field_is_named() {
        let err = Settings::from_toml("[light]\npower_w = 3\nbrightness = 2\n").unwrap_err();
        assert!(err.contains("brightness") && err.contains("line 3"), "{err}");
        assert!(!err.contains('\n'));
    }

    #[test]
    fn wrong_type_names_the_key() {
        let err = Settings::from_toml("[light]\npower_w = \"bright\"\n").unwrap_err();
        assert!(err.contains("light.power_w"), "{err}");
    }

    #[test]
    fn out_of_range_names_field_and_range() {
        let mut s = Settings::default();
        s.material.k = 1.5;
        let err = s.validate().unwrap_err().to_string();
        assert!(err.contains("material.k") && err.contains("0 … 1"), "{err}");
        let mut s = Settings::default();
        s.shadow.pcf_size = 4;
        assert!(s.validate().unwrap_err().to_string().contains("3, 5, 7 or 9"));
    }

    #[test]
    fn enum_names_are_the_design_names() {
        assert_eq!(Filter::choices(), "none|hw2x2|pcf|poisson|pcss|vsm|evsm|msm");
        assert_eq!(BiasMode::choices(), "auto|constant|slope|normal");
        assert_eq!(
            DebugView::choices(),
            "shaded|depth|visibility|ndotl|irradiance|brdf|diffuse|specular|texel-density|frustum|ref-visibility|error|delta-e"
        );
        let err = Settings::from_toml("[shadow]\nfilter = \"blur\"\n").unwrap_err();
        assert!(err.contains("pcf") && err.contains("blur"), "{err}");
    }
}
