//! The step correction of the unit contract (`Unit::correct_step`, for a
//! master closing a step after one sweep, `newton.one_sweep`): for every
//! sample kind that declares it, the last step moved to end inputs changed
//! by a small change is the step taken again with those inputs, to the
//! Jacobian's own error times the change (1e-3 of it where the Newton matrix
//! leaves tangents out: the drag kinds of `contract_jacobian.rs`; round-off
//! for the linear kinds) and to second order beyond, on the outputs its
//! Jacobian gives and on its energy ledger. The kinds that must declare it
//! are listed.

use slender_scene::export::ExportedUnit;
use slender_tests::samples::{SteppedSample, outputs_after, samples, started, stepped_samples};
use slender_units::{Driver, DriverSlot, Time};

/// The largest differences, relative to max(|output|, its row's scale), over `rows`, for
/// inputs moved by `size` of their scale: between the corrected step and the
/// step taken again, between the step taken again and the step (what the
/// correction moves), and between two solves of the step taken again (from
/// the step's start and warm: the solver's tolerance).
fn gap(
    driver: &mut Driver,
    slot: &DriverSlot,
    (t, h): (Time, Time),
    (inputs, size): (&[f64], f64),
    (rows, scales): (&[usize], &[f64]),
) -> [f64; 3] {
    let change: Vec<f64> = (inputs.iter().enumerate())
        .map(|(j, u)| size * u.abs().max(1.0) * [1.0, -0.7, 0.4][j % 3])
        .collect();
    let moved: Vec<f64> = inputs.iter().zip(&change).map(|(u, c)| u + c).collect();
    let again = outputs_after(driver, slot, (t, h), &moved);
    let base = outputs_after(driver, slot, (t, h), inputs);
    let n_out = again.len();
    let mut jacobian = vec![0.0; n_out * inputs.len()];
    driver.step_jacobian(&mut jacobian).unwrap();
    driver.correct_step(&change).unwrap();
    let mut corrected = vec![0.0; n_out];
    driver.outputs(&mut corrected).unwrap();
    driver.restore_warm(slot).unwrap();
    driver.set_inputs(&moved).unwrap();
    driver.do_step(t, h).unwrap();
    let mut warm = vec![0.0; n_out];
    driver.outputs(&mut warm).unwrap();
    let worst = |x: &[f64]| {
        (rows.iter().zip(scales))
            .map(|(&r, scale)| (x[r] - again[r]).abs() / again[r].abs().max(*scale))
            .fold(0.0, f64::max)
    };
    [worst(&corrected), worst(&base), worst(&warm)]
}

/// Each row's scale: 1, but an energy balance's error is a difference of the
/// energies (J): their size, so its round-off is not taken for an error.
fn row_scales(rows: &[usize], names: &[String], base: &[f64]) -> Vec<f64> {
    let energy = (rows.iter())
        .filter(|&&r| names[r].contains("energy") || names[r].contains("work"))
        .map(|&r| base[r].abs())
        .fold(1.0, f64::max);
    (rows.iter())
        .map(|&r| {
            if names[r].contains("error") {
                energy
            } else {
                1.0
            }
        })
        .collect()
}

/// The kinds whose Jacobian leaves part of a tangent out (as in
/// `contract_jacobian.rs`).
const DRAG_KINDS: [&str; 2] = ["nonlinear", "line3d coupled"];

/// The kinds whose samples must correct their steps.
const CORRECTING_KINDS: [&str; 7] = [
    "body",
    "catenary3d",
    "line3d coupled",
    "line3d linear",
    "nonlinear",
    "nonlinear linear",
    "static_section",
];

#[test]
fn every_declared_step_correction_is_the_step_taken_again_to_its_jacobian_s_error() {
    let dir = tempfile::tempdir().unwrap();
    let mut checked = Vec::new();
    for sample in stepped_samples(dir.path(), |c| c.step_correction) {
        let SteppedSample {
            kind,
            mut driver,
            slot,
            step: (t, h),
            inputs,
            base,
        } = sample;
        let mut jacobian = vec![0.0; base.len() * inputs.len()];
        driver.step_jacobian(&mut jacobian).unwrap();
        let names: Vec<String> = (driver.description().outputs.iter())
            .map(|p| p.name.clone())
            .collect();
        // The rows the Jacobian gives (what a master couples) and the ledger,
        // less the residual force at a free end (zero in the step, noise):
        // the corrected state leaves one there of the Jacobian's own error
        // (the nonlinear section's Newton matrix leaves the drag's turning
        // out: 8e-4 N m and 7e-4 N for inputs moved by 1e-2 here).
        let rows: Vec<usize> = (0..base.len())
            .filter(|&r| {
                jacobian[r * inputs.len()].is_finite()
                    || names[r].contains("energy")
                    || names[r].contains("work")
            })
            .filter(|&r| base[r].abs() > 1e-6)
            .collect();
        let scales = row_scales(&rows, &names, &base);
        let rows = (rows.as_slice(), scales.as_slice());
        let [large, moved, _] = gap(&mut driver, &slot, (t, h), (&inputs, 1e-4), rows);
        let [small, _, noise] = gap(&mut driver, &slot, (t, h), (&inputs, 1e-5), rows);
        eprintln!(
            "{kind}: {} rows moved by {moved:.2e}: corrected against stepped again {large:.2e} (inputs moved 1e-4), {small:.2e} (1e-5); two solves {noise:.2e}",
            rows.0.len()
        );
        // The correction is the step's to its Jacobian's error (first order,
        // the tangents its Newton matrix leaves out: 1e-3 of a row for the
        // kinds with drag, contract_jacobian.rs) and second order beyond.
        // Linear kinds' is exact (to round-off).
        let drag = DRAG_KINDS.contains(&kind);
        let jacobian_error = if drag { 1e-3 } else { 1e-9 };
        assert!(
            large <= jacobian_error * moved + 3.0 * noise + 1e-13,
            "{kind}: {large:e} of {moved:e}"
        );
        if drag {
            assert!(small < large, "{kind}: {small:e} against {large:e}");
        }
        // A correction by the step's derivatives needs the step's Jacobian
        // (the last step had none); the static sections' is their own rule.
        if !["static_section", "catenary3d"].contains(&kind) {
            let refused = driver.correct_step(&vec![0.0; inputs.len()]);
            assert!(refused.is_err(), "{kind}");
        }
        checked.push(kind);
    }
    for kind in CORRECTING_KINDS {
        assert!(
            checked.contains(&kind),
            "no `{kind}` sample checked: {checked:?}"
        );
    }
}

