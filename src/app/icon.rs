//! The application icon, drawn here rather than in an image editor: a
//! Lambert + Blinn-Phong sphere lit by a small yellow light above a dark
//! rounded square, the lab's subject in one picture.
//! It is stored in `assets/icon.png` (used by the `.desktop` entry), which
//! the window embeds; `LUMLAB_RENEW_ASSETS=1 cargo test --lib
//! generated_asset` writes it anew after a change here (then commit it).

use glam::Vec3;

/// The committed icon, relative to the crate root.
pub const ASSET_PATH: &str = "assets/icon.png";
/// The icon as checked in, embedded in the binary.
pub const ASSET: &[u8] = include_bytes!("../../assets/icon.png");
/// The icon's side (pixels).
pub const SIZE: u32 = 256;

/// Samples per pixel along each axis (antialiasing).
const SUPERSAMPLE: u32 = 4;
const LIGHT_CENTRE: (f32, f32) = (0.24, 0.22);
const SPHERE_CENTRE: (f32, f32) = (0.54, 0.57);
const SPHERE_RADIUS: f32 = 0.29;

/// The icon at `size` × `size` pixels, RGBA with sRGB colours.
pub fn draw(size: u32) -> image::RgbaImage {
    let n = SUPERSAMPLE;
    image::RgbaImage::from_fn(size, size, |i, j| {
        let mut colour = Vec3::ZERO;
        let mut coverage = 0.0;
        for sj in 0..n {
            for si in 0..n {
                let u = (i as f32 + (si as f32 + 0.5) / n as f32) / size as f32;
                let v = (j as f32 + (sj as f32 + 0.5) / n as f32) / size as f32;
                if let Some(c) = sample(u, v) {
                    colour += c;
                    coverage += 1.0;
                }
            }
        }
        if coverage == 0.0 {
            return image::Rgba([0, 0, 0, 0]);
        }
        let c = colour / coverage;
        let alpha = coverage / (n * n) as f32;
        image::Rgba([srgb8(c.x), srgb8(c.y), srgb8(c.z), (alpha * 255.0).round() as u8])
    })
}

/// The embedded icon for the window (None if the asset cannot be decoded,
/// which a test rules out).
pub fn window_icon() -> Option<egui::IconData> {
    let image = image::load_from_memory(ASSET).ok()?.to_rgba8();
    Some(egui::IconData {
        width: image.width(),
        height: image.height(),
        rgba: image.into_raw(),
    })
}

/// Linear radiance at (u, v) ∈ [0, 1]² (v down), None outside the rounded square.
fn sample(u: f32, v: f32) -> Option<Vec3> {
    if !in_rounded_square(u, v, 0.03, 0.2) {
        return None;
    }
    let background = Vec3::new(0.018, 0.022, 0.035).lerp(Vec3::new(0.004, 0.005, 0.009), v);
    // The sphere's soft shadow on the floor, away from the light.
    let (sx, sy) = ((u - 0.62) / 0.3, (v - 0.86) / 0.07);
    let shadow = 1.0 - 0.8 * (1.0 - (sx * sx + sy * sy)).clamp(0.0, 1.0);
    let mut colour = background * shadow;

    let (x, y) = (
        (u - SPHERE_CENTRE.0) / SPHERE_RADIUS,
        (SPHERE_CENTRE.1 - v) / SPHERE_RADIUS,
    );
    let r2 = x * x + y * y;
    if r2 < 1.0 {
        colour = shade_sphere(Vec3::new(x, y, (1.0 - r2).sqrt()));
    }
    // The light: a small disc with a glow.
    let d = ((u - LIGHT_CENTRE.0).powi(2) + (v - LIGHT_CENTRE.1).powi(2)).sqrt();
    let glow = Vec3::new(1.0, 0.8, 0.3) * (0.0018 / (d * d + 0.0009));
    colour += glow;
    if d < 0.045 {
        colour = Vec3::new(1.0, 0.93, 0.7) * 3.0;
    }
    Some(colour)
}

/// L = c · (k/π + (1 − k) · (m + 8)/8π · cos^m θ_h) · E, the lab's BRDF with
/// the light towards the upper left and the eye on +Z.
fn shade_sphere(n: Vec3) -> Vec3 {
    let light = Vec3::new(-0.62, 0.62, 0.48).normalize();
    let eye = Vec3::Z;
    let h = (light + eye).normalize();
    let (k, m) = (0.75_f32, 40.0_f32);
    let pi = std::f32::consts::PI;
    let cos_i = n.dot(light).max(0.0);
    let lobe = (m + 8.0) / (8.0 * pi) * n.dot(h).max(0.0).powf(m);
    let albedo = Vec3::new(0.85, 0.3, 0.08);
    let irradiance = 6.0 * cos_i;
    albedo * (k / pi) * irradiance + Vec3::splat((1.0 - k) * lobe * irradiance) + albedo * 0.015
}

fn in_rounded_square(u: f32, v: f32, margin: f32, radius: f32) -> bool {
    let (lo, hi) = (margin + radius, 1.0 - margin - radius);
    let dx = (u - u.clamp(lo, hi)).abs();
    let dy = (v - v.clamp(lo, hi)).abs();
    dx * dx + dy * dy <= radius * radius
}

/// Linear to an 8-bit sRGB value (clipped at white).
fn srgb8(linear: f32) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generated_asset_is_what_draw_paints() {
        let asset = image::load_from_memory(ASSET)
            .expect("assets/icon.png decodes")
            .to_rgba8();
        let drawn = draw(SIZE);
        // One unit of rounding apart at most: the float maths may round
        // differently from one CPU to another.
        let worst = asset
            .pixels()
            .zip(drawn.pixels())
            .flat_map(|(a, b)| (0..4).map(move |c| a.0[c].abs_diff(b.0[c])))
            .max();
        if asset.dimensions() != drawn.dimensions() || worst > Some(1) {
            let png = crate::image_io::encode(&drawn, image::ImageFormat::Png).expect("the icon encodes");
            crate::output::renew_asset_or_fail(ASSET_PATH, &png);
        }
    }

    #[test]
    fn the_window_icon_is_square_and_opaque_in_the_middle() {
        let icon = window_icon().expect("the embedded icon decodes");
        assert_eq!((icon.width, icon.height), (SIZE, SIZE));
        let centre = ((SIZE / 2 * SIZE + SIZE / 2) * 4 + 3) as usize;
        assert_eq!(icon.rgba[centre], 255);
        assert_eq!(icon.rgba[3], 0, "the corner is transparent");
    }
}
