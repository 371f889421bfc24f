//! A reflectance spectrum for a material that only has an RGB colour.
//!
//! Jakob & Hanika, "A Low-Dimensional Function Space for Efficient Spectral
//! Upsampling", Computer Graphics Forum 38(2), 2019: the reflectance is a
//! sigmoid of a quadratic in wavelength,
//!
//!   r(λ) = S(c₀ t² + c₁ t + c₂),  S(x) = ½ + x / (2 √(1 + x²)),
//!   t = (λ − 380 nm) / (780 nm − 380 nm),
//!
//! smooth (at most one bump or dip, like most paints and pigments) and in
//! 0..1 by construction, so it stays a physical reflectance. The three
//! coefficients are fitted so that the spectrum, lit by D65 (sRGB's white),
//! has the requested colour: a Gauss-Newton solve on the CIE Lab residual,
//! as the paper's optimizer does. The paper tabulates the fit on a 64³ grid
//! for speed; here one colour at a time is solved directly (a few hundred
//! spectrum integrations), which needs no table.

use super::data::Illuminant;
use super::spectrum::{LAMBDA_MAX_NM, LAMBDA_MIN_NM, Spectrum};
use super::tristimulus::{lab, linear_srgb_to_xyz, reflectance_xyz};
use glam::{DMat3, DVec3};

/// Components are clamped to this interval: the sigmoid reaches 0 and 1 only
/// at infinity, so a perfectly black or white component has no finite fit.
const RGB_MIN: f64 = 1e-3;
const RGB_MAX: f64 = 1.0 - 1e-3;
/// The fit walks from mid grey (all coefficients 0) to the target in this
/// many steps, each starting from the previous solution, as the paper's
/// optimizer walks outward from the centre of its grid: saturated colours
/// need large coefficients that a cold start does not reach.
const CONTINUATION_STEPS: usize = 8;
const MAX_ITERATIONS: usize = 50;
/// Stop when the Lab residual is below this (ΔE*ab units).
const TOLERANCE_LAB: f64 = 1e-7;

/// A smooth reflectance r(λ) = S(c₀ t² + c₁ t + c₂) (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SigmoidReflectance {
    /// c₀, c₁, c₂ for t = (λ − 380 nm) / 400 nm.
    pub coefficients: [f64; 3],
}

impl SigmoidReflectance {
    /// The reflectance at `nm` (0..1).
    pub fn at(&self, nm: f64) -> f64 {
        let t = (nm - LAMBDA_MIN_NM) / (LAMBDA_MAX_NM - LAMBDA_MIN_NM);
        let [c0, c1, c2] = self.coefficients;
        let x = (c0 * t + c1) * t + c2;
        0.5 + x / (2.0 * (1.0 + x * x).sqrt())
    }

    /// The reflectance sampled on the spectral grid.
    pub fn spectrum(&self) -> Spectrum {
        Spectrum::from_fn(|nm| self.at(nm))
    }
}

/// The smooth reflectance whose colour under D65 is the linear sRGB colour
/// `rgb` (each component clamped to 0.001 … 0.999). In-gamut colours are
/// matched to ΔE2000 well below 0.01; for a colour no reflectance can have,
/// the closest fit is returned.
pub fn uplift_linear_srgb(rgb: DVec3) -> SigmoidReflectance {
    let d65 = Illuminant::D65.spectrum();
    let white = linear_srgb_to_xyz(DVec3::ONE);
    let target_rgb = rgb.clamp(DVec3::splat(RGB_MIN), DVec3::splat(RGB_MAX));
    let lab_of = |c: DVec3| {
        let r = SigmoidReflectance {
            coefficients: c.to_array(),
        };
        lab(reflectance_xyz(&d65, &r.spectrum()) / 100.0, white)
    };
    let mut c = DVec3::ZERO;
    for step in 1..=CONTINUATION_STEPS {
        let s = step as f64 / CONTINUATION_STEPS as f64;
        let goal = lab(linear_srgb_to_xyz(DVec3::splat(0.5).lerp(target_rgb, s)), white);
        c = gauss_newton(c, goal, &lab_of);
    }
    SigmoidReflectance {
        coefficients: c.to_array(),
    }
}

