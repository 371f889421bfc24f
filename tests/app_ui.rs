//! The app's panels driven through egui_kittest, rendering through the real
//! `Renderer` on the test's wgpu device: the power slider scales the
//! radiance, presets set their documented values, the probe's numbers are
//! the physics of the clicked pixel.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use glam::DVec3;
use lumlab::app::LabApp;
use lumlab::physics::{BrdfParams, brdf, radiometry};
use lumlab::presets::Preset;
use lumlab::scene::SceneScale;
use lumlab::settings::{BiasMode, Filter, Settings};
use std::sync::Arc;
use std::time::Duration;

mod app_support;
use app_support::{SIZE, click_viewport, harness, step_until, wait_for_probe};

/// Mean radiance (W/m²/sr, luminance-free: the mean of r, g, b) over the
/// pixels the scene covers (alpha 1), read back from the renderer.
fn mean_radiance(app: &LabApp) -> f64 {
    let renderer = app.renderer().expect("renderer");
    let (sum, n) = renderer
        .read_quantity()
        .iter()
        .filter(|q| q[3] > 0.0)
        .fold((0.0, 0usize), |(s, n), q| {
            (s + (q[0] + q[1] + q[2]) as f64 / 3.0, n + 1)
        });
    assert!(n > 1000, "the scene covers {n} pixels");
    sum / n as f64
}

#[test]
fn power_slider_changes_settings_and_scales_the_radiance() {
    let mut harness = harness();
    let p0 = harness.state().settings().light.power_w;
    let before = mean_radiance(harness.state());
    harness
        .get_by_role_and_label(Role::Slider, "Power Φ")
        .set_value_accesskit(2.0 * p0 as f64);
    harness.run();
    let p1 = harness.state().settings().light.power_w;
    assert!((p1 / p0 - 2.0).abs() < 1e-6, "power {p0} → {p1}");
    let after = mean_radiance(harness.state());
    let ratio = after / before;
    assert!(
        (ratio - 2.0).abs() < 1e-3,
        "radiance ratio {ratio} for a power ratio 2"
    );
}

#[test]
fn presets_set_their_documented_values() {
    let mut harness = harness();
    let mut expected = harness.state().settings().clone();
    Preset::ShadowAcne.apply(&mut expected, SceneScale::BUILT_IN);
    harness.get_by_label(Preset::ShadowAcne.title()).click();
    harness.run();
    let s = harness.state().settings();
    assert_eq!(*s, expected);
    // The values its documentation names.
    assert_eq!(
        (s.shadow.bias.mode, s.shadow.bias.depth_m),
        (BiasMode::Constant, 0.0)
    );
    assert_eq!((s.shadow.filter, s.shadow.resolution), (Filter::None, 1024));

    harness.get_by_label(Preset::Penumbra.title()).click();
    harness.run();
    let s = harness.state().settings();
    assert_eq!((s.light.radius_m, s.shadow.filter), (0.4, Filter::Pcss));
    assert_eq!(
        (s.shadow.pcss_blocker_samples, s.shadow.poisson_samples),
        (32, 32)
    );

    // Undo goes back one preset.
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().settings().shadow.filter, Filter::None);
}

