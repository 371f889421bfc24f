//! `lumlab report`: the speed-against-error sweep, written as a folder
//! (CSV, figures, images, index.html). The folder is built beside DIR under a
//! temporary name and renamed into place only when complete, so a failure
//! never leaves half a report.

use super::args::SceneOptions;
use super::reference::Sampling;
use crate::gpu::GpuContext;
use crate::report::{self, ReportOptions, Step, sweep};
use anyhow::Context;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

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
          value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub frames: u32,
    /// Output folder: created, or replaced when it holds an earlier report.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let (settings, scene) = super::render::load(&args.scene)?;
    let points = match &args.sweep {
        Some(path) => sweep::load(path, &settings)?,
        None => sweep::parse(sweep::DEFAULT_SWEEP, &settings)?,
    };
    let staging = Staging::new(&args.out)?;
    let gpu = GpuContext::headless()?;
    let options = ReportOptions {
        frames: args.frames as usize,
        reference: args.sampling.options(),
        ..ReportOptions::default()
    };
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
    let report = report::run(&gpu, &scene, &settings, &points, &options, &mut progress)?;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    report::page::write(&report, staging.path()).context("writing the report")?;
    staging.commit()?;
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

/// A temporary folder beside the destination, renamed over it on success
/// (and removed, with everything in it, otherwise).
struct Staging {
    dir: tempfile::TempDir,
    destination: PathBuf,
}

impl Staging {
    /// Refuses a destination that is a file, or a folder that holds
    /// something other than an earlier report.
    fn new(destination: &Path) -> anyhow::Result<Self> {
        let shown = destination.display();
        if destination.exists() {
            anyhow::ensure!(destination.is_dir(), "--out {shown}: exists and is not a folder");
            let empty = std::fs::read_dir(destination)
                .with_context(|| format!("--out {shown}"))?
                .next()
                .is_none();
            anyhow::ensure!(
                empty || destination.join("report.csv").is_file(),
                "--out {shown}: the folder is not empty and holds no earlier report; give a new or empty folder"
            );
        }
        let parent = match destination.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        anyhow::ensure!(
            parent.is_dir(),
            "--out {shown}: the folder {} does not exist",
            parent.display()
        );
        let dir = tempfile::Builder::new()
            .prefix(".lumlab-report-")
            .tempdir_in(parent)
            .map_err(|e| {
                anyhow::anyhow!(
                    "--out {shown}: cannot write in {}: {}",
                    parent.display(),
                    e.kind()
                )
            })?;
        Ok(Self {
            dir,
            destination: destination.to_owned(),
        })
    }

    fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Moves the finished report into place; an earlier report there is
    /// set aside first and removed after.
    fn commit(self) -> anyhow::Result<()> {
        let shown = self.destination.display().to_string();
        let parent = self.dir.path().parent().unwrap_or(Path::new(".")).to_owned();
        let old = if self.destination.exists() {
            let aside = tempfile::Builder::new()
                .prefix(".lumlab-report-old-")
                .tempdir_in(&parent)
                .with_context(|| format!("--out {shown}"))?;
            std::fs::rename(&self.destination, aside.path())
                .with_context(|| format!("--out {shown}: cannot replace the earlier report"))?;
            Some(aside)
        } else {
            None
        };
        let staged = self.dir.keep();
        if let Err(e) = std::fs::rename(&staged, &self.destination) {
            let _ = std::fs::remove_dir_all(&staged);
            if let Some(old) = &old {
                let _ = std::fs::rename(old.path(), &self.destination);
            }
            return Err(anyhow::anyhow!("--out {shown}: {e}"));
        }
        drop(old);
        Ok(())
    }
}
