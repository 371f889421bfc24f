//! The lecture's experiments as one-click presets, and the comparisons the
//! split view offers. No GUI here: the app, the tests and a future command
//! line all apply the same values.
//!
//! A preset starts from the default settings, keeping the scene, the image
//! size and (unless it names one) the camera, then sets the values listed in
//! its doc comment. Light positions, cameras and lengths are tuned for the
//! built-in scene (a 12 m ground, a 1 m box at the origin, a sphere of
//! radius 0.5 m); another scene gets them through its [`SceneScale`].

use crate::colour::{ColourModel, Illuminant};
use crate::physics::Normalization;
use crate::scene::SceneScale;
use crate::settings::{BiasMode, DebugView, Filter, Settings, Visibility};
use glam::Vec3;

named_enum! {
    /// An experiment of the lecture.
    pub enum Preset {
        /// Shadow acne: no bias at all (`constant:0`), no filter, 1024².
        /// The surface shadows itself in stripes: depth quantization.
        ShadowAcne = "shadow-acne",
        /// Peter-panning: `constant:0.5` (far too much bias), PCF 3×3, light at
        /// (3.5, 3, 3), camera at (1.8, 1.6, −3.2) looking at (−0.6, 0.1, −0.6):
        /// the box's shadow comes loose from its base.
        PeterPanning = "peter-panning",
        /// Aliasing: a 256² map, no filter, automatic bias: stair steps
        /// along every shadow edge (one texel covers many pixels).
        Aliasing = "aliasing",
        /// PCF smoothing: the same 256² map with a 7×7 PCF kernel: the steps
        /// blur into a soft (but not physical) edge.
        PcfSmoothing = "pcf-smoothing",
        /// Penumbra: a sphere light of radius R = 0.4 m at (2.5, 4, 2), PCSS
        /// with 32 blocker and 32 filter samples, 2048²: soft edges that widen
        /// away from the contact point.
        Penumbra = "penumbra",
        /// Energy gain: no normalization (N = 1) at m = 1 with k = 0 on every
        /// object: a(0°) ≈ 2.86, the surfaces reflect more than they receive.
        EnergyGain = "energy-gain",
        /// Grazing incidence: the light low at (6, 0.8, 0), 2000 W, shown as
        /// n·l: cos θ, and so E, falls to zero at the horizon.
        Grazing = "grazing",
    }
}

