//! The GPU ray-traced visibility against the CPU reference: its hard
//! shadows pixel by pixel, and its progressive accumulation under a sphere
//! light converging to the reference's V at least as 1/√N. Its BVH
//! traversal is checked in `gpu_bvh.rs`.

mod common;

use glam::Vec3;
use lumlab::gpu::noise;
use lumlab::gpu::{Capabilities, GpuContext, Renderer, ShadeOptions};
use lumlab::reference::{Reference, ReferenceOptions, RenderControl};
use lumlab::scene::Scene;
use lumlab::settings::{Settings, Visibility};

/// The camera pass's targets: as the adapter offers, or f16 as GL's
/// fallback has them on llvmpipe (the mean is then kept in f32 by
/// gpu::accumulate).
#[derive(Clone, Copy, Debug)]
enum Targets {
    Adapters,
    F16,
}

fn renderer(gpu: &GpuContext, scene: &Scene, targets: Targets) -> Renderer {
    let mut caps = Capabilities::of(&gpu.adapter, &gpu.device);
    if let Targets::F16 = targets {
        caps.hdr_format = wgpu::TextureFormat::Rgba16Float;
    }
    Renderer::with_capabilities(&gpu.device, &gpu.queue, caps, scene)
}

/// The aux target (x: V, z: max(0, n·l)) of the ray tracer after each
/// number of `frames`.
fn ray_traced_aux(
    gpu: &GpuContext,
    scene: &Scene,
    settings: &Settings,
    frames: &[u32],
    targets: Targets,
) -> Vec<Vec<[f32; 4]>> {
    let mut renderer = renderer(gpu, scene, targets);
    let size = (settings.image.width, settings.image.height);
    let mut out = Vec::new();
    let mut done = 0;
    for &n in frames {
        while done < n {
            renderer.render(settings, size);
            done += 1;
        }
        let a = renderer.accumulation().expect("ray traced");
        assert_eq!(a.frames, n.min(settings.ray_traced_frames()));
        assert_eq!(a.is_complete(), n >= settings.ray_traced_frames());
        out.push(renderer.read_aux());
    }
    out
}

/// Whether pixel `i`'s 3×3 neighbourhood in the reference holds a change
/// of V or of what is seen: a shadow's or an object's silhouette.
fn on_silhouette(v: &[f32], coverage: &[f32], width: usize, i: usize) -> bool {
    let (x, y) = ((i % width) as i64, (i / width) as i64);
    let height = (v.len() / width) as i64;
    let mut seen = Vec::new();
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && nx < width as i64 && ny < height {
                let j = (ny * width as i64 + nx) as usize;
                seen.push((v[j], coverage[j]));
            }
        }
    }
    seen.iter().any(|s| *s != seen[0])
}

/// Hard shadows of a point light: at most 0.01 % of the pixels differ from
/// the reference's V, each on a silhouette. Its one ray per pixel is exact:
/// after three frames the accumulation still holds one, complete.
fn point_light_matches_the_reference(scene: &Scene, settings: &Settings) {
    let gpu = common::gpu();
    assert!(settings.shadow.rt_max_frames >= 3);
    let gpu_v: Vec<f32> = ray_traced_aux(&gpu, scene, settings, &[3], Targets::Adapters)[0]
        .iter()
        .map(|t| t[0])
        .collect();
    let reference = Reference::new(scene)
        .render(settings, &ReferenceOptions::DEFAULT, &RenderControl::default())
        .unwrap();
    let width = settings.image.width as usize;
    let mut differ = Vec::new();
    let mut shadowed = 0;
    for (i, (&g, &r)) in gpu_v.iter().zip(&reference.visibility).enumerate() {
        if reference.coverage[i] == 0.0 {
            continue;
        }
        shadowed += (r == 0.0) as usize;
        if (g - r).abs() > 1e-6 {
            assert!(
                on_silhouette(&reference.visibility, &reference.coverage, width, i),
                "pixel ({}, {}): GPU V {g}, reference {r}, away from any silhouette",
                i % width,
                i / width
            );
            differ.push(i);
        }
    }
    let pixels = gpu_v.len();
    eprintln!(
        "{} of {pixels} pixels differ ({shadowed} in shadow)",
        differ.len()
    );
    assert!(shadowed > pixels / 100, "only {shadowed} pixels in shadow");
    assert!(
        differ.len() as f64 <= 1e-4 * pixels as f64,
        "{} pixels differ",
        differ.len()
    );
}

