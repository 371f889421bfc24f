//! Shadow-map depth precision from millimetres to kilometres: the same scene
//! at scales 1e-3 … 1e4 gives the same visibility, compared with exact ray
//! casting. Depth is Depth32Float with reversed Z (near → 1, far → 0) for the
//! camera and every light layer, so its relative precision is about 1e-7 at
//! every distance; the receiver's depth is compared in metres.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use lumlab::scene::shapes::{cuboid, ground_grid};
use lumlab::scene::{Aabb, Object, Scene};
use lumlab::settings::Filter;

/// Pixels whose shadow state differs from the ray-cast truth, out of the
/// pixels that see the ground away from the shadow's edge.
fn wrong_visibility_fraction(scale: f32) -> (usize, usize) {
    let occluder = Aabb {
        min: Vec3::new(-0.5, 0.02, -0.5) * scale,
        max: Vec3::new(0.5, 0.06, 0.5) * scale,
    };
    // A thin plate just above the ground: the hard case for depth precision.
    let scene = Scene {
        objects: vec![
            Object::new("ground", ground_grid(Vec3::ZERO, 20.0 * scale, 20), 0),
            Object::new("plate", cuboid(occluder), 0),
        ],
        materials: vec![material(Vec3::ONE)],
        ..Scene::default()
    };
    let mut s = settings(200, 150);
    s.light.position = Vec3::new(0.7, 4.0, 0.3) * scale;
    s.light.power_w = 1000.0 * scale * scale;
    s.camera.eye = Vec3::new(0.0, 1.5, 3.0) * scale;
    s.camera.target = Vec3::new(0.0, 0.0, -0.3) * scale;
    s.shadow.filter = Filter::None;
    s.shadow.resolution = 2048;
    let gpu = gpu();
    let (report, _, aux) = render(&gpu, &scene, &s);
    let layer = &report.layout.expect("shadows on").layers[0].frustum;
    let texel_angle = (layer.tan[1] - layer.tan[0]) / s.shadow.resolution as f64;
    let q = s.light.position.as_dvec3();
    let (mut wrong, mut counted) = (0, 0);
    for j in 0..s.image.height {
        for i in 0..s.image.width {
            let idx = (j * s.image.width + i) as usize;
            let Some(p) = plane_hit(&s, i, j) else { continue };
            if aux[idx][3] == 0.0 || segment_hits_box(s.camera.eye.as_dvec3(), p, &occluder) {
                continue;
            }
            // Skip the shadow's edge: within two texels of the ray that grazes the plate.
            let near_edge = [-1.0, 1.0].iter().any(|&d| {
                let nudge = (p - q).length() * texel_angle * 2.0;
                segment_hits_box(p + DVec3::X * d * nudge, q, &occluder) != segment_hits_box(p, q, &occluder)
                    || segment_hits_box(p + DVec3::Z * d * nudge, q, &occluder)
                        != segment_hits_box(p, q, &occluder)
            });
            if near_edge {
                continue;
            }
            counted += 1;
            let truly_lit = !segment_hits_box(p, q, &occluder);
            if truly_lit != (aux[idx][0] > 0.5) {
                wrong += 1;
            }
        }
    }
    (wrong, counted)
}

#[test]
fn visibility_holds_from_a_millimetre_to_ten_kilometres() {
    for exponent in -3..=4 {
        let scale = 10f32.powi(exponent);
        let (wrong, counted) = wrong_visibility_fraction(scale);
        assert!(counted > 10_000, "scale {scale}: {counted}");
        let fraction = wrong as f64 / counted as f64;
        eprintln!(
            "scale {scale:e} m: {wrong} of {counted} pixels wrong ({:.3} %)",
            100.0 * fraction
        );
        assert!(fraction < 0.002, "scale {scale}: {wrong} of {counted} wrong");
    }
}

/// The window depth wgpu's GL back end gives a point `rel` (from the eye):
/// naga writes z · 2 − w (clip depth in [−1, 1], no clip control) and GL
/// maps it back to [0, 1], all in f32.
fn gl_window_depth(view_proj: glam::Mat4, rel: Vec3) -> f32 {
    let clip = view_proj * rel.extend(1.0);
    let z = clip.z * 2.0 - clip.w;
    (z / clip.w) * 0.5 + 0.5
}

#[test]
fn the_near_plane_keeps_surfaces_apart_on_gl_where_reversed_z_cannot() {
    use lumlab::gpu::capabilities::{NEAR_RATIO, NEAR_RATIO_GL};
    use lumlab::gpu::renderer::camera_depth_range;
    // A close, oblique camera inside the default scene, whose ground is a
    // slab: its top at y = 0 and its underside 10 cm below, along one ray.
    let scene = lumlab::scene::default_scene();
    let mut camera = lumlab::settings::Settings::default().camera;
    camera.eye = Vec3::new(-3.7, 2.4, 2.4);
    camera.target = Vec3::new(-3.7, 0.0, -0.1);
    camera.fovy_deg = 60.0;
    let ray = (camera.target - camera.eye).normalize();
    let on_plane = |y: f32| ray * ((y - camera.eye.y) / ray.y);
    let (top, underside) = (on_plane(0.0), on_plane(-0.1));
    let depths = |ratio: f64| {
        let (near, far) = camera_depth_range(&camera, &scene.bounds(), ratio);
        let view_proj = (camera.projection(16.0 / 9.0, near, far) * camera.view_rotation()).as_mat4();
        (
            gl_window_depth(view_proj, top),
            gl_window_depth(view_proj, underside),
        )
    };
    // Reversed Z: the nearer surface has the greater depth. GL's window
    // depth moves in steps of 2⁻²⁵ (an f32 near 1, halved), and the
    // rasterizer's interpolation rounds by a step or so: the surfaces need
    // many steps between them.
    let step = 2f32.powi(-25);
    let (top_depth, underside_depth) = depths(NEAR_RATIO_GL);
    assert!(
        top_depth - underside_depth > 100.0 * step,
        "{top_depth} against {underside_depth}"
    );
    // With Vulkan's ratio they are a step apart on GL: the underside showed
    // through the ground.
    let (top_depth, underside_depth) = depths(NEAR_RATIO);
    assert!(
        top_depth - underside_depth <= 2.0 * step,
        "{top_depth} against {underside_depth}"
    );
}
