//! The lab's BRDF: a Lambert term mixed with a Blinn-Phong lobe,
//!
//! ```text
//! f_r(l, o) = c · ( k / π + (1 − k) · N(m) · cos^m θ_h ),
//! ```
//!
//! with h = normalize(l + o) and cos θ_h = max(0, n·h). The normalization N(m)
//! is a user choice so that its effect on energy can be seen.
//!
//! Hard cases have defined values, never NaN or Inf: the lobe is 1 for m = 0
//! (0^0 = 1); the specular term is 0 when l + o = 0; nothing is reflected when
//! n·l ≤ 0 or n·o ≤ 0. The lobe is computed as exp(m · ln cos θ_h) with
//! 1 − cos θ_h taken from |n − h|² / 2, so that m = 10^6 keeps its precision.

use super::real::{Float, FloatConst, One, Real, Vector3, Zero};

crate::named_enum! {
    /// The normalization N(m) of the Blinn-Phong lobe.
    pub enum Normalization {
        /// N = 1: the raw lobe; reflects less and less energy as m grows.
        None = "none",
        /// N = (m + 1) / 2π: normalizes the lobe over half-vectors, not energy.
        Ndf = "ndf",
        /// N = (m + 8) / 8π: the usual approximation; exceeds 1 at small m.
        Approx = "approx",
        /// N = (m + 2)(m + 4) / (8π (2^(−m/2) + m)): exact at normal incidence.
        Exact = "exact",
    }
}

impl Normalization {
    /// The formula, for tooltips and tables.
    pub fn formula(self) -> &'static str {
        match self {
            Self::None => "N(m) = 1",
            Self::Ndf => "N(m) = (m + 1) / 2π",
            Self::Approx => "N(m) = (m + 8) / 8π",
            Self::Exact => "N(m) = (m + 2)(m + 4) / (8π (2^(−m/2) + m))",
        }
    }

    /// N(m) for the exponent m ≥ 0.
    pub fn factor<S: Real>(self, m: S) -> S {
        let pi = S::PI();
        let lit = S::lit;
        match self {
            Self::None => S::one(),
            Self::Ndf => (m + S::one()) / (lit(2.0) * pi),
            Self::Approx => (m + lit(8.0)) / (lit(8.0) * pi),
            Self::Exact => {
                (m + lit(2.0)) * (m + lit(4.0)) / (lit(8.0) * pi * (lit(2.0).powf(-m / lit(2.0)) + m))
            }
        }
    }
}

/// The material parameters of the BRDF (the colour c is applied by the caller).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrdfParams<S> {
    /// Diffuse/specular mix k ∈ [0, 1]: 1 is pure Lambert.
    pub k: S,
    /// Blinn-Phong exponent m ≥ 0.
    pub m: S,
    pub norm: Normalization,
}

/// The two parts of f_r / c (1/sr): f_r = c · (diffuse + specular).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BrdfTerms<S> {
    /// k / π
    pub diffuse: S,
    /// (1 − k) · N(m) · cos^m θ_h
    pub specular: S,
}

impl<S: Real> BrdfTerms<S> {
    pub fn total(self) -> S {
        self.diffuse + self.specular
    }
}

