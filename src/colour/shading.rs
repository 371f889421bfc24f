//! Colours a renderer shades with under a spectral light (DESIGN.md,
//! `--illuminant`).
//!
//! With one light and direct lighting, the only factors that depend on the
//! wavelength are the light's emission S(λ) and the material's reflectance
//! R(λ): the BRDF's shape, the irradiance and the visibility are the same at
//! every wavelength. So a pixel's spectral radiance is
//! L(λ) = (f_r / c) · E · V · R(λ) · S(λ), and its tristimulus values are that
//! scalar times the XYZ of R · S. This module computes, once per material,
//! that XYZ as linear sRGB (the *spectral colour*), which the GPU then uses as
//! the material's colour under a grey light; the CPU reference integrates
//! R(λ) S(λ) against the colour-matching functions itself, pixel by pixel.
//!
//! **How the light's power normalizes.** The illuminant is scaled so that a
//! perfect white (R = 1) under it has the luminance Y of the light's RGB
//! colour (1 for white): the spectrum changes the light's chromaticity, not
//! how bright the scene is. Both colour models follow this rule:
//! - `spectral`: material colour = linear sRGB of XYZ(R · S) / Y(S), light
//!   colour = Y_light · (1, 1, 1);
//! - `rgb-approx` (the lecture's product): material colour = its RGB base
//!   colour, light colour = the illuminant's own linear sRGB at Y = 1, × Y_light.
//!
//! Under D65 (sRGB's white) the two agree by construction for every
//! material whose base colour is its colour under D65 — the chart's
//! measured patches and the uplifted RGB colours alike.

use super::chart::illuminant_linear_srgb;
use super::data::{Illuminant, PATCH_COUNT, patch_names, patch_reflectance};
use super::delta_e::delta_e2000;
use super::spectrum::Spectrum;
use super::tristimulus::{lab, linear_srgb_to_xyz, reflectance_xyz, white_xyz, xyz_to_linear_srgb};
use super::uplift::uplift_linear_srgb;
use crate::physics::colour::luminance;
use glam::DVec3;

named_enum! {
    /// How a render under a spectral illuminant computes colour.
    #[derive(Default)]
    pub enum ColourModel {
        /// Emission × reflectance wavelength by wavelength, then the CMFs.
        #[default]
        Spectral = "spectral",
        /// The lecture's product: the light's RGB times the base colour's RGB.
        RgbApprox = "rgb-approx",
    }
}

impl ColourModel {
    /// The other model: what the `delta-e` view and the probe compare with.
    pub fn other(self) -> Self {
        match self {
            Self::Spectral => Self::RgbApprox,
            Self::RgbApprox => Self::Spectral,
        }
    }
}

/// A material whose name starts with this, followed by the patch number
/// (01–24), has that ColorChecker patch's measured reflectance
/// ("ColorChecker 13 blue"); every other material gets the smooth
/// reflectance uplifted from its base colour.
pub const CHART_MATERIAL_PREFIX: &str = "ColorChecker ";

/// The material name that carries patch `patch`'s (0..24) measured spectrum.
pub fn chart_material_name(patch: usize) -> String {
    format!("{CHART_MATERIAL_PREFIX}{:02} {}", patch + 1, patch_names()[patch])
}

/// The chart patch (0..24) a material name designates, if any.
pub fn chart_patch_of(name: &str) -> Option<usize> {
    let number = name.strip_prefix(CHART_MATERIAL_PREFIX)?.get(..2)?;
    let patch = number.parse::<usize>().ok()?.checked_sub(1)?;
    (patch < PATCH_COUNT).then_some(patch)
}

/// The reflectance of a material: measured for a chart patch, else uplifted
/// from its linear sRGB base colour (Jakob & Hanika 2019).
pub fn material_reflectance(name: &str, base_linear_srgb: DVec3) -> Spectrum {
    match chart_patch_of(name) {
        Some(patch) => patch_reflectance(patch),
        None => uplift_linear_srgb(base_linear_srgb).spectrum(),
    }
}

/// The linear sRGB colour of `reflectance` lit by `illuminant`, the perfect
/// white's Y being 1 (see the module docs).
pub fn spectral_colour(illuminant: &Spectrum, reflectance: &Spectrum) -> DVec3 {
    xyz_to_linear_srgb(reflectance_xyz(illuminant, reflectance) / 100.0)
}

/// The light colour and the material colours to shade with: what the GPU
/// uploads in place of the settings' light colour and the scene's base colours.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadingColours {
    pub light: DVec3,
    /// One per material given, in order.
    pub materials: Vec<DVec3>,
    /// The colour that replaces every material's, if one does.
    pub color_override: Option<DVec3>,
}

