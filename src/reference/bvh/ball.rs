//! A sphere light's shadow rays from one shading point: every segment from
//! the point to the ball lies in the cone the ball subtends. The occluders
//! that may meet that cone are gathered once, by the packets' cone walk, or
//! taken from those of a region of neighbouring points ([`BallRegion`]);
//! each ray is then tested against those few, and when there is none, no
//! ray needs a test.

use super::TriangleBvh;
use super::cone::{Cone, FrameCone, ROUNDING};
use super::packet::Visitor;
use super::widened;
use crate::reference::intersect::{ShearedRay, extent};
use glam::DVec3;

/// A region's cross-section at the point it was made for, as a share of
/// the ball's radius: its apex then lies three times the point's distance
/// from the ball's centre behind it (measured against 1/4 and 1/2: see
/// docs/journal/reference.md).
const REGION_SHARE: f64 = 0.75;
/// A region gathers no more occluders than this (a crowded one is left to
/// the points' own walks).
const REGION_LIMIT: usize = 32;

/// The occluders near every segment from a point of a region to the ball,
/// gathered once for the many shading points that lie in it (see
/// [`TriangleBvh::gather_near_ball_in`]). The region is a square pyramid
/// around the ball from an apex behind the point it was made for, above a
/// floor across that point's surface: for any point inside both, every
/// segment from it to the ball lies in their convex hull, so inside both
/// too, and the region's walk kept each occluder that may meet one.
#[derive(Debug, Default)]
pub struct BallRegion {
    /// The ball's centre and radius.
    ball: (DVec3, f64),
    /// None until the first region is made.
    cone: Option<Cone>,
    /// n · (x − apex) ≥ c for every point of the region.
    floor: (DVec3, f64),
    /// The greatest depth along the axis of a point of the ball.
    deepest: f64,
    /// Every occluder the region's walk kept, or None when it kept more
    /// than [`REGION_LIMIT`].
    slots: Option<Vec<u32>>,
    /// The block of pixels it was made for (see [`Self::make`]).
    block: Option<(u32, u32)>,
}

impl BallRegion {
    /// Whether `from` lies inside the region of this ball, by a margin for
    /// the rounding of the tests.
    fn holds(&self, from: DVec3, ball: (DVec3, f64)) -> bool {
        let Some(cone) = &self.cone else {
            return false;
        };
        let w = from - cone.apex;
        let tol = |n: DVec3| ROUNDING * n.abs().element_sum() * w.abs().max_element();
        let (n, c) = self.floor;
        self.ball == ball
            && cone.planes.iter().all(|&k| k.dot(w) > tol(k))
            && n.dot(w) > c + tol(n)
            && cone.axis.dot(w) < self.deepest
    }

    /// The block of pixels the region was made for, if any.
    pub fn block(&self) -> Option<(u32, u32)> {
        self.block
    }

    /// The region for a block of pixels, made for its `anchor` (the shadow
    /// origin and surface normal of one point of it: the same whichever of
    /// its points asks first, so each point's list, and the pixel, are the
    /// same in every render and in the probe). None where the anchor sees
    /// no region (background, the ball not above its surface): each point
    /// of the block then walks on its own.
    pub fn make(
        &mut self,
        bvh: &TriangleBvh,
        block: (u32, u32),
        anchor: Option<(DVec3, DVec3)>,
        (centre, radius): (DVec3, f64),
    ) {
        self.block = Some(block);
        self.cone = None;
        let Some((from, surface)) = anchor else {
            return;
        };
        if let Some((n, _)) = BallCone::new(from, centre, radius).and_then(|ball| ball.floor(surface)) {
            self.aim(bvh, from, n, (centre, radius));
        }
    }

