//! Frame cost of the GPU renderer on the default scene at 1280×720: every
//! filter × shadow-map resolution, for an unchanged frame (the shadow map is
//! reused) and for a frame whose light moved (the map is redrawn).
//! `cargo bench --bench frame_cost` prints a Markdown table; times are medians
//! of wall time around submit + wait, and of GPU timestamps where the adapter
//! has them.
//!
//! A second table (`cargo bench --bench frame_cost -- interaction` prints it
//! alone) gives what the lab's viewport costs while the user orbits, under
//! the shadow map (two filters) and ray-traced V (a point and a sphere light): the
//! generic and the specialised camera pass of a still frame as the app
//! draws it ([`ShadeOptions::still`]) against a minimal flat-colour pass
//! over the same geometry (their ratio), and the frame rate at the render
//! scales the app drops to during interaction. Ratios are taken within one
//! run, so a loaded machine slows both sides alike; the spread is over runs.
//! Then a drag's two ends (`-- drag-ends` prints them alone): its first
//! frame after a new view, the pipeline compiled on demand or ahead, and the
//! full frame at its end, after an orbit (the map from before the drag
//! still holds) and after a light drag (drawn again).

use lumlab::gpu::{GpuContext, Renderer, ShadeOptions};
use lumlab::settings::{DebugView, Filter, Settings, Visibility};
use std::time::{Duration, Instant};

/// The lab's viewport in its default 1600×900 window, side panels open (0.68 Mpixel).
const VIEWPORT: (u32, u32) = (1000, 680);
/// Repeats of the interaction measurements, for their spread.
const RUNS: usize = 5;
/// Render scales of the interaction table (the app chooses among such).
const SCALES: [f64; 4] = [1.0, 0.75, 0.5, 0.35];

const SIZE: (u32, u32) = (1280, 720);
const FRAMES: usize = 5;

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Median wall and GPU milliseconds of `FRAMES` frames; `moving` nudges the
/// light before each so the shadow map is redrawn every time.
fn measure(renderer: &mut Renderer, settings: &mut Settings, moving: bool) -> (f64, Option<f64>) {
    let (mut wall, mut gpu) = (Vec::new(), Vec::new());
    for frame in 0..FRAMES {
        if moving {
            settings.light.position.x += if frame % 2 == 0 { 0.01 } else { -0.01 };
        }
        let start = Instant::now();
        let report = renderer.render(settings, SIZE);
        renderer.wait_idle();
        wall.push(start.elapsed().as_secs_f64() * 1e3);
        assert_eq!(report.shadow_redrawn, moving);
        if let Some(t) = renderer.wait_timings() {
            gpu.push(t.total_ms());
        }
    }
    (median(wall), (!gpu.is_empty()).then(|| median(gpu)))
}

/// Median GPU time (ms) of the camera pass and of the whole frame, and the
/// median wall time, over `FRAMES` orbiting frames (the camera turns, the
/// shadow map is reused).
fn orbit(renderer: &mut Renderer, settings: &mut Settings, size: (u32, u32)) -> (f64, f64, f64) {
    renderer.render(settings, size);
    renderer.wait_idle();
    let _ = renderer.wait_timings();
    let (mut shade, mut gpu, mut wall) = (Vec::new(), Vec::new(), Vec::new());
    for frame in 0..FRAMES {
        let turn = if frame % 2 == 0 { 0.02 } else { -0.02 };
        settings.camera.eye = glam::Quat::from_rotation_y(turn) * settings.camera.eye;
        let start = Instant::now();
        renderer.render(settings, size);
        renderer.wait_idle();
        wall.push(start.elapsed().as_secs_f64() * 1e3);
        if let Some(t) = renderer.wait_timings() {
            shade.push(t.shade_ms.unwrap_or(0.0));
            gpu.push(t.total_ms());
        }
    }
    let or_wall = |v: Vec<f64>| {
        if v.is_empty() {
            median(wall.clone())
        } else {
            median(v)
        }
    };
    (or_wall(shade), or_wall(gpu), median(wall))
}

/// "median (min–max)" of several runs.
fn spread(values: &[f64]) -> String {
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    format!("{:.1} ({min:.1}–{max:.1})", median(values.to_vec()))
}

fn scaled(size: (u32, u32), scale: f64) -> (u32, u32) {
    let side = |n: u32| ((n as f64 * scale).round() as u32).max(1);
    (side(size.0), side(size.1))
}

