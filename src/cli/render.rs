//! `lumlab render`: the GPU image, headless. PNG holds what the lab displays;
//! EXR the linear quantity of the view (radiance in W/m²/sr for `shaded`).

use super::args::SceneOptions;
use crate::gpu::{GpuContext, Renderer};
use crate::image_io::{ImageFormat, write_exr_texels, write_png_rgba8};
use crate::reference::{Reference, ReferenceOptions};
use crate::scene::Scene;
use crate::settings::{DebugView, Settings, Visibility};
use anyhow::Context;
use std::path::{Path, PathBuf};

#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneOptions,
    /// Output image: .png (displayed) or .exr (linear values).
    #[arg(long, value_name = "FILE.png|FILE.exr", value_parser = super::reference::output_path)]
    pub out: PathBuf,
    /// Ray-traced visibility: render N frames and average them (the sphere
    /// light's noise falls as 1/√N); needs `--visibility ray-traced`.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=65536),
          allow_negative_numbers = true)]
    pub accumulate: Option<u32>,
    /// Ray-traced visibility under a sphere light: stop accumulating at the
    /// first power of two of frames whose measured noise (RMS standard
    /// error) is at most P % of the mean, or at `--accumulate N` (else the
    /// settings' frames); needs `--visibility ray-traced`.
    #[arg(long, value_name = "P", value_parser = noise_target)]
    pub noise_target: Option<f32>,
    /// Print the GPU adapter used.
    #[arg(long)]
    pub adapter_info: bool,
}

/// The settings and the scene they draw. A loaded scene, unless the
/// settings file was saved for it, is framed and lit from its own bounds
/// (the flags still override); a `gltf:N` camera is resolved against it;
/// the ground the settings ask for is added. The loader's repairs are
/// printed as warnings, and a physically impossible set-up is refused (or,
/// with `--allow-impossible`, warned of).
pub fn load(options: &SceneOptions) -> anyhow::Result<(Settings, Scene)> {
    let (mut settings, saved) = options.base()?;
    let scene = crate::scene::for_settings(&settings)?;
    for warning in &scene.warnings {
        eprintln!("lumlab: warning: {warning}");
    }
    if settings.scene.is_some() && !saved {
        crate::scene::framing::adopt(&mut settings, &scene);
    }
    let gltf_camera = options.apply_flags(&mut settings)?;
    if let Some(n) = gltf_camera {
        let camera = scene.cameras.get(n).ok_or_else(|| {
            super::usage(format!(
                "--camera gltf:{n}: the scene has {} camera(s)",
                scene.cameras.len()
            ))
        })?;
        settings.camera = camera.camera;
        settings.validate().context("camera from the scene file")?;
    }
    let scene = crate::scene::framing::with_ground(scene, &settings.ground);
    let impossible = crate::scene::plausibility::impossible_setups(&scene, &settings);
    if options.allow_impossible {
        for line in &impossible {
            eprintln!("lumlab: warning: {line}");
        }
    } else if !impossible.is_empty() {
        return Err(super::usage(format!(
            "{}; the GPU and the reference would disagree (--allow-impossible draws it anyway)",
            impossible.join("; ")
        )));
    }
    Ok((settings, scene))
}

