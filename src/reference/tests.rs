use super::*;
use crate::physics::display::srgb_decode;
use crate::scene::{Object, Texture, shapes};
use glam::{Vec3, Vec4};

/// A 4 m ground facing +Y with one material (and its texture, if any).
fn ground_scene(material: Material, texture: Option<Texture>) -> Scene {
    Scene {
        objects: vec![Object::new("ground", shapes::ground(Vec3::ZERO, 4.0), 0)],
        materials: vec![material],
        textures: texture.into_iter().collect(),
        ..Scene::default()
    }
}

/// Looking down at the ground from `eye_y` (negative: from below), the
/// light on the same side.
fn settings(eye_y: f32) -> Settings {
    let mut s = Settings::default();
    s.camera.eye = Vec3::new(0.0, eye_y, 0.5 * eye_y);
    s.camera.target = Vec3::ZERO;
    s.light.position = Vec3::new(0.3, eye_y, 0.2);
    (s.image.width, s.image.height) = (16, 12);
    s
}

fn centre(reference: &Reference, s: &Settings) -> Option<ShadingSample> {
    reference.trace_pixel(s, &ReferenceOptions::default(), 8.0, 6.0)
}

/// A triangle's shading data is its place in the scene, the rest read
/// from its mesh: each byte added to it is 1 MB more on 1 M triangles.
#[test]
fn the_shading_data_takes_8_bytes_a_triangle() {
    assert_eq!(std::mem::size_of::<TriangleInfo>(), 8);
}

/// A triangle with an index out of range is skipped and counted; the
/// triangles after it, in its object and the next, keep their own
/// object, index and material.
#[test]
fn skipped_triangles_leave_the_others_in_place() {
    let mut lower = shapes::ground(Vec3::ZERO, 4.0);
    let out_of_range = lower.positions.len() as u32;
    lower.indices.splice(0..0, [0, 1, out_of_range]);
    let upper = shapes::ground(Vec3::new(0.0, 1.0, 0.0), 2.0);
    let scene = Scene {
        objects: vec![Object::new("lower", lower, 0), Object::new("upper", upper, 1)],
        materials: vec![Material::default(); 2],
        ..Scene::default()
    };
    let reference = Reference::new(&scene);
    assert_eq!(reference.skipped_triangles(), 1);
    assert_eq!(reference.triangle_count(), 4);
    let s = settings(3.0);
    let hit = centre(&reference, &s).expect("the upper ground");
    assert_eq!((hit.object, hit.material), (1, Some(1)));
    assert!((hit.position.y - 1.0).abs() < 1e-12);
    // Beside the upper ground: the lower one, its triangles numbered from
    // 1 (triangle 0 is the skipped one).
    let hit = reference
        .trace_pixel(&s, &ReferenceOptions::default(), 1.0, 1.0)
        .expect("the lower ground");
    assert_eq!((hit.object, hit.material), (0, Some(0)));
    assert!(hit.position.y.abs() < 1e-12);
    assert!(
        hit.triangle == 1 || hit.triangle == 2,
        "triangle {}",
        hit.triangle
    );
}

#[test]
fn own_k_and_m_win_only_when_scene_materials_are_used() {
    let material = Material {
        k: Some(0.2),
        m: Some(5.0),
        ..Material::default()
    };
    let reference = Reference::new(&ground_scene(material, None));
    let mut s = settings(3.0);
    let sample = centre(&reference, &s).unwrap();
    assert_eq!((sample.k, sample.m), (0.2_f32 as f64, 5.0));
    s.material.use_scene_materials = false;
    let sample = centre(&reference, &s).unwrap();
    assert_eq!((sample.k, sample.m), (s.material.k as f64, s.material.m as f64));
}

#[test]
fn colour_is_base_times_decoded_texture_unless_overridden() {
    let material = Material {
        base_color: Vec4::new(0.5, 1.0, 0.25, 1.0),
        base_color_texture: Some(0),
        ..Material::default()
    };
    let texture = Texture {
        width: 1,
        height: 1,
        rgba8: vec![128, 64, 255, 255],
    };
    let reference = Reference::new(&ground_scene(material, Some(texture)));
    let mut s = settings(3.0);
    let c = centre(&reference, &s).unwrap().color;
    let decoded = |b: u8| srgb_decode(b as f64 / 255.0);
    let expected = DVec3::new(0.5 * decoded(128), decoded(64), 0.25);
    assert!((c - expected).abs().max_element() < 1e-15, "{c} vs {expected}");
    s.material.color_override = Some(Vec3::new(0.1, 0.2, 0.3));
    let c = centre(&reference, &s).unwrap().color;
    assert_eq!(c, Vec3::new(0.1, 0.2, 0.3).as_dvec3());
}

