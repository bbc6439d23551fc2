//! Issue 27: a nonlinear section's energy balance (`external_work`,
//! `energy_error`) and the watch on energy growth. The balance closes where
//! the answer is known — the trapezoidal rule and the energy-conserving
//! integrator keep E - E0 - W at the level of their step's quadrature under
//! driven ends, Rayleigh damping, drag, a current and a heaving seabed — and
//! shows numerical damping as energy removed; a steel catenary riser meshed
//! too coarsely and stepped by the trapezoidal rule gains energy, which the
//! watch reports where its loads still look possible.

use slender_app::run::{RunOptions, RunResult, run_scene};
use slender_tests::hanging_pipe_text;

const QUANTITIES: [&str; 5] = [
    "energy_error",
    "external_work",
    "kinetic_energy",
    "strain_energy",
    "potential_energy",
];

fn run(scene: &slender_scene::Scene) -> RunResult {
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    run_scene(scene, &options).expect("the run")
}

/// The hanging steel pipe (500 m, 50 elements) for 30 s with the unit
/// `parameters` given, its top heaving 2 m faded in over `fade` s, recording
/// the balance.
fn hanging(parameters: &str, drag: f64, fade: f64) -> RunResult {
    let signals: Vec<String> = QUANTITIES.iter().map(|q| format!("\"pipe.{q}\"")).collect();
    let output = format!("signals = [{}]", signals.join(", "));
    let heave = format!("{{ amplitude = 2.0, angular_frequency = 0.6, fade_in = {fade:?} }}");
    let text = hanging_pipe_text((30.0, parameters), (&heave, drag), &output);
    // One integrator table: the parameters' replaces the helper's.
    let text = if parameters.contains("integrator") {
        text.replace(
            "integrator = { kind = \"hht\", alpha = 0.1 }\n[output]",
            "[output]",
        )
    } else {
        text
    };
    let scene = slender_scene::Scene::parse(&slender_tests::root().join("h.toml"), text)
        .expect("the hanging pipe");
    run(&scene)
}

/// The balance's figures over a run: (largest |E - E0 - W| and the error at
/// the end, both over the largest energy exchanged, and that energy (J)).
fn balance(result: &RunResult, unit: &str) -> (f64, f64, f64) {
    let column = |q: &str| {
        (result.recorder.column(&format!("{unit}.{q}")))
            .unwrap_or_else(|| panic!("{unit}.{q} recorded"))
    };
    let (error, work, kinetic) = (
        column("energy_error"),
        column("external_work"),
        column("kinetic_energy"),
    );
    let (strain, potential) = (column("strain_energy"), column("potential_energy"));
    let exchanged = (0..error.len())
        .map(|i| {
            (kinetic[i].abs())
                .max(work[i].abs())
                .max((strain[i] - strain[0]).abs())
                .max((potential[i] - potential[0]).abs())
        })
        .fold(0.0f64, f64::max);
    let largest = error.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    let end = error[error.len() - 1];
    (largest / exchanged, end / exchanged, exchanged)
}

#[test]
fn the_balance_closes_under_driven_ends_damping_drag_and_a_current() {
    let trapezoidal = "integrator = { kind = \"hht\", alpha = 0.0 }";
    let damped = format!(
        "{trapezoidal}\nrayleigh_mass = 0.01\nrayleigh_stiffness = 0.001\ncurrent = {{ z = [-300.0, 0.0], velocity = [0.2, 1.0] }}"
    );
    for (name, parameters, drag) in [
        ("trapezoidal", trapezoidal.to_string(), 0.0),
        ("trapezoidal, damped, drag, current", damped, 1.0),
        (
            "energy-conserving",
            "integrator = { kind = \"energy_conserving\" }".to_string(),
            1.0,
        ),
    ] {
        let result = hanging(&parameters, drag, 10.0);
        assert_eq!(result.summary.status, "completed", "{name}");
        let (largest, end, exchanged) = balance(&result, "pipe");
        eprintln!("{name}: |E - E0 - W| up to {largest:.3e} of {exchanged:.4e} J exchanged");
        assert!(exchanged > 1e4, "{name}: the top does work: {exchanged}");
        assert!(
            largest < 1e-4,
            "{name}: {largest:.3e} ({end:.3e} at the end)"
        );
        assert!(result.summary.warnings.is_empty(), "{name}");
    }
}

