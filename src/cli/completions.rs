//! `lumlab completions SHELL` and `lumlab manpage`: the shell completions
//! and the man page, generated from the clap definitions themselves so that
//! they can never disagree with the options.

use clap::CommandFactory;
use std::io::Write;

#[derive(Debug, clap::Args)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

/// Prints the completion script for `args.shell` on stdout.
pub fn completions(args: &CompletionsArgs) -> anyhow::Result<()> {
    let mut command = super::Cli::command();
    let mut out = std::io::stdout().lock();
    clap_complete::generate(args.shell, &mut command, "lumlab", &mut out);
    out.flush()?;
    Ok(())
}

/// Prints the man page (roff, section 1) on stdout.
pub fn manpage() -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    clap_mangen::Man::new(super::Cli::command()).render(&mut out)?;
    out.flush()?;
    Ok(())
}
