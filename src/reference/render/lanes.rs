//! A covered pixel of one tint lit by a point light, its samples computed
//! lane by lane: each step a loop without branches over all of the
//! pixel's samples, which the compiler turns into SIMD instructions: 8
//! samples at once with AVX-512, 4 with AVX2 (chosen at run time), 2 with
//! the SSE2 every x86-64 has. A specular lobe then takes a lane step of its
//! own (`LaneBrdf`, its power in plain arithmetic; AVX2 at most), and the
//! shadow rays that the pixel's test did not clear are taken sample by sample.
//! Each lane does the very operations the sample-by-sample path does, in
//! the same order: the same bits (`tests` holds them to it).

use super::PixelSums;
use super::pixel::Pixel;
use super::primary::PrimaryDirections;
use crate::physics::brdf::LaneBrdf;
use crate::physics::radiometry::{incidence, point_irradiance};
use crate::reference::grid::Cover;
use crate::reference::sampling::Strata;
use crate::reference::shading::{LightEstimate, Setup};
use crate::reference::simd::{self, Isa};
use crate::reference::surface::Facet;
use glam::DVec3;
use std::f64::consts::PI;

/// The per-sample values of one pixel, in lanes.
#[derive(Default)]
pub(super) struct Lanes {
    /// Each sample's direction from the eye (not normalized).
    primary: PrimaryDirections,
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
    /// What a specular lobe needs of each sample: its irradiance E, cos θ,
    /// and its normal, direction to the light and to the eye by coordinate.
    e: Vec<f64>,
    cos: Vec<f64>,
    vectors: [Vec<f64>; 9],
}

/// |normal · d| below this fraction of Σ |normalᵢ dᵢ| is not trusted to
/// have the sign of normal · (d / |d|) computed (both round by ~4·10⁻¹⁶ of it).
const SIDE_MARGIN: f64 = 1e-14;

