//! The interface Jacobian of the unit contract (`Unit::step_jacobian`, issue
//! 25): for every sample kind that declares it, the derivative of its outputs
//! after a step with respect to the step's end inputs equals central finite
//! differences of the unit's own `do_step` from the rolled-back state, for every
//! input, at a state a few nudged steps away from the start; and the driver's
//! forward-difference fallback (what the master uses for units without one)
//! agrees with it. Entries a unit leaves NaN (outputs it does not derive) are
//! skipped, but every end output of a nonlinear section is given.

use slender_scene::export::ExportedUnit;
use slender_tests::samples::{
    SteppedSample, inputs_at, outputs_after, samples, started, stepped_samples,
};
use slender_units::{Driver, DriverSlot, Time};

/// Central differences of the step, column by column (row-major outputs x
/// inputs), each input moved by `relative` of its size (at least `relative`).
fn central_differences(
    driver: &mut Driver,
    slot: &DriverSlot,
    th: (Time, Time),
    inputs: &[f64],
    relative: f64,
) -> Vec<f64> {
    let n_in = inputs.len();
    let n_out = driver.description().outputs.len();
    let mut jacobian = vec![0.0; n_out * n_in];
    for j in 0..n_in {
        let delta = relative * inputs[j].abs().max(1.0);
        let mut moved = inputs.to_vec();
        moved[j] = inputs[j] + delta;
        let up = outputs_after(driver, slot, th, &moved);
        moved[j] = inputs[j] - delta;
        let down = outputs_after(driver, slot, th, &moved);
        for i in 0..n_out {
            jacobian[i * n_in + j] = (up[i] - down[i]) / (2.0 * delta);
        }
    }
    jacobian
}

/// The largest difference between a unit's Jacobian `a` and central
/// differences `b`, each row relative to the row's largest entry (rows are in
/// different units), over the rows `a` gives and where the differences resolve
/// the row: rows whose differences at two step sizes (`b`, `b_coarse`) disagree
/// by more than a tenth of the row (outputs at the unit's Newton noise, such as
/// the residual force at a free end) are counted apart. Returns (largest
/// difference, rows compared, rows at the noise floor); each entry is judged
/// against the closer of the two, less `floor` (per row: the round-off of the
/// coarse differences, a few ulps of the output over the step).
fn row_relative_difference(
    a: &[f64],
    (b, b_coarse): (&[f64], &[f64]),
    floor: &[f64],
    n_in: usize,
) -> (f64, usize, usize) {
    let (mut worst, mut compared, mut noisy) = (0.0f64, 0, 0);
    let rows = a
        .chunks(n_in)
        .zip(b.chunks(n_in))
        .zip(b_coarse.chunks(n_in));
    for (((ra, rb), rc), &floor) in rows.zip(floor) {
        if ra.iter().any(|v| v.is_nan()) {
            continue;
        }
        let scale = ra.iter().chain(rb).fold(0.0f64, |m, v| m.max(v.abs()));
        if scale == 0.0 {
            compared += 1;
            continue;
        }
        let spread = rb
            .iter()
            .zip(rc)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        if spread > 0.1 * scale {
            noisy += 1;
            continue;
        }
        compared += 1;
        // The closer of the two: the coarse step has less round-off, the fine
        // one less truncation.
        for ((x, y), z) in ra.iter().zip(rb).zip(rc) {
            let difference = (x - y).abs().min((x - z).abs());
            worst = worst.max((difference - floor).max(0.0) / scale);
        }
    }
    (worst, compared, noisy)
}

/// The kinds whose samples must give their own step Jacobian.
const DECLARING_KINDS: [&str; 10] = [
    "oscillator",
    "line3d coupled",
    "static_section",
    "nonlinear",
    "span_coupling",
    "cable",
    "beam",
    "chord",
    "fmu",
    "reduced",
];

/// The kinds whose Newton matrix leaves part of a tangent out, so their
/// Jacobian is the iteration's (1e-3 of a row). Linear units are exact (to
/// the round-off of the differences; the linear nonlinear section too:
/// 1.6e-12 of a row). The nonlinear section back-substitutes with its
/// Newton matrix, whose drag tangent leaves out the elements' turning (a few
/// 1e-4 of a row here); so does the reduced section's, formed from the same
/// tangents, and the sampled one's (its tangent through the sampled
/// elements). The 3D line's leaves out drag's and the axial damper's
/// position derivatives and takes sliding friction by its secant (1.4e-4).
const DRAG_KINDS: [&str; 4] = [
    "nonlinear",
    "nonlinear reduced",
    "nonlinear sampled",
    "line3d coupled",
];

