//! Large scenes for benchmarks: many finely tessellated spheres on a ground,
//! as many triangles as asked for.

use super::shapes::{ground_grid, sphere};
use super::{Material, Object, Scene};
use glam::Vec3;

/// Tessellation of each sphere: segments around, rings pole to pole
/// (segments × (2 rings − 2) triangles: 65 024).
const SEGMENTS: u32 = 256;
const RINGS: u32 = 128;
/// Centre-to-centre spacing of the spheres (m); their radius is 0.4 m.
const SPACING_M: f32 = 1.0;
const RADIUS_M: f32 = 0.4;

/// At least `triangles` triangles: a square field of spheres on a ground.
pub fn sphere_field(triangles: usize) -> Scene {
    let per_sphere = (SEGMENTS * (2 * RINGS - 2)) as usize;
    let count = triangles.div_ceil(per_sphere).max(1);
    let side = (count as f64).sqrt().ceil() as usize;
    let extent_m = side as f32 * SPACING_M;
    let mut objects = vec![Object::new(
        "ground",
        ground_grid(Vec3::ZERO, extent_m + 2.0 * SPACING_M, side as u32 + 2),
        0,
    )];
    for i in 0..count {
        let (row, col) = (i / side, i % side);
        let center = Vec3::new(
            (col as f32 + 0.5) * SPACING_M - 0.5 * extent_m,
            RADIUS_M,
            (row as f32 + 0.5) * SPACING_M - 0.5 * extent_m,
        );
        objects.push(Object::new(
            format!("sphere {i}"),
            sphere(center, RADIUS_M, SEGMENTS, RINGS),
            1,
        ));
    }
    Scene {
        objects,
        materials: vec![
            Material {
                name: "ground".into(),
                ..Material::default()
            },
            Material {
                name: "spheres".into(),
                k: Some(0.5),
                m: Some(64.0),
                ..Material::default()
            },
        ],
        ..Scene::default()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_field_has_at_least_the_triangles_asked_for() {
        let scene = super::sphere_field(200_000);
        assert!(scene.triangle_count() >= 200_000);
        assert!(scene.triangle_count() < 200_000 + 70_000);
    }
}
