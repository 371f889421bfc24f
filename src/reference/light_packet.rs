//! The shadow rays of a pixel (or of a block of pixels traced together)
//! towards a point light, cast together: they all end at the light and
//! start at the pixels' surface points, so they lie in one narrow cone from
//! the light, and walk the BVH as one packet (see
//! [`TriangleBvh::occluded_in_cone`]), lazily, at the first ray the light's
//! grid cannot answer. Each ray is still decided by the same f64 test, so
//! every answer is the one the BVH gives that ray on its own; a ray passes
//! over the triangle it was lifted off where the lift keeps it from that
//! triangle's plane (`own_unreached`, as the light's grid does),
//! an exact test spared for nearly every ray (engine at 32 spp: the walks'
//! instructions 626 → 552 M).
//!
//! Origins on two surfaces far apart along the light's rays (a sphere's
//! edge and the ground beyond it) span a wide cone, and the packet would
//! test everything between them (1 M triangles at 16 spp: 11 % of the
//! packets kept 68 % of the triangles inside the cones). They are cast as two packets,
//! split across the widest gap between their distances from the light,
//! where each side's cone is less than half as wide; each side may split
//! once more.

use super::bvh::{Cone, ShadowPacket, TriangleBvh};
use super::shading::STOP_SHORT_REL;
use super::simd::{self, Isa};
use glam::DVec3;
use std::ops::Range;

/// Fewer shadow rays than this in a packet: each on its own.
const MIN_RAYS: usize = 4;
/// Splits of a packet's origins, one within another: at most 2^SPLITS packets.
const SPLITS: u32 = 2;
/// The origins' distances from the light are binned this finely to find
/// the widest gap between them.
const BINS: usize = 32;
/// A gap narrower than this many bins is not split across: on the
/// 110 k-triangle engine, whose parts stand close, such splits cost more
/// than they spared (callgrind at 32 spp: gaps of one bin or more +1.9 %
/// of its instructions, of twelve or more +0.8 %; 1 M triangles at 16 spp
/// −7.9 % and −8.0 %).
const LEAST_GAP: usize = 12;

#[derive(Debug, Default)]
pub(super) struct LightPacket {
    origins: Vec<DVec3>,
    /// The triangle each ray's segment cannot reach (`usize::MAX`: none).
    passes: Vec<usize>,
    /// The sum of the unit normals, towards the light, of the surfaces the
    /// origins lie on: every packet's floor lies across it (across each
    /// part's own sum instead, the 1 M scene took 0.1 % more).
    normal_sum: DVec3,
    /// Whether the packet was cast (None: not yet) and could be.
    cast: Option<bool>,
    /// Just past where the last origin asked about was found: the samples
    /// ask in the order of `origins`, so each search starts there and
    /// finds its origin at once (one pass per pixel instead of one per
    /// ray; starting at the last one found, each search first failed on
    /// it, a branch often mispredicted).
    cursor: usize,
    /// The packet of every origin, when they were not split.
    whole: ShadowPacket,
    /// When they were (`used` > 0: the first `used` parts were cast):
    /// each origin's part and place in it (None: its ray goes on its own).
    places: Vec<Option<(usize, usize)>>,
    parts: Vec<Part>,
    used: usize,
    /// Each origin's distance along the whole cone's axis, with its index;
    /// each part's origins lie in a range of it.
    depths: Vec<(f64, usize)>,
}

/// The rays of one part, cast as a packet.
#[derive(Debug, Default)]
struct Part {
    origins: Vec<DVec3>,
    passes: Vec<usize>,
    packet: ShadowPacket,
}

impl LightPacket {
    /// A new packet for the shadow rays from these origins, each with the
    /// unit normal of its surface towards the light (any direction is
    /// exact; the surfaces' own cut the most) and the triangle it cannot
    /// reach (`usize::MAX`: none).
    pub fn reset(&mut self, origins: impl Iterator<Item = (DVec3, DVec3, usize)>) {
        self.clear();
        for ray in origins {
            self.add(ray);
        }
    }

    /// An empty packet, which [`Self::add`] then fills: [`Self::reset`]
    /// one ray at a time.
    #[inline(always)]
    pub fn clear(&mut self) {
        self.origins.clear();
        self.passes.clear();
        self.normal_sum = DVec3::ZERO;
        self.cast = None;
        self.cursor = 0;
    }

