//! The camera pass specialised per view × filter × bias × map layout, and
//! under ray-traced V per light and accumulation (one pipeline each, the
//! other cases compiled away) gives the pixels of the generic pipeline that
//! branches on the uniforms, and the pipeline without the aux target gives
//! the same quantity and displayed image. Every specialisation is compiled
//! and drawn; one compiled ahead, on a thread of its own, draws the same. Tests elsewhere hold the (specialised) renderer to the f64
//! physics and the CPU reference.

mod common;

use common::*;
use lumlab::gpu::light_frustum::LayoutKind;
use lumlab::gpu::{Capabilities, Renderer, ShadeOptions};
use lumlab::settings::{BiasMode, DebugView, Filter, Visibility};

/// Largest |a − b| / max(1, |b|) over every channel: the targets are
/// half floats (relative step 2⁻¹¹), so equal shading agrees to a few of those.
fn worst_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| (0..4).map(move |c| (x[c] as f64, y[c] as f64)))
        .map(|(x, y)| (x - y).abs() / y.abs().max(1.0))
        .fold(0.0, f64::max)
}

/// A renderer running the generic pipeline on the default scene, and one
/// sharing its shadow maps (the same V inputs) for the specialised ones.
fn generic_and_specialised() -> (Renderer, Renderer) {
    generic_and_specialised_into(None)
}

/// The same, drawing into targets of `format` where given (Rgba16Float:
/// as GL's fallback does on llvmpipe), else the adapter's.
fn generic_and_specialised_into(format: Option<wgpu::TextureFormat>) -> (Renderer, Renderer) {
    let gpu = gpu();
    let scene = lumlab::scene::default_scene();
    let mut caps = Capabilities::of(&gpu.adapter, &gpu.device);
    caps.hdr_format = format.unwrap_or(caps.hdr_format);
    let mut generic = Renderer::with_capabilities(&gpu.device, &gpu.queue, caps, &scene);
    generic.set_shade_options(ShadeOptions {
        specialised: false,
        ..ShadeOptions::default()
    });
    let specialised = generic.sharing();
    (generic, specialised)
}

#[test]
fn every_view_and_filter_specialisation_matches_the_generic_pipeline() {
    let (mut generic, mut specialised) = generic_and_specialised();
    let size = (64, 48);
    // Every filter with shadows on, and shadows off (one pipeline for all filters).
    let cases = Filter::ALL
        .iter()
        .map(|&f| (f, true))
        .chain([(Filter::Pcf, false)]);
    for (filter, shadows) in cases {
        let mut shaded_views = Vec::new();
        for &view in DebugView::ALL {
            let mut s = lumlab::settings::Settings::default();
            s.shadow.enabled = shadows;
            s.shadow.filter = filter;
            s.light.radius_m = 0.2;
            s.view.mode = view;
            generic.render(&s, size);
            let (q0, a0) = (generic.read_quantity(), generic.read_aux());
            specialised.set_shade_options(ShadeOptions::default());
            specialised.render(&s, size);
            let (q1, a1) = (specialised.read_quantity(), specialised.read_aux());
            let what = format!("{filter}{} × {view}", if shadows { "" } else { ", shadows off" });
            assert!(a0.iter().any(|t| t[3] > 0.0), "{what}: the scene is in view");
            assert!(worst_difference(&q1, &q0) < 2e-3, "{what}: quantity");
            assert!(worst_difference(&a1, &a0) < 2e-3, "{what}: aux");
            let display = specialised.read_display();
            // As the app's interaction frames draw it (no aux target, no
            // depth pre-pass): the same quantity and the same image.
            specialised.set_shade_options(ShadeOptions::INTERACTION);
            specialised.render(&s, size);
            assert!(
                worst_difference(&specialised.read_quantity(), &q1) < 2e-3,
                "{what}: no aux, no pre-pass"
            );
            assert!(
                specialised.read_display() == display,
                "{what}: displayed without aux and pre-pass"
            );
            shaded_views.push(q0);
        }
        // The views differ: a pipeline that ignored its view would not pass.
        let distinct = (1..shaded_views.len())
            .filter(|&i| worst_difference(&shaded_views[i], &shaded_views[0]) > 1e-2)
            .count();
        assert!(
            distinct >= 6,
            "{filter}: only {distinct} views differ from shaded"
        );
    }
}

