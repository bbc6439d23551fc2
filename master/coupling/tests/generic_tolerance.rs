//! Ports without a unit of measure (issue 29): FMUs from other tools often
//! declare none, so their connections are generic. An absolute 1e-9 cannot
//! judge a 1.9 MN force whose unit solves it to a relative 1e-12 inside (its
//! output wobbles by micronewtons between iterations); the default tolerance of
//! a generic connection is therefore relative to the values it carries, and a
//! connection that still fails names the key that set its tolerance.

use slender_coupling::settings::{MasterSettings, OnMaxIterations, Scheme};
use slender_coupling::{Link, Master, MasterError, System};
use slender_units::{
    Capabilities, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
    UnitError,
};

/// The loop's fixed point (N, though the ports do not say so).
const FORCE: f64 = 1.9e6;

/// y = 0.5 u + FORCE / 2, as an inner solver converged to a relative 1e-12
/// returns it: with a wobble of that size that depends on the input's last
/// digits, so successive iterates never agree to better than about 2e-6.
struct InnerSolver {
    description: UnitDescription,
    y: f64,
}

impl InnerSolver {
    fn new(kind: PortKind) -> InnerSolver {
        InnerSolver {
            description: UnitDescription {
                kind: "inner_solver".into(),
                inputs: vec![Port::input("u", kind)],
                outputs: vec![Port::output("y", kind)],
                capabilities: Capabilities {
                    rollback: true,
                    ..Capabilities::default()
                },
            },
            y: 0.0,
        }
    }

    fn solve(&mut self, u: f64) {
        let wobble = ((u * 1e7).fract() - 0.5) * 2.0 * 1e-12 * FORCE;
        self.y = 0.5 * u + 0.5 * FORCE + wobble;
    }
}

impl Unit for InnerSolver {
    fn description(&self) -> &UnitDescription {
        &self.description
    }
    fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.solve(inputs.end()[0]);
        Ok(())
    }
    fn do_step(&mut self, _t: Time, _h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.solve(inputs.end()[0]);
        Ok(StepReport::default())
    }
    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        out[0] = self.y;
    }
    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.y);
        Ok(())
    }
    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.y = *slot.load::<f64>()?;
        Ok(())
    }
}

/// Two inner solvers in a loop (each feeds the other), iterated by Jacobi for
/// ten steps; `adjust` changes the settings.
fn run(kind: PortKind, adjust: impl Fn(&mut MasterSettings)) -> (Result<(), MasterError>, f64) {
    let mut system = System::new();
    for name in ["a", "b"] {
        system
            .add_unit(name, Box::new(InnerSolver::new(kind)))
            .unwrap();
    }
    system.connect("a.y", "b.u", Link::default()).unwrap();
    system.connect("b.y", "a.u", Link::default()).unwrap();
    let mut settings = MasterSettings::new(Scheme::IterativeJacobi);
    settings.on_max_iterations = OnMaxIterations::Error;
    adjust(&mut settings);
    let mut master = Master::new(system, settings, Time::from_secs(0.1).unwrap()).unwrap();
    let mut result = master.initialize(Time::ZERO);
    for _ in 0..10 {
        if result.is_err() {
            break;
        }
        result = master.step();
    }
    let value = master.inputs(0)[0];
    (result, value)
}

#[test]
fn a_unitless_meganewton_loop_converges_under_the_default_relative_tolerance() {
    let (result, value) = run(PortKind::Generic, |_| {});
    result.expect("relative 1e-9 of 1.9 MN is 1.9 mN, above the wobble");
    assert!((value - FORCE).abs() < 1e-2, "{value}");
    // The same loop with units of measure: the force tolerance (0.1 N).
    let (result, value) = run(PortKind::Force, |_| {});
    result.expect("0.1 N is above the wobble");
    assert!((value - FORCE).abs() < 1.0, "{value}");
}

#[test]
fn an_absolute_tolerance_on_round_off_fails_and_names_its_key() {
    let (result, _) = run(PortKind::Generic, |s| s.tolerances.generic_relative = 0.0);
    let err = result.expect_err("1e-9 N is below a 1.9 MN force's round-off");
    let message = err.to_string();
    assert!(matches!(err, MasterError::NotConverged { .. }), "{message}");
    assert!(message.contains("[master] tolerances.generic"), "{message}");
}

#[test]
fn a_relative_tolerance_that_is_not_met_says_so_and_how_large_it_was() {
    let (result, _) = run(PortKind::Generic, |s| {
        s.tolerances.generic_relative = 1e-15;
    });
    let message = result.expect_err("1e-15 is below round-off").to_string();
    for expected in [
        "tolerances.generic_relative = 1e-15",
        "largest value carried",
        "no unit of measure",
    ] {
        assert!(message.contains(expected), "`{expected}` not in: {message}");
    }
}

#[test]
fn a_relative_tolerance_outside_0_to_1_is_refused() {
    for bad in [-1e-9, 1.0, f64::NAN] {
        let mut settings = MasterSettings::new(Scheme::IterativeJacobi);
        settings.tolerances.generic_relative = bad;
        let err = settings.validate().expect_err("must be refused");
        assert!(err.to_string().contains("generic_relative"), "{err}");
    }
}
