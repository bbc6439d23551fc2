//! Cross-checks of the FMI layer with other people's tools: FMPy validates and
//! simulates slender's FMUs and round-trips their state, and an FMU built by
//! pythonfmu is coupled with native units.
//!
//! These tests need the Python environment with FMPy and pythonfmu that
//! `./scripts/test.sh` creates (.venv); they are ignored in a plain `cargo test`
//! and test.sh runs them with `--ignored`.

use slender_fmi::export::ExportConfig;
use slender_scene::export::{ExportedUnit, FmiVersion, SceneExport, package_version};
use slender_tests::fmu::{python_paths, slender};
use slender_tests::{fmu, load, root};
use slender_units::{Hold, Time};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn python_script(args: &[&str]) -> Output {
    let out = Command::new(fmu::python())
        .arg(root().join("tests/python/fmpy_checks.py"))
        .args(args)
        .output()
        .expect("run python");
    println!("{}", String::from_utf8_lossy(&out.stdout));
    eprintln!("{}", String::from_utf8_lossy(&out.stderr));
    out
}

/// The slender CLI of the profile the tests run in.
fn slender_cli() -> PathBuf {
    let cli = fmu::library().with_file_name("slender");
    assert!(
        cli.exists(),
        "{} is missing: cargo build --release",
        cli.display()
    );
    cli
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn fmpy_validates_every_unit_of_every_example_scene() {
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root().join("examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    for path in scenes {
        let relative = format!("examples/{}", path.file_name().unwrap().to_string_lossy());
        let scene = load(&relative);
        for unit in &scene.spec.units {
            let folder = dir.path().join(path.file_stem().unwrap());
            std::fs::create_dir_all(&folder).unwrap();
            files.push(fmu::export(&relative, unit.name.get_ref(), &folder));
        }
    }
    let mut args = vec!["validate".to_owned()];
    args.extend(files.iter().map(|f| f.display().to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = python_script(&args);
    assert!(
        out.status.success(),
        "fmpy validate found problems in {} FMUs",
        files.len()
    );
    assert!(files.len() >= 30);
}

fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let names = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| {
            slender_app::record::split_column(s.trim_matches('"'))
                .0
                .to_owned()
        })
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.trim().parse().unwrap()).collect())
        .collect();
    (names, rows)
}

