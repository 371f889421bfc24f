//! Orbit, pan and zoom of the camera, and the light gizmo's projection and
//! drags, as plain functions of the camera settings (no egui here).

use crate::scene::Camera;
use crate::settings::CameraSettings;
use glam::{DVec2, DVec3, Vec3};

/// The closest the eye may come to the target (m).
pub const MIN_DISTANCE_M: f64 = 0.05;
/// The furthest (m).
pub const MAX_DISTANCE_M: f64 = 1e4;
/// Pitch stays within this of the poles (degrees) so the frame stays defined.
const POLE_MARGIN_DEG: f64 = 1.0;

/// The frame the settings' vertical field of view is meant for: the
/// command line's default 16:9 image.
pub const FRAME_ASPECT: f64 = 16.0 / 9.0;
/// The widest vertical field of view the fit gives (degrees).
const MAX_FITTED_FOVY_DEG: f64 = 75.0;

/// The camera a viewport of `size` pixels shows: as set when the viewport is
/// at least as wide as 16:9; narrower, the vertical field of view widens so
/// that the 16:9 frame's horizontal extent still fits (the panels, not the
/// user, chose the viewport's shape), up to 75° (beyond, a very narrow
/// viewport crops the sides rather than distort the view).
pub fn fitted(c: &CameraSettings, size: (u32, u32)) -> CameraSettings {
    let aspect = size.0 as f64 / size.1.max(1) as f64;
    if size.0 == 0 || aspect >= FRAME_ASPECT {
        return *c;
    }
    let tan_half = (0.5 * c.fovy_deg as f64).to_radians().tan() * FRAME_ASPECT / aspect;
    CameraSettings {
        fovy_deg: (2.0 * tan_half.atan().to_degrees()).min(MAX_FITTED_FOVY_DEG.max(c.fovy_deg as f64)) as f32,
        ..*c
    }
}

fn camera(c: &CameraSettings) -> Camera {
    Camera {
        eye: c.eye,
        target: c.target,
        fovy_deg: c.fovy_deg,
    }
}

/// Turns the eye around the target: `yaw_deg` about +Y, `pitch_deg` up/down.
pub fn orbit(c: &mut CameraSettings, yaw_deg: f64, pitch_deg: f64) {
    let target = c.target.as_dvec3();
    let offset = c.eye.as_dvec3() - target;
    let r = offset.length().max(MIN_DISTANCE_M);
    let yaw = offset.x.atan2(offset.z) + yaw_deg.to_radians();
    let limit = (90.0 - POLE_MARGIN_DEG).to_radians();
    let pitch = ((offset.y / r).clamp(-1.0, 1.0).asin() + pitch_deg.to_radians()).clamp(-limit, limit);
    let dir = DVec3::new(pitch.cos() * yaw.sin(), pitch.sin(), pitch.cos() * yaw.cos());
    c.eye = (target + dir * r).as_vec3();
}

/// Metres per pixel at `depth_m` in front of the eye, for an image
/// `height_px` tall.
fn metres_per_pixel(c: &CameraSettings, depth_m: f64, height_px: f64) -> f64 {
    2.0 * depth_m.max(1e-6) * camera(c).tan_half_fovy() / height_px.max(1.0)
}

/// Moves eye and target together so the point under the cursor follows it.
pub fn pan(c: &mut CameraSettings, delta_px: DVec2, height_px: f64) {
    let frame = camera(c).frame();
    let distance = (c.target - c.eye).as_dvec3().length();
    let s = metres_per_pixel(c, distance, height_px);
    let shift = (frame.up * delta_px.y - frame.right * delta_px.x) * s;
    c.eye = (c.eye.as_dvec3() + shift).as_vec3();
    c.target = (c.target.as_dvec3() + shift).as_vec3();
}

/// Scales the eye's distance to the target by `factor` (< 1 comes closer).
pub fn zoom(c: &mut CameraSettings, factor: f64) {
    let target = c.target.as_dvec3();
    let offset = c.eye.as_dvec3() - target;
    let r = offset.length();
    if r <= 0.0 || !factor.is_finite() {
        return;
    }
    let new_r = (r * factor).clamp(MIN_DISTANCE_M, MAX_DISTANCE_M);
    c.eye = (target + offset * (new_r / r)).as_vec3();
}

/// Where `point` appears in an image of `size` pixels (origin top left),
/// or None behind the eye.
pub fn project(c: &CameraSettings, point: Vec3, size: (f64, f64)) -> Option<DVec2> {
    let cam = camera(c);
    let f = cam.frame();
    let d = point.as_dvec3() - cam.eye.as_dvec3();
    let depth = d.dot(f.forward);
    if depth <= 1e-6 {
        return None;
    }
    let t = cam.tan_half_fovy();
    let aspect = size.0 / size.1.max(1.0);
    let sx = d.dot(f.right) / (depth * t * aspect);
    let sy = d.dot(f.up) / (depth * t);
    Some(DVec2::new((sx + 1.0) * 0.5 * size.0, (1.0 - sy) * 0.5 * size.1))
}

/// `point` moved in the plane parallel to the image through it, by the
/// cursor's motion `delta_px` (x right, y down).
pub fn drag_in_image_plane(c: &CameraSettings, point: Vec3, delta_px: DVec2, height_px: f64) -> Vec3 {
    let f = camera(c).frame();
    let depth = (point - c.eye).as_dvec3().dot(f.forward);
    let s = metres_per_pixel(c, depth, height_px);
    (point.as_dvec3() + (f.right * delta_px.x - f.up * delta_px.y) * s).as_vec3()
}

/// `point` moved vertically (world +Y) by the cursor's vertical motion.
pub fn drag_height(c: &CameraSettings, point: Vec3, delta_y_px: f64, height_px: f64) -> Vec3 {
    let f = camera(c).frame();
    let depth = (point - c.eye).as_dvec3().dot(f.forward);
    let s = metres_per_pixel(c, depth, height_px);
    point - Vec3::Y * (delta_y_px * s) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> CameraSettings {
        CameraSettings::default()
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
        zoom(&mut c, 0.5);
        assert!(((c.eye - c.target).length() as f64 - 0.5 * r0).abs() < 1e-4);
        zoom(&mut c, 1e-9);
        assert!(((c.eye - c.target).length() as f64 - MIN_DISTANCE_M).abs() < 1e-4);
    }

    #[test]
    fn a_narrow_viewport_keeps_the_16_9_frames_width() {
        let c = CameraSettings::default();
        assert_eq!(fitted(&c, (1600, 900)), c);
        assert_eq!(fitted(&c, (2000, 900)), c);
        let square = fitted(&c, (900, 900));
        assert!(square.fovy_deg > c.fovy_deg);
        let half_width =
            |c: &CameraSettings, aspect: f64| (0.5 * c.fovy_deg as f64).to_radians().tan() * aspect;
        assert!((half_width(&square, 1.0) / half_width(&c, FRAME_ASPECT) - 1.0).abs() < 1e-6);
        assert_eq!((square.eye, square.target), (c.eye, c.target));
        assert_eq!(fitted(&c, (1, 10_000)).fovy_deg, 75.0);
        // A view set wider than the cap is never narrowed.
        let wide = CameraSettings { fovy_deg: 120.0, ..c };
        assert_eq!(fitted(&wide, (500, 1000)).fovy_deg, 120.0);
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
        let ray = Camera {
            eye: c.eye,
            target: c.target,
            fovy_deg: c.fovy_deg,
        }
        .ray_direction(100.5, 50.5, w, h);
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
