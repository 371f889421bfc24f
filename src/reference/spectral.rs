//! The reference under a spectral light: it integrates the reflected
//! spectrum itself, sample by sample, instead of trusting RGB products.
//!
//! The radiance reflected towards the eye at wavelength λ is
//! L(λ) = (f_r / c) · E · V · R(λ) · E_rel(λ): only the reflectance R and the
//! light's relative emission E_rel depend on λ. For every primary sample the
//! reference forms R(λ) E_rel(λ) on the 5 nm grid, sums it against x̄, ȳ, z̄
//! (ASTM E308 direct summation) into X, Y, Z, and takes linear sRGB from
//! there; the wavelength-free factor multiplies afterwards. E_rel is the
//! illuminant scaled so that a perfect white reflects the luminance of the
//! light's RGB colour (`colour::shading`'s normalization).

use crate::colour::data::cmfs;
use crate::colour::shading::material_reflectance;
use crate::colour::spectrum::SAMPLES;
use crate::colour::tristimulus::srgb_to_xyz_matrix;
use crate::colour::{Illuminant, Spectrum, uplift_linear_srgb};
use crate::physics::colour::luminance;
use crate::scene::Material;
use glam::{DMat3, DVec3};

/// A spectral light and the reflectances it meets.
#[derive(Clone, Debug)]
pub(super) struct SpectralLight {
    /// E_rel(λ) = Y_light · S(λ) / Σ S(λ) ȳ(λ).
    emission: Spectrum,
    /// One per reference material (the scene's, then the default).
    reflectances: Vec<Spectrum>,
    /// The reflectance uplifted from the settings' override colour.
    override_reflectance: Option<Spectrum>,
    /// XYZ → linear sRGB.
    to_rgb: DMat3,
}

impl SpectralLight {
    pub fn new(
        illuminant: Illuminant,
        light_rgb: DVec3,
        materials: &[Material],
        color_override: Option<DVec3>,
    ) -> Self {
        let s = illuminant.spectrum();
        let y_bar = &cmfs()[1];
        let white_y: f64 = (0..SAMPLES).map(|i| s.0[i] * y_bar.0[i]).sum();
        Self {
            emission: s * (luminance(light_rgb.to_array()) / white_y),
            reflectances: materials
                .iter()
                .map(|m| material_reflectance(&m.name, m.base_color.truncate().as_dvec3()))
                .collect(),
            override_reflectance: color_override.map(|c| uplift_linear_srgb(c).spectrum()),
            to_rgb: srgb_to_xyz_matrix().inverse(),
        }
    }

    /// Linear sRGB of light reflected by material `material` (reference
    /// index), or by the override colour when there is one, per unit of
    /// the wavelength-free factor (f_r / c) · E · V.
    pub fn reflected_rgb(&self, material: usize) -> DVec3 {
        let r = self
            .override_reflectance
            .as_ref()
            .unwrap_or(&self.reflectances[material]);
        let [x_bar, y_bar, z_bar] = cmfs();
        let mut xyz = DVec3::ZERO;
        for i in 0..SAMPLES {
            let reflected = r.0[i] * self.emission.0[i];
            xyz += reflected * DVec3::new(x_bar.0[i], y_bar.0[i], z_bar.0[i]);
        }
        self.to_rgb * xyz
    }
}
