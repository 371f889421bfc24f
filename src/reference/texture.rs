//! Base-colour textures as the GPU samples them: sRGB texels decoded to linear
//! before filtering, bilinear between texel centres, repeat wrapping.

use crate::physics::display::srgb_decode;
use crate::scene::Texture;
use glam::{DVec2, DVec3};

/// A texture decoded to linear RGB once.
#[derive(Clone, Debug)]
pub struct LinearTexture {
    width: usize,
    height: usize,
    /// Row-major, row 0 at v = 0.
    texels: Vec<DVec3>,
}

impl LinearTexture {
    /// None when the texture is empty or its bytes do not match its size.
    pub fn new(texture: &Texture) -> Option<Self> {
        let (width, height) = (texture.width as usize, texture.height as usize);
        if width == 0 || height == 0 || texture.rgba8.len() != width * height * 4 {
            return None;
        }
        let lut: Vec<f64> = (0..=255).map(|b| srgb_decode(b as f64 / 255.0)).collect();
        let texels = texture
            .rgba8
            .chunks_exact(4)
            .map(|t| DVec3::new(lut[t[0] as usize], lut[t[1] as usize], lut[t[2] as usize]))
            .collect();
        Some(Self {
            width,
            height,
            texels,
        })
    }

    /// The bilinear, repeat-wrapped linear colour at `uv` (texel centres at
    /// ((i + 0.5) / w, (j + 0.5) / h)).
    pub fn sample(&self, uv: DVec2) -> DVec3 {
        let x = uv.x * self.width as f64 - 0.5;
        let y = uv.y * self.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        // Non-finite uv: the casts saturate and wrap to a texel, never panic.
        let wrap = |i: f64, n: usize| (i as i64).rem_euclid(n as i64) as usize;
        let (i0, i1) = (wrap(x0, self.width), wrap(x0 + 1.0, self.width));
        let (j0, j1) = (wrap(y0, self.height), wrap(y0 + 1.0, self.height));
        let at = |i: usize, j: usize| self.texels[j * self.width + i];
        let top = at(i0, j0).lerp(at(i1, j0), fx);
        let bottom = at(i0, j1).lerp(at(i1, j1), fx);
        let c = top.lerp(bottom, fy);
        if c.is_finite() { c } else { at(i0, j0) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker() -> LinearTexture {
        // 2 × 1: a black texel then a white one.
        LinearTexture::new(&Texture {
            width: 2,
            height: 1,
            rgba8: vec![0, 0, 0, 255, 255, 255, 255, 255],
        })
        .unwrap()
    }

    #[test]
    fn texel_centres_give_the_decoded_texel() {
        let t = checker();
        assert_eq!(t.sample(DVec2::new(0.25, 0.5)), DVec3::ZERO);
        assert_eq!(t.sample(DVec2::new(0.75, 0.5)), DVec3::ONE);
        let mid = LinearTexture::new(&Texture {
            width: 1,
            height: 1,
            rgba8: vec![128, 128, 128, 255],
        })
        .unwrap();
        let expected = srgb_decode(128.0 / 255.0);
        assert!((mid.sample(DVec2::new(0.3, 0.9)).x - expected).abs() < 1e-15);
    }

    #[test]
    fn filtering_is_linear_between_centres_and_wraps() {
        let t = checker();
        assert!((t.sample(DVec2::new(0.5, 0.5)).x - 0.5).abs() < 1e-15);
        // u = 0 lies halfway between the last texel (wrapped) and the first.
        assert!((t.sample(DVec2::new(0.0, 0.5)).x - 0.5).abs() < 1e-15);
        assert_eq!(t.sample(DVec2::new(3.75, -7.5)), DVec3::ONE);
        assert!(t.sample(DVec2::new(f64::NAN, 1e300)).is_finite());
    }

    #[test]
    fn mismatched_bytes_are_refused() {
        let bad = Texture {
            width: 2,
            height: 2,
            rgba8: vec![0; 4],
        };
        assert!(LinearTexture::new(&bad).is_none());
    }
}
