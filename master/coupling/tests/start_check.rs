//! Issue 30: the master's start check. A unit that solves its statics under a
//! coupled load (the cable under its top force) starts in equilibrium with
//! what the other side reported at the start; if that side reports something
//! else after the first step, the unit started off its equilibrium. The
//! original fault was a top section that reported a damping reaction at t = 0
//! only (3.32 MN, then 2.39 MN): here a source does the same on purpose, and
//! the run stops naming both units and both values; within the tolerance the
//! change is kept in the counters.

use slender_coupling::settings::{MasterSettings, Scheme};
use slender_coupling::{Link, Master, MasterError, System};
use slender_units::cable::CableParams;
use slender_units::cable::{Cable, Effects};
use slender_units::{
    Capabilities, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
    UnitError,
};

/// The polyester line's static top force (N), from its monolithic runs.
const TOP: [f64; 2] = [1_915_111.1, 1_581_573.3];

/// A top load that reports `spike` times the static force at the start and
/// the static force after any step (a damping reaction taken as load at t0).
struct SpikedTop {
    description: UnitDescription,
    spike: f64,
    stepped: bool,
}

impl SpikedTop {
    fn new(spike: f64) -> SpikedTop {
        SpikedTop {
            description: UnitDescription {
                kind: "spiked_top".into(),
                inputs: Vec::new(),
                outputs: vec![
                    Port::output("force_x", PortKind::Force),
                    Port::output("force_z", PortKind::Force),
                ],
                capabilities: Capabilities::default(),
            },
            spike,
            stepped: false,
        }
    }
}

impl Unit for SpikedTop {
    fn description(&self) -> &UnitDescription {
        &self.description
    }
    fn initialize(&mut self, _t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.stepped = false;
        Ok(())
    }
    fn do_step(&mut self, _t: Time, _h: Time, _i: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.stepped = true;
        Ok(StepReport::default())
    }
    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        let k = if self.stepped { 1.0 } else { self.spike };
        out[0] = k * TOP[0];
        out[1] = k * TOP[1];
    }
    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.stepped);
        Ok(())
    }
    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.stepped = *slot.load::<bool>()?;
        Ok(())
    }
}

/// The polyester line (20 elements) under a spiked top, first step taken.
fn first_step(spike: f64, start_tolerance: f64) -> (Result<(), MasterError>, Master) {
    let mut system = System::new();
    system
        .add_unit("top", Box::new(SpikedTop::new(spike)))
        .unwrap();
    let cable = Cable::new(CableParams::seed000_polyester(20), Effects::all()).unwrap();
    system.add_unit("line", Box::new(cable)).unwrap();
    for axis in ["x", "z"] {
        let (from, to) = (
            format!("top.force_{axis}"),
            format!("line.top_force_{axis}"),
        );
        system.connect(&from, &to, Link::default()).unwrap();
    }
    let mut settings = MasterSettings::new(Scheme::GaussSeidel);
    settings.start_tolerance = start_tolerance;
    let mut master = Master::new(system, settings, Time::from_secs(0.01).unwrap()).unwrap();
    master.initialize(Time::ZERO).unwrap();
    (master.step(), master)
}

#[test]
fn a_load_that_leaves_in_the_first_step_stops_the_run_naming_both_units_and_values() {
    let (result, _) = first_step(1.32, 0.2);
    let err = result.expect_err("a 24 % spike must be refused");
    assert!(
        matches!(err, MasterError::StartOffEquilibrium { ref from, ref to, .. }
            if from.starts_with("top.force_") && to.starts_with("line.top_force_")),
        "{err}"
    );
    let message = err.to_string();
    for expected in ["start_tolerance 0.2", "24.2 %", "fade_in"] {
        assert!(message.contains(expected), "`{expected}` not in: {message}");
    }
}

#[test]
fn within_the_tolerance_the_change_is_counted_and_a_consistent_start_shows_none() {
    let (result, master) = first_step(1.32, 0.3);
    result.unwrap();
    let load = master
        .counters()
        .start_load
        .expect("the cable's top is checked");
    assert!(
        (load.relative_change - 0.32 / 1.32).abs() < 1e-9,
        "{load:?}"
    );
    assert!((load.used - 1.32 * TOP[0]).abs() < 1.0 || (load.used - 1.32 * TOP[1]).abs() < 1.0);
    let (result, master) = first_step(1.0, 0.2);
    result.unwrap();
    let load = master.counters().start_load.unwrap();
    assert_eq!(load.relative_change, 0.0, "{load:?}");
}

#[test]
fn a_start_tolerance_that_is_not_positive_is_refused() {
    for bad in [0.0, -1.0, f64::NAN] {
        let mut settings = MasterSettings::new(Scheme::GaussSeidel);
        settings.start_tolerance = bad;
        let err = settings.validate().expect_err("must be refused");
        assert!(err.to_string().contains("start_tolerance"), "{err}");
    }
}
