//! Energy conservation: the directional albedo of the BRDF,
//!
//! ```text
//! a(θ_i) = ∫_{Ω+} f_r(l, o) cos θ_o dω_o   (with c = 1),
//! ```
//!
//! by deterministic adaptive quadrature. A BRDF conserves energy only if
//! a(θ_i) ≤ 1 for every θ_i.
//!
//! The integral is taken over half-vectors h, where the lobe lives: with
//! o = 2(l·h)h − l, dω_o = 4 (l·h) dω_h. Put l in the xz-plane at angle θ_i
//! from n = z and h at (θ_h, φ). Then l·h = A cos φ + B with A = sin θ_i sin θ_h
//! and B = cos θ_i cos θ_h, and cos θ_o = 2 (l·h) cos θ_h − cos θ_i. The
//! condition cos θ_o > 0 keeps |φ| < φ_max(θ_h), which is π for
//! θ_h ≤ π/4 − θ_i/2, 0 for θ_h ≥ π/4 + θ_i/2 and acos(t) in between, with
//! t = (cos θ_i / (2 cos θ_h) − B) / A. The integrand is a quadratic in cos φ,
//! so the φ integral is done exactly and only the θ_h integral is numerical:
//! adaptive Gauss–Kronrod (7/15) on panels that start at the kinks above and
//! at geometric multiples of the lobe width 1/√m, so lobes up to m = 10^6 are
//! resolved.

use super::brdf::{BrdfParams, lobe};
use std::collections::BinaryHeap;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The lecture's incidence angles (degrees).
pub const LECTURE_ANGLES_DEG: [f64; 6] = [0.0, 30.0, 45.0, 60.0, 75.0, 89.0];
/// The largest incidence angle the lab integrates at (degrees).
pub const MAX_THETA_DEG: f64 = 89.99;

/// Relative accuracy the quadrature aims at.
const REL_TOL: f64 = 1e-12;
/// Absolute floor of the accuracy (the albedo is of order 1).
const ABS_TOL: f64 = 1e-14;
/// At most this many panels: bounds the work for any input.
const MAX_PANELS: usize = 4000;

/// An albedo with the quadrature's own estimate of its absolute error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Albedo {
    pub value: f64,
    pub error: f64,
}

/// a(θ_i) of the lab's BRDF for the incidence angle θ_i in degrees, clamped
/// to [0°, 89.99°].
pub fn directional_albedo(theta_i_deg: f64, params: &BrdfParams<f64>) -> Albedo {
    let norm = params.norm.factor(params.m);
    let diffuse = params.k / PI;
    let specular = 1.0 - params.k;
    let brdf = |theta_h: f64| diffuse + specular * norm * lobe_at(theta_h, params.m);
    albedo_of(theta_i_deg, params.m, brdf)
}

/// a(θ_i) of any BRDF that depends on the half-vector angle θ_h alone
/// (`brdf(θ_h)` in 1/sr), whose features are no narrower than 1/√m.
pub fn albedo_of(theta_i_deg: f64, m: f64, brdf: impl Fn(f64) -> f64) -> Albedo {
    let theta_i = theta_i_deg.clamp(0.0, MAX_THETA_DEG).to_radians();
    let geometry = Incidence::new(theta_i);
    integrate(
        |theta_h| brdf(theta_h) * geometry.kernel(theta_h),
        &geometry.breakpoints(m),
    )
}

/// One value of the energy table.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct AlbedoRow {
    pub norm: super::Normalization,
    pub m: f64,
    pub k: f64,
    pub theta_deg: f64,
    pub albedo: f64,
}

impl AlbedoRow {
    /// Reflects more energy than it receives.
    pub fn gains_energy(&self) -> bool {
        self.albedo > 1.0 + 1e-9
    }
}

/// a(θ) for every normalization × exponent × angle, in that nesting order.
pub fn albedo_table(
    norms: &[super::Normalization],
    ms: &[f64],
    k: f64,
    angles_deg: &[f64],
) -> Vec<AlbedoRow> {
    let mut rows = Vec::with_capacity(norms.len() * ms.len() * angles_deg.len());
    for &norm in norms {
        for &m in ms {
            let params = BrdfParams { k, m, norm };
            for &theta_deg in angles_deg {
                let albedo = directional_albedo(theta_deg, &params).value;
                rows.push(AlbedoRow {
                    norm,
                    m,
                    k,
                    theta_deg,
                    albedo,
                });
            }
        }
    }
    rows
}

