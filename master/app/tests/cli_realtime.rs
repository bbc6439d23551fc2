//! Paced runs (`slender run --realtime`): the clock kept, computing times
//! and overruns reported, the overrun log bounded and a run that cannot keep
//! pace stopped (issue 27).

use std::path::{Path, PathBuf};

use crate::common;
use common::{slender, summary, text, variant_in};

#[test]
fn realtime_runs_keep_the_clock_and_report_every_overrun() {
    let dir = std::env::temp_dir().join(format!("slender-cli-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let variant = |example: &str, from: &[(&str, &str)]| variant_in(&dir, example, from);
    // Two masses, 30 steps of 10 ms: paced, the run lasts at least 0.3 s.
    let scene = variant(
        "examples/b1_two_masses.toml",
        &[("duration = 1.0", "duration = 0.3")],
    );
    let (run, out) = run_paced(&scene, &dir, "b1");
    assert!(run.status.success(), "{}", text(&run.stderr));
    let s = summary(&out);
    assert!(s["wall_time_s"].as_f64().unwrap() >= 0.3 - 1e-3, "{s}");
    let r = &s["realtime"];
    assert_eq!(r["steps"].as_u64(), Some(30));
    let histogram: u64 = r["histogram"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_u64().unwrap())
        .sum();
    assert_eq!(histogram, 30);
    assert!(r["p999_s"].as_f64() <= r["worst_s"].as_f64());
    assert!(text(&run.stdout).contains("real time    step 10.000 ms"));
    // Seed 002's frame at 10 us steps: an implicit step of 118 DOFs takes far
    // longer than 10 us, so (nearly) every step overruns, each one listed
    // (up to 1000) when the scene allows them.
    let scene = variant(
        "examples/seed002_frame.toml",
        &[
            ("duration = 10.0", "duration = 0.002"),
            ("step = 0.001", "step = 0.00001\nmax_overruns = 100000"),
        ],
    );
    let (run, out) = run_paced(&scene, &dir, "frame");
    assert!(run.status.success(), "{}", text(&run.stderr));
    let overruns = summary(&out)["realtime"]["overruns"]
        .as_array()
        .unwrap()
        .len();
    assert!(overruns >= 150, "{overruns} of 200 steps overran");
    let csv = std::fs::read_to_string(out.join("overruns.csv")).unwrap();
    assert_eq!(csv.lines().count(), overruns + 1);
    assert!(text(&run.stdout).contains("overruns in 200 steps"));
    assert_eq!(
        summary(&out)["realtime"]["overrun_count"].as_u64(),
        Some(overruns as u64)
    );
    bounded_overruns(&dir, &variant);
    // Without --realtime the summary has no such entry (and outputs are as before).
    let plain = dir.join("plain");
    let run = slender(&[
        "run",
        scene.to_str().unwrap(),
        "--quiet",
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(run.status.success());
    assert!(summary(&plain).get("realtime").is_none());
    std::fs::remove_dir_all(dir).unwrap();
}

/// `slender run SCENE --realtime` into `dir/name`: its output and folder.
fn run_paced(scene: &Path, dir: &Path, name: &str) -> (std::process::Output, PathBuf) {
    let out = dir.join(name);
    let run = slender(&[
        "run",
        scene.to_str().unwrap(),
        "--realtime",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    (run, out)
}

/// A scene file made from an example with its text replaced.
type Variant<'a> = dyn Fn(&str, &[(&str, &str)]) -> PathBuf + 'a;

/// Issue 27: a paced run that cannot keep pace stops after
/// `simulation.max_overruns` overruns (100 by default), and its overrun log
/// keeps the first 1000 and counts the rest.
fn bounded_overruns(dir: &Path, variant: &Variant<'_>) {
    let frame = |duration: &str, step: &str| {
        variant(
            "examples/seed002_frame.toml",
            &[("duration = 10.0", duration), ("step = 0.001", step)],
        )
    };
    let (run, out) = run_paced(&frame("duration = 0.01", "step = 0.00001"), dir, "stopped");
    assert_eq!(run.status.code(), Some(1), "{}", text(&run.stdout));
    let s = summary(&out);
    assert_eq!(s["status"].as_str(), Some("failed"));
    let error = s["error"].as_str().unwrap();
    assert!(
        error.contains("cannot keep pace") && error.contains("simulation.max_overruns = 100"),
        "{error}"
    );
    assert_eq!(s["realtime"]["overrun_count"].as_u64(), Some(101));
    let bounded = frame("duration = 0.015", "step = 0.00001\nmax_overruns = 100000");
    let (run, out) = run_paced(&bounded, dir, "bounded");
    assert!(run.status.success(), "{}", text(&run.stderr));
    let r = &summary(&out)["realtime"];
    let count = r["overrun_count"].as_u64().unwrap();
    assert!(count > 1000, "{count} of 1500 steps overran");
    assert_eq!(r["overruns"].as_array().unwrap().len(), 1000);
    let csv = std::fs::read_to_string(out.join("overruns.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1001);
}
