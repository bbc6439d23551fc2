//! The body against closed forms: free decay in each degree of freedom, a
//! free body spinning about a tilted axis (energy and angular momentum), a
//! free body with an offset centre of gravity (its momentum), the prescribed
//! motion's rates, the energy balance under damping and a fairlead's pull,
//! and the step Jacobian against differences of the step.

use super::*;
use crate::contract::Driver;
use nalgebra::Matrix3;

/// A body at rest in equilibrium (buoyancy = weight, centre of gravity at
/// the reference point) with principal inertia `inertia`.
pub(super) fn body_params(inertia: [f64; 3]) -> BodyParams {
    let mass: f64 = 2.0e5;
    toml::from_str::<BodyParams>(&format!(
        "mass = {mass}\ninertia = {inertia:?}\ndisplaced_volume = {}",
        mass / 1025.0
    ))
    .unwrap()
}

/// `x` seconds as a time.
pub(super) fn secs(x: f64) -> Time {
    Time::from_secs(x).unwrap()
}

/// The outputs of the body `driver` drives.
pub(super) fn outs(driver: &Driver<Body>) -> Vec<f64> {
    let mut out = vec![0.0; driver.description().outputs.len()];
    driver.outputs(&mut out).unwrap();
    out
}

/// One sine of amplitude `a` at `w` rad/s, phase 0.3 rad: a prescribed
/// motion's component.
fn phased_sine(a: f64, w: f64) -> Vec<crate::signal::sine::Sine> {
    vec![crate::signal::sine::Sine {
        amplitude: a,
        angular_frequency: w,
        phase: 0.3,
        decay: 0.0,
    }]
}

/// Runs `body` for `duration` (s) at step `h` with no inputs; the outputs
/// at every step.
fn run(params: BodyParams, h: f64, duration: f64) -> Vec<Vec<f64>> {
    let mut driver = Driver::new(Body::new(params).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    let steps = (duration / h).round() as usize;
    let mut out = vec![outs(&driver)];
    for k in 0..steps {
        driver.do_step(secs(k as f64 * h), secs(h)).unwrap();
        out.push(outs(&driver));
    }
    out
}

/// The largest error over `duration` of degree of freedom `dof` in free
/// decay from `x0` against the damped oscillator's closed form.
fn decay_error(dof: usize, x0: f64, h: f64) -> f64 {
    let mut p = body_params([3.0e7, 4.0e7, 5.0e7]);
    let (inertia, stiffness) = if dof < 3 {
        (p.mass, 8.0e5)
    } else {
        (p.inertia[dof - 3], 6.0e7 * (dof as f64))
    };
    let omega = (stiffness / inertia).sqrt();
    let zeta = 0.05;
    p.hydrostatic_stiffness[dof][dof] = stiffness;
    p.damping_linear[dof][dof] = 2.0 * zeta * omega * inertia;
    p.initial_offset[dof] = x0;
    let period = 2.0 * std::f64::consts::PI / omega;
    let duration = 3.0 * period;
    let outputs = run(p, h * period, duration);
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let exact = |t: f64| {
        x0 * (-zeta * omega * t).exp() * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin())
    };
    // Outputs 0-5: x, y, z (the reference at the origin), roll, pitch, yaw.
    outputs
        .iter()
        .enumerate()
        .map(|(k, o)| (o[dof] - exact(k as f64 * h * period)).abs() / x0)
        .fold(0.0, f64::max)
}

#[test]
fn free_decay_in_each_degree_of_freedom_matches_the_closed_form_to_second_order() {
    for dof in 0..6 {
        let x0 = if dof < 3 { 0.5 } else { 0.05 };
        let coarse = decay_error(dof, x0, 0.02);
        let fine = decay_error(dof, x0, 0.01);
        // The trapezoidal rule's period error is (omega h)^2 / 12: over three
        // periods at 50 steps a period, a phase of 0.025 rad.
        assert!(coarse < 0.03, "dof {dof}: {coarse:e}");
        let order = (coarse / fine).log2();
        eprintln!(
            "free decay, dof {dof}: {coarse:.3e} at T/50, {fine:.3e} at T/100 (order {order:.2})"
        );
        assert!(
            (1.8..2.2).contains(&order),
            "dof {dof}: {coarse:e} -> {fine:e}"
        );
    }
}