/// cos^m θ_h with the lab's conventions, from the angle itself.
fn lobe_at(theta_h: f64, m: f64) -> f64 {
    let half = (0.5 * theta_h).sin();
    lobe(theta_h.cos(), 2.0 * half * half, m)
}

/// The light's direction and the half-vector domain it implies.
struct Incidence {
    cos_i: f64,
    sin_i: f64,
    /// Below this θ_h every azimuth reflects above the horizon.
    full_until: f64,
    /// Above this θ_h no azimuth does.
    zero_from: f64,
}

impl Incidence {
    fn new(theta_i: f64) -> Self {
        Self {
            cos_i: theta_i.cos(),
            sin_i: theta_i.sin(),
            full_until: FRAC_PI_4 - 0.5 * theta_i,
            zero_from: FRAC_PI_4 + 0.5 * theta_i,
        }
    }

    /// sin θ_h · ∫ 4 (l·h) cos θ_o dφ over the azimuths with cos θ_o > 0:
    /// the measure that turns f_r into a(θ_i) when integrated over θ_h.
    fn kernel(&self, theta_h: f64) -> f64 {
        let (sin_h, cos_h) = theta_h.sin_cos();
        let a = self.sin_i * sin_h;
        let b = self.cos_i * cos_h;
        let phi_max = if theta_h <= self.full_until {
            PI
        } else if theta_h >= self.zero_from || a <= 0.0 {
            return 0.0;
        } else {
            ((self.cos_i / (2.0 * cos_h) - b) / a).clamp(-1.0, 1.0).acos()
        };
        let (sin_p, cos_p) = phi_max.sin_cos();
        let p1 = 2.0 * phi_max; // ∫ dφ
        let pc = 2.0 * sin_p; // ∫ cos φ dφ
        let pcc = phi_max + sin_p * cos_p; // ∫ cos² φ dφ
        let lh_sq = a * a * pcc + 2.0 * a * b * pc + b * b * p1; // ∫ (l·h)²
        let lh = a * pc + b * p1; // ∫ l·h
        (4.0 * (2.0 * cos_h * lh_sq - self.cos_i * lh)).max(0.0) * sin_h
    }

    /// Panel ends: the kinks of the domain and multiples of the lobe width.
    fn breakpoints(&self, m: f64) -> Vec<f64> {
        let end = self.zero_from.min(FRAC_PI_2);
        let mut points = vec![0.0, end];
        if self.full_until > 0.0 && self.full_until < end {
            points.push(self.full_until);
        }
        let mut width = 1.0 / m.max(1.0).sqrt();
        while width < end {
            points.push(width);
            width *= 2.0;
        }
        points.sort_by(f64::total_cmp);
        points.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
        points
    }
}

/// A panel of the adaptive quadrature, ordered by its error estimate.
struct Panel {
    a: f64,
    b: f64,
    value: f64,
    error: f64,
}

impl PartialEq for Panel {
    fn eq(&self, other: &Self) -> bool {
        self.error == other.error
    }
}
impl Eq for Panel {}
impl PartialOrd for Panel {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Panel {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.error.total_cmp(&other.error)
    }
}

/// Globally adaptive Gauss–Kronrod quadrature over the panels between
/// consecutive `points`: the panel with the largest error is halved until the
/// total error estimate meets the tolerance or the panel budget is spent.
pub fn integrate(f: impl Fn(f64) -> f64, points: &[f64]) -> Albedo {
    let panel = |a: f64, b: f64| {
        let (value, error) = gauss_kronrod_15(&f, a, b);
        Panel { a, b, value, error }
    };
    let mut heap: BinaryHeap<Panel> = points.windows(2).map(|w| panel(w[0], w[1])).collect();
    loop {
        let value: f64 = heap.iter().map(|p| p.value).sum();
        let error: f64 = heap.iter().map(|p| p.error).sum();
        let done = error <= ABS_TOL.max(REL_TOL * value.abs()) || heap.len() >= MAX_PANELS;
        let worst = heap.pop();
        match worst {
            Some(worst) if !done => {
                let mid = 0.5 * (worst.a + worst.b);
                heap.push(panel(worst.a, mid));
                heap.push(panel(mid, worst.b));
            }
            _ => return Albedo { value, error },
        }
    }
}

