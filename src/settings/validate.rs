//! The allowed range of every setting: one line naming the field, the
//! value and what is allowed when one is out of it.

use super::{LightSettings, Settings, SettingsError, ShadowSettings};
use crate::input::{compact_number, compact_numbers, compact_range};
use crate::scene::Camera;
use glam::Vec3;

impl Settings {
    /// Checks every value against its allowed range.
    pub fn validate(&self) -> Result<(), SettingsError> {
        Self::validate_camera(&self.camera)?;
        let far = Self::MAX_COORDINATE_M;
        check_int("image.width", self.image.width, 1, 16384)?;
        check_int("image.height", self.image.height, 1, 16384)?;
        Self::validate_light(&self.light)?;
        let m = &self.material;
        check("material.k", m.k, 0.0, 1.0)?;
        check("material.m", m.m, 0.0, 1e6)?;
        if let Some(color) = m.color_override {
            check_vec("material.color_override", color, 0.0, 1.0)?;
        }
        let s = &self.shadow;
        check_int(
            "shadow.resolution",
            s.resolution,
            ShadowSettings::MIN_RESOLUTION,
            ShadowSettings::MAX_RESOLUTION,
        )?;
        if !ShadowSettings::PCF_SIZES.contains(&s.pcf_size) {
            return Err(SettingsError::OutOfRange {
                field: "shadow.pcf_size",
                value: s.pcf_size.to_string(),
                allowed: "3, 5, 7 or 9".into(),
            });
        }
        check_int("shadow.poisson_samples", s.poisson_samples, 4, 64)?;
        check("shadow.poisson_radius_texels", s.poisson_radius_texels, 0.0, 64.0)?;
        check_int("shadow.pcss_blocker_samples", s.pcss_blocker_samples, 4, 64)?;
        check_int("shadow.vsm_blur_texels", s.vsm_blur_texels, 0, 16)?;
        check("shadow.vsm_bleed_reduction", s.vsm_bleed_reduction, 0.0, 0.99)?;
        check("shadow.msm_bias", s.msm_bias, 0.0, 0.5)?;
        check("shadow.bias.depth_m", s.bias.depth_m, 0.0, far)?;
        check("shadow.bias.slope", s.bias.slope, 0.0, 1e3)?;
        check("shadow.bias.normal_texels", s.bias.normal_texels, 0.0, 1e3)?;
        check_int(
            "shadow.rt_light_samples",
            s.rt_light_samples,
            1,
            ShadowSettings::MAX_RT_LIGHT_SAMPLES,
        )?;
        check_int(
            "shadow.rt_max_frames",
            s.rt_max_frames,
            1,
            ShadowSettings::MAX_RT_FRAMES,
        )?;
        check(
            "shadow.rt_noise_target_percent",
            s.rt_noise_target_percent,
            0.0,
            ShadowSettings::MAX_RT_NOISE_TARGET_PERCENT,
        )?;
        check("view.exposure_ev", self.view.exposure_ev, -30.0, 30.0)?;
        check("ground.k", self.ground.k, 0.0, 1.0)?;
        check("ground.m", self.ground.m, 0.0, 1e6)?;
        Ok(())
    }
}

impl Settings {
    /// Checks a camera alone (the settings' own, or one a scene file
    /// places) against the ranges [`Settings::validate`] allows.
    pub fn validate_camera(c: &Camera) -> Result<(), SettingsError> {
        let far = Self::MAX_COORDINATE_M;
        check_vec("camera.eye", c.eye, -far, far)?;
        check_vec("camera.target", c.target, -far, far)?;
        if (c.eye - c.target).length() < 1e-6 {
            return Err(SettingsError::OutOfRange {
                field: "camera.target",
                value: compact_numbers(c.target.to_array()),
                allowed: "any point at least 1 µm from camera.eye".into(),
            });
        }
        check("camera.fovy_deg", c.fovy_deg, 1.0, 179.0)
    }

    /// Checks a light alone (the settings' own, or one a scene file
    /// places) against the ranges [`Settings::validate`] allows.
    pub fn validate_light(l: &LightSettings) -> Result<(), SettingsError> {
        let far = Self::MAX_COORDINATE_M;
        check_vec("light.position", l.position, -far, far)?;
        check("light.power_w", l.power_w, 0.0, Self::MAX_POWER_W)?;
        check("light.radius_m", l.radius_m, 0.0, far)?;
        check_vec("light.color", l.color, 0.0, 1e6)
    }
}

fn check(field: &'static str, value: f32, min: f32, max: f32) -> Result<(), SettingsError> {
    if value.is_finite() && (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(SettingsError::OutOfRange {
            field,
            value: compact_number(value),
            allowed: compact_range(min, max),
        })
    }
}

fn check_int(field: &'static str, value: u32, min: u32, max: u32) -> Result<(), SettingsError> {
    check(field, value as f32, min as f32, max as f32)
}

fn check_vec(field: &'static str, value: Vec3, min: f32, max: f32) -> Result<(), SettingsError> {
    for x in value.to_array() {
        check(field, x, min, max).map_err(|_| SettingsError::OutOfRange {
            field,
            value: compact_numbers(value.to_array()),
            allowed: format!("three numbers in {}", compact_range(min, max)),
        })?;
    }
    Ok(())
}
