//! The GPU renderer against known values: the f64 physics on unshadowed
//! pixels, exact umbrae, the acne lesson, filters bounded, the shadow map
//! reused when nothing changed. Runs on the software adapter in CI.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use lumlab::physics::{BrdfParams, Normalization, brdf, radiometry};
use lumlab::settings::{BiasMode, DebugView, Filter, Settings};

/// L (W/m²/sr) on the white plane y = 0 at `p`, seen from `eye`, unshadowed, in f64.
fn expected_radiance(s: &Settings, p: DVec3) -> f64 {
    let n = DVec3::Y;
    let q = s.light.position.as_dvec3();
    let o = (s.camera.eye.as_dvec3() - p).normalize();
    let inc = radiometry::incidence(p, n, q);
    let e = radiometry::sphere_irradiance(
        s.light.power_w as f64,
        s.light.radius_m as f64,
        inc.cos_theta,
        inc.r,
    );
    let params = BrdfParams {
        k: s.material.k as f64,
        m: s.material.m as f64,
        norm: s.material.norm,
    };
    brdf::blinn_phong(n, inc.l, o, &params).total() * e
}

/// Points the camera at the mirror point of the light on the plane, so the
/// highlight is in view.
fn look_at_highlight(s: &mut Settings, eye: Vec3) {
    let q = s.light.position;
    let t = eye.y / (eye.y + q.y);
    let mirror = eye + (Vec3::new(q.x, -q.y, q.z) - eye) * t;
    s.camera.eye = eye;
    s.camera.target = mirror;
}

#[test]
fn unshadowed_pixels_equal_the_f64_physics() {
    let gpu = gpu();
    let mut worst = 0.0_f64;
    let scene = fine_plane_scene(40.0);
    // The same plane whose material carries k and m itself: its N(m) comes
    // from the material's table, the settings' from the globals.
    let mut own = fine_plane_scene(40.0);
    let setups = [
        (Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 2.0, 3.0)),
        (Vec3::new(1.0, 4.0, -2.0), Vec3::new(-1.0, 3.0, 4.0)),
        (Vec3::new(5.0, 1.5, 0.0), Vec3::new(-2.0, 1.0, 1.0)),
    ];
    for (light, eye) in setups {
        for m in [1.0, 64.0, 1e4, 1e6] {
            for (k, norm) in [(0.5, Normalization::Exact), (0.0, Normalization::Approx)] {
                let mut s = settings(96, 64);
                s.shadow.enabled = false;
                s.light.position = light;
                s.material.k = k;
                s.material.m = m;
                s.material.norm = norm;
                // Sharp lobes need a narrow view for their highlight to span pixels.
                s.camera.fovy_deg = (300.0 / m.sqrt()).clamp(1.0, 45.0);
                look_at_highlight(&mut s, eye);
                let (_, quantity, aux) = render(&gpu, &scene, &s);
                (own.materials[0].k, own.materials[0].m) = (Some(k), Some(m));
                let mut global = s.clone();
                (global.material.k, global.material.m) = (0.3, 5.0);
                global.material.use_scene_materials = true;
                let (_, own_quantity, _) = render(&gpu, &own, &global);
                assert!(
                    own_quantity == quantity,
                    "m={m} k={k} {norm:?}: the material's own m shades alike"
                );
                let expected: Vec<Option<f64>> = (0..s.image.height)
                    .flat_map(|j| (0..s.image.width).map(move |i| (i, j)))
                    .map(|(i, j)| plane_hit(&s, i, j).map(|p| expected_radiance(&s, p)))
                    .collect();
                let peak = expected.iter().flatten().copied().fold(0.0, f64::max);
                // With k > 0 every lit pixel; for the lobe alone, those not
                // lost to f32 underflow far from the highlight.
                let floor = if k > 0.0 { 0.0 } else { (1e-3 * peak).max(1e-30) };
                let mut checked = 0;
                for (idx, e) in expected.iter().enumerate() {
                    let Some(e) = *e else { continue };
                    if aux[idx][3] == 0.0 || e <= floor {
                        continue;
                    }
                    let got = quantity[idx][0] as f64;
                    worst = worst.max((got / e - 1.0).abs());
                    // 1e-3 of L at the pixel centre, or at a point the
                    // rasterizer's sub-pixel grid may have put it on.
                    let (x, y) = (idx as u32 % s.image.width, idx as u32 / s.image.width);
                    let (low, high) = subpixel_range(x as f64 + 0.5, y as f64 + 0.5, |x, y| {
                        plane_hit_at(&s, x, y).map_or(e, |p| expected_radiance(&s, p))
                    });
                    assert!(
                        got >= low * (1.0 - 1e-3) && got <= high * (1.0 + 1e-3),
                        "light {light} eye {eye} m={m} k={k}: pixel {idx}: GPU {got} vs f64 {e} \
                         ({low} … {high} within {SUBPIXEL_PX} px)"
                    );
                    checked += 1;
                }
                assert!(
                    checked > if k > 0.0 { 3000 } else { 10 },
                    "m={m} k={k}: only {checked} pixels compared"
                );
            }
        }
    }
    eprintln!("largest relative difference GPU vs f64: {worst:.2e}");
}

