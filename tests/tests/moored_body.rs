//! A body on its lines (`[mooring]`, issue 47): the system written out, the
//! body at its equilibrium, the coupling of a light buoy (non-iterative
//! Gauss-Seidel diverges where the lines' mass outweighs the body's, Newton
//! on the units' Jacobians does not), the OC3-Hywind example's surge decay
//! against its statics' natural period, and bad input refused by key.

use slender_scene::Scene;
use slender_tests::buoy::{FAIRLEADS, LINES};
use slender_tests::{Series, run, units_and_links};
use std::path::Path;

/// A buoy of mass MASS on three 120 m chains in 50 m of water, moved 2 m in
/// surge; SCHEME the master's scheme (NEWTON: its Newton line or none).
const BUOY: &str = r#"
title = "a buoy on three chains"
[simulation]
duration = DURATION
step = STEP
[master]
scheme = "SCHEME"
extrapolation = "linear"
max_iterations = 30
tolerances = { velocity = 1e-6, force = 1.0 }
NEWTON

[mooring.body]
name = "buoy"
mass = MASS
inertia = [INERTIA, INERTIA, INERTIA]
centre_of_gravity = [0.0, 0.0, -1.0]
displaced_volume = VOLUME
hydrostatic_stiffness = [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 2e5, 0, 0, 0], [0, 0, 0, 2e6, 0, 0], [0, 0, 0, 0, 2e6, 0], [0, 0, 0, 0, 0, 0]]
additional_stiffness = [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 1e5]]
initial_offset = [2.0, 0.0, 0.0, 0.0, 0.0, 0.0]
FAIRLEADS
LINES
"#;

/// [`BUOY`] with its fairleads and lines.
fn buoy_text() -> String {
    BUOY.replace("FAIRLEADS", FAIRLEADS).replace("LINES", LINES)
}

/// The lines' mass with their normal added mass (kg): 3 x 120 m x (60 +
/// 1025 pi 0.1^2 / 4).
const LINES_MASS: f64 = 3.0 * 120.0 * (60.0 + 1025.0 * std::f64::consts::PI * 0.01 / 4.0);

/// The buoy scene with body mass `mass` (kg), run by `scheme` at `step` (s)
/// for `duration` (s), with Newton on the units' Jacobians or without.
fn buoy(mass: f64, scheme: &str, newton: bool, step: f64, duration: f64) -> Scene {
    // Buoyancy carries the weight and about 30 kN of the lines' pull each.
    let volume = (mass * 9.80665 + 3.0 * 30_000.0) / (1025.0 * 9.80665);
    let text = buoy_text()
        .replace("SCHEME", scheme)
        .replace("MASS", &format!("{mass:e}"))
        .replace("INERTIA", &format!("{:e}", 4.0 * mass))
        .replace("VOLUME", &format!("{volume}"))
        .replace("STEP", &format!("{step}"))
        .replace("DURATION", &format!("{duration}"))
        .replace(
            "NEWTON",
            if newton {
                "newton = { derivatives = \"units\" }"
            } else {
                ""
            },
        );
    Scene::parse(Path::new("buoy.toml"), text).unwrap_or_else(|e| panic!("{e}"))
}

fn largest(s: &Series, name: &str) -> f64 {
    s.get(name).iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[test]
fn the_system_is_written_out_with_the_body_at_its_equilibrium() {
    let scene = buoy(2e5, "iterative_jacobi", true, 0.1, 1.0);
    let (units, links) = units_and_links(&scene);
    let names: Vec<&str> = units.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["buoy", "l1_full", "l2_full", "l3_full"]);
    // Each line: its top's velocity from the fairlead, its pull to it, x y z.
    assert_eq!(links.len(), 18);
    let body = units[0].1["parameters"].as_table().unwrap();
    let offset: Vec<f64> = (body["initial_offset"].as_array().unwrap().iter())
        .map(|v| v.as_float().unwrap())
        .collect();
    // The 2 m surge counted from the equilibrium, which heaves the buoy a
    // little (the lines pull about 30 kN down each, give or take).
    assert!((offset[0] - 2.0).abs() < 1e-6, "{offset:?}");
    assert!(
        offset[2].abs() > 1e-4 && offset[2].abs() < 0.5,
        "{offset:?}"
    );
    // The line's top is where the body puts its fairlead.
    let top = &units[1].1["parameters"]["end"]["position"];
    let x = top[0].as_float().unwrap();
    assert!((x - (2.0 + 2.0)).abs() < 1e-3, "{x}");
}