/// What a covered pixel's samples share.
pub(super) struct CoveredPixel<'a> {
    pub(super) setup: &'a Setup,
    pub(super) spp: Strata,
    pub(super) pixel: (u32, u32),
    pub(super) cover: &'a Cover,
    pub(super) surface: &'a Facet,
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
        simd::with(
            Isa::widest(),
            #[inline(always)]
            || self.shade_lanes(pixel, luminance, blocked),
        )
    }

    #[inline(always)]
    fn shade_lanes(&mut self, pixel: &CoveredPixel, luminance: &mut Vec<f64>, blocked: Blocked) -> Pixel {
        let n = pixel.spp.count();
        self.primary.of_here(pixel.setup, pixel.spp, pixel.pixel);
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

    /// Each sample's point and light ([`sample_light`]): on a flat,
    /// Lambertian facet, the side the eye is on without normalizing the
    /// direction; elsewhere with it, and then the specular lobe.
    #[inline(always)]
    fn lights(&mut self, pixel: &CoveredPixel) {
        let n = pixel.spp.count() as usize;
        for v in [
            &mut self.px,
            &mut self.py,
            &mut self.pz,
            &mut self.scaled,
            &mut self.visibility,
            &mut self.e,
            &mut self.cos,
        ]
        .into_iter()
        .chain(&mut self.vectors)
        {
            v.resize(n, 0.0);
        }
        self.shadow_rays.resize(n, 0);
        self.unsure.resize(n, false);
        let surface = pixel.surface;
        let specular = surface.brdf.k < 1.0;
        match (surface.normals.is_some(), specular) {
            (false, false) => self.light_loop::<false, false, false>(pixel),
            (false, true) => self.light_loop::<true, false, true>(pixel),
            (true, false) => self.light_loop::<true, true, false>(pixel),
            (true, true) => self.light_loop::<true, true, true>(pixel),
        }
        if specular {
            // In AVX2's lanes even where the CPU has AVX-512: the lobe's
            // long run of 512-bit arithmetic slowed the whole render (the
            // default scene's point light at 1280×720, 16 spp: 0.68–0.69 s
            // against 0.65–0.66 s, medians of 10 alternated runs).
            simd::with(
                Isa::Avx2,
                #[inline(always)]
                || self.specular(surface),
            );
        }
    }

    /// [`sample_light`] for every sample, o found from the normalized
    /// direction (`EXACT`) or, where its sign is sure, from normal · (−d);
    /// the normal interpolated (`SMOOTH`) or the facet's; what the lobe
    /// needs kept (`SPECULAR`: so many arrays that the loop stays scalar).
    #[inline(always)]
    fn light_loop<const EXACT: bool, const SMOOTH: bool, const SPECULAR: bool>(
        &mut self,
        pixel: &CoveredPixel,
    ) {
        let n = pixel.spp.count() as usize;
        let (xs, ys, zs) = (&self.primary.x[..n], &self.primary.y[..n], &self.primary.z[..n]);
        let (px, py, pz) = (&mut self.px[..n], &mut self.py[..n], &mut self.pz[..n]);
        let (scaled, visibility, rays) = (
            &mut self.scaled[..n],
            &mut self.visibility[..n],
            &mut self.shadow_rays[..n],
        );
        let (e, cos) = (&mut self.e[..n], &mut self.cos[..n]);
        let [nx, ny, nz, lx, ly, lz, ox, oy, oz] = self.vectors.each_mut().map(|v| &mut v[..n]);
        let unsure = &mut self.unsure[..n];
        let mut any_unsure = false;
        for s in 0..n {
            let d = DVec3::new(xs[s], ys[s], zs[s]);
            let b = pixel.cover.hit(d).at.barycentric;
            let normal = shading_normal::<SMOOTH>(pixel.surface, b);
            let o = if EXACT {
                // As `TriangleShading::point` has it.
                -d / d.length()
            } else {
                // The side the eye is on, without normalizing d (a square
                // root and three divisions): normal · (−d) has the sign of
                // normal · o where it is far from its rounding.
                let sure = normal.dot(-d).abs() > SIDE_MARGIN * normal.abs().dot(d.abs());
                unsure[s] = !sure;
                any_unsure |= unsure[s];
                -d
            };
            let light = sample_light(pixel, b, (normal, o));
            (px[s], py[s], pz[s]) = light.p.into();
            (scaled[s], visibility[s], rays[s]) = (light.scaled, light.visibility, light.shadow_rays);
            if SPECULAR {
                (e[s], cos[s]) = (light.e, light.cos);
                (nx[s], ny[s], nz[s]) = light.n.into();
                (lx[s], ly[s], lz[s]) = light.l.into();
                (ox[s], oy[s], oz[s]) = o.into();
            }
        }
        if !EXACT && any_unsure {
            for s in (0..n).filter(|&s| unsure[s]) {
                let d = DVec3::new(xs[s], ys[s], zs[s]);
                let b = pixel.cover.hit(d).at.barycentric;
                let normal = shading_normal::<SMOOTH>(pixel.surface, b);
                let light = sample_light(pixel, b, (normal, -d / d.length()));
                (scaled[s], visibility[s], rays[s]) = (light.scaled, light.visibility, light.shadow_rays);
            }
        }
    }

    /// The specular lobe's samples where the light is above the horizon:
    /// `point_light_at`'s (f_d + f_s) · E, in lanes.
    #[inline(always)]
    fn specular(&mut self, surface: &Facet) {
        let count = self.scaled.len();
        let [nx, ny, nz, lx, ly, lz, ox, oy, oz] = self.vectors.each_ref().map(|v| &v[..count]);
        let (cos, e, scaled) = (&self.cos[..count], &self.e[..count], &mut self.scaled[..count]);
        let brdf = LaneBrdf::new(&surface.brdf);
        for s in 0..count {
            let n = DVec3::new(nx[s], ny[s], nz[s]);
            let l = DVec3::new(lx[s], ly[s], lz[s]);
            let o = DVec3::new(ox[s], oy[s], oz[s]);
            let lit = brdf.terms(n, l, o).total() * e[s];
            scaled[s] = if cos[s] > 0.0 { lit } else { scaled[s] };
        }
    }

    /// Each shadow ray's answer, one by one: V = 0 where blocked.
    fn shadows(&mut self, blocked: Blocked) {
        for s in 0..self.visibility.len() {
            if self.shadow_rays[s] == 0 {
                continue;
            }
            let d = self.primary.direction(s);
            // As `TriangleShading::point` has it.
            let o = -d / d.length();
            if blocked(DVec3::new(self.px[s], self.py[s], self.pz[s]), o) {
                self.visibility[s] = 0.0;
            }
        }
    }
}

/// The shading normal at barycentrics b, before it turns towards the
/// viewer: [`Facet::normal_at`], or the flat facet's without a look at its
/// vertex normals (`SMOOTH` false).
#[inline(always)]
fn shading_normal<const SMOOTH: bool>(surface: &Facet, b: [f64; 3]) -> DVec3 {
    if SMOOTH {
        surface.normal_at(b)
    } else {
        surface.normal
    }
}

/// One sample's point and light.
struct SampleLight {
    p: DVec3,
    /// The shading normal, towards the viewer on double-sided materials.
    n: DVec3,
    l: DVec3,
    cos: f64,
    e: f64,
    /// L / (c · colour) where the point is visible, Lambertian.
    scaled: f64,
    visibility: f64,
    shadow_rays: u32,
}