impl Preset {
    /// A short title for a button.
    pub fn title(self) -> &'static str {
        match self {
            Self::ShadowAcne => "Shadow acne",
            Self::PeterPanning => "Peter-panning",
            Self::Aliasing => "Aliasing",
            Self::PcfSmoothing => "PCF smoothing",
            Self::Penumbra => "Penumbra (sphere light)",
            Self::EnergyGain => "Energy gain (no normalization)",
            Self::Grazing => "Grazing incidence",
        }
    }

    /// What the preset shows and which values it sets, for a tooltip.
    pub fn description(self) -> &'static str {
        match self {
            Self::ShadowAcne => {
                "No depth bias (constant, D = 0 m), no filter, 1024² map. Every lit surface \
                 compares its depth with its own quantized copy and shadows itself in stripes."
            }
            Self::PeterPanning => {
                "Constant bias D = 0.5 m, PCF 3×3, light at (3.5, 3, 3), a camera near the box's \
                 base. Too much bias: the shadow detaches from the object that casts it."
            }
            Self::Aliasing => {
                "256² shadow map, no filter, automatic bias: one shadow-map texel covers many \
                 pixels, so shadow edges show stair steps."
            }
            Self::PcfSmoothing => {
                "The same 256² map with 7×7 percentage-closer filtering: the average of 49 depth \
                 tests turns the steps into a soft edge."
            }
            Self::Penumbra => {
                "Sphere light R = 0.4 m at (2.5, 4, 2), PCSS with 32 blocker-search and 32 filter \
                 samples, 2048² map: the penumbra widens with the distance to the occluder."
            }
            Self::EnergyGain => {
                "N(m) = 1 at m = 1, k = 0 on every object: a(0°) ≈ 2.86 > 1, the BRDF creates \
                 energy. Compare with the approx or exact normalization."
            }
            Self::Grazing => {
                "Light low at (6, 0.8, 0), 2000 W, view n·l: E = I cos θ / r² falls to zero as \
                 the light reaches the horizon."
            }
        }
    }

    /// The split-view comparison that shows what the preset is about
    /// (A without, B with the remedy), if one fits.
    pub fn comparison(self) -> Option<Comparison> {
        let base = Comparison::default();
        let with = |axis| Comparison { axis, ..base };
        Some(match self {
            // No bias (acne) | automatic bias.
            Self::ShadowAcne => Comparison {
                bias: [BiasMode::Constant, BiasMode::Auto],
                ..with(ComparisonAxis::Bias)
            },
            // Too much constant bias (peter-panning) | automatic bias.
            Self::PeterPanning => Comparison {
                bias: [BiasMode::Constant, BiasMode::Auto],
                ..with(ComparisonAxis::Bias)
            },
            Self::Aliasing => Comparison {
                resolution: [256, 2048],
                ..with(ComparisonAxis::Resolution)
            },
            Self::PcfSmoothing => Comparison {
                filter: [Filter::None, Filter::Pcf],
                ..with(ComparisonAxis::Filter)
            },
            Self::Penumbra => Comparison {
                filter: [Filter::Pcf, Filter::Pcss],
                ..with(ComparisonAxis::Filter)
            },
            Self::EnergyGain => Comparison {
                norm: [Normalization::None, Normalization::Approx],
                ..with(ComparisonAxis::Normalization)
            },
            Self::Grazing => return None,
        })
    }

    /// Sets the preset's values (see each variant's documentation), its
    /// lengths and positions those of the built-in scene moved by `scale`.
    pub fn apply(self, settings: &mut Settings, scale: SceneScale) {
        let kept = Settings {
            scene: settings.scene.clone(),
            camera: settings.camera,
            image: settings.image,
            ..Settings::for_scale(scale)
        };
        *settings = kept;
        let s = settings;
        match self {
            Self::ShadowAcne => {
                s.shadow.bias.mode = BiasMode::Constant;
                s.shadow.bias.depth_m = 0.0;
                s.shadow.filter = Filter::None;
                s.shadow.resolution = 1024;
            }
            Self::PeterPanning => {
                s.shadow.bias.mode = BiasMode::Constant;
                s.shadow.bias.depth_m = scale.length(0.5);
                s.shadow.filter = Filter::Pcf;
                s.shadow.pcf_size = 3;
                s.light.position = scale.point(Vec3::new(3.5, 3.0, 3.0));
                s.camera.eye = scale.point(Vec3::new(1.8, 1.6, -3.2));
                s.camera.target = scale.point(Vec3::new(-0.6, 0.1, -0.6));
                s.camera.fovy_deg = 45.0;
            }
            Self::Aliasing => {
                s.shadow.resolution = 256;
                s.shadow.filter = Filter::None;
                s.shadow.bias.mode = BiasMode::Auto;
            }
            Self::PcfSmoothing => {
                s.shadow.resolution = 256;
                s.shadow.filter = Filter::Pcf;
                s.shadow.pcf_size = 7;
                s.shadow.bias.mode = BiasMode::Auto;
            }
            Self::Penumbra => {
                s.light.radius_m = scale.length(0.4);
                s.light.position = scale.point(Vec3::new(2.5, 4.0, 2.0));
                s.shadow.filter = Filter::Pcss;
                s.shadow.pcss_blocker_samples = 32;
                s.shadow.poisson_samples = 32;
                s.shadow.resolution = 2048;
            }
            Self::EnergyGain => {
                s.material.norm = Normalization::None;
                s.material.m = 1.0;
                s.material.k = 0.0;
                s.material.use_scene_materials = false;
            }
            Self::Grazing => {
                s.light.position = scale.point(Vec3::new(6.0, 0.8, 0.0));
                s.light.power_w = scale.power(2000.0);
                s.view.mode = DebugView::Ndotl;
            }
        }
    }
}

named_enum! {
    /// The setting in which the B half of the split view differs from A.
    pub enum ComparisonAxis {
        /// The lobe's normalization N(m).
        Normalization = "normalization",
        /// The shadow filter.
        Filter = "filter",
        /// The shadow-map resolution.
        Resolution = "resolution",
        /// The bias mode.
        Bias = "bias",
        /// Where V comes from: shadow map or ray traced.
        Visibility = "visibility",
        /// The colour model under the illuminant: the RGB product or the spectral result.
        Colour = "colour",
    }
}

