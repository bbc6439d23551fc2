//! Issue 30: a section's start takes no damping reaction as load. The
//! polyester line as a structure, a `cable` lower section under a short
//! `nonlinear` top driven by the fairlead's motion with Rayleigh damping on:
//! the top force starts at the monolithic line's static value, and the cable,
//! which solves its statics under that force, keeps the right mean. The whole
//! line alone reports its equilibrium at t = 0, and with its motion faded in
//! starts without a spike.

use slender_scene::Scene;
use slender_tests::{impulsive, root, run};

/// The mooring example cut `top` elements (of 80) below the fairlead, run
/// for `duration` s.
fn mooring(top: usize, duration: f64) -> Scene {
    mooring_with(top, duration, |t| t)
}

/// The same with the scene's text changed by `edit`.
fn mooring_with(top: usize, duration: f64, edit: impl Fn(String) -> String) -> Scene {
    let path = root().join("examples/structure_mooring.toml");
    let text = edit(impulsive(&std::fs::read_to_string(&path).unwrap()));
    let element = 1934.0 / 80.0;
    let cut = 1934.0 - top as f64 * element;
    assert!(text.contains("to = 1571.375") && text.contains("duration = 60.0"));
    let text = text
        .replace("to = 1571.375", &format!("to = {cut}"))
        .replace("duration = 60.0", &format!("duration = {duration:?}"));
    Scene::parse(&path, text).unwrap()
}

fn magnitude(s: &slender_tests::Series, unit: &str, k: usize) -> f64 {
    let x = s.get(&format!("{unit}.end_force_x"))[k];
    let z = s.get(&format!("{unit}.end_force_z"))[k];
    x.hypot(z)
}

#[test]
fn a_cable_under_a_short_nonlinear_top_starts_on_the_equilibrium_and_keeps_its_mean() {
    for top in [1, 2, 8] {
        let s = run(&mooring(top, 600.0));
        assert!(s.error.is_none(), "{top}: {:?}", s.error);
        let (start, twin_start) = (
            magnitude(&s, "line_upper", 0),
            magnitude(&s, "line_reference", 0),
        );
        assert!(
            (start - twin_start).abs() < 1e-3 * twin_start,
            "{top} elements: starts at {start} N, the line at {twin_start} N"
        );
        let mean = |unit: &str| {
            let ks: Vec<usize> = (0..s.time.len()).filter(|&k| s.time[k] >= 100.0).collect();
            ks.iter().map(|&k| magnitude(&s, unit, k)).sum::<f64>() / ks.len() as f64
        };
        let (sections, twin) = (mean("line_upper"), mean("line_reference"));
        // The master's start check saw the cable's top load and let it pass.
        let change = s
            .counters
            .start_load
            .as_ref()
            .expect("the cable is checked");
        assert!(
            change.connection.contains("line_lower.top_force"),
            "{change:?}"
        );
        assert!(change.relative_change < 0.2, "{change:?}");
        eprintln!(
            "{top} elements: start {start:.1} N (twin {twin_start:.1}), mean 100-600 s {sections:.1} N (twin {twin:.1}), start change {:.2} %",
            100.0 * change.relative_change
        );
        assert!(
            (sections - twin).abs() < 5e-3 * twin,
            "{top} elements: mean {sections} N against {twin} N"
        );
    }
}

#[test]
fn the_line_alone_reports_its_equilibrium_at_the_start_and_a_faded_motion_no_spike() {
    let impulsive = run(&mooring(15, 1.0));
    // The fairlead held still where the motion puts it at t = 0.
    let x0 = 34.64356882758602 + 0.8 * 0.5f64.sin();
    let z0 = -27.45901617359891 + 1.0 + 0.4 * 2.0f64.sin();
    let held = run(&mooring_with(15, 1.0, |t| {
        let line = t
            .lines()
            .find(|l| l.starts_with("ends.end = "))
            .unwrap()
            .to_owned();
        t.replace(
            &line,
            &format!(
                "ends.end = {{ x = {{ displacement = {x0} }}, z = {{ displacement = {z0} }} }}"
            ),
        )
    }));
    // The fairlead's surge and heave faded in over 20 s.
    let faded = run(&mooring_with(15, 1.0, |t| {
        t.replace(
            "angular_frequency = 0.6, sines",
            "angular_frequency = 0.6, fade_in = 20.0, sines",
        )
        .replace(
            "angular_frequency = 0.6, phase = 1.5707963267948966, sines",
            "angular_frequency = 0.6, phase = 1.5707963267948966, fade_in = 20.0, sines",
        )
    }));
    for s in [&impulsive, &held, &faded] {
        assert!(s.error.is_none(), "{:?}", s.error);
    }
    // At t = 0 the moving fairlead reports the equilibrium there, as the held
    // one does (it reported 4.29 MN before: the damping of its node alone).
    let (a, b) = (
        magnitude(&impulsive, "line_reference", 0),
        magnitude(&held, "line_reference", 0),
    );
    assert!((a - b).abs() < 1e-6 * b, "{a} N against {b} N");
    // Faded in, no step of the first second moves the top force by 1 %.
    let forces: Vec<f64> = (0..faded.time.len())
        .map(|k| magnitude(&faded, "line_reference", k))
        .collect();
    for w in forces.windows(2) {
        assert!((w[1] - w[0]).abs() < 1e-2 * w[0], "{forces:?}");
    }
}

#[test]
fn a_start_change_beyond_the_scene_tolerance_stops_the_run_naming_both_sections() {
    // The fairlead's motion starts at full speed: the top load changes by
    // 11.7 % over the first step, within the default 0.2 but not 0.05.
    let scene = mooring_with(1, 1.0, |t| {
        t.replacen("[master]", "[master]\nstart_tolerance = 0.05", 1)
    });
    let s = run(&scene);
    let error = s.error.expect("stopped by the start check");
    for expected in [
        "`line_lower.top_force_",
        "`line_upper.start_force_",
        "start_tolerance 0.05",
    ] {
        assert!(error.contains(expected), "`{expected}` not in: {error}");
    }
    assert_eq!(
        s.time,
        [0.0],
        "stopped in the first step, its start recorded"
    );
}