/// Gauss-Newton on residual(c) = lab_of(c) − goal, with a forward-difference
/// Jacobian and step halving when a full step does not reduce the residual.
fn gauss_newton(mut c: DVec3, goal: DVec3, lab_of: &impl Fn(DVec3) -> DVec3) -> DVec3 {
    const H: f64 = 1e-6;
    let mut residual = lab_of(c) - goal;
    for _ in 0..MAX_ITERATIONS {
        if residual.length() < TOLERANCE_LAB {
            break;
        }
        let jacobian = DMat3::from_cols(
            (lab_of(c + DVec3::X * H) - goal - residual) / H,
            (lab_of(c + DVec3::Y * H) - goal - residual) / H,
            (lab_of(c + DVec3::Z * H) - goal - residual) / H,
        );
        if jacobian.determinant().abs() < 1e-300 {
            break;
        }
        let step = jacobian.inverse() * -residual;
        let mut scale = 1.0;
        let improved = loop {
            let trial = c + step * scale;
            let r = lab_of(trial) - goal;
            if r.length() < residual.length() {
                break Some((trial, r));
            }
            scale *= 0.5;
            if scale < 1e-4 {
                break None;
            }
        };
        match improved {
            Some((trial, r)) => (c, residual) = (trial, r),
            None => break,
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::delta_e2000;

    fn colour_under_d65(r: &SigmoidReflectance) -> DVec3 {
        let xyz = reflectance_xyz(&Illuminant::D65.spectrum(), &r.spectrum()) / 100.0;
        lab(xyz, linear_srgb_to_xyz(DVec3::ONE))
    }

    #[test]
    fn mid_grey_is_flat() {
        let r = uplift_linear_srgb(DVec3::splat(0.5));
        let s = r.spectrum();
        assert!(s.0.iter().all(|v| (v - 0.5).abs() < 2e-3), "{:?}", r);
    }

    #[test]
    fn uplifted_spectra_reproduce_their_colour_and_stay_reflectances() {
        let white = linear_srgb_to_xyz(DVec3::ONE);
        let colours = [
            DVec3::new(0.8, 0.2, 0.1),
            DVec3::new(0.05, 0.6, 0.1),
            DVec3::new(0.1, 0.2, 0.9),
            DVec3::new(0.9, 0.9, 0.1),
            DVec3::new(0.18, 0.18, 0.18),
            DVec3::new(0.95, 0.95, 0.95),
            DVec3::new(0.9, 0.1, 0.9),
            DVec3::new(0.03, 0.03, 0.03),
        ];
        for rgb in colours {
            let r = uplift_linear_srgb(rgb);
            let got = colour_under_d65(&r);
            let want = lab(linear_srgb_to_xyz(rgb), white);
            assert!(
                delta_e2000(got, want) < 0.01,
                "{rgb}: ΔE {}",
                delta_e2000(got, want)
            );
            assert!(r.spectrum().0.iter().all(|v| (0.0..=1.0).contains(v)));
        }
    }

    #[test]
    fn uplifted_chart_under_a_beats_the_rgb_product() {
        // The point of an uplift: from a patch's RGB alone, a smooth spectrum
        // predicts its colour under tungsten light better than RGB × RGB.
        use crate::colour::chart::{compare_chart, mean_and_max, patch_linear_srgb};
        use crate::colour::{patch_reflectance, white_xyz};
        let a = Illuminant::A.spectrum();
        let white = white_xyz(&a);
        let uplift_mean = (0..crate::colour::PATCH_COUNT)
            .map(|p| {
                let uplifted = reflectance_xyz(&a, &uplift_linear_srgb(patch_linear_srgb(p)).spectrum());
                let measured = reflectance_xyz(&a, &patch_reflectance(p));
                delta_e2000(lab(uplifted, white), lab(measured, white))
            })
            .sum::<f64>()
            / crate::colour::PATCH_COUNT as f64;
        let (rgb_mean, _) = mean_and_max(&compare_chart(Illuminant::A));
        assert!(
            uplift_mean < 0.5 * rgb_mean,
            "uplift {uplift_mean}, RGB product {rgb_mean}"
        );
    }
}
