//! The reference image: pixels rendered in parallel over tiles, each with
//! its stratified samples, progress counted and cancellation honoured.

use super::bvh::{Cone, PrimaryPacket};
use super::grid::DirectionGrid;
use super::image::{ReferenceImage, RenderStats};
use super::sampling::{PixelStreams, Rng, Strata};
use super::shading::{Scratch, Setup, region_block};
use super::surface::{ShadingCache, Surface};
use super::{Reference, ReferenceError, ReferenceOptions, RenderControl, pixel_index};
use crate::settings::Settings;
use cover::{BlockCovers, Covered};
use glam::DVec3;
use pixel::{Pixel, PixelSums, Tile, TileRows, tile_rows};
use rayon::prelude::*;
use std::sync::atomic::Ordering;
use std::time::Instant;

mod cover;
mod lanes;
mod pixel;
mod point_run;
mod primary;

/// Edge length of the square tiles the image is split into for the threads.
const TILE: u32 = 16;
/// Scenes with more triangles build no direction grids: most of their cells
/// would list more than `grid::MAX_LIST` and defer to the BVH anyway, and
/// the packets of a pixel's rays go through the BVH faster than building
/// the grids takes.
const GRID_MAX_TRIANGLES: usize = 16_384;

/// Whether a scene of this many triangles is rendered through direction
/// grids (else through the BVH alone).
pub(super) fn builds_grids(triangles: usize) -> bool {
    triangles <= GRID_MAX_TRIANGLES
}

/// Blocks of pixels (columns, rows) whose primary rays walk the BVH as one
/// packet where there is no eye grid (several samples a pixel): against
/// one pixel a packet, 2 × 2 renders the 110 k-triangle engine 14 % faster
/// and 1 M triangles 9 % (4 × 1: 13 % and 7 %; runs of 8 or 16 in a row:
/// slower on 1 M triangles).
const BLOCK: (u32, u32) = (2, 2);
/// The blocks where the scene has fewer triangles than the image has
/// pixels: 4 × 2 took 8 % off the 110 k-triangle engine's process at
/// 512 × 384 (its shadow packets' cones hold few triangles), where it
/// added 2 % on 1 M triangles, whose bumpy surfaces fill a wider cone with
/// more of them (callgrind, 16 spp); 4 × 4 then took 4.5 % off the
/// engine's render against 4 × 2 (30 runs each, both orders), for 0.3 %
/// fewer instructions: each packet's nodes and triangles are fetched for
/// twice the rays.
const WIDE_BLOCK: (u32, u32) = (4, 4);

impl Reference {
    /// Renders the image, in parallel over tiles, reporting progress and
    /// stopping early when cancelled through `control`.
    pub fn render(
        &self,
        settings: &Settings,
        options: &ReferenceOptions,
        control: &RenderControl,
    ) -> Result<ReferenceImage, ReferenceError> {
        let pixels = settings.image.width as usize * settings.image.height as usize;
        let block = if self.triangles.len() < pixels {
            WIDE_BLOCK
        } else {
            BLOCK
        };
        self.render_in_blocks(settings, options, control, block, Shortcuts::ALL)
    }

