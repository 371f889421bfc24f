//! Ray casting against every triangle of the scene: a compressed wide BVH from
//! `obvhs`, traversed in f32, with each candidate triangle tested in f64.
//!
//! f32 traversal must never skip a node whose triangle the f64 ray hits. Three
//! measures make it conservative:
//! - the BVH lives in a normalized frame, (p − centre) / scale with scale the
//!   scene's largest extent, so every f32 coordinate is of order 1;
//! - each triangle's box is padded by [`PAD`] (10⁻⁵ of the scene's extent),
//!   about 100 times the worst rounding of an f32 ray (origin, direction,
//!   slab distances: a few units of 6·10⁻⁸ in this frame);
//! - a ray first clipped in f64 to the padded scene box starts its f32 copy
//!   just before the box, so a camera kilometres away loses no precision,
//!   and the f32 far limit is the f64 one plus a few pads.
//!
//! The f64 test decides every hit, so the BVH answers exactly what testing
//! every triangle would (see `closest_hit_brute_force` and the tests).

use super::intersect::{ShearedRay, TriangleHit};
use glam::DVec3;
use obvhs::ray::{Ray, RayHit};
use obvhs::{Boundable, BvhBuildParams, aabb::Aabb, cwbvh::CwBvh};

/// Padding of every triangle's box in the normalized frame (scene extent = 1).
pub const PAD: f64 = 1e-5;
/// obvhs's CWBVH node test only counts a node entered at f32 t ≥ 10⁻⁴: the f32
/// ray begins this far (in the frame) before the segment it stands for, so
/// every node along the segment is entered well after that clamp.
const EARLY_START: f64 = 2e-4 + 2.0 * PAD;

/// A triangle to cast rays against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhTriangle {
    pub corners: [DVec3; 3],
    /// Blocks shadow rays (the object casts shadows).
    pub occludes: bool,
}

/// The closest hit of a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Index of the triangle in the list given to [`TriangleBvh::new`].
    pub triangle: usize,
    /// Distance along the ray (its direction's units) and barycentrics.
    pub at: TriangleHit,
}

/// The padded box of one triangle in the normalized frame.
struct PaddedBox(Aabb);

impl Boundable for PaddedBox {
    fn aabb(&self) -> Aabb {
        self.0
    }
}

pub struct TriangleBvh {
    /// None when there is nothing to hit.
    bvh: Option<CwBvh>,
    /// Corners, in the BVH's leaf order so that a leaf slot indexes them directly.
    corners: Vec<[DVec3; 3]>,
    occludes: Vec<bool>,
    /// Leaf slot → index in the caller's list.
    original: Vec<usize>,
    centre: DVec3,
    /// World metres per unit of the normalized frame.
    scale: f64,
    /// The padded scene box (world, f64).
    min: DVec3,
    max: DVec3,
}