#[test]
fn a_step_correction_is_refused_in_sub_steps_and_by_a_unit_that_does_not_declare_it() {
    let dir = tempfile::tempdir().unwrap();
    let all = samples(dir.path());
    let config = |name: &str| &all.iter().find(|(k, _)| *k == name).unwrap().1;
    let (_, start, h) = started(config("nonlinear"), 2);
    let mut multirate = config("nonlinear").driver().unwrap();
    multirate.set_substeps(2).unwrap();
    multirate.set_inputs(&start).unwrap();
    multirate.initialize(Time::ZERO).unwrap();
    multirate.do_step(Time::ZERO, h).unwrap();
    assert!(!multirate.can_correct_step());
    assert!(multirate.correct_step(&vec![0.0; start.len()]).is_err());
    let (mut cable, start, _) = started(config("cable"), 2);
    assert!(!cable.description().capabilities.step_correction);
    let error = cable.correct_step(&vec![0.0; start.len()]).unwrap_err();
    assert!(error.to_string().contains("step correction"), "{error}");
}

/// The outputs after `driver` steps from `slot` with `inputs`, told (or not)
/// that the step will be corrected; then, after `finish` (a correction, or
/// taking a pending end), and after one more step: the three output vectors
/// and whether an end was pending.
fn stepped_with_end(
    driver: &mut Driver,
    slot: &DriverSlot,
    (t, h): (Time, Time),
    (inputs, deferred): (&[f64], bool),
    finish: &dyn Fn(&mut Driver) -> bool,
) -> ([Vec<f64>; 3], bool) {
    let n_out = driver.description().outputs.len();
    let ends: Vec<usize> = (0..n_out.min(18)).collect();
    driver.restore(slot).unwrap();
    driver.set_inputs(inputs).unwrap();
    if deferred {
        driver.defer_step_end(&ends);
    }
    driver.do_step(t, h).unwrap();
    let mut out = [vec![0.0; n_out], vec![0.0; n_out], vec![0.0; n_out]];
    driver.outputs(&mut out[0]).unwrap();
    let pending = finish(driver);
    driver.outputs(&mut out[1]).unwrap();
    driver.do_step(t + h, h).unwrap();
    driver.outputs(&mut out[2]).unwrap();
    (out, pending)
}

#[test]
fn a_step_end_left_pending_for_its_correction_is_the_whole_end_to_the_bit() {
    let dir = tempfile::tempdir().unwrap();
    let mut deferring = Vec::new();
    for sample in stepped_samples(dir.path(), |c| c.step_correction) {
        let SteppedSample {
            kind,
            mut driver,
            slot,
            step,
            inputs,
            ..
        } = sample;
        let change: Vec<f64> = (inputs.iter().enumerate())
            .map(|(j, u)| 1e-4 * u.abs().max(1.0) * [1.0, -0.7, 0.4][j % 3])
            .collect();
        let complete = |d: &mut Driver| d.complete_step().unwrap();
        let correct = |d: &mut Driver| {
            let n = d.description().outputs.len() * change.len();
            d.step_jacobian(&mut vec![0.0; n]).unwrap();
            d.correct_step(&change).unwrap();
            false
        };
        for (finish, what) in [
            (&complete as &dyn Fn(&mut Driver) -> bool, "taken"),
            (&correct, "corrected"),
        ] {
            let (whole, none) =
                stepped_with_end(&mut driver, &slot, step, (&inputs, false), finish);
            let (left, pending) =
                stepped_with_end(&mut driver, &slot, step, (&inputs, true), finish);
            assert!(!none, "{kind}: an end pending without the hint");
            // Before its end is taken, a pending step gives its end outputs.
            let ends = whole[0].len().min(18);
            assert_eq!(left[0][..ends], whole[0][..ends], "{kind}: end outputs");
            assert_eq!(left[1], whole[1], "{kind}: outputs after the end {what}");
            assert_eq!(left[2], whole[2], "{kind}: outputs a step later ({what})");
            if pending {
                deferring.push(kind);
            }
        }
    }
    // The planar section evaluates its whole length at a step's end, its
    // `linear` fidelity too (band products, forces and moments for the
    // outputs): both leave that end pending (the kinds whose end is cheap do
    // not).
    for kind in ["nonlinear", "nonlinear linear"] {
        assert!(deferring.contains(&kind), "{kind}: {deferring:?}");
    }
}
