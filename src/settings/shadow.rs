//! The visibility settings: where V comes from, the shadow map's filter
//! and depth bias (with its command-line form), and the ray tracer's
//! samples and frames.

use crate::scene::SceneScale;
use serde::{Deserialize, Serialize};

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
    /// the next points of the pixel's low-discrepancy sequence over the
    /// light's solid angle.
    pub rt_light_samples: u32,
    /// Frames accumulated by `ray-traced` while nothing changes; then the
    /// image holds (N frames × `rt_light_samples` rays per pixel).
    pub rt_max_frames: u32,
    /// The lab stops asking for ray-traced frames before `rt_max_frames`
    /// once the noise measured on the image (`gpu::noise`) is at most this
    /// percentage of the mean; 0: never. It changes when the image holds,
    /// not the image: the command line and the report render their N frames.
    pub rt_noise_target_percent: f32,
}

impl ShadowSettings {
    pub const MIN_RESOLUTION: u32 = 256;
    pub const MAX_RESOLUTION: u32 = 65536;
    pub const PCF_SIZES: [u32; 4] = [3, 5, 7, 9];
    /// Peters & Klein 2015's α for moments stored in 32-bit floats.
    pub const DEFAULT_MSM_BIAS: f32 = 3e-5;
    pub const MAX_RT_LIGHT_SAMPLES: u32 = 256;
    pub const MAX_RT_FRAMES: u32 = 65536;
    /// Eight rays a frame: one walk of the BVH (`bvh_occluded8`) costs some
    /// 1.4× a walk for four on lavapipe, so the mean reaches a noise target
    /// in ~60 % of the time four rays take, each frame ~1.2× as long.
    pub const DEFAULT_RT_LIGHT_SAMPLES: u32 = 8;
    /// The default noise target: 0.1 % of the mean, under a tenth of an
    /// 8-bit display step at mid-grey (met after 256 rays a pixel, 32
    /// frames of 8, on the default scene under R = 0.3 m).
    pub const DEFAULT_RT_NOISE_TARGET_PERCENT: f32 = 0.1;
    pub const MAX_RT_NOISE_TARGET_PERCENT: f32 = 10.0;
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
            rt_light_samples: Self::DEFAULT_RT_LIGHT_SAMPLES,
            rt_max_frames: 256,
            rt_noise_target_percent: Self::DEFAULT_RT_NOISE_TARGET_PERCENT,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
