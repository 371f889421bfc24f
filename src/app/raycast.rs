//! Casting one pixel's ray into the scene on the CPU, for the pixel probe:
//! a brute-force loop over every triangle (behind a bounding-box test per
//! object), in f64. One ray per click, so no acceleration structure is
//! needed; the CPU reference's BVH can replace it once it lands.

use crate::scene::{Aabb, Scene};
use glam::{DVec2, DVec3};

/// Where a ray meets the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Index into `Scene::objects`.
    pub object: usize,
    /// Triangle within the object's mesh.
    pub triangle: usize,
    /// Distance along the ray (m).
    pub t: f64,
    pub position: DVec3,
    /// The interpolated vertex normal, normalized (as the GPU shades it).
    pub normal: DVec3,
    /// The triangle's own normal (counter-clockwise front face).
    pub geometric_normal: DVec3,
    pub uv: DVec2,
}

/// The nearest hit of the ray `origin + t·dir` (t > 0), if any.
pub fn cast(scene: &Scene, origin: DVec3, dir: DVec3) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (o, object) in scene.objects.iter().enumerate() {
        let limit = best.map_or(f64::INFINITY, |h| h.t);
        if !ray_meets_box(origin, dir, &object.bounds, limit) {
            continue;
        }
        let mesh = &object.mesh;
        for t in 0..mesh.triangle_count() {
            let Some(corners) = mesh.indices.get(3 * t..3 * t + 3) else {
                break;
            };
            let index = |k: usize| corners[k] as usize;
            let (Some(a), Some(b), Some(c)) = (
                mesh.positions.get(index(0)),
                mesh.positions.get(index(1)),
                mesh.positions.get(index(2)),
            ) else {
                continue;
            };
            let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
            let Some((dist, u, v)) = intersect_triangle(origin, dir, a, b, c) else {
                continue;
            };
            if dist >= best.map_or(f64::INFINITY, |h| h.t) {
                continue;
            }
            let w = 1.0 - u - v;
            let vertex_normal = |k: usize| mesh.normals.get(index(k)).map(|n| n.as_dvec3());
            let geometric_normal = (b - a).cross(c - a).normalize_or_zero();
            let normal = match (vertex_normal(0), vertex_normal(1), vertex_normal(2)) {
                (Some(na), Some(nb), Some(nc)) => (na * w + nb * u + nc * v).normalize_or(geometric_normal),
                _ => geometric_normal,
            };
            let uv_of = |k: usize| mesh.uvs.get(index(k)).map_or(DVec2::ZERO, |p| p.as_dvec2());
            best = Some(Hit {
                object: o,
                triangle: t,
                t: dist,
                position: origin + dir * dist,
                normal,
                geometric_normal,
                uv: uv_of(0) * w + uv_of(1) * u + uv_of(2) * v,
            });
        }
    }
    best
}

/// Möller–Trumbore: (t, u, v) with the hit at (1 − u − v)·a + u·b + v·c;
/// both faces count.
fn intersect_triangle(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<(f64, f64, f64)> {
    let e1 = b - a;
    let e2 = c - a;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 1e-9).then_some((t, u, v))
}

/// Slab test: does the ray enter the box before `limit`?
fn ray_meets_box(origin: DVec3, dir: DVec3, b: &Aabb, limit: f64) -> bool {
    if b.is_empty() {
        return false;
    }
    let (mut t0, mut t1) = (0.0_f64, limit);
    for axis in 0..3 {
        let (lo, hi) = (b.min[axis] as f64, b.max[axis] as f64);
        if dir[axis].abs() < 1e-300 {
            if origin[axis] < lo || origin[axis] > hi {
                return false;
            }
            continue;
        }
        let (a, c) = ((lo - origin[axis]) / dir[axis], (hi - origin[axis]) / dir[axis]);
        t0 = t0.max(a.min(c));
        t1 = t1.min(a.max(c));
    }
    t0 <= t1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_down_hits_the_ground_with_an_up_normal() {
        let scene = crate::scene::default_scene();
        let hit = cast(&scene, DVec3::new(-3.0, 5.0, 3.0), DVec3::NEG_Y).unwrap();
        assert!((hit.position - DVec3::new(-3.0, 0.0, 3.0)).length() < 1e-9);
        assert!((hit.normal - DVec3::Y).length() < 1e-9);
        assert_eq!(scene.objects[hit.object].name, "ground");
    }

    #[test]
    fn the_box_top_is_nearer_than_the_ground() {
        let scene = crate::scene::default_scene();
        let hit = cast(&scene, DVec3::new(0.0, 5.0, 0.0), DVec3::NEG_Y).unwrap();
        assert!((hit.position.y - 1.0).abs() < 1e-9, "{:?}", hit.position);
        assert_eq!(scene.objects[hit.object].name, "box");
    }

    #[test]
    fn a_ray_into_the_sky_misses() {
        let scene = crate::scene::default_scene();
        assert!(cast(&scene, DVec3::new(0.0, 5.0, 0.0), DVec3::Y).is_none());
    }
}
