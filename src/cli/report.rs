//! `lumlab report`: the speed-against-error sweep, written as a folder
//! (CSV, figures, images, index.html). The folder is new, empty or an
//! earlier report's ([`report::folder`]); the report is staged beside it and
//! moved in only when complete, so a failure or an interrupt never leaves
//! half a report.

use super::args::SceneOptions;
use super::reference::Sampling;
use crate::gpu::GpuContext;
use crate::reference::RenderControl;
use crate::report::folder::ReportFolder;
use crate::report::{self, ReportOptions, Step, sweep};
use anyhow::Context;
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    #[command(flatten)]
    pub scene: SceneOptions,
    #[command(flatten)]
    pub sampling: Sampling,
    /// Shadow configurations to measure: a TOML file with [[config]] tables and/or a [cross] table of value
    /// lists (keys of the settings file's [shadow] table; bias also as 'slope:D,S'). Default: 2 resolutions ×
    /// 6 filters × 2 biases.
    #[arg(long, value_name = "FILE.toml")]
    pub sweep: Option<PathBuf>,
    /// Timed frames per configuration (the median is reported).
    #[arg(long, value_name = "N", default_value_t = report::DEFAULT_FRAMES as u32,
          value_parser = clap::value_parser!(u32).range(1..=1000), allow_negative_numbers = true)]
    pub frames: u32,
    /// Output folder: new, empty, or an earlier report's (its files are replaced, others kept).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let folder = ReportFolder::prepare(&args.out).map_err(|e| super::usage(format!("--out {e}")))?;
    let (settings, scene) = super::render::load(&args.scene)?;
    let points = match &args.sweep {
        Some(path) => sweep::load(path, &settings)?,
        None => sweep::parse(sweep::DEFAULT_SWEEP, &settings)?,
    };
    let options = ReportOptions {
        frames: args.frames as usize,
        reference: args.sampling.options(),
        ..ReportOptions::default()
    };
    let estimate = super::cost::reference(&settings, &options.reference, scene.triangle_count());
    super::cost::check_cpu("the report's reference", estimate, args.scene.yes)?;
    let gpu = GpuContext::headless()?;
    let size = (settings.image.width, settings.image.height);
    super::cost::check_gpu(&gpu.device.limits(), &gpu.describe(), size)?;
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(1);
        if let Ok(style) =
            indicatif::ProgressStyle::with_template("report {bar:30} {pos}/{len} {msg} ({elapsed})")
        {
            bar.set_style(style);
        }
        bar
    });
    let mut progress = |step: Step| {
        if let Some(bar) = &bar {
            bar.set_length(step.total as u64);
            bar.set_position(step.done as u64);
            bar.set_message(step.what);
        }
    };
    let control = RenderControl::default();
    let work = || {
        report::run(
            &gpu,
            &scene,
            &settings,
            &points,
            &options,
            &control,
            &mut progress,
        )
    };
    let report = super::reference::watch(&control, work, |_| {});
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    super::interrupt::check()?;
    let report = report??;
    report::page::write(&report, folder.staging()).context("writing the report")?;
    super::interrupt::check()?;
    folder.commit()?;
    let best = report
        .configurations
        .iter()
        .zip(&report.pareto)
        .filter(|(_, on)| **on)
        .map(|(c, _)| c.label.as_str())
        .collect::<Vec<_>>();
    eprintln!(
        "report: {} configurations and the reference in {:.1} s on {}; Pareto front: {}; open {}",
        report.configurations.len(),
        report.elapsed.as_secs_f64(),
        report.adapter,
        best.join(" | "),
        args.out.join("index.html").display()
    );
    Ok(())
}
