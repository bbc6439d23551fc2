//! Planar partitions closed in one sweep per step (`newton.one_sweep`): the
//! riser (laid as its static section, sag bend `nonlinear`, top `linear:30`)
//! and the mooring line (lower `nonlinear:16`) follow their iterated runs to
//! the coupling tolerance, at the sweeps per step (at most 1.2).

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

/// The example with `edits`, iterated and in one sweep: (iterated, one sweep).
fn both(scene: &str, edits: &[(&str, &str)]) -> (Series, Series) {
    let iterated = run_edited(scene, edits).unwrap();
    let mut one = edits.to_vec();
    one.push((NEWTON, ONE_SWEEP));
    (iterated, run_edited(scene, &one).unwrap())
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
    eprintln!(
        "riser: {:.3} sweeps per step (iterated {:.3}), {} of {} steps corrected",
        sweeps(&one),
        sweeps(&iterated),
        one.counters.corrected_steps,
        one.counters.steps
    );
    assert!(sweeps(&one) <= 1.2, "{}", sweeps(&one));
    assert!(one.counters.max_residual <= 1.0);
    // Within the coupling tolerance (1 N) of the iterated run: 0.09 N here.
    for signal in ["riser_top.end_force_x", "riser_top.end_force_z"] {
        let d = largest_difference(&one, &iterated, signal);
        eprintln!("{signal}: {d:.3e} N");
        assert!(d < 1.0, "{signal}: {d} N");
    }
    let d = largest_difference(&one, &iterated, "riser_sagbend.sagbend_moment");
    eprintln!("sag-bend moment: {d:.3e} N m");
    // 3.3e-2 N m measured, on moments of about 1e5 N m.
    assert!(d < 1.0, "{d} N m");
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