/// ln(cos θ) from the gap d = 1 − cos θ ∈ [0, 1), accurate for small d where
/// ln(1 − d) would lose the digits of d in the subtraction. With x = d/(2 − d),
/// 1 − d = (1 − x)/(1 + x), so ln(1 − d) = −2 atanh x = −2 (x + x³/3 + x⁵/5 + …),
/// a series that stands in for log1p (which WGSL lacks) up to d = 0.1; the
/// shader uses the same code, and so does `f32` here (`f64` takes
/// [`super::power::ln_one_minus`], which runs in lanes). Beyond, ln(1 − d)
/// is exact enough: the lobe m ln cos θ only stays visible there for m < 70,
/// so its error stays below 70 ε.
pub fn ln_cos_from_gap<S: Real>(gap: S) -> S {
    if gap < S::lit(0.1) {
        // x ≤ 0.053: the terms up to x¹³/13 leave an error below x¹⁵/15 ≈ 5e-16 x.
        let x = gap / (S::lit(2.0) - gap);
        let x2 = x * x;
        let lit = S::lit;
        let tail = lit(1.0 / 7.0) + x2 * (lit(1.0 / 9.0) + x2 * (lit(1.0 / 11.0) + x2 * lit(1.0 / 13.0)));
        -lit(2.0) * x * (S::one() + x2 * (lit(1.0 / 3.0) + x2 * (lit(0.2) + x2 * tail)))
    } else {
        (S::one() - gap).ln()
    }
}

/// cos^m θ with the lab's conventions: 1 when m = 0 (0^0 = 1), 0 when
/// cos θ ≤ 0 and m > 0; `gap` is 1 − cos θ computed accurately by the caller.
#[inline(always)]
pub fn lobe<S: Real>(cos_theta: S, gap: S, m: S) -> S {
    if m <= S::zero() {
        S::one()
    } else if cos_theta <= S::zero() {
        S::zero()
    } else {
        S::power_from_gap(gap, m)
    }
}

/// f_r / c for the unit normal `n`, unit light direction `l` and unit view
/// direction `o` (all pointing away from the surface). The horizons and
/// Lambert alone inline (the reference's samples call it in their loops),
/// the lobe in `specular`.
#[inline(always)]
pub fn blinn_phong<V: Vector3>(n: V, l: V, o: V, params: &BrdfParams<V::S>) -> BrdfTerms<V::S> {
    let zero = V::S::zero();
    if !(n.dot(l) > zero && n.dot(o) > zero) {
        return BrdfTerms::default();
    }
    let diffuse = params.k / V::S::PI();
    if params.k >= V::S::one() {
        // Lambert alone: (1 − k) = 0 times a finite lobe.
        return BrdfTerms {
            diffuse,
            specular: zero,
        };
    }
    BrdfTerms {
        diffuse,
        specular: specular(n, l, o, params),
    }
}

/// [`blinn_phong`] for loops over many samples of one material that run in
/// SIMD lanes: what does not depend on the directions is worked out once,
/// and [`Self::terms`] has no branch: every part is computed, then the one
/// `blinn_phong` returns is chosen, so the bits are the same. (The lobe is
/// computed even for k ≥ 1, where it is dropped: Lambert alone is better
/// served by `blinn_phong`.)
#[derive(Clone, Copy, Debug)]
pub struct LaneBrdf<S> {
    m: S,
    /// k / π, and (1 − k) N(m), as `specular` multiplies them.
    diffuse: S,
    scale: S,
    /// Whether k ≥ 1: no lobe.
    lambert: bool,
}

impl<S: Real> LaneBrdf<S> {
    pub fn new(params: &BrdfParams<S>) -> Self {
        Self {
            m: params.m,
            diffuse: params.k / S::PI(),
            scale: (S::one() - params.k) * params.norm.factor(params.m),
            lambert: params.k >= S::one(),
        }
    }

    /// Whether k ≥ 1: [`Self::lambert_terms`] then gives the same terms
    /// without computing a lobe.
    pub fn is_lambert(&self) -> bool {
        self.lambert
    }

    /// `blinn_phong(n, l, o, params)` where k ≥ 1: k / π above both
    /// horizons, no lobe.
    #[inline(always)]
    pub fn lambert_terms<V: Vector3<S = S>>(&self, n: V, l: V, o: V) -> BrdfTerms<S> {
        self.above_horizons(n, l, o, S::zero())
    }