    /// [`Self::render`] with primary packets of `block` pixels (columns,
    /// rows) where there is no eye grid, and the `shortcuts` taken (all but
    /// for the tests that show what they change).
    fn render_in_blocks(
        &self,
        settings: &Settings,
        options: &ReferenceOptions,
        control: &RenderControl,
        block: (u32, u32),
        shortcuts: Shortcuts,
    ) -> Result<ReferenceImage, ReferenceError> {
        settings.validate()?;
        let start = Instant::now();
        let mut setup = Setup::new(settings, options, &self.materials);
        // Every primary ray leaves the eye and every point-light shadow ray
        // ends at the light: both are cast through direction grids there,
        // unless the scene is so large that their cells would be crowded.
        let grids = builds_grids(self.triangles.len());
        let light_grid = grids && setup.shadows && !setup.is_sphere_light();
        let (eye_grid, light_grid) = rayon::join(
            || {
                grids.then(|| {
                    let image = image_region(&setup);
                    DirectionGrid::towards(setup.rays.eye, &self.grid_triangles, |_| true, &image)
                })
            },
            || {
                light_grid
                    .then(|| DirectionGrid::new(setup.light_position, &self.grid_triangles, |t| t.occludes))
            },
        );
        (setup.eye_grid, setup.light_grid) = (eye_grid, light_grid);
        let setup = setup;
        let (width, height) = (setup.width, setup.height);
        let tiles: Vec<(u32, u32)> = (0..height.div_ceil(TILE))
            .flat_map(|ty| (0..width.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
            .collect();
        let spp = Strata::new(options.spp);
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
        // Each tile writes its pixels into the image's arrays itself: kept
        // aside and copied after, they took as many fresh pages again and
        // a pass on one thread (the engine's render 1.1–1.5 % longer).
        let targets = tile_rows(
            width as usize,
            (&mut image.radiance, &mut image.visibility),
            (&mut image.coverage, &mut image.noise),
        );
        // One tile a job: rayon otherwise hands each thread a run of tiles
        // whose last part no idle thread may take, and the tiles' costs are
        // very uneven (background, a model's edges); with two threads one
        // sat idle for up to a fifth of the engine's render.
        let rendered: Vec<Option<Tile>> = tiles
            .into_par_iter()
            .zip(targets)
            .with_max_len(1)
            .map(|(origin, rows)| self.render_tile(&setup, spp, (origin, rows), block, shortcuts, control))
            .collect();
        if control.cancelled() {
            return Err(ReferenceError::Cancelled);
        }
        for tile in rendered.iter().flatten() {
            image.stats.primary_rays += tile.primary_rays;
            image.stats.shadow_rays += tile.shadow_rays;
            image.noise_known &= tile.noise_known;
        }
        image.stats.elapsed = start.elapsed();
        Ok(image)
    }

    /// One tile from (x0, y0), with primary packets of `block` pixels
    /// (columns, rows) where there is no eye grid, or None when cancelled.
    fn render_tile<'a>(
        &self,
        setup: &Setup,
        spp: Strata,
        ((x0, y0), target): ((u32, u32), TileRows<'a>),
        block: (u32, u32),
        shortcuts: Shortcuts,
        control: &RenderControl,
    ) -> Option<Tile<'a>> {
        let (cols, rows) = if setup.eye_grid.is_none() && spp.count() > 1 {
            block
        } else {
            (1, 1)
        };
        let (x1, y1) = ((x0 + TILE).min(setup.width), (y0 + TILE).min(setup.height));
        let mut tile = Tile::new(target);
        let n = spp.count();
        let sees = !shortcuts.background
            || self
                .bvh
                .meets_cone(&block_cone(setup, (x0, y0), (x1 - x0, y1 - y0)));
        if !sees {
            if control.cancelled() {
                return None;
            }
            for _ in 0..(x1 - x0) * (y1 - y0) {
                tile.add(Pixel::background(n));
            }
            control
                .pixels_done
                .fetch_add(((x1 - x0) * (y1 - y0)) as usize, Ordering::Relaxed);
            return Some(tile);
        }
        let mut buffers = PixelBuffers::default();
        // Kept from block to block: neighbours share triangles.
        let mut shading = ShadingCache::default();
        let mut blocks = (shortcuts.covers && n > 1).then(|| BlockCovers::new([x0, y0, x1, y1]));
        // A band's rows below its first, each in order, until the band is done.
        let mut below: Vec<Vec<Pixel>> = (1..rows).map(|_| Vec::new()).collect();
        for j in (y0..y1).step_by(rows as usize) {
            if control.cancelled() {
                return None;
            }
            let band = rows.min(y1 - j);
            for i in (x0..x1).step_by(cols as usize) {
                let width = cols.min(x1 - i);
                if width * band == 1 {
                    buffers.scratch.block = Some(region_block(i, j));
                    let block = match (&setup.eye_grid, &mut blocks) {
                        (Some(grid), Some(blocks)) => blocks.of(self, setup, grid, (i, j)),
                        _ => None,
                    };
                    tile.add(
                        match self.trace_pixel_samples(
                            setup,
                            spp,
                            (i, j),
                            (shortcuts, block),
                            (&mut buffers, &mut shading),
                        ) {
                            Traced::Background => Pixel::background(n),
                            Traced::Shaded(pixel) => pixel,
                            Traced::Samples { shadows_clear } => {
                                self.aim_light_packet(setup, &mut buffers);
                                self.shade_pixel(setup, 0, n, shadows_clear, &mut buffers)
                            }
                        },
                    );
                    continue;
                }
                // No background test here: within a tile that sees something
                // it costs more than the blocks it spares (engine: 2.7 % of
                // the process's instructions, same bits).
                self.trace_run(setup, spp, (i, j), (width, band), &mut buffers);
                let mut place = |k: usize, pixel: Pixel| match k / width as usize {
                    0 => tile.add(pixel),
                    row => below[row - 1].push(pixel),
                };
                if !setup.is_sphere_light() {
                    self.shade_point_run(setup, n, (&mut buffers, &mut shading), place);
                    continue;
                }
                // A sphere light: its shadow rays go through its own
                // gatherings, not the light packet.
                self.run_samples(setup, &mut buffers, &mut shading);
                for k in 0..(width * band) as usize {
                    let (c, r) = (k as u32 % width, k as u32 / width);
                    buffers.scratch.block = Some(region_block(i + c, j + r));
                    place(k, self.shade_pixel(setup, k * n as usize, n, false, &mut buffers));
                }
            }
            for pixel in below.iter_mut().flat_map(|row| row.drain(..)) {
                tile.add(pixel);
            }
            control
                .pixels_done
                .fetch_add(((x1 - x0) * band) as usize, Ordering::Relaxed);
        }
        Some(tile)
    }

    /// The primary samples of the block of width × height pixels from
    /// (i, j), row by row (no eye grid): one packet in the cone of the
    /// block's corner rays (a single pixel's for `trace_pixel_samples`), each
    /// ray still decided by its own exact test, with each pixel's own samples
    /// and random streams.
    fn trace_run(
        &self,
        setup: &Setup,
        spp: Strata,
        (i, j): (u32, u32),
        (width, height): (u32, u32),
        buffers: &mut PixelBuffers,
    ) {
        buffers.run_samples.clear();
        buffers.directions.clear();
        for r in 0..height {
            for c in 0..width {
                push_directions(setup, spp, (i + c, j + r), buffers);
            }
        }
        let cone = block_cone(setup, (i, j), (width, height));
        self.bvh
            .closest_hits_in_cone(&cone, &buffers.directions, &mut buffers.packet);
    }

    /// Every sample of a traced block, pixel by pixel (row by row), into
    /// `buffers.samples`.
    #[inline(always)]
    fn run_samples<'a>(
        &'a self,
        setup: &'a Setup,
        buffers: &mut PixelBuffers,
        shading: &mut ShadingCache<'a>,
    ) {
        buffers.samples.clear();
        for s in 0..buffers.directions.len() {
            let surface =
                buffers.packet.hits[s].map(|hit| self.surface_at(setup, buffers.directions[s], hit, shading));
            buffers.samples.push((surface, buffers.run_samples[s].clone()));
        }
    }

