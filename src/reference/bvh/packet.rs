//! Packets: rays that all lie in one convex cone from its apex (a pixel's
//! primary samples lie in the cone of its four corner rays from the eye; a
//! pixel's shadow rays to a point light, in the cone from the light around
//! their origins) walk the BVH together. A node is entered when its box
//! meets the cone no deeper than the deepest ray still needs; a triangle
//! outside the cone is passed over, and each one met is tested, in f64 by
//! the same watertight test, by every ray of the packet that can still
//! reach it.
//!
//! Primary packets visit a node's children nearest first along the axis
//! (the first hits found are then more often the closest, and cut what lies
//! behind them); shadow packets, for which any hit will do, keep obvhs's
//! order by the axis's octant.
//!
//! Every filter is conservative, so each ray gets exactly what it gets on
//! its own ([`TriangleBvh::closest_hit`], [`TriangleBvh::occluded`]) and
//! what testing every triangle gives it:
//! - a ray inside the cone only meets boxes and triangles that meet the
//!   cone; boxes are padded by [`super::PAD`] of the scene's extent, and
//!   both tests allow for the rounding of the planes and distances (10⁻¹²
//!   of the distances, far above it);
//! - depths are measured from the apex along the cone's axis a: a point at
//!   t along a primary ray d has depth t (d · a), and a shadow ray's points
//!   lie between the light (depth 0) and its origin; a box or triangle whose
//!   least depth is beyond what a ray can reach holds nothing for it, and
//!   ties are still tested, so the lowest index wins among equal distances;
//! - a shadow packet's segments all lie above a floor across the normal of
//!   the surfaces they leave, below their origins and the light (see
//!   `shadow::floor_below`): a box or triangle wholly below it blocks none;
//! - rays are tested eight at a time against the triangle's edge planes
//!   through the apex in f32 (`bvh/lanes.rs`), with a margin that makes a
//!   ray it rules out a miss of the scalar test.

use super::cone::{Cone, FrameCone, ROUNDING};
use super::lanes::{GROUP, LANES, LEFT_PACKED, Lines};
use super::{TRAVERSAL, TriangleBvh, widened};
use crate::reference::intersect::extent;
use crate::reference::simd::{self, Isa};
// `UVec2` is named inside obvhs's `traverse!` macro.
use glam::{DVec3, UVec2};
use obvhs::cwbvh::CwBvh;
pub use primary::PrimaryPacket;
pub use shadow::ShadowPacket;

mod primary;
mod shadow;

/// What the walk visits next: a node (its index) or a leaf's triangles
/// (first slot, count).
#[derive(Clone, Copy, Debug)]
enum Visit {
    Node(u32),
    Leaf(u32, u32),
}

thread_local! {
    /// Each thread's stack of visits, with their least depths, reused from
    /// packet to packet.
    static WALK: std::cell::Cell<Vec<(f64, Visit)>> = const { std::cell::Cell::new(Vec::new()) };
}

/// The rays of a packet: what each can still reach, and how to test it.
pub trait Rays {
    /// Whether the walk visits a node's children nearest first (closest
    /// hits: the first found is more often the closest, and cuts the rest).
    const NEAREST_FIRST: bool = false;

    /// A floor (n, c) below every ray: each point a ray can reach has
    /// n · (x − apex) ≥ c (none unless they say so).
    fn floor(&self) -> Option<(DVec3, f64)> {
        None
    }
    /// The rays as lines through the apex, for the eight-lane filter.
    fn lines(&self) -> &Lines;
    /// No shallower than the deepest depth that still matters to a ray
    /// (negative: every ray is done): the walk stops short of nothing it
    /// needs.
    fn deepest(&self) -> f64;
    /// Makes the rays and [`Self::lines`] where the packet left that to its
    /// first triangle (a packet that meets none never pays for them).
    fn make_ready(&mut self) {}
    /// Whether the triangle in leaf slot `slot` matters to these rays
    /// (every one does, unless they say otherwise).
    fn takes(&self, _bvh: &TriangleBvh, _slot: usize) -> bool {
        true
    }
    /// Ray k's own f64 test against the triangle in leaf slot `slot`
    /// (corners `relative` to the apex); true when its limit changed.
    fn test_ray(&mut self, bvh: &TriangleBvh, slot: usize, relative: &[DVec3; 3], k: usize) -> bool;

