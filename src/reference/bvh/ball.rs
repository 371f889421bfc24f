//! A sphere light's shadow rays from one shading point: every segment from
//! the point to the ball lies in the cone the ball subtends. The occluders
//! that may meet that cone are gathered once, by the packets' cone walk;
//! each ray is then tested against those few, and when there is none, no
//! ray needs a test.

use super::TriangleBvh;
use super::cone::{Cone, ROUNDING};
use super::packet::Visitor;
use crate::reference::intersect::{ShearedRay, extent};
use glam::DVec3;

impl TriangleBvh {
    /// The occluders that may block a segment from `from` to any point of
    /// the ball (`centre`, `radius`), e.g. every shadow ray of a sphere light
    /// from one shading point: into `out`, as indices for [`Self::blocked_by`].
    /// Conservative (see [`BallCone`]): an empty list means no segment is
    /// blocked. False, with `out` unfinished, when more than `limit` are
    /// found or `from` lies (nearly) in the ball: cast each ray through the
    /// BVH instead. `surface`: the normal (either way, or zero) of the
    /// surface `from` was lifted off, whose plane through `from` is the
    /// walk's floor when the whole ball lies above it (see
    /// [`BallCone::floor`]).
    pub fn gather_near_ball(
        &self,
        (from, surface): (DVec3, DVec3),
        centre: DVec3,
        radius: f64,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        let Some(ball) = BallCone::new(from, centre, radius) else {
            return false;
        };
        let floor = ball.floor(surface);
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

    /// Whether one of the gathered occluders (see [`Self::gather_near_ball`])
    /// lies at t ∈ (0, t_max) along the ray.
    pub fn blocked_by(&self, candidates: &[u32], origin: DVec3, direction: DVec3, t_max: f64) -> bool {
        let sheared = ShearedRay::new(origin, direction);
        candidates
            .iter()
            .any(|&slot| sheared.hits(&self.corners[slot as usize], 0.0, t_max))
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

    /// The gathered occluders block exactly the segments that brute force
    /// finds blocked (none is left out that blocks one), to points of the
    /// ball, its surface and its rim; from points lifted off the ground and
    /// off spheres, under balls that straddle occluders, their planes and
    /// their horizons. An empty list then means that no segment is blocked.
    #[test]
    fn gathered_occluders_block_what_brute_force_blocks() {
        let rng = &mut Rng::new(5, 0, 0);
        let ground = [[-4.0, 4.0], [4.0, 4.0], [4.0, -4.0], [-4.0, -4.0]].map(|[x, z]| DVec3::new(x, 0.0, z));
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
                corners: sphere.triangle(t).map(|p| p.as_dvec3()),
                occludes: true,
            }));
        }
        // Small triangles in the air: occluders at the cones' edges.
        for _ in 0..60 {
            let a = DVec3::new(
                6.0 * rng.next_f64() - 3.0,
                0.5 + 2.0 * rng.next_f64(),
                6.0 * rng.next_f64() - 3.0,
            );
            let [b, c] =
                [0, 1].map(|_| a + (DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5) * 0.4);
            tris.push(BvhTriangle {
                corners: [a, b, c],
                occludes: true,
            });
        }
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
            let [a, b, c] = tris[index].corners;
            let p = a.lerp(b, rng.next_f64()).lerp(c, rng.next_f64());
            let n = (b - a).cross(c - a).normalize();
            let from = p + n * 1e-9 * p.abs().max_element().max(1.0);
            let centre = p + DVec3::new(
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
            let says_clear = candidates.is_empty();
            let mut any_blocked = false;
            for _ in 0..300 {
                let d = in_ball(rng, from, centre, radius) - from;
                let expected = occluded_brute_force(&tris, from, d, 0.0, 1.0 - 1e-9);
                assert_eq!(
                    bvh.blocked_by(&candidates, from, d, 1.0 - 1e-9),
                    expected,
                    "case {case}"
                );
                any_blocked |= expected;
            }
            clear += usize::from(says_clear);
            blocked += usize::from(any_blocked);
        }
        assert!(clear > 100 && blocked > 100, "{clear} clear, {blocked} blocked");
    }
}