    /// Pixel (i, j)'s primary samples into `buffers.samples`: first every
    /// primary ray, then (in `shade_pixel`) the light at every surface. Two
    /// short loops of independent iterations let the CPU overlap the
    /// samples' long chains of divisions and square roots better than one
    /// long loop does (8 %). Background, and no samples, when the
    /// background shortcut is taken and the pixel lies in an empty cell of
    /// the eye grid; the pixel itself when a covered one is shaded at once.
    #[inline(always)]
    fn trace_pixel_samples<'a>(
        &'a self,
        setup: &'a Setup,
        spp: Strata,
        (i, j): (u32, u32),
        (shortcuts, block): (Shortcuts, Option<&Covered>),
        (buffers, shading): (&mut PixelBuffers, &mut ShadingCache<'a>),
    ) -> Traced {
        let n = spp.count();
        if let (Some(grid), Some(block)) = (&setup.eye_grid, block)
            && let Some(traced) = self.trace_covered_samples(setup, spp, (i, j), (grid, Some(block)), buffers)
        {
            return traced;
        }
        let (x, y) = (i as f64, j as f64);
        // Several samples: find their cell once when it is the same for all.
        let cell = setup
            .eye_grid
            .as_ref()
            .filter(|_| n > 1)
            .and_then(|grid| grid.pixel_cell(&setup.rays, x, y));
        if shortcuts.background
            && let (Some(grid), Some(cell)) = (&setup.eye_grid, cell)
            && grid.is_empty(cell)
        {
            return Traced::Background;
        }
        if shortcuts.covers
            && n > 1
            && let Some(grid) = &setup.eye_grid
            && let Some(traced) = self.trace_covered_samples(setup, spp, (i, j), (grid, None), buffers)
        {
            return traced;
        }
        // Crowded cells (or none): the pixel's rays go through the BVH
        // together, as one packet in the cone of its corner rays.
        let packet = n > 1
            && setup.eye_grid.as_ref().is_none_or(|grid| {
                let centre = cell.or_else(|| grid.cell_of(setup.rays.towards(x + 0.5, y + 0.5)));
                centre.is_none_or(|c| grid.is_crowded(c))
            });
        if packet {
            self.trace_run(setup, spp, (i, j), (1, 1), buffers);
            self.run_samples(setup, buffers, shading);
        } else {
            trace_samples(setup, spp, (i, j), buffers, |towards| {
                let hit = self.primary_hit(setup, towards, cell)?;
                Some(self.surface_at(setup, towards, hit, shading))
            });
        }
        Traced::Samples { shadows_clear: false }
    }

