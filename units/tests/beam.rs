//! The beam unit (seed 004): cantilever eigenfrequencies and free vibration against
//! the analytical solution, static distributed load against eq. 6.2, and the
//! static contact reference problem (eq. 4.41) for each contact method.

use crate::support::published;
use slender_units::Driver;
use slender_units::Time;
use slender_units::beam::boundary::{Boundary, Quantity};
use slender_units::beam::{Beam, BeamParams};
use slender_units::contact::{LambdaUpdate, Law};

use crate::support::beams::{
    cantilever, cond, contact_params, contact_problem, params, reference_distance,
};

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