fn ray_traced(width: u32, height: u32) -> Settings {
    let mut s = Settings::default();
    (s.image.width, s.image.height) = (width, height);
    s.shadow.visibility = Visibility::RayTraced;
    s.light.radius_m = 0.0;
    s
}

#[test]
fn point_light_shadows_are_the_references_on_the_default_scene() {
    point_light_matches_the_reference(&lumlab::scene::default_scene(), &ray_traced(320, 180));
}

#[test]
fn point_light_shadows_are_the_references_on_a_100k_triangle_scene() {
    let scene = lumlab::scene::stress::sphere_field(100_000);
    assert!(scene.triangle_count() >= 100_000);
    let mut settings = ray_traced(320, 180);
    lumlab::scene::framing::adopt(&mut settings, &scene);
    // Low and to the side: long shadows across the ground and the spheres.
    settings.light.position = Vec3::new(2.5, 1.2, 1.0);
    point_light_matches_the_reference(&scene, &settings);
}

/// Ray-traced V at 96 × 54 under a sphere light of R = 0.3 m, 4 rays a
/// frame.
fn under_a_sphere_light() -> Settings {
    let mut settings = ray_traced(96, 54);
    settings.light.radius_m = 0.3;
    settings.shadow.rt_light_samples = 4;
    settings
}

#[test]
fn sphere_light_accumulation_converges_to_the_reference_as_one_over_root_n() {
    converges_to_the_reference(Targets::Adapters);
}

#[test]
fn sphere_light_accumulation_converges_as_well_with_f16_targets_as_gl_has() {
    converges_to_the_reference(Targets::F16);
}

fn converges_to_the_reference(targets: Targets) {
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let settings = under_a_sphere_light();
    let frames = [1, 4, 16, 64, 128, 256];
    let runs = ray_traced_aux(&gpu, &scene, &settings, &frames, targets);
    let options = ReferenceOptions {
        light_samples: 4096,
        ..ReferenceOptions::DEFAULT
    };
    let tracer = Reference::new(&scene);
    let reference = tracer
        .render(&settings, &options, &RenderControl::default())
        .unwrap();
    // Pixels where both see the same surface (the same cos θ to the light's
    // centre: a pixel centre on an object's silhouette can fall on the
    // object for the rasterizer and beside it for the ray), away from the
    // terminator: where the sphere straddles the horizon (|cos θ| < R / d)
    // V hangs on rays grazing the facets, which f32 and f64 offsets treat
    // differently, and the radiance there is nearly 0.
    let width = settings.image.width;
    let one_sample = ReferenceOptions {
        light_samples: 1,
        ..ReferenceOptions::DEFAULT
    };
    let all: Vec<usize> = (0..reference.coverage.len())
        .filter(|&i| reference.coverage[i] > 0.0)
        .collect();
    let covered: Vec<usize> = all
        .iter()
        .copied()
        .filter(|&i| {
            let (x, y) = ((i as u32 % width) as f64 + 0.5, (i as u32 / width) as f64 + 0.5);
            tracer.trace_pixel(&settings, &one_sample, x, y).is_some_and(|s| {
                let straddles = s.cos_theta.abs() < 0.3 / s.light_distance_m;
                (s.cos_theta.max(0.0) - runs[0][i][2] as f64).abs() < 1e-3 && !straddles
            })
        })
        .collect();
    eprintln!(
        "{} of {} covered pixels on the same surface, off the terminator",
        covered.len(),
        all.len()
    );
    assert!(covered.len() as f64 > 0.97 * all.len() as f64);
    let mean = covered
        .iter()
        .map(|&i| reference.visibility[i] as f64)
        .sum::<f64>()
        / covered.len() as f64;
    let rmse: Vec<f64> = runs
        .iter()
        .map(|v| {
            let sum: f64 = covered
                .iter()
                .map(|&i| (v[i][0] as f64 - reference.visibility[i] as f64).powi(2))
                .sum();
            (sum / covered.len() as f64).sqrt()
        })
        .collect();
    eprintln!("{targets:?}: mean V {mean:.4}; RMSE at N = {frames:?}: {rmse:.5?}");
    for (k, &n) in frames.iter().enumerate() {
        // 1/√N with 25 % slack for the randomness of the estimate itself.
        let bound = 1.25 * rmse[0] / (n as f64).sqrt();
        assert!(rmse[k] <= bound, "N = {n}: RMSE {} above {bound}", rmse[k]);
    }
    assert!(
        rmse[5] < 0.02 * mean,
        "RMSE {} at 256 frames, mean {mean}",
        rmse[5]
    );
    // The noise measured on the image (gpu::noise), 256 frames against
    // 128: an estimate of the error for independent samples, which the
    // low-discrepancy sequence's error stays under (1.1–1.7× from 2 to 256
    // frames); the bound 0.5 / √(N·S) is 45× the error.
    let estimate = noise::standard_error(
        covered
            .iter()
            .map(|&i| (runs[5][i][0] as f64, runs[4][i][0] as f64)),
        256,
        128,
    )
    .unwrap();
    eprintln!(
        "{targets:?}: noise measured at 256 frames {estimate:.5}, error {:.5}",
        rmse[5]
    );
    assert!(
        (rmse[5]..3.0 * rmse[5]).contains(&estimate),
        "estimate {estimate} against an error of {}",
        rmse[5]
    );
}

