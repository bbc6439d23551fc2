//! The 3D line coupled at its fairlead, by velocity or by force: its step
//! Jacobian against central differences.

use super::Line3d;
use super::params::EndCondition;
use super::tests::{laid_line, output, started, step_from};
use crate::contract::{Driver, Time};

/// The laid line with its fairlead coupled by velocity or force and the
/// `extra` surroundings: stepped 2 s, then one step whose Jacobian is checked.
fn coupled(condition: &str, extra: &str) -> (Driver<Line3d>, Vec<f64>) {
    let mut p = laid_line(30, 25.0, extra);
    p.end.condition = if condition == "force" {
        EndCondition::Force
    } else {
        EndCondition::Velocity
    };
    let mut d = Driver::new(Line3d::new(p).unwrap());
    let inputs = if condition == "force" {
        // The static pull of the fairlead on the line (found first with
        // the end held), so the loaded line starts where the held one is.
        let held = started(laid_line(30, 25.0, extra));
        ["x", "y", "z"]
            .map(|c| -output(&held, &format!("end_force_{c}")))
            .to_vec()
    } else {
        vec![0.3, -0.2, 0.1]
    };
    d.set_inputs(&inputs).unwrap();
    d.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.1).unwrap();
    let mut t = Time::ZERO;
    for _ in 0..20 {
        d.do_step(t, h).unwrap();
        t += h;
    }
    (d, inputs)
}

#[test]
fn the_step_jacobian_matches_finite_differences() {
    // Exact where the line's forces' tangents are (bars, bending, seabed
    // spring, added mass, the axial damper); with drag in a current to the
    // drag's position derivative, which the Newton matrix leaves out.
    let drag = "drag_normal = 1.2\ncurrent = [{ depth = 0.0, speed = 0.5, heading_deg = 70.0 }]";
    let linear_drag = format!("linear = true\n{drag}");
    for (condition, extra, tolerance) in [
        ("velocity", "", 1e-5),
        ("force", "", 1e-5),
        ("velocity", drag, 1e-3),
        ("force", drag, 1e-3),
        // Linear: drag held from the step's start, so as exact with it.
        ("velocity", "linear = true", 1e-5),
        ("force", "linear = true", 1e-5),
        ("velocity", &linear_drag, 1e-5),
    ] {
        let (mut d, inputs) = coupled(condition, extra);
        let (n_out, n_in) = (d.description().outputs.len(), inputs.len());
        let mut slot = crate::contract::DriverSlot::new();
        d.save(&mut slot).unwrap();
        let (t, h) = (Time::from_secs(2.0).unwrap(), Time::from_secs(0.1).unwrap());
        let step = |d: &mut Driver<Line3d>, u: &[f64]| step_from(d, &slot, (t, h), u);
        let mut jacobian = vec![0.0; n_out * n_in];
        // Twice: a linear line's second Jacobian is its first, kept.
        for _ in 0..2 {
            step(&mut d, &inputs);
            d.step_jacobian(&mut jacobian).unwrap();
        }
        for j in 0..n_in {
            let delta = 1e-5 * inputs[j].abs().max(1.0);
            let (mut up, mut down) = (inputs.clone(), inputs.clone());
            up[j] += delta;
            down[j] -= delta;
            let (plus, minus) = (step(&mut d, &up), step(&mut d, &down));
            for row in 0..18 {
                let fd = (plus[row] - minus[row]) / (2.0 * delta);
                let exact = jacobian[row * n_in + j];
                let scale = (0..18)
                    .map(|r| ((plus[r] - minus[r]) / (2.0 * delta)).abs())
                    .fold(0.0, f64::max);
                assert!(
                    (fd - exact).abs() <= tolerance * scale,
                    "{condition} {extra}: output {row}, input {j}: {exact} against {fd} (scale {scale})"
                );
            }
            for row in 18..n_out {
                assert!(jacobian[row * n_in + j].is_nan());
            }
        }
    }
}

#[test]
fn a_sliding_line_s_step_jacobian_takes_friction_s_tangent() {
    // A pipe dragged sideways over the seabed at 5 and 50 times the stick
    // velocity: every node slides, where Newton's matrix holds friction's
    // secant (force over speed); the Jacobian puts the tanh's tangent back.
    // Measured: 4.4e-3 and 5.8e-2 of each end force's scale (with Newton's
    // secant 1.2 and 0.25); what is left is friction's change with the
    // line's direction, a position derivative left out as drag's is.
    for (speed, tolerance) in [(0.05, 1e-2), (0.5, 1e-1)] {
        let mut d = super::tests::dragged([0.0, speed, 0.0]);
        let inputs = [0.0, speed, 0.0, 0.0, speed, 0.0];
        let h = Time::from_secs(0.1).unwrap();
        let mut t = Time::ZERO;
        for _ in 0..20 {
            d.do_step(t, h).unwrap();
            t += h;
        }
        let n_out = d.description().outputs.len();
        let mut slot = crate::contract::DriverSlot::new();
        d.save(&mut slot).unwrap();
        let step = |d: &mut Driver<Line3d>, u: &[f64]| step_from(d, &slot, (t, h), u);
        step(&mut d, &inputs);
        let mut jacobian = vec![0.0; n_out * 6];
        d.step_jacobian(&mut jacobian).unwrap();
        let mut worst = 0.0f64;
        // The horizontal inputs: a vertical one changes friction through the
        // normal force, a derivative the symmetric band cannot hold.
        for j in [0, 1, 3, 4] {
            let (mut up, mut down) = (inputs, inputs);
            up[j] += 1e-6;
            down[j] -= 1e-6;
            let (plus, minus) = (step(&mut d, &up), step(&mut d, &down));
            let fd = |row: usize| (plus[row] - minus[row]) / 2e-6;
            // Each end's force rows on their own scale.
            for rows in [6..9, 15..18] {
                let scale = rows.clone().map(|r| fd(r).abs()).fold(0.0, f64::max);
                for row in rows {
                    let exact = jacobian[row * 6 + j];
                    let e = (fd(row) - exact).abs() / scale;
                    worst = worst.max(e);
                    assert!(
                        (fd(row) - exact).abs() <= tolerance * scale,
                        "{speed} m/s: output {row}, input {j}: {exact} against {} (scale {scale})",
                        fd(row)
                    );
                }
            }
        }
        assert!(worst > 0.0, "the ends' forces moved with the inputs");
    }
}

