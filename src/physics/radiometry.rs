//! Radiometry of a point light and of a small sphere light.
//!
//! A point light at `q` with power Φ (W) has intensity I = Φ / 4π (W/sr). At a
//! point `p` with unit normal `n`, r = |q − p| and l = (q − p) / r, it gives the
//! irradiance E = I · max(0, n·l) / r² (W/m²).
//!
//! A sphere light of radius R and the same power emits the uniform radiance
//! L_e = Φ / (4π² R²) (W/m²/sr). Fully above the horizon it gives exactly the
//! point light's E; when it straddles the horizon the visible part of its
//! solid angle is integrated in closed form.

use super::real::{Float, One, Real, Vector3, Zero};

/// Light distances are clamped to at least this (metres): a light lying on the
/// surface (r = 0) gives the finite irradiance I / (1 µm)², never Inf or NaN.
pub const MIN_LIGHT_DISTANCE_M: f64 = 1e-6;

/// I = Φ / 4π (W/sr), the intensity of an isotropic point light of power Φ (W).
pub fn intensity<S: Real>(power_w: S) -> S {
    power_w / (S::lit(4.0) * S::PI())
}

/// L_e = Φ / (4π² R²) (W/m²/sr), the radiance of a uniform sphere light of
/// power Φ (W) and radius R (m). The radius is clamped to the minimum light
/// distance so that R = 0 stays finite.
pub fn sphere_radiance<S: Real>(power_w: S, radius_m: S) -> S {
    let r = radius_m.max(S::lit(MIN_LIGHT_DISTANCE_M));
    power_w / (S::lit(4.0) * S::PI() * S::PI() * r * r)
}

/// Where the light is, seen from a surface point.
#[derive(Clone, Copy, Debug)]
pub struct Incidence<V: Vector3> {
    /// Unit direction towards the light, l = (q − p) / r. When the light sits
    /// exactly on the point (r = 0) it is taken to be the normal.
    pub l: V,
    /// Distance to the light (m), clamped to [`MIN_LIGHT_DISTANCE_M`].
    pub r: V::S,
    /// n·l, signed: negative when the light is below the surface's horizon.
    pub cos_theta: V::S,
}

/// Direction, distance and cosine from the point `p` (normal `n`) to the light at `q`.
pub fn incidence<V: Vector3>(p: V, n: V, q: V) -> Incidence<V> {
    let d = q - p;
    let r2 = d.length_squared();
    let l = if r2 > V::S::zero() {
        d * (V::S::one() / r2.sqrt())
    } else {
        n
    };
    Incidence {
        l,
        r: r2.sqrt().max(V::S::lit(MIN_LIGHT_DISTANCE_M)),
        cos_theta: n.dot(l),
    }
}

/// E = I · max(0, cos θ) / r² (W/m²) for a point light of intensity I (W/sr)
/// at distance r (m, clamped to [`MIN_LIGHT_DISTANCE_M`]).
pub fn point_irradiance<S: Real>(intensity_w_sr: S, cos_theta: S, r_m: S) -> S {
    let r = r_m.max(S::lit(MIN_LIGHT_DISTANCE_M));
    intensity_w_sr * cos_theta.max(S::zero()) / (r * r)
}