#[test]
fn only_double_sided_materials_reflect_from_their_back() {
    let below = settings(-3.0);
    for double_sided in [false, true] {
        let material = Material {
            double_sided,
            ..Material::default()
        };
        let reference = Reference::new(&ground_scene(material, None));
        let sample = centre(&reference, &below).unwrap();
        if double_sided {
            assert_eq!(sample.normal.y, -1.0);
            assert!(sample.radiance.x > 0.0 && sample.visibility == 1.0);
        } else {
            assert_eq!(sample.radiance, DVec3::ZERO);
        }
    }
}

#[test]
fn distance_and_view_direction_match_the_hit_point() {
    // Primary rays are cast along directions that are not normalized.
    let reference = Reference::new(&ground_scene(Material::default(), None));
    let s = settings(3.0);
    let eye = s.camera.eye.as_dvec3();
    for (x, y) in [(8.0, 6.0), (4.5, 3.5), (12.25, 9.75)] {
        let sample = reference
            .trace_pixel(&s, &ReferenceOptions::default(), x, y)
            .unwrap();
        let to_eye = eye - sample.position;
        let expected = to_eye.length();
        assert!(
            (sample.distance_m - expected).abs() < 1e-12 * expected,
            "({x}, {y})"
        );
        let direction = s.camera.ray_direction(x, y, s.image.width, s.image.height);
        assert!((to_eye / expected + direction).length() < 1e-12, "({x}, {y})");
    }
}

#[test]
fn background_has_no_sample_and_no_coverage() {
    let reference = Reference::new(&ground_scene(Material::default(), None));
    let mut s = settings(3.0);
    s.camera.target = Vec3::new(0.0, 6.0, 0.0);
    assert!(centre(&reference, &s).is_none());
    let image = reference
        .render(&s, &ReferenceOptions::default(), &RenderControl::default())
        .unwrap();
    assert!(image.coverage.iter().all(|&c| c == 0.0));
    assert!(image.radiance.iter().all(|l| *l == [0.0; 3]));
}

#[test]
fn a_silhouette_is_partly_covered_with_several_samples_per_pixel() {
    let reference = Reference::new(&ground_scene(Material::default(), None));
    let mut s = settings(3.0);
    // Far enough that the ground's edge crosses the image.
    s.camera.eye = Vec3::new(0.0, 3.0, 9.0);
    let options = ReferenceOptions {
        spp: 16,
        ..ReferenceOptions::default()
    };
    let image = reference.render(&s, &options, &RenderControl::default()).unwrap();
    assert!(image.coverage.iter().any(|&c| c > 0.0 && c < 1.0));
    assert_eq!(image.stats.primary_rays, 16 * 16 * 12);
}

#[test]
fn progress_counts_every_pixel_and_cancel_stops() {
    let reference = Reference::new(&ground_scene(Material::default(), None));
    let s = settings(3.0);
    let control = RenderControl::default();
    reference
        .render(&s, &ReferenceOptions::default(), &control)
        .unwrap();
    assert_eq!(control.pixels_done.load(Ordering::Relaxed), 16 * 12);
    let control = RenderControl::default();
    control.cancel();
    let result = reference.render(&s, &ReferenceOptions::default(), &control);
    assert!(matches!(result, Err(ReferenceError::Cancelled)));
}

#[test]
fn the_same_seed_gives_the_same_image_whatever_the_threads() {
    let reference = Reference::new(&ground_scene(Material::default(), None));
    let mut s = settings(3.0);
    s.light.radius_m = 0.5;
    let render = || {
        reference
            .render(&s, &ReferenceOptions::default(), &RenderControl::default())
            .unwrap()
            .radiance
    };
    let single = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    assert_eq!(render(), single.install(render));
}
