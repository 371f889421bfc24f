//! The reference's image: radiance with its visibility, coverage and noise.

use crate::physics::display::display_byte;
use std::time::Duration;

/// The scalar the noise estimate is given on (`physics::colour`).
pub use crate::physics::colour::luminance;

/// A rendered reference image; every buffer is row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceImage {
    pub width: u32,
    pub height: u32,
    /// Reflected radiance L (W/m²/sr, linear RGB): the mean over the pixel's
    /// primary samples, 0 for samples that hit nothing.
    pub radiance: Vec<[f64; 3]>,
    /// Mean visibility V ∈ [0, 1] over the primary samples that hit geometry
    /// (0 where none did). For a point light V ∈ {0, 1} per sample; for a
    /// sphere light it is the visible fraction of the light's cosine-weighted
    /// solid angle, Σ V_i cos⁺θ_i / Σ cos⁺θ_i = E_visible / E; 0 where the
    /// whole light is below the horizon (attached shadow); 1 with shadows off.
    pub visibility: Vec<f32>,
    /// Fraction of the pixel's primary samples that hit geometry: 0 is background.
    pub coverage: Vec<f32>,
    /// Standard error of the pixel's luminance estimate (W/m²/sr): from the
    /// sphere light's strata with one sample per pixel, from the pixel's own
    /// strata with more; 0 where the estimate is exact (a point light at one
    /// sample per pixel, background).
    pub noise: Vec<f32>,
    /// False when the noise could not be estimated (one light sample and one
    /// sample per pixel: nothing to compare); `noise` is then 0.
    pub noise_known: bool,
    pub stats: RenderStats,
}

/// What a render cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub primary_rays: u64,
    pub shadow_rays: u64,
    /// Wall time of the render (not the BVH build).
    pub elapsed: Duration,
    pub spp: u32,
    pub light_samples: u32,
}

impl RenderStats {
    pub fn rays(&self) -> u64 {
        self.primary_rays + self.shadow_rays
    }
}

/// The image's noise in a few numbers, over the covered pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoiseSummary {
    pub known: bool,
    /// Mean luminance of the covered pixels (W/m²/sr).
    pub mean_luminance: f64,
    /// √(mean σ²): the RMS of the per-pixel standard errors (W/m²/sr).
    pub rms_std_error: f64,
    pub max_std_error: f64,
    /// rms_std_error / mean_luminance: the image's relative noise.
    pub relative: f64,
}

impl ReferenceImage {
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Row-major index of pixel (i, j).
    pub fn index(&self, i: u32, j: u32) -> usize {
        j as usize * self.width as usize + i as usize
    }

    /// The displayed image: L · 2^EV, then the sRGB transfer, opaque
    /// (the same bytes as the GPU's PNG of the same radiance).
    pub fn to_display_rgba8(&self, exposure_ev: f64) -> image::RgbaImage {
        let mut bytes = Vec::with_capacity(self.pixel_count() * 4);
        for rgb in &self.radiance {
            bytes.extend(rgb.map(|c| display_byte(c, exposure_ev)));
            bytes.push(255);
        }
        image::RgbaImage::from_raw(self.width, self.height, bytes)
            .unwrap_or_else(|| image::RgbaImage::new(self.width, self.height))
    }

    /// Pixel (x, y)'s linear radiance (W/m²/sr) in RGB and its coverage in
    /// alpha: what an EXR holds.
    pub fn linear_rgba(&self, x: usize, y: usize) -> [f32; 4] {
        let i = y * self.width as usize + x;
        let [r, g, b] = self.radiance[i].map(|c| c as f32);
        [r, g, b, self.coverage[i]]
    }

    /// What the GPU's `error` and `ref-visibility` views compare with:
    /// rgb = L (W/m²/sr), a = V.
    pub fn to_comparison(&self) -> crate::gpu::ComparisonImage {
        crate::gpu::ComparisonImage {
            width: self.width,
            height: self.height,
            texels: self
                .radiance
                .iter()
                .zip(&self.visibility)
                .map(|(rgb, &v)| [rgb[0] as f32, rgb[1] as f32, rgb[2] as f32, v])
                .collect(),
        }
    }

    pub fn noise_summary(&self) -> NoiseSummary {
        let mut covered = 0usize;
        let (mut sum_y, mut sum_var, mut max) = (0.0, 0.0, 0.0_f64);
        for ((rgb, &cov), &se) in self.radiance.iter().zip(&self.coverage).zip(&self.noise) {
            if cov > 0.0 {
                covered += 1;
                sum_y += luminance(*rgb);
                sum_var += (se as f64) * (se as f64);
                max = max.max(se as f64);
            }
        }
        if covered == 0 {
            return NoiseSummary {
                known: self.noise_known,
                ..NoiseSummary::default()
            };
        }
        let mean_luminance = sum_y / covered as f64;
        let rms_std_error = (sum_var / covered as f64).sqrt();
        NoiseSummary {
            known: self.noise_known,
            mean_luminance,
            rms_std_error,
            max_std_error: max,
            relative: if mean_luminance > 0.0 {
                rms_std_error / mean_luminance
            } else {
                0.0
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_pixels() -> ReferenceImage {
        ReferenceImage {
            width: 2,
            height: 1,
            radiance: vec![[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]],
            visibility: vec![1.0, 0.0],
            coverage: vec![1.0, 0.0],
            noise: vec![0.1, 0.0],
            noise_known: true,
            stats: RenderStats::default(),
        }
    }

    #[test]
    fn display_bytes_follow_exposure_and_srgb() {
        let img = two_pixels();
        let rgba = img.to_display_rgba8(-1.0);
        // 1 · 2^−1 = 0.5 linear is 188 in sRGB.
        assert_eq!(rgba.get_pixel(0, 0).0, [188, 188, 188, 255]);
        assert_eq!(rgba.get_pixel(1, 0).0, [0, 0, 0, 255]);
    }

    #[test]
    fn exr_holds_radiance_and_coverage() {
        let img = two_pixels();
        assert_eq!(img.linear_rgba(0, 0), [1.0, 1.0, 1.0, 1.0]);
        assert_eq!(img.linear_rgba(1, 0)[3], 0.0);
    }

    #[test]
    fn noise_summary_counts_covered_pixels_only() {
        let s = two_pixels().noise_summary();
        assert!((s.mean_luminance - 1.0).abs() < 1e-12);
        assert!((s.rms_std_error - 0.1).abs() < 1e-7);
        assert!((s.relative - 0.1).abs() < 1e-7);
    }
}
