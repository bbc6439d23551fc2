//! Regression tests for the defects found by probing the CLI as a new user would
//! (issue 11): each probe that once panicked, hung, wrote outside the results
//! folder or reported a failure as success now gets a clear error.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `slender` from the repository root. A probe that once hung must now
/// return: after `GUARD` it is killed and the test fails (a hang guard, not a
/// timing assertion: every probe here answers in well under a second).
fn slender(args: &[&str]) -> Output {
    const GUARD: Duration = Duration::from_secs(120);
    let mut child = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(args)
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the slender binary runs");
    let started = Instant::now();
    while child.try_wait().expect("waits").is_none() {
        if started.elapsed() > GUARD {
            let _ = child.kill();
            panic!("`slender {}` did not return", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A folder of its own for each test.
fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slender-issue11-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An example scene with `from` replaced by `to`, written into `dir`.
fn variant(dir: &Path, example: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(root().join("examples").join(example)).unwrap();
    assert!(text.contains(from), "{example} has no `{from}`");
    let path = dir.join(format!("{}.toml", text.len() ^ to.len()));
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    path.to_string_lossy().into_owned()
}

/// Exit code 2 with every `expected` fragment in the message.
fn refused(out: &Output, expected: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    for e in expected {
        assert!(err.contains(e), "`{e}` not in: {err}");
    }
}

#[test]
fn span_bode_refuses_element_counts_and_orders_it_cannot_draw() {
    let out = temp("bode");
    let out = out.to_str().unwrap();
    for elements in ["0", "100000"] {
        refused(
            &slender(&["span", "bode", "--elements", elements, "--out", out]),
            &["--elements", "1 to 1024"],
        );
    }
    for order in ["0", "7", "100", "1000000"] {
        refused(
            &slender(&["span", "bode", "--order", order, "--out", out]),
            &["--order", "even order from 2 to 24"],
        );
    }
    assert!(!Path::new(out).join("bode.svg").exists());
}

#[test]
fn extreme_span_properties_are_refused_instead_of_spinning() {
    let dir = temp("span");
    let base = "flexural_rigidity = 1.0e4, mass_per_length = 100.0, damping_per_length = 5.0";
    for (to, key) in [
        (
            "flexural_rigidity = 1.0e4, mass_per_length = 1e125, damping_per_length = 5.0",
            "mass_per_length",
        ),
        (
            "flexural_rigidity = 1.0e4, mass_per_length = 100.0, damping_per_length = 1e308",
            "damping_per_length",
        ),
        (
            "flexural_rigidity = 1.0e4, mass_per_length = 100.0, damping_per_length = 5.0, band = 1e308",
            "band",
        ),
        (
            "flexural_rigidity = 1e-300, mass_per_length = 100.0, damping_per_length = 5.0",
            "flexural_rigidity",
        ),
    ] {
        let scene = variant(&dir, "pipe_span_coupling.toml", base, to);
        refused(&slender(&["check", &scene]), &[key, "expected"]);
    }
}

#[test]
fn plot_names_stay_inside_the_results_folder_and_are_unique() {
    let dir = temp("plots");
    for (name, expected) in [
        ("../../x", "plot name"),
        ("", "plot name"),
        ("a/b", "plot name"),
    ] {
        let scene = variant(
            &dir,
            "b1_two_masses.toml",
            "name = \"displacements\"",
            &format!("name = \"{name}\""),
        );
        refused(&slender(&["check", &scene]), &[expected]);
    }
    let twice = variant(
        &dir,
        "b1_two_masses.toml",
        "[[output.plots]]",
        "[[output.plots]]\nname = \"displacements\"\npanels = [[\"left.displacement\"]]\n\n[[output.plots]]",
    );
    refused(&slender(&["check", &twice]), &["used by an earlier plot"]);
}

#[test]
fn unit_names_that_would_corrupt_the_csv_and_duplicate_signals_are_refused() {
    let dir = temp("names");
    for bad in ["le,ft", "le\\nft", "le ft"] {
        let scene = variant(
            &dir,
            "b1_two_masses.toml",
            "name = \"left\"",
            &format!("name = \"{bad}\""),
        );
        refused(
            &slender(&["check", &scene]),
            &["unit name", "letters, digits and `_`"],
        );
    }
    let scene = variant(
        &dir,
        "b1_two_masses.toml",
        "signals = [\"left.displacement\",",
        "signals = [\"left.displacement\", \"left.displacement\",",
    );
    refused(&slender(&["check", &scene]), &["listed twice"]);
}

#[test]
fn times_beyond_the_nanosecond_clock_are_refused() {
    let dir = temp("time");
    let late = variant(
        &dir,
        "b1_two_masses.toml",
        "[simulation]\n",
        "[simulation]\nstart = 9.2e9\n",
    );
    let late = std::fs::read_to_string(&late)
        .unwrap()
        .replace("duration = 1.0", "duration = 1e8");
    let path = dir.join("late.toml");
    std::fs::write(&path, late).unwrap();
    refused(
        &slender(&["check", path.to_str().unwrap()]),
        &["representable range", "nanoseconds"],
    );
    let too_late = variant(
        &dir,
        "b1_two_masses.toml",
        "[simulation]\n",
        "[simulation]\nstart = 1e10\n",
    );
    refused(
        &slender(&["check", &too_late]),
        &["simulation.start", "within range"],
    );
}

#[test]
fn plots_and_indicators_are_checked_before_the_run() {
    let dir = temp("unrecorded");
    let scene = variant(
        &dir,
        "b1_two_masses.toml",
        "panels = [[\"left.displacement\", \"right.displacement\"]",
        "panels = [[\"left.displacement\", \"right.force\"]",
    );
    refused(&slender(&["check", &scene]), &["output.plots[0].panels"]);
    let out = dir.join("results");
    refused(
        &slender(&["run", &scene, "--quiet", "--out", out.to_str().unwrap()]),
        &["panels"],
    );
    assert!(
        !out.join("summary.json").exists(),
        "nothing runs, nothing is reported"
    );
}

#[test]
fn a_non_library_binary_is_not_packaged() {
    let dir = temp("binary");
    let fmu = dir.join("left.fmu");
    refused(
        &slender(&[
            "fmu",
            "export",
            "examples/b1_two_masses.toml",
            "--unit",
            "left",
            "--binary",
            "README.md",
            "-o",
            fmu.to_str().unwrap(),
        ]),
        &["not a shared library"],
    );
    assert!(!fmu.exists());
}

#[test]
fn an_fmi3_wrap_into_an_ssp_is_refused_with_the_way_out() {
    let dir = temp("wrap3");
    let ssp = dir.join("system.ssp");
    refused(
        &slender(&[
            "fmu",
            "wrap",
            "examples/b1_two_masses.toml",
            "--fmi",
            "3",
            "--out",
            ssp.to_str().unwrap(),
        ]),
        &["SSP 1.0 archive holds FMI 2.0 FMUs", "--fmi 2", "--fmi 3"],
    );
    assert!(!ssp.exists());
    refused(
        &slender(&[
            "fmu",
            "wrap",
            "examples/b1_two_masses.toml",
            "--fmi",
            "4",
            "--out",
            "x",
        ]),
        &["--fmi"],
    );
}

#[test]
fn counts_of_zero_repeated_sweep_values_and_negative_durations_are_refused() {
    refused(
        &slender(&["bench", "examples/b1_two_masses.toml", "--repeats", "0"]),
        &["--repeats"],
    );
    refused(
        &slender(&[
            "modes",
            "examples/truncation_emulated.toml",
            "--unit",
            "emulated",
            "--count",
            "0",
        ]),
        &["--count"],
    );
    refused(
        &slender(&[
            "study",
            "examples/truncation_study.toml",
            "--vary",
            "step=0.01,0.01",
        ]),
        &["given twice"],
    );
    refused(
        &slender(&[
            "study",
            "examples/truncation_study.toml",
            "--vary",
            "step=0.01,0.02",
            "--duration",
            "-1",
        ]),
        &["--duration -1", "> 0"],
    );
    refused(
        &slender(&["run", "examples/b1_two_masses.toml", "--out", "README.md"]),
        &["is a file"],
    );
}

#[test]
fn input_errors_of_modes_and_study_exit_with_code_2() {
    refused(
        &slender(&[
            "modes",
            "examples/truncation_emulated.toml",
            "--unit",
            "nobody",
        ]),
        &["nobody"],
    );
    refused(
        &slender(&[
            "study",
            // A scene without indicators (B6 now has one against its root).
            "examples/hybrid_oscillator.toml",
            "--vary",
            "master.max_iterations=30,40",
        ]),
        &["output.indicators"],
    );
}

#[test]
fn a_study_with_a_failing_run_writes_every_row() {
    let out = temp("study");
    let result = slender(&[
        "study",
        "examples/truncation_study.toml",
        "--duration",
        "1",
        "--vary",
        "step=0.01,0.013",
        "--out",
        out.to_str().unwrap(),
    ]);
    // Every row written, and the command says runs failed with exit code 1
    // (issue 27: it exited 0).
    assert_eq!(result.status.code(), Some(1), "{}", stderr(&result));
    assert!(
        stderr(&result).contains("1 of 2 runs failed"),
        "{}",
        stderr(&result)
    );
    let csv = std::fs::read_to_string(out.join("study.csv")).expect("study.csv written");
    assert_eq!(csv.lines().count(), 3, "{csv}");
    assert!(csv.contains("whole number of steps"), "{csv}");
}

#[test]
fn a_failing_run_reports_its_residual_and_no_nan_cost() {
    let dir = temp("fails");
    // Plain fixed-point iteration with two iterations allowed: the first step
    // cannot converge (docs/active-truncation.md).
    let scene = variant(
        &dir,
        "truncation_substructured.toml",
        "max_iterations = 100",
        "max_iterations = 2",
    );
    let text = std::fs::read_to_string(&scene).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("acceleration"))
        .unwrap()
        .to_owned();
    std::fs::write(
        &scene,
        text.replace(&line, "acceleration = { kind = \"none\" }"),
    )
    .unwrap();
    let out = dir.join("results");
    let result = slender(&["run", &scene, "--quiet", "--out", out.to_str().unwrap()]);
    assert_eq!(result.status.code(), Some(1), "{}", stderr(&result));
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(!stdout.contains("NaN"), "{stdout}");
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
    let json: serde_json::Value = serde_json::from_str(&summary).unwrap();
    let residual = json["counters"]["max_residual"].as_f64().unwrap();
    assert!(
        residual > 1.0,
        "largest residual {residual} of a step that did not converge"
    );
}

#[test]
fn type_errors_name_the_key() {
    let dir = temp("types");
    let path = dir.join("step.toml");
    std::fs::write(
        &path,
        "[simulation]\nduration = 1.0\nstep = { a = 1 }\n[master]\nscheme = \"jacobi\"\n",
    )
    .unwrap();
    refused(
        &slender(&["check", path.to_str().unwrap()]),
        &[":3", "`step`", "expected a number"],
    );
    std::fs::write(
        &path,
        "[[simulation]]\nduration = 1.0\n[master]\nscheme = \"jacobi\"\n",
    )
    .unwrap();
    refused(
        &slender(&["check", path.to_str().unwrap()]),
        &["`[[simulation]]`"],
    );
}

#[test]
fn an_absurd_flexural_rigidity_is_refused_not_diagnosed_as_a_rigid_body_mode() {
    let dir = temp("rigid");
    let text = std::fs::read_to_string(root().join("examples/pipe_static_contact.toml")).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("flexural_rigidity"))
        .expect("EI line")
        .to_owned();
    let path = dir.join("stiff.toml");
    std::fs::write(&path, text.replace(&line, "flexural_rigidity = 1.0e308")).unwrap();
    let out = slender(&["check", path.to_str().unwrap()]);
    refused(
        &out,
        &["flexural_rigidity", "1e308", "expected a value from"],
    );
    assert!(!stderr(&out).contains("rigid-body"), "{}", stderr(&out));
}