#[test]
fn every_bias_mode_and_map_layout_specialisation_matches_the_generic_pipeline() {
    let (mut generic, mut specialised) = generic_and_specialised();
    let size = (64, 48);
    // The light high above the scene: one fitted frustum; at its default
    // height (the ground seen wider than a frustum takes): six cube faces.
    for (light_y_m, layout) in [(40.0, LayoutKind::Single), (6.0, LayoutKind::Cube)] {
        // PCF's taps go through tap() and the per-tap bias; hw2x2 through its own bias.
        for filter in [Filter::Pcf, Filter::Hw2x2] {
            for &bias in BiasMode::ALL {
                let mut s = lumlab::settings::Settings::default();
                s.light.position.y = light_y_m;
                s.shadow.filter = filter;
                s.shadow.bias.mode = bias;
                let report = generic.render(&s, size);
                let what = format!("{filter}, bias {bias:?}, {layout:?} map");
                assert_eq!(report.layout.map(|l| l.kind), Some(layout), "{what}");
                let (q0, a0) = (generic.read_quantity(), generic.read_aux());
                specialised.set_shade_options(ShadeOptions::default());
                specialised.render(&s, size);
                let (q1, a1) = (specialised.read_quantity(), specialised.read_aux());
                assert!(a0.iter().any(|t| t[3] > 0.0), "{what}: the scene is in view");
                assert!(a0.iter().any(|t| t[3] > 0.0 && t[0] < 0.5), "{what}: some shadow");
                assert!(worst_difference(&q1, &q0) < 2e-3, "{what}: quantity");
                assert!(worst_difference(&a1, &a0) < 2e-3, "{what}: aux");
            }
        }
    }
}

/// Under ray-traced V the pipeline is also specialised to the light (a
/// point or a sphere) and to the frame (starting the mean or folding in the
/// frames before): each gives the generic pipeline's pixels, frame after
/// frame (the same random numbers: both renderers count their frames alike),
/// into the adapter's targets and into f16 ones (whose mean is kept in f32
/// after the camera pass, gpu::accumulate).
#[test]
fn every_ray_traced_specialisation_matches_the_generic_pipeline() {
    for format in [None, Some(wgpu::TextureFormat::Rgba16Float)] {
        ray_traced_specialisations_match_the_generic_pipeline(format);
    }
}

fn ray_traced_specialisations_match_the_generic_pipeline(format: Option<wgpu::TextureFormat>) {
    let (mut generic, mut specialised) = generic_and_specialised_into(format);
    specialised.set_shade_options(ShadeOptions::default());
    let size = (64, 48);
    // A sphere light's rays one at a time (one a pixel), four to a walk or
    // eight (12 rays: a last walk half empty).
    for (radius_m, samples) in [(0.0, 1), (0.3, 1), (0.3, 4), (0.3, 6), (0.3, 12)] {
        let mut s = lumlab::settings::Settings::default();
        s.shadow.visibility = Visibility::RayTraced;
        s.light.radius_m = radius_m;
        s.shadow.rt_light_samples = samples;
        for frame in 1..=3 {
            generic.render(&s, size);
            specialised.render(&s, size);
            let what = format!("{format:?}: R = {radius_m} m, {samples} rays a pixel, frame {frame}");
            let (a0, a1) = (generic.read_aux(), specialised.read_aux());
            assert!(a0.iter().any(|t| t[3] > 0.0 && t[0] < 0.5), "{what}: some shadow");
            let (q0, q1) = (generic.read_quantity(), specialised.read_quantity());
            assert!(worst_difference(&q1, &q0) < 2e-3, "{what}: quantity");
            assert!(worst_difference(&a1, &a0) < 2e-3, "{what}: aux");
            let frames = if radius_m > 0.0 { frame } else { 1 };
            assert_eq!(
                specialised.accumulation().map(|a| a.frames),
                Some(frames),
                "{what}"
            );
        }
    }
}

#[test]
fn a_pipeline_compiled_ahead_draws_what_one_compiled_when_needed_draws() {
    let gpu = gpu();
    let scene = lumlab::scene::default_scene();
    // A drag's frames, after a full frame (as the app draws them).
    let drag = ShadeOptions::INTERACTION;
    let settings = lumlab::settings::Settings::default();
    let size = (64, 48);
    let mut images = Vec::new();
    for ahead in [false, true] {
        let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
        renderer.render(&settings, size);
        if ahead {
            renderer.compile_ahead(&settings, drag);
        }
        renderer.set_shade_options(drag);
        renderer.render(&settings, size);
        assert_eq!(
            renderer.pipelines_compiled_ahead(),
            u64::from(ahead),
            "ahead: {ahead}"
        );
        images.push(renderer.read_quantity());
    }
    assert!(images[0].iter().any(|t| t[0] > 0.0), "something is lit");
    assert!(images[0] == images[1], "the same pixels either way");
}

/// A point light's drag pipeline is compiled ahead with the sphere light's,
/// under either visibility source: a radius slider's drag switches to it
/// without compiling.
#[test]
fn a_drag_finds_both_lights_pipelines_compiled_ahead() {
    let gpu = gpu();
    let scene = lumlab::scene::default_scene();
    for &visibility in Visibility::ALL {
        let mut settings = lumlab::settings::Settings::default();
        settings.shadow.visibility = visibility;
        settings.light.radius_m = 0.0;
        let size = (64, 48);
        let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
        renderer.render(&settings, size);
        renderer.compile_ahead(&settings, ShadeOptions::INTERACTION);
        renderer.set_shade_options(ShadeOptions::INTERACTION);
        for (radius_m, ahead) in [(0.0, 1), (0.2, 2), (0.0, 2)] {
            settings.light.radius_m = radius_m;
            renderer.render(&settings, size);
            assert_eq!(
                renderer.pipelines_compiled_ahead(),
                ahead,
                "{visibility:?}, R = {radius_m} m"
            );
        }
    }
}
