//! The `slender` command line and its results folders (issue 27): nothing
//! half-done looks done and nothing is written where it should not be.

use std::path::Path;

use crate::common;
use common::{slender, text};

/// A reader that closes the pipe early (`slender expand ... | head -1`) ends
/// the command quietly: no panic, no backtrace (exit 101 before). The
/// riser's expanded scene (170 kB) is more than a pipe holds.
#[test]
#[cfg(unix)]
fn a_closed_pipe_ends_a_command_quietly() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(["expand", "examples/structure_riser.toml"])
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    // The reader is dropped here: the pipe closes with most of the output unread.
    let out = child.wait_with_output().unwrap();
    assert!(!first.is_empty());
    let err = text(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_ne!(out.status.code(), Some(101));
}

/// A symbolic link planted in the results folder is refused, not written
/// through (issue 27: `ln -s ../victim.txt o/summary.json` overwrote it).
#[test]
#[cfg(unix)]
fn a_symbolic_link_in_the_results_folder_is_refused_and_not_followed() {
    let base = std::env::temp_dir().join(format!("slender-cli-link-{}", std::process::id()));
    let out = base.join("o");
    std::fs::create_dir_all(&out).unwrap();
    let victim = base.join("victim.txt");
    std::fs::write(&victim, "keep").unwrap();
    std::os::unix::fs::symlink(&victim, out.join("summary.json")).unwrap();
    let result = slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(result.status.code(), Some(2), "{}", text(&result.stderr));
    assert!(
        text(&result.stderr).contains("a symbolic link"),
        "{}",
        text(&result.stderr)
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
    std::fs::remove_dir_all(base).unwrap();
}

/// One writer per results folder: a folder another running slender holds is
/// refused with its process id; a lock left by a process that is gone is taken
/// over, and released when the command ends (issue 27: two runs into one
/// folder spliced their rows).
#[test]
#[cfg(target_os = "linux")]
fn a_results_folder_has_one_writer_at_a_time() {
    let out = std::env::temp_dir().join(format!("slender-cli-lock-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let lock = out.join(".slender.lock");
    // This test's own process stands for a running slender.
    std::fs::write(&lock, std::process::id().to_string()).unwrap();
    let args = [
        "run",
        "examples/b1_two_masses.toml",
        "--out",
        out.to_str().unwrap(),
    ];
    let held = slender(&args);
    assert_eq!(held.status.code(), Some(2), "{}", text(&held.stderr));
    assert!(
        text(&held.stderr).contains(&format!("another slender (process {})", std::process::id())),
        "{}",
        text(&held.stderr)
    );
    assert!(!out.join("summary.json").exists());
    // A process id that does not run: the stale lock is taken over.
    std::fs::write(&lock, "999999999").unwrap();
    let stale = slender(&args);
    assert!(stale.status.success(), "{}", text(&stale.stderr));
    assert!(out.join("summary.json").exists() && !lock.exists());
    // A lock holding no process id: refused while fresh (its holder may not
    // have written its id yet), taken over once old (it was never taken).
    std::fs::write(&lock, "garbage").unwrap();
    let fresh = slender(&args);
    assert_eq!(fresh.status.code(), Some(2), "{}", text(&fresh.stderr));
    let old = std::time::SystemTime::now() - std::time::Duration::from_secs(60);
    std::fs::File::options()
        .write(true)
        .open(&lock)
        .unwrap()
        .set_modified(old)
        .unwrap();
    let garbage = slender(&args);
    assert!(garbage.status.success(), "{}", text(&garbage.stderr));
    assert!(!lock.exists());
    // A folder that cannot be made is the user's input: exit 2.
    let unmakeable = slender(&["run", "examples/b1_two_masses.toml", "--out", "/proc/x"]);
    assert_eq!(
        unmakeable.status.code(),
        Some(2),
        "{}",
        text(&unmakeable.stderr)
    );
    assert!(text(&unmakeable.stderr).contains("/proc/x"));
    std::fs::remove_dir_all(out).unwrap();
}

/// Ctrl-C stops a run at a step boundary: every CSV row whole, a summary with
/// status "interrupted" and the time reached, exit 130 (issue 27: a torn last
/// row and no summary).
#[test]
#[cfg(unix)]
fn ctrl_c_stops_a_run_at_a_step_with_whole_rows_and_a_summary() {
    let out = std::env::temp_dir().join(format!("slender-cli-int-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let child = riser_recording(&out);
    // SAFETY: a signal to the child this test started.
    unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
    let csv = out.join("timeseries.csv");
    let result = child.wait_with_output().unwrap();
    assert_eq!(result.status.code(), Some(130), "{}", text(&result.stderr));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"interrupted\""), "{summary}");
    let rows = std::fs::read_to_string(&csv).unwrap();
    let fields: Vec<usize> = rows.lines().map(|l| l.split(',').count()).collect();
    assert!(
        fields.iter().all(|&f| f == fields[0]),
        "a torn row: {fields:?}"
    );
    assert!(!out.join(".slender.lock").exists());
    // Killed outright, a run leaves its rows under the partial name and no
    // summary: nothing that looks finished, not even the earlier run's.
    let child = riser_recording(&out);
    // SAFETY: as above.
    unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGKILL) };
    child.wait_with_output().unwrap();
    assert!(!out.join("summary.json").exists());
    assert!(!csv.exists());
    assert!(out.join("timeseries.csv.partial").exists());
    std::fs::remove_dir_all(out).unwrap();
}

/// The riser example running into `out`, once it has recorded a few rows
/// (polled, no clock limit) into `timeseries.csv.partial`, its name while the
/// run goes.
#[cfg(unix)]
fn riser_recording(out: &Path) -> std::process::Child {
    use std::process::{Command, Stdio};
    let child = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args([
            "run",
            "examples/structure_riser.toml",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ])
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let partial = out.join("timeseries.csv.partial");
    while std::fs::read_to_string(&partial).map_or(0, |t| t.lines().count()) < 3 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child
}

/// A study whose runs fail writes every row and exits 1 (issue 27: it exited
/// 0, and a script took it for complete).
#[test]
fn a_fidelity_study_with_failed_runs_writes_its_rows_and_exits_1() {
    let dir =
        std::env::temp_dir().join(format!("slender-cli-fidelity-fail-{}", std::process::id()));
    let out = slender(&[
        "fidelity",
        "examples/structure_mooring.toml",
        "--duration",
        "0.2",
        // More modes than the lower section has free DOFs (196): that run
        // fails when its scene is built; the others run.
        "--section",
        "lower=cable,reduced:500",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("1 of 3 runs failed (marked FAILED in fidelity.md and fidelity.csv; every row is written)"),
        "{}",
        text(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("fidelity.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4, "{csv}");
    std::fs::remove_dir_all(dir).unwrap();
}

/// Work is bounded before it starts: a scene of 1e11 steps is refused by
/// `check` with the bound and how to go past it (issue 27: it passed, and
/// `run` wrote CSV until the disk was full); `simulation.max_steps` lifts it.
#[test]
fn a_run_of_more_steps_than_the_bound_is_refused_unless_the_scene_lifts_it() {
    let dir = std::env::temp_dir().join(format!("slender-cli-bound-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/b1_two_masses.toml"),
    )
    .unwrap()
    .replace("duration = 1.0", "duration = 1.0e9");
    let scene = dir.join("long.toml");
    std::fs::write(&scene, &base).unwrap();
    let out = slender(&["check", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains("100000000000 steps, more than the bound of 100000000")
            && err.contains("simulation.max_steps"),
        "{err}"
    );
    // Past the step bound, its time series is past the output bound.
    let lifted = base.replace("step = 0.01", "step = 0.01\nmax_steps = 2000000000000");
    std::fs::write(&scene, &lifted).unwrap();
    let out = slender(&["check", scene.to_str().unwrap()]);
    assert!(text(&out.stderr).contains("output.max_bytes = 2000000000"));
    let lifted = lifted.replace("[output]", "[output]\nmax_bytes = 100000000000000");
    std::fs::write(&scene, lifted).unwrap();
    let out = slender(&["check", scene.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    // The recorded time series too: 101 rows of 7 columns (B1's motion and
    // its analytic solution) is about 17 kB, more than a stated 10 kB;
    // `output.max_bytes` lifts it.
    let results = dir.join("out");
    let small = |bytes: u64| {
        let text = base
            .replace("duration = 1.0e9", "duration = 1.0")
            .replace("[output]", &format!("[output]\nmax_bytes = {bytes}"));
        std::fs::write(&scene, text).unwrap();
        let args = ["run", scene.to_str().unwrap(), "--quiet", "--out"];
        slender(&[&args[..], &[results.to_str().unwrap()]].concat())
    };
    let out = small(10_000);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stdout));
    // `check` states the same bound.
    let checked = slender(&["check", scene.to_str().unwrap()]);
    assert_eq!(checked.status.code(), Some(2));
    assert!(text(&checked.stderr).contains("output.max_bytes = 10000"));
    let err = text(&out.stderr);
    assert!(
        err.contains("101 rows of 7 columns") && err.contains("output.max_bytes = 10000"),
        "{err}"
    );
    assert!(!results.join("timeseries.csv").exists());
    assert!(small(20_000).status.success());
    std::fs::remove_dir_all(dir).unwrap();
}

/// `check` refuses what `uq` and the plots cannot use, naming the key: a NaN
/// bound, a key varied twice, an empty figure (issue 27: they passed).
#[test]
fn check_refuses_a_bad_uncertainty_table_and_an_empty_figure() {
    let dir = std::env::temp_dir().join(format!("slender-cli-uq-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let read = |name: &str| {
        std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../examples")
                .join(name),
        )
        .unwrap()
    };
    let uq = read("truncation_uq.toml");
    let first = "distribution = { kind = \"normal\", mean = 1.0, sd = 0.015 } },";
    assert!(uq.contains(first));
    let cases = [
        (
            uq.replacen(first, "distribution = { kind = \"normal\", mean = nan, sd = 0.015 } },", 1),
            "uncertainty.inputs[0].distribution",
        ),
        (
            uq.replace("key = \"units.sensor.parameters.scale.1\"", "key = \"units.sensor.parameters.scale.0\""),
            "uncertainty.inputs[1].key",
        ),
        (
            read("b1_two_masses.toml").replace(
                "panels = [[\"left.displacement\", \"right.displacement\"], [\"left.velocity\", \"right.velocity\"]]",
                "panels = []",
            ),
            "output.plots[0].panels",
        ),
    ];
    for (k, (scene_text, key)) in cases.iter().enumerate() {
        let scene = dir.join(format!("bad{k}.toml"));
        std::fs::write(&scene, scene_text).unwrap();
        let out = slender(&["check", scene.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{key}: {}", text(&out.stderr));
        assert!(
            text(&out.stderr).contains(key),
            "{key}: {}",
            text(&out.stderr)
        );
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_study_larger_than_its_bound_is_refused_before_any_run() {
    // Issue 27: `uq --samples 4294967296` aborted on a failed 805 MB
    // allocation; a grid is counted, not built, before it is refused.
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let cases: [Vec<String>; 3] = [
        [
            "uq",
            "examples/truncation_uq.toml",
            "--samples",
            "4294967296",
        ]
        .map(String::from)
        .to_vec(),
        [
            "fidelity",
            "examples/structure_mooring.toml",
            "--grid",
            "--section",
            "lower=nonlinear:4,nonlinear:8,nonlinear:16,cable,static",
            "--section",
            "upper=nonlinear:4,nonlinear:8,nonlinear:16,nonlinear",
            "--max-runs",
            "20",
        ]
        .map(String::from)
        .to_vec(),
        [
            "study",
            "examples/truncation_study.toml",
            "--vary",
            "simulation.step=0.1,0.05,0.025",
            "--max-runs",
            "2",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for (k, (args, expected)) in cases
        .iter()
        .zip([
            "4294967296 runs, more than the bound of 10000",
            "22 runs, more than the bound of 20",
            "3 runs, more than the bound of 2",
        ])
        .enumerate()
    {
        let folder = out(&format!("study{k}"));
        let mut args: Vec<&str> = args.iter().map(String::as_str).collect();
        args.extend(["--out", &folder]);
        let run = slender(&args);
        assert_eq!(
            run.status.code(),
            Some(2),
            "{args:?}: {}",
            text(&run.stderr)
        );
        let err = text(&run.stderr);
        assert!(
            err.contains(expected) && err.contains("--max-runs"),
            "{args:?}: {err}"
        );
        assert!(!Path::new(&folder).join("runs.csv").exists());
    }
}

/// Issue 27: a component whose reference is round-off against the
/// indicator's largest (a free end's force) is judged against that largest
/// component, and the run says so on screen and in summary.json.
#[test]
fn a_run_states_which_components_were_judged_against_the_largest() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = "[[units]]\nname = \"tiny\"\nkind = \"signal\"\nparameters = { quantity = \"displacement\", offset = 1e-9 }\n\n[[connections]]";
    let mixed = "[[output.indicators]]\nname = \"mixed\"\nsignals = [\"left.displacement\", \"right.displacement\"]\nreference = [\"exact_left.value\", \"tiny.value\"]\n\n[[output.indicators]]";
    let scene = common::variant_in(
        dir.path(),
        "examples/b1_two_masses.toml",
        &[
            (
                "[[connections]]\nfrom = \"left.displacement\"",
                &format!("{tiny}\nfrom = \"left.displacement\""),
            ),
            (
                "[[output.indicators]]\nname = \"exact\"",
                &format!("{mixed}\nname = \"exact\""),
            ),
            (
                "\"exact_right.value\"]\n\n# Against",
                "\"exact_right.value\", \"tiny.value\"]\n\n# Against",
            ),
        ],
    );
    let out = dir.path().join("out");
    let run = slender(&[
        "run",
        scene.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let stdout = text(&run.stdout);
    assert!(
        stdout.contains("right.displacement judged against the indicator's largest component"),
        "{stdout}"
    );
    let summary = common::summary(&out);
    let indicators = summary["indicators"].as_array().unwrap();
    let floored = |name: &str| {
        let i = indicators.iter().find(|i| i["name"] == name).unwrap();
        i.get("floored").cloned()
    };
    assert_eq!(
        floored("mixed"),
        Some(serde_json::json!(["right.displacement"]))
    );
    assert_eq!(floored("exact"), None, "nothing floored, nothing listed");
    // A study says so too, for an indicator with its reference in the run and
    // for one against the study's reference run (`drift`, whose second
    // component is the constant 1e-9 in every run).
    let drift = "[[output.indicators]]\nname = \"drift\"\nsignals = [\"left.displacement\", \"tiny.value\"]\n";
    let with_drift = std::fs::read_to_string(&scene).unwrap() + "\n" + drift;
    std::fs::write(&scene, with_drift).unwrap();
    let study_out = dir.path().join("study");
    let study = slender(&[
        "study",
        scene.to_str().unwrap(),
        "--vary",
        "step=0.01,0.005",
        "--out",
        study_out.to_str().unwrap(),
    ]);
    assert!(study.status.success(), "{}", text(&study.stderr));
    let md = std::fs::read_to_string(study_out.join("study.md")).unwrap();
    assert!(
        md.contains("Judged against their indicator's largest component")
            && md.contains("`mixed: right.displacement`")
            && md.contains("`drift: tiny.value`"),
        "{md}"
    );
}

/// Issue 48: `--reference` takes `estimate`, `converged` or `model`, and
/// `--refinements` a number of halvings from 1 to 5; anything else is
/// refused before a run, naming what is expected.
#[test]
fn a_fidelity_reference_that_is_not_one_of_its_modes_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let base = [
        "fidelity",
        "examples/structure_hanging_pipe.toml",
        "--section",
        "middle=nonlinear:5",
        "--duration",
        "0.1",
        "--out",
        out.to_str().unwrap(),
    ];
    let with = |extra: &[&str]| {
        let mut args = base.to_vec();
        args.extend(extra);
        slender(&args)
    };
    let mode = with(&["--reference", "finest"]);
    assert_eq!(mode.status.code(), Some(2), "{}", text(&mode.stderr));
    assert!(
        text(&mode.stderr).contains("expected `estimate`"),
        "{}",
        text(&mode.stderr)
    );
    let refinements = with(&["--reference", "converged", "--refinements", "0"]);
    assert_eq!(refinements.status.code(), Some(2));
    assert!(
        text(&refinements.stderr).contains("--refinements 0: expected 1 to 5"),
        "{}",
        text(&refinements.stderr)
    );
    assert!(!out.join("fidelity.csv").exists());
}