    /// One more shadow ray, as [`Self::reset`] takes them; its index, for
    /// [`Self::blocked_ray`].
    #[inline(always)]
    pub fn add(&mut self, (origin, normal, passes): (DVec3, DVec3, usize)) -> usize {
        self.origins.push(origin);
        self.passes.push(passes);
        self.normal_sum += normal;
        self.origins.len() - 1
    }

    /// Whether the shadow ray from `origin` (one of the packet's) to the
    /// light at `light` is blocked; None when the packet cannot tell.
    pub fn blocked(&mut self, bvh: &TriangleBvh, light: DVec3, origin: DVec3) -> Option<bool> {
        // An equal origin elsewhere is the same ray, with the same answer.
        let i = (self.cursor..self.origins.len())
            .chain(0..self.cursor)
            .find(|&i| self.origins[i] == origin)?;
        self.cursor = i + 1;
        self.blocked_ray(bvh, light, i)
    }

    /// Whether ray `i` of the packet (as [`Self::add`] numbered it) is
    /// blocked: [`Self::blocked`] without the search for its origin (the
    /// engine's render: 1.4 % of its instructions).
    pub fn blocked_ray(&mut self, bvh: &TriangleBvh, light: DVec3, i: usize) -> Option<bool> {
        if self.origins.len() < MIN_RAYS {
            return None;
        }
        if self.cast.is_none() {
            self.cast = Some(self.cast_once(bvh, light));
        }
        match self.cast {
            Some(true) if self.used == 0 => Some(self.whole.blocked(i)),
            Some(true) => {
                let (part, k) = self.places[i]?;
                Some(self.parts[part].packet.blocked(k))
            }
            _ => None,
        }
    }

    /// [`Self::cast_packets`], compiled for AVX2 where the CPU has it, as
    /// the walk is; out of line, as it runs once a packet and
    /// [`Self::blocked`] once a ray.
    #[inline(never)]
    fn cast_once(&mut self, bvh: &TriangleBvh, light: DVec3) -> bool {
        simd::with(
            Isa::Avx2,
            #[inline(always)]
            || self.cast_packets(bvh, light),
        )
    }

    /// Casts the rays as one packet, or as parts split by their distance
    /// from the light; false when no cone holds them.
    #[inline(always)]
    fn cast_packets(&mut self, bvh: &TriangleBvh, light: DVec3) -> bool {
        let Some((cone, [near, far])) = Cone::around_reaching(light, &self.origins) else {
            return false;
        };
        let n = self.origins.len();
        self.used = 0;
        if n >= 2 * MIN_RAYS && spread_along((near, far), &cone) {
            let axis = cone.axis();
            self.depths.clear();
            self.depths.extend(
                self.origins
                    .iter()
                    .enumerate()
                    .map(|(i, &o)| ((o - light).dot(axis), i)),
            );
            self.cast_split(bvh, light, (0..n, &cone, (near, far)), SPLITS);
        }
        if self.used == 0 {
            let floor = self.normal_sum.normalize_or_zero();
            let rays = (&self.origins[..], floor, &self.passes[..]);
            bvh.occluded_in_cone(&cone, rays, 1.0 - STOP_SHORT_REL, &mut self.whole);
        }
        true
    }

    /// Casts the rays of `depths[range]` (inside `cone`) as two parts or
    /// more where [`Self::split`] splits them, each part split again while
    /// `levels` allow; false when it does not.
    fn cast_split(
        &mut self,
        bvh: &TriangleBvh,
        light: DVec3,
        (range, cone, reach): (Range<usize>, &Cone, (f64, f64)),
        levels: u32,
    ) -> bool {
        let Some((cut, cones)) = self.split(light, range.clone(), cone, reach) else {
            return false;
        };
        if self.used == 0 {
            self.places.clear();
            self.places.resize(self.origins.len(), None);
        }
        for (side, cone) in [range.start..cut, cut..range.end].into_iter().zip(cones) {
            // A side too small for a packet: its rays go on their own.
            let Some(cone) = cone else { continue };
            if !(levels > 1
                && self.cast_split(bvh, light, (side.clone(), &cone, self.reach(&side)), levels - 1))
            {
                self.cast_part(bvh, side, &cone);
            }
        }
        true
    }

