//! The command line: `lumlab [COMMAND]`. Without a command the lab opens.
//!
//! Every command reads the same [`Settings`](crate::settings::Settings): a `--settings FILE` first, then
//! the flags on top. Usage errors (the command line asks for what cannot be
//! done as given: a bad or missing flag, a value out of range, an unusable
//! output path, work beyond the machine or above the cost threshold without
//! `--yes`) exit with 2, runtime errors (a file that cannot be read, no GPU,
//! a failed write) with 1, an interrupt with 130, each as one line on
//! stderr; output files are written atomically.

mod args;
mod colour;
mod completions;
mod cost;
mod energy;
mod info;
pub mod interrupt;
mod reference;
mod render;
mod report;
mod stability;

pub use args::SceneOptions;
pub use render::load as load_scene;

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
    /// Open the lab at the first step of the lecture tour: the built-in one
    /// (assets/tour.toml), or FILE.
    #[arg(long, value_name = "FILE", num_args = 0..=1)]
    pub tour: Option<Option<PathBuf>>,
    /// Measure the window's frame rate while dragging: orbit over the
    /// viewport (or see --drag-bench-target) for N frames, print the
    /// frames/s and render scales, quit.
    #[arg(long, value_name = "N", hide = true, value_parser = clap::value_parser!(u32).range(1..))]
    pub drag_bench: Option<u32>,
    /// What --drag-bench drags: the camera's orbit, the light gizmo or the
    /// light radius slider.
    #[arg(long, value_name = "orbit|light|slider", hide = true, requires = "drag_bench")]
    pub drag_bench_target: Option<crate::app::DragTarget>,

    /// Where drag frames render: auto (a device of their own on software
    /// adapters), same (the window's) or own (for measuring).
    #[arg(long, value_name = "auto|same|own", hide = true)]
    pub drag_device: Option<crate::app::DragDevice>,
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
            tour: self.tour.clone(),
            drag_bench_frames: self.drag_bench,
            drag_bench_target: self.drag_bench_target.unwrap_or_default(),
            drag_device: self.drag_device.unwrap_or_default(),
        };
        let any = options.settings.is_some()
            || options.scene.is_some()
            || options.tour.is_some()
            || self.drag_device.is_some()
            || options.is_scripted();
        if any && self.command.is_some() {
            return Err(usage(
                "--settings, --scene, --tour, --screenshot and --quit-after-frames before a command apply to the \
                 window only; put a command's options after its name (e.g. 'lumlab render --settings FILE')",
            ));
        }
        Ok(options)
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Spectral colour of the ColorChecker under an illuminant, against the lecture's RGB product (ΔE2000).
    Colour(colour::ColourArgs),
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
    // The commands that write files stop cleanly on an interrupt; the others
    // keep the default (end at once), as they leave nothing behind.
    let writes = matches!(
        cli.command,
        Some(Command::Render(_) | Command::Reference(_) | Command::Report(_) | Command::Energy(_))
    );
    if writes && let Err(e) = interrupt::install() {
        eprintln!("lumlab: error: cannot install the interrupt handler: {e}");
        return ExitCode::from(1);
    }
    let result = cli.launch_options().and_then(|options| match &cli.command {
        Some(Command::Colour(args)) => colour::run(args),
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
        Err(_) if crate::output::interrupted() => {
            eprintln!("lumlab: {}", interrupt::Interrupted);
            ExitCode::from(interrupt::EXIT_CODE as u8)
        }
        Err(e) => {
            eprintln!("lumlab: error: {}", one_line(&e));
            if e.chain().any(|c| c.is::<Usage>()) {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

/// A usage error: the command line asks for what cannot be done as given
/// (exit 2). Wrapped around any error, at any depth of its chain.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct Usage(pub String);

/// `Err(Usage)` with a message.
pub fn usage(message: impl Into<String>) -> anyhow::Error {
    Usage(message.into()).into()
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
    let mut lines = text.lines().skip_while(|l| l.trim().is_empty());
    let mut message = lines.next().unwrap_or("invalid arguments").trim().to_owned();
    if e.kind() == ErrorKind::MissingRequiredArgument {
        // clap lists the missing flags on the lines below: name them.
        for flag in lines.take_while(|l| l.starts_with(' ') && !l.trim().is_empty()) {
            message = format!("{message} {}", flag.trim());
        }
    }
    eprintln!("lumlab: {message}");
    ExitCode::from(2)
}

/// An error and its causes on one line; a cause that the message already
/// quotes (as `cannot read '{path}': {source}` does) is not repeated.
pub fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string().replace('\n', " ");
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line += ": ";
        }
        line += &text;
    }
    line
}