    /// `blinn_phong(n, l, o, params)`.
    #[inline(always)]
    pub fn terms<V: Vector3<S = S>>(&self, n: V, l: V, o: V) -> BrdfTerms<S> {
        let (zero, one) = (S::zero(), S::one());
        let sum = l + o;
        let len2 = sum.length_squared();
        let h = sum * (one / len2.sqrt());
        let cos_h = n.dot(h);
        let gap = ((n - h).length_squared() * S::lit(0.5)).min(one);
        let power = S::power_from_gap(gap, self.m);
        // lobe()'s cases.
        let lobe = if self.m <= zero {
            one
        } else if cos_h <= zero {
            zero
        } else {
            power
        };
        // specular()'s and blinn_phong's.
        let no_half = len2.is_nan() || len2 <= zero;
        let specular = if no_half || self.lambert {
            zero
        } else {
            self.scale * lobe
        };
        self.above_horizons(n, l, o, specular)
    }

    /// k / π and `specular` where n · l > 0 and n · o > 0, else nothing.
    #[inline(always)]
    fn above_horizons<V: Vector3<S = S>>(&self, n: V, l: V, o: V, specular: S) -> BrdfTerms<S> {
        if n.dot(l) > S::zero() && n.dot(o) > S::zero() {
            BrdfTerms {
                diffuse: self.diffuse,
                specular,
            }
        } else {
            BrdfTerms::default()
        }
    }
}