/// The interaction table's rows: the default settings, PCSS, and ray-traced
/// V under a point light and a sphere light (drag frames send it one ray a
/// pixel, full frames the settings' samples).
fn interaction_cases() -> Vec<(String, Settings)> {
    let mut pcss = Settings::default();
    pcss.shadow.filter = Filter::Pcss;
    let traced = |radius_m: f32| {
        let mut s = Settings::default();
        s.shadow.visibility = Visibility::RayTraced;
        s.light.radius_m = radius_m;
        s
    };
    vec![
        (Settings::default().shadow.filter.to_string(), Settings::default()),
        (Filter::Pcss.to_string(), pcss),
        ("ray traced, point light".into(), traced(0.0)),
        ("ray traced, sphere light R = 0.2 m".into(), traced(0.2)),
    ]
}

/// The interaction table: camera pass against the flat pass, and frames
/// per second at each render scale, for the rows of [`interaction_cases`].
fn interaction(renderer: &mut Renderer) {
    println!(
        "viewport {}×{} ({:.2} Mpixel), default scene, medians of {FRAMES} orbiting frames; median (min–max) of {RUNS} runs\n",
        VIEWPORT.0,
        VIEWPORT.1,
        (VIEWPORT.0 * VIEWPORT.1) as f64 / 1e6
    );
    let mut header = String::from(
        "| visibility | flat pass (ms) | shading, generic (ms) | shading, specialised (ms) | specialised / flat | generic / flat |",
    );
    let mut rule = String::from("|---|---|---|---|---|---|");
    for scale in SCALES {
        header += &format!(" frames/s at scale {scale} (frame ms) |");
        rule += "---|";
    }
    println!("{header}\n{rule}");
    for (label, case) in interaction_cases() {
        let mut columns: Vec<Vec<f64>> = vec![Vec::new(); 5 + 2 * SCALES.len()];
        for _ in 0..RUNS {
            let mut settings = case.clone();
            let still = ShadeOptions::still(&settings, false);
            renderer.set_shade_options(ShadeOptions {
                specialised: false,
                ..still
            });
            let (generic, _, _) = orbit(renderer, &mut settings, VIEWPORT);
            // As the app draws a still frame.
            renderer.set_shade_options(still);
            let (specialised, _, _) = orbit(renderer, &mut settings, VIEWPORT);
            let flat = median((0..FRAMES).filter_map(|_| renderer.minimal_pass_ms()).collect());
            for (column, value) in [flat, generic, specialised, specialised / flat, generic / flat]
                .into_iter()
                .enumerate()
            {
                columns[column].push(value);
            }
            // Interaction frames, as the app draws them: specialised,
            // without the aux target and the depth pre-pass.
            renderer.set_shade_options(ShadeOptions::INTERACTION);
            for (k, scale) in SCALES.into_iter().enumerate() {
                let (_, gpu_ms, wall_ms) = orbit(renderer, &mut settings, scaled(VIEWPORT, scale));
                let frame_ms = gpu_ms.max(wall_ms);
                columns[5 + 2 * k].push(1e3 / frame_ms);
                columns[6 + 2 * k].push(frame_ms);
            }
            renderer.set_shade_options(ShadeOptions::default());
        }
        let mut row = format!("| {label} |");
        for column in &columns[..5] {
            row += &format!(" {} |", spread(column));
        }
        for k in 0..SCALES.len() {
            row += &format!(
                " {} ({}) |",
                spread(&columns[5 + 2 * k]),
                spread(&columns[6 + 2 * k])
            );
        }
        println!("{row}");
    }
    println!();
}

/// The first drag frame after a full frame of a view not drawn before: its
/// camera pass compiled when the drag needs it, or compiled ahead on a
/// thread of its own (as the app starts it after each full frame) while the
/// user pauses for a second. Each pair of views is new to the renderer.
fn first_drag(renderer: &mut Renderer) {
    let drag = ShadeOptions::INTERACTION;
    let size = scaled(VIEWPORT, 0.25);
    let pairs = [
        (DebugView::Irradiance, DebugView::Ndotl),
        (DebugView::Diffuse, DebugView::Specular),
        (DebugView::Brdf, DebugView::Depth),
    ];
    let (mut on_demand, mut ahead) = (Vec::new(), Vec::new());
    for (first, second) in pairs {
        for (view, compiled_ahead) in [(first, false), (second, true)] {
            let mut settings = Settings::default();
            settings.view.mode = view;
            renderer.set_shade_options(ShadeOptions::default());
            renderer.render(&settings, VIEWPORT);
            renderer.wait_idle();
            if compiled_ahead {
                renderer.compile_ahead(&settings, drag);
                std::thread::sleep(Duration::from_secs(1));
            }
            renderer.set_shade_options(drag);
            let start = Instant::now();
            renderer.render(&settings, size);
            renderer.wait_idle();
            let ms = start.elapsed().as_secs_f64() * 1e3;
            if compiled_ahead {
                ahead.push(ms);
            } else {
                on_demand.push(ms);
            }
        }
    }
    renderer.set_shade_options(ShadeOptions::default());
    println!(
        "first drag frame ({}×{}) after a full frame of a new view, ms, median (min–max) of {}: pipeline compiled on demand {}, compiled ahead {}\n",
        size.0,
        size.1,
        pairs.len(),
        spread(&on_demand),
        spread(&ahead)
    );
}

