//! The user guide's tutorials (`docs/tutorials/*.md`) run as written, in
//! order, in a fresh folder that sees the repository's `examples/`:
//! - every command of a ```sh block runs in full through the shell and exits 0;
//! - a study, fidelity or uq command of a ```text block (too long to run here:
//!   minutes) is checked up to its first run with `--max-runs 0`;
//! - a ```console block's `$ ` command runs, and the lines under it (its
//!   output as the tutorial shows it) are found in what it printed.
//!
//! The files a tutorial names under `results/` must then exist.

use crate::common;

use common::text;
use std::path::{Path, PathBuf};
use std::process::Command;

/// How a fenced block's commands are checked.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Block {
    Run,
    CheckedToTheStart,
    Shown,
}

/// One command of a tutorial and the output lines it must print.
#[derive(Debug)]
struct Step {
    block: Block,
    command: String,
    expected: Vec<String>,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The commands of a tutorial's fenced blocks, in order.
fn steps_of(markdown: &str) -> Vec<Step> {
    let mut steps: Vec<Step> = Vec::new();
    let mut block = None;
    let mut pending = String::new();
    // The steps before the open block: a block's lines are the output of
    // its own command only (a Python or TOML block shows no output).
    let mut before_block = 0;
    for line in markdown.lines() {
        if let Some(fence) = line.trim_start().strip_prefix("```") {
            before_block = steps.len();
            block = match block {
                Some(_) => None,
                None if fence == "sh" => Some(Block::Run),
                None if fence == "text" => Some(Block::CheckedToTheStart),
                None => Some(Block::Shown),
            };
            continue;
        }
        let Some(kind) = block else { continue };
        let command = match kind {
            Block::Shown => line.strip_prefix("$ ").map(str::to_owned),
            _ if !pending.is_empty() || line.starts_with("slender ") => Some(line.to_owned()),
            _ => None,
        };
        match (command, kind) {
            (Some(command), _) => {
                pending.push_str(command.trim_end_matches('\\'));
                if !command.ends_with('\\') {
                    steps.push(Step {
                        block: kind,
                        command: std::mem::take(&mut pending),
                        expected: Vec::new(),
                    });
                }
            }
            (None, Block::Shown) if !line.trim().is_empty() => {
                if steps.len() > before_block
                    && let Some(step) = steps.last_mut().filter(|s| s.block == Block::Shown)
                {
                    step.expected.push(line.trim().to_owned());
                }
            }
            _ => {}
        }
    }
    steps
}

/// Runs `command` through the shell in `dir`, `slender` on the PATH.
fn shell(dir: &Path, command: &str) -> std::process::Output {
    let binary = Path::new(env!("CARGO_BIN_EXE_slender"));
    let path = format!(
        "{}:{}",
        binary.parent().expect("the binary's folder").display(),
        std::env::var("PATH").unwrap_or_default()
    );
    Command::new("sh")
        .args(["-c", command])
        .current_dir(dir)
        .env("PATH", path)
        .output()
        .expect("sh runs")
}

/// Runs one tutorial; panics naming the command that did not do as shown.
fn run_tutorial(name: &str) {
    let markdown = std::fs::read_to_string(root().join("docs/tutorials").join(name)).unwrap();
    let steps = steps_of(&markdown);
    assert!(
        steps.iter().any(|s| s.block == Block::Run),
        "{name}: no command"
    );
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root().join("examples"), dir.path().join("examples")).unwrap();
    for step in &steps {
        let command = match step.block {
            Block::CheckedToTheStart => format!("{} --max-runs 0", step.command),
            _ => step.command.clone(),
        };
        let output = shell(dir.path(), &command);
        let printed = format!("{}{}", text(&output.stdout), text(&output.stderr));
        eprintln!("{name}: {command}: exit {:?}", output.status.code());
        match step.block {
            Block::Run => assert!(output.status.success(), "{name}: {command}\n{printed}"),
            Block::CheckedToTheStart => assert!(
                printed.contains("more than the bound of 0"),
                "{name}: {command} was refused before its size was checked:\n{printed}"
            ),
            Block::Shown => {
                for line in &step.expected {
                    assert!(
                        printed.contains(line),
                        "{name}: {command} did not print `{line}`:\n{printed}"
                    );
                }
            }
        }
    }
    for file in results_named(&markdown) {
        assert!(
            dir.path().join(&file).exists(),
            "{name}: {file} was not written"
        );
    }
}

/// The `results/...` paths a tutorial names in its prose (code spans).
fn results_named(markdown: &str) -> Vec<String> {
    let prose: String = markdown
        .split("```")
        .step_by(2)
        .collect::<Vec<_>>()
        .join(" ");
    prose
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| span.starts_with("results/") && !span.contains(' '))
        .map(str::to_owned)
        .collect()
}

#[test]
fn every_tutorial_is_listed_in_the_guide() {
    let summary = std::fs::read_to_string(root().join("docs/SUMMARY.md")).unwrap();
    let mut count = 0;
    for entry in std::fs::read_dir(root().join("docs/tutorials")).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(summary.contains(&format!("(tutorials/{name})")), "{name}");
        count += 1;
    }
    assert_eq!(count, 7);
}

#[test]
fn design_check() {
    run_tutorial("design-check.md");
}

#[test]
fn moored_body() {
    run_tutorial("moored-body.md");
}

#[test]
fn first_scene() {
    run_tutorial("first-scene.md");
}

#[test]
fn structure_and_fidelity_study() {
    run_tutorial("structure-fidelity.md");
}

#[test]
fn coupling_an_fmu() {
    run_tutorial("fmu.md");
}

#[test]
fn uncertainty_study() {
    run_tutorial("uncertainty.md");
}

#[test]
fn paced_real_time_run() {
    run_tutorial("realtime.md");
}