#[test]
fn the_noise_measured_on_the_image_compares_the_mean_with_its_first_half() {
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let mut settings = under_a_sphere_light();
    settings.shadow.rt_max_frames = 16;
    let size = (settings.image.width, settings.image.height);
    let mut renderer = renderer(&gpu, &scene, Targets::Adapters);
    let luminance = |q: Vec<[f32; 4]>| -> Vec<Option<f64>> {
        q.iter()
            .map(|t| {
                (t[3] > 0.0).then(|| lumlab::physics::colour::luminance([t[0], t[1], t[2]].map(f64::from)))
            })
            .collect()
    };
    let mut half = Vec::new();
    let mut measured = None;
    for n in 1..=16u32 {
        renderer.render(&settings, size);
        renderer.settle_noise();
        if n >= 4 && n.is_power_of_two() {
            measured = Some((n / 2, n));
        }
        let estimate = renderer.accumulation().unwrap().estimate;
        assert_eq!(
            estimate.map(|e| (e.earlier_frames, e.frames)),
            measured,
            "after {n} frames"
        );
        if n == 8 {
            half = luminance(renderer.read_quantity());
        }
    }
    let e = renderer
        .accumulation()
        .unwrap()
        .estimate
        .expect("measured at 16 frames");
    assert_eq!((e.earlier_frames, e.frames), (8, 16));
    let full = luminance(renderer.read_quantity());
    let pairs: Vec<(f64, f64)> = full
        .iter()
        .zip(&half)
        .filter_map(|(f, h)| Some(((*f)?, (*h)?)))
        .collect();
    let mean = pairs.iter().map(|p| p.0).sum::<f64>() / pairs.len() as f64;
    let expected = noise::standard_error(pairs, 16, 8).unwrap() / mean;
    assert!(
        (e.relative / expected - 1.0).abs() < 1e-5,
        "{} against {expected}",
        e.relative
    );
    assert!(e.relative > 0.0 && e.relative < 0.05, "{}", e.relative);
    // Any change starts a new mean, unmeasured.
    settings.light.radius_m = 0.25;
    renderer.render(&settings, size);
    renderer.settle_noise();
    assert_eq!(renderer.accumulation().unwrap().estimate, None);
}