impl TriangleBvh {
    /// Builds the BVH. Triangles with a non-finite corner or zero area can
    /// never be hit and are left out.
    pub fn new(triangles: &[BvhTriangle]) -> Self {
        let usable: Vec<usize> = (0..triangles.len())
            .filter(|&i| {
                let [a, b, c] = triangles[i].corners;
                a.is_finite() && b.is_finite() && c.is_finite() && (b - a).cross(c - a).length_squared() > 0.0
            })
            .collect();
        let (mut min, mut max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &i in &usable {
            for p in triangles[i].corners {
                min = min.min(p);
                max = max.max(p);
            }
        }
        if usable.is_empty() {
            return Self {
                bvh: None,
                corners: Vec::new(),
                occludes: Vec::new(),
                original: Vec::new(),
                centre: DVec3::ZERO,
                scale: 1.0,
                min: DVec3::ZERO,
                max: DVec3::ZERO,
            };
        }
        let centre = 0.5 * (min + max);
        let scale = (max - min).max_element().max(f64::MIN_POSITIVE);
        let to_frame = |p: DVec3| (p - centre) / scale;
        let boxes: Vec<PaddedBox> = usable
            .iter()
            .map(|&i| {
                let [a, b, c] = triangles[i].corners.map(to_frame);
                let lo = a.min(b).min(c) - DVec3::splat(PAD);
                let hi = a.max(b).max(c) + DVec3::splat(PAD);
                PaddedBox(Aabb::new(lo.as_vec3a(), hi.as_vec3a()))
            })
            .collect();
        let bvh = obvhs::cwbvh::builder::build_cwbvh(
            &boxes,
            BvhBuildParams::medium_build(),
            &mut std::time::Duration::default(),
        );
        let original: Vec<usize> = bvh
            .primitive_indices
            .iter()
            .map(|&slot| usable[slot as usize])
            .collect();
        let pad_world = DVec3::splat(PAD * scale);
        Self {
            corners: original.iter().map(|&i| triangles[i].corners).collect(),
            occludes: original.iter().map(|&i| triangles[i].occludes).collect(),
            original,
            bvh: Some(bvh),
            centre,
            scale,
            min: min - pad_world,
            max: max + pad_world,
        }
    }

    /// Triangles that can be hit.
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    pub fn is_empty(&self) -> bool {
        self.corners.is_empty()
    }

    /// The part (t_start, t_end) of the ray inside the padded scene box
    /// within (t_min, t_max), by the slab test in f64; None when it misses.
    fn clip(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (t_min, t_max);
        for axis in 0..3 {
            let (o, d) = (origin[axis], direction[axis]);
            let (lo, hi) = (self.min[axis], self.max[axis]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// Where the f32 ray begins: [`EARLY_START`] before the clipped start, so
    /// that obvhs's node entry clamp and the box's faces skip nothing (the f64
    /// test still keeps only t > t_min).
    fn early_start(&self, t_start: f64, direction: DVec3) -> f64 {
        t_start - EARLY_START * self.scale / direction.length()
    }

    /// The f32 copy of the ray segment starting at `t_start`, in the
    /// normalized frame, reaching a few pads beyond `t_end`.
    fn frame_ray(&self, origin: DVec3, direction: DVec3, t_start: f64, t_end: f64) -> Ray {
        let start = (origin + direction * t_start - self.centre) / self.scale;
        let length = direction.length();
        let far = if t_end.is_finite() {
            ((t_end - t_start) * length / self.scale + 4.0 * PAD) as f32
        } else {
            f32::INFINITY
        };
        Ray::new(start.as_vec3a(), (direction / length).as_vec3a(), 0.0, far)
    }

    /// The f32 distance in the frame that keeps every node up to the f64
    /// distance `t` (plus a few pads) in the traversal.
    fn frame_distance(&self, t: f64, t_start: f64, length: f64) -> f32 {
        ((t - t_start) * length / self.scale + 4.0 * PAD) as f32
    }

    /// The closest hit with t ∈ (t_min, t_max) (units of `direction`).
    pub fn closest_hit(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let bvh = self.bvh.as_ref()?;
        let (t_start, t_end) = self.clip(origin, direction, t_min, t_max)?;
        let t_start = self.early_start(t_start, direction);
        let ray = self.frame_ray(origin, direction, t_start, t_end);
        let sheared = ShearedRay::new(origin, direction);
        let length = direction.length();
        let mut best: Option<(usize, TriangleHit)> = None;
        let mut best_t = t_max;
        let mut record = RayHit::none();
        bvh.ray_traverse(ray, &mut record, |_, slot| {
            match sheared.intersect(&self.corners[slot], t_min, best_t) {
                Some(hit) => {
                    best_t = hit.t;
                    best = Some((slot, hit));
                    self.frame_distance(hit.t, t_start, length)
                }
                None => f32::INFINITY,
            }
        });
        best.map(|(slot, at)| Hit {
            triangle: self.original[slot],
            at,
        })
    }

    /// Whether an occluding triangle lies at t ∈ (t_min, t_max) along the ray.
    pub fn occluded(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        let nonempty = t_max > t_min;
        if !nonempty {
            return false;
        }
        let Some((t_start, t_end)) = self.clip(origin, direction, t_min, t_max) else {
            return false;
        };
        let t_start = self.early_start(t_start, direction);
        let ray = self.frame_ray(origin, direction, t_start, t_end);
        let sheared = ShearedRay::new(origin, direction);
        !bvh.ray_traverse_miss(ray, |_, slot| {
            let blocks =
                self.occludes[slot] && sheared.intersect(&self.corners[slot], t_min, t_max).is_some();
            if blocks { 0.0 } else { f32::INFINITY }
        })
    }
}

/// The closest hit by testing every triangle: what the BVH must reproduce.
pub fn closest_hit_brute_force(
    triangles: &[BvhTriangle],
    origin: DVec3,
    direction: DVec3,
    t_min: f64,
    t_max: f64,
) -> Option<Hit> {
    let sheared = ShearedRay::new(origin, direction);
    let mut best: Option<Hit> = None;
    for (i, tri) in triangles.iter().enumerate() {
        let limit = best.map_or(t_max, |b| b.at.t);
        if let Some(at) = sheared.intersect(&tri.corners, t_min, limit) {
            best = Some(Hit { triangle: i, at });
        }
    }
    best
}

/// Whether any occluding triangle blocks the segment, by testing every one.
pub fn occluded_brute_force(
    triangles: &[BvhTriangle],
    origin: DVec3,
    direction: DVec3,
    t_min: f64,
    t_max: f64,
) -> bool {
    let sheared = ShearedRay::new(origin, direction);
    triangles
        .iter()
        .any(|tri| tri.occludes && sheared.intersect(&tri.corners, t_min, t_max).is_some())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(y: f64, half: f64, occludes: bool) -> [BvhTriangle; 2] {
        let c = [
            DVec3::new(-half, y, half),
            DVec3::new(half, y, half),
            DVec3::new(half, y, -half),
            DVec3::new(-half, y, -half),
        ];
        [
            BvhTriangle {
                corners: [c[0], c[1], c[2]],
                occludes,
            },
            BvhTriangle {
                corners: [c[0], c[2], c[3]],
                occludes,
            },
        ]
    }

    #[test]
    fn closest_of_two_planes_is_found() {
        let mut tris = quad(0.0, 5.0, true).to_vec();
        tris.extend(quad(1.0, 0.5, true));
        let bvh = TriangleBvh::new(&tris);
        let down = DVec3::NEG_Y;
        let hit = bvh
            .closest_hit(DVec3::new(0.1, 3.0, 0.2), down, 0.0, f64::INFINITY)
            .unwrap();
        assert_eq!(hit.at.t, 2.0);
        assert!(hit.triangle >= 2);
        let hit = bvh
            .closest_hit(DVec3::new(2.0, 3.0, 0.2), down, 0.0, f64::INFINITY)
            .unwrap();
        assert_eq!(hit.at.t, 3.0);
        assert!(
            bvh.closest_hit(DVec3::new(9.0, 3.0, 0.0), down, 0.0, f64::INFINITY)
                .is_none()
        );
    }

    #[test]
    fn only_occluders_block_and_only_inside_the_segment() {
        let mut tris = quad(0.0, 5.0, true).to_vec();
        tris.extend(quad(1.0, 0.5, false));
        let bvh = TriangleBvh::new(&tris);
        let o = DVec3::new(0.0, 3.0, 0.0);
        assert!(bvh.occluded(o, DVec3::NEG_Y, 0.0, 3.5));
        assert!(
            !bvh.occluded(o, DVec3::NEG_Y, 0.0, 2.5),
            "the upper quad casts no shadow"
        );
        assert!(
            !bvh.occluded(o, DVec3::NEG_Y, 0.0, 3.0),
            "the segment ends at the plane"
        );
    }

    #[test]
    fn a_far_away_camera_keeps_exact_hits() {
        let tris = quad(0.0, 1.0, true);
        let bvh = TriangleBvh::new(&tris);
        let o = DVec3::new(0.3e6, 1.0e6, -0.2e6);
        let target = DVec3::new(0.999_999, 0.0, 0.5);
        let d = (target - o).normalize();
        let hit = bvh.closest_hit(o, d, 0.0, f64::INFINITY).unwrap();
        assert!((o + d * hit.at.t - target).length() < 1e-9);
    }

    #[test]
    fn nothing_to_hit_is_fine() {
        let degenerate = [BvhTriangle {
            corners: [DVec3::ZERO, DVec3::X, DVec3::X * 2.0],
            occludes: true,
        }];
        for tris in [&degenerate[..], &[]] {
            let bvh = TriangleBvh::new(tris);
            assert!(bvh.is_empty());
            assert!(
                bvh.closest_hit(DVec3::Y, DVec3::NEG_Y, 0.0, f64::INFINITY)
                    .is_none()
            );
            assert!(!bvh.occluded(DVec3::Y, DVec3::NEG_Y, 0.0, 2.0));
        }
    }
}
