//! The beam unit (seed 004): cantilever eigenfrequencies and free vibration against
//! the analytical solution, static distributed load against eq. 6.2, and the
//! static contact reference problem (eq. 4.41) for each contact method.

use slender_tests::published;
use slender_units::Driver;
use slender_units::Time;
use slender_units::beam::boundary::{Boundary, Condition, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams, ContactIntegration, ContactParams};
use slender_units::contact::surface::{Motion, Shape, Surface};
use slender_units::contact::{LambdaUpdate, Law};

fn cond(quantity: Quantity, value: f64) -> Condition {
    Condition {
        quantity,
        value: TimeFunction::Constant(value),
    }
}

fn params(elements: usize, boundary: Boundary) -> BeamParams {
    let mut p = BeamParams::new(10.0, elements, 1e4, 10.0, boundary);
    p.newton_tolerance = 1e-10;
    p
}

fn cantilever() -> Boundary {
    Boundary {
        left: [
            cond(Quantity::Deflection, 0.0),
            cond(Quantity::Rotation, 0.0),
        ],
        right: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
    }
}

fn floats(v: &toml::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_float().unwrap())
        .collect()
}

#[test]
fn cantilever_frequencies_match_the_analytical_values_to_the_printed_digits() {
    let reference = floats(&published()["cantilever"]["omega_rad_s"]);
    let mut beam = Driver::new(Beam::new(params(8, cantilever())).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    let modes = beam.modes(4).unwrap().modes;
    for (m, w) in modes.iter().zip(&reference) {
        let omega = 2.0 * std::f64::consts::PI / m.period;
        eprintln!("omega {omega:.6} rad/s, published {w}");
        // Printed to 6 significant digits: within half a unit of the sixth digit.
        let unit = 10f64.powi(w.abs().log10().floor() as i32 - 5);
        assert!((omega - w).abs() <= 0.5 * unit, "{omega} vs {w}");
    }
}

/// Cantilever mode shape n (seed 004 eq. 6.4) at x. The printed B has the wrong
/// sign: only B = -(sin + sinh) / (cos + cosh) satisfies the free-end conditions,
/// and only with it do the printed F_n reproduce v0 = (x/L)^2 (0.992 at the tip
/// with four modes).
fn mode_shape(nu: f64, l: f64, x: f64) -> f64 {
    let b = -((nu * l).sin() + (nu * l).sinh()) / ((nu * l).cos() + (nu * l).cosh());
    ((nu * x).sin() - (nu * x).sinh()) + b * ((nu * x).cos() - (nu * x).cosh())
}

#[test]
fn free_vibration_from_a_quadratic_velocity_follows_the_modal_solution() {
    let table = published();
    let c = &table["cantilever"];
    let (nu_l, omega, f) = (
        floats(&c["nu_L"]),
        floats(&c["omega_rad_s"]),
        floats(&c["modal_F"]),
    );
    let mut p = params(8, cantilever());
    p.initial_velocity = vec![0.0, 0.0, 1.0 / 100.0]; // v0 = (x / L)^2
    let mut beam = Driver::new(Beam::new(p).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.025).unwrap();
    let (mut worst, mut peak) = (0.0f64, 0.0f64);
    for k in 0..400 {
        beam.do_step(h * k, h).unwrap();
        let t = (k + 1) as f64 * 0.025;
        let exact: f64 = (0..4)
            .map(|n| f[n] * (omega[n] * t).sin() * mode_shape(nu_l[n] / 10.0, 10.0, 10.0))
            .sum();
        let y = beam.deflection_at(10.0);
        worst = worst.max((y - exact).abs());
        peak = peak.max(exact.abs());
    }
    eprintln!(
        "tip deflection over 10 s: largest difference to the 4-mode solution {worst:.3e} m (peak {peak:.3e} m)"
    );
    assert!(worst < 0.01 * peak, "{worst} vs peak {peak}");
}

#[test]
fn static_distributed_load_matches_the_exact_solution() {
    let (y0, th0, gamma, ei, l): (f64, f64, f64, f64, f64) = (1.0, -0.5, 0.05, 1e4, 10.0);
    let mut p = params(
        25,
        Boundary {
            left: [
                cond(Quantity::Deflection, y0),
                cond(Quantity::Rotation, th0),
            ],
            right: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
        },
    );
    p.distributed_load = vec![0.0, 0.0, 0.0, gamma];
    p.static_start = true;
    let mut beam = Driver::new(Beam::new(p).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    let exact = |x: f64| {
        gamma * x * x * (84.0 * l.powi(5) - 35.0 * l.powi(4) * x + x.powi(5)) / (840.0 * ei)
            + th0 * x
            + y0
    };
    let mut worst = 0.0f64;
    for (x, q) in beam.node_positions().iter().zip(beam.deflections()) {
        worst = worst.max((q[0] - exact(*x)).abs());
    }
    eprintln!("static w = gamma x^3: largest nodal error {worst:.3e} m");
    // Nodal values of Hermite elements are exact for an exactly integrated load;
    // two Gauss points integrate x^3 times a cubic (degree 6) only approximately,
    // which leaves ~3e-7 m on a tip deflection of 2.98 m (source: "almost perfectly").
    assert!(worst < 1e-6);
}

/// The static contact reference problem's parameters (seed 004 eq. 6.10).
fn contact_params(elements: usize, method: Law) -> BeamParams {
    let mut p = params(
        elements,
        Boundary {
            left: [
                cond(Quantity::Deflection, 1.0),
                cond(Quantity::Rotation, -0.5),
            ],
            right: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
        },
    );
    // The surface y >= 0 holds the beam from below; a small uniform load keeps the
    // free part on it without changing the shape before touchdown much.
    p.contact = Some(ContactParams {
        method,
        surface: Surface {
            shape: Shape::Flat { height: 0.0 },
            motion: Motion::None,
        },
        integration: ContactIntegration::Gauss,
        damping: 0.0,
        gap_band: 0.0,
    });
    p.static_start = true;
    p.newton_tolerance = 1e-9;
    p
}

fn contact_problem(elements: usize, method: Law) -> Driver<Beam> {
    Driver::new(Beam::new(contact_params(elements, method)).unwrap())
}

/// Reference distance (eq. 4.42) to y_ref and the largest penetration.
fn reference_distance(beam: &Beam) -> (f64, f64) {
    let yref = |x: f64| {
        if x < 6.0 {
            -0.5f64.powi(3) * x.powi(3) / 27.0 + 0.25 * x * x / 3.0 - 0.5 * x + 1.0
        } else {
            0.0
        }
    };
    let n = 2000;
    let (mut sum, mut pen) = (0.0, 0.0f64);
    for i in 0..n {
        let x = (i as f64 + 0.5) * 10.0 / n as f64;
        let y = beam.deflection_at(x);
        sum += (y - yref(x)).powi(2) * 10.0 / n as f64;
        pen = pen.max(-y);
    }
    (sum.sqrt(), pen)
}

#[test]
fn static_contact_converges_to_the_reference_solution_as_the_penalty_grows() {
    // Penalty and energy-conserving (the same functional in statics): the reference
    // distance falls as p grows, for 8 and 25 elements.
    let mut at_1e3 = f64::NAN;
    for (name, make) in [
        (
            "penalty",
            (|p| Law::Penalty { penalty: p }) as fn(f64) -> Law,
        ),
        ("energy-conserving", |p| Law::EnergyConserving {
            penalty: p,
        }),
    ] {
        for elements in [8, 25] {
            let mut previous = f64::INFINITY;
            for p in [1e2, 1e3, 1e4, 1e5] {
                let mut beam = contact_problem(elements, make(p));
                beam.initialize(Time::ZERO).unwrap();
                let (distance, penetration) = reference_distance(&beam);
                eprintln!(
                    "{name:<20} {elements:>2} el, p = {p:.0e}: reference distance {distance:.3e}, penetration {penetration:.3e} m, {} Newton iterations",
                    beam.last_newton_iterations()
                );
                assert!(
                    distance < previous,
                    "{name} {elements} el p {p}: {distance} not below {previous}"
                );
                previous = distance;
                if elements == 25 && p == 1e3 {
                    at_1e3 = distance;
                }
            }
            assert!(previous < 0.01, "{name} {elements} el: distance {previous}");
        }
    }
    assert!(at_1e3 > 0.1);
}

#[test]
#[ignore = "known gap (issue 4): at a fixed p = 1e4 (and with p0 = 1e2, psi = 2.5 up to p = 1e4) the static augmented-Lagrangian lambda update contracts by only ~2 % per iteration and misses the 1e-9 step tolerance in 600 iterations (distance already 4.1e-4); up to p = 1e5 it converges in 474"]
fn static_augmented_lagrangian_enforces_the_contact_at_finite_penalty() {
    // The augmented Lagrangian enforces the contact exactly at a finite p once lambda
    // has converged.
    for p in [1e4, 1e5] {
        let mut beam = contact_problem(
            25,
            Law::AugmentedLagrangian {
                penalty: p,
                lambda0: 0.0,
                eta: 0.0,
                update: LambdaUpdate::NewtonIteration,
            },
        );
        beam.initialize(Time::ZERO).unwrap();
        let (distance, penetration) = reference_distance(&beam);
        eprintln!(
            "augmented Lagrangian 25 el, p = {p:.0e}: reference distance {distance:.3e}, penetration {penetration:.3e} m"
        );
        assert!(penetration < 1e-6, "penetration {penetration}");
        assert!(distance < 5e-3, "distance {distance}");
    }
}

/// A 1 kg "ball": a short, very stiff beam with free ends, falling flat from 10 m
/// under g = 10 onto y >= 0 (seed 004 eqs. 6.13-6.15). Returns the total energy
/// (kinetic + strain + contact + gravity) at each step, and the Newton iterations.
fn bouncing(method: Law, seconds: f64, tau: f64, alpha: f64) -> (Vec<f64>, Vec<u32>) {
    let free = Boundary {
        left: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
        right: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
    };
    let mut p = params(1, free);
    p.length = 1.0;
    p.mass_per_length = 1.0;
    p.flexural_rigidity = 1e6;
    p.distributed_load = vec![-10.0];
    p.initial_deflection = vec![10.0];
    p.contact = Some(ContactParams {
        method,
        surface: Surface {
            shape: Shape::Flat { height: 0.0 },
            motion: Motion::None,
        },
        integration: ContactIntegration::Gauss,
        damping: 0.0,
        gap_band: 0.0,
    });
    p.newton_tolerance = 1e-12;
    p.alpha = alpha;
    let mut beam = Driver::new(Beam::new(p).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(tau).unwrap();
    let steps = (seconds / tau).round() as i64;
    let mut energy = Vec::new();
    let mut newton = Vec::new();
    for k in 0..steps {
        beam.do_step(h * k, h).unwrap();
        newton.push(beam.last_newton_iterations());
        let [kin, strain, contact] = beam.energies();
        let q = beam.deflections();
        // Gravity: -w int y dx = 10 * mean deflection (1 m, 1 kg/m).
        let gravity = 10.0 * 0.5 * (q[0][0] + q[1][0]);
        energy.push(kin + strain + contact + gravity);
    }
    (energy, newton)
}

#[test]
fn bouncing_ball_energy_per_contact_method() {
    let e0 = 100.0; // m g h = 1 * 10 * 10
    let cases: Vec<(&str, Law)> = vec![
        ("penalty", Law::Penalty { penalty: 1e6 }),
        ("energy-conserving", Law::EnergyConserving { penalty: 1e6 }),
        (
            "augmented Lagrangian",
            Law::AugmentedLagrangian {
                penalty: 1e6,
                lambda0: 0.0,
                eta: 0.0,
                update: LambdaUpdate::TimeStep,
            },
        ),
        (
            "augmented barrier",
            Law::AugmentedBarrier {
                penalty: 1e6,
                lambda0: 1.0,
                s: 1.0,
                beta: 0.5,
                eta: 0.0,
                update: LambdaUpdate::TimeStep,
            },
        ),
    ];
    let mut drift = Vec::new();
    for (name, law) in cases {
        let (energy, newton) = bouncing(law, 5.0, 0.001, 0.0);
        let last = *energy.last().unwrap();
        let max = energy.iter().copied().fold(f64::MIN, f64::max);
        eprintln!(
            "{name:<22} energy after 5 s: {last:.4} J (start {e0} J), largest {max:.4} J, max Newton iterations {}",
            newton.iter().max().unwrap()
        );
        drift.push((name, (max - e0) / e0, (last - e0) / e0));
    }
    // Penalty keeps the energy within a few percent over two bounces; the
    // energy-conserving law keeps it to round-off; the augmented methods add energy.
    assert!(drift[0].1 < 0.1, "penalty {:?}", drift[0]);
    assert!(
        drift[1].1.abs() < 1e-8 && drift[1].2.abs() < 1e-8,
        "energy-conserving {:?}",
        drift[1]
    );
    assert!(drift[2].2 > 0.5, "augmented Lagrangian {:?}", drift[2]);
    assert!(drift[3].2 > 0.5, "augmented barrier {:?}", drift[3]);
}

#[test]
fn repeated_impacts_for_100_s_stay_bounded() {
    // The energy-conserving law holds the energy at p = 1e8 and 1 ms steps, where
    // the contact (omega tau = sqrt(p / m) tau = 10) is far shorter than a step.
    let (energy, newton) = bouncing(Law::EnergyConserving { penalty: 1e8 }, 100.0, 0.001, 0.0);
    let worst = energy
        .iter()
        .map(|e| (e - 100.0).abs() / 100.0)
        .fold(0.0, f64::max);
    eprintln!(
        "energy-conserving, p = 1e8, 100 s: largest relative energy change {worst:.3e}, max Newton iterations {}",
        newton.iter().max().unwrap()
    );
    assert!(worst < 1e-7, "{worst}");
    // Plain penalty drifts bounce after bounce (a few percent per bounce at
    // p = 1e6, 1 ms): finite, reported, not conserved.
    let (energy, _) = bouncing(Law::Penalty { penalty: 1e6 }, 100.0, 0.001, 0.0);
    let worst = energy
        .iter()
        .map(|e| (e - 100.0).abs() / 100.0)
        .fold(0.0, f64::max);
    eprintln!("penalty, p = 1e6, 100 s: largest relative energy change {worst:.3e}");
    assert!(energy.iter().all(|e| e.is_finite()));
    // Under-resolved (p = 1e8, 1 ms) the penalty stays finite but gains energy,
    // even with alpha = 0.05: the reason for the energy-conserving law.
    let (energy, _) = bouncing(Law::Penalty { penalty: 1e8 }, 100.0, 0.001, 0.05);
    let gain = energy.last().unwrap() / 100.0;
    eprintln!("penalty, p = 1e8, alpha = 0.05, 100 s: energy x{gain:.1}");
    assert!(energy.iter().all(|e| e.is_finite()));
}

/// Seed 004 sec. 6.2.2: y(t,0) = 1, y'(t,0) = -1/2, free end, starting from the
/// reference shape at rest (eq. 6.11); 12 elements, tau = 0.1 s, alpha = 0.01,
/// Newton step tolerance 1e-5 with at most 10 iterations.
fn reference_start(law: Law, seconds: f64) -> (Driver<Beam>, Vec<u32>, f64) {
    let mut p = contact_params(12, law);
    p.static_start = false;
    p.alpha = 0.01;
    p.newton_tolerance = 1e-5;
    p.newton_max_iterations = 10;
    let mut beam = Driver::new(Beam::new(p).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    beam.set_initial_shape(|x| {
        if x < 6.0 {
            (
                -0.125 * x.powi(3) / 27.0 + 0.25 * x * x / 3.0 - 0.5 * x + 1.0,
                -0.125 * x * x / 9.0 + 0.5 * x / 3.0 - 0.5,
            )
        } else {
            (0.0, 0.0)
        }
    })
    .unwrap();
    let h = Time::from_secs(0.1).unwrap();
    let mut newton = Vec::new();
    let mut worst = 0.0f64;
    for k in 0..(seconds / 0.1).round() as i64 {
        beam.do_step(h * k, h).unwrap();
        newton.push(beam.last_newton_iterations());
        worst = worst.max(reference_distance(&beam).0);
    }
    (beam, newton, worst)
}

fn newton_counts(p: f64) -> (u32, f64, f64) {
    let (_, newton, worst) = reference_start(Law::Penalty { penalty: p }, 6.0);
    let max = *newton.iter().max().unwrap();
    let mean = newton.iter().sum::<u32>() as f64 / newton.len() as f64;
    eprintln!(
        "penalty p = {p:.0e}: Newton iterations max {max}, mean {mean:.2}; largest distance to y_ref over 6 s {worst:.3e}"
    );
    (max, mean, worst)
}

#[test]
fn dynamic_contact_from_the_reference_shape_with_penalty() {
    let (max_low, _, far) = newton_counts(1e2);
    let (max_high, mean_high, near) = newton_counts(1e4);
    assert!(max_low <= 3, "p = 1e2: {max_low} Newton iterations");
    // Never near the cap of 10 that the source treats as failure.
    assert!(
        max_high <= 6 && mean_high < 3.5,
        "p = 1e4: max {max_high}, mean {mean_high}"
    );
    // p = 1e4 stays much closer to the reference shape than p = 1e2.
    assert!(near < 0.2 * far, "{near} vs {far}");
}

#[test]
#[ignore = "known gap (issue 4): the source needs at most 3 Newton steps per step at p = 1e4 too; here the maximum is 5 (mean 3.23). Likely cause: contact forces are alpha-weighted here, while the source evaluates contact at the alpha-weighted state (eq. 4.31)"]
fn dynamic_contact_at_p_1e4_needs_at_most_three_newton_steps() {
    assert!(newton_counts(1e4).0 <= 3);
}

/// Seed 004 eq. 6.12: y(t,0) = 1 + 0.25 sin(0.3 t), y'(t,0) = -0.5, free end,
/// penalty 1e4, 20 elements, tau = 0.2 s, 15 s. Returns the tip deflection series
/// and the largest energy.
fn moving_support(alpha: f64) -> (Vec<f64>, f64) {
    let mut p = contact_params(20, Law::Penalty { penalty: 1e4 });
    p.boundary.left[0] = Condition {
        quantity: Quantity::Deflection,
        value: TimeFunction::Expression(slender_units::beam::boundary::Expression {
            offset: 1.0,
            amplitude: 0.25,
            angular_frequency: 0.3,
            ..Default::default()
        }),
    };
    p.static_start = true;
    p.alpha = alpha;
    p.newton_tolerance = 1e-8;
    let mut beam = Driver::new(Beam::new(p).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.2).unwrap();
    let (mut tip, mut energy) = (Vec::new(), 0.0f64);
    for k in 0..75 {
        beam.do_step(h * k, h).unwrap();
        tip.push(beam.deflection_at(10.0));
        energy = energy.max(beam.energies().iter().sum());
    }
    (tip, energy)
}

#[test]
fn large_steps_with_a_moving_support_stay_bounded_and_alpha_damps_the_high_frequencies() {
    let roughness = |s: &[f64]| {
        s.windows(3)
            .map(|w| (w[2] - 2.0 * w[1] + w[0]).powi(2))
            .sum::<f64>()
    };
    let (tip0, e0) = moving_support(0.0);
    let (tip5, e5) = moving_support(0.05);
    let (r0, r5) = (roughness(&tip0), roughness(&tip5));
    eprintln!(
        "tau = 0.2 s, 15 s: alpha = 0: largest energy {e0:.3} J, tip roughness {r0:.3e}; alpha = 0.05: {e5:.3} J, {r5:.3e}"
    );
    assert!(tip0.iter().chain(&tip5).all(|v| v.is_finite()));
    assert!(e0.is_finite() && e5.is_finite() && e5 < 1e6);
    assert!(
        r5 < r0,
        "alpha = 0.05 should damp the step-to-step oscillation: {r5} vs {r0}"
    );
}

#[test]
fn penalty_up_to_1e8_with_the_source_time_step_runs_or_reports_why_not() {
    // The source accepts a step after 10 Newton iterations; slender stops instead and
    // says where and how Newton stalled. Either way nothing blows up silently.
    for p in [1e6, 1e8] {
        let mut params = contact_params(12, Law::Penalty { penalty: p });
        params.static_start = false;
        params.alpha = 0.01;
        params.newton_tolerance = 1e-5;
        params.newton_max_iterations = 30;
        let mut beam = Driver::new(Beam::new(params).unwrap());
        beam.initialize(Time::ZERO).unwrap();
        let h = Time::from_secs(0.1).unwrap();
        let mut outcome = Ok(());
        for k in 0..60 {
            if let Err(e) = beam.do_step(h * k, h) {
                outcome = Err(e.to_string());
                break;
            }
            assert!(beam.energies().iter().all(|e| e.is_finite()));
        }
        eprintln!(
            "penalty {p:.0e}, tau = 0.1 s, 6 s: {:?}",
            outcome.as_ref().map(|_| "ran to the end")
        );
        if let Err(e) = outcome {
            assert!(
                e.contains("did not converge") && e.contains("t = ") && e.contains("corrections"),
                "{e}"
            );
        }
    }
}

#[test]
fn a_newton_failure_names_the_time_and_the_corrections() {
    let mut p = contact_params(12, Law::Penalty { penalty: 1e4 });
    p.static_start = false;
    p.newton_max_iterations = 1;
    p.newton_tolerance = 1e-14;
    let mut beam = Driver::new(Beam::new(p).unwrap());
    beam.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.1).unwrap();
    let err = beam.do_step(Time::ZERO, h).unwrap_err().to_string();
    assert!(
        err.contains("t = 0.1 s") && err.contains("corrections per iteration"),
        "{err}"
    );
}

#[test]
fn bad_beam_input_is_refused() {
    let base = || params(8, cantilever());
    let e = |p: BeamParams| {
        Beam::new(p)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let mut p = base();
    p.boundary.left = [cond(Quantity::Deflection, 0.0), cond(Quantity::Shear, 0.0)];
    assert!(e(p).contains("degenerate"), "degenerate pair accepted");
    let mut p = base();
    p.boundary.right = [cond(Quantity::Rotation, 0.0), cond(Quantity::Moment, 0.0)];
    assert!(e(p).contains("degenerate"));
    let mut p = base();
    p.flexural_rigidity = 0.0;
    assert!(e(p).contains("flexural_rigidity"));
    let mut p = base();
    p.mass_per_length = -1.0;
    assert!(e(p).contains("mass_per_length"));
    let mut p = base();
    p.alpha = 0.4;
    assert!(e(p).contains("alpha"));
    // A free-free beam has no static equilibrium.
    let mut p = base();
    p.boundary.left = [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)];
    p.static_start = true;
    let mut beam = Driver::new(Beam::new(p).unwrap());
    let err = beam.initialize(Time::ZERO).unwrap_err().to_string();
    assert!(err.contains("rigid-body mode"), "{err}");
    // Starting 0.5 m into the seabed.
    let mut p = contact_params(12, Law::Penalty { penalty: 1e4 });
    p.static_start = false;
    p.initial_deflection = vec![1.0, -0.5];
    let mut beam = Driver::new(Beam::new(p).unwrap());
    let err = beam.initialize(Time::ZERO).unwrap_err().to_string();
    assert!(err.contains("penetrates the contact surface"), "{err}");
}

#[test]
fn the_touchdown_estimate_matches_the_fe_contact_point() {
    use slender_units::beam::touchdown::TouchdownEstimate;
    // Static reference: y0 = 1, y0' = -0.5 touches down at 6 m.
    assert_eq!(TouchdownEstimate::estimate(1.0, -0.5), (6.0, true));
    assert!(!TouchdownEstimate::estimate(1.0, 0.1).1);
    // Against the FE static solution at p = 1e5 (25 elements): where the
    // deflection first falls below 1 mm.
    let mut beam = contact_problem(25, Law::Penalty { penalty: 1e5 });
    beam.initialize(Time::ZERO).unwrap();
    let mut out = vec![0.0; beam.description().outputs.len()];
    beam.outputs(&mut out).unwrap();
    let fe = out[11]; // contact_start: first integration point in contact
    eprintln!("touchdown: estimate 6.000 m, FE contact start (p = 1e5, 25 el) {fe:.3} m");
    assert!((fe - 6.0).abs() < 1.0, "{fe}");
}

#[test]
fn on_the_beam_the_energy_conserving_law_keeps_the_energy_and_the_augmented_lagrangian_adds_some() {
    // The dynamic reference-start problem with alpha = 0 and no damping: total
    // energy (kinetic + strain + contact) should stay at its initial value.
    let run = |law: Law| {
        let mut p = contact_params(12, law);
        p.static_start = false;
        p.alpha = 0.0;
        p.newton_tolerance = 1e-10;
        let mut beam = Driver::new(Beam::new(p).unwrap());
        beam.initialize(Time::ZERO).unwrap();
        beam.set_initial_shape(|x| {
            if x < 6.0 {
                (
                    -0.125 * x.powi(3) / 27.0 + 0.25 * x * x / 3.0 - 0.5 * x + 1.0,
                    -0.125 * x * x / 9.0 + 0.5 * x / 3.0 - 0.5,
                )
            } else {
                (0.0, 0.0)
            }
        })
        .unwrap();
        let e0: f64 = beam.energies().iter().sum();
        let h = Time::from_secs(0.01).unwrap();
        let mut worst = 0.0f64;
        for k in 0..1000 {
            beam.do_step(h * k, h).unwrap();
            let e: f64 = beam.energies().iter().sum();
            worst = worst.max((e - e0).abs() / e0);
        }
        (e0, worst)
    };
    let (e0, ec) = run(Law::EnergyConserving { penalty: 1e4 });
    let (_, pen) = run(Law::Penalty { penalty: 1e4 });
    let (_, al) = run(Law::AugmentedLagrangian {
        penalty: 1e4,
        lambda0: 0.0,
        eta: 0.0,
        update: LambdaUpdate::TimeStep,
    });
    eprintln!(
        "beam from y_ref, 10 s, tau = 0.01 s: E0 = {e0:.3} J; largest relative energy change: energy-conserving {ec:.2e}, penalty {pen:.2e}, augmented Lagrangian {al:.2e}"
    );
    assert!(ec < 1e-6, "{ec}");
    assert!(ec < pen && ec < al);
}

#[test]
fn static_contact_with_the_augmented_barrier() {
    for p in [1e3, 1e4] {
        let mut beam = contact_problem(
            25,
            Law::AugmentedBarrier {
                penalty: p,
                lambda0: 1.0,
                s: 1.0,
                beta: 0.5,
                eta: 0.0,
                update: LambdaUpdate::NewtonIteration,
            },
        );
        let outcome = beam.initialize(Time::ZERO);
        let (distance, penetration) = reference_distance(&beam);
        eprintln!(
            "augmented barrier 25 el, p = {p:.0e}: {outcome:?}, reference distance {distance:.3e}, penetration {penetration:.3e} m"
        );
        assert!(outcome.is_ok());
        assert!(
            distance < 1e-3 && penetration < 1e-4,
            "{distance} {penetration}"
        );
    }
}

#[test]
fn static_augmented_lagrangian_with_the_source_penalty_growth() {
    // Seed 004 Fig. 6.5 settings: p0 = 1e2 growing by psi = 2.5 per iteration.
    let target = 1e5;
    let mut params = contact_params(
        25,
        Law::AugmentedLagrangian {
            penalty: target,
            lambda0: 0.0,
            eta: 0.0,
            update: LambdaUpdate::NewtonIteration,
        },
    );
    params.static_penalty_start = Some(1e2);
    params.static_penalty_growth = 2.5;
    let mut beam = Driver::new(Beam::new(params).unwrap());
    let outcome = beam.initialize(Time::ZERO);
    let (distance, penetration) = reference_distance(&beam);
    eprintln!(
        "augmented Lagrangian, p0 = 1e2, psi = 2.5, p = {target:.0e}: {outcome:?} after {} iterations, reference distance {distance:.3e}, penetration {penetration:.3e} m",
        beam.last_newton_iterations()
    );
    assert!(outcome.is_ok());
    assert!(
        distance < 1e-3 && penetration < 1e-4,
        "{distance} {penetration}"
    );
}
