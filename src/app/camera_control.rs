//! Orbit, pan and zoom of the camera, and the light gizmo's projection and
//! drags, as plain functions of the camera settings (no egui here).

use crate::scene::Camera;
use glam::{DVec2, DVec3, Vec3};

/// Pitch stays within this of the poles (degrees) so the frame stays defined.
const POLE_MARGIN_DEG: f64 = 1.0;

/// Turns the eye around the target: `yaw_deg` about +Y, `pitch_deg` up/down.
pub fn orbit(c: &mut Camera, yaw_deg: f64, pitch_deg: f64) {
    let target = c.target.as_dvec3();
    let offset = c.eye.as_dvec3() - target;
    let r = offset.length();
    if r <= 0.0 {
        return;
    }
    let yaw = offset.x.atan2(offset.z) + yaw_deg.to_radians();
    let limit = (90.0 - POLE_MARGIN_DEG).to_radians();
    let pitch = ((offset.y / r).clamp(-1.0, 1.0).asin() + pitch_deg.to_radians()).clamp(-limit, limit);
    let dir = DVec3::new(pitch.cos() * yaw.sin(), pitch.sin(), pitch.cos() * yaw.cos());
    c.eye = (target + dir * r).as_vec3();
}

/// Metres per pixel at `depth_m` in front of the eye, for an image
/// `height_px` tall.
fn metres_per_pixel(c: &Camera, depth_m: f64, height_px: f64) -> f64 {
    2.0 * depth_m.max(1e-6) * c.tan_half_fovy() / height_px.max(1.0)
}

/// Moves eye and target together so the point under the cursor follows it.
pub fn pan(c: &mut Camera, delta_px: DVec2, height_px: f64) {
    let frame = c.frame();
    let distance = (c.target - c.eye).as_dvec3().length();
    let s = metres_per_pixel(c, distance, height_px);
    let shift = (frame.up * delta_px.y - frame.right * delta_px.x) * s;
    c.eye = (c.eye.as_dvec3() + shift).as_vec3();
    c.target = (c.target.as_dvec3() + shift).as_vec3();
}

/// Scales the eye's distance to the target by `factor` (< 1 comes closer),
/// within `limits` = (nearest, furthest) (m; see `SceneScale::orbit_distance_m`).
pub fn zoom(c: &mut Camera, factor: f64, limits: (f64, f64)) {
    let target = c.target.as_dvec3();
    let offset = c.eye.as_dvec3() - target;
    let r = offset.length();
    if r <= 0.0 || !factor.is_finite() {
        return;
    }
    let new_r = (r * factor).clamp(limits.0, limits.1);
    c.eye = (target + offset * (new_r / r)).as_vec3();
}

/// Where `point` appears in an image of `size` pixels (origin top left),
/// or None behind the eye.
pub fn project(c: &Camera, point: Vec3, size: (f64, f64)) -> Option<DVec2> {
    let f = c.frame();
    let d = point.as_dvec3() - c.eye.as_dvec3();
    let depth = d.dot(f.forward);
    if depth <= 1e-6 {
        return None;
    }
    let t = c.tan_half_fovy();
    let aspect = size.0 / size.1.max(1.0);
    let sx = d.dot(f.right) / (depth * t * aspect);
    let sy = d.dot(f.up) / (depth * t);
    Some(DVec2::new((sx + 1.0) * 0.5 * size.0, (1.0 - sy) * 0.5 * size.1))
}

/// `point` moved in the plane parallel to the image through it, by the
/// cursor's motion `delta_px` (x right, y down).
pub fn drag_in_image_plane(c: &Camera, point: Vec3, delta_px: DVec2, height_px: f64) -> Vec3 {
    let f = c.frame();
    let depth = (point - c.eye).as_dvec3().dot(f.forward);
    let s = metres_per_pixel(c, depth, height_px);
    (point.as_dvec3() + (f.right * delta_px.x - f.up * delta_px.y) * s).as_vec3()
}

/// `point` moved vertically (world +Y) by the cursor's vertical motion.
pub fn drag_height(c: &Camera, point: Vec3, delta_y_px: f64, height_px: f64) -> Vec3 {
    let f = c.frame();
    let depth = (point - c.eye).as_dvec3().dot(f.forward);
    let s = metres_per_pixel(c, depth, height_px);
    point - Vec3::Y * (delta_y_px * s) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        Camera::default()
    }

    #[test]
    fn orbit_keeps_the_distance_and_target() {
        let mut c = cam();
        let r0 = (c.eye - c.target).length();
        orbit(&mut c, 37.0, -12.0);
        assert!(((c.eye - c.target).length() - r0).abs() < 1e-4);
        assert_eq!(c.target, cam().target);
        orbit(&mut c, 0.0, 500.0);
        let elevation = ((c.eye - c.target).normalize().y as f64).asin().to_degrees();
        assert!(elevation < 89.5 && elevation > 88.0, "{elevation}");
    }

    #[test]
    fn zoom_scales_the_distance_within_limits() {
        let mut c = cam();
        let r0 = (c.eye - c.target).length() as f64;
        let limits = crate::scene::SceneScale::BUILT_IN.orbit_distance_m();
        zoom(&mut c, 0.5, limits);
        assert!(((c.eye - c.target).length() as f64 - 0.5 * r0).abs() < 1e-4);
        zoom(&mut c, 1e-9, limits);
        assert!(((c.eye - c.target).length() as f64 - limits.0).abs() < 1e-4);
    }

    #[test]
    fn the_target_projects_to_the_centre() {
        let c = cam();
        let p = project(&c, c.target, (800.0, 600.0)).unwrap();
        assert!((p - DVec2::new(400.0, 300.0)).length() < 1e-3);
        let behind = c.eye + (c.eye - c.target);
        assert!(project(&c, behind, (800.0, 600.0)).is_none());
    }

    #[test]
    fn projection_matches_the_pixel_rays() {
        let c = cam();
        let (w, h) = (640u32, 480u32);
        let ray = c.ray_direction(100.5, 50.5, w, h);
        let point = (c.eye.as_dvec3() + ray * 6.0).as_vec3();
        let p = project(&c, point, (w as f64, h as f64)).unwrap();
        assert!((p - DVec2::new(100.5, 50.5)).length() < 1e-2, "{p}");
    }

    #[test]
    fn dragging_in_the_image_plane_follows_the_cursor() {
        let c = cam();
        let size = (800.0, 600.0);
        let light = Vec3::new(1.0, 3.0, 0.5);
        let before = project(&c, light, size).unwrap();
        let moved = drag_in_image_plane(&c, light, DVec2::new(30.0, -20.0), size.1);
        let after = project(&c, moved, size).unwrap();
        assert!(
            (after - before - DVec2::new(30.0, -20.0)).length() < 0.05,
            "{}",
            after - before
        );
        let up = drag_height(&c, light, -10.0, size.1);
        assert!(up.y > light.y && up.x == light.x && up.z == light.z);
    }

    #[test]
    fn pan_moves_eye_and_target_together() {
        let mut c = cam();
        let offset = c.eye - c.target;
        pan(&mut c, DVec2::new(15.0, 5.0), 600.0);
        assert!(((c.eye - c.target) - offset).length() < 1e-5);
        assert_ne!(c.target, cam().target);
    }
}
