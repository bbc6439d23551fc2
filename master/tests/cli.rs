//! The `slender` command line: help, check, run, bench, and bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn slender(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
        .output()
        .expect("the slender binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn help_lists_every_command() {
    let out = slender(&["--help"]);
    assert!(out.status.success());
    let help = text(&out.stdout);
    for cmd in ["run", "check", "bench", "kinds"] {
        assert!(help.contains(cmd), "{help}");
    }
}

#[test]
fn check_accepts_an_example_and_rejects_a_bad_scene_with_exit_code_2() {
    let out = slender(&["check", "examples/b1_two_masses.toml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("ok"));
    let bad = std::env::temp_dir().join(format!("slender-cli-bad-{}.toml", std::process::id()));
    std::fs::write(
        &bad,
        "[simulation]\nduration = 1.0\nstep = 0.0\n[master]\nscheme = \"jacobi\"\n",
    )
    .unwrap();
    let out = slender(&["check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("simulation.step") && err.contains("> 0"),
        "{err}"
    );
    std::fs::remove_file(bad).unwrap();
    let out = slender(&["run", "no/such/scene.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("cannot read the file"));
}

#[test]
fn run_writes_results_and_prints_a_summary() {
    let dir: PathBuf = std::env::temp_dir().join(format!("slender-cli-run-{}", std::process::id()));
    let out = slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    assert!(
        summary.contains("iterations") && summary.contains("per simulated second"),
        "{summary}"
    );
    for f in ["timeseries.csv", "summary.json", "displacements.svg"] {
        assert!(dir.join(f).exists(), "{f} missing");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bench_reports_cost_and_master_overhead() {
    let out = slender(&[
        "bench",
        "examples/b1_two_masses.toml",
        "--repeats",
        "1",
        "--json",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json = text(&out.stdout);
    assert!(json.contains("median_cost_per_simulated_second"), "{json}");
    assert!(
        json.contains("master_overhead_per_connection_iteration_s"),
        "{json}"
    );
}
