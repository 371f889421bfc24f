//! What each visibility source reads and honours: under ray-traced V the
//! shadow map is drawn only for the view that shows it, and the images do
//! not depend on it.

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
