//! The `delta-e` view on the GPU: ΔE2000 per pixel between the image under
//! the colour model shown and under the other one (spectral ↔ the lecture's
//! RGB product), both at the displayed exposure, in CIE Lab with the
//! illuminant's white as reference — `colour::shading::pixel_delta_e`, the
//! probe's and `lumlab colour`'s definition (DESIGN.md).
//!
//! With one light and direct lighting only the tint depends on the
//! wavelength (`colour::shading`), so the camera pass shades each pixel
//! both ways at once: every material carries the other model's colour
//! (`Material::other_model_color`), the globals the other model's light and
//! override colours and the matrix below; `shaders/delta_e.wgsl` holds CIE
//! Lab and CIEDE2000 in WGSL; the display maps ΔE to a fixed false-colour
//! scale (`colormap::DELTA_E_VIEW_MAX`). Without a spectral illuminant the
//! two models are one and ΔE is undefined: the view shows "nothing here".
//! A ray-traced sphere light's frames average ΔE itself, not the colours:
//! the two differ only in penumbrae, where V varies from frame to frame.

use super::spectral::ModelColours;
use super::uniforms::GlobalsRaw;
use crate::colour::Illuminant;
use crate::colour::tristimulus::{srgb_to_xyz_matrix, white_xyz};
use crate::settings::Settings;
use glam::DMat3;

/// The WGSL of CIE Lab and CIEDE2000 (part of the camera pass; the tests
/// run it alone against `colour`).
pub const WGSL: &str = include_str!("../../shaders/delta_e.wgsl");

/// Linear sRGB (white's Y = 1) → X/Xn, Y/Yn, Z/Zn, the XYZ relative to the
/// illuminant's white point (Y = 1): what CIE Lab takes, as in
/// `colour::shading::pixel_delta_e`.
pub fn lab_white_relative(illuminant: Illuminant) -> DMat3 {
    let white = white_xyz(&illuminant.spectrum()) / 100.0;
    DMat3::from_diagonal(white.recip()) * srgb_to_xyz_matrix()
}

/// `globals` with the `delta-e` view's fields filled from the settings and
/// both models' colours.
pub fn with_delta_e(globals: GlobalsRaw, settings: &Settings, colours: &ModelColours) -> GlobalsRaw {
    let illuminant = settings.colour.illuminant;
    let m = illuminant.map_or(DMat3::ZERO, lab_white_relative).as_mat3();
    GlobalsRaw {
        exposure_ev: settings.view.exposure_ev,
        other_light_color: colours.other.light.as_vec3().to_array(),
        delta_e_defined: illuminant.is_some() as u32,
        other_color_override: colours
            .other
            .color_override
            .unwrap_or_default()
            .as_vec3()
            .to_array(),
        lab_white_relative: [m.x_axis, m.y_axis, m.z_axis].map(|c| c.extend(0.0).to_array()),
        ..globals
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::chart::illuminant_linear_srgb;
    use glam::DVec3;

    #[test]
    fn the_illuminants_own_colour_is_the_reference_white() {
        for i in [
            Illuminant::D65,
            Illuminant::A,
            Illuminant::Fl11,
            Illuminant::Blackbody { kelvin: 2000.0 },
        ] {
            let t = lab_white_relative(i) * illuminant_linear_srgb(&i.spectrum());
            assert!((t - DVec3::ONE).abs().max_element() < 1e-12, "{i}: {t}");
        }
    }
}
