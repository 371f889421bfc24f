//! The shadow rays of a pixel (or of a block of pixels traced together)
//! towards a point light, cast together: they all end at the light and
//! start at the pixels' surface points, so they lie in one narrow cone from
//! the light, and walk the BVH as one packet (see
//! [`TriangleBvh::occluded_in_cone`]), lazily, at the first ray the light's
//! grid cannot answer. Each ray is still decided by the same f64 test, so
//! every answer is the one the BVH gives that ray on its own; a ray passes
//! over the triangle it was lifted off where the lift keeps it from that
//! triangle's plane (`Reference::own_unreached`, as the light's grid does),
//! an exact test spared for nearly every ray (engine at 32 spp: the walks'
//! instructions 626 → 552 M).

use super::bvh::{Cone, ShadowPacket, TriangleBvh};
use super::shading::STOP_SHORT_REL;
use super::simd::{self, Isa};
use glam::DVec3;

/// Fewer shadow rays than this in a pixel: each on its own.
const MIN_RAYS: usize = 4;

#[derive(Debug, Default)]
pub(super) struct LightPacket {
    origins: Vec<DVec3>,
    /// The triangle each ray's segment cannot reach (`usize::MAX`: none).
    passes: Vec<usize>,
    /// The sum of the unit normals, towards the light, of the surfaces the
    /// origins lie on: the packet's floor lies across it.
    normals: DVec3,
    /// Whether the packet was cast (None: not yet) and could be.
    cast: Option<bool>,
    /// Where the last origin asked about was found: the samples ask in
    /// the order of `origins`, so each search starts there (one pass per
    /// pixel instead of one per ray).
    cursor: usize,
    packet: ShadowPacket,
}

impl LightPacket {
    /// A new packet for the shadow rays from these origins, each with the
    /// unit normal of its surface towards the light (any direction is
    /// exact; the surfaces' own cut the most) and the triangle it cannot
    /// reach (`usize::MAX`: none).
    pub fn reset(&mut self, origins: impl Iterator<Item = (DVec3, DVec3, usize)>) {
        self.origins.clear();
        self.passes.clear();
        self.normals = DVec3::ZERO;
        for (origin, normal, passes) in origins {
            self.origins.push(origin);
            self.passes.push(passes);
            self.normals += normal;
        }
        self.cast = None;
        self.cursor = 0;
    }

    /// Whether the shadow ray from `origin` (one of the packet's) to the
    /// light at `light` is blocked; None when the packet cannot tell.
    pub fn blocked(&mut self, bvh: &TriangleBvh, light: DVec3, origin: DVec3) -> Option<bool> {
        if self.origins.len() < MIN_RAYS {
            return None;
        }
        let cast = *self.cast.get_or_insert_with(|| {
            // Compiled for AVX2 where the CPU has it, as the walk is.
            let cone = simd::with(
                Isa::Avx2,
                #[inline(always)]
                || Cone::around(light, self.origins.iter().copied()),
            );
            if let Some(cone) = &cone {
                let floor = self.normals.normalize_or_zero();
                bvh.occluded_in_cone(
                    cone,
                    (&self.origins, floor, &self.passes),
                    1.0 - STOP_SHORT_REL,
                    &mut self.packet,
                );
            }
            cone.is_some()
        });
        // An equal origin elsewhere is the same ray, with the same answer.
        let i = (self.cursor..self.origins.len())
            .chain(0..self.cursor)
            .find(|&i| self.origins[i] == origin)?;
        self.cursor = i;
        cast.then(|| self.packet.blocked(i))
    }
}