/// E (W/m²) from a sphere light of power Φ (W) and radius R (m) whose centre is
/// at distance r (m) and at angle θ from the normal (`cos_theta` signed).
///
/// E = L_e · F, with F the cosine-weighted solid angle of the visible part of
/// the sphere (Snyder 1996): F = π sin²α cos θ while the sphere is entirely
/// above the horizon (sin α = R / r), so that E then equals the point light's
/// I cos θ / r²; a closed form while it straddles the horizon; 0 below it.
/// A point inside the sphere sees emission over its whole hemisphere: E = π L_e.
/// R = 0 is the point light.
pub fn sphere_irradiance<S: Real>(power_w: S, radius_m: S, cos_theta: S, r_m: S) -> S {
    let zero = S::zero();
    let one = S::one();
    if radius_m <= zero {
        return point_irradiance(intensity(power_w), cos_theta, r_m);
    }
    let r = r_m.max(S::lit(MIN_LIGHT_DISTANCE_M));
    let sin2_alpha = (radius_m * radius_m) / (r * r);
    if sin2_alpha >= one {
        return S::PI() * sphere_radiance(power_w, radius_m);
    }
    let cos_theta = cos_theta.max(-one).min(one);
    if cos_theta > zero && cos_theta * cos_theta >= sin2_alpha {
        // Entirely above the horizon: the point light's formula, written so
        // that it does not lose the 1/r² scale when R is tiny.
        return point_irradiance(intensity(power_w), cos_theta, r);
    }
    if cos_theta <= zero && cos_theta * cos_theta >= sin2_alpha {
        return zero;
    }
    let sin_theta = (one - cos_theta * cos_theta).max(zero).sqrt();
    // x = cot α, the distance to the centre over the radius of the cap.
    let x = (one / sin2_alpha - one).sqrt();
    let y = (-x * cos_theta / sin_theta).max(-one).min(one);
    let s = sin_theta * (one - y * y).max(zero).sqrt();
    // Snyder's F = (cos θ acos y − x s) sin²α + atan(s / x). With t = s / x and
    // x² sin²α = 1 − sin²α it is F = sin²α (cos θ acos y + t) − (t − atan t):
    // the form Snyder's terms take without cancelling each other, which for a
    // small sphere (α → 0) would leave rounding noise of order α instead of
    // a value of order α³.
    let t = s / x;
    let form = sin2_alpha * (cos_theta * y.acos() + t) - t_minus_atan(t);
    sphere_radiance(power_w, radius_m) * form.max(zero)
}