#[test]
fn a_repeated_step_starts_from_the_last_attempt_and_ends_where_a_cold_one_does() {
    // The master's Newton restores the line and steps it again with inputs
    // moved by its correction (`Unit::warm_repeat`): Newton starts from the
    // last attempt moved by the step's derivatives and needs fewer
    // iterations; the answer is the cold repeat's to Newton's tolerance.
    let drag = "drag_normal = 1.2\ncurrent = [{ depth = 0.0, speed = 0.5, heading_deg = 70.0 }]";
    for condition in ["velocity", "force"] {
        let (mut d, inputs) = coupled(condition, drag);
        let mut slot = crate::contract::DriverSlot::new();
        d.save(&mut slot).unwrap();
        let (t, h) = (Time::from_secs(2.0).unwrap(), Time::from_secs(0.1).unwrap());
        d.set_inputs(&inputs).unwrap();
        d.do_step(t, h).unwrap();
        let n_out = d.description().outputs.len();
        let mut jacobian = vec![0.0; n_out * inputs.len()];
        d.step_jacobian(&mut jacobian).unwrap();
        let moved: Vec<f64> = inputs.iter().map(|u| u + 1e-3 * u.abs().max(1.0)).collect();
        let mut repeat = |warm: bool| {
            if warm {
                d.restore_warm(&slot).unwrap();
            } else {
                d.restore(&slot).unwrap();
            }
            d.set_inputs(&moved).unwrap();
            let report = d.do_step(t, h).unwrap();
            let mut out = vec![0.0; n_out];
            d.outputs(&mut out).unwrap();
            (report.solver_iterations, out)
        };
        let (cold_iterations, cold) = repeat(false);
        let (warm_iterations, warm) = repeat(true);
        assert!(
            warm_iterations < cold_iterations,
            "{condition}: {warm_iterations} warm against {cold_iterations} cold"
        );
        for row in 0..18 {
            let scale = (0..18).map(|r| cold[r].abs()).fold(1.0, f64::max);
            assert!(
                (warm[row] - cold[row]).abs() <= 1e-6 * scale,
                "{condition}: output {row}: {} warm against {} cold",
                warm[row],
                cold[row]
            );
        }
    }
}

#[test]
fn a_corrected_step_is_the_step_taken_again_to_second_order() {
    // `Unit::correct_step` moves the last step to end inputs moved by a
    // change, by the step's derivatives: its outputs (end motion and forces,
    // tension, energies and the ledger's balance) differ from the step taken
    // again with the moved inputs by the change squared (the difference falls
    // 100-fold for a change 10 times smaller), and a linear line's not at all.
    let drag = "drag_normal = 1.2\ncurrent = [{ depth = 0.0, speed = 0.5, heading_deg = 70.0 }]";
    let linear_drag = format!("linear = true\n{drag}");
    for (condition, extra) in [
        ("velocity", drag),
        ("force", drag),
        ("velocity", linear_drag.as_str()),
        ("force", "linear = true"),
    ] {
        let (mut d, inputs) = coupled(condition, extra);
        let mut slot = crate::contract::DriverSlot::new();
        d.save(&mut slot).unwrap();
        let (t, h) = (Time::from_secs(2.0).unwrap(), Time::from_secs(0.1).unwrap());
        let n_out = d.description().outputs.len();
        let names: Vec<String> = (d.description().outputs.iter())
            .map(|p| p.name.clone())
            .collect();
        let mut gap = |size: f64| {
            let change: Vec<f64> = (inputs.iter().enumerate())
                .map(|(j, u)| size * u.abs().max(1.0) * [1.0, -0.7, 0.4][j % 3])
                .collect();
            let moved: Vec<f64> = inputs.iter().zip(&change).map(|(u, c)| u + c).collect();
            let again = step_from(&mut d, &slot, (t, h), &moved);
            step_from(&mut d, &slot, (t, h), &inputs);
            let mut jacobian = vec![0.0; n_out * inputs.len()];
            d.step_jacobian(&mut jacobian).unwrap();
            d.correct_step(&change).unwrap();
            let mut corrected = vec![0.0; n_out];
            d.outputs(&mut corrected).unwrap();
            let scale = |row: usize| again[row].abs().max(1.0);
            (0..n_out)
                // Not the solver's count, nor the extremes (a node's index).
                .filter(|&r| {
                    !(names[r].contains("touchdown")
                        || names[r].starts_with("largest")
                        || names[r].contains("iterations"))
                })
                .map(|r| ((corrected[r] - again[r]).abs() / scale(r), r))
                .fold((0.0f64, 0), |w, e| if e.0 > w.0 { e } else { w })
        };
        let (large, row) = gap(1e-2);
        let (small, _) = gap(1e-3);
        if extra.contains("linear") {
            assert!(
                large < 1e-9,
                "{condition} {extra}: {large:e} at {}",
                names[row]
            );
        } else {
            assert!(
                small < large / 30.0 && large < 1e-3,
                "{condition} {extra}: {large:e} then {small:e} at {}",
                names[row]
            );
        }
    }
}
