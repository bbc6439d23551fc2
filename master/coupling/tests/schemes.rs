//! The coupling schemes on a problem with a known answer, with a mock unit
//! and no physics: two affine units in a loop, `x1 = a1 x2 + b1 c(t)` and
//! `x2 = a2 x1 + b2 c(t)` with `c(t) = cos(10 t)`, each output depending on
//! the step's end input. Every step's coupled values are the loop's fixed
//! point `x1 = c(t) (a1 b2 + b1) / (1 - a1 a2)`, which moves from step to
//! step so that no predictor finds it; the plain fixed-point iteration
//! contracts by `a1 a2` per Gauss-Seidel sweep and diverges past one.

use slender_contract::{
    Capabilities, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
    UnitError,
};
use slender_coupling::settings::{
    Acceleration, Extrapolation, MasterSettings, NewtonSettings, Scheme,
};
use slender_coupling::{Link, Master, MasterError, System};

/// `y = gain * u + offset * c(t)` at the step's end; its state is the time
/// reached (s).
struct Affine {
    description: UnitDescription,
    gain: f64,
    offset: f64,
    time: f64,
}

/// How the offsets vary: the fixed point moves with it.
fn c(t: f64) -> f64 {
    (10.0 * t).cos()
}

impl Affine {
    fn new(gain: f64, offset: f64) -> Affine {
        Affine {
            description: UnitDescription {
                kind: "affine".into(),
                inputs: vec![Port::input("u", PortKind::Generic)],
                outputs: vec![Port::output("y", PortKind::Generic).with_feedthrough(&[0])],
                capabilities: Capabilities {
                    rollback: true,
                    ..Capabilities::default()
                },
            },
            gain,
            offset,
            time: 0.0,
        }
    }
}

impl Unit for Affine {
    fn description(&self) -> &UnitDescription {
        &self.description
    }
    fn initialize(&mut self, t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.time = t0.as_secs();
        Ok(())
    }
    fn do_step(&mut self, t: Time, h: Time, _i: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.time = (t + h).as_secs();
        Ok(StepReport::default())
    }
    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        out[0] = self.gain * inputs.end()[0] + self.offset * c(self.time);
    }
    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.time);
        Ok(())
    }
    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.time = *slot.load::<f64>()?;
        Ok(())
    }
}

/// The loop's gains and offsets.
const B: [f64; 2] = [1.0, 2.0];

/// The fixed point's x1 for gains `a` at the end of the run (5 steps of 10 ms).
fn exact(a: [f64; 2]) -> f64 {
    c(0.05) * (a[0] * B[1] + B[0]) / (1.0 - a[0] * a[1])
}

/// A master over the loop with gains `a`, tolerances of 1e-12.
/// (Errors as text: the tests read their message.)
fn master(a: [f64; 2], settings: MasterSettings) -> Result<Master, String> {
    master_within(a, settings, 1e-12, 10_000_000)
}

/// The same with absolute tolerances `tolerance` on the coupled values and
/// a step of `step` ns.
fn master_within(
    a: [f64; 2],
    mut settings: MasterSettings,
    tolerance: f64,
    step: i64,
) -> Result<Master, String> {
    let mut system = System::new();
    // Building the system cannot fail for these names and ports.
    let built = system.add_unit("one", Box::new(Affine::new(a[0], B[0])));
    built
        .and(system.add_unit("two", Box::new(Affine::new(a[1], B[1]))))
        .and(system.connect("two.y", "one.u", Link::default()))
        .and(system.connect("one.y", "two.u", Link::default()))
        .expect("the loop");
    settings.tolerances.generic = tolerance;
    settings.tolerances.generic_relative = 1e-12;
    settings.max_iterations = 200;
    let text = |e: MasterError| e.to_string();
    let mut master = Master::new(system, settings, Time::from_nanos(step)).map_err(text)?;
    master.initialize(Time::ZERO).map_err(text)?;
    Ok(master)
}

/// Steps `master` five times; the iterations per step and x1 at the end.
fn run(mut master: Master) -> Result<(f64, f64), String> {
    for _ in 0..5 {
        master.step().map_err(|e| e.to_string())?;
    }
    let c = master.counters();
    let x1 = master.output("one.y").map_err(|e| e.to_string())?;
    Ok((c.iterations as f64 / c.steps as f64, x1))
}

fn settings(scheme: Scheme, acceleration: Acceleration) -> MasterSettings {
    MasterSettings {
        acceleration,
        ..MasterSettings::new(scheme)
    }
}

#[test]
fn iterative_schemes_find_the_fixed_point_gauss_seidel_in_fewer_sweeps() {
    let a = [0.5, -0.8];
    let (gs, x_gs) = run(master(
        a,
        settings(Scheme::IterativeGaussSeidel, Acceleration::None),
    )
    .unwrap())
    .unwrap();
    let (jacobi, x_jacobi) =
        run(master(a, settings(Scheme::IterativeJacobi, Acceleration::None)).unwrap()).unwrap();
    for x in [x_gs, x_jacobi] {
        assert!((x - exact(a)).abs() < 1e-10, "{x} against {}", exact(a));
    }
    // Contraction 0.4 per Gauss-Seidel sweep, sqrt(0.4) per Jacobi sweep.
    assert!(
        gs < jacobi,
        "Gauss-Seidel {gs}, Jacobi {jacobi} iterations per step"
    );
    assert!(gs > 5.0 && gs < 40.0, "{gs}");
}