/// The full frame at a drag's end, after a drag frame at scale 0.25 (its
/// shadow map a quarter of the side, as the app draws it): the camera
/// turned and the light stayed, or the light moved too.
fn drag_end(renderer: &mut Renderer) {
    let (mut kept, mut moved) = (Vec::new(), Vec::new());
    let mut settings = Settings::default();
    renderer.set_shade_options(ShadeOptions::default());
    renderer.render(&settings, VIEWPORT);
    renderer.wait_idle();
    for run in 0..2 * RUNS {
        let light_moves = run % 2 == 1;
        let mut drag = settings.clone();
        drag.shadow.resolution /= 4;
        drag.camera.eye = glam::Quat::from_rotation_y(0.02) * drag.camera.eye;
        if light_moves {
            drag.light.position.x += 0.01;
            settings.light.position.x += 0.02;
        }
        renderer.set_shade_options(ShadeOptions::INTERACTION);
        renderer.render(&drag, scaled(VIEWPORT, 0.25));
        renderer.wait_idle();
        renderer.set_shade_options(ShadeOptions::default());
        let start = Instant::now();
        let report = renderer.render(&settings, VIEWPORT);
        renderer.wait_idle();
        assert_eq!(report.shadow_redrawn, light_moves);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        if light_moves {
            moved.push(ms);
        } else {
            kept.push(ms);
        }
    }
    println!(
        "full frame ({}×{}) at a drag's end, ms, median (min–max) of {RUNS}: the light kept (the map from before the drag) {}, the light moved (the map drawn again) {}\n",
        VIEWPORT.0,
        VIEWPORT.1,
        spread(&kept),
        spread(&moved)
    );
}

