//! A pixel's values from its samples, and the tiles that collect them.

use super::TILE;
use crate::reference::image::luminance;
use crate::reference::sampling::collapsed_strata_variance;
use crate::reference::shading::LightEstimate;
use glam::DVec3;

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

/// One row of a tile in the image's arrays: radiance, visibility,
/// coverage and noise.
type Row<'a> = (&'a mut [[f64; 3]], &'a mut [f32], &'a mut [f32], &'a mut [f32]);

/// A tile's rows, top to bottom.
pub(super) type TileRows<'a> = Vec<Row<'a>>;

/// The image's arrays (`width` pixels a row) cut into the rows of each
/// [`TILE`]-pixel square, the squares in row order.
pub(super) fn tile_rows<'a>(
    width: usize,
    (radiance, visibility): (&'a mut [[f64; 3]], &'a mut [f32]),
    (coverage, noise): (&'a mut [f32], &'a mut [f32]),
) -> Vec<TileRows<'a>> {
    let side = TILE as usize;
    let across = width.div_ceil(side);
    let down = radiance.len().div_ceil(width * side);
    let mut tiles: Vec<TileRows> = (0..across * down).map(|_| Vec::with_capacity(side)).collect();
    let rows = radiance
        .chunks_mut(width)
        .zip(visibility.chunks_mut(width))
        .zip(coverage.chunks_mut(width).zip(noise.chunks_mut(width)));
    for (j, ((r, v), (c, n))) in rows.enumerate() {
        let parts = r
            .chunks_mut(side)
            .zip(v.chunks_mut(side))
            .zip(c.chunks_mut(side).zip(n.chunks_mut(side)));
        for (i, ((r, v), (c, n))) in parts.enumerate() {
            tiles[j / side * across + i].push((r, v, c, n));
        }
    }
    tiles
}

/// A tile being rendered: its pixels go straight into its rows of the
/// image, and its rays are counted.
pub(super) struct Tile<'a> {
    rows: TileRows<'a>,
    /// Where the next pixel goes: row, column.
    next: (usize, usize),
    pub(super) primary_rays: u64,
    pub(super) shadow_rays: u64,
    pub(super) noise_known: bool,
}

impl<'a> Tile<'a> {
    pub(super) fn new(rows: TileRows<'a>) -> Self {
        Self {
            rows,
            next: (0, 0),
            primary_rays: 0,
            shadow_rays: 0,
            noise_known: true,
        }
    }

    /// The next pixel, in row order, and its rays.
    #[inline(always)]
    pub(super) fn add(&mut self, pixel: Pixel) {
        self.primary_rays += pixel.primary_rays;
        self.shadow_rays += pixel.shadow_rays;
        self.noise_known &= pixel.noise_known;
        let (j, i) = self.next;
        let (radiance, visibility, coverage, noise) = &mut self.rows[j];
        radiance[i] = pixel.radiance;
        visibility[i] = pixel.visibility;
        coverage[i] = pixel.coverage;
        noise[i] = pixel.noise;
        self.next = if i + 1 == radiance.len() {
            (j + 1, 0)
        } else {
            (j, i + 1)
        };
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