#[test]
fn probe_numbers_are_the_physics_of_the_clicked_pixel() {
    let mut harness = harness();
    // Low in the middle of the viewport: the ground in front of the objects.
    click_viewport(&mut harness, 0.93);
    wait_for_probe(&mut harness);
    let app = harness.state();
    let pixel = app.probe_pixel().expect("a pixel was probed");
    let t = app.probe_terms().expect("the pixel shows the ground");
    assert_eq!(t.object, "ground");

    // The pixel's ray meets the plane y = 0 here (f64, independently of the probe).
    let s: &Settings = app.settings();
    // The camera as the viewport shows it (its shape may widen the view).
    let camera = s.camera.widened_for(pixel.size);
    let d = camera.ray_direction(
        pixel.pixel.0 as f64 + 0.5,
        pixel.pixel.1 as f64 + 0.5,
        pixel.size.0,
        pixel.size.1,
    );
    let eye = s.camera.eye.as_dvec3();
    let p = eye + d * (-eye.y / d.y);
    assert!((t.position - p).length() < 1e-9, "{} vs {p}", t.position);

    let q = s.light.position.as_dvec3();
    let inc = radiometry::incidence(p, DVec3::Y, q);
    let e = radiometry::sphere_irradiance(
        s.light.power_w as f64,
        s.light.radius_m as f64,
        inc.cos_theta,
        inc.r,
    );
    assert!((t.irradiance_w_m2 / e - 1.0).abs() < 1e-12);
    assert!((t.intensity_w_sr - radiometry::intensity(s.light.power_w as f64)).abs() < 1e-12);
    // The ground's own k and m (the default settings use the scene's materials).
    let scene = lumlab::scene::default_scene();
    let ground = scene.objects.iter().find(|o| o.name == "ground").unwrap();
    let material = scene.material_of(ground);
    assert!(s.material.use_scene_materials);
    let params = BrdfParams {
        k: material.k.unwrap_or(s.material.k) as f64,
        m: material.m.unwrap_or(s.material.m) as f64,
        norm: s.material.norm,
    };
    let f = brdf::blinn_phong(DVec3::Y, inc.l, (eye - p).normalize(), &params);
    assert!((t.brdf.diffuse - f.diffuse).abs() < 1e-15 && (t.brdf.specular - f.specular).abs() < 1e-12);

    // The GPU's radiance at that pixel agrees with f_r · E · V in f64.
    let gpu = app.probe_gpu().unwrap();
    let l_gpu = gpu.radiance.expect("the shaded view holds L");
    let l = t.unshadowed_radiance() * gpu.visibility as f64;
    for c in 0..3 {
        assert!(
            (l_gpu[c] as f64 - l[c]).abs() <= 2e-3 * l[c].abs().max(1e-3),
            "channel {c}: GPU {} vs physics {}",
            l_gpu[c],
            l[c]
        );
    }
    // The panel shows the same E, with its unit.
    let shown = format!("{} W/m²", lumlab_number(t.irradiance_w_m2));
    harness.get_by_label(&shown);
}

