//! The lecture's figure: a row of equal spheres whose only difference is
//! the Blinn-Phong exponent m (1, 8, 32, 128, 1000, left to right), so that
//! the highlight's size and brightness can be compared at a glance, with or
//! without the normalization N(m). Built in code beside the default scene
//! (`default_scene`); the tour shows it (`tour::TourScene::Spheres`).
//!
//! Each sphere's material gives its own m and leaves k to the Material
//! panel (`MaterialSettings::use_scene_materials`), so the panel's k and N
//! act on the whole row.

use super::shapes::{ground_slab, sphere};
use super::{Camera, Material, Object, Scene, SceneCamera, SceneScale};
use glam::{Vec3, Vec4};

/// The exponents m of the row, left to right.
pub const EXPONENTS: [f32; 5] = [1.0, 8.0, 32.0, 128.0, 1000.0];
/// Radius of each sphere (m).
pub const SPHERE_RADIUS_M: f32 = 0.35;
/// Distance between the centres of neighbouring spheres (m).
pub const SPACING_M: f32 = 0.85;
/// Fine tessellation: interpolated normals keep even m = 1000's small
/// highlight round.
pub const SPHERE_SEGMENTS: u32 = 96;
pub const SPHERE_RINGS: u32 = 48;
/// The spheres' colour c (linear RGB): light grey, so that the highlight's
/// colour is the light's.
pub const SPHERE_COLOR: [f32; 3] = [0.8, 0.8, 0.8];
/// Ground: side (m), thickness (m), quads per side, colour and its k, m.
pub const GROUND_SIZE_M: f32 = 8.0;
pub const GROUND_THICKNESS_M: f32 = 0.1;
pub const GROUND_CELLS: u32 = 8;
pub const GROUND_COLOR: [f32; 3] = [0.25, 0.25, 0.27];
pub const GROUND_K: f32 = 0.9;
pub const GROUND_M: f32 = 16.0;

/// The view of the row: in front, a little above; the row still fits the
/// width of one half of the split view side by side.
pub const HOME: Camera = Camera {
    eye: Vec3::new(0.0, 1.5, 5.0),
    target: Vec3::new(0.0, 0.35, 0.0),
    fovy_deg: 40.0,
};

/// Where a light shows a highlight on the front of every sphere (m): above
/// the camera, a little to its right.
pub const LIGHT_POSITION: Vec3 = Vec3::new(1.0, 4.0, 5.0);

/// The centre of the sphere of exponent `EXPONENTS[i]`.
pub fn sphere_center(i: usize) -> Vec3 {
    let first = -0.5 * SPACING_M * (EXPONENTS.len() - 1) as f32;
    Vec3::new(first + i as f32 * SPACING_M, SPHERE_RADIUS_M, 0.0)
}

/// The scene, built in code.
pub fn scene() -> Scene {
    let grey = |c: [f32; 3]| Vec3::from_array(c).extend(1.0);
    let mut materials = vec![Material {
        name: "ground".into(),
        base_color: grey(GROUND_COLOR),
        k: Some(GROUND_K),
        m: Some(GROUND_M),
        ..Material::default()
    }];
    let mut objects = vec![Object::new(
        "ground",
        ground_slab(Vec3::ZERO, GROUND_SIZE_M, GROUND_THICKNESS_M, GROUND_CELLS),
        0,
    )];
    for (i, &m) in EXPONENTS.iter().enumerate() {
        let name = format!("sphere m = {m}");
        materials.push(Material {
            name: name.clone(),
            base_color: Vec4::from((Vec3::from_array(SPHERE_COLOR), 1.0)),
            m: Some(m),
            ..Material::default()
        });
        let mesh = sphere(sphere_center(i), SPHERE_RADIUS_M, SPHERE_SEGMENTS, SPHERE_RINGS);
        objects.push(Object::new(name, mesh, materials.len() - 1));
    }
    Scene {
        objects,
        materials,
        cameras: vec![SceneCamera {
            name: "row".into(),
            camera: HOME,
        }],
        scale: SceneScale::BUILT_IN,
        designed_view: Some(HOME),
        ..Scene::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sphere_has_its_own_exponent_and_no_k() {
        let scene = scene();
        let spheres: Vec<_> = scene.objects.iter().skip(1).collect();
        assert_eq!(spheres.len(), EXPONENTS.len());
        for (object, m) in spheres.iter().zip(EXPONENTS) {
            let material = scene.material_of(object);
            assert_eq!((material.m, material.k), (Some(m), None), "{}", object.name);
            assert_eq!(object.bounds.min.y, 0.0, "{} rests on the ground", object.name);
        }
    }

    #[test]
    fn the_row_is_in_the_home_view_and_spheres_do_not_touch() {
        let image = crate::settings::ImageSettings::default();
        let aspect = image.width as f64 / image.height as f64;
        let projection = HOME.projection(aspect, 0.1, 100.0) * HOME.view_rotation();
        for object in scene().objects.iter().skip(1) {
            for corner in object.bounds.corners() {
                let clip = projection * (corner.as_dvec3() - HOME.eye.as_dvec3()).extend(1.0);
                let (x, y) = (clip.x / clip.w, clip.y / clip.w);
                assert!(
                    clip.w > 0.0 && x.abs() < 0.95 && y.abs() < 0.95,
                    "{}: {x}, {y}",
                    object.name
                );
            }
        }
        const { assert!(SPACING_M > 2.0 * SPHERE_RADIUS_M) };
    }
}