/// The spinning body's energy and angular momentum (global) drift over
/// 20 s at step `h`, relative.
fn spin_drift(h: f64) -> (f64, f64) {
    let mut p = body_params([2.0e6, 3.0e6, 5.0e6]);
    p.gravity = 0.0;
    p.initial_offset = [0.0, 0.0, 0.0, 0.3, -0.2, 0.1];
    p.initial_velocity = [0.0, 0.0, 0.0, 0.4, 0.1, 1.2];
    let inertia = dynamics::inertia_tensor(&p);
    let mut driver = Driver::new(Body::new(p).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    let momentum = |b: &Body| {
        let k = b.kinematics();
        let r = k.motion.rotation.to_rotation_matrix();
        let w = Vector3::new(
            k.motion.velocity[3],
            k.motion.velocity[4],
            k.motion.velocity[5],
        );
        let global: Matrix3<f64> = r.matrix() * inertia * r.matrix().transpose();
        global * w
    };
    let (e0, l0) = (outs(&driver)[POSE_KINETIC], momentum(driver.unit()));
    let steps = (20.0 / h).round() as usize;
    let (mut de, mut dl) = (0.0_f64, 0.0_f64);
    for k in 0..steps {
        driver.do_step(secs(k as f64 * h), secs(h)).unwrap();
        de = de.max((outs(&driver)[POSE_KINETIC] - e0).abs() / e0);
        dl = dl.max((momentum(driver.unit()) - l0).norm() / l0.norm());
    }
    (de, dl)
}

/// The kinetic energy's output without fairleads.
const POSE_KINETIC: usize = 12;

#[test]
fn a_body_spinning_about_a_tilted_axis_keeps_its_energy_and_momentum_to_second_order() {
    let (e1, l1) = spin_drift(0.02);
    let (e2, l2) = spin_drift(0.01);
    eprintln!(
        "spinning body over 20 s: energy {e1:.2e} / {e2:.2e}, momentum {l1:.2e} / {l2:.2e} at 0.02 / 0.01 s"
    );
    assert!(e1 < 1e-3 && l1 < 1e-3, "{e1:e} {l1:e}");
    assert!((e1 / e2).log2() > 1.8, "energy {e1:e} -> {e2:e}");
    assert!((l1 / l2).log2() > 1.8, "momentum {l1:e} -> {l2:e}");
}

#[test]
fn a_free_body_with_its_centre_of_gravity_off_the_reference_keeps_its_momentum() {
    let mut p = body_params([2.0e6, 3.0e6, 5.0e6]);
    p.gravity = 0.0;
    p.centre_of_gravity = [1.0, -2.0, -5.0];
    p.initial_velocity = [0.3, 0.0, 0.1, 0.2, 0.5, 0.8];
    let cg = Vector3::from(p.centre_of_gravity);
    let mut driver = Driver::new(Body::new(p).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    let cg_velocity = |b: &Body| {
        let m = b.kinematics().motion;
        let w = Vector3::new(m.velocity[3], m.velocity[4], m.velocity[5]);
        Vector3::new(m.velocity[0], m.velocity[1], m.velocity[2]) + w.cross(&(m.rotation * cg))
    };
    let v0 = cg_velocity(driver.unit());
    for k in 0..500 {
        driver.do_step(secs(k as f64 * 0.01), secs(0.01)).unwrap();
    }
    let drift = (cg_velocity(driver.unit()) - v0).norm() / v0.norm();
    eprintln!("offset centre of gravity: momentum drift {drift:.2e} over 5 s");
    assert!(drift < 1e-3, "{drift:e}");
}

#[test]
fn a_prescribed_motion_s_fairlead_velocity_and_acceleration_are_its_position_s_rates() {
    let mut p = body_params([2.0e6, 3.0e6, 5.0e6]);
    p.motion = Some([
        phased_sine(2.0, 0.5),
        phased_sine(1.0, 0.3),
        phased_sine(0.5, 0.7),
        phased_sine(0.05, 0.4),
        phased_sine(0.08, 0.6),
        phased_sine(0.2, 0.2),
    ]);
    p.fairleads = vec![Fairlead {
        name: "f".into(),
        position: [5.0, -3.0, -70.0],
    }];
    let body = Body::new(p).unwrap();
    let at = |t: f64| {
        let k = body.prescribed(t);
        body.model
            .point(&k.motion, &k.acceleration, &body.model.fairleads[0])
    };
    let d = 1e-5;
    for t in [1.0, 7.3] {
        let [_, v, a] = at(t);
        let ([xp, vp, _], [xm, vm, _]) = (at(t + d), at(t - d));
        assert!(((xp - xm) / (2.0 * d) - v).norm() < 1e-7 * v.norm(), "{t}");
        assert!(((vp - vm) / (2.0 * d) - a).norm() < 1e-6 * a.norm(), "{t}");
    }
}

#[test]
fn the_energy_balance_closes_under_damping_and_a_fairlead_s_pull() {
    let mut p = body_params([3.0e7, 4.0e7, 5.0e7]);
    p.centre_of_gravity = [0.0, 0.0, -10.0];
    for i in 0..6 {
        p.hydrostatic_stiffness[i][i] = [2e5, 2e5, 8e5, 5e8, 5e8, 1e8][i];
        p.damping_linear[i][i] = [1e5, 1e5, 1e5, 1e7, 1e7, 1e7][i];
        p.damping_quadratic[i][i] = 1e5;
    }
    p.fairleads = vec![Fairlead {
        name: "f".into(),
        position: [5.0, 0.0, -20.0],
    }];
    let n_out = Body::new(p.clone()).unwrap().description.outputs.len();
    let mut driver = Driver::new(Body::new(p).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    let h = 0.05;
    let mut largest_work = 0.0_f64;
    for k in 0..2000 {
        let t = k as f64 * h;
        let pull = 2e5 * (0.3 * t).sin();
        driver
            .set_inputs(&[pull, 0.5 * pull, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
            .unwrap();
        driver.do_step(secs(t), secs(h)).unwrap();
        largest_work = largest_work.max(outs(&driver)[n_out - 3].abs());
    }
    let error = outs(&driver)[n_out - 2].abs();
    eprintln!("energy balance over 100 s: error {error:.2e} J of {largest_work:.2e} J of work");
    assert!(largest_work > 1e4, "{largest_work}");
    assert!(error < 1e-3 * largest_work, "{error:e} of {largest_work:e}");
}

#[test]
fn the_step_jacobian_matches_differences_of_the_step() {
    let mut p = body_params([3.0e7, 4.0e7, 5.0e7]);
    p.centre_of_gravity = [0.5, 0.0, -10.0];
    p.initial_velocity = [0.1, 0.0, 0.0, 0.01, 0.02, 0.0];
    p.damping_quadratic[0][0] = 1e5;
    p.fairleads = vec![Fairlead {
        name: "f".into(),
        position: [5.0, 0.0, -20.0],
    }];
    let inputs = [1e5, -2e4, 3e4, 0.0, 0.0, 1e3, 0.0, 0.0, 0.0];
    let mut body = Body::new(p).unwrap();
    let n_in = inputs.len();
    let n_out = body.description.outputs.len();
    let holds = vec![crate::contract::Hold::Ramp; n_in];
    let view = Inputs::new(&holds, &inputs, &inputs);
    body.initialize(Time::ZERO, view).unwrap();
    let mut slot = crate::contract::StateSlot::new();
    body.save_state(&mut slot).unwrap();
    body.do_step(Time::ZERO, secs(0.1), view).unwrap();
    let mut jacobian = vec![0.0; n_out * n_in];
    body.step_jacobian(view, &mut jacobian).unwrap();
    let mut out = [vec![0.0; n_out], vec![0.0; n_out]];
    for j in 0..n_in {
        let delta = 10.0;
        for (s, sign) in [1.0, -1.0].iter().enumerate() {
            let mut end = inputs;
            end[j] += sign * delta;
            body.restore_state(&slot).unwrap();
            let moved = Inputs::new(&holds, &inputs, &end);
            body.do_step(Time::ZERO, secs(0.1), moved).unwrap();
            body.outputs(moved, &mut out[s]);
        }
        for i in 0..n_out - 5 {
            let fd = (out[0][i] - out[1][i]) / (2.0 * delta);
            let scale = jacobian[i * n_in..(i + 1) * n_in]
                .iter()
                .fold(1e-12, |m: f64, x| m.max(x.abs()));
            let d = jacobian[i * n_in + j];
            assert!(
                (d - fd).abs() < 1e-5 * scale,
                "d out {i} / d in {j}: {d:e} vs {fd:e}"
            );
        }
    }
}

#[test]
fn bad_parameters_are_refused_by_key() {
    let mut p = body_params([1.0, 1.0, 5.0]);
    p.inertia_products = [0.0, 0.0, 0.0];
    let e = Body::new(p.clone()).err().map(|e| e.to_string());
    assert!(e.is_none(), "{e:?}");
    p.inertia = [1.0, 1.0, 3.0];
    p.inertia_products = [2.0, 0.0, 0.0];
    let e = Body::new(p.clone()).err().unwrap().to_string();
    assert!(e.contains("inertia_products"), "{e}");
    let mut q = body_params([1.0, 1.0, 1.0]);
    q.added_mass[0][4] = 3.0;
    let e = Body::new(q).err().unwrap().to_string();
    assert!(
        e.contains("added_mass[0][4]") && e.contains("symmetric"),
        "{e}"
    );
    let mut r = body_params([1.0, 1.0, 1.0]);
    r.fairleads = vec![
        Fairlead {
            name: "a".into(),
            position: [0.0; 3],
        },
        Fairlead {
            name: "a".into(),
            position: [1.0; 3],
        },
    ];
    let e = Body::new(r).err().unwrap().to_string();
    assert!(e.contains("fairleads[1].name"), "{e}");
}

/// A motion table sampled from sines every 0.1 s moves the fairlead as the
/// sines do (away from the natural spline's ends), and a run past its last
/// time stops with an error that says so.
#[test]
fn a_motion_table_follows_the_motion_it_samples() {
    let mut by_sines = body_params([3.0e7, 4.0e7, 5.0e7]);
    by_sines.motion = Some([
        phased_sine(2.0, 0.5),
        vec![],
        phased_sine(0.5, 0.7),
        vec![],
        phased_sine(0.08, 0.6),
        phased_sine(0.2, 0.2),
    ]);
    by_sines.fairleads = vec![Fairlead {
        name: "f".into(),
        position: [5.0, -3.0, -70.0],
    }];
    let time: Vec<f64> = (0..=300).map(|i| 0.1 * i as f64).collect();
    let column = |dof: usize| {
        let m = by_sines.motion.as_ref().unwrap();
        let s = time.iter().map(|&t| faded_sum(0.0, &m[dof], 0.0, t)[0]);
        Some(s.collect::<Vec<f64>>())
    };
    let table = motion_table::MotionTable {
        time: time.clone(),
        surge: column(0),
        sway: None,
        heave: column(2),
        roll: None,
        pitch: column(4),
        yaw: column(5),
    };
    let mut by_table = by_sines.clone();
    by_table.motion = None;
    by_table.motion_table = Some(table);
    let (a, b) = (Body::new(by_sines).unwrap(), Body::new(by_table).unwrap());
    let fairlead = |body: &Body, t: f64| {
        let k = body.prescribed(t);
        body.model
            .point(&k.motion, &k.acceleration, &body.model.fairleads[0])
    };
    for t in [5.03, 12.71, 20.0, 24.96] {
        let (want, got) = (fairlead(&a, t), fairlead(&b, t));
        for (d, tolerance) in [(0, 1e-8), (1, 1e-5), (2, 1e-3)] {
            let error = (got[d] - want[d]).norm() / want[d].norm();
            assert!(error < tolerance, "t {t}, derivative {d}: {error:.2e}");
        }
    }
    let mut driver = Driver::new(b);
    driver.initialize(secs(29.5)).unwrap();
    driver.do_step(secs(29.5), secs(0.5)).unwrap();
    let late = driver.do_step(secs(30.0), secs(0.5)).unwrap_err();
    assert!(late.to_string().contains("covers 0 s to 30"), "{late}");
}
