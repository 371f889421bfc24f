//! Shadow rays to one point (the light) as a packet: blocked ones are
//! done (see `bvh/packet.rs`).

use super::Rays;
use crate::reference::bvh::cone::{Cone, ROUNDING};
use crate::reference::bvh::lanes::Lines;
use crate::reference::bvh::{TriangleBvh, widened};
use crate::reference::intersect::Shear;
use glam::DVec3;

/// The floor (n, c) across `normal` below the apex and every point of a
/// packet, `lowest` the least of 0 and n · (p − apex) over them: a segment
/// from a point to the apex stays above a plane that both its ends lie
/// above, so what lies wholly below it blocks none. It is lowered by the
/// rounding of the points' heights and of the segments' own tests, which
/// work relative to the points (10⁻¹² of their distances from the apex,
/// `reach` the farthest by |·|∞, beside the filters' own 10⁻¹² of a box's
/// or triangle's, far above it). None for a normal that is not finite.
fn floor_below(normal: DVec3, lowest: f64, reach: f64) -> Option<(DVec3, f64)> {
    let floor = lowest - ROUNDING * reach * normal.abs().element_sum();
    floor.is_finite().then_some((normal, floor))
}

/// Shadow rays to one point: blocked ones are done (limit −∞).
#[derive(Debug, Default)]
pub struct ShadowPacket {
    /// The rays' origins, their end (the light) and the origins' spread
    /// about it: the rays' lines are made from them at the first triangle
    /// tested (`ready`), so that a packet whose cone meets none (a lit
    /// patch) never pays for them, and a ray's shear at each of its exact
    /// tests (most rays have none, few more than one: kept from one test
    /// to the next, the shears' array cost the engine 6.6 M instructions
    /// and 1 M triangles 12 M more).
    origins: Vec<DVec3>,
    /// The triangle each ray passes over (`usize::MAX`: none).
    passes: Vec<usize>,
    apex: DVec3,
    spread: f64,
    ready: bool,
    limits: Vec<f64>,
    /// What lies below it blocks no ray (see [`floor_below`]).
    floor: Option<(DVec3, f64)>,
    t_max: f64,
    /// The slot of the last triangle found blocking a ray.
    last_blocker: Option<usize>,
    /// The rays in blocks for the eight-lane miss test.
    lines: Lines,
}

impl ShadowPacket {
    /// Whether ray i was found blocked.
    #[inline]
    pub fn blocked(&self, i: usize) -> bool {
        self.limits[i] == f64::NEG_INFINITY
    }

    /// Whether every ray was found blocked.
    #[inline]
    pub(super) fn all_blocked(&self) -> bool {
        self.limits.iter().all(|&l| l < 0.0)
    }

    /// Ready for a walk of the segments from `origins` to the apex of
    /// `cone` (see [`TriangleBvh::occluded_in_cone`]).
    #[inline]
    pub(super) fn start(
        &mut self,
        cone: &Cone,
        (origins, up, passes): (&[DVec3], DVec3, &[usize]),
        t_max: f64,
    ) {
        self.origins.clear();
        self.origins.extend_from_slice(origins);
        self.passes.clear();
        self.passes.extend_from_slice(passes);
        self.passes.resize(origins.len(), usize::MAX);
        self.limits.clear();
        self.t_max = t_max;
        self.apex = cone.apex;
        self.ready = false;
        // One pass over the origins: their limits, their spread and the
        // lowest across `up`.
        let (mut spread, mut lowest) = (0.0_f64, 0.0_f64);
        self.limits.extend(origins.iter().map(|&o| {
            let d = o - cone.apex;
            spread = spread.max(d.abs().max_element());
            lowest = lowest.min(up.dot(d));
            d.dot(cone.axis) + ROUNDING * d.abs().element_sum()
        }));
        self.spread = spread;
        self.floor = floor_below(up, lowest, spread);
    }

    /// The slot of the last triangle found blocking a ray.
    #[inline]
    pub(super) fn last_blocker(&self) -> Option<usize> {
        self.last_blocker
    }
}

impl Rays for ShadowPacket {
    /// The deepest of the rays' limits.
    #[inline]
    fn deepest(&self) -> f64 {
        self.limits.iter().fold(f64::NEG_INFINITY, |m, &l| m.max(l))
    }

    #[inline]
    fn floor(&self) -> Option<(DVec3, f64)> {
        self.floor
    }

    #[inline]
    fn lines(&self) -> &Lines {
        &self.lines
    }

    #[inline]
    fn takes(&self, bvh: &TriangleBvh, slot: usize) -> bool {
        bvh.occludes[slot]
    }

    #[inline(always)]
    fn make_ready(&mut self) {
        if self.ready {
            return;
        }
        self.ready = true;
        let apex = self.apex;
        let directions = self.origins.iter().map(|&o| apex - o);
        self.lines
            .fill(directions.zip(self.limits.iter().copied()), self.spread);
    }

    #[inline(always)]
    fn test_ray(&mut self, bvh: &TriangleBvh, slot: usize, _: &[DVec3; 3], k: usize) -> bool {
        if bvh.original[slot] == self.passes[k] {
            return false;
        }
        let o = self.origins[k];
        let apex = self.apex;
        let shear = Shear::new(apex - o);
        let blocked = shear.hits_from(o, &widened(&bvh.corners[slot]), 0.0, self.t_max);
        if blocked {
            self.limits[k] = f64::NEG_INFINITY;
            self.lines.set_limit(k, f64::NEG_INFINITY);
            self.last_blocker = Some(slot);
        }
        blocked
    }
}
