//! The master's contract with units: exact rollback, capability checks, error
//! reports with context, iteration policies, counters, holds and links.

use slender_coupling::settings::{MasterSettings, OnMaxIterations, Scheme};
use slender_coupling::{Link, Master, MasterError, System};
use slender_tests::probe::{Act, Probe};
use slender_tests::{load, run};
use slender_units::benchmark::algebraic_loop::{
    LinearPair, LinearPairParams, SphereClosure, SphereParams,
};
use slender_units::benchmark::oscillator::{Coupling, Oscillator, OscillatorParams};
use slender_units::{Driver, DriverSlot};
use slender_units::{Hold, Time, Unit};

fn ms(ms: i64) -> Time {
    Time::from_nanos(ms * 1_000_000)
}

fn oscillator(coupling: Coupling) -> Driver<Oscillator> {
    let (kc, dc) = if coupling == Coupling::Spring {
        (50.0, 0.5)
    } else {
        (0.0, 0.0)
    };
    Driver::new(
        Oscillator::new(OscillatorParams {
            mass: 2.0,
            stiffness: 30.0,
            damping: 0.3,
            coupling,
            coupling_stiffness: kc,
            coupling_damping: dc,
            initial_displacement: 0.1,
            initial_velocity: -0.2,
            substeps: 3,
        })
        .unwrap(),
    )
}

/// Save, step, restore, step again with the same inputs: outputs bit-identical;
/// a different input in between does not leak into the repeat.
fn assert_exact_rollback<U: Unit>(mut unit: Driver<U>, inputs: &[f64]) {
    let n_out = unit.description().outputs.len();
    unit.set_inputs(&vec![0.1; inputs.len()]).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    for k in 1..4 {
        let v: Vec<f64> = inputs.iter().map(|x| x * k as f64 * 0.3).collect();
        unit.set_inputs(&v).unwrap();
        unit.do_step(ms(10 * (k - 1)), ms(10)).unwrap();
    }
    let mut slot = DriverSlot::new();
    unit.save(&mut slot).unwrap();
    let step = |unit: &mut Driver<U>, v: &[f64]| {
        unit.set_inputs(v).unwrap();
        unit.do_step(ms(30), ms(10)).unwrap();
        let mut out = vec![0.0; n_out];
        unit.outputs(&mut out).unwrap();
        out.iter().map(|x| x.to_bits()).collect::<Vec<u64>>()
    };
    let first = step(&mut unit, inputs);
    unit.restore(&slot).unwrap();
    let other: Vec<f64> = inputs.iter().map(|x| x + 0.05).collect();
    let different = step(&mut unit, &other);
    unit.restore(&slot).unwrap();
    let repeat = step(&mut unit, inputs);
    assert_eq!(
        first,
        repeat,
        "{}: repeated step differs",
        unit.description().kind
    );
    assert_ne!(
        first,
        different,
        "{}: the input had no effect",
        unit.description().kind
    );
}

#[test]
fn rollback_is_bit_exact_for_every_native_unit() {
    assert_exact_rollback(oscillator(Coupling::Spring), &[0.02, 0.3]);
    assert_exact_rollback(oscillator(Coupling::Force), &[4.0]);
    assert_exact_rollback(Driver::new(LinearPair::new(LinearPairParams {})), &[0.7]);
    assert_exact_rollback(
        Driver::new(SphereClosure::new(SphereParams::default()).unwrap()),
        &[0.5, 0.4],
    );
}

fn probes(a: Probe, b: Probe) -> System {
    let mut s = System::new();
    s.add_unit("a", Box::new(a)).unwrap();
    s.add_unit("b", Box::new(b)).unwrap();
    s.connect("a.y", "b.u", Link::default()).unwrap();
    s.connect("b.y", "a.u", Link::default()).unwrap();
    s
}

#[test]
fn a_unit_without_rollback_is_refused_by_iterative_schemes_only() {
    for scheme in [Scheme::IterativeJacobi, Scheme::IterativeGaussSeidel] {
        let err = Master::new(
            probes(Probe::new(true), Probe::new(false)),
            MasterSettings::new(scheme),
            ms(10),
        )
        .err()
        .expect("must be refused");
        assert!(
            matches!(err, MasterError::RollbackUnsupported { ref unit, .. } if unit == "b"),
            "{err}"
        );
        assert!(err.to_string().contains("`b` cannot roll back"), "{err}");
    }
    for scheme in [Scheme::Jacobi, Scheme::GaussSeidel] {
        let mut m = Master::new(
            probes(Probe::new(true), Probe::new(false)),
            MasterSettings::new(scheme),
            ms(10),
        )
        .unwrap();
        m.initialize(Time::ZERO).unwrap();
        m.step().unwrap();
    }
}

