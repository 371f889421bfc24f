//! The split view's two halves share one uploaded scene and, when their
//! shadow settings give the same map, one shadow map: a normalization split
//! draws the map once per change, and each half still shows exactly what a
//! renderer of its own shows. Also: the visibility method is a setting of
//! its own that old settings files do without.

mod common;

use common::*;
use glam::Vec3;
use lumlab::gpu::Renderer;
use lumlab::physics::Normalization;
use lumlab::settings::{Filter, Settings, Visibility};

const OCCLUDER: ([f32; 3], [f32; 3]) = ([-0.5, 0.5, -0.5], [0.5, 1.0, 0.5]);

fn split_settings() -> (Settings, Settings) {
    let mut a = settings(64, 48);
    a.camera.eye = Vec3::new(0.0, 4.0, 6.0);
    a.camera.target = Vec3::ZERO;
    a.light.position = Vec3::new(1.0, 4.0, 1.0);
    a.material.k = 0.2;
    a.material.m = 32.0;
    a.material.norm = Normalization::Exact;
    let mut b = a.clone();
    b.material.norm = Normalization::None;
    (a, b)
}

/// What a renderer of its own draws with `settings`: the quantity and aux targets.
fn single(
    gpu: &lumlab::gpu::GpuContext,
    scene: &lumlab::scene::Scene,
    settings: &Settings,
) -> [Vec<[f32; 4]>; 2] {
    let (_, quantity, aux) = render(gpu, scene, settings);
    [quantity, aux]
}

/// A frame's quantity and aux targets, and whether it drew a shadow map.
fn frame(renderer: &mut Renderer, settings: &Settings) -> ([Vec<[f32; 4]>; 2], bool) {
    let report = renderer.render(settings, (settings.image.width, settings.image.height));
    (
        [renderer.read_quantity(), renderer.read_aux()],
        report.shadow_redrawn,
    )
}

#[test]
fn a_normalization_split_draws_the_shadow_map_once_per_change() {
    let gpu = gpu();
    let scene = occluder_scene(20.0, aabb(OCCLUDER.0, OCCLUDER.1));
    let (mut a_settings, mut b_settings) = split_settings();
    let mut a = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let mut b = a.sharing();

    for (change, expected_draws) in [
        ("first frame", 1),
        ("light moved", 2),
        ("filter of a depth map", 2),
    ] {
        match change {
            "light moved" => {
                a_settings.light.position.x += 0.5;
                b_settings.light.position.x += 0.5;
            }
            "filter of a depth map" => {
                // B filters the same depth map differently: still one map.
                b_settings.shadow.filter = Filter::Poisson;
            }
            _ => {}
        }
        let (a_frame, _) = frame(&mut a, &a_settings);
        let (b_frame, b_drew) = frame(&mut b, &b_settings);
        assert!(!b_drew, "{change}: B reads the map A drew");
        assert_eq!(a.shadow_draws(), expected_draws, "{change}");
        assert_eq!(
            b.shadow_draws(),
            expected_draws,
            "{change}: one count for both halves"
        );
        // Each half shows exactly what a renderer of its own shows.
        assert!(a_frame == single(&gpu, &scene, &a_settings), "{change}: half A");
        assert!(b_frame == single(&gpu, &scene, &b_settings), "{change}: half B");
        // The halves differ where N(m) does: the shading, not V.
        assert!(a_frame[0] != b_frame[0], "{change}: N(m) changes the image");
        let shadowed = a_frame[1].iter().filter(|x| x[3] > 0.0 && x[0] < 0.01).count();
        assert!(shadowed > 20, "{change}: the occluder's shadow is in view");
    }

    // Shadow settings that change the map: B draws its own, A keeps its own.
    b_settings.shadow.resolution = 512;
    let (b_frame, b_drew) = frame(&mut b, &b_settings);
    assert!(b_drew);
    assert_eq!(b.shadow_draws(), 3, "B's own map");
    let (a_frame, a_drew) = frame(&mut a, &a_settings);
    assert!(!a_drew);
    assert_eq!(a.shadow_draws(), 3, "A's map is still there");
    assert!(
        a_frame == single(&gpu, &scene, &a_settings),
        "half A after B diverged"
    );
    assert!(
        b_frame == single(&gpu, &scene, &b_settings),
        "half B with its own map"
    );

    // One upload for both halves: a new scene reaches B through A.
    let plane = plane_scene(20.0);
    a.set_scene(&plane);
    let (b_frame, b_drew) = frame(&mut b, &b_settings);
    assert!(b_drew, "a new scene, a new map");
    assert!(
        b_frame == single(&gpu, &plane, &b_settings),
        "B sees the scene A uploaded"
    );
    assert!(
        b_frame[1].iter().all(|x| x[3] == 0.0 || x[0] > 0.99),
        "no occluder left"
    );
}

/// The materials' own N(m) are in the materials buffer, which the halves
/// share: each half writes its normalization's before it draws.
#[test]
fn each_half_shades_the_materials_own_m_under_its_own_normalization() {
    let gpu = gpu();
    let mut scene = occluder_scene(20.0, aabb(OCCLUDER.0, OCCLUDER.1));
    for material in &mut scene.materials {
        material.m = Some(32.0);
    }
    let (mut a_settings, mut b_settings) = split_settings();
    for s in [&mut a_settings, &mut b_settings] {
        s.material.m = 5.0;
        s.material.use_scene_materials = true;
    }
    let mut a = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let mut b = a.sharing();
    for round in 0..2 {
        let (a_frame, _) = frame(&mut a, &a_settings);
        let (b_frame, _) = frame(&mut b, &b_settings);
        assert!(
            a_frame == single(&gpu, &scene, &a_settings),
            "round {round}: half A"
        );
        assert!(
            b_frame == single(&gpu, &scene, &b_settings),
            "round {round}: half B"
        );
        assert!(
            a_frame[0] != b_frame[0],
            "round {round}: N(own m) changes the image"
        );
    }
}

#[test]
fn visibility_is_a_setting_of_its_own_and_defaults_to_the_shadow_map() {
    assert_eq!(Visibility::ALL, &[Visibility::ShadowMap, Visibility::RayTraced]);
    assert_eq!(Visibility::ShadowMap.name(), "shadow-map");
    let old =
        Settings::from_toml("[shadow]\nfilter = \"pcss\"\n").expect("a file without `visibility` loads");
    assert_eq!(old.shadow.visibility, Visibility::ShadowMap);
    assert_eq!(old.shadow.filter, Filter::Pcss);
    let written = Settings::default().to_toml();
    assert!(written.contains("visibility = \"shadow-map\""), "{written}");
    assert_eq!(Settings::from_toml(&written).unwrap(), Settings::default());
}