#[test]
fn numerical_damping_shows_as_energy_removed() {
    // Started at full speed, the top sends axial waves down the pipe that
    // the step does not resolve: HHT's damping removes their energy, more
    // with a larger alpha; the trapezoidal rule keeps (here slightly gains) it.
    let mut ends = Vec::new();
    for alpha in [0.0, 0.1, 0.3] {
        let integrator = format!("integrator = {{ kind = \"hht\", alpha = {alpha:?} }}");
        let (_, end, exchanged) = balance(&hanging(&integrator, 0.0, 0.0), "pipe");
        eprintln!("alpha = {alpha}: E - E0 - W at the end {end:.3e} of {exchanged:.4e} J");
        ends.push(end);
    }
    assert!(ends[0] > -1e-3, "{ends:?}");
    assert!(ends[1] < -1e-2 && ends[2] < ends[1], "{ends:?}");
}

/// 100 m of pipe pinned at both ends, lying on a seabed 1 cm below them that
/// heaves 0.1 m at 1 rad/s, for 20 s at step `h` (s) with `integrator` and
/// the contact `law`.
fn on_a_heaving_seabed(integrator: &str, law: &str, h: f64) -> RunResult {
    let signals: Vec<String> = QUANTITIES.iter().map(|q| format!("\"pipe.{q}\"")).collect();
    let text = format!(
        r#"
title = "pipe on a heaving seabed"
[simulation]
duration = 20.0
step = {h:?}
[master]
scheme = "gauss_seidel"
[[units]]
name = "pipe"
kind = "nonlinear"
[units.parameters]
static_start = true
start = [0.0, 0.0]
segments = [{{ length = 100.0, angle_deg = 0.0, elements = 50, axial_stiffness = 1e9, bending_stiffness = 1e6, mass_per_length = 100.0, submerged_weight = 500.0, diameter = 0.3 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned" }}
contact = {{ method = {{ kind = "{law}", penalty = 1e6 }}, surface = {{ shape = {{ kind = "flat", height = -0.01 }}, motion = {{ kind = "sine", amplitude = 0.1, angular_frequency = 1.0 }} }} }}
integrator = {integrator}
[output]
signals = [{}]
"#,
        signals.join(", ")
    );
    let scene = slender_scene::Scene::parse(&slender_tests::root().join("s.toml"), text)
        .expect("the heaving seabed");
    run(&scene)
}

#[test]
fn a_heaving_seabed_puts_in_the_work_the_balance_counts() {
    // The energy-conserving integrator and law: the surface moves at each
    // step's start, the balance closes to Newton's tolerance.
    let conserving = on_a_heaving_seabed(
        "{ kind = \"energy_conserving\" }",
        "energy_conserving",
        0.02,
    );
    let (largest, _, exchanged) = balance(&conserving, "pipe");
    eprintln!("energy-conserving: {largest:.3e} of {exchanged:.4e} J");
    assert!(exchanged > 1e3 && largest < 1e-8, "{largest:.3e}");
    // The trapezoidal rule on the penalty law converges on the balance as
    // the step shrinks; at 20 ms it gains energy — the pipe bounces on the
    // stiff seabed with 37 times the kinetic energy of the converged run —
    // and the watch says so. (Lifting the pinned pipe takes five times its
    // small static tension, which the watch on loads reports at both steps.)
    let trapezoidal = "{ kind = \"hht\", alpha = 0.0 }";
    let mut errors = Vec::new();
    for h in [0.02, 0.005] {
        let result = on_a_heaving_seabed(trapezoidal, "penalty", h);
        let (largest, end, exchanged) = balance(&result, "pipe");
        let kinetic = result.recorder.column("pipe.kinetic_energy").unwrap();
        let last = kinetic[kinetic.len() - 1];
        eprintln!(
            "trapezoidal, penalty, h = {h}: {largest:.3e} ({end:.3e} at the end) of {exchanged:.4e} J; kinetic at the end {last:.4e} J; {:?}",
            result.summary.warnings
        );
        let warnings = result.summary.warnings.iter();
        let growth = warnings.filter(|w| w.contains("energy growth")).count();
        errors.push((end, last, growth));
    }
    let ((coarse, coarse_kinetic, coarse_warnings), (fine, fine_kinetic, fine_warnings)) =
        (errors[0], errors[1]);
    assert!(fine.abs() < 1e-3 && fine_warnings == 0, "{fine}");
    assert!(coarse > 0.05 && coarse_warnings == 1, "{coarse}");
    assert!(coarse_kinetic > 10.0 * fine_kinetic);
}

/// The steel catenary riser example (200 s) at `elements` elements with HHT
/// `alpha`, for `duration` s, with the `[output]` watch table `watch`.
fn riser(elements: usize, alpha: f64, duration: f64, watch: &str) -> RunResult {
    let path = slender_tests::root().join("examples/structure_riser.toml");
    let text = std::fs::read_to_string(&path).expect("the riser example");
    let text = text
        .replace("elements = 200", &format!("elements = {elements}"))
        .replace("alpha = 0.1", &format!("alpha = {alpha:?}"))
        .replace("duration = 200.0", &format!("duration = {duration:?}"))
        .replace("[output]\n", &format!("[output]\n{watch}\n"));
    let scene = slender_scene::Scene::parse(&path, text).expect("the riser");
    run(&scene)
}

#[test]
fn a_riser_meshed_too_coarsely_and_stepped_without_damping_is_reported() {
    // At 50 elements and alpha = 0 the riser gains energy from about 30 s,
    // its top tension reaching 2.5 times the static one: within the watch on
    // tension (5 times), beyond the one on energy.
    let coarse = riser(50, 0.0, 60.0, "");
    let w = &coarse.summary.warnings;
    eprintln!("{w:?}");
    assert_eq!(coarse.summary.status, "completed");
    assert!(
        w.iter().any(|w| w.contains("implausible energy growth")
            && w.contains("`riser_reference.energy_error`")),
        "{w:?}"
    );
    assert!(!w.iter().any(|w| w.contains("implausible load")), "{w:?}");
    // The example's mesh and damping: nothing.
    let converged = riser(200, 0.1, 60.0, "");
    assert!(
        converged.summary.warnings.is_empty(),
        "{:?}",
        converged.summary.warnings
    );
    // With `stop`, the run ends at the first growth, as failed.
    let stopped = riser(50, 0.0, 60.0, "watch = { stop = true }");
    let error = stopped.summary.error.expect("stopped");
    assert!(error.contains("implausible energy growth"), "{error}");
    assert_eq!(stopped.summary.status, "failed");
    assert!(stopped.summary.simulated_s < 60.0);
}

#[test]
fn a_bad_energy_growth_is_refused_naming_the_key() {
    for value in ["0.0", "-1.0", "nan"] {
        let output =
            format!("signals = [\"pipe.max_tension\"]\nwatch = {{ energy_growth = {value} }}");
        let heave = "{ amplitude = 2.0, angular_frequency = 0.6 }";
        let text = hanging_pipe_text((20.0, ""), (heave, 1.0), &output);
        let parsed = slender_scene::Scene::parse(&slender_tests::root().join("h.toml"), text);
        let error = parsed.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            error.contains("output.watch.energy_growth"),
            "{value}: {error}"
        );
    }
}
