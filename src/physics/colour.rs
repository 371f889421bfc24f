//! Colour as the lab computes it: linear RGB, the tint that light of one
//! colour takes from a surface of another, and the luminance Y that error
//! measures and noise estimates are given on.
//!
//! The RGB product of [`tint`] is the lecture's approximation. A spectral mode
//! replaces it, and only it: the tristimulus values of the reflectance times
//! the illuminant's spectrum, integrated against the colour-matching
//! functions, then brought back to linear RGB. Every caller (the reference,
//! the probe, the shaders' `tint` in `shaders/common.wgsl`) goes through here.

use glam::DVec3;

/// Rec. 709 / sRGB luminance weights of linear R, G, B (sum 1).
pub const LUMINANCE_WEIGHTS: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// Y = 0.2126 R + 0.7152 G + 0.0722 B of a linear RGB colour.
pub fn luminance(rgb: [f64; 3]) -> f64 {
    LUMINANCE_WEIGHTS[0] * rgb[0] + LUMINANCE_WEIGHTS[1] * rgb[1] + LUMINANCE_WEIGHTS[2] * rgb[2]
}

/// The colour light of colour `light` (linear RGB factors of Φ) takes when
/// reflected by a surface of BRDF colour `surface`: L = tint · (f_r / c) E V.
/// In RGB this is the per-channel product (the spectral tristimulus would
/// replace it here).
pub fn tint(surface: DVec3, light: DVec3) -> DVec3 {
    surface * light
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_has_unit_luminance_and_weights_follow_rec709() {
        assert!((luminance([1.0, 1.0, 1.0]) - 1.0).abs() < 1e-12);
        assert_eq!(luminance([0.0, 1.0, 0.0]), 0.7152);
        assert_eq!(luminance([0.0, 0.0, 2.0]), 2.0 * 0.0722);
    }

    #[test]
    fn tint_is_the_per_channel_product() {
        let t = tint(DVec3::new(0.5, 1.0, 0.0), DVec3::new(2.0, 0.25, 7.0));
        assert_eq!(t, DVec3::new(1.0, 0.25, 0.0));
    }
}
