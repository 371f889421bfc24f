//! A covered pixel lit by a point light that no shadow ray can miss,
//! Lambertian and flat, its samples computed lane by lane: each step a
//! loop without branches over all of the pixel's samples, which the
//! compiler turns into SIMD instructions: 8 samples at once with AVX-512,
//! 4 with AVX2 (chosen at run time), 2 with the SSE2 every x86-64 has. Each lane does
//! the very operations the sample-by-sample path does, in the same order:
//! the same bits (`tests` holds them to it).

use super::PixelSums;
use super::pixel::Pixel;
use crate::physics::radiometry::{incidence, point_irradiance};
use crate::reference::grid::Cover;
use crate::reference::sampling::{PixelStreams, Strata};
use crate::reference::shading::{LightEstimate, Setup};
use crate::reference::surface::FlatLambert;
use glam::DVec3;

/// The per-sample values of one pixel, in lanes.
#[derive(Default)]
pub(super) struct Lanes {
    /// Each stratum's cell, (ix, iy), for the current sample count.
    cells: Vec<(u32, u32)>,
    /// Each sample's direction from the eye (not normalized), by coordinate.
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    /// Each sample's point on the triangle, by coordinate.
    px: Vec<f64>,
    py: Vec<f64>,
    pz: Vec<f64>,
    /// Each sample's light where visible: L / (c · colour), its V and
    /// its shadow rays.
    scaled: Vec<f64>,
    visibility: Vec<f64>,
    shadow_rays: Vec<u32>,
    /// Whether the sign of a sample's normal · o needs o itself.
    unsure: Vec<bool>,
}

/// |normal · d| below this fraction of Σ |normalᵢ dᵢ| is not trusted to
/// have the sign of normal · (d / |d|) computed (both round by ~4·10⁻¹⁶ of it).
const SIDE_MARGIN: f64 = 1e-14;

/// What a covered, flat, Lambertian pixel's samples share.
pub(super) struct CoveredPixel<'a> {
    pub(super) setup: &'a Setup,
    pub(super) spp: Strata,
    pub(super) pixel: (u32, u32),
    pub(super) cover: &'a Cover,
    pub(super) surface: FlatLambert,
    pub(super) tint: DVec3,
    /// Whether its points cast shadow rays.
    pub(super) shadowed: bool,
    /// Whether none of them can be blocked.
    pub(super) shadows_clear: bool,
}

