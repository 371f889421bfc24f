//! What a step asks the class to observe: one number, computed by
//! `physics` (or `colour`) from the settings the step set, so that it stays
//! true when the teacher moves a slider. The step's text holds `{value}`
//! where the number goes.

use crate::colour::{Illuminant, compare_chart};
use crate::i18n::Language;
use crate::physics::BrdfParams;
use crate::physics::energy::{MAX_THETA_DEG, directional_albedo};
use crate::physics::radiometry::{incidence, intensity, sphere_irradiance, sphere_radiance};
use crate::settings::Settings;
use glam::{DVec3, Vec3};
use serde::Deserialize;

/// The quantity a step shows, with where it is measured.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "quantity", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Observe {
    /// I = Φ / 4π (W/sr) of the light.
    Intensity,
    /// E (W/m²) at the point `at` with unit normal `normal` (default +Y):
    /// I cos θ / r² for a point light, the sphere light's closed form else.
    Irradiance {
        at: Vec3,
        #[serde(default = "up")]
        normal: Vec3,
    },
    /// L_e = Φ / 4π²R² (W/m²/sr) of the sphere light.
    SphereRadiance,
    /// r = |q − p| (m), the distance from `at` to the light: the depth the
    /// light's pass stores.
    LightDistance { at: Vec3 },
    /// a(θ_i), the directional albedo of the material's BRDF (k, m, N).
    Albedo { theta_deg: f64 },
    /// N(m), the lobe's normalization at the material's m (1/sr).
    NormFactor,
    /// The mean ΔE2000 over the 24 ColorChecker patches between the
    /// spectral colour and the lecture's RGB product, under `illuminant`.
    DeltaE { illuminant: String },
}

fn up() -> Vec3 {
    Vec3::Y
}

impl Observe {
    /// The number, from the settings shown.
    pub fn value(&self, settings: &Settings) -> f64 {
        let light = &settings.light;
        let power = light.power_w as f64;
        let material = &settings.material;
        match self {
            Self::Intensity => intensity(power),
            Self::Irradiance { at, normal } => {
                let seen = incidence(
                    at.as_dvec3(),
                    normal.as_dvec3().normalize_or(DVec3::Y),
                    light.position.as_dvec3(),
                );
                sphere_irradiance(power, light.radius_m as f64, seen.cos_theta, seen.r)
            }
            Self::SphereRadiance => sphere_radiance(power, light.radius_m as f64),
            Self::LightDistance { at } => at.as_dvec3().distance(light.position.as_dvec3()),
            Self::Albedo { theta_deg } => {
                let params = BrdfParams {
                    k: material.k as f64,
                    m: material.m as f64,
                    norm: material.norm,
                };
                directional_albedo(*theta_deg, &params).value
            }
            Self::NormFactor => material.norm.factor(material.m as f64),
            Self::DeltaE { illuminant } => illuminant.parse::<Illuminant>().map_or(f64::NAN, |i| {
                crate::colour::chart::mean_and_max(&compare_chart(i)).0
            }),
        }
    }

    /// The unit the number is in ("" for a pure number).
    pub fn unit(&self) -> &'static str {
        match self {
            Self::Intensity => "W/sr",
            Self::Irradiance { .. } => "W/m²",
            Self::SphereRadiance => "W/m²/sr",
            Self::LightDistance { .. } => "m",
            Self::NormFactor => "1/sr",
            Self::Albedo { .. } | Self::DeltaE { .. } => "",
        }
    }

    /// A problem with the quantity's own values, as "key: problem".
    pub fn check(&self) -> Result<(), String> {
        let finite = |key: &str, v: Vec3| match v.is_finite() {
            true => Ok(()),
            false => Err(format!("observe.{key} must be finite, got {:?}", v.to_array())),
        };
        match self {
            Self::Irradiance { at, normal } => {
                finite("at", *at)?;
                finite("normal", *normal)?;
                if normal.length() < 1e-6 {
                    return Err("observe.normal must not be the zero vector".into());
                }
                Ok(())
            }
            Self::LightDistance { at } => finite("at", *at),
            Self::Albedo { theta_deg } if !(0.0..=MAX_THETA_DEG).contains(theta_deg) => Err(format!(
                "observe.theta_deg = {theta_deg} is out of range (allowed: 0 … {MAX_THETA_DEG})"
            )),
            Self::DeltaE { illuminant } => illuminant
                .parse::<Illuminant>()
                .map(|_| ())
                .map_err(|e| format!("observe.illuminant: {e}")),
            _ => Ok(()),
        }
    }

    /// The number with its unit, as the step's text shows it: four
    /// significant digits, a decimal comma in French.
    pub fn format(&self, value: f64, language: Language) -> String {
        let number = format_number(value);
        let number = match language {
            Language::Fr => number.replace('.', ","),
            Language::En => number,
        };
        match self.unit() {
            "" => number,
            unit => format!("{number} {unit}"),
        }
    }
}

/// Four significant digits (at least the units), no exponent below 10⁶.
pub fn format_number(value: f64) -> String {
    if !value.is_finite() {
        return "—".into();
    }
    let magnitude = value.abs();
    if magnitude >= 1e6 || (magnitude > 0.0 && magnitude < 1e-3) {
        return format!("{value:.3e}");
    }
    let digits = if magnitude == 0.0 {
        0
    } else {
        (3 - magnitude.log10().floor() as i32).max(0) as usize
    };
    format!("{value:.digits$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(format_number(1.07512), "1.075");
        assert_eq!(format_number(79.577), "79.58");
        assert_eq!(format_number(1234.6), "1235");
        assert_eq!(format_number(0.0), "0");
        assert_eq!(format_number(0.24687), "0.2469");
        assert_eq!(format_number(2.5e7), "2.500e7");
    }

    #[test]
    fn french_numbers_have_a_decimal_comma() {
        let albedo = Observe::Albedo { theta_deg: 0.0 };
        assert_eq!(albedo.format(1.075, Language::Fr), "1,075");
        assert_eq!(Observe::Intensity.format(79.577, Language::En), "79.58 W/sr");
    }

    #[test]
    fn intensity_of_the_default_light_is_phi_over_four_pi() {
        let s = Settings::default();
        let expected = s.light.power_w as f64 / (4.0 * std::f64::consts::PI);
        assert!((Observe::Intensity.value(&s) - expected).abs() < 1e-12);
    }

    #[test]
    fn irradiance_below_the_light_is_i_over_r_squared() {
        let mut s = Settings::default();
        s.light.position = Vec3::new(0.0, 2.0, 0.0);
        let e = Observe::Irradiance {
            at: Vec3::ZERO,
            normal: Vec3::Y,
        }
        .value(&s);
        let i = s.light.power_w as f64 / (4.0 * std::f64::consts::PI);
        assert!((e - i / 4.0).abs() < 1e-9, "{e}");
    }
}
