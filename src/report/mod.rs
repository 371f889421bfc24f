//! `lumlab report`: every shadow configuration of a sweep weighed against
//! the CPU reference, speed against error, plus the BRDF normalizations'
//! albedo beside the brightness they give the scene.
//!
//! [`run`] renders and measures; [`page`] writes the CSV, the figures and
//! the HTML page into a folder.

pub mod folder;
pub mod metrics;
pub mod page;
pub mod sweep;

use crate::gpu::timing::PassTimes;
use crate::gpu::{GpuContext, Renderer};
use crate::physics::{Normalization, energy};
use crate::reference::{Reference, ReferenceError, ReferenceOptions, RenderControl};
use crate::scene::Scene;
use crate::settings::{DebugView, Settings, ShadowSettings, Visibility};
use metrics::{Comparison, ErrorMetrics, Frame};
use std::time::{Duration, Instant};
use sweep::SweepPoint;

/// How much each configuration is measured.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportOptions {
    /// Timed frames per configuration (the light nudged before each, so the
    /// shadow map is redrawn every time: the cost of a moving light).
    pub frames: usize,
    pub reference: ReferenceOptions,
    /// Exponents m of the normalization section.
    pub normalization_ms: Vec<f64>,
}

impl Default for ReportOptions {
    fn default() -> Self {
        Self {
            frames: DEFAULT_FRAMES,
            reference: ReferenceOptions::DEFAULT,
            normalization_ms: vec![1.0, 8.0, 64.0, 512.0],
        }
    }
}

/// Timed frames per configuration unless told otherwise.
pub const DEFAULT_FRAMES: usize = 5;

/// Median times of one configuration's frames (ms).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameTimes {
    /// The whole frame: GPU timestamps where the adapter has them, else wall time.
    pub frame_ms: f64,
    /// The passes (0 where a pass did not run or there are no timestamps).
    pub shadow_ms: f64,
    pub blur_ms: f64,
    pub shade_ms: f64,
    pub display_ms: f64,
    /// Wall time around submit + wait.
    pub wall_ms: f64,
}

/// One measured configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    pub label: String,
    pub shadow: ShadowSettings,
    /// The resolution drawn (the device may clamp the one asked for).
    pub resolution_used: u32,
    pub times: FrameTimes,
    pub error: ErrorMetrics,
    /// The displayed GPU image and its signed error image (RGBA8).
    pub shaded: image::RgbaImage,
    pub error_image: image::RgbaImage,
}

/// Albedo and scene brightness of one normalization and exponent (k = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct NormalizationRow {
    pub norm: Normalization,
    pub m: f64,
    /// a(θ) at `energy::LECTURE_ANGLES_DEG`.
    pub albedo: Vec<f64>,
    /// Mean luminance of the GPU image over the covered pixels (W/m²/sr).
    pub mean_radiance: f64,
}

/// Everything the report page shows.
pub struct Report {
    pub settings: Settings,
    pub adapter: String,
    /// True when frame times are GPU timestamps, false when wall time.
    pub gpu_timestamps: bool,
    pub triangles: usize,
    pub reference_time: Duration,
    pub reference_display: image::RgbaImage,
    /// The reference measured against itself: zero by construction, a check
    /// of the metrics.
    pub reference_error: ErrorMetrics,
    pub configurations: Vec<Measured>,
    /// Of `configurations`, then the reference as the last point.
    pub pareto: Vec<bool>,
    pub normalization: Vec<NormalizationRow>,
    /// The largest |L − L_ref| the error images resolve (W/m²/sr).
    pub error_scale: f64,
    pub elapsed: Duration,
}

/// What the caller is told as the report advances.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub done: usize,
    pub total: usize,
    pub what: String,
}

