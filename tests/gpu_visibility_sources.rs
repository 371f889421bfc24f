//! What each visibility source reads and honours: under ray-traced V the
//! shadow map is drawn only for the view that shows it, and the images do
//! not depend on it; an object that receives no shadows has V = 1 under both
//! sources, as in the reference.

mod common;

use lumlab::gpu::Renderer;
use lumlab::scene::Scene;
use lumlab::settings::{DebugView, Settings, Visibility};

fn ray_traced_point_light(width: u32, height: u32) -> Settings {
    let mut s = Settings::default();
    (s.image.width, s.image.height) = (width, height);
    s.shadow.visibility = Visibility::RayTraced;
    s.light.radius_m = 0.0;
    s
}

fn size(s: &Settings) -> (u32, u32) {
    (s.image.width, s.image.height)
}

#[test]
fn ray_traced_visibility_draws_no_shadow_map_and_its_images_do_not_change() {
    let gpu = common::gpu();
    let scene: Scene = lumlab::scene::default_scene();
    let mut s = ray_traced_point_light(160, 90);

    // A fresh renderer under ray-traced V: no map, not even once.
    let mut skipping = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let report = skipping.render(&s, size(&s));
    assert!(report.shadow_map_unused && !report.shadow_redrawn);
    assert!(
        report.layout.is_some(),
        "the layout is still fitted (texel density, frustum)"
    );
    let quantity = skipping.read_quantity();
    let aux = skipping.read_aux();
    let mut moved = s.clone();
    moved.light.position.x += 0.5;
    for view in [DebugView::Shaded, DebugView::TexelDensity, DebugView::Frustum] {
        moved.view.mode = view;
        let report = skipping.render(&moved, size(&moved));
        assert!(report.shadow_map_unused, "{view:?}");
    }
    assert_eq!(skipping.shadow_draws(), 0, "no view but depth reads the map");

    // The same frame from a renderer that has drawn the map first: equal
    // to the last bit, V and texel density included.
    let mut drawing = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let mut map = s.clone();
    map.shadow.visibility = Visibility::ShadowMap;
    assert!(drawing.render(&map, size(&map)).shadow_redrawn);
    let map_aux = drawing.read_aux();
    drawing.render(&s, size(&s));
    assert_eq!(drawing.read_quantity(), quantity, "radiance");
    assert_eq!(drawing.read_aux(), aux, "V, texel density, cos θ, coverage");
    let density = |a: &[[f32; 4]]| a.iter().map(|t| t[1]).collect::<Vec<_>>();
    assert_eq!(density(&aux), density(&map_aux), "texel density needs no map");
    assert!(density(&aux).iter().any(|&d| d > 0.0));

    // The depth view shows the map: under ray-traced V it is drawn, and it
    // is the shadow-map method's picture.
    s.view.mode = DebugView::Depth;
    map.view.mode = DebugView::Depth;
    let report = skipping.render(&s, size(&s));
    assert!(!report.shadow_map_unused && report.shadow_redrawn);
    assert_eq!(skipping.shadow_draws(), 1);
    drawing.render(&map, size(&map));
    assert_eq!(skipping.read_display(), drawing.read_display());
}

/// Pixels whose 3×3 neighbourhood is covered and satisfies `keep`.
fn interior(width: usize, coverage: &[f32], keep: impl Fn(usize) -> bool) -> Vec<usize> {
    let height = coverage.len() / width;
    (0..coverage.len())
        .filter(|&i| {
            let (x, y) = (i % width, i / width);
            x > 0
                && y > 0
                && x + 1 < width
                && y + 1 < height
                && (y - 1..=y + 1).all(|ny| {
                    (x - 1..=x + 1).all(|nx| {
                        let j = ny * width + nx;
                        coverage[j] > 0.0 && keep(j)
                    })
                })
        })
        .collect()
}

#[test]
fn an_object_that_receives_no_shadows_has_the_references_v_under_both_sources() {
    let gpu = common::gpu();
    let receiving = lumlab::scene::default_scene();
    let mut scene = receiving.clone();
    let ground = scene
        .objects
        .iter_mut()
        .find(|o| o.name == "ground")
        .expect("a ground");
    ground.receives_shadows = false;
    let mut s = ray_traced_point_light(240, 135);
    s.shadow.filter = lumlab::settings::Filter::None;
    let reference = |scene: &Scene| {
        use lumlab::reference::{Reference, ReferenceOptions, RenderControl};
        Reference::new(scene)
            .render(&s, &ReferenceOptions::DEFAULT, &RenderControl::default())
            .expect("reference")
    };
    let (with, without) = (reference(&receiving), reference(&scene));
    let width = s.image.width as usize;
    // Umbra that the flag takes away: shadowed with it, lit without, well
    // inside both (the ground's cast shadows, no silhouette nearby).
    let lifted = interior(width, &without.coverage, |j| {
        with.visibility[j] == 0.0 && without.visibility[j] == 1.0
    });
    // Umbra on the objects that still receive.
    let kept = interior(width, &without.coverage, |j| without.visibility[j] == 0.0);
    let pixels = without.coverage.len();
    assert!(lifted.len() > pixels / 100, "{} lifted pixels", lifted.len());
    assert!(!kept.is_empty(), "some umbra stays");
    for visibility in [Visibility::RayTraced, Visibility::ShadowMap] {
        s.shadow.visibility = visibility;
        let (_, _, aux) = common::render(&gpu, &scene, &s);
        let v = |i: usize| aux[i][0];
        let wrong_lifted = lifted.iter().filter(|&&i| v(i) != 1.0).count();
        let wrong_kept = kept.iter().filter(|&&i| v(i) != 0.0).count();
        assert_eq!(wrong_lifted, 0, "{visibility:?}: non-receiver shadowed");
        assert_eq!(wrong_kept, 0, "{visibility:?}: receivers lost their umbra");
        if visibility == Visibility::RayTraced {
            let differ = (0..pixels)
                .filter(|&i| without.coverage[i] > 0.0 && (v(i) - without.visibility[i]).abs() > 1e-6)
                .count();
            assert!(differ as f64 <= 1e-3 * pixels as f64, "{differ} pixels differ");
        }
    }
}