    /// A new region for the points near `from`, whose surface's plane
    /// (normal `n`, towards the ball) is `from`'s own walk's floor, and
    /// its occluders gathered; none where the ball is not above the floor.
    fn aim(&mut self, bvh: &TriangleBvh, from: DVec3, n: DVec3, (centre, radius): (DVec3, f64)) {
        let to_centre = centre - from;
        let distance = to_centre.length();
        let axis = to_centre / distance;
        // At `from` the pyramid then reaches REGION_SHARE · radius or more
        // from its axis (its slope is above R / (d + back)).
        let back = distance * REGION_SHARE / (1.0 - REGION_SHARE);
        let apex = from - axis * back;
        let length = distance + back;
        let slope = radius / ((length - radius) * (length + radius)).sqrt() * (1.0 + 1e-9);
        // The floor a little below `from` (the shading points of one
        // surface are lifted off it by slightly different heights), and
        // the whole ball above it by a margin for the rounding.
        let w = from - apex;
        let level = n.dot(w) - 1e-10 * from.abs().max_element();
        let margin = radius * (1.0 + ROUNDING) + ROUNDING * (to_centre.abs().max_element() + length);
        if !(slope.is_finite() && n.dot(centre - apex) - level > margin) {
            return;
        }
        let cone = Cone::square(apex, axis, slope);
        self.ball = (centre, radius);
        self.cone = Some(cone);
        self.floor = (n, level);
        self.deepest = (length + radius) * (1.0 + ROUNDING);
        let mut slots = self.slots.take().unwrap_or_default();
        slots.clear();
        let mut fits = true;
        let keep = |slot: usize, _: &[DVec3; 3]| {
            if bvh.occludes[slot] {
                fits = slots.len() < REGION_LIMIT;
                if fits {
                    slots.push(slot as u32);
                }
            }
            fits
        };
        bvh.walk_cone(
            &cone,
            &mut Visitor::new(self.deepest, keep).with_floor(Some(self.floor)),
        );
        self.slots = fits.then_some(slots);
    }
}

impl TriangleBvh {
    /// The occluders that may block a segment from `from` to any point of
    /// the ball (`centre`, `radius`), e.g. every shadow ray of a sphere light
    /// from one shading point: into `out`, as indices for [`Self::blocked_by`].
    /// Conservative (see `BallCone`): an empty list means no segment is
    /// blocked. False, with `out` unfinished, when more than `limit` are
    /// found or `from` lies (nearly) in the ball: cast each ray through the
    /// BVH instead. `surface`: the normal (either way, or zero) of the
    /// surface `from` was lifted off, whose plane through `from` is the
    /// walk's floor when the whole ball lies above it (see
    /// `BallCone::floor`).
    pub fn gather_near_ball(
        &self,
        (from, surface): (DVec3, DVec3),
        centre: DVec3,
        radius: f64,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        // No region: the point's own walk.
        let region = BallRegion::default();
        self.gather_near_ball_in(&region, (from, surface), (centre, radius), limit, out)
    }

    /// A point's own walk through `ball`'s pyramid above `floor`, into
    /// `out` (cleared).
    fn walk_near_ball(
        &self,
        ball: &BallCone,
        floor: Option<(DVec3, f64)>,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        let mut fits = true;
        let keep = |slot: usize, relative: &[DVec3; 3]| {
            if !self.occludes[slot] || ball.apart_by_plane(relative) {
                return true;
            }
            fits = out.len() < limit;
            if fits {
                out.push(slot as u32);
            }
            fits
        };
        self.walk_cone(
            &ball.pyramid,
            &mut Visitor::new(ball.deepest, keep).with_floor(floor),
        );
        fits
    }

    /// [`Self::gather_near_ball`], from the occluders `region` holds where
    /// `from` lies in it: the region's occluders that `from`'s own walk
    /// would keep. So the list holds every occluder that may block one of
    /// `from`'s segments, and no more than its own walk gives (fewer where
    /// that walk's square pyramid reaches past the region).
    pub fn gather_near_ball_in(
        &self,
        region: &BallRegion,
        (from, surface): (DVec3, DVec3),
        (centre, radius): (DVec3, f64),
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        let Some(ball) = BallCone::new(from, centre, radius) else {
            return false;
        };
        let floor = ball.floor(surface);
        // A region's list serves only a point with a floor inside it.
        let Some(slots) = region
            .slots
            .as_ref()
            .filter(|_| floor.is_some() && region.holds(from, (centre, radius)))
        else {
            return self.walk_near_ball(&ball, floor, limit, out);
        };
        let frame = FrameCone::new(ball.pyramid, self, floor);
        for &slot in slots {
            let slot = slot as usize;
            let (relative, slack) = self.relative_to(slot, from);
            if frame.misses(&relative, slack)
                || ball.pyramid.least_depth(&relative, slack) > ball.deepest
                || ball.apart_by_plane(&relative)
            {
                continue;
            }
            if out.len() == limit {
                return false;
            }
            out.push(slot as u32);
        }
        true
    }