/// The specular term of [`blinn_phong`] above both horizons, k < 1. Inlined:
/// in a loop over one material (the sphere light's samples), N(m) and 1 − k
/// are then worked out once.
#[inline(always)]
fn specular<V: Vector3>(n: V, l: V, o: V, params: &BrdfParams<V::S>) -> V::S {
    let zero = V::S::zero();
    let one = V::S::one();
    let sum = l + o;
    let len2 = sum.length_squared();
    if len2.is_nan() || len2 <= zero {
        // l + o = 0: no half vector, no specular term.
        return zero;
    }
    let h = sum * (one / len2.sqrt());
    let cos_h = n.dot(h);
    let gap = ((n - h).length_squared() * V::S::lit(0.5)).min(one);
    (one - params.k) * params.norm.factor(params.m) * lobe(cos_h, gap, params.m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};
    use std::f64::consts::PI;

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.cos(), t.sin() * p.sin())
    }

    fn params(k: f64, m: f64, norm: Normalization) -> BrdfParams<f64> {
        BrdfParams { k, m, norm }
    }

    #[test]
    fn lambert_is_k_over_pi() {
        let f = blinn_phong(
            DVec3::Y,
            dir(30.0, 0.0),
            dir(50.0, 120.0),
            &params(0.8, 10.0, Normalization::Exact),
        );
        assert!((f.diffuse - 0.8 / PI).abs() < 1e-15);
    }

    #[test]
    fn mirror_direction_gives_the_lobe_peak() {
        for &norm in Normalization::ALL {
            let p = params(0.0, 64.0, norm);
            let f = blinn_phong(DVec3::Y, dir(40.0, 0.0), dir(40.0, 180.0), &p);
            assert!((f.specular - norm.factor(64.0)).abs() < 1e-12 * norm.factor(64.0));
        }
    }

    #[test]
    fn normalization_factors_match_their_formulas() {
        let m: f64 = 8.0;
        assert_eq!(Normalization::None.factor(m), 1.0);
        assert!((Normalization::Ndf.factor(m) - 9.0 / (2.0 * PI)).abs() < 1e-15);
        assert!((Normalization::Approx.factor(m) - 16.0 / (8.0 * PI)).abs() < 1e-15);
        let exact = 10.0 * 12.0 / (8.0 * PI * (2f64.powf(-4.0) + 8.0));
        assert!((Normalization::Exact.factor(m) - exact).abs() < 1e-15);
        assert!((Normalization::Exact.factor(0.0) - 1.0 / PI).abs() < 1e-15);
    }

    #[test]
    fn zero_exponent_lobe_is_one_even_at_cos_zero() {
        assert_eq!(lobe(0.0_f64, 1.0, 0.0), 1.0);
        assert_eq!(lobe(-0.5_f64, 1.5, 0.0), 1.0);
        assert_eq!(lobe(0.0_f64, 1.0, 2.0), 0.0);
    }

    #[test]
    fn back_facing_reflects_nothing() {
        let p = params(0.5, 8.0, Normalization::Approx);
        assert_eq!(
            blinn_phong(DVec3::Y, dir(100.0, 0.0), dir(20.0, 0.0), &p).total(),
            0.0
        );
        assert_eq!(
            blinn_phong(DVec3::Y, dir(20.0, 0.0), dir(90.5, 0.0), &p).total(),
            0.0
        );
    }

    #[test]
    fn opposite_directions_have_no_specular_term() {
        // Only reachable with n·l > 0 and n·o > 0 if the vectors cancel exactly;
        // the tangent-plane case is the limit and must stay finite.
        let l = dir(89.99, 0.0);
        let o = dir(89.99, 180.0);
        let f = blinn_phong(DVec3::Y, l, o, &params(0.0, 1e6, Normalization::Exact));
        assert!(f.specular.is_finite());
        let exactly_opposite = blinn_phong(
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::X,
            -DVec3::X,
            &params(0.0, 4.0, Normalization::None),
        );
        assert_eq!(exactly_opposite.total(), 0.0);
    }

    #[test]
    fn huge_exponent_stays_precise_in_f32() {
        // θ_h = 1 mrad, m = 10^6: cos^m = exp(m ln cos θ_h) ≈ exp(−0.5).
        let theta_h: f64 = 1e-3;
        let m = 1e6;
        let l64 = dir(20.0 + theta_h.to_degrees(), 0.0);
        let o64 = dir(20.0 - theta_h.to_degrees(), 180.0);
        let p64 = params(0.0, m, Normalization::None);
        let f64v = blinn_phong(DVec3::Y, l64, o64, &p64).specular;
        let expected = (m * theta_h.cos().ln()).exp();
        assert!((f64v / expected - 1.0).abs() < 1e-9, "{f64v} vs {expected}");
        let p32 = BrdfParams {
            k: 0.0_f32,
            m: m as f32,
            norm: Normalization::None,
        };
        let f32v = blinn_phong(Vec3::Y, l64.as_vec3(), o64.as_vec3(), &p32).specular;
        assert!(
            (f32v as f64 / expected - 1.0).abs() < 1e-3,
            "{f32v} vs {expected}"
        );
    }

    #[test]
    fn reciprocity() {
        let p = params(0.3, 20.0, Normalization::Exact);
        let (l, o) = (dir(25.0, 10.0), dir(60.0, 200.0));
        let a = blinn_phong(DVec3::Y, l, o, &p).total();
        let b = blinn_phong(DVec3::Y, o, l, &p).total();
        assert_eq!(a, b);
    }

    #[test]
    fn ln_cos_series_matches_ln() {
        for &d in &[1e-12_f64, 1e-6, 5e-4, 9.99e-4, 1e-3, 0.05, 0.0999, 0.1, 0.2] {
            let exact = (-d).ln_1p();
            assert!((ln_cos_from_gap(d) / exact - 1.0).abs() < 1e-15, "{d}");
        }
    }

    #[test]
    fn lobe_keeps_its_precision_in_f32_between_narrow_and_wide() {
        // m = 5000 is still visible at d = 1e-3 … 1.4e-3, where ln(1 − d)
        // in f32 would cost m × 6e-8 = 3e-4 of relative error.
        let m = 5000.0;
        for i in 0..200 {
            let d32 = 1e-3_f32 + 2e-6 * i as f32;
            let exact = (m * (-(d32 as f64)).ln_1p()).exp();
            let f32v = lobe(1.0 - d32, d32, m as f32) as f64;
            assert!((f32v / exact - 1.0).abs() < 2e-6, "d = {d32}: {f32v} vs {exact}");
        }
    }
}
