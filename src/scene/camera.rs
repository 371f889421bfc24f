//! The lab's camera model, shared by the GPU renderer and the CPU reference so
//! that their images compare pixel by pixel.
//!
//! Perspective, given by eye, target and the vertical field of view; up is +Y.
//! Pixel (i, j) of a W×H image has its centre at (i + 0.5, j + 0.5) and row 0
//! is the top of the image. The GPU's depth is reversed-Z (near → 1, far → 0)
//! for precision from millimetres to kilometres.

use glam::{DMat4, DVec3, DVec4, Vec3};
use serde::{Deserialize, Serialize};

/// A perspective camera: eye, target and vertical field of view; up is +Y.
/// The one camera type of the lab: the settings hold it, the app orbits it,
/// the renderer, the probe and the reference cast their rays from it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Camera {
    /// Eye position (m).
    pub eye: Vec3,
    /// Point looked at (m).
    pub target: Vec3,
    /// Vertical field of view (degrees).
    pub fovy_deg: f32,
}

impl Default for Camera {
    /// The built-in scene's designed view.
    fn default() -> Self {
        Self {
            eye: Self::DEFAULT_EYE,
            target: Self::DEFAULT_TARGET,
            fovy_deg: Self::DEFAULT_FOVY_DEG,
        }
    }
}

/// The rays of one image size: the camera's frame and the pixel-to-tangent
/// scales computed once, so that a ray costs no division but its
/// normalization. Every ray of the lab (the reference, the probe, the tests)
/// comes from here.
#[derive(Clone, Debug)]
pub struct PixelRays {
    pub eye: DVec3,
    frame: Frame,
    /// 2 / width and 2 / height (per pixel).
    x_scale: f64,
    y_scale: f64,
    /// tan(fovy / 2) · aspect and tan(fovy / 2).
    tan_x: f64,
    tan_y: f64,
}

impl PixelRays {
    /// The unit direction through image point (x, y) (pixels).
    #[inline]
    pub fn direction(&self, x: f64, y: f64) -> DVec3 {
        self.towards(x, y).normalize()
    }

    /// A direction through image point (x, y), not normalized:
    /// forward + sx · right + sy · up on the plane one metre ahead.
    #[inline]
    pub fn towards(&self, x: f64, y: f64) -> DVec3 {
        let f = &self.frame;
        let (sx, sy) = self.tangents(x, y);
        f.forward + f.right * sx + f.up * sy
    }

    /// [`Self::towards`] of each image point (x\[k\], y\[k\]), by coordinate
    /// into `out`: the same operations, in a loop without branches, for
    /// lanes.
    #[inline(always)]
    pub fn towards_all(&self, (x, y): (&[f64], &[f64]), out: [&mut [f64]; 3]) {
        let n = x.len();
        let y = &y[..n];
        let [ox, oy, oz] = out.map(|o| &mut o[..n]);
        let f = &self.frame;
        for k in 0..n {
            let (sx, sy) = self.tangents(x[k], y[k]);
            ox[k] = f.forward.x + f.right.x * sx + f.up.x * sy;
            oy[k] = f.forward.y + f.right.y * sx + f.up.y * sy;
            oz[k] = f.forward.z + f.right.z * sx + f.up.z * sy;
        }
    }

    /// The tangents (sx, sy) of image point (x, y) on the plane one metre
    /// ahead.
    #[inline(always)]
    fn tangents(&self, x: f64, y: f64) -> (f64, f64) {
        (
            (x * self.x_scale - 1.0) * self.tan_x,
            (1.0 - y * self.y_scale) * self.tan_y,
        )
    }
}

/// An orthonormal camera frame in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub right: DVec3,
    pub up: DVec3,
    /// Unit direction from the eye towards the target.
    pub forward: DVec3,
}

impl Camera {
    pub const DEFAULT_EYE: Vec3 = Vec3::new(0.0, 3.4, 8.2);
    pub const DEFAULT_TARGET: Vec3 = Vec3::new(0.0, 0.7, 0.0);
    pub const DEFAULT_FOVY_DEG: f32 = 45.0;
    /// The image shape the vertical field of view is meant for: the command
    /// line's default 16:9 image.
    pub const FRAME_ASPECT: f64 = 16.0 / 9.0;
    /// The widest vertical field of view [`Camera::widened_for`] gives (degrees).
    const MAX_WIDENED_FOVY_DEG: f64 = 75.0;