impl Lanes {
    /// The pixel: what `Reference::shade_pixel` makes of its samples.
    /// `blocked(p, o)`: whether the shadow ray of the sample at p, seen
    /// along o (unit, towards the eye), is blocked.
    pub(super) fn shade(
        &mut self,
        pixel: &CoveredPixel,
        luminance: &mut Vec<f64>,
        blocked: Blocked,
    ) -> Pixel {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512dq") {
            // SAFETY: the CPU has AVX-512 F and DQ.
            return unsafe { self.shade_avx512(pixel, luminance, blocked) };
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.shade_avx2(pixel, luminance, blocked) };
        }
        self.shade_lanes(pixel, luminance, blocked)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn shade_avx2(&mut self, pixel: &CoveredPixel, luminance: &mut Vec<f64>, blocked: Blocked) -> Pixel {
        self.shade_lanes(pixel, luminance, blocked)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512dq")]
    fn shade_avx512(&mut self, pixel: &CoveredPixel, luminance: &mut Vec<f64>, blocked: Blocked) -> Pixel {
        self.shade_lanes(pixel, luminance, blocked)
    }

    #[inline(always)]
    fn shade_lanes(&mut self, pixel: &CoveredPixel, luminance: &mut Vec<f64>, blocked: Blocked) -> Pixel {
        let n = pixel.spp.count();
        self.directions(pixel);
        self.lights(pixel);
        if pixel.shadowed && !pixel.shadows_clear {
            self.shadows(blocked);
        }
        let mut sums = PixelSums::new(luminance);
        for s in 0..n as usize {
            let light = LightEstimate {
                scaled_radiance: if self.visibility[s] > 0.0 {
                    self.scaled[s]
                } else {
                    0.0
                },
                visibility: self.visibility[s],
                std_error: Some(0.0),
                shadow_rays: self.shadow_rays[s],
            };
            sums.add(pixel.tint, &light, n);
        }
        sums.pixel(n)
    }

    /// Each sample's direction: `render::sample_points` and
    /// `PixelRays::towards`.
    #[inline(always)]
    fn directions(&mut self, pixel: &CoveredPixel) {
        let spp = pixel.spp;
        let n = spp.count() as usize;
        if self.cells.len() != n {
            self.cells = spp.cells().collect();
        }
        for v in [&mut self.x, &mut self.y, &mut self.z] {
            v.resize(n, 0.0);
        }
        let setup = pixel.setup;
        let (i, j) = pixel.pixel;
        let streams = PixelStreams::new(setup.seed, super::pixel_index(setup, i as f64, j as f64));
        let (x0, y0) = (i as f64, j as f64);
        let (xs, ys, zs) = (&mut self.x[..n], &mut self.y[..n], &mut self.z[..n]);
        let cells = &self.cells[..n];
        for s in 0..n {
            let (dx, dy) = spp.jittered(cells[s], &mut streams.sample(s as u64));
            let d = setup.rays.towards(x0 + dx, y0 + dy);
            (xs[s], ys[s], zs[s]) = (d.x, d.y, d.z);
        }
    }

    /// Each sample's point and light ([`sample_light`]).
    #[inline(always)]
    fn lights(&mut self, pixel: &CoveredPixel) {
        let n = pixel.spp.count() as usize;
        for v in [
            &mut self.px,
            &mut self.py,
            &mut self.pz,
            &mut self.scaled,
            &mut self.visibility,
        ] {
            v.resize(n, 0.0);
        }
        self.shadow_rays.resize(n, 0);
        self.unsure.resize(n, false);
        let normal = pixel.surface.normal;
        let (xs, ys, zs) = (&self.x[..n], &self.y[..n], &self.z[..n]);
        let (px, py, pz) = (&mut self.px[..n], &mut self.py[..n], &mut self.pz[..n]);
        let (scaled, visibility, rays) = (
            &mut self.scaled[..n],
            &mut self.visibility[..n],
            &mut self.shadow_rays[..n],
        );
        let unsure = &mut self.unsure[..n];
        let mut any_unsure = false;
        for s in 0..n {
            let d = DVec3::new(xs[s], ys[s], zs[s]);
            // The side the eye is on, without normalizing d (a square
            // root and three divisions): normal · (−d) has the sign of
            // normal · o where it is far from its rounding.
            let side = normal.dot(-d);
            let sure = side.abs() > SIDE_MARGIN * normal.abs().dot(d.abs());
            unsure[s] = !sure;
            any_unsure |= unsure[s];
            let (p, light) = sample_light(pixel, d, side);
            (px[s], py[s], pz[s]) = (p.x, p.y, p.z);
            (scaled[s], visibility[s], rays[s]) = light;
        }
        if any_unsure {
            for s in (0..n).filter(|&s| unsure[s]) {
                let d = DVec3::new(xs[s], ys[s], zs[s]);
                // As `TriangleShading::point` has it.
                let side = normal.dot(-d / d.length());
                (_, (scaled[s], visibility[s], rays[s])) = sample_light(pixel, d, side);
            }
        }
    }

    /// Each shadow ray's answer, one by one: V = 0 where blocked.
    fn shadows(&mut self, blocked: Blocked) {
        for s in 0..self.visibility.len() {
            if self.shadow_rays[s] == 0 {
                continue;
            }
            let d = DVec3::new(self.x[s], self.y[s], self.z[s]);
            // As `TriangleShading::point` has it.
            let o = -d / d.length();
            if blocked(DVec3::new(self.px[s], self.py[s], self.pz[s]), o) {
                self.visibility[s] = 0.0;
            }
        }
    }
}

/// A sample's point and light, along d from the eye (not normalized):
/// `TriangleShading::point` and `shading::point_light_at`, whose branches
/// become selects. `side` has the sign of normal · o (o the unit direction
/// to the eye), which is all the point's normal and BRDF need of o. The
/// light: L / (c · colour) where the point is visible, V and the shadow
/// rays (`Lanes::shadows` tells whether they are blocked).
#[inline(always)]
fn sample_light(pixel: &CoveredPixel, d: DVec3, side: f64) -> (DVec3, (f64, f64, u32)) {
    let FlatLambert {
        corners: [a, b, c],
        normal,
        double_sided,
        diffuse,
    } = pixel.surface;
    let setup = pixel.setup;
    let [b0, b1, b2] = pixel.cover.hit(d).at.barycentric;
    let p = a * b0 + b * b1 + c * b2;
    // −normal · o is −(normal · o) exactly.
    let flip = double_sided & (side < 0.0);
    let (n, facing) = if flip {
        (-normal, -side > 0.0)
    } else {
        (normal, side > 0.0)
    };
    let inc = incidence(p, n, setup.light_position);
    let cos = inc.cos_theta;
    // A shadowed point casts its one shadow ray unless the light is below
    // its horizon.
    let below = cos <= 0.0;
    let e = point_irradiance(setup.intensity_w_sr, cos, inc.r);
    let scaled = if (cos > 0.0) & facing { diffuse * e } else { 0.0 };
    let shadowed = pixel.shadowed;
    let visibility = if shadowed & below { 0.0 } else { 1.0 };
    (p, (scaled, visibility, (shadowed & !below) as u32))
}

/// Whether the shadow ray of the point p seen along o (unit, towards the
/// eye) is blocked.
pub(super) type Blocked<'a> = &'a mut dyn FnMut(DVec3, DVec3) -> bool;

#[cfg(test)]
mod tests {
    use super::super::PixelBuffers;
    use super::super::cover::shade_one_by_one;
    use super::*;
    use crate::reference::grid::DirectionGrid;
    use crate::reference::surface::TriangleShading;
    use crate::reference::{Reference, ReferenceOptions};
    use crate::scene::{Aabb, Material, Object, Scene, shapes};
    use crate::settings::Settings;
    use glam::Vec3;

