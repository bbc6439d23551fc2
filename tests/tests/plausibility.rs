//! Issue 27: the watch on physical plausibility. A section's largest tension
//! beyond `output.watch.factor` times the structure's at the start is a
//! warning with the unit, port, value and time, or with `stop` the end of
//! the run; a run within it has none.

use slender_app::run::{RunOptions, run_scene};
use slender_tests::{hanging_pipe, hanging_pipe_text};

/// 500 m of steel pipe hanging from a top heaving 2 m (faded in over `fade`
/// s), started from its statics, with `watch` as the `[output]` watch table.
fn hanging(watch: &str, fade: f64) -> slender_app::run::RunResult {
    let heave = format!("{{ amplitude = 2.0, angular_frequency = 0.6, fade_in = {fade:?} }}");
    let output = format!("signals = [\"pipe.max_tension\"]\n{watch}");
    let scene = hanging_pipe((20.0, ""), (&heave, 1.0), &output);
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    run_scene(&scene, &options).unwrap()
}

#[test]
fn a_tension_beyond_the_stated_multiple_of_the_static_one_is_reported_or_stops_the_run() {
    // Started at full speed, the axially stiff pipe takes an axial wave of
    // 5.7 times its static tension in the first step: a warning.
    let impulsive = hanging("", 0.0);
    assert!(impulsive.summary.warnings[0].contains("at t = 0.05 s"));
    // Faded in over 10 s it stays within the default (5 times): nothing.
    let calm = hanging("", 10.0);
    assert!(
        calm.summary.error.is_none() && calm.summary.warnings.is_empty(),
        "{:?} {:?}",
        calm.summary.error,
        calm.summary.warnings
    );
    let peak = calm.recorder.column("pipe.max_tension").unwrap();
    let ratio = peak.iter().fold(0.0f64, |m, t| m.max(*t)) / peak[0];
    eprintln!("largest tension {ratio:.3} times the static one");
    assert!(ratio > 1.05 && ratio < 5.0, "{ratio}");
    // A factor below what the heave reaches: a warning naming the port, once.
    let warned = hanging("watch = { factor = 1.05 }", 10.0);
    assert!(warned.summary.error.is_none());
    let w = &warned.summary.warnings;
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("`pipe.max_tension`") && w[0].contains("at t = "),
        "{w:?}"
    );
    // With `stop`, the run ends there as failed.
    let stopped = hanging("watch = { factor = 1.05, stop = true }", 10.0);
    let error = stopped.summary.error.expect("stopped");
    assert!(error.contains("implausible load") && stopped.summary.status == "failed");
    assert!(stopped.summary.simulated_s < 20.0);
}

#[test]
fn a_tension_beyond_the_breaking_load_is_reported_and_bad_watch_keys_are_refused() {
    // The calm pipe's largest tension, and a breaking load just below it:
    // a warning that names the breaking load, though within the factor.
    let calm = hanging("", 10.0);
    let peak = calm.recorder.column("pipe.max_tension").unwrap();
    let largest = peak.iter().fold(0.0f64, |m, t| m.max(*t));
    let breaking = format!("watch = {{ breaking_load = {:?} }}", 0.99 * largest);
    let warned = hanging(&breaking, 10.0);
    let w = &warned.summary.warnings;
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("output.watch.breaking_load"), "{w:?}");
    // Above the largest: nothing.
    let above = format!("watch = {{ breaking_load = {:?} }}", 1.01 * largest);
    assert!(hanging(&above, 10.0).summary.warnings.is_empty());
    for (watch, key) in [
        ("watch = { factor = 0.5 }", "output.watch.factor"),
        (
            "watch = { breaking_load = -1.0 }",
            "output.watch.breaking_load",
        ),
    ] {
        let output = format!("signals = [\"pipe.max_tension\"]\n{watch}");
        let heave = "{ amplitude = 2.0, angular_frequency = 0.6 }";
        let text = hanging_pipe_text((20.0, ""), (heave, 1.0), &output);
        let parsed = slender_scene::Scene::parse(&slender_tests::root().join("h.toml"), text);
        let error = parsed.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(error.contains(key), "{watch}: {error}");
    }
}