/// A sample's point and light at barycentrics b: `TriangleShading::point`
/// and `shading::point_light_at`, whose branches become selects. `normal` is the shading normal before it
/// turns towards the viewer, `o` the unit direction to the eye or any
/// vector on its side of `normal`'s plane (all that the normal and Lambert
/// need of it). `Lanes::shadows` tells whether the shadow rays are blocked,
/// `Lanes::specular` adds a specular lobe.
#[inline(always)]
fn sample_light(pixel: &CoveredPixel, b: [f64; 3], (normal, o): (DVec3, DVec3)) -> SampleLight {
    let Facet {
        double_sided, brdf, ..
    } = *pixel.surface;
    let setup = pixel.setup;
    let p = pixel.surface.point_at(b);
    let side = normal.dot(o);
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
    // blinn_phong's diffuse term.
    let scaled = if (cos > 0.0) & facing {
        brdf.k / PI * e
    } else {
        0.0
    };
    let shadowed = pixel.shadowed;
    SampleLight {
        p,
        n,
        l: inc.l,
        cos,
        e,
        scaled,
        visibility: if shadowed & below { 0.0 } else { 1.0 },
        shadow_rays: (shadowed & !below) as u32,
    }
}

/// Whether the shadow ray of the point p seen along o (unit, towards the
/// eye) is blocked.
pub(super) type Blocked<'a> = &'a mut dyn FnMut(DVec3, DVec3) -> bool;

#[cfg(test)]
mod tests {
    use super::super::{PixelBuffers, directions_first};
    use super::*;
    use crate::reference::grid::DirectionGrid;
    use crate::reference::shading::point_light_at;
    use crate::reference::surface::TriangleShading;
    use crate::reference::{Reference, ReferenceOptions};
    use crate::scene::{Aabb, Material, Object, Scene, shapes};
    use crate::settings::Settings;
    use glam::Vec3;

    /// A covered pixel of plain tint whose shadow rays towards a point light
    /// are known unblocked, its samples shaded one by one (what
    /// `Reference::shade_pixel` makes of them, without keeping them).
    fn shade_one_by_one(
        setup: &Setup,
        spp: Strata,
        pixel: (u32, u32),
        (cover, shading, tint): (&Cover, &TriangleShading, DVec3),
        buffers: &mut PixelBuffers,
    ) -> Pixel {
        directions_first(setup, spp, pixel, buffers);
        let PixelBuffers {
            directions,
            luminance,
            ..
        } = buffers;
        let n = spp.count();
        let mut sums = PixelSums::new(luminance);
        for &towards in directions.iter() {
            let (p, normal, o) = shading.point(towards, cover.hit(towards));
            let light = point_light_at(
                setup,
                (p, normal, o),
                &shading.facet().brdf,
                shading.shadowed(),
                || false,
            );
            sums.add(tint, &light, n);
        }
        sums.pixel(n)
    }

    /// Covered pixels in lanes give the bits their samples give one by one:
    /// one-sided and double-sided faces, flat and smooth, Lambertian and
    /// Blinn-Phong, seen from above and from below the light's horizon,
    /// with shadows and without, at 64, 32, 16 and 9 samples (lanes left
    /// over), in every code this CPU runs (SSE2, AVX2, AVX-512).
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
                Object::new("ball", shapes::sphere(Vec3::new(1.0, 0.5, 0.8), 0.5, 24, 12), 0),
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
        settings.camera.target = Vec3::new(0.0, 0.2, 0.0);
        (settings.image.width, settings.image.height) = (128, 96);
        // Pixels compared in the dark and in the light, smooth and specular.
        let mut compared = [0; 4];
        // The light above everything, then level with the box's top (with
        // shadows and without: V = 1 on the far faces); then
        // the eye and the light below the double-sided ground, which turns
        // its normal towards them.
        let (above, below) = (Vec3::new(1.8, 1.4, 2.6), Vec3::new(1.8, -1.2, 2.6));
        for (eye, light, shadows, spp, k) in [
            (above, Vec3::new(-1.0, 3.0, 1.0), true, 64, 1.0),
            (above, Vec3::new(2.0, 0.8, -1.5), true, 32, 0.5),
            (above, Vec3::new(2.0, 0.8, -1.5), false, 16, 1.0),
            (below, Vec3::new(1.0, -0.5, 0.5), false, 9, 0.3),
        ] {
            settings.material.k = k;
            settings.camera.eye = eye;
            settings.light.position = light;
            settings.shadow.enabled = shadows;
            let options = ReferenceOptions {
                spp,
                ..ReferenceOptions::default()
            };
            let setup = Setup::new(&settings, &options, &reference.materials);
            let grid = DirectionGrid::new(setup.rays.eye, &reference.grid_triangles, |_| true);
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
                let Some(tint) = shading.plain_tint() else {
                    panic!("every face is plain");
                };
                let surface = shading.facet();
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
                let laned: Vec<Pixel> = Isa::available()
                    .into_iter()
                    .map(|isa| {
                        simd::with(
                            isa,
                            #[inline(always)]
                            || lanes.shade_lanes(&pixel, &mut luminance, &mut |_, _| true),
                        )
                    })
                    .collect();
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
                compared[2] += surface.normals.is_some() as usize;
                compared[3] += (k < 1.0) as usize;
            }
        }
        assert!(
            compared[0] > 500 && compared[1] > 10_000 && compared[2] > 200 && compared[3] > 5_000,
            "{compared:?}"
        );
    }
}