/// A split-view comparison: both halves show the current settings, each
/// with its own value of one setting.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Comparison {
    pub axis: ComparisonAxis,
    pub norm: [Normalization; 2],
    pub filter: [Filter; 2],
    pub resolution: [u32; 2],
    pub bias: [BiasMode; 2],
    pub visibility: [Visibility; 2],
    pub colour: [ColourModel; 2],
}

impl Default for Comparison {
    /// The lecture's figure: without normalization | with the approximate one.
    fn default() -> Self {
        Self {
            axis: ComparisonAxis::Normalization,
            norm: [Normalization::None, Normalization::Approx],
            filter: [Filter::None, Filter::Pcf],
            resolution: [256, 2048],
            bias: [BiasMode::Constant, BiasMode::Auto],
            visibility: [Visibility::ShadowMap, Visibility::RayTraced],
            colour: [ColourModel::RgbApprox, ColourModel::Spectral],
        }
    }
}

/// The illuminant the colour comparison uses when none is chosen: under
/// D65 the two models agree, under A (a tungsten lamp) they visibly do not.
pub const COMPARISON_ILLUMINANT: Illuminant = Illuminant::A;

/// The one-click comparisons of the split view, each a [`Comparison`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplitPreset {
    Normalization,
    Filter,
    Pcss,
    Resolution,
    Visibility,
    Colour,
}

impl SplitPreset {
    pub const ALL: [Self; 6] = [
        Self::Normalization,
        Self::Filter,
        Self::Pcss,
        Self::Resolution,
        Self::Visibility,
        Self::Colour,
    ];

    /// Its name, in English ("filter PCF | PCSS").
    pub fn title(self) -> &'static str {
        match self {
            Self::Normalization => "norm none | approx",
            Self::Filter => "filter none | PCF",
            Self::Pcss => "filter PCF | PCSS",
            Self::Resolution => "resolution 256² | 2048²",
            Self::Visibility => "shadow map | ray traced",
            Self::Colour => "RGB | spectral",
        }
    }

    /// What the two halves show.
    pub fn comparison(self) -> Comparison {
        let base = Comparison::default();
        let axis = match self {
            Self::Normalization => ComparisonAxis::Normalization,
            Self::Filter | Self::Pcss => ComparisonAxis::Filter,
            Self::Resolution => ComparisonAxis::Resolution,
            Self::Visibility => ComparisonAxis::Visibility,
            Self::Colour => ComparisonAxis::Colour,
        };
        let filter = match self {
            Self::Pcss => [Filter::Pcf, Filter::Pcss],
            _ => base.filter,
        };
        Comparison { axis, filter, ..base }
    }
}

/// Which half of the split view.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Half {
    A = 0,
    B = 1,
}

impl Comparison {
    /// The settings one half shows: `base` with this half's value.
    pub fn settings_for(&self, half: Half, base: &Settings) -> Settings {
        let mut s = base.clone();
        let i = half as usize;
        match self.axis {
            ComparisonAxis::Normalization => s.material.norm = self.norm[i],
            ComparisonAxis::Filter => s.shadow.filter = self.filter[i],
            ComparisonAxis::Resolution => s.shadow.resolution = self.resolution[i],
            ComparisonAxis::Bias => s.shadow.bias.mode = self.bias[i],
            ComparisonAxis::Visibility => s.shadow.visibility = self.visibility[i],
            ComparisonAxis::Colour => {
                s.colour.illuminant.get_or_insert(COMPARISON_ILLUMINANT);
                s.colour.model = self.colour[i];
            }
        }
        s
    }

