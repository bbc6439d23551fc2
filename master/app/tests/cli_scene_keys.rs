//! Scene keys over the file (`--set`) on every command that reads a scene,
//! and the checks a study makes before its first run (issue 28).

use crate::common;
use common::{slender, summary, text};

/// Issue 28: `run --set KEY=VALUE` sets scene keys over the file (a TOML
/// value, a bare word a string), lists them in summary.json and on screen,
/// and names a bad one.
#[test]
fn run_sets_scene_keys_over_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("set");
    let run_b1 = |sets: &[&str]| {
        let mut args = vec!["run", "examples/b1_two_masses.toml", "--quiet"];
        args.extend(["--out", out.to_str().unwrap()]);
        args.extend(sets.iter().flat_map(|s| ["--set", s]));
        slender(&args)
    };
    let run = run_b1(&[
        "simulation.duration=0.5",
        "master.acceleration={ kind = \"aitken\" }",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("set          simulation.duration=0.5"));
    let s = summary(&out);
    assert_eq!(s["simulated_s"].as_f64(), Some(0.5));
    assert_eq!(
        s["settings"]["acceleration"]["kind"].as_str(),
        Some("aitken")
    );
    assert_eq!(s["overrides"].as_array().map(Vec::len), Some(2));
    for (set, expected) in [
        ("master.shceme=jacobi", "unknown field `shceme`"),
        ("simulation.duration", "expected KEY=VALUE"),
        ("simulation.step=-1", "--set simulation.step=-1"),
    ] {
        let run = run_b1(&[set]);
        assert_eq!(run.status.code(), Some(2), "{set}");
        let err = text(&run.stderr);
        assert!(err.contains(expected), "{set}: {err}");
    }
}

/// An error about a value `--set` changed names the file, the key and the
/// change, not a line (the value is not on the user's line; it once named
/// line 90 of the 62-line mooring example).
#[test]
fn an_error_under_set_names_no_line_of_another_text() {
    let set = "structure.sections[0].fidelity={ kind = \"span\", elements = 3 }";
    let check = slender(&["check", "examples/structure_mooring.toml", "--set", set]);
    assert_eq!(check.status.code(), Some(2));
    let err = text(&check.stderr);
    assert!(
        err.contains("examples/structure_mooring.toml: structure: `structure.sections[0].fidelity.elements`: unknown key"),
        "{err}"
    );
    assert!(
        err.contains(&format!("(the scene as changed by --set {set})")),
        "{err}"
    );
}

/// Issue 28: `--set` on the commands that read a scene (check, expand,
/// bench), refused on one that reads none.
#[test]
fn every_scene_command_takes_set() {
    let b1 = "examples/b1_two_masses.toml";
    let jacobi = "master.scheme=jacobi";
    let check = slender(&["check", b1, "--set", jacobi]);
    assert!(check.status.success(), "{}", text(&check.stderr));
    assert!(text(&check.stdout).contains("scheme jacobi"));
    let expand = slender(&["expand", b1, "--set", "simulation.duration=0.25"]);
    assert!(text(&expand.stdout).contains("duration = 0.25"));
    let bench = slender(&["bench", b1, "--repeats", "1", "--json", "--set", jacobi]);
    let figures: serde_json::Value = serde_json::from_slice(&bench.stdout).unwrap();
    // Jacobi makes one pass per step where the file's iterative scheme iterates.
    assert_eq!(figures["iterations"].as_u64(), figures["steps"].as_u64());
    let kinds = slender(&["kinds", "--set", jacobi]);
    assert_eq!(kinds.status.code(), Some(2));
    assert!(text(&kinds.stderr).contains("reads no scene"));
}