    /// Tests the triangle (least depth `nearest`) against every ray that
    /// can reach it and that the eight-lane filter keeps; true when
    /// a ray's limit changed.
    #[inline(always)]
    fn test(&mut self, bvh: &TriangleBvh, slot: usize, relative: &[DVec3; 3], nearest: f64) -> bool {
        if !self.takes(bvh, slot) {
            return false;
        }
        self.make_ready();
        let planes = self.lines().planes(relative);
        let mut changed = false;
        for group in 0..self.lines().groups() {
            // The group's kept rays listed first, then tested: a loop a
            // block over its kept lanes ended in a mispredicted branch
            // nearly every time. (A test changes only its own block's
            // limits, which its block's filter has already read.)
            let mut kept = [0_u8; GROUP * LANES];
            let mut count = 0;
            let mut blocks = self.lines().group_may_hit(group, &planes, nearest);
            while blocks != 0 {
                let block = blocks.trailing_zeros() as usize;
                blocks &= blocks - 1;
                let lanes = self.lines().may_hit(group * GROUP + block, &planes, nearest);
                let packed = &LEFT_PACKED[lanes as usize];
                for (entry, &lane) in kept[count..count + LANES].iter_mut().zip(packed) {
                    *entry = (block * LANES) as u8 + lane;
                }
                count += lanes.count_ones() as usize;
            }
            for &k in &kept[..count] {
                changed |= self.test_ray(bvh, slot, relative, group * GROUP * LANES + k as usize);
            }
        }
        changed
    }
}

impl TriangleBvh {
    /// Walks the BVH with a packet of rays inside `cone`, compiled for
    /// AVX2 where the CPU has it (same IEEE operations, wider registers).
    pub fn walk_cone(&self, cone: &Cone, rays: &mut impl Rays) {
        simd::with(
            Isa::Avx2,
            #[inline(always)]
            || self.walk_cone_here(cone, rays),
        );
    }

    #[inline(always)]
    fn walk_cone_here<R: Rays>(&self, cone: &Cone, rays: &mut R) {
        let Some(bvh) = self.bvh.as_ref() else {
            return;
        };
        let frame = FrameCone::new(*cone, self, rays.floor());
        let mut farthest = rays.deepest();
        if R::NEAREST_FIRST {
            self.walk_nearest_first(bvh, &frame, rays, &mut farthest);
            return;
        }
        // Taken out of its cell, so that the walk is compiled into the caller.
        let mut owned = TRAVERSAL.take();
        let state = &mut owned;
        {
            state.reinit(cone.axis.as_vec3a());
            let mut node;
            // Out of the whole walk once every ray is done (a plain `break`
            // leaves only the leaf's triangles).
            'walk: {
                obvhs::traverse!(
                    bvh,
                    node,
                    state,
                    frame.child_mask(self, node, farthest, state.oct_inv4),
                    {
                        if self.test_triangle(&frame, rays, state.primitive_id as usize, &mut farthest) {
                            break 'walk;
                        }
                    }
                );
            }
        }
        TRAVERSAL.set(owned);
    }

    /// The walk with each node's children visited nearest first along the
    /// cone's axis (obvhs's walk orders them by the octant of the axis
    /// alone): a packet's first hits are then more often its closest, and
    /// cut more of what lies behind them.
    #[inline(always)]
    fn walk_nearest_first(&self, bvh: &CwBvh, frame: &FrameCone, rays: &mut impl Rays, farthest: &mut f64) {
        let mut stack = WALK.take();
        stack.clear();
        stack.push((f64::NEG_INFINITY, Visit::Node(0)));
        'walk: while let Some((least, visit)) = stack.pop() {
            // Limits fall as hits are found: a child pushed before may now
            // lie beyond them all.
            if least > *farthest {
                continue;
            }
            match visit {
                Visit::Node(index) => {
                    let node = &bvh.nodes[index as usize];
                    let first = stack.len();
                    frame.children(self, node, *farthest, |depth, child| {
                        let visit = if node.is_leaf(child) {
                            let (start, count) = node.child_primitives(child);
                            // Its corners (and a child node's data) asked for
                            // now, to come while the siblings are pushed and
                            // sorted: 1 M triangles' render −2 %, the 110 k
                            // engine's the same.
                            simd::prefetch(&self.corners[start as usize]);
                            Visit::Leaf(start, count)
                        } else {
                            let index = node.child_node_index(child);
                            simd::prefetch(&bvh.nodes[index as usize]);
                            Visit::Node(index)
                        };
                        stack.push((depth, visit));
                    });
                    // Nearest last, so that it is popped first.
                    stack[first..].sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
                }
                Visit::Leaf(start, count) => {
                    for slot in start..start + count {
                        if self.test_triangle(frame, rays, slot as usize, farthest) {
                            break 'walk;
                        }
                    }
                }
            }
        }
        WALK.set(stack);
    }

    /// The corners of the triangle in leaf slot `slot` relative to `apex`,
    /// and the allowance for the rounding of the tests on them.
    #[inline(always)]
    pub(super) fn relative_to(&self, slot: usize, apex: DVec3) -> ([DVec3; 3], f64) {
        let relative = widened(&self.corners[slot]).map(|p| p - apex);
        (relative, ROUNDING * extent(&relative))
    }

    /// The triangle in leaf slot `slot` against the rays, unless it lies
    /// outside the cone, below the rays' floor or beyond `farthest`, which
    /// follows their deepest limit; true when every ray is done.
    #[inline(always)]
    fn test_triangle(
        &self,
        frame: &FrameCone,
        rays: &mut impl Rays,
        slot: usize,
        farthest: &mut f64,
    ) -> bool {
        let cone = &frame.cone;
        let (relative, slack) = self.relative_to(slot, cone.apex);
        if frame.misses(&relative, slack) {
            return false;
        }
        let nearest = cone.least_depth(&relative, slack);
        // The deepest limit is found again only when one fell.
        if nearest <= *farthest && rays.test(self, slot, &relative, nearest) {
            *farthest = rays.deepest();
        }
        *farthest < 0.0
    }

    /// Whether a triangle may meet `cone`: false only when none does, so
    /// that no ray inside it hits anything (a block of pixels that sees
    /// only background). The walk's own filters, stopped at the first
    /// triangle they keep.
    pub fn meets_cone(&self, cone: &Cone) -> bool {
        let mut found = false;
        self.walk_cone(
            cone,
            &mut Visitor::new(f64::INFINITY, |_, _| {
                found = true;
                false
            }),
        );
        found
    }

    /// The closest hit, t > 0, of each ray from the cone's apex along
    /// `directions` (each inside the cone), into `hits`: what
    /// [`Self::closest_hit`] gives each with t ∈ (0, ∞).
    pub fn closest_hits_in_cone(&self, cone: &Cone, directions: &[DVec3], packet: &mut PrimaryPacket) {
        packet.start(cone, directions);
        self.walk_cone(cone, packet);
    }

    /// Whether each segment from `origins[i]` to `target`, t ∈ (0, t_max)
    /// along target − origin, is blocked, into `blocked`: what
    /// [`Self::occluded`] gives each. `cone`: from `target` around the
    /// origins; `up`: the normal of the floor the walk puts below them (any
    /// direction gives the same answers; the surfaces' own cuts the most);
    /// each ray i passes over the triangle `passes[i]` (none past the
    /// slice's end, or `usize::MAX`), which the caller knows cannot block
    /// it.
    pub fn occluded_in_cone(
        &self,
        cone: &Cone,
        (origins, up, passes): (&[DVec3], DVec3, &[usize]),
        t_max: f64,
        packet: &mut ShadowPacket,
    ) {
        packet.start(cone, (origins, up, passes), t_max);
        // The triangle that blocked a ray of the previous packet first: it
        // often blocks these too, and a blocked ray is done (any hit will
        // do); unless it lies outside the cone, as the walk would find.
        if let Some(slot) = packet.last_blocker() {
            let (relative, slack) = self.relative_to(slot, cone.apex);
            if !cone.misses(&relative, slack) {
                packet.test(self, slot, &relative, f64::MIN);
                if packet.all_blocked() {
                    return;
                }
            }
        }
        self.walk_cone(cone, packet);
    }
}

