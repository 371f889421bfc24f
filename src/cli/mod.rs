//! The command line: `lumlab [COMMAND]`. Without a command the lab opens.
//!
//! Every command reads the same [`Settings`]: a `--settings FILE` first, then
//! the flags on top. Usage errors exit with 2, runtime errors with 1, each as
//! one line on stderr; output files are written atomically.

mod args;
mod energy;
mod reference;
mod render;

pub use args::SceneOptions;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// lumlab: a lighting lab for direct lighting (radiometry, BRDFs, shadow maps).
#[derive(Debug, Parser)]
#[command(name = "lumlab", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Directional albedo a(θ) of the BRDF: the energy-conservation table.
    Energy(energy::EnergyArgs),
    /// Render the scene on the GPU, headless, to PNG or EXR.
    Render(render::RenderArgs),
    /// Ray-trace the scene on the CPU (the exact reference), to PNG or EXR.
    Reference(reference::ReferenceArgs),
}

/// Parses the arguments and runs the command; the binary's whole `main`.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    let result = match cli.command {
        Some(Command::Energy(args)) => energy::run(&args),
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Reference(args)) => reference::run(&args),
        None => anyhow::Result::Err(anyhow::anyhow!(
            "the lab window is not built yet: try 'lumlab energy'"
        )),
    };
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