/// Seen from below (the light below too), a double-sided plane shades as
/// its top does in the mirrored view, and a one-sided one reflects nothing
/// (the material's flags as the vertex stage reads them).
#[test]
fn only_a_double_sided_plane_reflects_from_below() {
    let gpu = gpu();
    let mut s = settings(96, 64);
    s.shadow.enabled = false;
    s.material.use_scene_materials = true;
    (s.light.position, s.camera.eye) = (Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, -2.0, 3.0));
    s.camera.target = Vec3::ZERO;
    let mut mirrored = s.clone();
    mirrored.light.position.y = 1.0;
    mirrored.camera.eye.y = 2.0;
    for double_sided in [false, true] {
        let mut scene = fine_plane_scene(40.0);
        scene.materials[0].double_sided = double_sided;
        let (_, quantity, _) = render(&gpu, &scene, &s);
        let mut checked = 0;
        for (idx, q) in quantity.iter().enumerate() {
            let (x, y) = (
                (idx as u32 % s.image.width) as f64 + 0.5,
                (idx as u32 / s.image.width) as f64 + 0.5,
            );
            let Some(p) = plane_hit_at(&s, x, y) else { continue };
            let got = q[0] as f64;
            if !double_sided {
                assert_eq!(got, 0.0, "one-sided, pixel {idx}: {got}");
            } else {
                let (low, high) = subpixel_range(x, y, |x, y| {
                    plane_hit_at(&s, x, y).map_or(0.0, |p| expected_radiance(&mirrored, p))
                });
                assert!(
                    got >= low * (1.0 - 1e-3) && got <= high * (1.0 + 1e-3) && got > 0.0,
                    "double-sided, pixel {idx} at {p}: GPU {got} vs f64 {low} … {high}"
                );
            }
            checked += 1;
        }
        assert!(checked > 3000, "only {checked} pixels compared");
    }
}

fn occluder_settings() -> Settings {
    let mut s = settings(160, 120);
    s.light.position = Vec3::new(0.0, 4.0, 0.0);
    // Below the occluder, so the ground under it is in view.
    s.camera.eye = Vec3::new(0.0, 1.0, 4.0);
    s.camera.target = Vec3::new(0.0, 0.0, -0.5);
    s.camera.fovy_deg = 60.0;
    s.material.k = 1.0;
    s.shadow.resolution = 1024;
    s
}

const OCCLUDER: ([f32; 3], [f32; 3]) = ([-0.5, 1.5, -0.5], [0.5, 1.55, 0.5]);

#[test]
fn umbra_is_black_and_lit_ground_is_analytic() {
    let gpu = gpu();
    let occluder = aabb(OCCLUDER.0, OCCLUDER.1);
    let scene = occluder_scene(20.0, occluder);
    let s = occluder_settings();
    let (_, quantity, aux) = render(&gpu, &scene, &s);
    let (mut umbra, mut lit) = (0, 0);
    let q = s.light.position.as_dvec3();
    for j in 0..s.image.height {
        for i in 0..s.image.width {
            let idx = (j * s.image.width + i) as usize;
            let Some(p) = plane_hit(&s, i, j) else { continue };
            // Seen from above, the occluder hides part of the ground: skip
            // pixels that do not see the ground.
            if segment_hits_box(s.camera.eye.as_dvec3(), p, &occluder) || aux[idx][3] == 0.0 {
                continue;
            }
            // The shadow's edge lies at |x| = 0.5 × 4 / 2.5 = 0.8 m; stay 0.1 m clear of it.
            let edge = p.x.abs().max(p.z.abs());
            if edge < 0.7 {
                assert_eq!(quantity[idx][0], 0.0, "umbra pixel ({i},{j}) at {p}");
                umbra += 1;
            } else if edge > 0.9 {
                let e = expected_radiance(&s, p);
                let got = quantity[idx][0] as f64;
                assert!((got / e - 1.0).abs() < 1e-3, "lit pixel ({i},{j}): {got} vs {e}");
                assert!(!segment_hits_box(p, q, &occluder));
                lit += 1;
            }
        }
    }
    assert!(umbra > 200 && lit > 1000, "umbra {umbra}, lit {lit}");
}