/// `lumlab render` of the default scene under a sphere light of R = 0.3 m
/// with `args`, into `out`.
fn render_command(args: &[&str], out: &std::path::Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_lumlab"))
        .args(["render", "--light-radius", "0.3"])
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn accumulate_needs_ray_traced_visibility_and_renders_n_frames() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.png");
    let run =
        |extra: &[&str]| render_command(&[&["--size", "64x36", "--accumulate", "3"], extra].concat(), &out);
    let refused = run(&[]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(
        message.contains("--accumulate needs --visibility ray-traced"),
        "{message}"
    );
    assert!(!out.exists());
    let traced = run(&["--visibility", "ray-traced"]);
    let message = String::from_utf8_lossy(&traced.stderr);
    assert!(traced.status.success(), "{message}");
    assert!(
        message.contains("ray traced, 3 frame(s) × 8 ray(s) per pixel"),
        "{message}"
    );
    assert!(out.exists());
}

#[test]
fn noise_target_stops_the_command_line_s_mean_once_met() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.exr");
    let run = |extra: &[&str]| render_command(&[&["--size", "96x54"], extra].concat(), &out);
    for (extra, says) in [
        (
            &["--noise-target", "2"][..],
            "--noise-target needs --visibility ray-traced",
        ),
        (
            &["--visibility", "ray-traced", "--noise-target", "0"],
            "not a percentage",
        ),
    ] {
        let refused = run(extra);
        let message = String::from_utf8_lossy(&refused.stderr);
        assert_eq!(refused.status.code(), Some(2), "{message}");
        assert!(message.contains(says), "{message}");
    }
    assert!(!out.exists());
    let held = run(&[
        "--visibility",
        "ray-traced",
        "--accumulate",
        "256",
        "--noise-target",
        "2",
    ]);
    let message = String::from_utf8_lossy(&held.stderr);
    assert!(held.status.success(), "{message}");
    let number_after = |prefix: &str| -> f64 {
        let rest = &message[message.find(prefix).unwrap_or_else(|| panic!("{message}")) + prefix.len()..];
        rest.split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .next()
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{message}"))
    };
    let frames = number_after("ray traced, ") as u32;
    let noise = number_after("RMS standard error ");
    assert!(
        frames.is_power_of_two() && (2..256).contains(&frames) && noise <= 2.0,
        "{message}"
    );
    assert!(message.contains("at most the 2 % asked for"), "{message}");
    assert!(out.exists());
}

#[test]
fn a_mean_begun_without_the_aux_target_restarts_when_it_is_asked_for() {
    restarts_when_the_aux_target_is_asked_for(Targets::Adapters);
    restarts_when_the_aux_target_is_asked_for(Targets::F16);
}

fn restarts_when_the_aux_target_is_asked_for(targets: Targets) {
    // The app's frames skip the aux target until the probe reads it; the
    // frames of the mean before then left none in the history.
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let settings = under_a_sphere_light();
    let size = (settings.image.width, settings.image.height);
    let mut renderer = renderer(&gpu, &scene, targets);
    let quantity_only = ShadeOptions {
        aux: false,
        ..ShadeOptions::default()
    };
    renderer.set_shade_options(quantity_only);
    for _ in 0..3 {
        renderer.render(&settings, size);
    }
    assert_eq!(renderer.accumulation().unwrap().frames, 3);
    assert!(renderer.read_aux().is_empty(), "no aux target was written");
    renderer.set_shade_options(ShadeOptions::default());
    renderer.render(&settings, size);
    assert_eq!(renderer.accumulation().unwrap().frames, 1, "the mean restarted");
    let aux = renderer.read_aux();
    assert_eq!(aux.len(), (size.0 * size.1) as usize);
    // Coverage is 0 or 1 and V within [0, 1] (and an f32 rounding: the
    // H200 gives 1 + 1 ulp): no frame without aux in the mean.
    let odd = |a: &&[f32; 4]| !((a[3] == 0.0 || a[3] == 1.0) && (0.0..=1.0 + 1e-6).contains(&a[0]));
    let odd: Vec<_> = aux.iter().filter(odd).take(5).collect();
    assert!(odd.is_empty(), "{odd:?}");
    assert!(aux.iter().filter(|a| a[3] == 1.0).count() > aux.len() / 2);
    // Without the aux target the mean goes on as before: the quantity's
    // alpha still marks the pixels covered.
    renderer.set_shade_options(quantity_only);
    renderer.render(&settings, size);
    renderer.render(&settings, size);
    assert_eq!(renderer.accumulation().unwrap().frames, 2);
    let covered = renderer.read_quantity().iter().filter(|q| q[3] > 0.0).count();
    assert_eq!(covered, aux.iter().filter(|a| a[3] == 1.0).count());
}
