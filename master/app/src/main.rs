//! `slender`: run, check and benchmark co-simulation scenes, study them, and export
//! their units as FMUs. The arguments are in `cli.rs`, what each command does in
//! `commands/`.

mod cli;
mod commands;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    end_quietly_on_a_closed_pipe();
    slender_app::interrupt::install();
    match commands::dispatch(cli::Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", e.message);
            ExitCode::from(e.code)
        }
    }
}

/// A reader that closes the pipe (`slender check big.toml | head -1`) ends the
/// command quietly, as any Unix tool does: Rust ignores SIGPIPE, so the next
/// print would panic on the broken pipe instead (exit 101 and a backtrace).
#[cfg(unix)]
fn end_quietly_on_a_closed_pipe() {
    // SAFETY: called first in `main`, before any thread starts; restoring a
    // signal's default disposition touches no Rust state.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

#[cfg(not(unix))]
fn end_quietly_on_a_closed_pipe() {}