/// Pixels strictly inside the penumbra (0.02 < V < 0.98).
fn penumbra_pixels(aux: &[[f32; 4]]) -> usize {
    aux.iter()
        .filter(|a| a[3] > 0.0 && a[0] > 0.02 && a[0] < 0.98)
        .count()
}

#[test]
fn pcf_penumbra_widens_with_the_kernel() {
    let gpu = gpu();
    let scene = occluder_scene(20.0, aabb(OCCLUDER.0, OCCLUDER.1));
    let mut s = occluder_settings();
    s.shadow.resolution = 256;
    s.shadow.filter = Filter::Pcf;
    let widths: Vec<usize> = [3, 5, 7, 9]
        .iter()
        .map(|&n| {
            s.shadow.pcf_size = n;
            penumbra_pixels(&render(&gpu, &scene, &s).2)
        })
        .collect();
    assert!(widths.windows(2).all(|w| w[1] > w[0]), "{widths:?}");
}

/// Light at 80° from the plane's normal (far away, so the angle barely
/// varies), a post casting a long shadow; returns (shadowed truly-lit pixels,
/// truly-lit pixels) for the given filter and bias.
fn acne_at_80_degrees(gpu: &lumlab::gpu::GpuContext, filter: Filter, bias: &str) -> (usize, usize) {
    let post = aabb([-0.1, 0.0, -0.1], [0.1, 0.6, 0.1]);
    let scene = occluder_scene(12.0, post);
    let mut s = settings(200, 150);
    let angle = 80f32.to_radians();
    s.light.position = Vec3::new(100.0 * angle.sin(), 100.0 * angle.cos(), 0.0);
    s.light.power_w = 4e5;
    s.camera.eye = Vec3::new(-1.0, 5.0, 5.0);
    s.camera.target = Vec3::new(-1.5, 0.0, 0.0);
    s.shadow.resolution = 1024;
    s.shadow.filter = filter;
    s.shadow.bias = s.shadow.bias.parse_onto(bias).unwrap();
    let (_, _, aux) = render(gpu, &scene, &s);
    let (mut wrong, mut lit) = (0, 0);
    let q = s.light.position.as_dvec3();
    for j in 0..s.image.height {
        for i in 0..s.image.width {
            let idx = (j * s.image.width + i) as usize;
            let Some(p) = plane_hit(&s, i, j) else { continue };
            if aux[idx][3] == 0.0
                || p.x.abs() > 6.0
                || p.z.abs() > 6.0
                || segment_hits_box(s.camera.eye.as_dvec3(), p, &post)
                || segment_hits_box(p, q, &post)
            {
                continue;
            }
            lit += 1;
            if aux[idx][0] < 0.5 {
                wrong += 1;
            }
        }
    }
    (wrong, lit)
}

#[test]
fn auto_bias_removes_acne_that_zero_bias_shows() {
    let gpu = gpu();
    for filter in [Filter::None, Filter::Pcf] {
        let (wrong, lit) = acne_at_80_degrees(&gpu, filter, "auto");
        assert!(lit > 10_000, "{lit}");
        assert!(
            (wrong as f64) < 0.001 * lit as f64,
            "{filter} auto: {wrong} of {lit} lit pixels shadowed"
        );
        let (acne, lit) = acne_at_80_degrees(&gpu, filter, "constant:0");
        assert!(
            (acne as f64) > 0.05 * lit as f64,
            "{filter} no bias: only {acne} of {lit} show acne"
        );
    }
}

#[test]
fn every_filter_and_bias_keeps_visibility_in_the_unit_interval() {
    let gpu = gpu();
    let scene = occluder_scene(20.0, aabb(OCCLUDER.0, OCCLUDER.1));
    let mut s = occluder_settings();
    s.light.radius_m = 0.3;
    for &filter in Filter::ALL {
        for bias in ["auto", "constant:0.01", "slope:0.005,2", "normal:1.5"] {
            s.shadow.filter = filter;
            s.shadow.bias = s.shadow.bias.parse_onto(bias).unwrap();
            let (_, _, aux) = render(&gpu, &scene, &s);
            let covered: Vec<f32> = aux.iter().filter(|a| a[3] > 0.0).map(|a| a[0]).collect();
            let outside: Vec<f32> = covered
                .iter()
                .copied()
                .filter(|v| !(0.0..=1.0).contains(v))
                .take(5)
                .collect();
            assert!(outside.is_empty(), "{filter} {bias}: V = {outside:?}");
            assert!(
                covered.iter().any(|&v| v < 0.01),
                "{filter} {bias}: no shadow at all"
            );
            assert!(
                covered.iter().any(|&v| v > 0.99),
                "{filter} {bias}: no light at all"
            );
        }
    }
}