    /// "norm none", "filter pcf", "2048²": the label of one half.
    pub fn label(&self, half: Half) -> String {
        let i = half as usize;
        match self.axis {
            ComparisonAxis::Normalization => format!("norm {}", self.norm[i]),
            ComparisonAxis::Filter => format!("filter {}", self.filter[i]),
            ComparisonAxis::Resolution => format!("shadow map {}²", self.resolution[i]),
            ComparisonAxis::Bias => format!("bias {}", self.bias[i]),
            ComparisonAxis::Visibility => self.visibility[i].name().replace('-', " "),
            ComparisonAxis::Colour => match self.colour[i] {
                ColourModel::RgbApprox => "RGB approximation".into(),
                ColourModel::Spectral => "spectral".into(),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_gives_valid_settings() {
        for &p in Preset::ALL {
            let mut s = Settings::default();
            p.apply(&mut s, SceneScale::BUILT_IN);
            s.validate().unwrap_or_else(|e| panic!("{p}: {e}"));
            assert!(!p.description().is_empty() && !p.title().is_empty());
        }
    }

    #[test]
    fn presets_compare_without_and_with_the_remedy() {
        let base = Settings::default();
        let c = Preset::ShadowAcne.comparison().unwrap();
        let mut acne = base.clone();
        Preset::ShadowAcne.apply(&mut acne, SceneScale::BUILT_IN);
        assert_eq!(
            c.settings_for(Half::A, &acne).shadow.bias.describe(),
            "constant:0"
        );
        assert_eq!(c.settings_for(Half::B, &acne).shadow.bias.mode, BiasMode::Auto);
        let c = Preset::Aliasing.comparison().unwrap();
        assert_eq!(c.label(Half::A), "shadow map 256²");
        assert_eq!(c.label(Half::B), "shadow map 2048²");
        let c = Preset::Penumbra.comparison().unwrap();
        assert_eq!(c.label(Half::B), "filter pcss");
        let c = Preset::EnergyGain.comparison().unwrap();
        assert_eq!(
            (c.label(Half::A), c.label(Half::B)),
            ("norm none".into(), "norm approx".into())
        );
        assert!(Preset::Grazing.comparison().is_none());
        let c = SplitPreset::Visibility.comparison();
        assert_eq!(SplitPreset::Visibility.title(), "shadow map | ray traced");
        assert_eq!(
            (c.label(Half::A), c.label(Half::B)),
            ("shadow map".into(), "ray traced".into())
        );
        assert_eq!(
            c.settings_for(Half::B, &base).shadow.visibility,
            Visibility::RayTraced
        );
    }

    #[test]
    fn acne_preset_has_no_bias_and_no_filter() {
        let mut s = Settings::default();
        Preset::ShadowAcne.apply(&mut s, SceneScale::BUILT_IN);
        assert_eq!(s.shadow.bias.describe(), "constant:0");
        assert_eq!(s.shadow.filter, Filter::None);
    }

    #[test]
    fn presets_keep_the_scene_and_image() {
        let mut s = Settings {
            scene: Some("x.glb".into()),
            ..Settings::default()
        };
        s.image.width = 123;
        s.material.k = 0.9;
        Preset::Aliasing.apply(&mut s, SceneScale::BUILT_IN);
        assert_eq!(s.scene.as_deref(), Some(std::path::Path::new("x.glb")));
        assert_eq!(s.image.width, 123);
        assert_eq!(s.material.k, Settings::default().material.k);
    }

    #[test]
    fn energy_gain_preset_gains_energy() {
        let mut s = Settings::default();
        Preset::EnergyGain.apply(&mut s, SceneScale::BUILT_IN);
        let params = crate::physics::BrdfParams {
            k: s.material.k as f64,
            m: s.material.m as f64,
            norm: s.material.norm,
        };
        let a = crate::physics::energy::directional_albedo(0.0, &params).value;
        assert!((a - 2.86).abs() < 0.01, "{a}");
    }

    #[test]
    fn default_comparison_is_the_lectures_figure() {
        let c = Comparison::default();
        let base = Settings::default();
        assert_eq!(c.settings_for(Half::A, &base).material.norm, Normalization::None);
        assert_eq!(
            c.settings_for(Half::B, &base).material.norm,
            Normalization::Approx
        );
        assert_eq!(c.label(Half::A), "norm none");
        for c in SplitPreset::ALL.map(SplitPreset::comparison) {
            for half in [Half::A, Half::B] {
                c.settings_for(half, &base).validate().unwrap();
            }
        }
    }

    #[test]
    fn colour_comparison_is_rgb_against_spectral_under_the_chosen_light() {
        let c = Comparison {
            axis: ComparisonAxis::Colour,
            ..Comparison::default()
        };
        let mut base = Settings::default();
        let (a, b) = (c.settings_for(Half::A, &base), c.settings_for(Half::B, &base));
        assert_eq!(
            (a.colour.model, b.colour.model),
            (ColourModel::RgbApprox, ColourModel::Spectral)
        );
        assert_eq!(a.colour.illuminant, Some(COMPARISON_ILLUMINANT));
        base.colour.illuminant = Some(Illuminant::Fl11);
        assert_eq!(
            c.settings_for(Half::B, &base).colour.illuminant,
            Some(Illuminant::Fl11)
        );
        assert_eq!(c.label(Half::A), "RGB approximation");
    }
}