#[test]
fn newton_couples_a_light_buoy_where_gauss_seidel_diverges() {
    // The lines' mass and added mass against the body's: 0.12, 1.2 and 12.
    let mut rows = Vec::new();
    for mass in [2e5, 2e4, 2e3] {
        let ratio = LINES_MASS / mass;
        let newton = run(&buoy(mass, "iterative_jacobi", true, 0.1, 60.0));
        assert!(newton.error.is_none(), "{mass}: {:?}", newton.error);
        assert_eq!(newton.counters.non_converged_steps, 0, "{mass}");
        let sweeps = newton.counters.iterations as f64 / newton.counters.steps as f64;
        assert!(sweeps < 2.2, "{mass}: {sweeps}");
        assert!(largest(&newton, "buoy.x") < 2.1, "{mass}");
        let explicit = run(&buoy(mass, "gauss_seidel", false, 0.1, 60.0));
        let diverged = explicit.error.is_some() || largest(&explicit, "buoy.x") > 10.0;
        rows.push((ratio, sweeps, diverged, explicit.error.clone()));
        if ratio < 0.5 {
            assert!(!diverged, "{mass}: {:?}", explicit.error);
            // Stable, Gauss-Seidel follows Newton to the step's lag.
            let (a, b) = (explicit.get("buoy.x"), newton.get("buoy.x"));
            let gap = a
                .iter()
                .zip(b)
                .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(gap < 0.05, "{mass}: {gap}");
        } else {
            assert!(diverged, "{mass}: Gauss-Seidel held at mass ratio {ratio}");
        }
    }
    for (ratio, sweeps, diverged, error) in rows {
        eprintln!(
            "lines/body mass {ratio:.2}: Newton {sweeps:.2} sweeps a step; Gauss-Seidel diverged: {diverged} ({error:?})"
        );
    }
}

#[test]
fn the_light_buoy_under_newton_converges_with_the_step() {
    let coarse = run(&buoy(2e3, "iterative_jacobi", true, 0.1, 30.0));
    let fine = run(&buoy(2e3, "iterative_jacobi", true, 0.05, 30.0));
    let finest = run(&buoy(2e3, "iterative_jacobi", true, 0.025, 30.0));
    // The coarse run at the fine run's times (every other sample).
    let gap = |a: &Series, b: &Series| {
        let (x, y) = (a.get("buoy.x"), b.get("buoy.x"));
        x.iter()
            .zip(y.iter().step_by(2))
            .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()))
    };
    let (e1, e2) = (gap(&coarse, &fine), gap(&fine, &finest));
    eprintln!("buoy surge, step 0.1 vs 0.05 s: {e1:.3e} m; 0.05 vs 0.025 s: {e2:.3e} m");
    assert!(e1 < 0.05 && e2 < 0.5 * e1, "{e1:e} {e2:e}");
}

#[test]
fn the_oc3_spar_s_surge_decay_has_its_statics_period() {
    use slender_app::decay::decay;
    use slender_scene::mooring;
    use slender_units::body::mooring::natural_modes;
    let scene = slender_tests::load("examples/oc3_hywind.toml");
    let system = mooring::of_scene(&scene).unwrap().unwrap();
    let lines = system.catenaries().unwrap();
    let eq = system.equilibrium_on(&lines).unwrap();
    let modes = natural_modes(&system.body, &lines, &eq.offset).unwrap();
    let surge = modes.iter().find(|m| m.dominant == 0).unwrap().period;
    let s = run(&scene);
    assert!(s.error.is_none(), "{:?}", s.error);
    assert_eq!(s.counters.non_converged_steps, 0);
    let d = decay(&s.time, s.get("spar.x"), eq.offset[0]).unwrap();
    eprintln!(
        "OC3 surge decay: {:.2} s (linear {surge:.2} s), damping ratio {:.3}, {} cycles",
        d.period, d.damping_ratio, d.cycles
    );
    // The linear period about the equilibrium against the decay from 10 m,
    // whose quadratic drag and catenary stiffen and damp it a little.
    assert!((d.period - surge).abs() < 0.02 * surge, "{d:?} vs {surge}");
    assert!(d.cycles >= 3 && d.damping_ratio > 0.0, "{d:?}");
}