/// No ray: each triangle the walk keeps (slot, corners relative to the
/// apex) goes to `visit`, which says whether the walk goes on.
pub struct Visitor<F> {
    /// The deepest depth visited while the walk goes on, then −1: it stops.
    deepest: f64,
    lines: Lines,
    /// What lies wholly below it is not visited ([`Rays::floor`]).
    floor: Option<(DVec3, f64)>,
    visit: F,
}

impl<F: FnMut(usize, &[DVec3; 3]) -> bool> Visitor<F> {
    /// A visitor of the triangles no deeper along the cone than `deepest`.
    pub fn new(deepest: f64, visit: F) -> Self {
        Self {
            deepest,
            lines: Lines::default(),
            floor: None,
            visit,
        }
    }

    /// The visitor with a floor (n, c): triangles and nodes wholly below
    /// n · (x − apex) = c are passed over.
    pub fn with_floor(self, floor: Option<(DVec3, f64)>) -> Self {
        Self { floor, ..self }
    }
}

impl<F: FnMut(usize, &[DVec3; 3]) -> bool> Rays for Visitor<F> {
    fn deepest(&self) -> f64 {
        self.deepest
    }

    fn floor(&self) -> Option<(DVec3, f64)> {
        self.floor
    }

    fn lines(&self) -> &Lines {
        &self.lines
    }

    /// Never called (a visitor has no rays): as `test`.
    fn test_ray(&mut self, bvh: &TriangleBvh, slot: usize, relative: &[DVec3; 3], _: usize) -> bool {
        self.test(bvh, slot, relative, 0.0)
    }

    fn test(&mut self, _: &TriangleBvh, slot: usize, relative: &[DVec3; 3], _: f64) -> bool {
        if (self.visit)(slot, relative) {
            return false;
        }
        self.deepest = -1.0;
        true
    }
}
