//! Planar partitions closed in one sweep per step (`newton.one_sweep`): the
//! riser (laid as its static section, sag bend `nonlinear`, top `linear:30`)
//! and the mooring line (lower `nonlinear:16`) follow their iterated runs to
//! the coupling tolerance, at the sweeps per step (at most 1.2), and
//! so does the OC3 spar on its three lines (1.00 sweeps per step) and the
//! S-lay, whose rollers make a first correction miss (a later sweep is
//! corrected in turn: 1.10 sweeps per step); a
//! section that cannot correct its step leaves every step iterated.

use slender_tests::Series;
use slender_tests::edited::run_edited;

const NEWTON: &str = "newton = { derivatives = \"units\" }";
const ONE_SWEEP: &str = "newton = { derivatives = \"units\", one_sweep = true }";

/// The largest difference between two runs' `signal` over the run.
fn largest_difference(a: &Series, b: &Series, signal: &str) -> f64 {
    (a.get(signal).iter().zip(b.get(signal)))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Sweeps per step of a run.
fn sweeps(s: &Series) -> f64 {
    s.counters.iterations as f64 / s.counters.steps as f64
}

/// The example with `edits`, iterated and in one sweep: (iterated, one
/// sweep), whichever of the two the example ships with.
fn both(scene: &str, edits: &[(&str, &str)]) -> (Series, Series) {
    let text = std::fs::read_to_string(slender_tests::root().join(scene)).unwrap();
    let (to_iterated, to_one) = if text.contains(ONE_SWEEP) {
        (Some((ONE_SWEEP, NEWTON)), None)
    } else {
        (None, Some((NEWTON, ONE_SWEEP)))
    };
    let with = |extra: Option<(&'static str, &'static str)>| {
        let mut all = edits.to_vec();
        all.extend(extra);
        run_edited(scene, &all).unwrap()
    };
    (with(to_iterated), with(to_one))
}

/// Asserts that the run in one sweep took at most 1.2 sweeps per step and
/// followed the iterated run to the coupling tolerance (1 N) on the end
/// `forces` (N) and within 1 N m on `moment`; prints what it measured.
fn assert_follows(label: &str, iterated: &Series, one: &Series, forces: [&str; 2], moment: &str) {
    eprintln!(
        "{label}: {:.3} sweeps per step (iterated {:.3}), {} of {} steps corrected",
        sweeps(one),
        sweeps(iterated),
        one.counters.corrected_steps,
        one.counters.steps
    );
    assert!(sweeps(one) <= 1.2, "{}", sweeps(one));
    assert!(one.counters.max_residual <= 1.0);
    for signal in forces {
        let d = largest_difference(one, iterated, signal);
        eprintln!("{signal}: {d:.3e} N");
        assert!(d < 1.0, "{signal}: {d} N");
    }
    let d = largest_difference(one, iterated, moment);
    eprintln!("{moment}: {d:.3e} N m");
    assert!(d < 1.0, "{d} N m");
}

#[test]
fn the_riser_in_one_sweep_per_step_follows_its_iterated_run() {
    let (iterated, one) = both(
        "examples/structure_riser.toml",
        &[
            ("duration = 200.0", "duration = 60.0"),
            ("name = \"laid\"", "name = \"laid\"\nfidelity = \"static\""),
            ("name = \"top\"", "name = \"top\"\nfidelity = \"linear:30\""),
        ],
    );
    // Within the coupling tolerance (1 N) of the iterated run: 0.1 N here;
    // the sag-bend moment 2.9e-2 N m of about 1e5 N m.
    assert_follows(
        "riser",
        &iterated,
        &one,
        ["riser_top.end_force_x", "riser_top.end_force_z"],
        "riser_sagbend.sagbend_moment",
    );
}

#[test]
fn the_mooring_line_in_one_sweep_per_step_follows_its_iterated_run() {
    let (iterated, one) = both(
        "examples/structure_mooring.toml",
        &[("fidelity = \"cable\"", "fidelity = \"nonlinear:16\"")],
    );
    eprintln!(
        "mooring line: {:.3} sweeps per step (iterated {:.3}), {} of {} steps corrected",
        sweeps(&one),
        sweeps(&iterated),
        one.counters.corrected_steps,
        one.counters.steps
    );
    assert!(sweeps(&one) <= 1.2, "{}", sweeps(&one));
    let d = largest_difference(&one, &iterated, "line_upper.end_force_z");
    eprintln!("fairlead force: {d:.3e} N");
    assert!(d < 1.0, "{d} N");
}

#[test]
fn a_section_that_cannot_correct_its_step_leaves_every_step_iterated() {
    // The mooring line as shipped: its lower section is a `cable`, which
    // offers no correction; the run is the iterated one to the bit, and a
    // warning names the section.
    let (iterated, asked) = both("examples/structure_mooring.toml", &[]);
    assert_eq!(asked.counters.corrected_steps, 0);
    assert_eq!(
        asked.get("line_upper.end_force_z"),
        iterated.get("line_upper.end_force_z")
    );
    assert!(
        (asked.warnings.iter()).any(|w| w.contains("one_sweep") && w.contains("`line_lower`")),
        "{:?}",
        asked.warnings
    );
}

#[test]
fn the_moored_spar_in_one_sweep_per_step_follows_its_iterated_run() {
    // The body and its lines (upper halves `line3d`, lower halves as their
    // catenaries) all correct their steps: 1.00 sweeps per step (2.00
    // iterated); the fairlead tensions within 0.06 N and the surge within
    // 3e-8 m of the iterated run measured (tolerance 1 N).
    let edits = [("duration = 600.0", "duration = 100.0")];
    let (iterated, one) = both("examples/oc3_hywind.toml", &edits);
    eprintln!(
        "OC3: {:.3} sweeps per step (iterated {:.3})",
        sweeps(&one),
        sweeps(&iterated)
    );
    assert!(sweeps(&one) <= 1.05, "{}", sweeps(&one));
    for signal in ["line1_upper.end_tension", "line2_upper.end_tension"] {
        let d = largest_difference(&one, &iterated, signal);
        eprintln!("{signal}: {d:.3e} N");
        assert!(d < 1.0, "{signal}: {d} N");
    }
    let d = largest_difference(&one, &iterated, "spar.x");
    assert!(d < 1e-5, "surge {d} m");
}

#[test]
fn the_s_lay_in_one_sweep_per_step_follows_its_iterated_run() {
    // The stinger's rollers (penalty contact, 1e6 N/m) engage and leave
    // inside steps, so a correction after the first sweep can miss the
    // tolerance; the step is then swept again and that sweep corrected in
    // turn. Measured: 1.10 sweeps per step (2.07 iterated), the top force
    // within 0.18 N and the sag-bend moment within 0.11 N m (of about
    // 5e4 N m) of the iterated run (tolerance 1 N).
    let (iterated, one) = both("examples/structure_slay.toml", &[]);
    assert_follows(
        "S-lay",
        &iterated,
        &one,
        ["pipe_stinger.end_force_x", "pipe_stinger.end_force_z"],
        "pipe_sagbend.sagbend_moment",
    );
}

#[test]
fn a_step_whose_first_correction_misses_is_corrected_after_its_next_sweep() {
    // The S-lay at the tolerances it shipped with before (1e-7 m/s,
    // 1e-2 N: 1e-7 of its tension): what a correction leaves after the
    // first sweep is 3-1000 tolerances on the stinger's cut force on most
    // steps. Corrected after the first sweep only, 226 of 600 steps closed
    // by a correction and 2.13 sweeps per step; corrected after later
    // sweeps too, 531 and 1.62.
    let tight = [(
        "velocity = 1e-6, force = 1.0, generic = 1e-6",
        "velocity = 1e-7, force = 1e-2, generic = 1e-7",
    )];
    let (_, one) = both("examples/structure_slay.toml", &tight);
    eprintln!(
        "S-lay at 1e-2 N: {:.3} sweeps per step, {} of {} steps corrected",
        sweeps(&one),
        one.counters.corrected_steps,
        one.counters.steps
    );
    assert!(one.counters.max_residual <= 1.0);
    assert!(sweeps(&one) < 1.8, "{}", sweeps(&one));
    assert!(one.counters.corrected_steps > 400);
}
