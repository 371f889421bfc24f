//! From radiance to a displayed value: exposure, then the sRGB transfer.
//! Shared by every image the lab writes so that the GPU's PNG and the
//! reference's PNG of the same radiance are the same bytes.

use super::real::Real;

/// L · 2^EV: the exposed value of radiance L at exposure `ev` (EV).
pub fn expose<S: Real>(radiance: S, exposure_ev: S) -> S {
    radiance * S::lit(2.0).powf(exposure_ev)
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value, clamped to [0, 1].
pub fn srgb_encode<S: Real>(linear: S) -> S {
    let x = linear.max(S::zero()).min(S::one());
    if x.is_nan() {
        S::zero()
    } else if x <= S::lit(0.003_130_8) {
        S::lit(12.92) * x
    } else {
        S::lit(1.055) * x.powf(S::lit(1.0 / 2.4)) - S::lit(0.055)
    }
}

/// The inverse transfer: an sRGB-encoded value in [0, 1] to linear.
pub fn srgb_decode<S: Real>(encoded: S) -> S {
    if encoded <= S::lit(0.040_45) {
        encoded / S::lit(12.92)
    } else {
        ((encoded + S::lit(0.055)) / S::lit(1.055)).powf(S::lit(2.4))
    }
}

/// An 8-bit display value of radiance L at exposure `ev`.
pub fn display_byte(radiance: f64, exposure_ev: f64) -> u8 {
    (srgb_encode(expose(radiance, exposure_ev)) * 255.0).round() as u8
}

/// The share of lit pixels auto exposure keeps below white.
pub const AUTO_EXPOSURE_PERCENTILE: f64 = 0.95;
/// Where that percentile is shown (linear, before the sRGB transfer).
pub const AUTO_EXPOSURE_TARGET: f64 = 0.8;

/// The exposure (EV) that shows the 95th percentile of `luminances` (the
/// lit pixels' luminance, W/m²/sr) at 0.8 linear: bright enough to read,
/// highlights kept. None when nothing is lit (or nothing is finite).
pub fn auto_exposure_ev(luminances: &[f64]) -> Option<f64> {
    let mut lit: Vec<f64> = luminances
        .iter()
        .copied()
        .filter(|l| l.is_finite() && *l > 0.0)
        .collect();
    if lit.is_empty() {
        return None;
    }
    let rank = ((lit.len() - 1) as f64 * AUTO_EXPOSURE_PERCENTILE).round() as usize;
    let (_, high, _) = lit.select_nth_unstable_by(rank, f64::total_cmp);
    Some((AUTO_EXPOSURE_TARGET / *high).log2().clamp(-30.0, 30.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_exposure_shows_the_95th_percentile_at_0_8() {
        let lum: Vec<f64> = (1..=100).map(|i| i as f64 * 1e-3).collect();
        let ev = auto_exposure_ev(&lum).unwrap();
        // The 95th percentile of 0.001..0.1 is 0.095.
        assert!((expose(0.095, ev) - 0.8).abs() < 1e-3 * 0.8, "{ev}");
        assert_eq!(auto_exposure_ev(&[0.0, f64::NAN]), None);
        // A million times brighter (a far sun): the same displayed image.
        let far: Vec<f64> = lum.iter().map(|l| l * 1e6).collect();
        let ev_far = auto_exposure_ev(&far).unwrap();
        assert!((expose(0.095e6, ev_far) - 0.8).abs() < 1e-3);
    }

    #[test]
    fn srgb_round_trips_and_hits_known_values() {
        assert_eq!(srgb_encode(0.0_f64), 0.0);
        assert!((srgb_encode(1.0_f64) - 1.0).abs() < 1e-12);
        assert!((srgb_encode(0.18_f64) - 0.461_356).abs() < 1e-5);
        for x in [0.001_f64, 0.02, 0.5, 0.9] {
            assert!((srgb_decode(srgb_encode(x)) - x).abs() < 1e-12);
        }
        assert_eq!(display_byte(f64::NAN, 0.0), 0);
        assert_eq!(display_byte(1e9, 0.0), 255);
    }

    #[test]
    fn one_ev_doubles() {
        assert_eq!(expose(0.25_f64, 1.0), 0.5);
    }
}
