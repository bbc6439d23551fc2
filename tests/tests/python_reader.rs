//! The Python reader (`python/slender`, issue 28) against the CLI's own files:
//! tests/python/reader_checks.py runs B1, a study, a fidelity study and bad
//! input through the package and compares its frames with the CSV files.
//!
//! Needs pandas and the package in the test environment (.venv: `./scripts/test.sh`
//! installs both); ignored in a plain `cargo test`, run by test.sh with `--ignored`.

use slender_tests::{fmu, root};
use std::process::Command;

/// Runs `tests/python/SCRIPT` in the test venv with the release CLI; fails
/// with what it printed.
fn python_checks(script: &str) {
    let binary = root().join("target/release/slender");
    assert!(
        binary.is_file(),
        "build the CLI first: cargo build --release"
    );
    let out = Command::new(fmu::python())
        .arg(root().join("tests/python").join(script))
        .arg(root())
        .env("SLENDER_BINARY", &binary)
        .output()
        .expect("run python");
    println!("{}", String::from_utf8_lossy(&out.stdout));
    assert!(
        out.status.success(),
        "{script}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
#[ignore = "needs the slender package in .venv: ./scripts/test.sh runs it"]
fn the_python_reader_returns_what_the_cli_wrote() {
    python_checks("reader_checks.py");
}

#[test]
#[ignore = "needs scipy, rainflow and the slender package in .venv: ./scripts/test.sh runs it"]
fn a_runs_spectra_fatigue_and_cases_agree_with_scipy_rainflow_and_pandas() {
    python_checks("analysis_checks.py");
}
