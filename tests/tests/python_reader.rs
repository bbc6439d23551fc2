//! The Python reader (`python/slender`, issue 28) against the CLI's own files:
//! tests/python/reader_checks.py runs B1, a study, a fidelity study and bad
//! input through the package and compares its frames with the CSV files.
//!
//! Needs pandas and the package in the test environment (.venv: `./scripts/test.sh`
//! installs both); ignored in a plain `cargo test`, run by test.sh with `--ignored`.

use slender_tests::{fmu, root};
use std::process::Command;

#[test]
#[ignore = "needs the slender package in .venv: ./scripts/test.sh runs it"]
fn the_python_reader_returns_what_the_cli_wrote() {
    let binary = root().join("target/release/slender");
    assert!(
        binary.is_file(),
        "build the CLI first: cargo build --release"
    );
    let out = Command::new(fmu::python())
        .arg(root().join("tests/python/reader_checks.py"))
        .arg(root())
        .env("SLENDER_BINARY", &binary)
        .output()
        .expect("run python");
    println!("{}", String::from_utf8_lossy(&out.stdout));
    assert!(
        out.status.success(),
        "reader checks: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
#[ignore = "needs scipy, rainflow and the slender package in .venv: ./scripts/test.sh runs it"]
fn a_runs_spectra_and_fatigue_agree_with_scipy_and_rainflow() {
    let binary = root().join("target/release/slender");
    assert!(
        binary.is_file(),
        "build the CLI first: cargo build --release"
    );
    let out = Command::new(fmu::python())
        .arg(root().join("tests/python/analysis_checks.py"))
        .arg(root())
        .env("SLENDER_BINARY", &binary)
        .output()
        .expect("run python");
    println!("{}", String::from_utf8_lossy(&out.stdout));
    assert!(
        out.status.success(),
        "analysis checks: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}