/// FMPy's run of `unit` of `scene` exported as an FMU, with its first input (if
/// any) held at `force`, against the native unit stepped alike: the worst
/// relative difference over every output and row.
fn fmpy_against_native(
    scene: &str,
    unit: &str,
    force: Option<f64>,
    (stop, step): (f64, f64),
) -> (usize, f64) {
    let dir = tempfile::tempdir().unwrap();
    let file = fmu::export(scene, unit, dir.path());
    let csv = dir.path().join("fmpy.csv");
    let mut args = vec![
        "simulate".to_owned(),
        file.display().to_string(),
        csv.display().to_string(),
        stop.to_string(),
        step.to_string(),
    ];
    args.extend(force.map(|f| format!("force={f}")));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    assert!(python_script(&args).status.success());
    let (names, rows) = read_csv(&csv);
    // The native unit with the same constant input (FMPy holds unconnected
    // inputs at their start values).
    let config = ExportConfig::from_scene(&load(scene), unit).unwrap();
    let mut native = config.driver().unwrap();
    if let Some(f) = force {
        native.set_hold(0, Hold::ZeroOrder).unwrap();
        native.set_inputs(&[f]).unwrap();
    }
    native.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(step).unwrap();
    let ports: Vec<String> = native
        .description()
        .outputs
        .iter()
        .map(|p| p.name.clone())
        .collect();
    let mut values = vec![0.0; ports.len()];
    let mut worst = 0.0_f64;
    for (n, row) in rows.iter().enumerate() {
        if n > 0 {
            native.do_step(h * (n as i64 - 1), h).unwrap();
        }
        native.outputs(&mut values).unwrap();
        for (port, v) in ports.iter().zip(&values) {
            let column = names.iter().position(|c| c == port).unwrap();
            worst = worst.max((row[column] - v).abs() / v.abs().max(1e-3));
        }
    }
    println!(
        "{scene} {unit}: {} rows, worst relative difference {worst:.2e}",
        rows.len()
    );
    (rows.len(), worst)
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn fmpy_simulation_of_an_exported_unit_matches_the_native_unit_alone() {
    let (rows, worst) = fmpy_against_native(
        "examples/b3_force_displacement.toml",
        "b",
        Some(2.0),
        (2.0, 0.01),
    );
    assert_eq!(rows, 201);
    // FMPy's CSV keeps 16 significant digits.
    assert!(worst < 1e-14, "{worst:e}");
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn fmpy_simulation_of_the_nonlinear_frame_fmu_matches_the_native_section() {
    let (rows, worst) =
        fmpy_against_native("examples/seed002_frame.toml", "frame", None, (1.0, 0.001));
    assert_eq!(rows, 1001);
    assert!(worst < 1e-14, "{worst:e}");
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn fmu_state_save_restore_serialise_round_trip_through_fmpy() {
    let dir = tempfile::tempdir().unwrap();
    for (scene, unit) in [
        ("examples/b1_two_masses.toml", "left"),
        ("examples/truncation_substructured.toml", "n"),
        ("examples/truncation_signal_loss.toml", "sensor"),
        ("examples/pipe_dynamic_contact.toml", "pipe"),
    ] {
        let folder = dir.path().join(unit);
        std::fs::create_dir_all(&folder).unwrap();
        let file = fmu::export(scene, unit, &folder);
        let out = python_script(&["state", &file.display().to_string()]);
        assert!(
            out.status.success(),
            "{scene} {unit}: state round trip failed"
        );
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(text.matches("bit-identical").count(), 3, "{text}");
    }
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn fmpy_step_derivatives_match_differences_of_the_step_and_the_standards_are_zero() {
    let dir = tempfile::tempdir().unwrap();
    for (scene, unit, rows) in [
        (
            "examples/b1_two_masses.toml",
            "left",
            "displacement,velocity,coupling_force",
        ),
        (
            "examples/structure_mooring.toml",
            "line_upper",
            "start_force_x,start_force_z,start_position_x,start_velocity_z",
        ),
    ] {
        let folder = dir.path().join(unit);
        std::fs::create_dir_all(&folder).unwrap();
        let file = fmu::export(scene, unit, &folder);
        let out = python_script(&["derivatives", &file.display().to_string(), rows]);
        assert!(out.status.success(), "{scene} {unit}: derivatives differ");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("directional derivatives of"), "{text}");
        // The oscillator's coupling force follows its coupling input at once
        // (feedthrough): the standard's derivative is refused; the section's
        // outputs are its state's: zero.
        let instant = match unit {
            "left" => "is refused (feedthrough)",
            _ => "is zero",
        };
        assert!(text.contains(instant), "{unit}: {text}");
    }
}

/// A scene coupling a native oscillator (force input) with the pythonfmu spring.
fn spring_scene(scheme: &str, step: f64, libpython: &Path) -> String {
    format!(
        r#"
[simulation]
duration = 5.0
step = {step}

[master]
scheme = "{scheme}"
order = ["mass", "spring"]

[[units]]
name = "mass"
kind = "oscillator"
parameters = {{ mass = 1.0, stiffness = 100.0, damping = 1.0, coupling = "force", initial_displacement = 0.01 }}

[[units]]
name = "spring"
kind = "fmu"
parameters = {{ file = "SpringDamper.fmu", preload = ["{}"], start = {{ stiffness = 50.0 }} }}

[[connections]]
from = "mass.displacement"
to = "spring.displacement"

[[connections]]
from = "mass.velocity"
to = "spring.velocity"

[[connections]]
from = "spring.force"
to = "mass.force"

[output]
signals = ["mass.displacement"]
"#,
        libpython.display()
    )
}

/// Largest |x(t) - exact(t)| of the mass's displacement in a results folder,
/// against the mass on both springs (k = 150 N/m, c = 1 N s/m) in closed form.
fn error_against_exact(results: &Path) -> f64 {
    let (names, rows) = read_csv(&results.join("timeseries.csv"));
    let col = names.iter().position(|n| n == "mass.displacement").unwrap();
    let (k, c, m, x0) = (150.0_f64, 1.0_f64, 1.0_f64, 0.01_f64);
    let zeta_w = c / (2.0 * m);
    let wd = (k / m - zeta_w * zeta_w).sqrt();
    rows.iter()
        .map(|r| {
            let t = r[0];
            let exact = x0 * (-zeta_w * t).exp() * ((wd * t).cos() + zeta_w / wd * (wd * t).sin());
            (r[col] - exact).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn a_pythonfmu_fmu_couples_with_native_units_and_iterative_schemes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    fmu::pythonfmu_build("spring_damper.py", &[], dir.path());
    let (libpython, site) = python_paths();

    // Without libpython loaded, the importer says what to do.
    let info = slender(
        &[
            "fmu",
            "info",
            &dir.path().join("SpringDamper.fmu").display().to_string(),
        ],
        &site,
    );
    assert!(!info.status.success());
    let message = String::from_utf8_lossy(&info.stderr);
    assert!(
        message.contains("libpython") && message.contains("preload"),
        "{message}"
    );

    // Non-iterative Gauss-Seidel runs, and its error against the closed form
    // halves with the step (first order, as an explicit coupling should).
    let mut errors = Vec::new();
    for step in [0.002, 0.001] {
        let scene = dir.path().join(format!("spring_{step}.toml"));
        std::fs::write(&scene, spring_scene("gauss_seidel", step, &libpython)).unwrap();
        let results = dir.path().join(format!("results_{step}"));
        let out = slender(
            &[
                "run",
                &scene.display().to_string(),
                "--quiet",
                "--out",
                &results.display().to_string(),
            ],
            &site,
        );
        assert!(
            out.status.success(),
            "gauss_seidel with a pythonfmu FMU failed"
        );
        errors.push(error_against_exact(&results));
    }
    let ratio = errors[0] / errors[1];
    println!("errors against the exact solution: {errors:?} (ratio {ratio:.2})");
    assert!(errors[1] < 0.05 * 0.01, "{errors:?}");
    assert!((1.7..2.3).contains(&ratio), "not first order: {ratio}");

    // An iterative scheme needs rollback, which the FMU does not declare.
    let scene = dir.path().join("iterative.toml");
    std::fs::write(
        &scene,
        spring_scene("iterative_gauss_seidel", 0.001, &libpython),
    )
    .unwrap();
    let out = slender(&["check", &scene.display().to_string()], &site);
    assert!(!out.status.success());
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(
        message.contains("unit `spring` cannot roll back")
            && message.contains("iterative_gauss_seidel"),
        "{message}"
    );
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn the_fmpy_truncation_example_agrees_with_slender_within_its_tolerance() {
    let out = Command::new(fmu::python())
        .arg(root().join("examples/fmpy_truncation.py"))
        .args(["--duration", "5", "--slender"])
        .arg(slender_cli())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for line in text.lines().filter(|l| l.contains("velocity")) {
        let worst: f64 = line
            .split("difference from slender's run ")
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("cannot read: {line}"));
        // Both masters stop iterating below 1e-6 m/s.
        assert!(worst < 1e-6, "{line}");
    }
}

/// Exports `unit` of `scene` into `dir` as FMI `version`.
fn export_version(scene: &str, unit: &str, dir: &Path, version: FmiVersion) -> PathBuf {
    let config = ExportConfig::from_scene(&load(scene), unit).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join(format!("{unit}-{version:?}.fmu"));
    package_version(&config, &fmu::library(), &out, version).unwrap_or_else(|e| panic!("{e}"));
    out
}

#[test]
#[ignore = "needs FMPy and pythonfmu in .venv: ./scripts/test.sh runs it"]
fn fmi3_fmus_validate_simulate_as_their_fmi2_twins_and_round_trip_state_in_fmpy() {
    let dir = tempfile::tempdir().unwrap();
    for (scene, unit) in [
        ("examples/b3_force_displacement.toml", "b"),
        ("examples/truncation_substructured.toml", "n"),
        ("examples/pipe_dynamic_contact.toml", "pipe"),
        ("examples/structure_mooring.toml", "line_upper"),
    ] {
        let three = export_version(scene, unit, dir.path(), FmiVersion::Three);
        let two = export_version(scene, unit, dir.path(), FmiVersion::Two);
        let path = |p: &Path| p.display().to_string();
        let out = python_script(&["validate", &path(&three)]);
        assert!(out.status.success(), "{scene} {unit}: FMI 3.0 not valid");
        let out = python_script(&["state", &path(&three)]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(text.matches("bit-identical").count(), 3, "{text}");
        let mut csv = Vec::new();
        for (fmu, name) in [(&three, "three.csv"), (&two, "two.csv")] {
            let file = dir.path().join(format!("{unit}-{name}"));
            let out = python_script(&["simulate", &path(fmu), &path(&file), "0.5", "0.01"]);
            assert!(out.status.success(), "{scene} {unit}: simulate failed");
            csv.push(std::fs::read_to_string(&file).unwrap());
        }
        // FMI 3.0 adds a section's fields as array outputs (a cable's x, z
        // and tension; a nonlinear section's moment too); the rest is equal.
        let arrays = match unit {
            "n" => 3,
            "line_upper" => 4,
            _ => 0,
        };
        assert!(
            scalar_columns(&csv[0], arrays) == csv[1] && csv[0].lines().count() > 40,
            "{scene} {unit}: FMI 3.0 and 2.0 results differ"
        );
        if arrays > 0 {
            let out = python_script(&["arrays", &path(&three), "2.0", "0.01"]);
            let text = String::from_utf8_lossy(&out.stdout);
            println!("{text}");
            assert!(
                out.status.success() && text.contains(" 0 disagreements"),
                "{text}"
            );
        }
    }
}

/// FMPy's CSV without its last `arrays` columns (FMI 3.0 array outputs come
/// after every scalar).
fn scalar_columns(csv: &str, arrays: usize) -> String {
    let mut kept = String::new();
    for line in csv.lines() {
        let fields: Vec<&str> = line.split(',').collect();
        kept.push_str(&fields[..fields.len() - arrays].join(","));
        kept.push('\n');
    }
    kept
}

/// A section exported as FMI 3.0 whose mesh a parameter changes (issue 49
/// #13): its arrays read in FMPy at the sizes the FMU reports after
/// initialisation (`n_nodes`, `n_elements`), the sizes set before it taken
/// and a wrong one refused, and FMPy's `simulate_fmu` given the sizes (it
/// takes array shapes from the description's starts) bit-identical at the
/// arrays' ends to the scalar outputs: a cable (its end tensions) and a 3D
/// line (its end positions).
#[test]
#[ignore = "needs FMPy in .venv: ./scripts/test.sh runs it"]
fn fmi3_arrays_follow_a_mesh_changed_by_a_parameter_in_fmpy() {
    let dir = tempfile::tempdir().unwrap();
    for (scene, unit, elements) in [
        ("examples/truncation_substructured.toml", "n", "160"),
        ("examples/polyester_line_3d.toml", "line", "120"),
    ] {
        let fmu = export_version(scene, unit, dir.path(), FmiVersion::Three);
        let out = python_script(&["resize", &fmu.display().to_string(), "elements", elements]);
        let text = String::from_utf8_lossy(&out.stdout);
        println!("{text}");
        assert!(
            out.status.success() && text.contains("0 failures"),
            "{unit}: {text}"
        );
        assert!(text.contains("a wrong n_nodes refused"), "{text}");
    }
}
