//! The command line: `lumlab [COMMAND]`. Without a command the lab opens.
//!
//! Every command reads the same [`Settings`](crate::settings::Settings): a `--settings FILE` first, then
//! the flags on top. Usage errors exit with 2, runtime errors with 1, each as
//! one line on stderr; output files are written atomically.

mod args;
mod completions;
mod energy;
mod info;
mod reference;
mod render;
mod report;
mod stability;

pub use args::SceneOptions;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// lumlab: a lighting lab for direct lighting (radiometry, BRDFs, shadow maps).
#[derive(Debug, Parser)]
#[command(name = "lumlab", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Settings file (TOML) to start the lab with, instead of the last session's.
    #[arg(long, value_name = "FILE")]
    pub settings: Option<PathBuf>,
    /// glTF or GLB scene to open in the lab.
    #[arg(long, value_name = "FILE.gltf|FILE.glb")]
    pub scene: Option<PathBuf>,
    /// Save a screenshot of the whole window after N frames (see
    /// --quit-after-frames, default 3), then quit.
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<PathBuf>,
    /// Quit after this many frames (with --screenshot: take it then).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub quit_after_frames: Option<u32>,
}

impl Cli {
    /// The window's options; an error when they come with a command
    /// (commands take their own --settings and --scene after their name).
    fn launch_options(&self) -> anyhow::Result<crate::app::LaunchOptions> {
        let options = crate::app::LaunchOptions {
            settings: self.settings.clone(),
            scene: self.scene.clone(),
            screenshot: self.screenshot.clone(),
            quit_after_frames: self.quit_after_frames,
        };
        let any = options.settings.is_some() || options.scene.is_some() || options.is_scripted();
        if any && self.command.is_some() {
            anyhow::bail!(
                "--settings, --scene, --screenshot and --quit-after-frames before a command apply to the \
                 window only; put a command's options after its name (e.g. 'lumlab render --settings FILE')"
            );
        }
        Ok(options)
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Print a shell completion script (e.g. `lumlab completions bash > ~/.local/share/bash-completion/completions/lumlab`).
    Completions(completions::CompletionsArgs),
    /// Print the man page (e.g. `lumlab manpage > ~/.local/share/man/man1/lumlab.1`).
    Manpage,
    /// Directional albedo a(θ) of the BRDF: the energy-conservation table.
    Energy(energy::EnergyArgs),
    /// Facts of a scene: counts, bounds, objects, cameras, repairs.
    Info(info::InfoArgs),
    /// Render the scene on the GPU, headless, to PNG or EXR.
    Render(render::RenderArgs),
    /// Ray-trace the scene on the CPU (the exact reference), to PNG or EXR.
    Reference(reference::ReferenceArgs),
    /// Speed against error: a sweep of shadow settings measured against the reference (CSV, Pareto plot, HTML).
    Report(report::ReportArgs),
    /// Hard cases (m = 1e6, 89.99°, r = 0, far/near = 1e8…) in f64, f32 and on the GPU, beside naive formulas.
    Stability(stability::StabilityArgs),
}

/// Parses the arguments and runs the command; the binary's whole `main`.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    let result = cli.launch_options().and_then(|options| match &cli.command {
        Some(Command::Completions(args)) => completions::completions(args),
        Some(Command::Manpage) => completions::manpage(),
        Some(Command::Energy(args)) => energy::run(args),
        Some(Command::Info(args)) => info::run(args),
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Reference(args)) => reference::run(args),
        Some(Command::Report(args)) => report::run(args),
        Some(Command::Stability(args)) => stability::run_command(args),
        None => crate::app::run(options),
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lumlab: error: {}", one_line(&e));
            ExitCode::from(1)
        }
    }
}

/// Help and version print as clap formats them; any other parse error is
/// reduced to its first line and exits with 2.
fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        let _ = e.print();
        return ExitCode::SUCCESS;
    }
    let text = e.to_string();
    let first = text
        .lines()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("invalid arguments");
    eprintln!("lumlab: {}", first.trim());
    ExitCode::from(2)
}

/// An error and its causes on one line.
pub fn one_line(e: &anyhow::Error) -> String {
    e.chain()
        .map(|c| c.to_string().replace('\n', " "))
        .collect::<Vec<_>>()
        .join(": ")
}
