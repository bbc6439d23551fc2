//! The reduced section's forces through sampled elements and seabed nodes
//! (`reduced_sampling`, ECSW, issue 26): at a tight tolerance the sample is
//! the whole projection; at the default it follows the reduced section on the
//! three flagships; what it cannot sample is refused with the reason.

use slender_tests::edited::{run_edited, worst_epsilon};
use slender_tests::samples::NONLINEAR_SAMPLE;
use slender_tests::seed002::section;
use slender_units::Time;
use slender_units::nonlinear::NonlinearSection;
use slender_units::{Driver, UnitError};

/// The sample section (no stinger) with `extra` appended, its end outputs
/// over `steps` steps of 10 ms under nudged inputs, and the driver.
/// (`elements = N` in `extra` sets the segment's element count, `no
/// contact` takes the seabed away).
fn stepped(extra: &str, steps: i64) -> (Vec<Vec<f64>>, Driver<NonlinearSection>) {
    let no_contact = extra.contains("no contact");
    let without = |l: &&str| !(l.starts_with("stinger") || no_contact && l.starts_with("contact"));
    let table: Vec<&str> = NONLINEAR_SAMPLE.lines().filter(without).collect();
    let mut text = format!("{}\n", table.join("\n"));
    for line in extra.lines().filter(|l| *l != "no contact") {
        match line.strip_prefix("elements = ") {
            Some(n) => text = text.replace("elements = 8", &format!("elements = {n}")),
            None => text += &format!("{line}\n"),
        }
    }
    let mut driver = section(&text);
    let h = Time::from_secs(0.01).unwrap();
    let mut out = vec![0.0; driver.description().outputs.len()];
    let ports = driver.description().inputs.len();
    let outputs = (0..steps)
        .map(|k| {
            let inputs: Vec<f64> = (0..ports).map(|_| 0.05 * (k as f64 * 0.3).sin()).collect();
            driver.set_inputs(&inputs).unwrap();
            driver.do_step(h * k, h).unwrap();
            driver.outputs(&mut out).unwrap();
            out[..18].to_vec()
        })
        .collect();
    (outputs, driver)
}

/// The largest difference relative to 1 + |value| between two output runs.
fn largest_difference(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| x.iter().zip(y))
        .map(|(x, y)| (x - y).abs() / (1.0 + x.abs()))
        .fold(0.0, f64::max)
}