    /// This camera as a viewport of `size` pixels shows it: unchanged when
    /// the viewport is at least as wide as 16:9; narrower, the vertical
    /// field of view widens so that the 16:9 frame's horizontal extent still
    /// fits (the panels, not the user, chose the viewport's shape), up to
    /// 75° (beyond, a very narrow viewport crops the sides rather than
    /// distort the view). It frames nothing: eye and target stay.
    pub fn widened_for(&self, size: (u32, u32)) -> Self {
        let aspect = size.0 as f64 / size.1.max(1) as f64;
        if size.0 == 0 || aspect >= Self::FRAME_ASPECT {
            return *self;
        }
        let tan_half = self.tan_half_fovy() * Self::FRAME_ASPECT / aspect;
        let widest = Self::MAX_WIDENED_FOVY_DEG.max(self.fovy_deg as f64);
        Self {
            fovy_deg: (2.0 * tan_half.atan().to_degrees()).min(widest) as f32,
            ..*self
        }
    }

    /// Right, up and forward. Up is +Y; when looking straight up or down, +Z
    /// stands in for it so the frame stays defined.
    pub fn frame(&self) -> Frame {
        look_frame(self.eye.as_dvec3(), self.target.as_dvec3())
    }

    /// tan(fovy / 2).
    pub fn tan_half_fovy(&self) -> f64 {
        (0.5 * (self.fovy_deg as f64).to_radians()).tan()
    }

    /// Unit direction of the ray through the image point (x, y) in pixels of a
    /// `width`×`height` image; pixel centres are at (i + 0.5, j + 0.5).
    pub fn ray_direction(&self, x: f64, y: f64, width: u32, height: u32) -> DVec3 {
        self.pixel_rays(width, height).direction(x, y)
    }

    /// The rays of a `width`×`height` image, for casting many.
    pub fn pixel_rays(&self, width: u32, height: u32) -> PixelRays {
        let t = self.tan_half_fovy();
        PixelRays {
            eye: self.eye.as_dvec3(),
            frame: self.frame(),
            x_scale: 2.0 / width as f64,
            y_scale: 2.0 / height as f64,
            tan_x: t * (width as f64 / height as f64),
            tan_y: t,
        }
    }

    /// World → view: a rotation (no translation: the GPU works relative to the
    /// eye for precision). View space looks down −Z with +Y up.
    pub fn view_rotation(&self) -> DMat4 {
        let f = self.frame();
        rotation_to_view(&f)
    }

    /// Reversed-Z perspective projection for `aspect` = width / height.
    pub fn projection(&self, aspect: f64, near: f64, far: f64) -> DMat4 {
        let t = self.tan_half_fovy();
        reversed_z_projection(-t * aspect, t * aspect, -t, t, near, far)
    }
}

/// The frame looking from `eye` at `target` with +Y up (+Z when vertical).
pub fn look_frame(eye: DVec3, target: DVec3) -> Frame {
    let forward = (target - eye).normalize_or(DVec3::NEG_Z);
    let up_hint = if forward.cross(DVec3::Y).length_squared() < 1e-12 {
        DVec3::Z
    } else {
        DVec3::Y
    };
    let right = forward.cross(up_hint).normalize();
    let up = right.cross(forward);
    Frame { right, up, forward }
}

/// The rotation taking world directions to a view space that looks down −Z.
pub fn rotation_to_view(f: &Frame) -> DMat4 {
    DMat4::from_cols(
        DVec4::new(f.right.x, f.up.x, -f.forward.x, 0.0),
        DVec4::new(f.right.y, f.up.y, -f.forward.y, 0.0),
        DVec4::new(f.right.z, f.up.z, -f.forward.z, 0.0),
        DVec4::W,
    )
}