/// Checks `--out` before any work: a usage error naming the flag.
pub fn check_out(flag: &str, path: &Path) -> anyhow::Result<PathBuf> {
    crate::output::check_writable(path).map_err(|e| super::usage(format!("{flag} {e}")))
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let format = ImageFormat::of_path(&args.out)?;
    check_out("--out", &args.out)?;
    let (mut settings, scene) = load(&args.scene)?;
    let traced = settings.shadow.visibility == Visibility::RayTraced;
    for (flag, given) in [
        ("--accumulate", args.accumulate.is_some()),
        ("--noise-target", args.noise_target.is_some()),
    ] {
        if given && !traced {
            return Err(super::usage(format!("{flag} needs --visibility ray-traced")));
        }
    }
    let frames = match (args.accumulate, args.noise_target) {
        (Some(n), _) => n,
        (None, Some(_)) => settings.ray_traced_frames(),
        (None, None) => 1,
    };
    if let Some(n) = args.accumulate {
        settings.shadow.rt_max_frames = n;
    }
    // Without a spectrum both colour models are the RGB one: no ΔE to show.
    let no_delta_e = settings.view.mode == DebugView::DeltaE && settings.colour.illuminant.is_none();
    if no_delta_e {
        eprintln!(
            "lumlab: warning: --view delta-e compares the RGB approximation with the spectral result \
             and needs --illuminant (D65, A, …); the image shows a checker"
        );
    }
    // These views compare with the CPU reference of the same settings.
    let compare = matches!(settings.view.mode, DebugView::Error | DebugView::RefVisibility);
    let reference_options = ReferenceOptions::DEFAULT;
    if compare {
        let estimate = super::cost::reference(&settings, &reference_options, scene.triangle_count());
        super::cost::check_cpu("the reference for this view", estimate, args.scene.yes)?;
    }
    let gpu = GpuContext::headless()?;
    if args.adapter_info {
        eprintln!("adapter: {}", gpu.describe());
    }
    let size = (settings.image.width, settings.image.height);
    super::cost::check_gpu(&gpu.device.limits(), &gpu.describe(), size)?;
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    if compare {
        let reference = Reference::new(&scene);
        let image = super::reference::render_with_progress(&reference, &settings, &reference_options)?;
        renderer.set_comparison(Some(image.to_comparison()));
    }
    let start = std::time::Instant::now();
    let mut report = renderer.render(&settings, size);
    for n in 2..=frames {
        report = renderer.render(&settings, size);
        if let Some(target) = args.noise_target
            && n.is_power_of_two()
        {
            // The probe reads the mean back at powers of two (gpu::noise).
            renderer.settle_noise();
            if renderer.accumulation().is_some_and(|a| a.meets(target)) {
                break;
            }
        }
    }
    let accumulated_s = start.elapsed().as_secs_f64();
    if let Some(note) = &report.resolution_note {
        eprintln!(
            "lumlab: shadow-map resolution clamped to {}: {note}",
            report.resolution
        );
    }
    match format {
        ImageFormat::Png => {
            let image = renderer.read_display();
            let legend = crate::gpu::colormap::legend(settings.view.mode, renderer.read_scale())
                .filter(|_| !no_delta_e);
            match legend {
                Some(legend) => write_png_rgba8(&args.out, &crate::plot::with_legend(&image, &legend)?)?,
                None => write_png_rgba8(&args.out, &image)?,
            }
        }
        ImageFormat::Exr => {
            write_exr_texels(&args.out, size, &renderer.read_quantity())?;
        }
    }
    let times = renderer.wait_timings();
    renderer.settle_noise();
    let visibility = match renderer.accumulation() {
        Some(a) => format!(
            "ray traced, {} frame(s) × {} ray(s) per pixel{}{}, {accumulated_s:.2} s",
            a.frames,
            a.rays_per_frame,
            a.estimate.map_or(String::new(), |e| format!(
                ", noise: RMS standard error {:.3} % of the mean (frames {} → {})",
                100.0 * e.relative,
                e.earlier_frames,
                e.frames
            )),
            args.noise_target
                .filter(|&t| a.meets(t))
                .map_or(String::new(), |t| format!(", at most the {t} % asked for")),
        ),
        None => format!("shadow map {}² ({})", report.resolution, report.layout_summary()),
    };
    eprintln!(
        "rendered {}×{} ({}, {} triangles); {visibility}; GPU {}",
        size.0,
        size.1,
        settings.view.mode,
        scene.triangle_count(),
        times.map_or("time n/a".into(), |t| t.to_string()),
    );
    Ok(())
}

/// `--noise-target P`: a percentage of the mean, 0 < P ≤ 100.
fn noise_target(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(p) if p > 0.0 && p <= 100.0 => Ok(p),
        _ => Err(format!("'{text}' is not a percentage in (0, 100]")),
    }
}
