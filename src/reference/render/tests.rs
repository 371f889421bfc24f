//! The render's shortcuts against the plain path: the same bits.

use super::*;
use crate::scene::{Object, Scene, shapes};
use glam::Vec3;

/// Above the grids' limit, blocks of pixels sharing a packet give every
/// pixel exactly what one packet a pixel gives (partial blocks at the
/// image's bottom row and the tiles' right edges included), their point
/// light shaded without a surface a sample (`point_run`) as each sample's
/// surface is one by one: on a Lambertian ground, then under Blinn-Phong
/// with a smooth double-sided ball and a box that receives no shadows, the
/// light low enough for points under its horizon.
#[test]
fn runs_of_pixels_render_what_single_pixels_render() {
    let mut ground = shapes::ground_grid(Vec3::ZERO, 6.0, 100);
    ground.append(&shapes::ground_grid(Vec3::new(0.3, 0.7, -0.2), 1.5, 20));
    let ball = shapes::sphere(Vec3::new(-0.8, 0.5, 0.6), 0.5, 48, 24);
    let cube = crate::scene::Aabb {
        min: Vec3::new(0.6, 0.0, 0.4),
        max: Vec3::new(1.2, 0.5, 1.0),
    };
    let mut boxed = Object::new("box", shapes::cuboid(cube), 0);
    boxed.receives_shadows = false;
    let materials = vec![
        crate::scene::Material::default(),
        crate::scene::Material {
            double_sided: true,
            ..crate::scene::Material::default()
        },
    ];
    let plain = Scene {
        objects: vec![Object::new("ground", ground.clone(), 0)],
        materials: materials.clone(),
        ..Scene::default()
    };
    let mixed = Scene {
        objects: vec![
            Object::new("ground", ground, 0),
            Object::new("ball", ball, 1),
            boxed,
        ],
        materials,
        ..Scene::default()
    };
    for (scene, k, light) in [
        (plain, 1.0, Vec3::new(-1.0, 4.0, 1.0)),
        (mixed, 0.4, Vec3::new(2.5, 0.6, -1.5)),
    ] {
        let reference = Reference::new(&scene);
        assert!(reference.triangles.len() > GRID_MAX_TRIANGLES && reference.grid_triangles.is_empty());
        let mut settings = Settings::default();
        settings.camera.eye = Vec3::new(1.0, 3.0, 4.0);
        settings.camera.target = Vec3::ZERO;
        settings.light.position = light;
        settings.material.k = k;
        (settings.image.width, settings.image.height) = (23, 7);
        let options = ReferenceOptions {
            spp: 4,
            ..ReferenceOptions::default()
        };
        let control = RenderControl::default();
        let single = reference
            .render_in_blocks(&settings, &options, &control, (1, 1), Shortcuts::ALL)
            .unwrap();
        assert!(single.coverage.iter().any(|&c| c > 0.0) && single.visibility.iter().any(|&v| v < 1.0));
        for block in [BLOCK, WIDE_BLOCK] {
            let runs = reference
                .render_in_blocks(&settings, &options, &control, block, Shortcuts::ALL)
                .unwrap();
            assert_eq!(single.radiance, runs.radiance, "block {block:?}");
            assert_eq!(single.visibility, runs.visibility, "block {block:?}");
            assert_eq!(single.coverage, runs.coverage, "block {block:?}");
            assert_eq!(single.noise, runs.noise, "block {block:?}");
            assert_eq!(
                single.stats.shadow_rays, runs.stats.shadow_rays,
                "block {block:?}"
            );
        }
    }
}

/// Tiles and pixels that see only background are told so without
/// casting their samples, and the image is the same bit for bit:
/// through the eye grid (small scene) and the BVH's packets.
#[test]
fn skipping_background_tiles_changes_no_pixel() {
    for divisions in [10, 100] {
        let ground = shapes::ground_grid(Vec3::ZERO, 6.0, divisions);
        let scene = Scene {
            objects: vec![Object::new("ground", ground, 0)],
            materials: vec![crate::scene::Material::default()],
            ..Scene::default()
        };
        let reference = Reference::new(&scene);
        let mut settings = Settings::default();
        // Level with the ground's far edge: the top half is sky, the
        // horizon runs through tiles and blocks.
        settings.camera.eye = Vec3::new(0.3, 1.0, 2.0);
        settings.camera.target = Vec3::new(0.0, 0.9, -3.0);
        settings.light.position = Vec3::new(-1.0, 4.0, 1.0);
        (settings.image.width, settings.image.height) = (40, 36);
        let options = ReferenceOptions {
            spp: 4,
            ..ReferenceOptions::default()
        };
        let setup = Setup::new(&settings, &options, &reference.materials);
        assert!(!reference.bvh.meets_cone(&block_cone(&setup, (0, 0), (16, 16))));
        assert!(reference.bvh.meets_cone(&block_cone(&setup, (0, 20), (16, 16))));
        let control = RenderControl::default();
        let cast = reference
            .render_in_blocks(
                &settings,
                &options,
                &control,
                BLOCK,
                Shortcuts {
                    background: false,
                    ..Shortcuts::ALL
                },
            )
            .unwrap();
        let skipped = reference
            .render_in_blocks(&settings, &options, &control, BLOCK, Shortcuts::ALL)
            .unwrap();
        assert!(cast.coverage.contains(&0.0) && cast.coverage.contains(&1.0));
        assert_eq!(cast.radiance, skipped.radiance);
        assert_eq!(cast.visibility, skipped.visibility);
        assert_eq!(cast.coverage, skipped.coverage);
        assert_eq!(cast.noise, skipped.noise);
        assert_eq!(cast.noise_known, skipped.noise_known);
        assert_eq!(cast.stats.primary_rays, skipped.stats.primary_rays);
    }
}