    /// The least and the greatest of `depths[range]`.
    fn reach(&self, range: &Range<usize>) -> (f64, f64) {
        self.depths[range.clone()]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(d, _)| {
                (a.min(d), b.max(d))
            })
    }

    /// Casts the rays of `depths[range]` as one packet in `cone`.
    fn cast_part(&mut self, bvh: &TriangleBvh, range: Range<usize>, cone: &Cone) {
        let p = self.used;
        self.used += 1;
        if self.parts.len() <= p {
            self.parts.push(Part::default());
        }
        let part = &mut self.parts[p];
        part.origins.clear();
        part.passes.clear();
        for &(_, i) in &self.depths[range] {
            self.places[i] = Some((p, part.origins.len()));
            part.origins.push(self.origins[i]);
            part.passes.push(self.passes[i]);
        }
        let floor = self.normal_sum.normalize_or_zero();
        let rays = (&part.origins[..], floor, &part.passes[..]);
        bvh.occluded_in_cone(cone, rays, 1.0 - STOP_SHORT_REL, &mut part.packet);
    }

    /// Reorders `depths[range]` into two sides across the widest gap
    /// between the distances (binned), and gives where the second starts
    /// with each side's cone (None for a side of fewer than [`MIN_RAYS`]):
    /// when the origins lie farther apart along `cone`'s axis than across
    /// it and each side's cone is less than half as wide.
    fn split(
        &mut self,
        light: DVec3,
        range: Range<usize>,
        cone: &Cone,
        (near, far): (f64, f64),
    ) -> Option<(usize, [Option<Cone>; 2])> {
        if !spread_along((near, far), cone) {
            return None;
        }
        let width = cone.width();
        let depths = &mut self.depths[range.clone()];
        let scale = BINS as f64 / (far - near);
        let bin = |d: f64| (((d - near) * scale) as usize).min(BINS - 1);
        let filled = depths.iter().fold(0_u64, |m, &(d, _)| m | 1 << bin(d));
        let gap = widest_gap(filled)?;
        // The nearer side first.
        let mut cut = 0;
        for k in 0..depths.len() {
            if bin(depths[k].0) < gap {
                depths.swap(k, cut);
                cut += 1;
            }
        }
        let mut cones = [None, None];
        for (side, rays) in cones.iter_mut().zip([&depths[..cut], &depths[cut..]]) {
            if rays.len() >= MIN_RAYS {
                let narrow = Cone::around(light, rays.iter().map(|&(_, i)| self.origins[i]))?;
                if narrow.width() < 0.5 * width {
                    *side = Some(narrow);
                } else {
                    return None;
                }
            }
        }
        // Not every ray on its own.
        cones
            .iter()
            .any(Option::is_some)
            .then_some((range.start + cut, cones))
    }
}

/// Whether points from depth `near` to `far` along `cone`'s axis lie
/// farther apart along it than across it.
fn spread_along((near, far): (f64, f64), cone: &Cone) -> bool {
    far - near > cone.width() * near
}