/// The app's number format (4 significant digits), as the probe shows it.
fn lumlab_number(x: f64) -> String {
    let decimals = (3 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
    let text = format!("{x:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// Renders the window as kittest draws it (egui + the renderer's texture).
fn render(harness: &mut Harness<'_, LabApp>) -> image::RgbaImage {
    harness.render().expect("the harness renders through wgpu")
}

/// Where the screenshots go: `LUMLAB_SCREENSHOTS=DIR`, else the target dir.
fn screenshot_dir() -> std::path::PathBuf {
    let dir = std::env::var_os("LUMLAB_SCREENSHOTS")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("app-screenshots"));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Distinct colours in a rectangle (x0, y0, x1, y1) of an image.
fn colours(image: &image::RgbaImage, r: (u32, u32, u32, u32)) -> usize {
    let mut set = std::collections::HashSet::new();
    for j in r.1..r.3 {
        for i in r.0..r.2 {
            set.insert(image.get_pixel(i, j).0);
        }
    }
    set.len()
}

#[test]
fn split_view_and_energy_panel_render() {
    let mut harness = harness();
    let dir = screenshot_dir();
    let default = render(&mut harness);
    default.save(dir.join("app-default.png")).unwrap();
    assert!(
        colours(&default, (500, 400, 800, 700)) > 50,
        "the viewport is blank"
    );

    // The lecture's figure: no normalization | approx, at a low m.
    let app = harness.state_mut();
    app.state_mut().split.enabled = true;
    app.settings_mut().material.m = 4.0;
    app.settings_mut().material.k = 0.2;
    app.settings_mut().material.use_scene_materials = false;
    harness.run();
    step_until(&mut harness, "both halves", |app| app.viewport_size().0 > 0);
    let split = render(&mut harness);
    split.save(dir.join("app-split.png")).unwrap();
    harness.get_by_label("A: norm none");
    harness.get_by_label("B: norm approx");

    // The energy panel: no normalization at m = 1 against approx, both curves.
    let app = harness.state_mut();
    Preset::EnergyGain.apply(app.settings_mut(), SceneScale::BUILT_IN);
    app.state_mut().panels.settings = false;
    harness.run();
    step_until(&mut harness, "the energy panel", |app| {
        app.viewport_size().0 > 800
    });
    harness.get_by_label("A: a(θ_i)");
    harness.get_by_label("B: a(θ_i)");
    let energy = render(&mut harness);
    energy.save(dir.join("app-energy.png")).unwrap();
}

#[test]
fn idle_frames_render_nothing() {
    let mut harness = harness();
    // Let the first frame's readbacks (scale, timings) come back.
    for _ in 0..20 {
        harness.step();
        std::thread::sleep(Duration::from_millis(20));
    }
    let before = harness.state().renders();
    assert!(before >= 1);
    harness.run_steps(10);
    assert_eq!(
        harness.state().renders(),
        before,
        "frames without a change re-rendered"
    );
    harness.state_mut().settings_mut().view.exposure_ev = 1.0;
    harness.run_steps(1);
    assert_eq!(harness.state().renders(), before + 1, "a change renders once");
    harness.run_steps(5);
    assert_eq!(harness.state().renders(), before + 1);
}

#[test]
fn tiny_and_zero_sized_windows_never_panic() {
    let mut harness = harness();
    for size in [
        egui::vec2(300.0, 200.0),
        egui::vec2(1.0, 1.0),
        egui::vec2(0.0, 0.0),
        SIZE,
    ] {
        harness.set_size(size);
        harness.run_steps(3);
    }
    // Panels hidden (F9), then back: the viewport follows.
    harness.key_press(egui::Key::F9);
    harness.run_steps(2);
    let wide = harness.state().viewport_size();
    assert!(wide.0 > 1200, "without panels the image is {wide:?}");
    harness.key_press(egui::Key::F9);
    harness.run_steps(2);
    assert!(
        harness.state().viewport_size().0 < wide.0,
        "{:?} {:?}",
        harness.state().viewport_size(),
        harness.state_mut().state_mut().panels
    );
}

#[test]
fn settings_file_round_trip_and_reset_everything() {
    let mut harness = harness();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lab.toml");
    harness.state_mut().state_mut().paths.settings_file = path.display().to_string();
    harness.state_mut().settings_mut().light.power_w = 123.0;
    // Tall enough that the Files section is not scrolled out of view.
    harness.set_size(egui::vec2(1280.0, 2400.0));
    harness.get_by_label("Files").click();
    harness.run();
    harness.get_by_label("Save (Ctrl+S)").click_accesskit();
    harness.run();
    let saved = Settings::load(&path).expect("the app wrote a valid settings file");
    assert_eq!(saved.light.power_w, 123.0);
    assert_eq!(&saved, harness.state().settings());

    harness.state_mut().settings_mut().light.power_w = 5.0;
    harness.get_by_label("Load").click_accesskit();
    harness.run();
    assert_eq!(harness.state().settings().light.power_w, 123.0);

    harness.get_by_label("Reset everything").click_accesskit();
    harness.run();
    assert_eq!(*harness.state().settings(), Settings::default());
    // Let the change settle into the undo stack, then bring it back.
    harness.run_steps(3);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().settings().light.power_w, 123.0);
}

/// Presses at `from`, moves to `to` in a few steps, releases, with `modifiers` held.
fn drag(harness: &mut Harness<'_, LabApp>, from: egui::Pos2, to: egui::Pos2, modifiers: egui::Modifiers) {
    use egui::{Event, PointerButton};
    harness.event(Event::PointerMoved(from));
    harness.step();
    harness.event(Event::PointerButton {
        pos: from,
        button: PointerButton::Primary,
        pressed: true,
        modifiers,
    });
    harness.step();
    for k in 1..=5 {
        harness.event_modifiers(
            Event::PointerMoved(from + (to - from) * (k as f32 / 5.0)),
            modifiers,
        );
        harness.step();
    }
    harness.event(Event::PointerButton {
        pos: to,
        button: PointerButton::Primary,
        pressed: false,
        modifiers,
    });
    harness.step();
}

#[test]
fn dragging_orbits_scrolling_zooms_and_the_light_follows_its_gizmo() {
    let mut harness = harness();
    let rect = harness.state().viewport_rect();
    let c0 = harness.state().settings().camera;
    let r0 = (c0.eye - c0.target).length();
    drag(
        &mut harness,
        rect.center(),
        rect.center() + egui::vec2(80.0, 0.0),
        egui::Modifiers::NONE,
    );
    let c1 = harness.state().settings().camera;
    assert_ne!(c1.eye, c0.eye, "a drag orbits");
    assert_eq!(c1.target, c0.target);
    assert!(((c1.eye - c1.target).length() - r0).abs() < 1e-3);

    harness.event(egui::Event::PointerMoved(rect.center()));
    harness.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, 120.0),
        phase: egui::TouchPhase::Move,
        modifiers: egui::Modifiers::NONE,
        source: egui::MouseWheelSource::Wheel,
    });
    harness.run_steps(4);
    let c2 = harness.state().settings().camera;
    assert!(
        (c2.eye - c2.target).length() < (c1.eye - c1.target).length(),
        "wheel up zooms in"
    );

    // Put the light in view, find its gizmo, drag it parallel to the image.
    harness.key_press(egui::Key::R);
    harness.state_mut().settings_mut().light.position = glam::Vec3::new(-1.5, 2.0, 2.0);
    harness.run_steps(2);
    let s = harness.state().settings().clone();
    let size = harness.state().viewport_size();
    let camera = s.camera.widened_for(size);
    // Project by intersecting pixel rays: find the pixel whose ray passes the light.
    let to_light = (s.light.position - s.camera.eye).as_dvec3().normalize();
    let f = camera.frame();
    let t = camera.tan_half_fovy();
    let aspect = size.0 as f64 / size.1 as f64;
    let depth = to_light.dot(f.forward);
    let sx = to_light.dot(f.right) / depth / (t * aspect);
    let sy = to_light.dot(f.up) / depth / t;
    let px = egui::vec2(
        ((sx + 1.0) * 0.5 * size.0 as f64) as f32,
        ((1.0 - sy) * 0.5 * size.1 as f64) as f32,
    );
    let gizmo = rect.min + px;
    drag(
        &mut harness,
        gizmo,
        gizmo + egui::vec2(60.0, 0.0),
        egui::Modifiers::NONE,
    );
    let moved = harness.state().settings().light.position;
    assert!(
        (moved - s.light.position).length() > 0.1,
        "the light moved: {moved}"
    );
    assert_eq!(
        harness.state().settings().camera,
        s.camera,
        "dragging the light does not orbit"
    );
    let along_right = (moved - s.light.position).as_dvec3().normalize().dot(f.right);
    assert!(
        along_right > 0.99,
        "moved along the image's x axis ({along_right})"
    );
}