/// The buoy at rest at its equilibrium, heavily damped, `l1` breaking at 5 s
/// (its line stepped at 0.02 s inside the coupling step: it falls onto the
/// seabed's penalty springs), at coupling step `step` (s).
fn broken(duration: f64, step: f64) -> String {
    let volume = (2e5 * 9.80665 + 3.0 * 30_000.0) / (1025.0 * 9.80665);
    buoy_text().replace("SCHEME", "iterative_jacobi")
        .replace("MASS", "2e5")
        .replace("INERTIA", "8e5")
        .replace("VOLUME", &format!("{volume}"))
        .replace("STEP", &format!("{step}"))
        .replace("DURATION", &format!("{duration}"))
        .replace("NEWTON", "newton = { derivatives = \"units\" }")
        .replace(
            "initial_offset = [2.0, 0.0, 0.0, 0.0, 0.0, 0.0]",
            "initial_offset = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\ndamping_linear = [[5e4, 0, 0, 0, 0, 0], [0, 5e4, 0, 0, 0, 0], [0, 0, 5e4, 0, 0, 0], [0, 0, 0, 1e5, 0, 0], [0, 0, 0, 0, 1e5, 0], [0, 0, 0, 0, 0, 1e5]]",
        )
        .replace(
            "anchor = [100.0, 0.0, -50.0]",
            "anchor = [100.0, 0.0, -50.0]\nbreak_at = 5.0\nmodel = { max_step = 0.02 }",
        )
}

/// The buoy's drift over 60 s after `l1` breaks (m), and the largest gap
/// (m) to the same body without `l1` let go at rest from the three lines'
/// equilibrium (its lines' statics solved there, not the body's), at
/// coupling step `step` (s).
fn break_against_absence(step: f64) -> (f64, f64) {
    let with_break = broken(65.0, step);
    let scene = Scene::parse(Path::new("broken.toml"), with_break.clone()).unwrap();
    let eq = slender_scene::mooring::of_scene(&scene)
        .unwrap()
        .unwrap()
        .equilibrium()
        .unwrap();
    let a = run(&scene);
    assert!(a.error.is_none(), "{:?}", a.error);
    let l1 = with_break.find("[[mooring.lines]]\nname = \"l1\"").unwrap();
    let l2 = with_break.find("[[mooring.lines]]\nname = \"l2\"").unwrap();
    let without = format!("{}{}", &with_break[..l1], &with_break[l2..])
        .replace("duration = 65", "duration = 60")
        .replace(
            "initial_offset = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]",
            &format!("initial_offset = {:?}", eq.offset),
        )
        .replace(
            "[mooring.body]",
            "[mooring]\nstatics = false\n\n[mooring.body]",
        )
        .replace("\"l1_full.end_tension\"", "\"l2_full.end_tension\"");
    let b = run(&Scene::parse(Path::new("without.toml"), without).unwrap());
    assert!(b.error.is_none(), "{:?}", b.error);
    // A at 5 s + tau against B at tau.
    let shift = (5.0 / step).round() as usize;
    let mut gap = 0.0_f64;
    for name in ["buoy.x", "buoy.z"] {
        let (x, y) = (a.get(name), b.get(name));
        for (p, q) in x[shift..].iter().zip(y) {
            gap = gap.max((p - q).abs());
        }
    }
    // The broken line pulls nothing from the break on.
    assert!(
        a.get("l1_full.end_tension")[shift + 1..]
            .iter()
            .all(|&t| t == 0.0)
    );
    ((a.last("buoy.x") - a.get("buoy.x")[shift]).abs(), gap)
}

#[test]
fn after_a_line_breaks_the_body_drifts_as_if_the_line_had_never_been_there() {
    let (drift, gap) = break_against_absence(0.1);
    let (_, finer) = break_against_absence(0.05);
    eprintln!(
        "after the break: drift {drift:.3} m in 60 s; largest gap to the run without the line {gap:.3e} m at 0.1 s, {finer:.3e} m at 0.05 s"
    );
    assert!(drift > 1.0, "{drift}");
    // The break falls inside a step, whose trapezoidal rule spreads the
    // lost pull over it: an impulse of half a step's pull, first order in h.
    assert!(gap < 2e-3 * drift, "{gap:e} of {drift}");
    assert!(finer < 0.6 * gap, "{finer:e} vs {gap:e}");
}