/// Renders the reference, every configuration and the normalization rows;
/// `control` counts the reference's pixels, and a cancel through it stops
/// the work at the next step with [`ReferenceError::Cancelled`].
pub fn run(
    gpu: &GpuContext,
    scene: &Scene,
    base: &Settings,
    sweep: &[SweepPoint],
    options: &ReportOptions,
    control: &RenderControl,
    progress: &mut dyn FnMut(Step),
) -> anyhow::Result<Report> {
    let start = Instant::now();
    let mut base = base.clone();
    base.view.mode = DebugView::Shaded;
    base.validate()?;
    let size = (base.image.width, base.image.height);
    let norms = Normalization::ALL;
    let total = 1 + sweep.len() + norms.len() * options.normalization_ms.len();
    let mut step = 0;
    let mut tell = |what: String| {
        if control.cancel.load(std::sync::atomic::Ordering::Relaxed) {
            return Err(ReferenceError::Cancelled);
        }
        progress(Step {
            done: step,
            total,
            what,
        });
        step += 1;
        Ok(())
    };

    tell("reference (CPU ray tracing)".into())?;
    let reference_start = Instant::now();
    let reference = Reference::new(scene).render(&base, &options.reference, control)?;
    let reference_time = reference_start.elapsed();

    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, scene);
    renderer.render(&base, size);
    let comparison = Comparison::new(&reference, &renderer.read_aux());
    let reference_error = comparison.measure(comparison.reference());
    let error_scale = comparison.reference().mean_luminance().max(1e-12);

    let mut configurations = Vec::with_capacity(sweep.len());
    let mut gpu_timestamps = true;
    for point in sweep {
        tell(format!("GPU {}", point.label))?;
        let mut settings = base.clone();
        settings.shadow = point.shadow;
        let (measured, timestamps) =
            measure(&mut renderer, &settings, point, &comparison, error_scale, options);
        gpu_timestamps &= timestamps;
        configurations.push(measured);
    }
    let mut points: Vec<(f64, f64)> = configurations
        .iter()
        .map(|c| (c.times.frame_ms, c.error.rmse))
        .collect();
    points.push((reference_time.as_secs_f64() * 1e3, reference_error.rmse));
    let pareto = metrics::pareto_front(&points);

    let mut normalization = Vec::new();
    for &norm in norms {
        for &m in &options.normalization_ms {
            tell(format!("normalization {norm}, m = {m}"))?;
            normalization.push(normalization_row(&mut renderer, &base, norm, m));
        }
    }
    Ok(Report {
        adapter: gpu.describe(),
        gpu_timestamps,
        triangles: scene.triangle_count(),
        reference_time,
        reference_display: reference.to_display_rgba8(base.view.exposure_ev as f64),
        reference_error,
        configurations,
        pareto,
        normalization,
        error_scale,
        elapsed: start.elapsed(),
        settings: base,
    })
}

/// Renders one configuration at its exact settings (for the error), then
/// times `options.frames` frames with the light nudged by ±1 mm.
fn measure(
    renderer: &mut Renderer,
    settings: &Settings,
    point: &SweepPoint,
    comparison: &Comparison,
    error_scale: f64,
    options: &ReportOptions,
) -> (Measured, bool) {
    let size = (settings.image.width, settings.image.height);
    // A ray-traced point is its accumulated image: N frames of S rays.
    let frames = match settings.shadow.visibility {
        Visibility::RayTraced => settings.ray_traced_frames(),
        Visibility::ShadowMap => 1,
    };
    let mut report = renderer.render(settings, size);
    for _ in 1..frames {
        report = renderer.render(settings, size);
    }
    let frame = Frame::from_gpu(&renderer.read_quantity(), &renderer.read_aux());
    let error = comparison.measure(&frame);
    let error_image = page::error_image(&comparison.signed_error(&frame), &frame, size, error_scale);
    let shaded = renderer.read_display();
    let _ = renderer.wait_timings();

    let mut moved = settings.clone();
    let (mut walls, mut passes) = (Vec::new(), Vec::new());
    for frame in 0..options.frames.max(1) {
        moved.light.position.x = settings.light.position.x + if frame % 2 == 0 { 1e-3 } else { -1e-3 };
        let t = Instant::now();
        renderer.render(&moved, size);
        renderer.wait_idle();
        walls.push(t.elapsed().as_secs_f64() * 1e3);
        passes.extend(renderer.wait_timings());
    }
    let timestamps = !passes.is_empty();
    let pass =
        |f: fn(&PassTimes) -> Option<f64>| median(passes.iter().map(|p| f(p).unwrap_or(0.0)).collect());
    // The time to the measured image: every frame of an accumulation.
    let frames = frames as f64;
    let pass = |f: fn(&PassTimes) -> Option<f64>| frames * pass(f);
    let wall_ms = frames * median(walls);
    let times = FrameTimes {
        frame_ms: if timestamps {
            frames * median(passes.iter().map(PassTimes::total_ms).collect())
        } else {
            wall_ms
        },
        shadow_ms: pass(|p| p.shadow_ms),
        blur_ms: pass(|p| p.blur_ms),
        shade_ms: pass(|p| p.shade_ms),
        display_ms: pass(|p| p.display_ms),
        wall_ms,
    };
    let measured = Measured {
        label: point.label.clone(),
        shadow: point.shadow,
        resolution_used: report.resolution,
        times,
        error,
        shaded,
        error_image,
    };
    (measured, timestamps)
}

/// The scene with every object's k = 0 and exponent m under `norm`.
fn normalization_row(
    renderer: &mut Renderer,
    base: &Settings,
    norm: Normalization,
    m: f64,
) -> NormalizationRow {
    let mut settings = base.clone();
    settings.material.use_scene_materials = false;
    settings.material.k = 0.0;
    settings.material.m = m as f32;
    settings.material.norm = norm;
    renderer.render(&settings, (settings.image.width, settings.image.height));
    let frame = Frame::from_gpu(&renderer.read_quantity(), &renderer.read_aux());
    let params = crate::physics::BrdfParams { k: 0.0, m, norm };
    NormalizationRow {
        norm,
        m,
        albedo: energy::LECTURE_ANGLES_DEG
            .iter()
            .map(|&theta| energy::directional_albedo(theta, &params).value)
            .collect(),
        mean_radiance: frame.mean_luminance(),
    }
}

fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
