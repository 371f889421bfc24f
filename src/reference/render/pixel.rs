//! A pixel's values from its samples, and the tiles that collect them.

use super::TILE;
use crate::reference::image::{ReferenceImage, luminance};
use crate::reference::sampling::collapsed_strata_variance;
use crate::reference::shading::LightEstimate;
use glam::DVec3;
use rayon::prelude::*;

pub(super) struct Pixel {
    pub(super) radiance: [f64; 3],
    pub(super) visibility: f32,
    pub(super) coverage: f32,
    pub(super) noise: f32,
    pub(super) primary_rays: u64,
    pub(super) shadow_rays: u64,
    pub(super) noise_known: bool,
}

impl Pixel {
    /// A pixel whose `n` samples all see the background: what
    /// `Reference::shade_pixel` makes of them.
    pub(super) fn background(n: u32) -> Self {
        Self {
            radiance: [0.0; 3],
            visibility: 0.0,
            coverage: 0.0,
            noise: 0.0,
            primary_rays: n as u64,
            shadow_rays: 0,
            noise_known: true,
        }
    }
}

pub(super) struct Tile {
    pub(super) x0: u32,
    pub(super) width: u32,
    pub(super) pixels: Vec<Pixel>,
    pub(super) primary_rays: u64,
    pub(super) shadow_rays: u64,
    pub(super) noise_known: bool,
}

impl Tile {
    /// The next pixel, in row order, and its rays.
    #[inline(always)]
    pub(super) fn add(&mut self, pixel: Pixel) {
        self.primary_rays += pixel.primary_rays;
        self.shadow_rays += pixel.shadow_rays;
        self.noise_known &= pixel.noise_known;
        self.pixels.push(pixel);
    }
}

/// The running sums of a pixel's samples, in their order.
pub(super) struct PixelSums<'a> {
    sum: [f64; 3],
    hits: u32,
    visibility: f64,
    variance: f64,
    shadow_rays: u64,
    noise_known: bool,
    /// Each sample's luminance, for the noise estimate.
    luminance: &'a mut Vec<f64>,
}

impl<'a> PixelSums<'a> {
    pub(super) fn new(luminance: &'a mut Vec<f64>) -> Self {
        luminance.clear();
        Self {
            sum: [0.0; 3],
            hits: 0,
            visibility: 0.0,
            variance: 0.0,
            shadow_rays: 0,
            noise_known: true,
            luminance,
        }
    }

    /// A sample that sees the background.
    pub(super) fn add_background(&mut self) {
        self.luminance.push(0.0);
    }

    /// A sample on a surface of this tint, lit by `light`, of a pixel of
    /// `n` samples.
    #[inline(always)]
    pub(super) fn add(&mut self, tint: DVec3, light: &LightEstimate, n: u32) {
        self.shadow_rays += light.shadow_rays as u64;
        self.hits += 1;
        self.visibility += light.visibility;
        let l = (tint * light.scaled_radiance).to_array();
        for (sum, l) in self.sum.iter_mut().zip(l) {
            *sum += l;
        }
        self.luminance.push(luminance(l));
        match light.std_error {
            // A point light's: nothing to add.
            Some(0.0) => {}
            Some(se) => self.variance += (luminance(tint.to_array()) * se).powi(2),
            None => self.noise_known &= n > 1,
        }
    }

    /// The pixel of `n` samples.
    pub(super) fn pixel(self, n: u32) -> Pixel {
        // One sample: its own light-sampling error; more: the spread
        // between the pixel's strata, which includes it.
        let noise = if n == 1 {
            self.variance.sqrt()
        } else {
            collapsed_strata_variance(self.luminance).map_or(0.0, f64::sqrt)
        };
        Pixel {
            radiance: self.sum.map(|c| c / n as f64),
            visibility: if self.hits > 0 {
                (self.visibility / self.hits as f64) as f32
            } else {
                0.0
            },
            coverage: self.hits as f32 / n as f32,
            noise: noise as f32,
            primary_rays: n as u64,
            shadow_rays: self.shadow_rays,
            noise_known: self.noise_known,
        }
    }
}

impl ReferenceImage {
    /// Copies each tile's pixels into place, `tiles` in row order of
    /// [`TILE`]-pixel squares: one band of tiles a job, a row at a time (on
    /// one thread, pixel by pixel with two divisions each and the arrays'
    /// first touch, it took some 4 % of the engine's render).
    pub(super) fn place_tiles(&mut self, tiles: &[Option<Tile>]) {
        let width = self.width as usize;
        let band = width * TILE as usize;
        self.radiance
            .par_chunks_mut(band)
            .zip(self.visibility.par_chunks_mut(band))
            .zip(self.coverage.par_chunks_mut(band))
            .zip(self.noise.par_chunks_mut(band))
            .zip(tiles.par_chunks(width.div_ceil(TILE as usize)))
            .for_each(|((((radiance, visibility), coverage), noise), tiles)| {
                for tile in tiles.iter().flatten() {
                    for (r, row) in tile.pixels.chunks(tile.width as usize).enumerate() {
                        let at = r * width + tile.x0 as usize;
                        for (k, px) in row.iter().enumerate() {
                            radiance[at + k] = px.radiance;
                            visibility[at + k] = px.visibility;
                            coverage[at + k] = px.coverage;
                            noise[at + k] = px.noise;
                        }
                    }
                }
            });
    }
}