    /// Whether one of the gathered occluders (see [`Self::gather_near_ball`])
    /// lies at t ∈ (0, t_max) along the ray.
    pub fn blocked_by(&self, candidates: &[u32], origin: DVec3, direction: DVec3, t_max: f64) -> bool {
        let sheared = ShearedRay::new(origin, direction);
        candidates
            .iter()
            .any(|&slot| sheared.hits(&widened(&self.corners[slot as usize]), 0.0, t_max))
    }
}

/// Every segment from a point to a ball: they lie in a square pyramid from
/// the point around the ball, no deeper along its axis than the ball's far
/// side. The cone walk keeps the occluders that meet the pyramid within
/// that depth; of those, a triangle is left out when the point and the
/// whole ball lie on one side of its plane (the surface the point was
/// lifted off, a wall facing away).
struct BallCone {
    /// The ball's centre and radius, relative to the point.
    centre: DVec3,
    radius: f64,
    pyramid: Cone,
    /// The greatest depth along the axis of a point of the ball.
    deepest: f64,
}

impl BallCone {
    /// None when `from` is (nearly) inside the ball.
    fn new(from: DVec3, centre: DVec3, radius: f64) -> Option<Self> {
        let to_centre = centre - from;
        let distance = to_centre.length();
        // False for NaN too.
        let outside = distance > radius * (1.0 + ROUNDING);
        if !outside {
            return None;
        }
        // Every segment lies in the ball's tangent cone (sin α = R / d):
        // inside the square pyramid whose sides have slope tan α, a little
        // steeper.
        let slope = radius / ((distance - radius) * (distance + radius)).sqrt() * (1.0 + 1e-9);
        Some(Self {
            centre: to_centre,
            radius,
            pyramid: Cone::square(from, to_centre / distance, slope),
            deepest: (distance + radius) * (1.0 + ROUNDING),
        })
    }

    /// The plane through the point (0) across `surface` as a floor (n, 0),
    /// n towards the ball, when the whole ball lies above it (by a margin
    /// for the rounding of its height): every segment from the point to
    /// the ball then stays on or above the plane, and a triangle wholly
    /// below it blocks none (the walk allows for the rounding of its own
    /// tests). None for a zero or non-finite normal.
    fn floor(&self, surface: DVec3) -> Option<(DVec3, f64)> {
        let n = surface.try_normalize()?;
        let n = if n.dot(self.centre) < 0.0 { -n } else { n };
        let margin = self.radius * (1.0 + ROUNDING) + ROUNDING * self.centre.abs().max_element();
        (n.dot(self.centre) > margin).then_some((n, 0.0))
    }