#[test]
fn nan_from_a_unit_stops_the_run_naming_unit_port_and_time() {
    let b = Probe::scripted(true, |t, _| {
        if t > 0.045 {
            Act::ProduceNan
        } else {
            Act::Behave
        }
    });
    let mut m = Master::new(
        probes(Probe::new(true), b),
        MasterSettings::new(Scheme::IterativeGaussSeidel),
        ms(10),
    )
    .unwrap();
    m.initialize(Time::ZERO).unwrap();
    let err = m.run_until(ms(100), |_| {}).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, MasterError::NonFinite { .. }), "{text}");
    assert!(
        text.contains("unit `b`") && text.contains("output `y`") && text.contains("t = 0.05 s"),
        "{text}"
    );
}

#[test]
fn a_unit_error_inside_an_iteration_names_the_unit_call_time_and_iteration() {
    // The fifth do_step of `a` fails: with B1-like 1-iteration steps that is the
    // step ending at 0.05 s.
    let a = Probe::scripted(true, |_, calls| {
        if calls == 5 {
            Act::Fail("solver diverged")
        } else {
            Act::Behave
        }
    });
    let mut m = Master::new(
        probes(a, Probe::new(true)),
        MasterSettings::new(Scheme::IterativeJacobi),
        ms(10),
    )
    .unwrap();
    m.initialize(Time::ZERO).unwrap();
    let err = m.run_until(ms(1000), |_| {}).unwrap_err();
    let text = err.to_string();
    assert_eq!(
        text,
        "unit `a`: do_step failed at t = 0.05 s (iteration 1): solver diverged"
    );
}

#[test]
fn the_iteration_cap_either_stops_the_run_or_is_counted() {
    for policy in [OnMaxIterations::Error, OnMaxIterations::Accept] {
        let mut scene = load("examples/b1_two_masses.toml");
        scene.spec.master.max_iterations = 2;
        scene.spec.master.tolerances.displacement = 1e-15;
        scene.spec.master.on_max_iterations = policy;
        let s = run(&scene);
        match policy {
            OnMaxIterations::Error => {
                let e = s.error.expect("must stop");
                assert!(e.contains("did not converge in 2 iterations"), "{e}");
            }
            OnMaxIterations::Accept => {
                assert!(s.error.is_none());
                assert_eq!(s.counters.non_converged_steps, 100);
                assert!(s.counters.max_residual > 1.0);
            }
        }
    }
}

#[test]
fn counters_add_up() {
    let scene = load("examples/b3_force_displacement.toml");
    let s = run(&scene);
    let c = &s.counters;
    assert_eq!(c.iteration_histogram.iter().sum::<u64>(), c.steps);
    let weighted: u64 = c
        .iteration_histogram
        .iter()
        .enumerate()
        .map(|(k, n)| k as u64 * n)
        .sum();
    assert_eq!(weighted, c.iterations);
    // Every iteration after the first of a step rolls both coupled units back.
    assert_eq!(c.rollbacks, 2 * (c.iterations - c.steps));
    // Initialisation calls `initialize`, not `do_step`; the coupled units step
    // once per iteration, the analytic solution's two signals (sources, which
    // take no input) once per step.
    let calls = |name: &str| {
        let unit = c.units.iter().find(|u| u.name == name).unwrap();
        unit.do_step_calls
    };
    assert_eq!(calls("a") + calls("b"), 2 * c.iterations);
    assert_eq!(calls("exact_a") + calls("exact_b"), 2 * c.steps);
    assert_eq!(c.do_step_calls(), 2 * c.iterations + 2 * c.steps);
    assert!(c.last_residual <= 1.0);
}

/// Unit `a` integrates a constant 1 (so y_a = t); unit `b` integrates y_a.
fn ramp_integral(hold: Hold) -> f64 {
    let mut s = System::new();
    s.add_unit("a", Box::new(Probe::new(true))).unwrap();
    s.add_unit("b", Box::new(Probe::new(true))).unwrap();
    s.set_start_input("a.u", 1.0).unwrap();
    s.connect("a.y", "b.u", Link::default()).unwrap();
    let mut m = Master::new(s, MasterSettings::new(Scheme::GaussSeidel), ms(100)).unwrap();
    m.set_hold(1, hold).unwrap();
    m.initialize(Time::ZERO).unwrap();
    m.run_until(ms(1000), |_| {}).unwrap();
    m.output("b.y").unwrap()
}

