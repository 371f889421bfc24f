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
mod validate;

pub use colour::ColourSettings;

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
    /// Where the visibility V(p, q) ∈ [0, 1] of the light comes from: a source
    /// of its own, beside the shadow map's `Filter`, so that the BRDF and the
    /// radiance are computed the same whatever gives V.
    #[derive(Default)]
    pub enum Visibility {
        /// The shadow map, filtered by `ShadowSettings::filter`.
        #[default]
        ShadowMap = "shadow-map",
        /// Shadow rays traced on the GPU through a BVH: exact for a point
        /// light; a sphere light is sampled per frame and accumulated.
        RayTraced = "ray-traced",
    }
}

named_enum! {
    /// How the shadow map's depth tests are filtered into a visibility V ∈ [0, 1].
    pub enum Filter {
        /// One nearest-texel depth test: hard, aliased edges.
        None = "none",
        /// The hardware comparison sampler: 2×2 tests bilinearly weighted.
        Hw2x2 = "hw2x2",
        /// Percentage-closer filtering over n×n texels.
        Pcf = "pcf",
        /// Poisson-disc samples rotated per pixel: noise instead of banding.
        Poisson = "poisson",
        /// Percentage-closer soft shadows: a blocker search sizes the penumbra
        /// of the sphere light.
        Pcss = "pcss",
        /// Variance shadow map: filtered depth moments and Chebyshev's bound.
        Vsm = "vsm",
        /// Exponential variance shadow map: warped moments, less light bleeding.
        Evsm = "evsm",
        /// Moment shadow map: four moments of the depth, Hamburger
        /// reconstruction of the sharpest distribution that has them.
        Msm = "msm",
    }
}

named_enum! {
    /// How the receiver's depth is offset before it is compared.
    pub enum BiasMode {
        /// The receiver's tangent plane predicts its depth at every sample,
        /// plus a slack of a fraction of the texel footprint.
        Auto = "auto",
        /// A constant depth D (m) towards the light.
        Constant = "constant",
        /// D plus S × texel footprint × tan θ: more bias at grazing light.
        Slope = "slope",
        /// The receiver moved N texel footprints along its normal.
        Normal = "normal",
    }
}

/// Depth bias: trades shadow acne (too little) against peter-panning (too much).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BiasSettings {
    pub mode: BiasMode,
    /// D, the constant depth offset of `constant` and `slope` (m).
    pub depth_m: f32,
    /// S, the slope factor of `slope` (texel footprints per unit of tan θ).
    pub slope: f32,
    /// N, the normal offset of `normal` (shadow-map texels).
    pub normal_texels: f32,
}

impl Default for BiasSettings {
    fn default() -> Self {
        Self {
            mode: BiasMode::Auto,
            depth_m: SceneScale::DEFAULT_BIAS,
            slope: 1.0,
            normal_texels: 1.0,
        }
    }
}

impl BiasSettings {
    /// The command-line form: `auto`, `constant:D`, `slope:D,S` or `normal:N`.
    pub fn describe(&self) -> String {
        match self.mode {
            BiasMode::Auto => "auto".into(),
            BiasMode::Constant => format!("constant:{}", self.depth_m),
            BiasMode::Slope => format!("slope:{},{}", self.depth_m, self.slope),
            BiasMode::Normal => format!("normal:{}", self.normal_texels),
        }
    }

    /// Parses the command-line form, keeping the other values of `self`.
    pub fn parse_onto(mut self, text: &str) -> Result<Self, String> {
        const FORMS: &str = "auto, constant:D, slope:D,S or normal:N";
        let (mode, args) = text.split_once(':').unwrap_or((text, ""));
        let numbers: Result<Vec<f32>, _> = if args.is_empty() {
            Ok(Vec::new())
        } else {
            args.split(',').map(|a| a.trim().parse::<f32>()).collect()
        };
        let numbers = numbers.map_err(|_| format!("bad number in '{text}' (expected {FORMS})"))?;
        if numbers.iter().any(|x| !x.is_finite() || *x < 0.0) {
            return Err(format!("'{text}': bias values must be finite and ≥ 0"));
        }
        match (mode, numbers.as_slice()) {
            ("auto", []) => self.mode = BiasMode::Auto,
            ("constant", [d]) => {
                self.mode = BiasMode::Constant;
                self.depth_m = *d;
            }
            ("slope", [d, s]) => {
                self.mode = BiasMode::Slope;
                self.depth_m = *d;
                self.slope = *s;
            }
            ("normal", [n]) => {
                self.mode = BiasMode::Normal;
                self.normal_texels = *n;
            }
            _ => {
                return Err(format!(
                    "unknown bias '{}' (expected {FORMS})",
                    crate::input::escape_controls(text)
                ));
            }
        }
        Ok(self)
    }
}