/// An off-centre perspective projection with reversed Z: view-space points at
/// depth z = −z_view ∈ [near, far] whose x/z lies in [left, right] and y/z in
/// [bottom, top] (tangents) map to NDC x, y ∈ [−1, 1] and depth
/// d = a / z + b ∈ [0, 1], with d(near) = 1 and d(far) = 0.
pub fn reversed_z_projection(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> DMat4 {
    let (a, b) = reversed_z_coefficients(near, far);
    let sx = 2.0 / (right - left);
    let sy = 2.0 / (top - bottom);
    let cx = (right + left) / (right - left);
    let cy = (top + bottom) / (top - bottom);
    // clip = (sx x + cx z, sy y + cy z, a + b z, z) with z = −z_view.
    DMat4::from_cols(
        DVec4::new(sx, 0.0, 0.0, 0.0),
        DVec4::new(0.0, sy, 0.0, 0.0),
        DVec4::new(cx, cy, -b, -1.0),
        DVec4::new(0.0, 0.0, a, 0.0),
    )
}

/// The (a, b) of reversed-Z depth d = a / z + b: a = near·far / (far − near),
/// b = −near / (far − near). The inverse is z = a / (d − b).
pub fn reversed_z_coefficients(near: f64, far: f64) -> (f64, f64) {
    let span = far - near;
    (near * far / span, -near / span)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: Vec3::new(1.0, 2.0, 5.0),
            target: Vec3::new(0.0, 0.5, 0.0),
            fovy_deg: 50.0,
        }
    }

    #[test]
    fn centre_ray_looks_at_the_target() {
        let c = camera();
        let d = c.ray_direction(50.0, 40.0, 100, 80);
        let expected = (c.target - c.eye).as_dvec3().normalize();
        assert!((d - expected).length() < 1e-12);
    }

    #[test]
    fn projection_maps_pixel_rays_to_pixel_centres() {
        let c = camera();
        let (w, h) = (64, 48);
        let proj = c.projection(w as f64 / h as f64, 0.1, 100.0);
        let view = c.view_rotation();
        for &(i, j) in &[(0u32, 0u32), (63, 0), (10, 47), (32, 24)] {
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            let p = c.ray_direction(x, y, w, h) * 7.0;
            let clip = proj * view * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let px = (ndc.x + 1.0) * 0.5 * w as f64;
            let py = (1.0 - ndc.y) * 0.5 * h as f64;
            assert!(
                (px - x).abs() < 1e-9 && (py - y).abs() < 1e-9,
                "{px},{py} vs {x},{y}"
            );
        }
    }

    #[test]
    fn off_centre_projection_maps_its_extents_to_the_ndc_edges() {
        let proj = reversed_z_projection(-0.2, 0.6, 0.1, 0.5, 1.0, 10.0);
        let ndc = |tx: f64, ty: f64| {
            let clip = proj * DVec4::new(tx * 3.0, ty * 3.0, -3.0, 1.0);
            (clip.x / clip.w, clip.y / clip.w)
        };
        let (x0, y0) = ndc(-0.2, 0.1);
        let (x1, y1) = ndc(0.6, 0.5);
        assert!((x0 + 1.0).abs() < 1e-12 && (y0 + 1.0).abs() < 1e-12, "{x0} {y0}");
        assert!((x1 - 1.0).abs() < 1e-12 && (y1 - 1.0).abs() < 1e-12, "{x1} {y1}");
    }

    #[test]
    fn reversed_z_maps_near_to_one_and_far_to_zero() {
        let proj = reversed_z_projection(-1.0, 1.0, -1.0, 1.0, 0.5, 200.0);
        let depth = |z: f64| {
            let clip = proj * DVec4::new(0.0, 0.0, -z, 1.0);
            clip.z / clip.w
        };
        assert!((depth(0.5) - 1.0).abs() < 1e-12);
        assert!(depth(200.0).abs() < 1e-12);
        let (a, b) = reversed_z_coefficients(0.5, 200.0);
        assert!((a / (depth(13.0) - b) - 13.0).abs() < 1e-9);
    }

    #[test]
    fn a_narrow_viewport_keeps_the_16_9_frames_width() {
        let c = Camera::default();
        assert_eq!(c.widened_for((1600, 900)), c);
        assert_eq!(c.widened_for((2000, 900)), c);
        let square = c.widened_for((900, 900));
        assert!(square.fovy_deg > c.fovy_deg);
        let half_width = |c: &Camera, aspect: f64| (0.5 * c.fovy_deg as f64).to_radians().tan() * aspect;
        assert!((half_width(&square, 1.0) / half_width(&c, Camera::FRAME_ASPECT) - 1.0).abs() < 1e-6);
        assert_eq!((square.eye, square.target), (c.eye, c.target));
        assert_eq!(c.widened_for((1, 10_000)).fovy_deg, 75.0);
        // A view set wider than the cap is never narrowed.
        let wide = Camera { fovy_deg: 120.0, ..c };
        assert_eq!(wide.widened_for((500, 1000)).fovy_deg, 120.0);
    }

    #[test]
    fn looking_straight_down_keeps_a_frame() {
        let f = look_frame(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO);
        assert!(f.right.is_finite() && f.up.is_finite());
        assert!((f.right.cross(f.up) - (-f.forward)).length() < 1e-12);
    }
}
