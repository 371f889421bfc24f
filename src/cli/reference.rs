//! `lumlab reference`: the CPU ray-traced image. PNG holds what the lab
//! displays (exposure, then sRGB); EXR the linear radiance in W/m²/sr with the
//! coverage in alpha.

use super::args::SceneOptions;
use crate::image_io::{ImageFormat, write_exr, write_png_rgba8};
use crate::reference::{Reference, ReferenceImage, ReferenceOptions, RenderControl};
use crate::settings::Settings;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

#[derive(Debug, clap::Args)]
pub struct ReferenceArgs {
    #[command(flatten)]
    pub scene: SceneOptions,
    #[command(flatten)]
    pub sampling: Sampling,
    /// Output image: .png (displayed) or .exr (linear radiance).
    #[arg(long, value_name = "FILE.png|FILE.exr", value_parser = output_path)]
    pub out: PathBuf,
}

/// How many samples the reference takes (shared by `reference` and `report`).
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct Sampling {
    /// Primary samples per pixel: 1 = the pixel centre; more are stratified over the pixel (box filter).
    #[arg(long, value_name = "N", default_value_t = ReferenceOptions::DEFAULT.spp,
          value_parser = clap::value_parser!(u32).range(1..=65536), allow_negative_numbers = true)]
    pub spp: u32,
    /// Samples of the sphere light's cone per primary sample (squares stratify best).
    #[arg(long, value_name = "N", default_value_t = ReferenceOptions::DEFAULT.light_samples,
          value_parser = clap::value_parser!(u32).range(1..=1048576), allow_negative_numbers = true)]
    pub light_samples: u32,
    /// Seed of the random numbers (same seed, same image).
    #[arg(long, value_name = "S", default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// Sample the sphere light's cone even where nothing can block it (plain
    /// Monte Carlo everywhere, to show its noise); by default the diffuse
    /// part there is the closed form, exact and noiseless.
    #[arg(long)]
    pub sample_everywhere: bool,
}

impl Sampling {
    pub fn options(&self) -> ReferenceOptions {
        ReferenceOptions {
            spp: self.spp,
            light_samples: self.light_samples,
            seed: self.seed,
            sample_everywhere: self.sample_everywhere,
        }
    }
}

/// The output path, refused at parse time unless it ends in .png or .exr.
pub(super) fn output_path(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    ImageFormat::of_path(&path).map_err(|e| e.to_string())?;
    Ok(path)
}

pub fn run(args: &ReferenceArgs) -> anyhow::Result<()> {
    let format = ImageFormat::of_path(&args.out)?;
    super::render::check_out("--out", &args.out)?;
    let (settings, scene) = super::render::load(&args.scene)?;
    let options = args.sampling.options();
    let estimate = super::cost::reference(&settings, &options, scene.triangle_count());
    super::cost::check_cpu("the reference", estimate, args.scene.yes)?;
    let start = Instant::now();
    let reference = Reference::new(&scene);
    let build = start.elapsed();
    if reference.skipped_triangles() > 0 {
        eprintln!(
            "lumlab: {} triangle(s) with indices outside their mesh were skipped",
            reference.skipped_triangles()
        );
    }
    let image = render_with_progress(&reference, &settings, &options)?;
    match format {
        ImageFormat::Png => write_png_rgba8(
            &args.out,
            &image.to_display_rgba8(settings.view.exposure_ev as f64),
        )?,
        ImageFormat::Exr => write_exr(&args.out, (image.width, image.height), |x, y| {
            image.linear_rgba(x, y)
        })?,
    }
    eprintln!("{}", summary(&settings, &reference, &image, build));
    Ok(())
}

/// Renders on the thread pool while this thread draws a progress bar (when
/// stderr is a terminal) and passes an interrupt on as a cancel.
pub fn render_with_progress(
    reference: &Reference,
    settings: &Settings,
    options: &ReferenceOptions,
) -> anyhow::Result<ReferenceImage> {
    let control = RenderControl::default();
    let bar = std::io::stderr().is_terminal().then(|| {
        let pixels = settings.image.width as u64 * settings.image.height as u64;
        let bar = indicatif::ProgressBar::new(pixels);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "reference {bar:40} {percent:>3}%  {elapsed_precise} (about {eta} left)",
        ) {
            bar.set_style(style);
        }
        bar
    });
    let result = watch(
        &control,
        || reference.render(settings, options, &control),
        |done| {
            if let Some(bar) = &bar {
                bar.set_position(done as u64);
            }
        },
    );
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    super::interrupt::check()?;
    Ok(result??)
}

/// Runs `work` on another thread; every 50 ms this one reports the pixels
/// done and turns an interrupt into a cancel of `control`. It returns as soon
/// as the work ends (the wait is on a channel, not a sleep: a 15 ms render
/// no longer waits out the rest of a 50 ms tick).
pub(super) fn watch<T: Send>(
    control: &RenderControl,
    work: impl FnOnce() -> T + Send,
    mut progress: impl FnMut(usize),
) -> anyhow::Result<T> {
    let result = std::thread::scope(|s| {
        let (done, finished) = std::sync::mpsc::channel::<()>();
        let worker = s.spawn(move || {
            let result = work();
            // The watcher may have gone (it never does before the join).
            let _ = done.send(());
            result
        });
        // A panic drops the sender: the wait ends too, and the join says so.
        while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(Duration::from_millis(50)) {
            if crate::output::interrupted() {
                control.cancel();
            }
            progress(control.pixels_done.load(Ordering::Relaxed));
        }
        worker.join()
    });
    result.map_err(|_| anyhow::anyhow!("the reference render stopped unexpectedly"))
}

/// One line: size, light, time, rays and the noise estimate.
fn summary(settings: &Settings, reference: &Reference, image: &ReferenceImage, build: Duration) -> String {
    let stats = &image.stats;
    let seconds = stats.elapsed.as_secs_f64();
    let light = if settings.light.is_sphere() {
        format!(
            "sphere light R = {} m, {} light samples",
            settings.light.radius_m, stats.light_samples
        )
    } else {
        "point light".to_string()
    };
    let noise = image.noise_summary();
    let noise_text = if !noise.known {
        "noise: not estimated (one sample per pixel and one light sample)".to_string()
    } else if noise.rms_std_error == 0.0 {
        "noise: none (exact)".to_string()
    } else {
        format!(
            "noise: RMS standard error {:.3e} W/m²/sr = {:.3} % of the mean (max {:.3e})",
            noise.rms_std_error,
            100.0 * noise.relative,
            noise.max_std_error
        )
    };
    format!(
        "reference {}×{}, {} triangles, {light}, {} spp: {:.4} s (BVH {:.4} s), {:.2} M rays ({:.2} M rays/s); {noise_text}",
        image.width,
        image.height,
        reference.triangle_count(),
        stats.spp,
        seconds,
        build.as_secs_f64(),
        stats.rays() as f64 * 1e-6,
        stats.rays() as f64 * 1e-6 / seconds.max(1e-9),
    )
}