    /// Aims the light packet at the shadow rays of every sample in
    /// `buffers.samples` (a pixel's: one walk for them all; a block's are
    /// aimed at by `point_run`),
    /// unless the light's grid answers every cell: the rare ray it cannot
    /// answer (one from the light's centre) then walks the BVH on its own.
    #[inline(always)]
    fn aim_light_packet(&self, setup: &Setup, buffers: &mut PixelBuffers) {
        let grid_answers = setup
            .light_grid
            .as_ref()
            .is_some_and(|grid| !grid.is_crowded_anywhere());
        if setup.shadows && !setup.is_sphere_light() && !grid_answers {
            let origins = buffers
                .samples
                .iter()
                .filter_map(|(s, _)| s.as_ref()?.shadow_ray(setup.light_position));
            buffers.scratch.light_packet.reset(origins);
        }
    }

    /// The pixel from its `n` samples from `first` in `buffers.samples`,
    /// the light packet aimed at them; `shadows_clear`: their shadow rays
    /// towards a point light are known unblocked.
    #[inline(always)]
    fn shade_pixel(
        &self,
        setup: &Setup,
        first: usize,
        n: u32,
        shadows_clear: bool,
        buffers: &mut PixelBuffers,
    ) -> Pixel {
        let PixelBuffers {
            samples,
            luminance: sample_luminance,
            scratch,
            ..
        } = buffers;
        let mut sums = PixelSums::new(sample_luminance);
        for (surface, rng) in &mut samples[first..first + n as usize] {
            match surface {
                Some(surface) => {
                    let light = self.light(setup, surface, rng, shadows_clear, scratch);
                    sums.add(surface.tint, &light, n);
                }
                None => sums.add_background(),
            }
        }
        sums.pixel(n)
    }
}

/// What tracing a pixel's primary samples gave.
enum Traced {
    /// It sees only background.
    Background,
    /// Its samples, in `PixelBuffers::samples`, to be shaded, and whether
    /// their shadow rays towards a point light are known unblocked.
    Samples { shadows_clear: bool },
    /// The pixel itself, shaded at once.
    Shaded(Pixel),
}

/// Ways of sparing work that leave every pixel's coverage and visibility
/// as they are (the tests turn them off to show it).
#[derive(Clone, Copy, Debug)]
struct Shortcuts {
    /// Tiles and pixels whose cone meets no triangle are background
    /// without a sample cast: the same bits.
    background: bool,
    /// Pixels that one triangle covers, lit by a point light, take their
    /// hits from it and their shadows from one test of the whole pixel
    /// (`cover`): the same hits and visibility, radiance to ~10⁻¹⁵.
    covers: bool,
}

impl Shortcuts {
    const ALL: Self = Self {
        background: true,
        covers: true,
    };
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
    /// A block of pixels' random streams, in the order of `directions`.
    run_samples: Vec<Rng>,
    /// A covered pixel's samples, in lanes.
    lanes: lanes::Lanes,
    /// A pixel's primary samples, in lanes.
    primary: primary::PrimaryDirections,
    /// A block's samples under a point light (`point_run`).
    lit: Vec<Option<point_run::LitSample>>,
}

