//! The ColorChecker under an illuminant: the spectral truth against the
//! lecture's RGB product (DESIGN.md, `lumlab colour`).
//!
//! Spectral: X, Y, Z of illuminant × reflectance, wavelength by wavelength.
//! RGB: the patch's linear sRGB (its colour under D65, i.e. "under a white
//! source") times the illuminant's own linear sRGB scaled to Y = 1,
//! component by component, back to XYZ. Under D65 both agree by
//! construction; under any other light the RGB product ignores how the
//! reflectance and the emission overlap inside each of the three bands.

use super::data::{Illuminant, PATCH_COUNT, patch_names, patch_reflectance};
use super::delta_e::delta_e2000;
use super::spectrum::Spectrum;
use super::tristimulus::{lab, linear_srgb_to_xyz, reflectance_xyz, white_xyz, xyz_to_linear_srgb};
use glam::DVec3;

/// One patch under one illuminant, both ways.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchComparison {
    /// Index in chart order (0..24).
    pub patch: usize,
    /// Spectral XYZ, Y of the perfect white under the illuminant = 100.
    pub spectral_xyz: DVec3,
    /// The RGB product's XYZ, same scale.
    pub approx_xyz: DVec3,
    /// ΔE2000 between the two, in CIE Lab relative to the illuminant's white.
    pub delta_e2000: f64,
}

impl PatchComparison {
    /// The patch's name in the chart (N. Ohta's).
    pub fn name(&self) -> &'static str {
        patch_names()[self.patch]
    }
}

/// The illuminant's colour as linear sRGB with Y = 1: the "RGB of the light"
/// that the lecture's approximation multiplies by.
pub fn illuminant_linear_srgb(illuminant: &Spectrum) -> DVec3 {
    xyz_to_linear_srgb(white_xyz(illuminant) / 100.0)
}

/// A patch's colour under a white source: its linear sRGB under D65 (white's
/// Y = 1). This is the RGB base colour a material would be given.
pub fn patch_linear_srgb(patch: usize) -> DVec3 {
    xyz_to_linear_srgb(reflectance_xyz(&Illuminant::D65.spectrum(), &patch_reflectance(patch)) / 100.0)
}

/// The 24 patches under `illuminant`, in chart order.
pub fn compare_chart(illuminant: Illuminant) -> Vec<PatchComparison> {
    let spectrum = illuminant.spectrum();
    let white = white_xyz(&spectrum);
    let light_rgb = illuminant_linear_srgb(&spectrum);
    (0..PATCH_COUNT)
        .map(|patch| {
            let spectral_xyz = reflectance_xyz(&spectrum, &patch_reflectance(patch));
            let approx_xyz = 100.0 * linear_srgb_to_xyz(patch_linear_srgb(patch) * light_rgb);
            PatchComparison {
                patch,
                spectral_xyz,
                approx_xyz,
                delta_e2000: delta_e2000(lab(spectral_xyz, white), lab(approx_xyz, white)),
            }
        })
        .collect()
}

/// Mean and maximum ΔE2000 over a chart.
pub fn mean_and_max(rows: &[PatchComparison]) -> (f64, f64) {
    let sum: f64 = rows.iter().map(|r| r.delta_e2000).sum();
    let max = rows.iter().map(|r| r.delta_e2000).fold(0.0, f64::max);
    (sum / rows.len().max(1) as f64, max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::spectrum::blackbody;
    use crate::colour::tristimulus::{chromaticity, srgb_encode};

    #[test]
    fn under_d65_the_rgb_product_is_the_spectral_result() {
        for row in compare_chart(Illuminant::D65) {
            assert!(row.delta_e2000 < 0.05, "{}: {}", row.name(), row.delta_e2000);
        }
    }

    #[test]
    fn under_a_the_rgb_product_is_visibly_off() {
        let (mean, max) = mean_and_max(&compare_chart(Illuminant::A));
        assert!(mean > 1.0 && max > 3.0, "mean {mean}, max {max}");
    }

    #[test]
    fn blackbody_6504_k_has_the_planckian_chromaticity() {
        // colour-science 0.4.7, computed once:
        // XYZ_to_xy(sd_to_XYZ(sd_blackbody(6504, SpectralShape(360, 830, 1)),
        // CIE 1931 2°)) = (0.313465, 0.323569): ASTM E308 on a 1 nm grid over
        // 360–830 nm, independent of this module's 5 nm, 380–780 nm sums.
        // (D65, at the same CCT, lies above the Planckian locus: 0.3127, 0.3290.)
        let expected = glam::DVec2::new(0.313_465, 0.323_569);
        let xy = chromaticity(white_xyz(&blackbody(6504.0)));
        assert!((xy - expected).abs().max_element() < 1e-3, "{xy}");
    }

    /// D. Pascale, "RGB coordinates of the Macbeth ColorChecker" (BabelColor,
    /// 2006): sRGB (D65) of the average of 30 charts, 8 bits, chart order.
    const PUBLISHED_SRGB8: [[u8; 3]; PATCH_COUNT] = [
        [115, 82, 68],
        [194, 150, 130],
        [98, 122, 157],
        [87, 108, 67],
        [133, 128, 177],
        [103, 189, 170],
        [214, 126, 44],
        [80, 91, 166],
        [193, 90, 99],
        [94, 60, 108],
        [157, 188, 64],
        [224, 163, 46],
        [56, 61, 150],
        [70, 148, 73],
        [175, 54, 60],
        [231, 199, 31],
        [187, 86, 149],
        [8, 133, 161],
        [243, 243, 242],
        [200, 200, 200],
        [160, 160, 160],
        [122, 122, 121],
        [85, 85, 85],
        [52, 52, 52],
    ];

    #[test]
    fn colorchecker_under_d65_is_near_its_published_srgb() {
        // Ohta measured one chart; BabelColor averaged 30 later ones, so the
        // two differ by a few 8-bit steps (most on the saturated blue and
        // cyan, whose red is clipped at 0).
        let mut worst: f64 = 0.0;
        let mut total = 0.0;
        for (patch, published) in PUBLISHED_SRGB8.iter().enumerate() {
            let rgb = patch_linear_srgb(patch);
            for (channel, &p) in published.iter().enumerate() {
                let ours = 255.0 * srgb_encode(rgb[channel].clamp(0.0, 1.0));
                let diff = (ours - f64::from(p)).abs();
                worst = worst.max(diff);
                total += diff;
            }
        }
        let mean = total / (3 * PATCH_COUNT) as f64;
        assert!(
            worst < 12.0 && mean < 3.0,
            "worst {worst}, mean {mean} (8-bit steps)"
        );
    }
}
