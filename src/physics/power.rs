//! cos^m θ in `f64` without libm: ln cos θ from the gap 1 − cos θ, and the
//! exponential, each in plain arithmetic with selects instead of branches,
//! so that a loop over many samples (the sphere light's) runs in SIMD lanes.
//! Each call does the same operations in the same order whether it runs in
//! a lane or alone: the same bits either way. Both stay within 2 ulp of
//! libm's (`tests`); libm's `ln` and `exp`, which took 14 % of a sphere
//! light's reference at 64 samples, cannot run in lanes.

/// ln 2 in two parts: the high part's last 21 bits are zero, so k · LN2_HI
/// is exact for |k| < 2¹¹ (fdlibm's split).
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
/// 1.5 · 2⁵²: x + ROUNDER − ROUNDER is x rounded to an integer (|x| < 2⁵¹),
/// whose value also sits in the low bits of x + ROUNDER.
const ROUNDER: f64 = 6_755_399_441_055_744.0;
/// 2⁵², whose ulp is 1.
const TWO_52: f64 = 4_503_599_627_370_496.0;
/// Below this, e^z is below half the least subnormal: 0.
const LEAST_EXPONENT: f64 = -746.0;
/// √2, above which a mantissa in [1, 2) is halved: f ∈ [√½, √2).
const SQRT_2: f64 = std::f64::consts::SQRT_2;
/// 1 − √½: up to this gap, 1 − d ∈ [√½, 1] needs no power of two.
const NEAR_ONE: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;

/// ln(1 − d) for the gap d = 1 − cos θ ∈ [0, 1]: −∞ at d = 1.
///
/// Each way writes 1 − d = 2^e (1 + s)/(1 − s) with |s| ≤ 0.172 and ends in
/// ln(1 − d) = e ln 2 + 2 (s + s³/3 + s⁵/5 + …), whose terms up to s²³/23
/// leave less than s²⁵/25 < 10⁻¹⁷ |s|. s is found without rounding 1 − d
/// where that would lose digits of d:
/// - d ≤ 1 − √½: e = 0, s = −d/(2 − d);
/// - d ≤ ½: e = −1, s = (1 − 2d)/(3 − 2d), whose numerator is exact;
/// - beyond, 1 − d is exact: 1 − d = 2^e f with f ∈ [√½, √2), s = (f − 1)/(f + 1).
#[inline(always)]
pub fn ln_one_minus(d: f64) -> f64 {
    let y = 1.0 - d;
    let bits = y.to_bits();
    // The exponent and the mantissa of y (normal: y ≥ 2⁻⁵³ or 0).
    let exponent = below_2_52(bits >> 52) - 1023.0;
    let mantissa = f64::from_bits((bits & ((1 << 52) - 1)) | 1.0_f64.to_bits());
    let high = mantissa > SQRT_2;
    let f = if high { mantissa * 0.5 } else { mantissa };
    let e = if high { exponent + 1.0 } else { exponent };
    let (top, bottom, e) = if d <= NEAR_ONE {
        (-d, 2.0 - d, 0.0)
    } else if d <= 0.5 {
        (1.0 - 2.0 * d, 3.0 - 2.0 * d, -1.0)
    } else {
        (f - 1.0, f + 1.0, e)
    };
    let s = top / bottom;
    let w = s * s;
    // 1/3 + w/5 + w²/7 + … + w¹⁰/23, and three zeros.
    const TAIL: [f64; 14] = {
        let mut c = [0.0; 14];
        let mut i = 0;
        while i < 11 {
            c[i] = 1.0 / (2 * i + 3) as f64;
            i += 1;
        }
        c
    };
    let tail = estrin(&TAIL, w);
    let two_s = 2.0 * s;
    let ln = e * LN2_HI + (e * LN2_LO + (two_s + two_s * (w * tail)));
    if y == 0.0 { f64::NEG_INFINITY } else { ln }
}

