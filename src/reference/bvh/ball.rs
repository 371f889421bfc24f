//! A sphere light's shadow rays from one shading point: every segment from
//! the point to the ball lies in the capsule of its radius around the
//! segment to its centre, and in the cone the ball subtends. The occluders
//! near that capsule are gathered once; each ray is then tested against
//! those few, and when none of them can meet the cone, no ray needs a test.

use super::packet::{Cone, ROUNDING};
use super::{PAD, TRAVERSAL, TriangleBvh};
use crate::reference::intersect::ShearedRay;
// `UVec2` is named inside obvhs's `traverse!` macro.
use glam::{DVec3, UVec2};
use obvhs::cwbvh::node::CwBvhNode;

impl TriangleBvh {
    /// The occluders that may block a segment from `from` to any point of
    /// the ball (`centre`, `radius`), e.g. every shadow ray of a sphere light
    /// from one shading point: into `out`, as indices for [`Self::blocked_by`].
    /// Such segments lie in the capsule of that radius around the segment
    /// from `from` to `centre`; a BVH node is kept when its bounding sphere
    /// (padded) reaches the capsule. False, with `out` unfinished, when more
    /// than `limit` are found: cast each ray through the BVH instead.
    pub fn gather_near_ball(
        &self,
        from: DVec3,
        centre: DVec3,
        radius: f64,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        let Some(bvh) = self.bvh.as_ref() else {
            return true;
        };
        let to_frame = |p: DVec3| (p - self.centre) * self.per_scale;
        let (a, b) = (to_frame(from), to_frame(centre));
        let reach = radius * self.per_scale + 4.0 * PAD;
        let mut fits = true;
        TRAVERSAL.with_borrow_mut(|state| {
            state.reinit((b - a).as_vec3a());
            let mut node;
            obvhs::traverse!(
                bvh,
                node,
                state,
                near_capsule(node, a, b, reach, state.oct_inv4),
                {
                    let slot = state.primitive_id;
                    if self.occludes[slot as usize] {
                        if out.len() == limit {
                            fits = false;
                            break;
                        }
                        out.push(slot);
                    }
                }
            );
        });
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

    /// Whether none of the gathered occluders (see [`Self::gather_near_ball`])
    /// can meet a segment from `from` to a point of the ball (`centre`,
    /// `radius`): then every shadow ray of a sphere light from that origin
    /// is unblocked, and V = 1 over the whole cone. Conservative: false
    /// whenever one might. An occluder is ruled out when it lies outside a
    /// pyramid from `from` around the ball, or wholly beyond the ball, or
    /// when `from` and the whole ball lie on one side of its plane (the
    /// surface the origin was lifted off, a wall facing away).
    pub fn clear_towards_ball(&self, candidates: &[u32], from: DVec3, centre: DVec3, radius: f64) -> bool {
        let to_centre = centre - from;
        let distance = to_centre.length();
        if !(distance > radius * (1.0 + ROUNDING)) {
            return false;
        }
        // The ball's tangent cone meets the plane through its centre across
        // the axis in a circle of radius d tan α; the square around it, a
        // little wider, spans a pyramid that holds the cone.
        let axis = to_centre / distance;
        let half = distance * radius / ((distance - radius) * (distance + radius)).sqrt() * (1.0 + 1e-9);
        let (u, v) = axis.any_orthonormal_pair();
        let corners = [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .map(|(a, b)| centre + (u * a + v * b) * half);
        let Some(cone) = Cone::around(from, corners.into_iter()) else {
            return false;
        };
        let deepest = (to_centre.dot(cone.axis()) + radius) * (1.0 + ROUNDING) + ROUNDING * distance;
        candidates.iter().all(|&slot| {
            let relative = self.corners[slot as usize].map(|p| p - from);
            let size = relative.iter().fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
            let slack = ROUNDING * size;
            let nearest = relative
                .iter()
                .fold(f64::INFINITY, |m, p| m.min(p.dot(cone.axis())));
            cone.misses(&relative, slack)
                || nearest - slack > deepest
                || apart_by_plane(&relative, to_centre, radius, size)
        })
    }
}

/// The hit mask (obvhs's layout) of the children of `node` whose boxes'
/// bounding spheres come within `reach` of the segment a–b (frame units).
#[inline(always)]
fn near_capsule(node: &CwBvhNode, a: DVec3, b: DVec3, reach: f64, oct_inv4: u32) -> u32 {
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
    let ab = b - a;
    let length2 = ab.length_squared();
    let mut hit_mask = 0;
    for child in 0..8 {
        let child_box = node.child_aabb(child);
        let (lo, hi) = (child_box.min.as_dvec3(), child_box.max.as_dvec3());
        let c = 0.5 * (lo + hi);
        let r = 0.5 * (hi - lo).length();
        // The point of a–b nearest to the box's centre.
        let s = if length2 > 0.0 {
            ((c - a).dot(ab) / length2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let gap = (a + ab * s - c).length();
        if gap <= r + reach {
            hit_mask |= obvhs::cwbvh::node::extract_byte64(child_bits8, child)
                << obvhs::cwbvh::node::extract_byte64(bit_index8, child);
        }
    }
    hit_mask
}

/// Whether the origin (0) and the whole ball (`centre`, `radius`, relative
/// to the origin) lie strictly on one side of the triangle's plane.
fn apart_by_plane(relative: &[DVec3; 3], centre: DVec3, radius: f64, size: f64) -> bool {
    let [a, b, c] = *relative;
    let m = (b - a).cross(c - a);
    let length = m.length();
    // Both products are rounded to ~10⁻¹⁶ of |m| times the lengths involved.
    let tol = ROUNDING * length * (size + centre.abs().max_element());
    let origin_side = -m.dot(a);
    let centre_side = m.dot(centre - a);
    let clearance = radius * length * (1.0 + ROUNDING) + tol;
    (origin_side > tol && centre_side > clearance) || (origin_side < -tol && centre_side < -clearance)
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

    /// Whenever `clear_towards_ball` says no segment to the ball can be
    /// blocked, none of many segments to its points and its surface is, by
    /// brute force; from points lifted off the ground and off spheres, under
    /// balls that straddle occluders, their planes and their horizons.
    #[test]
    fn a_clear_ball_has_no_blocked_segment() {
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
            let [a, b, c] = tris[if case % 2 == 0 {
                case % 2
            } else {
                2 + case % (tris.len() - 62)
            }]
            .corners;
            let p = a.lerp(b, rng.next_f64()).lerp(c, rng.next_f64());
            let n = (b - a).cross(c - a).normalize();
            let from = p + n * 1e-9 * p.abs().max_element().max(1.0);
            let centre = p + DVec3::new(
                4.0 * rng.next_f64() - 2.0,
                3.0 * rng.next_f64(),
                4.0 * rng.next_f64() - 2.0,
            );
            let radius = 0.05 + 0.8 * rng.next_f64();
            assert!(bvh.gather_near_ball(from, centre, radius, usize::MAX, &mut candidates));
            let says_clear = bvh.clear_towards_ball(&candidates, from, centre, radius);
            let any_blocked = (0..300).any(|_| {
                let target = in_ball(rng, from, centre, radius);
                occluded_brute_force(&tris, from, target - from, 0.0, 1.0 - 1e-9)
            });
            assert!(!(says_clear && any_blocked), "case {case}: a segment is blocked");
            clear += usize::from(says_clear);
            blocked += usize::from(any_blocked);
        }
        assert!(clear > 100 && blocked > 100, "{clear} clear, {blocked} blocked");
    }
}
