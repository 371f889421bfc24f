//! A block of pixels traced as one packet ([`Reference::trace_run`]: large
//! scenes, without an eye grid) and lit by a point light, shaded without a
//! [`Surface`](crate::reference::surface::Surface) a sample: one pass
//! works out each hit's point, lift and light into a short record and
//! adds its shadow ray to the light packet, then each pixel sums its
//! records. The same operations in the same order as `run_samples`,
//! `aim_light_packet` and `shade_pixel` make of the samples' surfaces, so
//! the same bits (`tests` holds them to it), with a third of the bytes
//! moved a sample and none of the streams, which a point light never
//! draws from.

use super::PixelBuffers;
use super::pixel::{Pixel, PixelSums};
use crate::reference::Reference;
use crate::reference::shading::{PointLit, Setup};
use crate::reference::surface::{ShadingCache, shadow_ray};
use glam::DVec3;

/// What a sample that meets a surface needs once its shadow ray is known.
#[derive(Clone, Copy, Debug)]
pub(super) struct LitSample {
    tint: DVec3,
    lit: PointLit,
    /// Where its shadow ray starts, and its index in the light packet
    /// (None: not in it).
    origin: DVec3,
    ray: Option<usize>,
}

impl Reference {
    /// The pixels of the block whose packet `trace_run` left in `buffers`
    /// (`n` samples each, in its order), each handed to `done` with its
    /// place in the block. Only without a light grid, as `trace_run` is.
    #[inline(always)]
    pub(super) fn shade_point_run<'a>(
        &'a self,
        setup: &'a Setup,
        n: u32,
        (buffers, cache): (&mut PixelBuffers, &mut ShadingCache<'a>),
        mut done: impl FnMut(usize, Pixel),
    ) {
        debug_assert!(setup.light_grid.is_none() && !setup.is_sphere_light());
        let PixelBuffers {
            directions,
            packet,
            lit,
            luminance,
            scratch,
            ..
        } = buffers;
        lit.clear();
        let light_packet = &mut scratch.light_packet;
        light_packet.clear();
        for (&towards, hit) in directions.iter().zip(&packet.hits) {
            lit.push(hit.map(|hit| {
                let shading = cache.get(self, setup, hit.triangle);
                let (p, normal, o) = shading.point(towards, hit);
                let (g, origin) = shading.lift(p, o);
                let facet = shading.facet();
                let shadowed = shading.shadowed();
                let ray = shadow_ray(
                    setup.light_position,
                    (hit.triangle, shadowed),
                    (p, normal, g),
                    (origin, shading.shadow_offset_m()),
                )
                .map(|ray| light_packet.add(ray));
                LitSample {
                    tint: shading.tint_at(self, hit.at.barycentric),
                    lit: PointLit::new(setup, (p, normal, o), &facet.brdf, shadowed),
                    origin,
                    ray,
                }
            }));
        }
        for (k, samples) in lit.chunks(n as usize).enumerate() {
            let mut sums = PixelSums::new(luminance);
            for sample in samples {
                match sample {
                    Some(s) => {
                        let blocked = s.lit.casts()
                            && self.ray_blocked_in_packet(setup, (s.origin, s.ray), light_packet);
                        sums.add(s.tint, &s.lit.estimate(blocked), n);
                    }
                    None => sums.add_background(),
                }
            }
            done(k, sums.pixel(n));
        }
    }
}