#[test]
fn plain_iteration_stops_where_the_loop_gain_passes_one_and_acceleration_converges() {
    let a = [1.5, -1.0];
    let plain = master(
        a,
        settings(Scheme::IterativeGaussSeidel, Acceleration::None),
    )
    .and_then(run);
    let error = plain.expect_err("a loop gain of -1.5 diverges");
    assert!(error.contains("did not converge"), "{error}");
    let accelerated = [
        Acceleration::Aitken {
            initial_factor: 0.5,
        },
        Acceleration::IqnIls {
            initial_factor: 0.5,
            reuse_steps: 0,
        },
    ];
    for acceleration in accelerated {
        let name = format!("{acceleration:?}");
        let outcome = master(a, settings(Scheme::IterativeGaussSeidel, acceleration)).and_then(run);
        let (iterations, x) = outcome.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            (x - exact(a)).abs() < 1e-10,
            "{name}: {x} against {}",
            exact(a)
        );
        // A linear loop: the secant is exact after two sweeps.
        assert!(
            iterations <= 5.0,
            "{name}: {iterations} iterations per step"
        );
    }
}

#[test]
fn newton_on_the_interface_solves_the_linear_loop_in_a_few_sweeps() {
    let a = [1.5, -1.0];
    let settings = MasterSettings {
        newton: Some(NewtonSettings::default()),
        ..MasterSettings::new(Scheme::IterativeJacobi)
    };
    let (iterations, x) = run(master(a, settings).unwrap()).unwrap();
    assert!((x - exact(a)).abs() < 1e-9, "{x} against {}", exact(a));
    assert!(iterations <= 4.0, "{iterations} iterations per step");
}

/// x1 after five steps of a non-iterative scheme, from the start's fixed
/// point: each unit reads the other's value held from the step's start
/// (Jacobi), or the second unit the first's fresh value (Gauss-Seidel).
fn non_iterative(a: [f64; 2], sequential: bool) -> f64 {
    let x1 = (a[0] * B[1] + B[0]) / (1.0 - a[0] * a[1]);
    let (mut x1, mut x2) = (x1, a[1] * x1 + B[1]);
    for n in 1..=5 {
        let cn = c(0.01 * f64::from(n));
        let next = a[0] * x2 + B[0] * cn;
        x2 = a[1] * if sequential { next } else { x1 } + B[1] * cn;
        x1 = next;
    }
    x1
}

#[test]
fn non_iterative_schemes_trail_the_moving_fixed_point_as_their_recursion_says() {
    let a = [0.5, -0.8];
    for (scheme, sequential) in [(Scheme::Jacobi, false), (Scheme::GaussSeidel, true)] {
        let outcome = master(a, settings(scheme, Acceleration::None)).and_then(run);
        let (iterations, x) = outcome.unwrap_or_else(|e| panic!("{scheme:?}: {e}"));
        assert_eq!(iterations, 1.0, "{scheme:?}");
        let expected = non_iterative(a, sequential);
        assert!(
            (x - expected).abs() < 1e-12,
            "{scheme:?}: {x} against {expected}"
        );
        // One sweep a step does not reach the fixed point.
        assert!(
            (x - exact(a)).abs() > 1e-4,
            "{scheme:?}: {x} on the fixed point"
        );
    }
}

/// The first iterate of a step is the fixed point extrapolated from the
/// accepted values; its error is of order h^2 x'' when linear and h^3 x'''
/// when quadratic (x = K cos(10 t): 8.9e-4 and 2.2e-5 at 2.5 ms). With a
/// tolerance between the two, Newton accepts the quadratic prediction after
/// one sweep (the first steps have fewer values to extrapolate from) and the
/// linear one after two (one only where x'' passes zero); both answers are
/// the fixed point within the tolerance. The loop gain is small here (0.02,
/// a heavy body on its lines): a value accepted after one sweep is off by the
/// loop gain times the prediction's error, and the quadratic extrapolation
/// weighs the last three values by 3, 3 and 1, so at a loop gain of 0.4 these
/// errors grow until a second sweep clears them (1.5 sweeps a step).
#[test]
fn a_quadratic_prediction_is_accepted_after_one_sweep_where_a_linear_one_is_not() {
    let a = [0.1, -0.2];
    let sweeps = |extrapolation: Extrapolation| {
        let settings = MasterSettings {
            newton: Some(NewtonSettings::default()),
            extrapolation,
            ..MasterSettings::new(Scheme::IterativeJacobi)
        };
        let (tolerance, steps) = (3e-4, 240);
        let mut master = master_within(a, settings, tolerance, 2_500_000).unwrap();
        for _ in 0..steps {
            master.step().unwrap();
        }
        let x1 = master.output("one.y").unwrap();
        let fixed_point = exact(a) / c(0.05) * c(0.0025 * f64::from(steps));
        assert!(
            (x1 - fixed_point).abs() < tolerance,
            "{extrapolation:?}: {x1} against {fixed_point}"
        );
        let counters = master.counters();
        counters.iterations as f64 / counters.steps as f64
    };
    let (linear, quadratic) = (
        sweeps(Extrapolation::Linear),
        sweeps(Extrapolation::Quadratic),
    );
    assert!(linear > 1.7, "linear: {linear} sweeps per step");
    assert!(quadratic < 1.05, "quadratic: {quadratic} sweeps per step");
}
