//! Lengths relative to the scene. The lab's own lengths (the default light
//! and eye, the presets' positions, orbit limits, the largest sphere light,
//! the default bias) were chosen for the built-in scene, in metres. A scene
//! of another size sees each of them scaled by its size and moved to its
//! floor, so that a model in millimetres or in kilometres behaves as the
//! built-in scene does. Every such length goes through [`SceneScale`]: the
//! one place that decides what "the size of the scene" means.

use super::Aabb;
use glam::Vec3;

/// How the built-in scene's lengths map onto a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneScale {
    /// Metres of this scene per metre of the built-in scene.
    pub unit: f32,
    /// Where the built-in scene's origin (the centre of its ground) falls.
    pub anchor: Vec3,
}

impl Default for SceneScale {
    fn default() -> Self {
        Self::BUILT_IN
    }
}

impl SceneScale {
    /// The built-in scene's own scale: every length as designed.
    pub const BUILT_IN: Self = Self {
        unit: 1.0,
        anchor: Vec3::ZERO,
    };
    /// Radius of the bounding sphere of the built-in scene's objects,
    /// without their ground (m): a model whose bounding sphere is r plays
    /// their part, with `unit` = r / this (checked by a test).
    pub const BUILT_IN_MODEL_RADIUS_M: f32 = 3.76;

    /// The closest the eye may orbit to its target, in built-in metres.
    const MIN_ORBIT_DISTANCE: f64 = 0.05;
    /// The furthest, in built-in metres.
    const MAX_ORBIT_DISTANCE: f64 = 1e4;
    /// The largest sphere-light radius the sliders offer, in built-in metres.
    const MAX_LIGHT_RADIUS: f32 = 2.0;
    /// The default constant depth bias, in built-in metres.
    pub const DEFAULT_BIAS: f32 = 0.005;

    /// The scale of a model bounded by `bounds`: its bounding sphere's
    /// radius against the built-in scene's objects', anchored at the centre
    /// of its floor (the bounds' lowest height). An empty or degenerate
    /// scene gets the built-in scale.
    pub fn of_bounds(bounds: &Aabb) -> Self {
        let (centre, radius) = bounds.bounding_sphere();
        if bounds.is_empty() || !radius.is_finite() || radius <= 0.0 {
            return Self::BUILT_IN;
        }
        Self {
            unit: radius as f32 / Self::BUILT_IN_MODEL_RADIUS_M,
            anchor: Vec3::new(centre.x as f32, bounds.min.y, centre.z as f32),
        }
    }

    /// A length of the built-in scene, in this scene (m).
    pub fn length(&self, built_in_m: f32) -> f32 {
        built_in_m * self.unit
    }

    /// A light power of the built-in scene, in this scene (W): scaled by
    /// the square of the unit, so that the irradiance E = Φ cos θ / 4πr² at
    /// the scaled distances is the built-in scene's.
    pub fn power(&self, built_in_w: f32) -> f32 {
        built_in_w * self.unit * self.unit
    }

    /// A position of the built-in scene, in this scene.
    pub fn point(&self, built_in: Vec3) -> Vec3 {
        self.anchor + built_in * self.unit
    }

    /// The orbit's nearest and furthest eye-to-target distances (m).
    pub fn orbit_distance_m(&self) -> (f64, f64) {
        let unit = self.unit as f64;
        (Self::MIN_ORBIT_DISTANCE * unit, Self::MAX_ORBIT_DISTANCE * unit)
    }

    /// The largest sphere-light radius the sliders offer (m).
    pub fn max_light_radius_m(&self) -> f32 {
        self.length(Self::MAX_LIGHT_RADIUS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_scene_has_the_built_in_scale() {
        let scene = crate::scene::default_scene();
        let objects = scene
            .objects
            .iter()
            .filter(|o| o.name != "ground")
            .fold(Aabb::EMPTY, |b, o| b.union(&o.bounds));
        assert!(objects.extent().x < 10.0, "the ground is left out");
        let radius = objects.bounding_sphere().1 as f32;
        assert!(
            (radius / SceneScale::BUILT_IN_MODEL_RADIUS_M - 1.0).abs() < 1e-2,
            "the built-in objects' radius is {radius} m"
        );
        assert_eq!(crate::scene::default_scene().scale, SceneScale::BUILT_IN);
        let p = Vec3::new(2.5, 6.0, 2.0);
        assert_eq!(SceneScale::BUILT_IN.point(p), p);
        assert_eq!(SceneScale::BUILT_IN.length(0.4), 0.4);
    }

    #[test]
    fn a_scene_a_thousand_times_smaller_scales_every_length() {
        // A cube whose bounding sphere is the built-in objects'.
        let h = SceneScale::BUILT_IN_MODEL_RADIUS_M / 3f32.sqrt();
        let built_in = Aabb {
            min: Vec3::splat(-h),
            max: Vec3::splat(h),
        };
        let offset = Vec3::new(3.0, -2.0, 1.0);
        let small = Aabb {
            min: built_in.min * 1e-3 + offset,
            max: built_in.max * 1e-3 + offset,
        };
        let s = SceneScale::of_bounds(&small);
        assert!((s.unit - 1e-3).abs() < 1e-5, "{}", s.unit);
        assert!((s.anchor.y - small.min.y).abs() < 1e-6);
        let (near, far) = s.orbit_distance_m();
        assert!((near - 5e-5).abs() < 1e-6 && (far - 10.0).abs() < 0.1);
        assert!((s.max_light_radius_m() - 2e-3).abs() < 1e-5);
        // The same irradiance at a thousandth of the distance.
        let e = |power: f32, r: f32| power / (4.0 * std::f32::consts::PI * r * r);
        let ratio = e(s.power(1000.0), s.length(6.0)) / e(1000.0, 6.0);
        assert!((ratio - 1.0).abs() < 1e-4, "{ratio}");
    }

    #[test]
    fn an_empty_scene_keeps_the_built_in_scale() {
        assert_eq!(SceneScale::of_bounds(&Aabb::EMPTY), SceneScale::BUILT_IN);
    }
}