/// The shadow map and how it is filtered and biased.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ShadowSettings {
    /// Shadows on; off gives V = 1 everywhere.
    pub enabled: bool,
    /// Where V comes from (the struct's `serde(default)` lets files without it load).
    pub visibility: Visibility,
    /// Shadow-map resolution (texels per side), clamped to the device limit.
    pub resolution: u32,
    pub filter: Filter,
    /// Kernel size n of `pcf` (n×n texels): 3, 5, 7 or 9.
    pub pcf_size: u32,
    /// Samples of `poisson` and of the filtering step of `pcss`.
    pub poisson_samples: u32,
    /// Radius of the `poisson` disc (texels).
    pub poisson_radius_texels: f32,
    /// Samples of the blocker search of `pcss`.
    pub pcss_blocker_samples: u32,
    /// Radius of the separable blur of `vsm`/`evsm`/`msm` (texels).
    pub vsm_blur_texels: u32,
    /// Light-bleeding reduction of `vsm`/`evsm`: the part of Chebyshev's bound cut off.
    pub vsm_bleed_reduction: f32,
    /// Moment bias α of `msm`: the moments are pulled towards those of a
    /// uniform depth, b' = (1 − α) b + α (½, ½, ½, ½), which keeps the
    /// Hankel matrix invertible under rounding (α small: sharper, acne-prone
    /// where rounding shows; larger: more light leaking).
    pub msm_bias: f32,
    pub bias: BiasSettings,
    /// Shadow rays per pixel per frame towards a sphere light (`ray-traced`):
    /// strata of the light's solid angle.
    pub rt_light_samples: u32,
    /// Frames accumulated by `ray-traced` while nothing changes; then the
    /// image holds (N frames × `rt_light_samples` rays per pixel).
    pub rt_max_frames: u32,
}

impl ShadowSettings {
    pub const MIN_RESOLUTION: u32 = 256;
    pub const MAX_RESOLUTION: u32 = 65536;
    pub const PCF_SIZES: [u32; 4] = [3, 5, 7, 9];
    /// Peters & Klein 2015's α for moments stored in 32-bit floats.
    pub const DEFAULT_MSM_BIAS: f32 = 3e-5;
    pub const MAX_RT_LIGHT_SAMPLES: u32 = 256;
    pub const MAX_RT_FRAMES: u32 = 65536;
}

impl Default for ShadowSettings {
    fn default() -> Self {
        Self {
            enabled: true,
            visibility: Visibility::ShadowMap,
            resolution: 2048,
            filter: Filter::Pcf,
            pcf_size: 3,
            poisson_samples: 16,
            poisson_radius_texels: 2.0,
            pcss_blocker_samples: 16,
            vsm_blur_texels: 2,
            vsm_bleed_reduction: 0.2,
            msm_bias: Self::DEFAULT_MSM_BIAS,
            bias: BiasSettings::default(),
            rt_light_samples: 4,
            rt_max_frames: 256,
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
    /// The largest component of the light's linear RGB colour.
    pub const MAX_LIGHT_COLOR: f32 = 1e6;

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
    /// `rt_light_samples` strata of a sphere light's solid angle; one ray
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

    #[test]
    fn bias_parses_every_form() {
        let b = BiasSettings::default();
        assert_eq!(b.parse_onto("auto").unwrap().mode, BiasMode::Auto);
        let c = b.parse_onto("constant:0.02").unwrap();
        assert_eq!((c.mode, c.depth_m), (BiasMode::Constant, 0.02));
        let s = b.parse_onto("slope:0.01,2.5").unwrap();
        assert_eq!((s.mode, s.depth_m, s.slope), (BiasMode::Slope, 0.01, 2.5));
        let n = b.parse_onto("normal:1.5").unwrap();
        assert_eq!((n.mode, n.normal_texels), (BiasMode::Normal, 1.5));
        for bad in ["slope:1", "constant:x", "normal:-1", "bogus", "constant:nan"] {
            assert!(b.parse_onto(bad).is_err(), "{bad}");
        }
        // Found by the fuzzer: the message quotes the text on one line.
        let err = b.parse_onto("c\nstant:0.02").unwrap_err();
        assert!(err.starts_with("unknown bias 'c\\nstant:0.02'"), "{err}");
        for form in ["auto", "constant:0.02", "slope:0.01,2.5", "normal:1.5"] {
            assert_eq!(b.parse_onto(form).unwrap().describe(), form);
        }
    }
}