/// t − atan t for t ≥ 0 without cancellation: below 0.05 its series
/// t³/3 − t⁵/5 + … + t¹⁵/15 (truncation below t¹⁷/17), above it directly.
pub fn t_minus_atan<S: Real>(t: S) -> S {
    if t < S::lit(0.05) {
        let t2 = t * t;
        let lit = S::lit;
        let tail = lit(1.0 / 11.0) - t2 * (lit(1.0 / 13.0) - t2 * lit(1.0 / 15.0));
        t * t2
            * (lit(1.0 / 3.0) - t2 * (lit(0.2) - t2 * (lit(1.0 / 7.0) - t2 * (lit(1.0 / 9.0) - t2 * tail))))
    } else {
        t - t.atan()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use std::f64::consts::PI;

    #[test]
    fn intensity_is_power_over_four_pi() {
        assert!((intensity(100.0_f64) - 100.0 / (4.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn irradiance_falls_as_inverse_square_and_cosine() {
        let i = intensity(1000.0_f64);
        let e1 = point_irradiance(i, 1.0, 2.0);
        let e2 = point_irradiance(i, 1.0, 4.0);
        assert!((e1 / e2 - 4.0).abs() < 1e-12);
        let tilted = point_irradiance(i, (60.0_f64).to_radians().cos(), 2.0);
        assert!((tilted / e1 - 0.5).abs() < 1e-12);
        assert_eq!(point_irradiance(i, -0.3, 2.0), 0.0);
    }

    #[test]
    fn light_on_the_surface_gives_a_finite_value() {
        let p = DVec3::new(1.0, 0.0, 0.0);
        let n = DVec3::Y;
        let inc = incidence(p, n, p);
        assert_eq!(inc.l, n);
        assert_eq!(inc.r, MIN_LIGHT_DISTANCE_M);
        let e = point_irradiance(intensity(1.0), inc.cos_theta, inc.r);
        assert!(e.is_finite() && e > 0.0);
        let e32 = point_irradiance(intensity(1e9_f32), 1.0, 0.0);
        assert!(e32.is_finite());
    }

    #[test]
    fn zero_power_gives_zero() {
        assert_eq!(point_irradiance(intensity(0.0_f64), 1.0, 1.0), 0.0);
        assert_eq!(sphere_irradiance(0.0_f64, 0.1, 0.3, 1.0), 0.0);
    }

    #[test]
    fn sphere_light_above_horizon_equals_point_light() {
        for &(cos, r) in &[(1.0, 2.0), (0.5, 3.0), (0.2, 10.0)] {
            let point = point_irradiance(intensity(50.0_f64), cos, r);
            let sphere = sphere_irradiance(50.0_f64, 0.1, cos, r);
            assert!((sphere / point - 1.0).abs() < 1e-12, "{cos} {r}");
        }
    }

    /// The cosine-weighted solid angle of the sphere's cap above the horizon,
    /// integrated numerically over the cap: checks the closed form.
    fn form_factor_by_quadrature(theta: f64, sin_alpha: f64) -> f64 {
        let alpha = sin_alpha.asin();
        let c = DVec3::new(theta.sin(), 0.0, theta.cos());
        let (t1, t2) = c.any_orthonormal_pair();
        let (nu, nv) = (2000, 2000);
        let mut sum = 0.0;
        for i in 0..nu {
            // Directions in the cone: cos of the angle to the centre uniform in [cos α, 1].
            let cu = 1.0 - (1.0 - alpha.cos()) * (i as f64 + 0.5) / nu as f64;
            let su = (1.0 - cu * cu).sqrt();
            for j in 0..nv {
                let phi = 2.0 * PI * (j as f64 + 0.5) / nv as f64;
                let w = c * cu + (t1 * phi.cos() + t2 * phi.sin()) * su;
                sum += w.z.max(0.0);
            }
        }
        sum * 2.0 * PI * (1.0 - alpha.cos()) / (nu * nv) as f64
    }

    #[test]
    fn sphere_light_straddling_the_horizon_matches_quadrature() {
        let (power, radius, r) = (10.0_f64, 0.5, 1.0);
        let sin_alpha = radius / r;
        let le = sphere_radiance(power, radius);
        for deg in [70.0_f64, 85.0, 90.0, 100.0, 115.0] {
            let theta = deg.to_radians();
            let e = sphere_irradiance(power, radius, theta.cos(), r);
            let expected = le * form_factor_by_quadrature(theta, sin_alpha);
            assert!((e - expected).abs() < 1e-4 * le, "{deg}°: {e} vs {expected}");
        }
        assert_eq!(
            sphere_irradiance(power, radius, (125.0_f64).to_radians().cos(), r),
            0.0
        );
    }

    #[test]
    fn a_tiny_sphere_straddling_the_horizon_keeps_its_precision_in_f32() {
        // R/r = 1e-4: F is of order α³ while Snyder's separate terms are of
        // order α; written as they are, f32 got E wrong by a factor of ten.
        let (power, radius, r) = (1.0_f64, 1e-4, 1.0);
        let scale = point_irradiance(intensity(power), 1.0, r);
        for fraction in [-0.9, -0.5, 0.0, 0.5, 0.9] {
            let cos32 = (fraction * radius / r) as f32;
            let e64 = sphere_irradiance(power, radius, cos32 as f64, r);
            let e32 = sphere_irradiance(power as f32, radius as f32, cos32, r as f32);
            assert!(e64 > 0.0 && e64 < scale * radius, "{fraction}: {e64}");
            assert!(
                (e32 as f64 - e64).abs() < 1e-3 * e64,
                "{fraction}: f32 {e32} vs f64 {e64}"
            );
        }
    }

    #[test]
    fn t_minus_atan_is_continuous_at_its_switch() {
        let below = t_minus_atan(0.05_f64 - 1e-12);
        let direct = (0.05_f64 - 1e-12) - (0.05_f64 - 1e-12).atan();
        assert!((below / direct - 1.0).abs() < 1e-12);
        let series = 1e-9 / 3.0 - 1e-15 / 5.0 + 1e-21 / 7.0;
        assert!((t_minus_atan(1e-3_f64) / series - 1.0).abs() < 1e-14);
    }

    #[test]
    fn inside_the_sphere_light_the_hemisphere_is_lit() {
        let e = sphere_irradiance(10.0_f64, 0.5, 0.3, 0.2);
        assert!((e - PI * sphere_radiance(10.0, 0.5)).abs() < 1e-12);
    }
}