#[test]
fn ramp_hold_integrates_a_linear_input_exactly_and_zero_order_hold_does_not() {
    // y_b(1) = integral of t = 0.5 exactly with a ramp; with zero-order hold of the
    // end value: sum of h t_{n+1} = 0.55.
    assert!((ramp_integral(Hold::Ramp) - 0.5).abs() < 1e-14);
    assert!((ramp_integral(Hold::ZeroOrder) - 0.55).abs() < 1e-14);
}

#[test]
fn gain_and_offset_apply_to_the_value_passed() {
    let mut s = System::new();
    s.add_unit("a", Box::new(Probe::new(true))).unwrap();
    s.add_unit("b", Box::new(Probe::new(true))).unwrap();
    s.set_start_input("a.u", 1.0).unwrap();
    s.connect(
        "a.u_seen",
        "b.u",
        Link {
            gain: 2.0,
            offset: 0.5,
            tolerance: None,
        },
    )
    .unwrap();
    let mut m = Master::new(s, MasterSettings::new(Scheme::GaussSeidel), ms(10)).unwrap();
    m.initialize(Time::ZERO).unwrap();
    m.step().unwrap();
    assert_eq!(m.output("b.u_seen").unwrap(), 2.5);
}

#[test]
fn calls_out_of_order_and_bad_orders_are_errors() {
    let mut m = Master::new(
        probes(Probe::new(true), Probe::new(true)),
        MasterSettings::new(Scheme::Jacobi),
        ms(10),
    )
    .unwrap();
    assert!(
        m.step()
            .unwrap_err()
            .to_string()
            .contains("before Master::initialize")
    );
    let mut settings = MasterSettings::new(Scheme::GaussSeidel);
    settings.order = vec!["a".into(), "bb".into()];
    let e = Master::new(
        probes(Probe::new(true), Probe::new(true)),
        settings.clone(),
        ms(10),
    )
    .err()
    .unwrap();
    assert!(
        e.to_string()
            .contains("no unit named `bb`; did you mean `b`?"),
        "{e}"
    );
    settings.order = vec!["a".into()];
    let e = Master::new(probes(Probe::new(true), Probe::new(true)), settings, ms(10))
        .err()
        .unwrap();
    assert!(e.to_string().contains("missing: b"), "{e}");
    let e = Master::new(
        probes(Probe::new(true), Probe::new(true)),
        MasterSettings::new(Scheme::Jacobi),
        Time::ZERO,
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("expected > 0"), "{e}");
}

/// Issue 11: under Jacobi every connection is torn; the cable under the constant
/// top load used to start from 0 N ("the line is slack"). Initialisation now starts
/// with one upstream-first pass, so each section starts from its upstream's values.
#[test]
fn jacobi_initialises_units_from_their_upstream_values() {
    use slender_coupling::settings::{Acceleration, Scheme};
    let mut scene = load("examples/truncation_substructured.toml");
    scene.spec.master.scheme = Scheme::Jacobi;
    scene.spec.master.acceleration = Acceleration::None;
    let mut master = scene.build().unwrap();
    master.initialize(scene.start).unwrap();
    let index = |name: &str| master.unit_names().position(|n| n == name).unwrap();
    let (load_unit, emulated) = (index("load"), index("emulated"));
    assert_eq!(
        &master.inputs(emulated)[..2],
        &master.outputs(load_unit)[..2]
    );
    assert!(
        master.inputs(emulated)[1] > 1e5,
        "a taut line: {:?}",
        master.inputs(emulated)
    );
}

#[test]
fn a_chain_of_100_000_units_builds_and_orders_in_linear_time() {
    // Issue 27: unit lookups, the driven-input check and the ordering were
    // quadratic (`slender check` of 100 000 connected units took 4 min; 2.2 s
    // now). A regression shows as a test that does not end.
    let n = 100_000;
    let mut s = System::new();
    for i in 0..n {
        s.add_unit(&format!("u{i}"), Box::new(Probe::new(true)))
            .unwrap();
    }
    for i in 1..n {
        s.connect(
            &format!("u{}.y", i - 1),
            &format!("u{i}.u"),
            Link::default(),
        )
        .unwrap();
    }
    let err = s
        .connect("u0.y", &format!("u{}.u", n - 1), Link::default())
        .unwrap_err();
    assert!(err.to_string().contains("already driven"), "{err}");
    let m = Master::new(s, MasterSettings::new(Scheme::GaussSeidel), ms(10)).unwrap();
    let order = m.order();
    assert_eq!(order.len(), n);
    assert!(order.iter().enumerate().all(|(i, u)| *u == format!("u{i}")));
}
