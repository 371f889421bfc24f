//! From spectra to numbers the eye agrees with: CIE XYZ, linear sRGB, CIE Lab.

use super::data::cmfs;
use super::spectrum::Spectrum;
use glam::{DMat3, DVec2, DVec3};

/// CIE XYZ of light of relative power `illuminant` reflected by
/// `reflectance`, with Y of the perfect white under that illuminant = 100.
///
/// CIE 015:2018 §7.1–7.2 (ASTM E308's direct summation on a 5 nm grid):
/// X = k Σ S(λ) R(λ) x̄(λ) Δλ, and the same with ȳ, z̄, where
/// k = 100 / Σ S(λ) ȳ(λ) Δλ; Δλ cancels.
pub fn reflectance_xyz(illuminant: &Spectrum, reflectance: &Spectrum) -> DVec3 {
    let [x_bar, y_bar, z_bar] = cmfs();
    let stimulus = *illuminant * *reflectance;
    let sum = |cmf: &Spectrum| -> f64 { stimulus.0.iter().zip(cmf.0.iter()).map(|(s, c)| s * c).sum() };
    let k = 100.0
        / illuminant
            .0
            .iter()
            .zip(y_bar.0.iter())
            .map(|(s, y)| s * y)
            .sum::<f64>();
    k * DVec3::new(sum(x_bar), sum(y_bar), sum(z_bar))
}

/// XYZ of the perfect reflecting diffuser (R = 1) under `illuminant`: the
/// illuminant's white point, Y = 100.
pub fn white_xyz(illuminant: &Spectrum) -> DVec3 {
    reflectance_xyz(illuminant, &Spectrum::constant(1.0))
}

/// Chromaticity (x, y) = (X, Y) / (X + Y + Z).
pub fn chromaticity(xyz: DVec3) -> DVec2 {
    DVec2::new(xyz.x, xyz.y) / xyz.element_sum()
}

/// sRGB's primaries and white (IEC 61966-2-1 / ITU-R BT.709): x, y of R, G, B, D65.
const SRGB_PRIMARIES_XY: [[f64; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
const SRGB_WHITE_XY: [f64; 2] = [0.3127, 0.3290];

/// The matrix from linear sRGB to XYZ (Y of white = 1), derived from the
/// primaries and white point (SMPTE RP 177): columns are the primaries' XYZ,
/// each scaled so that R = G = B = 1 gives the white.
pub fn srgb_to_xyz_matrix() -> DMat3 {
    let xyz_of = |[x, y]: [f64; 2]| DVec3::new(x / y, 1.0, (1.0 - x - y) / y);
    let primaries = DMat3::from_cols(
        xyz_of(SRGB_PRIMARIES_XY[0]),
        xyz_of(SRGB_PRIMARIES_XY[1]),
        xyz_of(SRGB_PRIMARIES_XY[2]),
    );
    let scale = primaries.inverse() * xyz_of(SRGB_WHITE_XY);
    primaries * DMat3::from_diagonal(scale)
}

/// Linear sRGB of an XYZ colour (both with white's Y = 1; no clamping:
/// colours outside the sRGB gamut get components below 0 or above 1).
pub fn xyz_to_linear_srgb(xyz: DVec3) -> DVec3 {
    srgb_to_xyz_matrix().inverse() * xyz
}

/// XYZ of a linear sRGB colour (white's Y = 1).
pub fn linear_srgb_to_xyz(rgb: DVec3) -> DVec3 {
    srgb_to_xyz_matrix() * rgb
}

/// The sRGB transfer function (IEC 61966-2-1): linear 0..1 → encoded 0..1.
pub fn srgb_encode(linear: f64) -> f64 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// CIE 1976 L*a*b* of `xyz` relative to the reference white `white` (same
/// scale), CIE 015:2018 §8.2.1 with the exact constants ε = 216/24389 and
/// κ = 24389/27 for the linear segment near black.
pub fn lab(xyz: DVec3, white: DVec3) -> DVec3 {
    const EPSILON: f64 = 216.0 / 24389.0;
    const KAPPA: f64 = 24389.0 / 27.0;
    let f = |t: f64| {
        if t > EPSILON {
            t.cbrt()
        } else {
            (KAPPA * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(xyz.x / white.x), f(xyz.y / white.y), f(xyz.z / white.z));
    DVec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::Illuminant;

    #[test]
    fn perfect_white_under_d65_is_the_cie_white_point() {
        // CIE 015:2018, white point of D65, 2° observer: X = 95.047, Y = 100, Z = 108.883.
        let w = white_xyz(&Illuminant::D65.spectrum());
        assert!(
            (w - DVec3::new(95.047, 100.0, 108.883)).abs().max_element() < 0.1,
            "{w}"
        );
    }

    #[test]
    fn perfect_white_under_a_is_the_cie_white_point() {
        // CIE 015:2018, white point of A, 2° observer: X = 109.850, Y = 100, Z = 35.585.
        let w = white_xyz(&Illuminant::A.spectrum());
        assert!(
            (w - DVec3::new(109.850, 100.0, 35.585)).abs().max_element() < 0.1,
            "{w}"
        );
    }

    #[test]
    fn srgb_matrix_is_the_iec_matrix() {
        // IEC 61966-2-1 publishes the matrix rounded to 4 decimals.
        let published = DMat3::from_cols_array(&[
            0.4124, 0.2126, 0.0193, 0.3576, 0.7152, 0.1192, 0.1805, 0.0722, 0.9505,
        ]);
        let m = srgb_to_xyz_matrix();
        for (a, b) in m.to_cols_array().iter().zip(published.to_cols_array()) {
            assert!((a - b).abs() < 6e-5, "{a} {b}");
        }
        let rgb = DVec3::new(0.2, 0.5, 0.9);
        assert!(
            (xyz_to_linear_srgb(linear_srgb_to_xyz(rgb)) - rgb)
                .abs()
                .max_element()
                < 1e-12
        );
    }

    #[test]
    fn lab_of_white_grey_and_black() {
        let white = DVec3::new(95.047, 100.0, 108.883);
        assert!((lab(white, white) - DVec3::new(100.0, 0.0, 0.0)).length() < 1e-12);
        // Y/Yn = 0.18 (middle grey) is L* = 49.496.
        assert!((lab(white * 0.18, white).x - 49.496).abs() < 1e-3);
        assert_eq!(lab(DVec3::ZERO, white), DVec3::ZERO);
    }

    #[test]
    fn srgb_encoding_is_continuous_at_the_knee() {
        let below = srgb_encode(0.003_130_8);
        let above = srgb_encode(0.003_130_8 + 1e-12);
        assert!((below - above).abs() < 1e-6);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-12);
    }
}