/// The first bin of the widest run of empty bins in `filled` (bins 0 and
/// BINS − 1 hold the nearest and the farthest), if there is one.
fn widest_gap(filled: u64) -> Option<usize> {
    let (mut best, mut widest, mut run) = (None, 0, 0);
    for b in 1..BINS {
        if filled & (1 << b) == 0 {
            run += 1;
        } else {
            if run > widest && run >= LEAST_GAP {
                (best, widest) = (Some(b - run), run);
            }
            run = 0;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bvh::BvhTriangle;

    /// A square grid of 2 × cells² triangles at height y, from (x0, z0).
    fn grid(y: f64, (x0, z0): (f64, f64), size: f64, cells: usize) -> Vec<BvhTriangle> {
        let step = size / cells as f64;
        let at = |i: usize, j: usize| DVec3::new(x0 + i as f64 * step, y, z0 + j as f64 * step);
        (0..cells * cells)
            .flat_map(|k| {
                let (i, j) = (k % cells, k / cells);
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                [[a, d, c], [a, c, b]].map(|corners| BvhTriangle {
                    corners: corners.map(|p| p.as_vec3()),
                    occludes: true,
                })
            })
            .collect()
    }

    /// A raised platform with a strip above the ground beyond it, a small
    /// block higher up on the light's other side, and the light.
    fn platforms() -> (TriangleBvh, DVec3) {
        let mut triangles = grid(0.0, (-3.0, -3.0), 6.0, 40);
        triangles.extend(grid(1.0, (-1.0, -1.0), 2.0, 20));
        triangles.extend(grid(2.0, (3.3, 0.0), 0.4, 4));
        // The strip over the ground origins' rays where x < 1.52.
        let strip = |x: f64, z: f64| DVec3::new(x, 3.0, z);
        for corners in [
            [strip(1.8, -1.0), strip(1.8, 1.0), strip(1.964, 1.0)],
            [strip(1.8, -1.0), strip(1.964, 1.0), strip(1.964, -1.0)],
        ] {
            triangles.push(BvhTriangle {
                corners: corners.map(|p| p.as_vec3()),
                occludes: true,
            });
        }
        (TriangleBvh::new(&triangles), DVec3::new(3.0, 10.0, 0.2))
    }

    /// `n` origins by the platform's edge and on the ground beyond it, as
    /// a block of pixels on the platform's silhouette sees them, the
    /// ground's half in the strip's shadow.
    fn edge_and_ground(n: usize) -> Vec<DVec3> {
        let mut rng = crate::reference::sampling::Rng::new(7, 0, 0);
        (0..n)
            .map(|k| {
                let (u, z) = (rng.next_f64(), 0.1 + 0.02 * rng.next_f64());
                match k % 2 {
                    0 => DVec3::new(0.96 + 0.04 * u, 1.0 + 1e-6, z),
                    _ => DVec3::new(1.5 + 0.04 * u, 1e-6, z),
                }
            })
            .collect()
    }

    /// Each origin's answer from the packet, against the ray's own walk;
    /// how many the packet told, and how many of those are blocked.
    fn answers(
        bvh: &TriangleBvh,
        light: DVec3,
        origins: &[DVec3],
        packet: &mut LightPacket,
    ) -> (usize, usize) {
        packet.reset(origins.iter().map(|&o| (o, DVec3::Y, usize::MAX)));
        let (mut told, mut blocked) = (0, 0);
        for &o in origins {
            let alone = bvh.occluded(o, light - o, 0.0, 1.0 - STOP_SHORT_REL);
            if let Some(answer) = packet.blocked(bvh, light, o) {
                assert_eq!(answer, alone, "{o}");
                told += 1;
                blocked += usize::from(alone);
            }
        }
        (told, blocked)
    }

    /// Split into two packets, every ray gets what it gets on its own,
    /// blocked or not.
    #[test]
    fn a_split_packet_gives_each_ray_its_own_answer() {
        let (bvh, light) = platforms();
        let origins = edge_and_ground(64);
        let mut packet = LightPacket::default();
        let (told, blocked) = answers(&bvh, light, &origins, &mut packet);
        assert_eq!(packet.used, 2, "parts");
        assert_eq!(told, origins.len());
        assert!(0 < blocked && blocked < told, "{blocked} blocked");
    }

    /// Three origins on the small block, nearest the light and on its
    /// other side: split off first, too few for a packet, so the packet
    /// leaves them to their own walks; the others split again in two.
    #[test]
    fn a_side_too_small_for_a_packet_goes_ray_by_ray() {
        let (bvh, light) = platforms();
        let mut origins = edge_and_ground(48);
        let alone = [0.05, 0.15, 0.25].map(|z| DVec3::new(3.5, 2.0 + 1e-6, 0.1 + z));
        origins.extend(alone);
        let mut packet = LightPacket::default();
        let (told, blocked) = answers(&bvh, light, &origins, &mut packet);
        assert_eq!(packet.used, 2, "parts");
        assert_eq!(told, origins.len() - alone.len());
        assert!(0 < blocked && blocked < told, "{blocked} blocked");
        for o in alone {
            assert_eq!(packet.blocked(&bvh, light, o), None, "{o}");
        }
    }
}
