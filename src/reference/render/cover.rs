//! Pixels that one triangle covers: their samples' hits from the triple
//! products of `grid::cover` instead of a search of the cell ray by ray,
//! and, lit by a point light, their shadow rays decided once for the whole
//! pixel where the light's grid shows that nothing can block any of them.
//! The same triangle under every sample and the same visibility as the
//! search ray by ray; the radiance to the rounding of the hit point.
//! Covers are tried for blocks of pixels first ([`BlockCovers`]); a covered
//! pixel of one tint under a point light is shaded in lanes (`lanes`).

use super::lanes::CoveredPixel;
use super::{PixelBuffers, Traced, trace_samples};
use crate::reference::grid::{Cover, DirectionGrid};
use crate::reference::sampling::Strata;
use crate::reference::shading::Setup;
use crate::reference::surface::TriangleShading;
use crate::reference::{Reference, lift_clearance};
use glam::DVec3;

/// The own-triangle test of a shadow ray (`Reference::blocked_from_light`)
/// is trusted over the pixel when it passes at the corners by this factor.
const OWN_SLACK: f64 = 2.0;

/// Edge length (pixels) of the blocks tried for a cover first: a triangle
/// that covers a block covers each of its pixels (their cones lie in the
/// block's), which then need no test of their own.
const BLOCK: u32 = 4;

/// The triangle that covers a pixel or a block of pixels, what its points
/// share, and whether their shadow rays towards a point light are known
/// unblocked.
pub(super) struct Covered<'a> {
    cover: Cover,
    shading: TriangleShading<'a>,
    clear: bool,
}

/// The covers of the blocks of one band of BLOCK rows of a tile, each
/// found when a pixel first asks for it.
pub(super) struct BlockCovers<'a> {
    /// The tile: (x0, y0) to (x1, y1), excluded.
    tile: [u32; 4],
    /// The top row of the band.
    band: u32,
    covers: Vec<Option<Option<Covered<'a>>>>,
}

impl<'a> BlockCovers<'a> {
    pub(super) fn new(tile: [u32; 4]) -> Self {
        Self {
            tile,
            band: u32::MAX,
            covers: Vec::new(),
        }
    }

    /// The cover of the block that holds pixel (i, j), if it has one.
    pub(super) fn of(
        &mut self,
        reference: &'a Reference,
        setup: &'a Setup,
        grid: &DirectionGrid,
        (i, j): (u32, u32),
    ) -> Option<&Covered<'a>> {
        let [x0, y0, x1, y1] = self.tile;
        let band = y0 + (j - y0) / BLOCK * BLOCK;
        if band != self.band {
            self.band = band;
            self.covers.clear();
            self.covers
                .resize_with((x1 - x0).div_ceil(BLOCK) as usize, || None);
        }
        let k = ((i - x0) / BLOCK) as usize;
        self.covers[k]
            .get_or_insert_with(|| {
                let (bx, by) = (x0 + k as u32 * BLOCK, band);
                let (far_x, far_y) = ((bx + BLOCK).min(x1) as f64, (by + BLOCK).min(y1) as f64);
                let (bx, by) = (bx as f64, by as f64);
                let corners = [(bx, by), (far_x, by), (bx, far_y), (far_x, far_y)];
                reference.covered(setup, grid, &corners.map(|(x, y)| setup.rays.towards(x, y)))
            })
            .as_ref()
    }
}