#[test]
fn the_body_exported_as_an_fmu_and_coupled_back_gives_the_native_results() {
    use slender_fmi::export::ExportConfig;
    use slender_scene::export::{FmiVersion, SceneExport, package_version};
    let dir = tempfile::tempdir().unwrap();
    let volume = (2e4 * 9.80665 + 3.0 * 30_000.0) / (1025.0 * 9.80665);
    let native_text = buoy_text()
        .replace("SCHEME", "iterative_jacobi")
        .replace("MASS", "2e4")
        .replace("INERTIA", "8e4")
        .replace("VOLUME", &format!("{volume}"))
        .replace("STEP", "0.1")
        .replace("DURATION", "20.0")
        .replace("NEWTON", "newton = { derivatives = \"units\" }");
    let native_path = dir.path().join("native.toml");
    std::fs::write(&native_path, &native_text).unwrap();
    let native = Scene::load(&native_path).unwrap();
    for (fmi, version) in [(2, FmiVersion::Two), (3, FmiVersion::Three)] {
        let config = ExportConfig::from_scene(&native, "buoy").unwrap();
        let file = format!("buoy{fmi}.fmu");
        let library = slender_tests::fmu::library();
        package_version(&config, &library, &dir.path().join(&file), version).unwrap();
        let with_fmu = native_text.replace(
            "name = \"buoy\"\n",
            &format!("name = \"buoy\"\nfmu = {{ file = \"{file}\" }}\n"),
        );
        let fmu_path = dir.path().join(format!("fmu{fmi}.toml"));
        std::fs::write(&fmu_path, with_fmu).unwrap();
        let with_fmu = Scene::load(&fmu_path).unwrap_or_else(|e| panic!("{e}"));
        let (units, _) = units_and_links(&with_fmu);
        assert_eq!(units[0].1["kind"].as_str(), Some("fmu"));
        let (a, b) = (run(&native), run(&with_fmu));
        assert!(
            a.error.is_none() && b.error.is_none(),
            "{:?} {:?}",
            a.error,
            b.error
        );
        assert_eq!(
            a.columns, b.columns,
            "FMI {fmi}: the FMU body differs from the native one"
        );
        assert_eq!(a.counters.iterations, b.counters.iterations);
        assert!(b.counters.jacobian_evaluations > 0);
    }
}

#[test]
fn one_sea_reaches_the_lines_and_the_body() {
    let scene = slender_tests::load("examples/oc3_hywind_jonswap.toml");
    let (units, _) = units_and_links(&scene);
    for (name, unit) in &units {
        let waves = &unit["parameters"]["waves"]["spectrum"]["significant_height"];
        assert_eq!(waves.as_float(), Some(6.0), "{name}");
    }
    // The sea moves the spar: over the first 60 s it surges and pitches.
    let mut short = scene;
    short.set_duration(60.0).unwrap();
    let s = run(&short);
    assert!(s.error.is_none(), "{:?}", s.error);
    assert!(
        largest(&s, "spar.pitch") > 1e-3,
        "{}",
        largest(&s, "spar.pitch")
    );
}

/// The spar and its lines stepped on two or three threads give the same bits
/// as on one: the sweep's units step alone, and a line's wave sums, shared
/// out among the threads that are idle, take each node alone.
#[test]
fn the_moored_spar_on_threads_is_bit_identical_to_one_thread() {
    let path = slender_tests::root().join("examples/oc3_hywind_jonswap.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let run_on = |threads: u32| {
        let text = text.replacen("[master]\n", &format!("[master]\nthreads = {threads}\n"), 1);
        let mut scene = Scene::parse(&path, text).unwrap();
        scene.set_duration(20.0).unwrap();
        run(&scene)
    };
    let one = run_on(1);
    assert!(one.error.is_none(), "{:?}", one.error);
    for threads in [2, 3] {
        let many = run_on(threads);
        assert_eq!(one.names, many.names);
        for (name, (a, b)) in one.names.iter().zip(one.columns.iter().zip(&many.columns)) {
            let same = a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "{threads} threads differ on {name}");
        }
        assert_eq!(one.counters.iterations, many.counters.iterations);
    }
}