    /// Covered pixels in lanes give the bits their samples give one by one:
    /// one-sided and double-sided faces, seen from above and from below
    /// the light's horizon, with shadows and without, at 64, 32 and 9 samples
    /// (lanes left over), in every code this CPU runs (SSE2, AVX2, AVX-512).
    #[test]
    fn lanes_give_the_bits_of_samples_one_by_one() {
        let cube = Aabb {
            min: Vec3::new(-0.5, 0.0, -0.4),
            max: Vec3::new(0.3, 0.8, 0.4),
        };
        let scene = Scene {
            objects: vec![
                Object::new("ground", shapes::ground(Vec3::ZERO, 6.0), 1),
                Object::new("box", shapes::cuboid(cube), 0),
            ],
            materials: vec![
                Material::default(),
                Material {
                    double_sided: true,
                    ..Material::default()
                },
            ],
            ..Scene::default()
        };
        let reference = Reference::new(&scene);
        let mut settings = Settings::default();
        settings.material.k = 1.0;
        settings.camera.target = Vec3::new(0.0, 0.2, 0.0);
        (settings.image.width, settings.image.height) = (128, 96);
        let mut compared = [0; 2];
        // The light above everything, then level with the box's top (with
        // shadows and without: V = 1 on the far faces); then
        // the eye and the light below the double-sided ground, which turns
        // its normal towards them.
        let (above, below) = (Vec3::new(1.8, 1.4, 2.6), Vec3::new(1.8, -1.2, 2.6));
        for (eye, light, shadows, spp) in [
            (above, Vec3::new(-1.0, 3.0, 1.0), true, 64),
            (above, Vec3::new(2.0, 0.8, -1.5), true, 32),
            (above, Vec3::new(2.0, 0.8, -1.5), false, 16),
            (below, Vec3::new(1.0, -0.5, 0.5), false, 9),
        ] {
            settings.camera.eye = eye;
            settings.light.position = light;
            settings.shadow.enabled = shadows;
            let options = ReferenceOptions {
                spp,
                ..ReferenceOptions::default()
            };
            let setup = Setup::new(&settings, &options, &reference.materials);
            let grid = DirectionGrid::new(setup.rays.eye, &reference.bvh_triangles, |_| true);
            let spp = Strata::new(spp);
            let (mut lanes, mut buffers) = (Lanes::default(), PixelBuffers::default());
            for (i, j) in (0..96).flat_map(|j| (0..128).map(move |i| (i, j))) {
                let (x, y) = (i as f64, j as f64);
                let corners = [(x, y), (x + 1.0, y), (x, y + 1.0), (x + 1.0, y + 1.0)]
                    .map(|(cx, cy)| setup.rays.towards(cx, cy));
                let Some(cover) = grid.cover(&corners) else {
                    continue;
                };
                let shading = TriangleShading::new(&reference, &setup, cover.triangle());
                let (Some(surface), Some(tint)) = (shading.flat_lambert(), shading.plain_tint()) else {
                    panic!("every face is flat and plain");
                };
                let pixel = CoveredPixel {
                    setup: &setup,
                    spp,
                    pixel: (i, j),
                    cover: &cover,
                    surface,
                    tint,
                    shadowed: shading.shadowed(),
                    // As the one-by-one path is asked: `render::cover`'s
                    // tests compare the shadows.
                    shadows_clear: true,
                };
                let one = shade_one_by_one(&setup, spp, (i, j), (&cover, &shading, tint), &mut buffers);
                let mut luminance = Vec::new();
                let mut laned = vec![lanes.shade_lanes(&pixel, &mut luminance, &mut |_, _| true)];
                #[cfg(target_arch = "x86_64")]
                {
                    use std::arch::is_x86_feature_detected as has;
                    if has!("avx2") {
                        // SAFETY: the CPU has AVX2.
                        laned.push(unsafe { lanes.shade_avx2(&pixel, &mut luminance, &mut |_, _| true) });
                    }
                    if has!("avx512f") && has!("avx512dq") {
                        // SAFETY: the CPU has AVX-512 F and DQ.
                        laned.push(unsafe { lanes.shade_avx512(&pixel, &mut luminance, &mut |_, _| true) });
                    }
                }
                for laned in laned {
                    let bits = |p: &Pixel| {
                        (
                            p.radiance.map(f64::to_bits),
                            p.visibility.to_bits(),
                            p.coverage.to_bits(),
                            p.noise.to_bits(),
                            p.shadow_rays,
                            p.noise_known,
                        )
                    };
                    assert_eq!(bits(&laned), bits(&one), "pixel ({i}, {j}), light at {light}");
                }
                compared[(one.visibility > 0.0) as usize] += 1;
            }
        }
        // Pixels in the dark and in the light, the most of the image.
        assert!(compared[0] > 500 && compared[1] > 10_000, "{compared:?}");
    }
}