/// What the camera pass's cost is made of (`-- breakdown`): the specialised
/// pass at full scale with one ingredient taken away at a time, against the
/// flat pass: the depth pre-pass (timed with the pass, the flat pass has
/// none), the filter's taps (PCF 3×3 decided from the depth ranges, or
/// 16 depth tests each → one → no shadows; PCSS's blocker search and
/// bilinear taps under a sphere light), the BRDF (the `visibility` view), the second target (aux).
fn breakdown(renderer: &mut Renderer) {
    println!(
        "viewport {}×{}, camera pass GPU ms, median of {FRAMES} orbiting frames; median (min–max) of {RUNS} runs\n",
        VIEWPORT.0, VIEWPORT.1
    );
    println!("| variant | camera pass (ms) | / flat |\n|---|---|---|");
    // Quantity only, as the app's still frames.
    let plain = ShadeOptions::STILL;
    type Variant = (&'static str, fn(&mut Settings), ShadeOptions);
    let variants: [Variant; 11] = [
        ("default: PCF 3×3, shaded, quantity only", |_| {}, plain),
        (
            "PCF 3×3, every texel tested (no depth ranges)",
            |_| {},
            ShadeOptions {
                depth_ranges: false,
                ..plain
            },
        ),
        (
            "Poisson 16 taps, decided from the depth ranges",
            |s| s.shadow.filter = Filter::Poisson,
            plain,
        ),
        (
            "Poisson 16 taps, every tap tested",
            |s| s.shadow.filter = Filter::Poisson,
            ShadeOptions {
                depth_ranges: false,
                ..plain
            },
        ),
        (
            "PCSS 16 + 16 taps, sphere light R = 0.2 m",
            |s| {
                s.shadow.filter = Filter::Pcss;
                s.light.radius_m = 0.2;
            },
            plain,
        ),
        (
            "+ aux target (two targets written)",
            |_| {},
            ShadeOptions { aux: true, ..plain },
        ),
        (
            "no depth pre-pass (as while dragging)",
            |_| {},
            ShadeOptions::INTERACTION,
        ),
        (
            "filter none (one depth tap)",
            |s| s.shadow.filter = Filter::None,
            plain,
        ),
        (
            "shadows off (no shadow-map lookup)",
            |s| s.shadow.enabled = false,
            plain,
        ),
        (
            "visibility view (PCF, no BRDF)",
            |s| s.view.mode = lumlab::settings::DebugView::Visibility,
            plain,
        ),
        (
            "shadows off, visibility view (neither)",
            |s| {
                s.shadow.enabled = false;
                s.view.mode = lumlab::settings::DebugView::Visibility;
            },
            plain,
        ),
    ];
    let mut flat = Vec::new();
    let mut rows: Vec<Vec<(f64, f64)>> = vec![Vec::new(); variants.len()];
    for _ in 0..RUNS {
        for (k, (_, change, options)) in variants.iter().enumerate() {
            let mut settings = Settings::default();
            change(&mut settings);
            renderer.set_shade_options(*options);
            let (shade, _, _) = orbit(renderer, &mut settings, VIEWPORT);
            let f = median((0..FRAMES).filter_map(|_| renderer.minimal_pass_ms()).collect());
            flat.push(f);
            rows[k].push((shade, shade / f));
        }
    }
    renderer.set_shade_options(ShadeOptions::default());
    for ((name, _, _), row) in variants.iter().zip(&rows) {
        let ms: Vec<f64> = row.iter().map(|r| r.0).collect();
        let ratio: Vec<f64> = row.iter().map(|r| r.1).collect();
        println!("| {name} | {} | {} |", spread(&ms), spread(&ratio));
    }
    println!("| flat pass | {} | 1 |\n", spread(&flat));
    ranges_build(renderer);
}

/// What building the depth ranges costs, once per map (GPU ms of the
/// prefilter span): the map drawn anew (the light moved a little), then
/// reused by the frame that builds them.
fn ranges_build(renderer: &mut Renderer) {
    let mut pcss = Settings::default();
    pcss.shadow.filter = Filter::Pcss;
    pcss.light.radius_m = 0.2;
    for (name, mut settings) in [("PCF 3×3", Settings::default()), ("PCSS's search", pcss)] {
        let (mut build, mut layers, mut block) = (Vec::new(), String::new(), 0);
        for run in 0..RUNS {
            settings.light.position.x += if run % 2 == 0 { 0.01 } else { -0.01 };
            renderer.render(&settings, VIEWPORT);
            renderer.wait_idle();
            let _ = renderer.wait_timings();
            let report = renderer.render(&settings, VIEWPORT);
            renderer.wait_idle();
            block = report.depth_ranges.expect("the reused map's ranges are built");
            layers = report.layout_summary();
            if let Some(ms) = renderer.wait_timings().and_then(|t| t.blur_ms) {
                build.push(ms);
            }
        }
        println!(
            "depth ranges for {name} (B = {block}), built once per map ({layers}, {}²): {} GPU ms, median (min–max) of {RUNS}",
            settings.shadow.resolution,
            spread(&build)
        );
    }
    println!();
}

fn main() {
    let gpu = GpuContext::headless().unwrap_or_else(|e| panic!("{e}"));
    let scene = lumlab::scene::default_scene();
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    println!("adapter: {}\n", gpu.describe());
    if std::env::args().any(|a| a == "breakdown") {
        breakdown(&mut renderer);
        return;
    }
    if std::env::args().any(|a| a == "drag-ends") {
        first_drag(&mut renderer);
        drag_end(&mut renderer);
        return;
    }
    interaction(&mut renderer);
    first_drag(&mut renderer);
    drag_end(&mut renderer);
    if std::env::args().any(|a| a == "interaction") {
        return;
    }
    println!("| filter | shadow map | unchanged frame (ms) | light moved (ms) | moved / unchanged |");
    println!("|---|---|---|---|---|");
    for &filter in Filter::ALL {
        for resolution in [512, 1024, 2048, 4096] {
            let mut settings = Settings::default();
            settings.shadow.filter = filter;
            settings.shadow.resolution = resolution;
            settings.light.radius_m = 0.2;
            // Warm up: pipelines, textures and the first map.
            renderer.render(&settings, SIZE);
            renderer.wait_idle();
            let _ = renderer.wait_timings();
            let (still, still_gpu) = measure(&mut renderer, &mut settings, false);
            let (moved, moved_gpu) = measure(&mut renderer, &mut settings, true);
            let show = |wall: f64, gpu: Option<f64>| match gpu {
                Some(g) => format!("{wall:.1} (GPU {g:.1})"),
                None => format!("{wall:.1}"),
            };
            println!(
                "| {filter} | {resolution}² | {} | {} | {:.2} |",
                show(still, still_gpu),
                show(moved, moved_gpu),
                moved / still
            );
        }
    }
}