/// The image's rectangle on the plane a metre ahead of the eye, a pixel
/// wider on each side, as two triangles: every primary ray goes through it.
fn image_region(setup: &Setup) -> [[DVec3; 3]; 2] {
    let far = (setup.width as f64 + 1.0, setup.height as f64 + 1.0);
    let [a, b, c, d] = corner_rays(setup, (-1.0, -1.0), far).map(|w| setup.rays.eye + w);
    [[a, b, c], [a, c, d]]
}

/// The rays from the eye through the corners of the image's rectangle
/// from (x, y) to (far_x, far_y) (pixels), in order around it.
fn corner_rays(setup: &Setup, (x, y): (f64, f64), (far_x, far_y): (f64, f64)) -> [DVec3; 4] {
    [(x, y), (far_x, y), (far_x, far_y), (x, far_y)].map(|(cx, cy)| setup.rays.towards(cx, cy))
}

/// The cone from the eye of the block of width × height pixels from (x, y),
/// spanned by its corner rays: every primary ray of the block lies inside.
fn block_cone(setup: &Setup, (x, y): (u32, u32), (width, height): (u32, u32)) -> Cone {
    let (x, y) = (x as f64, y as f64);
    let far = (x + width as f64, y + height as f64);
    Cone::spanned(setup.rays.eye, corner_rays(setup, (x, y), far))
}

/// Pixel (i, j)'s samples into `buffers.samples`: its directions first
/// ([`directions_first`]), then the surface `surface_of` finds along each.
fn trace_samples(
    setup: &Setup,
    spp: Strata,
    pixel: (u32, u32),
    buffers: &mut PixelBuffers,
    mut surface_of: impl FnMut(DVec3) -> Option<Surface>,
) {
    directions_first(setup, spp, pixel, buffers);
    let PixelBuffers {
        samples,
        directions,
        run_samples,
        ..
    } = buffers;
    samples.clear();
    for (&towards, rng) in directions.iter().zip(run_samples.drain(..)) {
        samples.push((surface_of(towards), rng));
    }
}

/// Pixel (i, j)'s primary rays' directions and random streams into
/// `buffers.directions` and `buffers.run_samples`: computed in a loop of
/// their own, before the rays' surfaces, they overlap better (~10 %).
fn directions_first(setup: &Setup, spp: Strata, (i, j): (u32, u32), buffers: &mut PixelBuffers) {
    buffers.directions.clear();
    buffers.run_samples.clear();
    if spp.count() == 1 {
        let (x, y, rng) = centre_sample(setup, i, j);
        buffers.directions.push(setup.rays.towards(x, y));
        buffers.run_samples.push(rng);
        return;
    }
    push_directions(setup, spp, (i, j), buffers);
}

/// Pixel (i, j)'s primary rays' directions and random streams, stratum by
/// stratum, for several samples a pixel (one is the pixel's centre:
/// [`centre_sample`]), pushed onto `buffers.directions` and
/// `buffers.run_samples`.
fn push_directions(setup: &Setup, spp: Strata, pixel: (u32, u32), buffers: &mut PixelBuffers) {
    let primary = &mut buffers.primary;
    primary.of(setup, spp, pixel);
    let n = spp.count() as usize;
    buffers.directions.extend((0..n).map(|s| primary.direction(s)));
    buffers.run_samples.extend_from_slice(&primary.streams);
}

/// Pixel (i, j)'s one sample: DESIGN.md makes it the pixel centre.
#[inline(always)]
fn centre_sample(setup: &Setup, i: u32, j: u32) -> (f64, f64, Rng) {
    (
        i as f64 + 0.5,
        j as f64 + 0.5,
        pixel_streams(setup, i, j).sample(0),
    )
}

/// Pixel (i, j)'s random streams, one a sample: every path that samples
/// the pixel draws from these, so all give it the same samples.
#[inline(always)]
fn pixel_streams(setup: &Setup, i: u32, j: u32) -> PixelStreams {
    PixelStreams::new(setup.seed, pixel_index(setup, i as f64, j as f64))
}

#[cfg(test)]
mod tests;