#[test]
fn every_declared_step_jacobian_equals_finite_differences_of_the_step() {
    let dir = tempfile::tempdir().unwrap();
    let mut checked = Vec::new();
    for sample in stepped_samples(dir.path(), |c| c.step_jacobian) {
        let SteppedSample {
            kind,
            mut driver,
            slot,
            step: (t, h),
            inputs,
            base,
        } = sample;
        let (n_in, n_out) = (inputs.len(), base.len());
        let mut own = vec![0.0; n_out * n_in];
        driver
            .step_jacobian(&mut own)
            .unwrap_or_else(|e| panic!("{kind}: {e}"));
        let reference = central_differences(&mut driver, &slot, (t, h), &inputs, 1e-6);
        let coarse = central_differences(&mut driver, &slot, (t, h), &inputs, 1e-4);
        let smallest_step = inputs
            .iter()
            .map(|u| 1e-4 * u.abs().max(1.0))
            .fold(f64::INFINITY, f64::min);
        let floor: Vec<f64> = base
            .iter()
            .map(|y| 8.0 * f64::EPSILON * y.abs() / smallest_step)
            .collect();
        let (worst, rows, noisy) =
            row_relative_difference(&own, (&reference, &coarse), &floor, n_in);
        eprintln!(
            "{kind}: {rows} of {n_out} output rows compared ({noisy} at the noise floor), largest difference {worst:.2e} of the row"
        );
        let drag = DRAG_KINDS.contains(&kind);
        let tolerance = if drag { 1e-3 } else { 1e-6 };
        assert!(worst < tolerance, "{kind}: {worst:e}");
        if kind == "nonlinear" {
            assert!(
                rows + noisy >= 18,
                "{kind}: the end outputs must all be given"
            );
            assert!(rows >= 15, "{kind}: {rows} rows resolved");
        }
        // The master's fallback for units without a Jacobian: forward
        // differences of the step, inputs moved by 1e-6 of their size.
        let delta: Vec<f64> = inputs.iter().map(|u| 1e-6 * u.abs().max(1.0)).collect();
        let mut forward = vec![0.0; n_out * n_in];
        let mut scratch = Vec::new();
        driver
            .finite_difference_jacobian(
                &slot,
                (t, h),
                (&inputs, &delta),
                &base,
                (&mut forward, &mut scratch),
            )
            .unwrap();
        // Its round-off floor is that of its own (smaller) step.
        let fd_floor: Vec<f64> = floor.iter().map(|f| f * 100.0).collect();
        let (fd_worst, _, _) =
            row_relative_difference(&forward, (&reference, &coarse), &fd_floor, n_in);
        assert!(fd_worst < 1e-3, "{kind}: forward differences {fd_worst:e}");
        checked.push(kind);
    }
    for kind in DECLARING_KINDS {
        assert!(
            checked.contains(&kind),
            "no `{kind}` sample checked: {checked:?}"
        );
    }
}

#[test]
fn a_step_jacobian_is_refused_after_a_rollback_and_in_sub_steps() {
    let dir = tempfile::tempdir().unwrap();
    let (_, config) = samples(dir.path())
        .into_iter()
        .find(|(k, _)| *k == "nonlinear")
        .unwrap();
    let (mut driver, start, h) = started(&config, 2);
    let n = driver.description().outputs.len() * start.len();
    let mut jacobian = vec![0.0; n];
    assert!(driver.step_jacobian(&mut jacobian).is_ok());
    let mut slot = DriverSlot::new();
    driver.save(&mut slot).unwrap();
    driver.restore(&slot).unwrap();
    // Restored: the factor is not of a step from this state.
    assert!(driver.step_jacobian(&mut jacobian).is_err());
    driver.set_inputs(&inputs_at(&start, 3)).unwrap();
    driver.do_step(h * 2, h).unwrap();
    assert!(driver.step_jacobian(&mut jacobian).is_ok());
    assert!(
        driver.step_jacobian(&mut vec![0.0; n + 1]).is_err(),
        "a wrong buffer size"
    );
    let mut multirate = config.driver().unwrap();
    multirate.set_substeps(2).unwrap();
    multirate.set_inputs(&start).unwrap();
    multirate.initialize(Time::ZERO).unwrap();
    multirate.do_step(Time::ZERO, h).unwrap();
    assert!(multirate.step_jacobian(&mut jacobian).is_err(), "sub-steps");
}