/// e^z for z ≤ 709 (0 below −745, NaN for NaN): z = k ln 2 + r with k an
/// integer and |r| ≤ ln 2 / 2, e^r by its Taylor series up to r¹³/13! (the
/// first term left out, r¹⁴/14!, is below 5·10⁻¹⁸), then scaled by 2^k in
/// two exact halves so that a subnormal result is rounded once.
#[inline(always)]
pub fn exp(z: f64) -> f64 {
    // NaN fails the comparison and stays NaN.
    let z = if z < LEAST_EXPONENT { LEAST_EXPONENT } else { z };
    let k = (z * std::f64::consts::LOG2_E + ROUNDER) - ROUNDER;
    let r = (z - k * LN2_HI) - k * LN2_LO;
    const INVERSE_FACTORIALS: [f64; 14] = {
        let mut c = [1.0; 14];
        let mut i = 1;
        while i < 14 {
            c[i] = c[i - 1] / i as f64;
            i += 1;
        }
        c
    };
    let p = estrin(&INVERSE_FACTORIALS, r);
    // 2^k = 2^a · 2^b, a ≈ k/2: both normal for −1077 ≤ k ≤ 1024.
    let a = (k * 0.5 + ROUNDER) - ROUNDER;
    let b = k - a;
    (p * power_of_two(a)) * power_of_two(b)
}

/// c₀ + c₁x + … + c₁₃x¹³ by Estrin's scheme: pairs c₂ᵢ + c₂ᵢ₊₁x, then
/// pairs of those with x², x⁴ and x⁸: a chain of four steps where Horner's
/// has thirteen, so that a lone call (outside the lanes) waits less. Zeros
/// at the end leave the others' sums unchanged (finite x).
#[inline(always)]
fn estrin(c: &[f64; 14], x: f64) -> f64 {
    let (x2, pair) = (x * x, |i: usize| c[i] + c[i + 1] * x);
    let (x4, quad) = (x2 * x2, |i: usize| pair(i) + pair(i + 2) * x2);
    let x8 = x4 * x4;
    let low = quad(0) + quad(4) * x4;
    let high = quad(8) + pair(12) * x4;
    low + high * x8
}

/// n as an f64, for n < 2⁵², in lanes: n's bits placed under 2⁵² (whose
/// ulp is 1), less 2⁵². A conversion from u64, which AVX2 lacks, would
/// leave the lanes.
#[inline(always)]
pub fn below_2_52(n: u64) -> f64 {
    f64::from_bits(TWO_52.to_bits() | n) - TWO_52
}

/// 2^n for an integer n in [−1022, 1023] held as an f64.
#[inline(always)]
fn power_of_two(n: f64) -> f64 {
    let biased = (n + ROUNDER)
        .to_bits()
        .wrapping_sub(ROUNDER.to_bits())
        .wrapping_add(1023);
    f64::from_bits(biased << 52)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite positives.
    fn ulps(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn exp_stays_within_two_ulp_of_libm() {
        let mut worst = 0;
        for i in 0..200_000 {
            let z = -745.0 * (i as f64 / 200_000.0).powi(3) - 1e-9 * i as f64;
            let (ours, libm) = (exp(z), z.exp());
            if libm >= f64::MIN_POSITIVE {
                worst = worst.max(ulps(ours, libm));
            } else {
                // Subnormal: within one of libm's least step.
                assert!((ours - libm).abs() <= 5e-324, "{z}: {ours} vs {libm}");
            }
        }
        assert!(worst <= 2, "worst {worst} ulp");
    }

    #[test]
    fn exp_meets_its_edges() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-0.0), 1.0);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert_eq!(exp(-1e300), 0.0);
        assert_eq!(exp(-746.0), 0.0);
        assert!(exp(f64::NAN).is_nan());
        assert!(ulps(exp(1.0), std::f64::consts::E) <= 1);
        assert!(ulps(exp(700.0), 700.0_f64.exp()) <= 2);
        // The least subnormal is e^−744.44.
        assert_eq!(exp(-744.4), 5e-324);
    }

    #[test]
    fn ln_one_minus_stays_within_two_ulp_across_both_ways() {
        let mut worst = 0;
        for i in 1..200_000 {
            // Gaps from 10⁻¹⁶ to 0.1, then on to 1 − 10⁻¹².
            let d = if i < 100_000 {
                10f64.powf(-16.0 + 15.0 * i as f64 / 100_000.0)
            } else {
                0.1 + 0.9 * ((i - 100_000) as f64 / 100_000.0) - 1e-12
            };
            let exact = (-d).ln_1p();
            worst = worst.max(ulps(-ln_one_minus(d), -exact));
        }
        assert!(worst <= 2, "worst {worst} ulp");
    }

    #[test]
    fn ln_one_minus_meets_its_edges() {
        assert_eq!(ln_one_minus(0.0), 0.0);
        assert_eq!(ln_one_minus(1.0), f64::NEG_INFINITY);
        assert!(ulps(-ln_one_minus(0.5), std::f64::consts::LN_2) <= 1);
        assert!(ulps(-ln_one_minus(1.0 - 2f64.powi(-53)), 53.0 * std::f64::consts::LN_2) <= 1);
    }
}
