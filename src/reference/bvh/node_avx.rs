//! obvhs's single-ray test of a CWBVH node's eight children
//! (`CwBvhNode::intersect_ray`), in one AVX2 register instead of two SSE
//! ones: the quantized bounds widen to f32 with two instructions a bound
//! instead of four scalar conversions and inserts each, and only the
//! children hit are looked up. Every lane runs obvhs's operations in its
//! order, without fused multiply-adds, so the hit mask is the same bits
//! (`tests::the_same_mask_as_obvhs`): the walk stays as conservative as
//! obvhs's, which `super`'s padding makes exact.

use std::arch::x86_64::*;

use glam::Vec3A;
use obvhs::cwbvh::node::{CwBvhNode, extract_byte64};
use obvhs::ray::Ray;

/// obvhs's nearest node entry (its `node::EPSILON`, not public).
const NEAREST_ENTRY: f32 = 0.0001;

/// The children of `node` that `ray` enters, as obvhs's
/// `intersect_ray(ray, oct_inv4)` packs them (internal children in bits 24
/// to 31, leaves' triangles below).
#[target_feature(enable = "avx2")]
#[inline]
pub fn children_hit(node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32 {
    let scale = node.compute_extent() * ray.inv_direction;
    let offset = (Vec3A::from(node.p) - ray.origin) * ray.inv_direction;
    // Eight u8 bounds, widened exactly to f32.
    let widen = |q: &[u8; 8]| {
        // SAFETY: an unaligned load of the array's eight bytes.
        let bytes = unsafe { _mm_loadl_epi64(q.as_ptr().cast()) };
        _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(bytes))
    };
    // Entry and exit distances along one axis: the near and far bounds
    // swap where the ray runs backwards along it.
    let slab = |low: &[u8; 8], high: &[u8; 8], backwards: bool, scale: f32, offset: f32| {
        let (near, far) = if backwards { (high, low) } else { (low, high) };
        let at = |q| {
            _mm256_add_ps(
                _mm256_mul_ps(widen(q), _mm256_set1_ps(scale)),
                _mm256_set1_ps(offset),
            )
        };
        (at(near), at(far))
    };
    let d = ray.direction;
    let (near_x, far_x) = slab(&node.child_min_x, &node.child_max_x, d.x < 0.0, scale.x, offset.x);
    let (near_y, far_y) = slab(&node.child_min_y, &node.child_max_y, d.y < 0.0, scale.y, offset.y);
    let (near_z, far_z) = slab(&node.child_min_z, &node.child_max_z, d.z < 0.0, scale.z, offset.z);
    let near = _mm256_max_ps(near_x, _mm256_max_ps(near_y, near_z));
    let far = _mm256_min_ps(far_x, _mm256_min_ps(far_y, far_z));
    let near = _mm256_max_ps(near, _mm256_set1_ps(NEAREST_ENTRY));
    let far = _mm256_min_ps(far, _mm256_set1_ps(ray.tmax));
    let mut entered = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
    let (child_bits, bit_index) = node.get_child_and_index_bits(oct_inv4);
    let mut hits = 0;
    while entered != 0 {
        let child = entered.trailing_zeros() as usize;
        entered &= entered - 1;
        hits |= extract_byte64(child_bits, child) << extract_byte64(bit_index, child);
    }
    hits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::bvh::{BvhTriangle, TriangleBvh};
    use crate::reference::sampling::Rng;
    use glam::DVec3;

    /// The ray's octant as obvhs's walk passes it to the node test.
    fn octant(ray: &Ray) -> u32 {
        let mut traversal = obvhs::cwbvh::Traversal::default();
        traversal.reinit(ray.direction);
        traversal.oct_inv4
    }

    /// Every node of a BVH over random triangles, against random rays
    /// (from inside the scene and outside, some along an axis), gives
    /// obvhs's mask.
    #[test]
    fn the_same_mask_as_obvhs() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = Rng::new(7, 0, 0);
        let mut point = |scale: f64| {
            DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * scale * 2.0 - DVec3::splat(scale)
        };
        let triangles: Vec<BvhTriangle> = (0..3000)
            .map(|_| {
                let centre = point(1.0);
                BvhTriangle {
                    corners: [centre, centre + point(0.05), centre + point(0.05)].map(|p| p.as_vec3()),
                    occludes: true,
                }
            })
            .collect();
        let bvh = TriangleBvh::new(&triangles);
        let mut entered = 0;
        for k in 0..400 {
            let origin = point(if k % 2 == 0 { 1.0 } else { 3.0 });
            let mut direction = point(1.0);
            if k % 5 == 0 {
                direction = DVec3::new(direction.x, 0.0, 0.0);
            }
            let Some((ray, nodes)) = bvh.ray_and_nodes(origin, direction) else {
                continue;
            };
            let octant = octant(&ray);
            for node in nodes {
                let expected = node.intersect_ray(&ray, octant);
                // SAFETY: the CPU has AVX2 (checked above).
                let got = unsafe { children_hit(node, &ray, octant) };
                assert_eq!(got, expected, "ray {k}");
                entered += (expected != 0) as usize;
            }
        }
        assert!(entered > 1000, "too few nodes entered to tell: {entered}");
    }

    /// Random nodes against rays that enter a child's box about where
    /// obvhs's nearest entry lies (s = 10⁻⁴), some ending soon after,
    /// give obvhs's mask.
    #[test]
    fn the_same_mask_at_the_nearest_entry() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = Rng::new(13, 0, 0);
        let mut byte = || (rng.next_u64() % 256) as u8;
        let (mut entered, mut passed) = (0, 0);
        for k in 0..4000 {
            let mut node = CwBvhNode {
                p: glam::Vec3::new(0.25, -0.5, 0.125),
                // Quanta of 2⁻¹⁰ (exponent 117).
                e: [117; 3],
                imask: byte(),
                child_meta: std::array::from_fn(|_| byte()),
                ..Default::default()
            };
            for (low, high) in [
                (&mut node.child_min_x, &mut node.child_max_x),
                (&mut node.child_min_y, &mut node.child_max_y),
                (&mut node.child_min_z, &mut node.child_max_z),
            ] {
                for c in 0..8 {
                    let (a, b) = (byte(), byte());
                    (low[c], high[c]) = (a.min(b), a.max(b));
                }
            }
            // From just before (or after) child c's nearest corner, along
            // a direction with every component positive (or some negative).
            let c = k % 8;
            let corner = node.p
                + glam::Vec3::new(
                    node.child_min_x[c] as f32,
                    node.child_min_y[c] as f32,
                    node.child_min_z[c] as f32,
                ) / 1024.0;
            let direction = glam::Vec3A::new(
                0.2 + (byte() as f32) / 255.0,
                if k % 3 == 0 { -0.5 } else { 0.7 },
                0.3 + (byte() as f32) / 300.0,
            );
            let before = (byte() as f32 - 64.0) * 2e-6;
            let origin = glam::Vec3A::from(corner) - direction * before;
            // Some rays end near the box too.
            let far = if k % 4 == 0 { byte() as f32 * 1e-3 } else { 1e3 };
            let ray = Ray::new(origin, direction, 0.0, far);
            let octant = octant(&ray);
            let expected = node.intersect_ray(&ray, octant);
            // SAFETY: the CPU has AVX2 (checked above).
            let got = unsafe { children_hit(&node, &ray, octant) };
            assert_eq!(got, expected, "node {k}");
            entered += (expected != 0) as usize;
            passed += (expected == 0) as usize;
        }
        assert!(
            entered > 500 && passed > 500,
            "entered {entered}, passed {passed}: too one-sided to tell"
        );
    }
}
