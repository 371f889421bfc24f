//! Ray-traced drag frames (`ShadeOptions::INTERACTION`): on a large scene
//! the shadow rays meet the simplified meshes the frame draws, through a BVH
//! of their own, and a sphere light gets one ray a pixel; the still frame
//! after the drag traces the full meshes with every sample, its
//! accumulation started anew.

mod common;

use lumlab::gpu::{Renderer, ShadeOptions};
use lumlab::scene::Scene;
use lumlab::scene::simplify::{THRESHOLD_TRIANGLES, simplify};
use lumlab::settings::{Settings, Visibility};

const SIZE: (u32, u32) = (192, 108);

/// A drag frame's options, with the aux target (V) kept for the comparison.
const DRAG: ShadeOptions = ShadeOptions {
    aux: true,
    ..ShadeOptions::INTERACTION
};

fn ray_traced(scene: &Scene) -> Settings {
    let mut s = Settings::default();
    lumlab::scene::framing::adopt(&mut s, scene);
    s.shadow.visibility = Visibility::RayTraced;
    s.light.radius_m = 0.0;
    s
}

#[test]
fn a_drag_frame_traces_the_simplified_meshes_it_draws_and_the_still_frame_the_full_ones() {
    let gpu = common::gpu();
    let renderer = |scene: &Scene| Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, scene);
    let scene = lumlab::scene::stress::sphere_field(THRESHOLD_TRIANGLES + 1);
    let meshes = simplify(&scene).expect("above the threshold");
    // The simplified meshes as a scene of their own: what a drag frame
    // must show, its spheres shadowing the ground and not themselves.
    let mut coarse = scene.clone();
    for (object, indices) in coarse.objects.iter_mut().zip(&meshes.indices) {
        object.mesh.indices.clone_from(indices);
    }
    let s = ray_traced(&scene);

    let mut dragging = renderer(&scene);
    dragging.set_simplified(&meshes);
    dragging.set_shade_options(DRAG);
    let report = dragging.render(&s, SIZE);
    assert_eq!(report.simplified_triangles, Some(meshes.counts.camera));
    let mut expected = renderer(&coarse);
    expected.render(&s, SIZE);
    let shadowed = |aux: &[[f32; 4]]| aux.iter().filter(|t| t[3] > 0.0 && t[0] < 0.5).count();
    let aux = expected.read_aux();
    assert!(shadowed(&aux) > 100, "the spheres cast shadows");
    assert!(
        dragging.read_aux() == aux,
        "V of the drag frame is that of the simplified meshes, bit for bit"
    );
    assert!(dragging.read_quantity() == expected.read_quantity());

    // The still frame after the drag: the full meshes' rays, as a renderer
    // that never had the simplified meshes traces them.
    dragging.set_shade_options(ShadeOptions::default());
    let report = dragging.render(&s, SIZE);
    assert_eq!(report.simplified_triangles, None);
    let mut full = renderer(&scene);
    full.render(&s, SIZE);
    assert!(dragging.read_aux() == full.read_aux(), "V of the full meshes");
    assert!(dragging.read_quantity() == full.read_quantity());
}

#[test]
fn a_drag_frame_sends_one_ray_to_a_sphere_light_and_the_still_frame_starts_anew() {
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let mut s = ray_traced(&scene);
    s.light.radius_m = 0.3;
    s.shadow.rt_light_samples = 16;
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);

    renderer.set_shade_options(DRAG);
    for frames in 1..=2 {
        renderer.render(&s, SIZE);
        let a = renderer.accumulation().expect("ray traced");
        assert_eq!(
            (a.frames, a.rays_per_frame),
            (frames, 1),
            "a held drag accumulates its own frames"
        );
    }
    renderer.set_shade_options(ShadeOptions::default());
    renderer.render(&s, SIZE);
    let a = renderer.accumulation().expect("ray traced");
    assert_eq!(
        (a.frames, a.rays_per_frame),
        (1, 16),
        "the still frame does not fold in the drag's frames"
    );
}