/// Issue 28: `--set` on the study commands (their runs, uq's cluster scripts)
/// and on fmu export, each bad key named.
#[test]
fn the_study_commands_take_set() {
    let b1 = "examples/b1_two_masses.toml";
    let jacobi = "master.scheme=jacobi";
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study");
    let study = slender(&[
        "study",
        b1,
        "--vary",
        "step=0.01,0.005",
        "--set",
        jacobi,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(study.status.success(), "{}", text(&study.stderr));
    let table = std::fs::read_to_string(out.join("study.csv")).unwrap();
    let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|h| h.starts_with("iterations"))
        .unwrap();
    for row in table.lines().skip(1) {
        assert_eq!(row.split(',').nth(column), Some("1"), "{table}");
    }
    let uq = dir.path().join("uq");
    let scripts = slender(&[
        "uq",
        "examples/truncation_uq.toml",
        "--slurm",
        "2",
        "--out",
        uq.to_str().unwrap(),
        "--set",
        "simulation.duration=2",
    ]);
    assert!(scripts.status.success(), "{}", text(&scripts.stderr));
    let sbatch = std::fs::read_to_string(uq.join("uq-shards.sbatch")).unwrap();
    assert!(
        sbatch.contains("--set \"simulation.duration=2\""),
        "{sbatch}"
    );
    for args in [
        vec![
            "fmu",
            "export",
            b1,
            "--unit",
            "left",
            "--set",
            "master.shceme=x",
        ],
        vec![
            "study",
            b1,
            "--vary",
            "step=0.01",
            "--set",
            "master.shceme=x",
        ],
        vec![
            "fidelity",
            b1,
            "--section",
            "a=cable",
            "--set",
            "master.shceme=x",
        ],
    ] {
        let bad = slender(&args);
        assert_eq!(bad.status.code(), Some(2), "{args:?}");
        assert!(
            text(&bad.stderr).contains("--set master.shceme=x"),
            "{}",
            text(&bad.stderr)
        );
    }
}

/// A misspelt `--quantities` is refused before any run (it was refused only
/// after the whole study had run), and `--max-runs 0` refuses a study only
/// once everything else in it was found valid.
#[test]
fn a_fidelity_study_is_checked_before_its_first_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f");
    let out = out.to_str().unwrap();
    let mooring = "examples/structure_mooring.toml";
    let section = "lower=nonlinear,cable";
    let typo = slender(&[
        "fidelity",
        mooring,
        "--section",
        section,
        "--quantities",
        "top_forc",
        "--out",
        out,
    ]);
    assert_eq!(typo.status.code(), Some(2));
    assert!(text(&typo.stderr).contains("`top_forc` is not a quantity"));
    assert!(
        !text(&typo.stdout).contains("[1/"),
        "{}",
        text(&typo.stdout)
    );
    let both = slender(&[
        "fidelity",
        mooring,
        "--section",
        section,
        "--quantities",
        "top_forc",
        "--max-runs",
        "0",
        "--out",
        out,
    ]);
    assert!(
        text(&both.stderr).contains("top_forc"),
        "{}",
        text(&both.stderr)
    );
    let study = slender(&[
        "study",
        "examples/b1_two_masses.toml",
        "--vary",
        "units.left.parameters.mas=1,2",
        "--max-runs",
        "0",
        "--out",
        out,
    ]);
    assert!(
        text(&study.stderr).contains("mas"),
        "{}",
        text(&study.stderr)
    );
    assert!(
        !text(&study.stderr).contains("bound"),
        "{}",
        text(&study.stderr)
    );
}