#[test]
fn exr_export_and_a_bad_scene_file() {
    let mut harness = harness();
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("l.exr");
    harness.state_mut().state_mut().paths.exr_file = exr.display().to_string();
    harness.state_mut().state_mut().paths.scene_file = dir.path().join("missing.glb").display().to_string();
    harness.set_size(egui::vec2(1280.0, 2400.0));
    harness.run();
    harness.get_by_label("Files").click_accesskit();
    harness.run();
    harness.get_by_label("Export EXR").click_accesskit();
    harness.run();
    let image = image::open(&exr).expect("an EXR was written").to_rgba32f();
    let (w, h) = image.dimensions();
    assert!(w > 100 && h == harness.state().viewport_size().1, "{w}×{h}");
    assert!(image.pixels().any(|p| p.0[0] > 0.0), "radiance, not black");

    let before = harness.state().settings().clone();
    harness.get_by_label("Open scene").click_accesskit();
    for _ in 0..100 {
        harness.step();
        if harness
            .query_all_by_label_contains("the current scene is kept")
            .next()
            .is_some()
        {
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    // The status line and the error toast (shown from the next frame) both
    // say so, naming the file.
    harness.run();
    let messages: Vec<String> = harness
        .get_all_by_label_contains("the current scene is kept")
        .filter_map(|n| n.accesskit_node().value())
        .collect();
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(messages.iter().all(|m| m.contains("missing.glb")), "{messages:?}");
    assert_eq!(*harness.state().settings(), before);
}

/// Runs the reference job to its end (F5), failing after a while.
fn compute_reference(harness: &mut Harness<'_, LabApp>) {
    assert!(!harness.state().has_reference());
    harness.key_press(egui::Key::F5);
    for _ in 0..3000 {
        harness.step();
        if harness.state().has_reference() && !harness.state().reference_running() {
            return;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    panic!("the reference never finished");
}

#[test]
fn a_reference_job_feeds_the_error_view_and_its_rmse() {
    use lumlab::settings::DebugView;
    let mut harness = harness();
    // A stand-in reference on the job's thread: black everywhere, fully visible,
    // so that the error is the GPU's own luminance.
    harness.state_mut().set_reference_fn(Arc::new(
        |_scene: &lumlab::scene::Scene, s: &Settings, control: &lumlab::reference::RenderControl| {
            let n = (s.image.width * s.image.height) as usize;
            control.pixels_done.store(n, std::sync::atomic::Ordering::Relaxed);
            Ok(lumlab::gpu::ComparisonImage {
                width: s.image.width,
                height: s.image.height,
                texels: vec![[0.0, 0.0, 0.0, 1.0]; n],
            })
        },
    ));
    compute_reference(&mut harness);
    harness.state_mut().settings_mut().view.mode = DebugView::Error;
    harness.run();
    step_until(&mut harness, "the error statistics", |app| {
        app.error_stats().is_some()
    });
    let stats = harness.state().error_stats().unwrap();

    let renderer = harness.state().renderer().unwrap();
    let (sum2, n) = renderer
        .read_quantity()
        .iter()
        .filter(|q| q[3] > 0.0)
        .fold((0.0, 0), |(s, n), q| {
            let y = 0.2126 * q[0] as f64 + 0.7152 * q[1] as f64 + 0.0722 * q[2] as f64;
            (s + y * y, n + 1)
        });
    assert_eq!(stats.pixels, n);
    assert!(
        (stats.rmse / (sum2 / n as f64).sqrt() - 1.0).abs() < 1e-9,
        "{stats:?}"
    );
    harness.get_by_label("RMSE");
    harness.get_by_label_contains("RMSE = ");

    // Moving the light makes the reference stale, and says so.
    harness.state_mut().settings_mut().light.position.x += 1.0;
    harness.run();
    assert_eq!(
        harness.query_all_by_label_contains("STALE").count(),
        2,
        "panel and image say so"
    );
}

#[test]
fn the_cpu_reference_job_agrees_with_the_gpu_without_shadows() {
    use lumlab::settings::DebugView;
    let mut harness = harness();
    harness.state_mut().settings_mut().shadow.enabled = false;
    harness.run();
    compute_reference(&mut harness);
    harness.state_mut().settings_mut().view.mode = DebugView::Error;
    harness.run();
    step_until(&mut harness, "the error statistics", |app| {
        app.error_stats().is_some()
    });
    let stats = harness.state().error_stats().unwrap();
    // Same camera, light and BRDF: f32 against f64 rounding, and a few
    // pixels on a box's edge whose centre raster and ray give to different
    // faces (tests/reference_gpu.rs checks every pixel on a fixed view).
    assert!(stats.pixels > 1000, "{stats:?}");
    let squared_sum = stats.rmse.powi(2) * stats.pixels as f64;
    assert!(
        squared_sum <= 4.0 * stats.max_abs.powi(2),
        "more than a few edge pixels differ: {stats:?}"
    );
    assert!(stats.relative < 5e-3, "{stats:?}");

    // With shadows, the probe's ray-traced L is its own terms recombined:
    // c · light colour · E · f_r · V (a point light).
    harness.state_mut().settings_mut().shadow.enabled = true;
    harness.state_mut().settings_mut().view.mode = DebugView::Shaded;
    harness.run();
    click_viewport(&mut harness, 0.7);
    wait_for_probe(&mut harness);
    render(&mut harness)
        .save(screenshot_dir().join("app-probe.png"))
        .unwrap();
    let t = harness.state().probe_terms().expect("a surface").clone();
    assert!((0.0..=1.0).contains(&t.visibility));
    let l = t.unshadowed_radiance() * t.visibility;
    assert!(
        (t.radiance - l).abs().max_element() <= 1e-12 * l.max_element().max(1e-12),
        "{} vs {l}",
        t.radiance
    );
}
