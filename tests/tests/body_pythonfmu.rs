//! Another tool's body in a mooring (issue 47): a floating body written with
//! pythonfmu (tests/python/point_body.py: surge, sway and heave, the
//! trapezoidal rule, its state saved and restored by pythonfmu's
//! `--handle-state`, no directional derivatives) in `[mooring.body]`'s
//! place, coupled to three 3D chains by Newton with Jacobians by
//! differences from rolled-back states, against slender's own body with its
//! rotations held by stiff springs.
//!
//! Needs pythonfmu in the test environment (.venv, `./scripts/test.sh`);
//! ignored in a plain `cargo test`, run by test.sh with `--ignored`.

use slender_scene::Scene;
use slender_scene::mooring;
use slender_tests::buoy::{FAIRLEADS, LINES};
use slender_tests::fmu::{python_paths, pythonfmu_build, slender};
use std::path::Path;

/// A buoy of 2e4 kg on three chains in 50 m of water, rotations held by
/// springs of 1e14 N m/rad, moved 2 m in surge; BODY_EXTRA goes in
/// `[mooring.body]`.
const SCENE: &str = r#"
title = "a buoy on three chains"
[simulation]
duration = 30.0
step = 0.1
[master]
scheme = "iterative_jacobi"
extrapolation = "linear"
max_iterations = 30
tolerances = { velocity = 1e-8, force = 1e-3 }
newton = { derivatives = "units" }

[mooring.body]
name = "buoy"
BODY_EXTRA
mass = 2e4
inertia = [8e4, 8e4, 8e4]
displaced_volume = 27.458
hydrostatic_stiffness = [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 2e5, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]
additional_stiffness = [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 1e14, 0, 0], [0, 0, 0, 0, 1e14, 0], [0, 0, 0, 0, 0, 1e14]]
damping_linear = [[1e3, 0, 0, 0, 0, 0], [0, 1e3, 0, 0, 0, 0], [0, 0, 2e3, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]
initial_offset = [2.0, 0.0, 0.0, 0.0, 0.0, 0.0]
FAIRLEADS
LINES
"#;

/// [`SCENE`] with the buoy's fairleads and lines.
fn scene_text() -> String {
    SCENE
        .replace("FAIRLEADS", FAIRLEADS)
        .replace("LINES", LINES)
}

/// The pythonfmu body's start values for the native scene's body: its mass
/// and restoring per axis, its net load, fairleads, and start position.
fn start_values(native: &Scene) -> String {
    let system = mooring::of_scene(native).unwrap().unwrap();
    let body = &system.body;
    let eq = system.equilibrium().unwrap();
    let net = 1025.0 * 9.80665 * body.displaced_volume - body.mass * 9.80665;
    let mut values = Vec::new();
    for (i, a) in ["x", "y", "z"].iter().enumerate() {
        values.push(format!("mass_{a} = {}", body.mass));
        values.push(format!(
            "stiffness_{a} = {}",
            body.hydrostatic_stiffness[i][i]
        ));
        values.push(format!("damping_{a} = {}", body.damping_linear[i][i]));
        values.push(format!(
            "start_{a} = {}",
            eq.offset[i] + body.initial_offset[i]
        ));
    }
    values.push(format!("net_force_z = {net}"));
    for f in &body.fairleads {
        for (i, a) in ["x", "y", "z"].iter().enumerate() {
            values.push(format!("{}_offset_{a} = {}", f.name, f.position[i]));
        }
    }
    format!("{{ {} }}", values.join(", "))
}

fn column(results: &Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(results.join("timeseries.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header.iter().position(|h| h.starts_with(name)).unwrap();
    lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect()
}

#[test]
#[ignore = "needs pythonfmu in .venv: ./scripts/test.sh runs it"]
fn a_pythonfmu_body_holds_the_lines_as_slender_s_body_does() {
    let dir = tempfile::tempdir().unwrap();
    pythonfmu_build("point_body.py", &["--handle-state"], dir.path());
    let (libpython, site) = python_paths();
    let native_text = scene_text().replace("BODY_EXTRA", "");
    let native = Scene::parse(Path::new("native.toml"), native_text.clone()).unwrap();
    let fmu = format!(
        "fmu = {{ file = \"PointBody.fmu\", preload = [{:?}], start = {} }}",
        libpython.display().to_string(),
        start_values(&native)
    );
    let files = [
        ("native", native_text),
        ("python", scene_text().replace("BODY_EXTRA", &fmu)),
    ];
    let mut runs = Vec::new();
    for (name, text) in files {
        let scene = dir.path().join(format!("{name}.toml"));
        std::fs::write(&scene, text).unwrap();
        let out = dir.path().join(name);
        let args = [
            "run",
            &scene.display().to_string(),
            "--quiet",
            "--out",
            &out.display().to_string(),
        ];
        assert!(slender(&args, &site).status.success(), "{name}");
        runs.push(out);
    }
    let mut worst = 0.0_f64;
    for signal in ["buoy.x", "buoy.z", "l1_full.end_tension"] {
        let (a, b) = (column(&runs[0], signal), column(&runs[1], signal));
        let scale = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let gap = a
            .iter()
            .zip(&b)
            .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
        println!("{signal}: largest gap {gap:.3e} of {scale:.3e}");
        worst = worst.max(gap / scale);
    }
    // The same trapezoidal rule on the same translations: the gap is the
    // coupling tolerance's and the held rotations' (some 1e-9 rad).
    assert!(worst < 1e-5, "{worst:e}");
}