/// The colours for `illuminant` (None: RGB mode, everything unchanged) and
/// `model`, given the light's RGB colour, each material's (name, linear sRGB
/// base colour) and the settings' override colour.
pub fn shading_colours<'a>(
    illuminant: Option<Illuminant>,
    model: ColourModel,
    light_rgb: DVec3,
    materials: impl Iterator<Item = (&'a str, DVec3)>,
    color_override: Option<DVec3>,
) -> ShadingColours {
    let light_y = luminance(light_rgb.to_array());
    match (illuminant, model) {
        (None, _) => ShadingColours {
            light: light_rgb,
            materials: materials.map(|(_, c)| c).collect(),
            color_override,
        },
        (Some(i), ColourModel::RgbApprox) => ShadingColours {
            light: illuminant_linear_srgb(&i.spectrum()) * light_y,
            materials: materials.map(|(_, c)| c).collect(),
            color_override,
        },
        (Some(i), ColourModel::Spectral) => {
            let s = i.spectrum();
            ShadingColours {
                light: DVec3::splat(light_y),
                materials: materials
                    .map(|(name, c)| spectral_colour(&s, &material_reflectance(name, c)))
                    .collect(),
                color_override: color_override
                    .map(|c| spectral_colour(&s, &uplift_linear_srgb(c).spectrum())),
            }
        }
    }
}

/// ΔE2000 between two linear sRGB pixel values (as displayed: radiance ×
/// exposure) lit by `illuminant`, in CIE Lab with the illuminant's white at
/// Y = 1 as reference white: what the probe and the `delta-e` view show.
pub fn pixel_delta_e(illuminant: Illuminant, a: DVec3, b: DVec3) -> f64 {
    let white = white_xyz(&illuminant.spectrum()) / 100.0;
    let to_lab = |rgb: DVec3| lab(linear_srgb_to_xyz(rgb), white);
    delta_e2000(to_lab(a), to_lab(b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::chart::patch_linear_srgb;

    #[test]
    fn chart_names_round_trip() {
        for p in 0..PATCH_COUNT {
            assert_eq!(chart_patch_of(&chart_material_name(p)), Some(p));
        }
        for other in [
            "ColorChecker 00 x",
            "ColorChecker 25 x",
            "ColorChecker",
            "wall",
            "ColorChecker ab",
        ] {
            assert_eq!(chart_patch_of(other), None, "{other}");
        }
    }

    fn tint(c: &ShadingColours, i: usize) -> DVec3 {
        c.materials[i] * c.light
    }

    #[test]
    fn under_d65_the_rgb_approximation_is_the_spectral_result() {
        // The chart (measured spectra) and uplifted RGB colours.
        let mut materials: Vec<(String, DVec3)> = (0..PATCH_COUNT)
            .map(|p| (chart_material_name(p), patch_linear_srgb(p)))
            .collect();
        for c in [
            [0.8, 0.8, 0.8],
            [0.7, 0.2, 0.1],
            [0.1, 0.4, 0.6],
            [0.05, 0.05, 0.05],
        ] {
            materials.push(("plain".into(), DVec3::from_array(c)));
        }
        let light = DVec3::new(1.0, 0.9, 0.8);
        let run = |model| {
            shading_colours(
                Some(Illuminant::D65),
                model,
                light,
                materials.iter().map(|(n, c)| (n.as_str(), *c)),
                None,
            )
        };
        let (spectral, approx) = (run(ColourModel::Spectral), run(ColourModel::RgbApprox));
        let white = linear_srgb_to_xyz(DVec3::ONE);
        for (i, (name, _)) in materials.iter().enumerate() {
            let to_lab = |rgb| lab(linear_srgb_to_xyz(rgb), white);
            let de = delta_e2000(to_lab(tint(&spectral, i)), to_lab(tint(&approx, i)));
            assert!(de < 0.05, "{name}: ΔE2000 {de}");
        }
    }

    #[test]
    fn the_light_keeps_its_luminance_whatever_the_spectrum() {
        let light = DVec3::new(0.5, 0.5, 0.5);
        for i in [
            Illuminant::A,
            Illuminant::Fl11,
            Illuminant::Blackbody { kelvin: 1500.0 },
        ] {
            for model in ColourModel::ALL {
                let c = shading_colours(Some(i), *model, light, [("white", DVec3::ONE)].into_iter(), None);
                // A perfect white (uplift of 1 is 0.999) reflects Y = 0.5.
                let y = luminance(tint(&c, 0).to_array());
                assert!((y - 0.5).abs() < 2e-3, "{i} {model}: {y}");
            }
        }
    }

    #[test]
    fn rgb_mode_changes_nothing() {
        let c = shading_colours(
            None,
            ColourModel::Spectral,
            DVec3::new(1.0, 0.5, 0.25),
            [("a", DVec3::new(0.1, 0.2, 0.3))].into_iter(),
            Some(DVec3::ONE),
        );
        assert_eq!(c.light, DVec3::new(1.0, 0.5, 0.25));
        assert_eq!(c.materials, vec![DVec3::new(0.1, 0.2, 0.3)]);
        assert_eq!(c.color_override, Some(DVec3::ONE));
    }
}