#[test]
fn at_a_tight_tolerance_the_sample_is_the_reduced_section() {
    // 8 elements and 9 nodes on the seabed plane (the sample's contact):
    // the forces of the whole section reproduced to 1e-10 over the window
    // need every active term with weight 1, so the sampled section steps
    // as the reduced one after its training window too.
    let (reduced, _) = stepped("reduced_modes = 4", 100);
    let extra = "reduced_modes = 4\nreduced_sampling = { training = 0.3, tolerance = 1e-10 }";
    let (sampled, driver) = stepped(extra, 100);
    let (picked, candidates) = driver.unit().sample_size().expect("trained after 0.3 s");
    let worst = largest_difference(&reduced, &sampled);
    eprintln!("tight tolerance: {picked} of {candidates} terms, difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
    assert_eq!(candidates, 8 + 9);
}

#[test]
fn at_the_default_tolerance_the_sample_is_smaller_and_follows() {
    // The sample section in 60 elements without its seabed, trained over
    // 1 s and run 2 s further on the sampled elements.
    let steps = 300;
    let section = "elements = 60\nno contact\nreduced_modes = 4";
    let (reduced, _) = stepped(section, steps);
    let extra = format!("{section}\nreduced_sampling = {{ training = 1.0 }}");
    let (sampled, driver) = stepped(&extra, steps);
    let (picked, candidates) = driver.unit().sample_size().expect("trained");
    let worst = largest_difference(&reduced, &sampled);
    eprintln!("sample: {picked} of {candidates} elements, difference {worst:.2e}");
    assert_eq!(candidates, 60);
    assert!(picked < candidates, "{picked} of {candidates}");
    assert!(worst < 1e-2, "{worst}");
}

#[test]
fn a_window_without_motion_is_refused_when_it_ends() {
    let table: Vec<&str> = NONLINEAR_SAMPLE
        .lines()
        .filter(|l| !l.starts_with("stinger"))
        .collect();
    let extra = "static_start = true\nreduced_modes = 4\nreduced_sampling = { training = 0.05 }";
    let mut driver = section(&format!("{}\n{extra}\n", table.join("\n")));
    let h = Time::from_secs(0.01).unwrap();
    let zeros = vec![0.0; driver.description().inputs.len()];
    driver.set_inputs(&zeros).unwrap();
    let error = (0..20)
        .find_map(|k| driver.do_step(h * k, h).err())
        .map(|e| e.to_string())
        .unwrap_or_default();
    // The sample hangs at rest in its equilibrium: nothing to train on.
    assert!(
        error.contains("did not change over the training window")
            && error.contains("reduced_sampling.training"),
        "{error}"
    );
}

#[test]
fn sampling_needs_a_reduced_section_and_a_window() {
    let refuse = |extra: &str| {
        let params: Result<slender_units::nonlinear::params::NonlinearParams, _> =
            toml::from_str(&format!("{NONLINEAR_SAMPLE}\n{extra}\n"));
        NonlinearSection::new(params.expect("parses")).err()
    };
    let named = |e: Option<UnitError>, key: &str| {
        let text = e.map(|e| e.to_string()).unwrap_or_default();
        assert!(text.contains(key), "{key}: {text}");
    };
    named(
        refuse("reduced_sampling = { training = 1.0 }"),
        "without reduced_modes",
    );
    named(
        refuse("reduced_modes = 4\nreduced_sampling = { training = 0.0 }"),
        "reduced_sampling.training",
    );
    named(
        refuse("reduced_modes = 4\nreduced_sampling = { training = 1.0, tolerance = 2.0 }"),
        "reduced_sampling.tolerance",
    );
}

#[test]
fn sampled_sections_follow_the_twin_on_the_mooring_line_the_s_lay_and_the_riser() {
    // The mooring line's lower section in a current (elements with drag),
    // the S-lay's laid pipe and the riser's laid section on the seabed
    // (elements and seabed nodes): within 1 % of the twin on every
    // indicator, as the reduced sections without sampling.
    let mooring = run_edited(
        "examples/structure_mooring.toml",
        &[(
            "fidelity = \"cable\"",
            "fidelity = { kind = \"reduced\", modes = 6, training = 5.0 }",
        )],
    )
    .unwrap();
    let worst = worst_epsilon("mooring lower reduced:6 sampled", &mooring);
    assert!(worst < 1e-2, "{worst}");
    let slay = run_edited(
        "examples/structure_slay.toml",
        &[(
            "name = \"laid\"\n",
            "name = \"laid\"\nfidelity = { kind = \"reduced\", modes = 6, training = 5.0 }\n",
        )],
    )
    .unwrap();
    let worst = worst_epsilon("S-lay laid reduced:6 sampled", &slay);
    assert!(worst < 1e-2, "{worst}");
    let riser = run_edited(
        "examples/structure_riser.toml",
        &[
            ("duration = 200.0", "duration = 60.0"),
            (
                "name = \"laid\"\n",
                "name = \"laid\"\nfidelity = { kind = \"reduced\", modes = 6, training = 10.0 }\n",
            ),
        ],
    )
    .unwrap();
    let worst = worst_epsilon("riser laid reduced:6 sampled", &riser);
    assert!(worst < 1e-2, "{worst}");
}

#[test]
fn a_long_section_sampled_on_two_modes_follows_the_twin() {
    // The mooring line on 500 elements, its lower section (406) reduced to
    // two modes (13 coordinates with the attachments, derivatives and the
    // anchor's constraint modes) and sampled after 2 s: where the reduced
    // fidelity pays (2.4x the full section, BENCHMARKS.md), the top force
    // within 1e-3 of the twin's and the anchor's force within 1 % of its peak.
    let series = run_edited(
        "examples/structure_mooring.toml",
        &[
            ("duration = 60.0", "duration = 40.0"),
            ("elements = 80", "elements = 500"),
            (
                "fidelity = \"cable\"",
                "fidelity = { kind = \"reduced\", modes = 2, training = 2.0 }",
            ),
            (
                "signals = [",
                "signals = [\"line_lower.sampled_terms\", \"line_lower.start_force_x\", \"line_lower.start_force_z\", ",
            ),
        ],
    )
    .unwrap();
    let worst = worst_epsilon("mooring lower (406 elements) reduced:2 sampled", &series);
    assert!(worst < 1e-3, "{worst}");
    let from = series.time.iter().position(|&t| t >= 20.0).unwrap();
    for axis in ["x", "z"] {
        let reduced = &series.get(&format!("line_lower.start_force_{axis}"))[from..];
        let twin = &series.get(&format!("line_reference.start_force_{axis}"))[from..];
        let peak = twin.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let miss = (reduced.iter().zip(twin)).fold(0.0f64, |a, (r, t)| a.max((r - t).abs()));
        eprintln!("anchor force {axis}: {:.2e} of its peak", miss / peak);
        assert!(miss < 1e-2 * peak, "{axis}: {miss} of {peak}");
    }
    // The sample's size, an output: none during the 2 s of training, then
    // under a tenth of the section's 406 elements (what makes it cheap:
    // 16 here).
    let sampled = series.get("line_lower.sampled_terms");
    let at = |t: f64| sampled[series.time.iter().position(|&s| s >= t).unwrap()];
    assert_eq!(at(1.0), 0.0);
    let picked = *sampled.last().unwrap();
    eprintln!("sampled terms: {picked} of 406 elements");
    assert!((1.0..406.0 / 10.0).contains(&picked), "{picked}");
}

#[test]
fn a_section_the_stingers_rollers_press_on_is_not_sampled() {
    // The S-lay's stinger section rides the rollers: its sample would drop
    // their force, so `check` refuses it with the roller it passes over.
    let error = run_edited(
        "examples/structure_slay.toml",
        &[(
            "name = \"stinger\"\n",
            "name = \"stinger\"\nfidelity = { kind = \"reduced\", modes = 6, training = 1.0 }\n",
        )],
    )
    .err()
    .unwrap_or_default();
    assert!(
        error.contains("stinger's roller at x =") && error.contains("leave `training` out"),
        "{error}"
    );
    // The unit alone (the contract sample over its roller, a penalty law):
    // the run stops when the window ends, saying why.
    let text = NONLINEAR_SAMPLE.replace("augmented_lagrangian", "penalty")
        + "reduced_modes = 4\nreduced_sampling = { training = 0.05 }\n";
    let mut driver = section(&text);
    let h = Time::from_secs(0.01).unwrap();
    let inputs = vec![0.05; driver.description().inputs.len()];
    driver.set_inputs(&inputs).unwrap();
    let error = (0..20)
        .find_map(|k| driver.do_step(h * k, h).err())
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        error.contains("roller presses on it") && error.contains("reduced_sampling"),
        "{error}"
    );
}

#[test]
fn sampling_keys_are_for_a_section_reduced_about_its_static_state() {
    let error = run_edited(
        "examples/structure_mooring.toml",
        &[(
            "fidelity = \"cable\"",
            "fidelity = { kind = \"reduced\", modes = 6, tolerance = 1e-3 }",
        )],
    )
    .err()
    .unwrap_or_default();
    assert!(error.contains("with `training`"), "{error}");
}
