//! A spectrum sampled on the visible domain, and Planck's law.

/// Shortest wavelength sampled (nm).
pub const LAMBDA_MIN_NM: f64 = 380.0;
/// Longest wavelength sampled (nm).
pub const LAMBDA_MAX_NM: f64 = 780.0;
/// Sampling interval (nm): CIE 015:2018's 5 nm tables and N. Ohta's
/// reflectances share it, so no table is interpolated.
pub const LAMBDA_STEP_NM: f64 = 5.0;
/// Number of samples: 380, 385, …, 780 nm.
pub const SAMPLES: usize = 81;

/// Lowest colour temperature accepted for a blackbody (K).
pub const BLACKBODY_MIN_K: f64 = 1000.0;
/// Highest colour temperature accepted for a blackbody (K).
pub const BLACKBODY_MAX_K: f64 = 25000.0;

/// Second radiation constant c₂ = hc/k (m·K), the value CIE 015:2018 uses
/// for Planckian radiators (ITS-90).
const C2_M_K: f64 = 1.4388e-2;

/// A spectral quantity (relative power, or reflectance in 0..1) at
/// [`SAMPLES`] wavelengths from [`LAMBDA_MIN_NM`] every [`LAMBDA_STEP_NM`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum(pub [f64; SAMPLES]);

impl Spectrum {
    /// The wavelength of sample `i` (nm).
    pub fn wavelength_nm(i: usize) -> f64 {
        LAMBDA_MIN_NM + LAMBDA_STEP_NM * i as f64
    }

    /// Every sampled wavelength, in order (nm).
    pub fn wavelengths_nm() -> impl Iterator<Item = f64> {
        (0..SAMPLES).map(Self::wavelength_nm)
    }

    /// `f(λ)` sampled at every wavelength (λ in nm).
    pub fn from_fn(f: impl Fn(f64) -> f64) -> Self {
        Self(std::array::from_fn(|i| f(Self::wavelength_nm(i))))
    }

    /// The same value at every wavelength (a perfect white is 1).
    pub fn constant(value: f64) -> Self {
        Self([value; SAMPLES])
    }

    /// (wavelength in nm, value) pairs, for tables and plots.
    pub fn samples(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.0
            .iter()
            .enumerate()
            .map(|(i, &v)| (Self::wavelength_nm(i), v))
    }

    /// The largest sample.
    pub fn max(&self) -> f64 {
        self.0.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    /// This spectrum scaled so that its largest sample is 1 (unchanged when
    /// it has no positive sample): spectra of different sources on one plot.
    pub fn normalized_to_peak(&self) -> Self {
        let peak = self.max();
        if peak > 0.0 { *self * (1.0 / peak) } else { *self }
    }
}

/// Spectrum × spectrum, wavelength by wavelength: what an illuminant's power
/// becomes after a reflectance (the spectral form of the lecture's
/// (r, g, b) · f_r).
impl std::ops::Mul for Spectrum {
    type Output = Spectrum;
    fn mul(self, rhs: Spectrum) -> Spectrum {
        Spectrum(std::array::from_fn(|i| self.0[i] * rhs.0[i]))
    }
}

impl std::ops::Mul<f64> for Spectrum {
    type Output = Spectrum;
    fn mul(self, rhs: f64) -> Spectrum {
        Spectrum(self.0.map(|v| v * rhs))
    }
}

/// The relative spectral power of a blackbody at `kelvin`, normalized to 100
/// at 560 nm as CIE illuminant A is. Planck's law for the spectral exitance,
/// M(λ, T) = c₁ λ⁻⁵ / (exp(c₂ / λT) − 1); c₁ cancels in the ratio.
/// `kelvin` must lie in [`BLACKBODY_MIN_K`] … [`BLACKBODY_MAX_K`]: callers
/// validate it (see [`crate::colour::Illuminant`]).
pub fn blackbody(kelvin: f64) -> Spectrum {
    let planck = |nm: f64| {
        let lambda_m = nm * 1e-9;
        // exp_m1 keeps the denominator exact when c₂/λT is small (hot bodies).
        lambda_m.powi(-5) / (C2_M_K / (lambda_m * kelvin)).exp_m1()
    };
    let at_560 = planck(560.0);
    Spectrum::from_fn(|nm| 100.0 * planck(nm) / at_560)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_is_380_to_780_every_5_nm() {
        let nm: Vec<f64> = Spectrum::wavelengths_nm().collect();
        assert_eq!(nm.len(), SAMPLES);
        assert_eq!(nm[0], LAMBDA_MIN_NM);
        assert_eq!(nm[SAMPLES - 1], LAMBDA_MAX_NM);
        assert_eq!(nm[1] - nm[0], LAMBDA_STEP_NM);
    }

    #[test]
    fn product_is_wavelength_by_wavelength() {
        let ramp = Spectrum::from_fn(|nm| nm);
        let half = Spectrum::constant(0.5);
        let p = ramp * half;
        assert_eq!(p.0[0], 190.0);
        assert_eq!(p.0[SAMPLES - 1], 390.0);
    }

    #[test]
    fn blackbody_is_100_at_560_nm_and_peaks_by_wien() {
        for kelvin in [BLACKBODY_MIN_K, 2856.0, 6504.0, BLACKBODY_MAX_K] {
            let s = blackbody(kelvin);
            assert!((s.0[36] - 100.0).abs() < 1e-9, "{kelvin} K at 560 nm");
            assert!(s.0.iter().all(|v| v.is_finite() && *v > 0.0));
        }
        // Wien: λ_max = 2.898e6 nm·K / T; 5000 K peaks at 579.6 nm.
        let s = blackbody(5000.0);
        let (peak_nm, _) = s.samples().fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        assert!((peak_nm - 579.6_f64).abs() <= 2.5, "{peak_nm}");
    }

    #[test]
    fn blackbody_at_2856_k_is_illuminant_a() {
        // CIE 015:2018 defines illuminant A by Planck's law at 2848 K with
        // the older c₂ = 1.435e-2 m·K: the same curve as 2848 · 1.4388/1.435
        // ≈ 2856 K with today's c₂.
        let a = crate::colour::data::Illuminant::A.spectrum();
        let bb = blackbody(2848.0 * 1.4388 / 1.435);
        for (x, y) in a.0.iter().zip(bb.0.iter()) {
            assert!((x - y).abs() / x < 2e-4, "{x} {y}");
        }
    }
}