    /// Whether the point (0) and the whole ball lie strictly on one side
    /// of the triangle's plane (corners `relative` to the point).
    fn apart_by_plane(&self, relative: &[DVec3; 3]) -> bool {
        let [a, b, c] = *relative;
        let size = extent(relative);
        let m = (b - a).cross(c - a);
        let length = m.length();
        // Both products are rounded to ~10⁻¹⁶ of |m| times the lengths involved.
        let tol = ROUNDING * length * (size + self.centre.abs().max_element());
        let origin_side = -m.dot(a);
        let centre_side = m.dot(self.centre - a);
        let clearance = self.radius * length * (1.0 + ROUNDING) + tol;
        (origin_side > tol && centre_side > clearance) || (origin_side < -tol && centre_side < -clearance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bvh::{BvhTriangle, occluded_brute_force};
    use crate::reference::sampling::Rng;
    use glam::Vec3;

    /// A point of the ball: inside, on its surface, or (one time in three)
    /// on the circle where segments from `from` graze it, the cone's edge.
    fn in_ball(rng: &mut Rng, from: DVec3, centre: DVec3, radius: f64) -> DVec3 {
        if rng.next_f64() < 1.0 / 3.0 {
            let w = centre - from;
            let (d, axis) = (w.length(), w.normalize());
            let (u, v) = axis.any_orthonormal_pair();
            let (s, c) = (std::f64::consts::TAU * rng.next_f64()).sin_cos();
            let rim = radius * (1.0 - (radius / d).powi(2)).max(0.0).sqrt() * (1.0 - 1e-9);
            return centre - axis * (radius * radius / d) + (u * c + v * s) * rim;
        }
        loop {
            let p = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0 - 1.0;
            if p.length_squared() <= 1.0 && p.length_squared() > 1e-6 {
                let p = if rng.next_f64() < 0.5 { p.normalize() } else { p };
                return centre + p * radius;
            }
        }
    }

    /// A ground of two triangles (the first two), six spheres of 0.3 m
    /// over it, and 60 small triangles in the air: occluders at the cones'
    /// edges.
    fn scene(rng: &mut Rng) -> Vec<BvhTriangle> {
        let ground = [[-4.0, 4.0], [4.0, 4.0], [4.0, -4.0], [-4.0, -4.0]].map(|[x, z]| Vec3::new(x, 0.0, z));
        let mut tris = vec![
            BvhTriangle {
                corners: [ground[0], ground[1], ground[2]],
                occludes: true,
            },
            BvhTriangle {
                corners: [ground[0], ground[2], ground[3]],
                occludes: true,
            },
        ];
        for _ in 0..6 {
            let centre = DVec3::new(
                4.0 * rng.next_f64() - 2.0,
                0.3 + rng.next_f64(),
                4.0 * rng.next_f64() - 2.0,
            );
            let sphere = crate::scene::shapes::sphere(centre.as_vec3(), 0.3, 16, 8);
            tris.extend((0..sphere.triangle_count()).map(|t| BvhTriangle {
                corners: sphere.triangle(t),
                occludes: true,
            }));
        }
        for _ in 0..60 {
            let a = DVec3::new(
                6.0 * rng.next_f64() - 3.0,
                0.5 + 2.0 * rng.next_f64(),
                6.0 * rng.next_f64() - 3.0,
            );
            let [b, c] =
                [0, 1].map(|_| a + (DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5) * 0.4);
            tris.push(BvhTriangle {
                corners: [a, b, c].map(|p| p.as_vec3()),
                occludes: true,
            });
        }
        tris
    }

    /// A point of triangle `tri` at barycentric-ish (s, t), lifted off its
    /// front side as the reference lifts shadow origins, and its normal.
    fn lifted(tri: &BvhTriangle, (s, t): (f64, f64)) -> (DVec3, DVec3) {
        let [a, b, c] = tri.corners_f64();
        let p = a.lerp(b, s).lerp(c, t);
        let n = (b - a).cross(c - a).normalize();
        (p + n * 1e-9 * p.abs().max_element().max(1.0), n)
    }

    /// Segments from `from` to `rays` points of the ball (inside, on it,
    /// on its rim): those the `gathered` occluders block are those brute
    /// force finds blocked, `case` naming the failure; how many are.
    fn blocks_as_brute_force(
        (bvh, tris): (&TriangleBvh, &[BvhTriangle]),
        gathered: &[u32],
        from: DVec3,
        (centre, radius): (DVec3, f64),
        rays: usize,
        rng: &mut Rng,
        case: &dyn std::fmt::Debug,
    ) -> usize {
        let mut blocked = 0;
        for _ in 0..rays {
            let d = in_ball(rng, from, centre, radius) - from;
            let expected = occluded_brute_force(tris, from, d, 0.0, 1.0 - 1e-9);
            assert_eq!(
                bvh.blocked_by(gathered, from, d, 1.0 - 1e-9),
                expected,
                "{case:?}"
            );
            blocked += usize::from(expected);
        }
        blocked
    }

    /// The gathered occluders block exactly the segments that brute force
    /// finds blocked (none is left out that blocks one), to points of the
    /// ball, its surface and its rim; from points lifted off the ground and
    /// off spheres, under balls that straddle occluders, their planes and
    /// their horizons. An empty list then means that no segment is blocked.
    #[test]
    fn gathered_occluders_block_what_brute_force_blocks() {
        let rng = &mut Rng::new(5, 0, 0);
        let tris = scene(rng);
        let bvh = TriangleBvh::new(&tris);
        let mut candidates = Vec::new();
        let (mut clear, mut blocked) = (0, 0);
        for case in 0..1000 {
            // Off the ground or off a sphere's triangle, on its front side.
            let index = if case % 2 == 0 {
                (case / 2) % 2
            } else {
                2 + case % (tris.len() - 62)
            };
            let (from, n) = lifted(&tris[index], (rng.next_f64(), rng.next_f64()));
            let centre = from
                + DVec3::new(
                    4.0 * rng.next_f64() - 2.0,
                    3.0 * rng.next_f64(),
                    4.0 * rng.next_f64() - 2.0,
                );
            let radius = 0.05 + 0.8 * rng.next_f64();
            // The surface's normal, or none (the walk without a floor).
            let surface = if case % 3 == 0 { DVec3::ZERO } else { n };
            if !bvh.gather_near_ball((from, surface), centre, radius, usize::MAX, &mut candidates) {
                // Only from inside the ball: each ray then goes through the BVH.
                assert!((centre - from).length() <= radius * (1.0 + 1e-9), "case {case}");
                continue;
            }
            let ball = (centre, radius);
            let blocks = blocks_as_brute_force((&bvh, &tris), &candidates, from, ball, 300, rng, &case);
            clear += usize::from(candidates.is_empty());
            blocked += usize::from(blocks > 0);
        }
        assert!(clear > 100 && blocked > 100, "{clear} clear, {blocked} blocked");
    }

    /// Rows of neighbouring shading points on a ground and on a sphere,
    /// each row under one ball with its region made for its first point:
    /// the occluders the region gives a point block exactly what brute force
    /// blocks, and each is one the point's own walk keeps; a quarter of the
    /// points at least lie in their region (rows on the ground leave it,
    /// regions among the small occluders fill up).
    #[test]
    fn a_region_gives_each_point_what_blocks_its_segments() {
        let rng = &mut Rng::new(9, 0, 0);
        let tris = scene(rng);
        let bvh = TriangleBvh::new(&tris);
        let mut region = BallRegion::default();
        let (mut own, mut shared) = (Vec::new(), Vec::new());
        let (mut points, mut held, mut blocked) = (0, 0, 0);
        for run in 0..60 {
            let index = if run % 3 == 0 {
                run % 2
            } else {
                2 + rng.next_u64() as usize % (tris.len() - 62)
            };
            let radius = 0.05 + 0.6 * rng.next_f64();
            let (start, t) = (rng.next_f64() * 0.5, rng.next_f64() * 0.5);
            let anchor = lifted(&tris[index], (start, t));
            let centre = anchor.0 + DVec3::new(3.0 * rng.next_f64() - 1.5, 1.0 + 2.0 * rng.next_f64(), 1.0);
            region.make(&bvh, (run as u32, 0), Some(anchor), (centre, radius));
            assert_eq!(region.block(), Some((run as u32, 0)));
            for step in 0..40 {
                let (from, n) = lifted(&tris[index], (start + step as f64 * 0.004, t));
                if !bvh.gather_near_ball_in(&region, (from, n), (centre, radius), usize::MAX, &mut shared) {
                    continue;
                }
                points += 1;
                held += usize::from(region.slots.is_some() && region.holds(from, (centre, radius)));
                assert!(bvh.gather_near_ball((from, n), centre, radius, usize::MAX, &mut own));
                for slot in &shared {
                    assert!(
                        own.contains(slot),
                        "run {run}, step {step}: {slot} not in the point's own list"
                    );
                }
                let ball = (centre, radius);
                blocked += blocks_as_brute_force((&bvh, &tris), &shared, from, ball, 60, rng, &(run, step));
            }
        }
        assert!(
            points > 2000 && blocked > 2000,
            "{points} points, {blocked} blocked"
        );
        assert!(held * 4 > points, "{held} of {points} points in their region");
    }
}
