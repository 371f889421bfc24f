//! Ctrl-C, SIGTERM and SIGHUP during a command: the first one sets a flag
//! that the work polls (the reference render, the report's steps, every
//! file write), so the command stops at the next check, its temporary
//! files and folders are removed as the stack unwinds, and it exits with
//! 130; a second one quits at once.
//!
//! signal-hook rather than ctrlc: its handlers only store to an atomic
//! flag (async-signal-safe, no thread, no unsafe code here), it covers the
//! three terminating signals, and its one dependency besides libc is its
//! own registry crate.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

/// The command was stopped by a signal.
#[derive(Debug, thiserror::Error)]
#[error("interrupted; nothing was written")]
pub struct Interrupted;

/// Installs the handlers (once, before a command's work begins).
pub fn install() -> std::io::Result<()> {
    let flag = crate::output::interrupt_flag();
    for signal in [SIGINT, SIGTERM, SIGHUP] {
        // Registered first, so it sees the flag as the earlier signal left it.
        signal_hook::flag::register_conditional_shutdown(signal, EXIT_CODE, flag.clone())?;
        signal_hook::flag::register(signal, flag.clone())?;
    }
    Ok(())
}

/// An error when an interrupt has come: for the checks between steps.
pub fn check() -> Result<(), Interrupted> {
    if crate::output::interrupted() {
        Err(Interrupted)
    } else {
        Ok(())
    }
}

/// The exit status of an interrupted command (128 + SIGINT, as shells use).
pub const EXIT_CODE: i32 = 130;