/// `--set` on an SSP (a packaged system, not a scene file) is refused with the
/// reason, not with a TOML parse error of a zip archive.
#[test]
fn set_on_an_ssp_says_why_it_cannot() {
    let dir = tempfile::tempdir().unwrap();
    let ssp = dir.path().join("b1.ssp");
    std::fs::write(&ssp, b"PK\x03\x04 not really an archive").unwrap();
    let run = slender(&[
        "check",
        ssp.to_str().unwrap(),
        "--set",
        "master.scheme=jacobi",
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = text(&run.stderr);
    assert!(err.contains("an SSP is a packaged system"), "{err}");
}

/// Issue 45: a change is made on the keys as read, not on TOML text written
/// again, so an error about a changed value names the change and one about a
/// key the user wrote names its line.
#[test]
fn errors_of_a_change_name_it_and_others_the_users_line() {
    use slender_app::AppError;
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/structure_hanging_pipe.toml");
    let set = |scene: &std::path::Path, key: &str| match slender_app::study::scene_with_overrides(
        scene,
        &[key.to_owned()],
    ) {
        Err(AppError::Scene(e)) => e,
        other => panic!("{key}: expected the scene refused, got {other:?}"),
    };
    let error = set(&scene, "simulation.step=fast");
    assert_eq!(
        (error.line, error.key.as_str()),
        (None, "`simulation.step`")
    );
    assert!(
        error.message.starts_with("--set simulation.step=fast: "),
        "{error}"
    );
    let error = set(&scene, "structure.sections[0].fidelity=wrong");
    assert!(
        error
            .message
            .ends_with("(the scene as changed by --set structure.sections[0].fidelity=wrong)"),
        "{error}"
    );
    // A key the user wrote, wrong where a change made no difference: its line.
    let dir = tempfile::tempdir().expect("a folder");
    let text = std::fs::read_to_string(&scene).expect("the example");
    let text = text.replacen("to = 10.0", "to = 10.0\nelemnts = 4", 1);
    let written = dir.path().join("pipe.toml");
    std::fs::write(&written, &text).expect("the scene");
    let error = set(&written, "simulation.duration=1");
    let line = 1 + text
        .lines()
        .position(|l| l.contains("elemnts"))
        .expect("the line");
    assert_eq!(error.line, Some(line), "{error}");
}

/// Issue 49, item 5: an indicator's `from` leaves the build-up out of its
/// error, in a run's summary (the window's error, as the library measures it
/// from the recorded columns), and is refused before the start.
#[test]
fn an_indicators_window_leaves_out_the_build_up() {
    use slender_app::indicators::{measure, window};
    use slender_app::run::{RunOptions, run_scene};
    let b1 =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/b1_two_masses.toml");
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    let run = |set: &[&str]| {
        let set: Vec<String> = set.iter().map(|s| (*s).to_owned()).collect();
        let scene = slender_app::study::scene_with_overrides(&b1, &set).expect("the scene");
        let result = run_scene(&scene, &options).expect("the run");
        (scene, result)
    };
    let (_, whole) = run(&[]);
    let (scene, late) = run(&["output.indicators[0].from=0.5"]);
    let spec = &scene.spec.output.indicators[0];
    let column = |n: &String| late.recorder.column(n).expect("recorded");
    let x: Vec<&[f64]> = spec.signals.iter().map(column).collect();
    let r: Vec<&[f64]> = spec.reference.iter().map(column).collect();
    let (time, x) = window(&late.recorder.time, &x, Some(0.5));
    let (_, r) = window(&late.recorder.time, &r, Some(0.5));
    let expected = measure((&spec.name, &spec.signals), spec.norm, time, &x, &r);
    let got = &late.summary.indicators[0];
    assert_eq!(got.relative_error, expected.relative_error);
    assert_ne!(
        got.relative_error,
        whole.summary.indicators[0].relative_error
    );
    let refused =
        slender_app::study::scene_with_overrides(&b1, &["output.indicators[0].from=-1".to_owned()])
            .expect_err("before the start")
            .to_string();
    assert!(
        refused.contains("output.indicators[0].from: -1: expected a time"),
        "{refused}"
    );
}

/// `slender statics --set` changes the system it solves: `[mooring]` is
/// read from the scene's keys as changed (it was read from the file's text,
/// so a `--set` on the body or a line was silently left out).
#[test]
fn statics_reads_the_mooring_as_set() {
    let dir = tempfile::tempdir().unwrap();
    let heave = |sets: &[&str]| {
        let json = oc3_json("statics", dir.path(), sets);
        let statics: serde_json::Value = serde_json::from_str(&json).expect("JSON");
        statics["offset"][2].as_f64().expect("the heave offset")
    };
    let (written, buoyant) = (heave(&[]), heave(&["mooring.body.displaced_volume=8100"]));
    // 8100 m^3 against the file's 8029.21 m^3: the buoyancy rho g dV lifts
    // the spar against its hydrostatic stiffness (332,941 N/m) and the
    // lines' vertical stiffness, so by a little less than rho g dV / k33.
    let hydrostatic = 1025.0 * 9.80665 * (8100.0 - 8029.21) / 332_941.0;
    let rise = buoyant - written;
    assert!(
        rise > 0.8 * hydrostatic && rise < hydrostatic,
        "{written} -> {buoyant} m (hydrostatics alone: {hydrostatic} m)"
    );
}

/// `slender decay --set` compares the run with the statics of the same
/// system: the undamped periods beside the measured ones come from the
/// `[mooring]` as changed (they came from the file, so with a heavier spar the
/// surge's measured period grew and its linear one did not).
#[test]
fn decay_compares_with_the_statics_of_the_system_as_set() {
    let dir = tempfile::tempdir().unwrap();
    let surge = |sets: &[&str]| {
        let json = oc3_json("decay", dir.path(), sets);
        let rows: serde_json::Value = serde_json::from_str(&json).expect("JSON");
        let row = (rows.as_array().expect("rows").iter())
            .find(|r| r["dof"] == "surge")
            .expect("the surge row")
            .clone();
        let period = |v: &serde_json::Value| v.as_f64().expect("a period (s)");
        (
            period(&row["decay"]["period"]),
            period(&row["linear_period_s"]),
        )
    };
    let (measured, linear) = surge(&[]);
    let (heavy_measured, heavy_linear) = surge(&["mooring.body.mass=9000000"]);
    assert!(
        heavy_measured > 1.1 * measured,
        "{measured} -> {heavy_measured} s"
    );
    for (m, l) in [(measured, linear), (heavy_measured, heavy_linear)] {
        assert!((m - l).abs() < 0.02 * l, "measured {m} s, linear {l} s");
    }
}

/// `slender COMMAND examples/oc3_hywind.toml --set ...` run into a folder of
/// `dir`: the `<command>.json` it writes.
fn oc3_json(command: &str, dir: &std::path::Path, sets: &[&str]) -> String {
    let out = dir.join(format!("{command}{}", sets.len()));
    let mut args = vec![command, "examples/oc3_hywind.toml"];
    args.extend(["--out", out.to_str().unwrap()]);
    args.extend(sets.iter().flat_map(|s| ["--set", s]));
    let run = slender(&args);
    assert!(run.status.success(), "{}", text(&run.stderr));
    std::fs::read_to_string(out.join(format!("{command}.json"))).expect("the JSON file")
}
