//! `slender`: run, check and benchmark co-simulation scenes, study them, and export
//! their units as FMUs. The arguments are in `cli.rs`, what each command does in
//! `commands/`.

mod cli;
mod commands;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    match commands::dispatch(cli::Cli::parse().command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", e.message);
            ExitCode::from(e.code)
        }
    }
}
