//! The reference image: pixels rendered in parallel over tiles, each with
//! its stratified samples, progress counted and cancellation honoured.

use super::bvh::{Cone, PrimaryPacket};
use super::grid::DirectionGrid;
use super::image::{ReferenceImage, RenderStats, luminance};
use super::sampling::{Rng, Strata, collapsed_strata_variance};
use super::shading::{Scratch, Setup, Surface};
use super::{Reference, ReferenceError, ReferenceOptions, RenderControl, pixel_index};
use crate::settings::Settings;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::Ordering;
use std::time::Instant;

/// Edge length of the square tiles the image is split into for the threads.
const TILE: u32 = 16;
/// Scenes with more triangles build no direction grids: most of their cells
/// would list more than `grid::MAX_LIST` and defer to the BVH anyway, and
/// the packets of a pixel's rays go through the BVH faster than building
/// the grids takes.
const GRID_MAX_TRIANGLES: usize = 16_384;

impl Reference {
    /// Renders the image, in parallel over tiles, reporting progress and
    /// stopping early when cancelled through `control`.
    pub fn render(
        &self,
        settings: &Settings,
        options: &ReferenceOptions,
        control: &RenderControl,
    ) -> Result<ReferenceImage, ReferenceError> {
        settings.validate()?;
        let start = Instant::now();
        let mut setup = Setup::new(settings, options.light_samples, options.seed, &self.materials);
        // Every primary ray leaves the eye and every point-light shadow ray
        // ends at the light: both are cast through direction grids there,
        // unless the scene is so large that their cells would be crowded.
        let grids = self.bvh_triangles.len() <= GRID_MAX_TRIANGLES;
        let light_grid = grids && setup.shadows && !setup.is_sphere_light();
        let (eye_grid, light_grid) = rayon::join(
            || grids.then(|| DirectionGrid::new(setup.rays.eye, &self.bvh_triangles, |_| true)),
            || {
                light_grid
                    .then(|| DirectionGrid::new(setup.light_position, &self.bvh_triangles, |t| t.occludes))
            },
        );
        (setup.eye_grid, setup.light_grid) = (eye_grid, light_grid);
        let setup = setup;
        let (width, height) = (setup.width, setup.height);
        let tiles: Vec<(u32, u32)> = (0..height.div_ceil(TILE))
            .flat_map(|ty| (0..width.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
            .collect();
        let spp = Strata::new(options.spp);
        let rendered: Vec<Option<Tile>> = tiles
            .par_iter()
            .map(|&(x0, y0)| self.render_tile(&setup, spp, x0, y0, control))
            .collect();
        if control.cancelled() {
            return Err(ReferenceError::Cancelled);
        }
        let pixels = width as usize * height as usize;
        let mut image = ReferenceImage {
            width,
            height,
            radiance: vec![[0.0; 3]; pixels],
            visibility: vec![0.0; pixels],
            coverage: vec![0.0; pixels],
            noise: vec![0.0; pixels],
            noise_known: true,
            stats: RenderStats {
                spp: spp.count(),
                light_samples: if setup.is_sphere_light() {
                    setup.light_strata.count()
                } else {
                    0
                },
                ..RenderStats::default()
            },
        };
        for tile in rendered.into_iter().flatten() {
            image.stats.primary_rays += tile.primary_rays;
            image.stats.shadow_rays += tile.shadow_rays;
            image.noise_known &= tile.noise_known;
            for (k, px) in tile.pixels.iter().enumerate() {
                let (i, j) = (tile.x0 + k as u32 % tile.width, tile.y0 + k as u32 / tile.width);
                let at = image.index(i, j);
                image.radiance[at] = px.radiance;
                image.visibility[at] = px.visibility;
                image.coverage[at] = px.coverage;
                image.noise[at] = px.noise;
            }
        }
        image.stats.elapsed = start.elapsed();
        Ok(image)
    }

    /// One tile, or None when cancelled.
    fn render_tile(
        &self,
        setup: &Setup,
        spp: Strata,
        x0: u32,
        y0: u32,
        control: &RenderControl,
    ) -> Option<Tile> {
        let (x1, y1) = ((x0 + TILE).min(setup.width), (y0 + TILE).min(setup.height));
        let mut tile = Tile {
            x0,
            y0,
            width: x1 - x0,
            pixels: Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize),
            primary_rays: 0,
            shadow_rays: 0,
            noise_known: true,
        };
        let mut buffers = PixelBuffers::default();
        for j in y0..y1 {
            if control.cancelled() {
                return None;
            }
            for i in x0..x1 {
                let pixel = self.render_pixel(setup, spp, i, j, &mut buffers);
                tile.primary_rays += spp.count() as u64;
                tile.shadow_rays += pixel.shadow_rays;
                tile.noise_known &= pixel.noise_known;
                tile.pixels.push(pixel);
            }
            control
                .pixels_done
                .fetch_add((x1 - x0) as usize, Ordering::Relaxed);
        }
        Some(tile)
    }

    /// Pixel (i, j) with `spp` primary samples: first every primary ray,
    /// then the light at every surface. Two short loops of independent
    /// iterations let the CPU overlap the samples' long chains of
    /// divisions and square roots better than one long loop does (8 %).
    #[inline(always)]
    fn render_pixel(&self, setup: &Setup, spp: Strata, i: u32, j: u32, buffers: &mut PixelBuffers) -> Pixel {
        let n = spp.count();
        let pixel = pixel_index(setup, i as f64, j as f64);
        let (x, y) = (i as f64, j as f64);
        // Several samples: find their cell once when it is the same for all.
        let cell = setup
            .eye_grid
            .as_ref()
            .filter(|_| n > 1)
            .and_then(|grid| grid.pixel_cell(&setup.rays, x, y));
        // Crowded cells (or none): the pixel's rays go through the BVH
        // together, as one packet in the cone of its corner rays.
        let packet = n > 1
            && setup.eye_grid.as_ref().is_none_or(|grid| {
                let centre = cell.or_else(|| grid.cell_of(setup.rays.towards(x + 0.5, y + 0.5)));
                centre.is_none_or(|c| grid.is_crowded(c))
            });
        let PixelBuffers {
            samples,
            luminance: sample_luminance,
            scratch,
            directions,
            packet: primary,
        } = buffers;
        samples.clear();
        directions.clear();
        let mut rngs = spp.cells().enumerate().map(|(s, stratum)| {
            let mut rng = Rng::new(setup.seed, pixel, s as u64);
            // DESIGN.md: one sample per pixel is the pixel centre.
            let (dx, dy) = if n == 1 {
                (0.5, 0.5)
            } else {
                spp.jittered(stratum, &mut rng)
            };
            (x + dx, y + dy, rng)
        });
        if packet {
            for (sx, sy, rng) in rngs {
                directions.push(setup.rays.towards(sx, sy));
                samples.push((None, rng));
            }
            let corners = [(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)];
            let cone = Cone::spanned(setup.rays.eye, corners.map(|(cx, cy)| setup.rays.towards(cx, cy)));
            self.bvh.closest_hits_in_cone(&cone, directions, primary);
            for ((surface, _), (&towards, hit)) in
                samples.iter_mut().zip(directions.iter().zip(primary.hits.iter()))
            {
                *surface = hit.map(|hit| self.surface_at(setup, towards, hit));
            }
        } else {
            for (sx, sy, rng) in &mut rngs {
                samples.push((self.surface(setup, sx, sy, cell), rng));
            }
        }
        let mut sum = [0.0; 3];
        let (mut hits, mut visibility, mut variance) = (0u32, 0.0, 0.0);
        let (mut shadow_rays, mut noise_known) = (0, true);
        if setup.shadows && !setup.is_sphere_light() {
            let origins = samples
                .iter()
                .filter_map(|(s, _)| s.as_ref()?.shadow_ray_origin(setup.light_position));
            scratch.light_packet.reset(origins);
        }
        sample_luminance.clear();
        for (surface, rng) in samples.iter_mut() {
            let Some(surface) = surface else {
                sample_luminance.push(0.0);
                continue;
            };
            let light = self.light(setup, surface, rng, scratch);
            shadow_rays += light.shadow_rays as u64;
            hits += 1;
            visibility += light.visibility;
            let l = (surface.tint * light.scaled_radiance).to_array();
            for c in 0..3 {
                sum[c] += l[c];
            }
            sample_luminance.push(luminance(l));
            let tint_y = luminance(surface.tint.to_array());
            match light.std_error {
                Some(se) => variance += (tint_y * se).powi(2),
                None => noise_known &= n > 1,
            }
        }
        // One sample: its own light-sampling error; more: the spread
        // between the pixel's strata, which includes it.
        let noise = if n == 1 {
            variance.sqrt()
        } else {
            collapsed_strata_variance(sample_luminance).map_or(0.0, f64::sqrt)
        };
        Pixel {
            radiance: sum.map(|c| c / n as f64),
            visibility: if hits > 0 {
                (visibility / hits as f64) as f32
            } else {
                0.0
            },
            coverage: hits as f32 / n as f32,
            noise: noise as f32,
            shadow_rays,
            noise_known,
        }
    }
}

/// Buffers one thread reuses from pixel to pixel.
#[derive(Default)]
struct PixelBuffers {
    /// Each sample's surface (None: background) and its random stream.
    samples: Vec<(Option<Surface>, Rng)>,
    /// Each sample's luminance, for the noise estimate.
    luminance: Vec<f64>,
    scratch: Scratch,
    /// A packet's directions and closest hits.
    directions: Vec<DVec3>,
    packet: PrimaryPacket,
}

struct Pixel {
    radiance: [f64; 3],
    visibility: f32,
    coverage: f32,
    noise: f32,
    shadow_rays: u64,
    noise_known: bool,
}

struct Tile {
    x0: u32,
    y0: u32,
    width: u32,
    pixels: Vec<Pixel>,
    primary_rays: u64,
    shadow_rays: u64,
    noise_known: bool,
}