impl Reference {
    /// The triangle that covers the cone of the corner rays `corners` in
    /// the eye grid, if one surely does.
    fn covered<'a>(
        &'a self,
        setup: &'a Setup,
        grid: &DirectionGrid,
        corners: &[DVec3; 4],
    ) -> Option<Covered<'a>> {
        let cover = grid.cover(corners)?;
        let shading = TriangleShading::new(self, setup, cover.triangle());
        let clear = self.shadows_clear(setup, &cover, &shading, corners);
        Some(Covered {
            cover,
            shading,
            clear,
        })
    }

    /// Pixel (i, j) when one triangle covers it in the eye grid (None,
    /// nothing done, when none surely does), `block` the cover of its
    /// block if it has one: shaded at once where a point light's shadow
    /// rays are all known unblocked, or may be asked of the light's grid
    /// one by one, and the triangle's tint is the same everywhere; else
    /// its samples into `buffers.samples` and whether their shadow rays
    /// are known unblocked.
    pub(super) fn trace_covered_samples(
        &self,
        setup: &Setup,
        spp: Strata,
        (i, j): (u32, u32),
        (grid, block): (&DirectionGrid, Option<&Covered>),
        buffers: &mut PixelBuffers,
    ) -> Option<Traced> {
        let (x, y) = (i as f64, j as f64);
        let corners = || {
            [(x, y), (x + 1.0, y), (x, y + 1.0), (x + 1.0, y + 1.0)]
                .map(|(cx, cy)| setup.rays.towards(cx, cy))
        };
        let own;
        let (cover, shading, clear) = match block {
            // The pixel's own patch may be clear where its block's is not.
            Some(Covered {
                cover,
                shading,
                clear,
            }) => (
                cover,
                shading,
                *clear || self.shadows_clear(setup, cover, shading, &corners()),
            ),
            None => {
                own = self.covered(setup, grid, &corners())?;
                (&own.cover, &own.shading, own.clear)
            }
        };
        // Shadow rays that the light's grid may not answer go through the
        // BVH as the pixel's packet, in `covered_samples`.
        let asked = clear
            || !shading.shadowed()
            || setup
                .light_grid
                .as_ref()
                .is_some_and(|g| !g.is_crowded_anywhere());
        let Some(tint) = shading.plain_tint().filter(|_| !setup.is_sphere_light() && asked) else {
            return Some(self.covered_samples(setup, spp, (i, j), (cover, shading), clear, buffers));
        };
        // What `shade_pixel` makes of these samples, without keeping them.
        let pixel = CoveredPixel {
            setup,
            spp,
            pixel: (i, j),
            cover,
            surface: shading.facet(),
            tint,
            shadowed: shading.shadowed(),
            shadows_clear: clear,
        };
        let PixelBuffers {
            lanes,
            luminance,
            scratch,
            ..
        } = buffers;
        Some(Traced::Shaded(lanes.shade(&pixel, luminance, &mut |p, o| {
            shading.blocked_from_light(self, (p, o), &mut scratch.light_packet)
        })))
    }

    /// A covered pixel's samples into `buffers.samples`, hit by hit.
    fn covered_samples(
        &self,
        setup: &Setup,
        spp: Strata,
        pixel: (u32, u32),
        (cover, shading): (&Cover, &TriangleShading),
        shadows_clear: bool,
        buffers: &mut PixelBuffers,
    ) -> Traced {
        trace_samples(setup, spp, pixel, buffers, |towards| {
            Some(shading.surface(self, towards, cover.hit(towards)))
        });
        Traced::Samples { shadows_clear }
    }

    /// Whether no shadow ray of the covered pixel's samples can be blocked:
    /// they start on the lifted part of the triangle's plane that the pixel
    /// sees, whose corners are lifted from the corner rays' hits, and the
    /// light's grid lists nothing that could block a ray from there
    /// ([`DirectionGrid::clear_towards_centre`]) but the triangle itself,
    /// which no ray of the pixel tests where the light lies well on its
    /// lifted side. Every sample is lifted alike: the cover's margin puts
    /// the eye surely on one side of the triangle's plane.
    fn shadows_clear(
        &self,
        setup: &Setup,
        cover: &Cover,
        shading: &TriangleShading,
        corners: &[DVec3; 4],
    ) -> bool {
        let Some(grid) = &setup.light_grid else {
            return false;
        };
        if !shading.shadowed() {
            return false;
        }
        let q = setup.light_position;
        let points = corners.map(|d| setup.rays.eye + d * cover.hit(d).at.t);
        // Every corner is seen from one side (the cover's margin): the
        // first's face normal is all of theirs, and so is their lift.
        let g = shading.geometric_normal(-corners[0]);
        // g · (q − p) is linear over the pixel's part of the plane and the
        // clearance convex: both bounded by their corner values.
        let least_lift = points.iter().fold(f64::INFINITY, |m, &p| m.min(g.dot(q - p)));
        let most_clear = points.iter().fold(0.0_f64, |m, &p| {
            m.max(lift_clearance(shading.shadow_offset_m(), q - p))
        });
        let own = if least_lift > OWN_SLACK * most_clear {
            cover.triangle()
        } else {
            usize::MAX
        };
        grid.clear_towards_centre(&points.map(|p| shading.lift(p, -corners[0]).1), own)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{BLOCK, Shortcuts};
    use crate::reference::grid::DirectionGrid;
    use crate::reference::{Reference, ReferenceOptions, RenderControl};
    use crate::scene::{Aabb, Material, Object, Scene, shapes};
    use crate::settings::Settings;
    use glam::Vec3;

    /// Covered pixels render what the search ray by ray renders: the same
    /// coverage and visibility bit for bit, the radiance to 10⁻¹², under a
    /// point light above, grazing the ground, and between two boxes.
    #[test]
    fn covered_pixels_render_what_the_search_ray_by_ray_renders() {
        let boxes = [
            Aabb {
                min: Vec3::new(-0.6, 0.0, -0.4),
                max: Vec3::new(0.2, 0.9, 0.3),
            },
            Aabb {
                min: Vec3::new(0.5, 0.0, -0.2),
                max: Vec3::new(0.9, 0.4, 0.6),
            },
        ];
        let mut objects = vec![Object::new("ground", shapes::ground(Vec3::ZERO, 6.0), 0)];
        objects.extend(boxes.map(|b| Object::new("box", shapes::cuboid(b), 0)));
        let scene = Scene {
            objects,
            materials: vec![Material::default()],
            ..Scene::default()
        };
        let reference = Reference::new(&scene);
        let mut settings = Settings::default();
        settings.camera.eye = Vec3::new(1.8, 1.6, 2.6);
        settings.camera.target = Vec3::new(0.0, 0.2, 0.0);
        (settings.image.width, settings.image.height) = (160, 120);
        let options = ReferenceOptions {
            spp: 4,
            ..ReferenceOptions::default()
        };
        let rays = settings.camera.pixel_rays(160, 120);
        let grid = DirectionGrid::new(rays.eye, &reference.grid_triangles, |_| true);
        let covered = (0..160 * 120)
            .filter(|k| {
                let (i, j) = ((k % 160) as f64, (k / 160) as f64);
                let corners = [(i, j), (i + 1.0, j), (i, j + 1.0), (i + 1.0, j + 1.0)];
                grid.cover(&corners.map(|(x, y)| rays.towards(x, y))).is_some()
            })
            .count();
        assert!(covered > 160 * 120 / 2, "{covered} pixels covered");
        let control = RenderControl::default();
        // Blinn-Phong and Lambert, both in lanes.
        for (light, k) in [
            (Vec3::new(-1.0, 3.0, 1.0), 0.5),
            (Vec3::new(2.5, 0.05, -1.0), 0.5),
            (Vec3::new(0.35, 0.3, 0.2), 0.5),
            (Vec3::new(-1.0, 3.0, 1.0), 1.0),
            (Vec3::new(0.35, 0.3, 0.2), 1.0),
        ] {
            settings.light.position = light;
            settings.material.k = k;
            let render = |covers| {
                let shortcuts = Shortcuts {
                    covers,
                    ..Shortcuts::ALL
                };
                reference
                    .render_in_blocks(&settings, &options, &control, BLOCK, shortcuts)
                    .unwrap()
            };
            let (searched, covered) = (render(false), render(true));
            let differ = |a: &[f32], b: &[f32]| a.iter().zip(b).filter(|(a, b)| a != b).count();
            assert_eq!(
                differ(&searched.coverage, &covered.coverage),
                0,
                "coverage, light at {light}"
            );
            assert_eq!(
                differ(&searched.visibility, &covered.visibility),
                0,
                "visibility, light at {light}"
            );
            assert!(searched.visibility.contains(&0.0) && searched.visibility.contains(&1.0));
            assert_eq!(searched.stats.shadow_rays, covered.stats.shadow_rays);
            for (s, c) in searched.radiance.iter().zip(&covered.radiance) {
                for (s, c) in s.iter().zip(c) {
                    assert!((s - c).abs() <= 1e-12 * s.abs().max(1e-30), "{s} vs {c}");
                }
            }
        }
    }
}