/// QUADPACK's 15-point Kronrod rule with its embedded 7-point Gauss rule:
/// returns the Kronrod estimate and |Kronrod − Gauss| as its error.
fn gauss_kronrod_15(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    const XGK: [f64; 8] = [
        0.991_455_371_120_812_6,
        0.949_107_912_342_758_5,
        0.864_864_423_359_769_1,
        0.741_531_185_599_394_4,
        0.586_087_235_467_691_1,
        0.405_845_151_377_397_2,
        0.207_784_955_007_898_5,
        0.0,
    ];
    const WGK: [f64; 8] = [
        0.022_935_322_010_529_22,
        0.063_092_092_629_978_55,
        0.104_790_010_322_250_18,
        0.140_653_259_715_525_92,
        0.169_004_726_639_267_9,
        0.190_350_578_064_785_4,
        0.204_432_940_075_298_9,
        0.209_482_141_084_727_83,
    ];
    // Gauss weights for the nodes XGK[1], XGK[3], XGK[5] and the centre.
    const WG: [f64; 4] = [
        0.129_484_966_168_869_7,
        0.279_705_391_489_276_7,
        0.381_830_050_505_118_9,
        0.417_959_183_673_469_4,
    ];
    let centre = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let fc = f(centre);
    let mut kronrod = WGK[7] * fc;
    let mut gauss = WG[3] * fc;
    for j in 0..7 {
        let dx = half * XGK[j];
        let pair = f(centre - dx) + f(centre + dx);
        kronrod += WGK[j] * pair;
        if j % 2 == 1 {
            gauss += WG[j / 2] * pair;
        }
    }
    (kronrod * half, ((kronrod - gauss) * half).abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::Normalization;

    fn albedo(theta: f64, k: f64, m: f64, norm: Normalization) -> f64 {
        directional_albedo(theta, &BrdfParams { k, m, norm }).value
    }

    #[test]
    fn lambert_albedo_is_k() {
        for theta in [0.0, 30.0, 45.0, 60.0, 75.0, 89.0, 89.99] {
            for k in [1.0, 0.5, 0.25] {
                let a = albedo_of(theta, 1.0, |_| k / PI).value;
                assert!((a - k).abs() < 1e-10, "θ={theta} k={k}: {a}");
            }
            let mixed = albedo(theta, 1.0, 8.0, Normalization::Approx);
            assert!(
                (mixed - 1.0).abs() < 1e-10,
                "θ={theta}: k = 1 is pure Lambert, {mixed}"
            );
        }
    }

    #[test]
    fn albedo_is_linear_in_the_mix() {
        for theta in [0.0, 60.0] {
            let lobe_only = albedo(theta, 0.0, 32.0, Normalization::Approx);
            let mixed = albedo(theta, 0.3, 32.0, Normalization::Approx);
            assert!((mixed - (0.3 + 0.7 * lobe_only)).abs() < 1e-10);
        }
    }

    #[test]
    fn exact_normalization_gives_one_at_normal_incidence() {
        for m in [0.0, 1.0, 2.0, 8.0, 64.0, 512.0, 4096.0] {
            let a = albedo(0.0, 0.0, m, Normalization::Exact);
            assert!((a - 1.0).abs() < 1e-6, "m={m}: {a}");
        }
    }

    #[test]
    fn approx_norm_exceeds_one_at_normal_incidence_for_m8() {
        let a = albedo(0.0, 0.0, 8.0, Normalization::Approx);
        assert!((a - 1.075).abs() < 1e-3, "{a}");
    }

    #[test]
    fn unnormalized_albedo_falls_monotonically_for_m8() {
        let values: Vec<f64> = (0..=89)
            .map(|t| albedo(t as f64, 0.0, 8.0, Normalization::None))
            .collect();
        assert!(values.windows(2).all(|w| w[1] < w[0]), "{values:?}");
    }

    #[test]
    fn normal_incidence_matches_the_closed_form() {
        // At θ_i = 0, ∫ cos^m(θ_o/2) cos θ_o dω_o = 8π (2^(−m/2) + m) / ((m + 2)(m + 4)).
        for m in [0.0, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6] {
            let expected = 8.0 * PI * (2f64.powf(-m / 2.0) + m) / ((m + 2.0) * (m + 4.0));
            let got = albedo(0.0, 0.0, m, Normalization::None);
            assert!((got / expected - 1.0).abs() < 1e-9, "m={m}: {got} vs {expected}");
        }
    }

    #[test]
    fn sharp_lobes_are_finite_and_report_their_accuracy() {
        for theta in [0.0, 45.0, 89.99] {
            let estimate = directional_albedo(
                theta,
                &BrdfParams {
                    k: 0.0,
                    m: 1e6,
                    norm: Normalization::Exact,
                },
            );
            assert!(estimate.value.is_finite() && estimate.value > 0.0 && estimate.value <= 1.0 + 1e-6);
            assert!(estimate.error < 1e-8, "θ={theta}: {estimate:?}");
        }
    }
}