#[test]
fn resolution_beyond_the_device_is_clamped_and_said() {
    let gpu = gpu();
    let mut s = occluder_settings();
    s.shadow.resolution = 65536;
    let (report, _, _) = render(&gpu, &plane_scene(10.0), &s);
    let max = gpu.device.limits().max_texture_dimension_2d;
    assert!(
        report.resolution <= max && report.resolution >= 256,
        "{}",
        report.resolution
    );
    let note = report.resolution_note.expect("the clamp is reported");
    assert!(note.contains("65536"), "{note}");
}

#[test]
fn shadow_map_is_redrawn_only_when_light_geometry_or_shadow_settings_change() {
    let gpu = gpu();
    let scene = occluder_scene(20.0, aabb(OCCLUDER.0, OCCLUDER.1));
    let mut renderer = lumlab::gpu::Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let mut s = occluder_settings();
    let size = (64, 48);
    assert!(
        renderer.render(&s, size).shadow_redrawn,
        "first frame draws the map"
    );
    assert!(!renderer.render(&s, size).shadow_redrawn, "nothing changed");
    s.material.m = 8.0;
    s.view.exposure_ev = 1.0;
    s.view.mode = DebugView::Visibility;
    assert!(
        !renderer.render(&s, size).shadow_redrawn,
        "material and view do not touch the map"
    );
    s.shadow.filter = Filter::Poisson;
    assert!(
        !renderer.render(&s, size).shadow_redrawn,
        "a depth filter reuses the depth map"
    );
    s.light.position.x += 0.1;
    assert!(renderer.render(&s, size).shadow_redrawn, "the light moved");
    s.shadow.bias.mode = BiasMode::Slope;
    assert!(
        !renderer.render(&s, size).shadow_redrawn,
        "bias is applied in the camera pass"
    );
    s.shadow.resolution = 512;
    assert!(renderer.render(&s, size).shadow_redrawn, "resolution changed");
    s.shadow.filter = Filter::Vsm;
    assert!(renderer.render(&s, size).shadow_redrawn, "moments needed");
    renderer.set_scene(&plane_scene(20.0));
    assert!(renderer.render(&s, size).shadow_redrawn, "geometry changed");
}

#[test]
fn the_map_from_before_a_drag_is_used_again_at_its_end() {
    let gpu = gpu();
    let scene = occluder_scene(20.0, aabb(OCCLUDER.0, OCCLUDER.1));
    let renderer = || lumlab::gpu::Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let mut renderer_a = renderer();
    let mut s = occluder_settings();
    s.shadow.resolution = 1024;
    let size = (64, 48);
    assert!(renderer_a.render(&s, size).shadow_redrawn);
    let before = renderer_a.read_quantity();
    // A drag draws a smaller map (the camera turns, the light stays).
    let mut drag = s.clone();
    drag.shadow.resolution = 256;
    drag.camera.eye.x += 0.1;
    assert!(
        renderer_a.render(&drag, (16, 12)).shadow_redrawn,
        "the drag's map"
    );
    assert!(
        !renderer_a.render(&s, size).shadow_redrawn,
        "the map from before the drag"
    );
    assert!(renderer_a.read_quantity() == before, "the same pixels");
    // A drag that moves the light: the map is drawn again, into textures kept.
    drag.light.position.x += 0.1;
    assert!(renderer_a.render(&drag, (16, 12)).shadow_redrawn);
    s.light.position.x += 0.1;
    assert!(renderer_a.render(&s, size).shadow_redrawn, "the light moved");
    let mut never_dragged = renderer();
    never_dragged.render(&s, size);
    assert!(renderer_a.read_quantity() == never_dragged.read_quantity());
}

#[test]
fn light_among_the_geometry_uses_only_the_cube_faces_that_see_it() {
    let gpu = gpu();
    let scene = occluder_scene(20.0, aabb([2.0, 0.0, -0.5], [3.0, 1.0, 0.5]));
    let mut s = occluder_settings();
    s.light.position = Vec3::new(0.0, 0.5, 0.0);
    let (report, _, aux) = render(&gpu, &scene, &s);
    let layout = report.layout.expect("shadows on");
    assert_eq!(layout.kind, lumlab::gpu::light_frustum::LayoutKind::Cube);
    assert!(layout.layers[3].active, "−Y sees the ground");
    assert!(!layout.layers[2].active, "+Y sees nothing");
    // The box at +X shadows the ground behind it.
    assert!(aux.iter().any(|a| a[3] > 0.0 && a[0] < 0.01));
}
