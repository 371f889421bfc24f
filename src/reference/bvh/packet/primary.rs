//! Primary rays from one point (the eye) as a packet: each ray's closest
//! hit so far (see `bvh/packet.rs`).

use super::Rays;
use crate::reference::bvh::cone::{Cone, ROUNDING};
use crate::reference::bvh::lanes::Lines;
use crate::reference::bvh::{Hit, TriangleBvh, closer};
use crate::reference::intersect::{Shear, with_axes};
use glam::DVec3;

/// Primary rays from one point: each one's closest hit so far.
#[derive(Debug, Default)]
pub struct PrimaryPacket {
    /// The rays' directions, and the cone's axis: the rays, their
    /// depths along the axis and their lines are made from them at the
    /// first triangle the walk tests (`ready`), so that a packet that
    /// meets none (background) never pays for them.
    directions: Vec<DVec3>,
    axis: DVec3,
    ready: bool,
    rays: Vec<PrimaryRay>,
    pub hits: Vec<Option<Hit>>,
    /// The rays in blocks for the eight-lane miss test.
    lines: Lines,
}

/// A primary ray and what its tests need beside it, in one place (one
/// look-up a test: engine's primary walk −3 %).
#[derive(Debug)]
struct PrimaryRay {
    /// Its shear (its origin is the apex).
    shear: Shear,
    /// d · axis (rounded up): depth = t · along.
    along: f64,
    /// The farthest t its next hit may have: just past its closest so far.
    t_max: f64,
}

impl PrimaryPacket {
    /// Ready for a walk of the rays along `directions` inside `cone`.
    #[inline]
    pub(super) fn start(&mut self, cone: &Cone, directions: &[DVec3]) {
        self.directions.clear();
        self.directions.extend_from_slice(directions);
        self.hits.clear();
        self.hits.resize(directions.len(), None);
        self.axis = cone.axis;
        self.ready = false;
    }

    /// Ray k's test against the triangle (`relative` to the apex, the
    /// rays' common origin), kept when it is the closest hit so far (true).
    #[inline(always)]
    fn test_axes<const KZ: usize, const SWAP: bool>(
        &mut self,
        k: usize,
        triangle: usize,
        relative: &[DVec3; 3],
    ) -> bool {
        let ray = &mut self.rays[k];
        if let Some(at) = ray.shear.intersect_in::<KZ, SWAP>(relative, 0.0, ray.t_max) {
            let best = &mut self.hits[k];
            if best.is_none_or(|b| closer(at, triangle, b)) {
                *best = Some(Hit { triangle, at });
                ray.t_max = at.t.next_up();
                let limit = at.t * ray.along * (1.0 + ROUNDING);
                self.lines.set_limit(k, limit);
                return true;
            }
        }
        false
    }
}

impl Rays for PrimaryPacket {
    const NEAREST_FIRST: bool = true;

    #[inline]
    fn lines(&self) -> &Lines {
        &self.lines
    }

    /// From the blocks' limits, 32 for a packet of 256 rays (engine's
    /// primary walk −1.8 %; the shadow packets' walk ran 0.4 % more, its
    /// coarser bound cutting less). Unbounded before the first test: no
    /// ray has a hit yet (and the lines are not made).
    #[inline]
    fn deepest(&self) -> f64 {
        if self.ready {
            self.lines.deepest()
        } else {
            f64::INFINITY
        }
    }

    #[inline(always)]
    fn make_ready(&mut self) {
        if self.ready {
            return;
        }
        self.ready = true;
        let axis = self.axis;
        self.rays.clear();
        for &d in &self.directions {
            self.rays.push(PrimaryRay {
                shear: Shear::new(d),
                along: d.dot(axis) * (1.0 + ROUNDING),
                t_max: f64::INFINITY,
            });
        }
        self.lines
            .fill(self.directions.iter().map(|&d| (d, f64::INFINITY)), 0.0);
    }

    #[inline(always)]
    fn test_ray(&mut self, bvh: &TriangleBvh, slot: usize, relative: &[DVec3; 3], k: usize) -> bool {
        let triangle = bvh.original[slot];
        with_axes!(self.rays[k].shear.axes(), KZ, SWAP => self.test_axes::<KZ, SWAP>(k, triangle, relative))
    }
}
