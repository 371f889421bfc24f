//! Frame cost of the GPU renderer on the default scene at 1280×720: every
//! filter × shadow-map resolution, for an unchanged frame (the shadow map is
//! reused) and for a frame whose light moved (the map is redrawn).
//! `cargo bench --bench frame_cost` prints a Markdown table; times are medians
//! of wall time around submit + wait, and of GPU timestamps where the adapter
//! has them.

use lumlab::gpu::{GpuContext, Renderer};
use lumlab::settings::{Filter, Settings};
use std::time::Instant;

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

fn main() {
    let gpu = GpuContext::headless().unwrap_or_else(|e| panic!("{e}"));
    let scene = lumlab::scene::default_scene();
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    println!("adapter: {}\n", gpu.describe());
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
