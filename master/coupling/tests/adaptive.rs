//! The adaptive coupling step on problems with known answers: a damped
//! two-mass chain (B1 with dampers to ground) whose motion decays, so that
//! the step must start short and grow; a unit that fails at long steps for a
//! while, so that the step must halve and come back.

use slender_contract::{
    Capabilities, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
    UnitError,
};
use slender_coupling::counters::StepSizes;
use slender_coupling::settings::{AdaptiveStep, MasterSettings, Scheme};
use slender_coupling::{Link, Master, System};
use slender_units::benchmark::oscillator::{Oscillator, OscillatorParams};

const PI: f64 = std::f64::consts::PI;
/// Springs to ground and the middle spring (N/m), masses 1 kg (B1).
const K: f64 = 4.0 * PI * PI;
const KC: f64 = 16.0 * PI * PI;
/// Dampers to ground (N s/m): 4.8 % of critical on the 1 Hz mode, 1.6 % on
/// the 3 Hz one.
const C: f64 = 0.6;
/// The synchronisation step (s) and the run (s).
const STEP: f64 = 0.1;
const DURATION: f64 = 20.0;

/// One mode of the chain from q(0) = 0.5 m at rest: stiffness `k`, damping C.
fn mode(k: f64, t: f64) -> f64 {
    let omega = k.sqrt();
    let zeta = C / (2.0 * omega);
    let damped = omega * (1.0 - zeta * zeta).sqrt();
    0.5 * (-zeta * omega * t).exp()
        * ((damped * t).cos() + zeta * omega / damped * (damped * t).sin())
}

/// The exact displacements (m): the in-phase mode (k) plus and minus the
/// anti-phase one (k + 2 kc), from u = (1, 0) m at rest.
fn exact(t: f64) -> [f64; 2] {
    let (a, b) = (mode(K, t), mode(K + 2.0 * KC, t));
    [a + b, a - b]
}

fn oscillator(initial_displacement: f64) -> Box<dyn Unit> {
    let params = OscillatorParams {
        mass: 1.0,
        stiffness: K,
        damping: C,
        coupling: Default::default(),
        coupling_stiffness: KC,
        coupling_damping: 0.0,
        initial_displacement,
        initial_velocity: 0.0,
        substeps: 1,
    };
    Box::new(Oscillator::new(params).expect("valid oscillator"))
}

/// The chain under iterative Gauss-Seidel with `adaptive` (None: fixed steps
/// of `step`).
fn chain(step: f64, adaptive: Option<AdaptiveStep>) -> Master {
    let mut system = System::new();
    let built = system.add_unit("left", oscillator(1.0));
    built
        .and(system.add_unit("right", oscillator(0.0)))
        .and(system.connect(
            "left.displacement",
            "right.coupling_displacement",
            Link::default(),
        ))
        .and(system.connect(
            "right.displacement",
            "left.coupling_displacement",
            Link::default(),
        ))
        .expect("the chain");
    let mut settings = MasterSettings::new(Scheme::IterativeGaussSeidel);
    settings.tolerances.displacement = 1e-10;
    settings.adaptive = adaptive;
    let step = Time::from_secs(step).expect("a step");
    let mut master = Master::new(system, settings, step).expect("a master");
    master.initialize(Time::ZERO).expect("initialised");
    master
}

fn adaptive(tolerance: f64, min_step: f64) -> AdaptiveStep {
    AdaptiveStep {
        tolerance,
        min_step,
        calm_steps: 4,
        kinds: Vec::new(),
        interface: true,
        displacement: None,
    }
}

/// What a run gave: the largest displacement error against the exact
/// solution, `do_step` calls, and the steps taken in each synchronisation step.
struct Outcome {
    error: f64,
    do_steps: u64,
    steps_per_sync: Vec<u64>,
    sizes: Option<StepSizes>,
}

fn run(mut master: Master) -> Outcome {
    let mut outcome = Outcome {
        error: 0.0,
        do_steps: 0,
        steps_per_sync: Vec::new(),
        sizes: None,
    };
    let syncs = (DURATION / master.step_size().as_secs()).round() as usize;
    let mut taken = 0;
    for _ in 0..syncs {
        master.step().expect("a step");
        let steps = master.counters().steps;
        outcome.steps_per_sync.push(steps - taken);
        taken = steps;
        let e = exact(master.time().as_secs());
        let u = [
            master.output("left.displacement"),
            master.output("right.displacement"),
        ];
        for (ui, ei) in u.into_iter().zip(e) {
            outcome.error = outcome.error.max((ui.expect("an output") - ei).abs());
        }
    }
    let counters = master.counters();
    outcome.do_steps = counters.do_step_calls();
    outcome.sizes = counters.adaptive;
    outcome
}

#[test]
fn the_step_starts_short_where_the_chain_moves_fast_and_grows_as_it_decays() {
    let adaptive = run(chain(STEP, Some(adaptive(1e-3, STEP / 64.0))));
    let sizes = adaptive.sizes.as_ref().expect("adaptive counters");
    eprintln!(
        "adaptive 1e-3: error {:.3e}, {} do_step calls, {sizes:?}",
        adaptive.error, adaptive.do_steps
    );
    let first: u64 = adaptive.steps_per_sync[..10].iter().sum();
    let last: u64 = adaptive.steps_per_sync[adaptive.steps_per_sync.len() - 10..]
        .iter()
        .sum();
    eprintln!("steps in the first second {first}, in the last {last}");
    assert!(first >= 4 * last, "first second {first} steps, last {last}");
    assert_eq!(sizes.over_tolerance, 0, "{sizes:?}");
    assert!(sizes.rejected > 0, "{sizes:?}");
    // Fixed steps: as many steps as it took (0.0125 s), and its largest.
    let same_cost = run(chain(0.0125, None));
    let coarse = run(chain(STEP, None));
    eprintln!(
        "fixed 0.0125 s: error {:.3e} in {} calls; fixed {STEP} s: error {:.3e}",
        same_cost.error, same_cost.do_steps, coarse.error
    );
    assert!(
        adaptive.error < 0.5 * same_cost.error && adaptive.do_steps < same_cost.do_steps * 11 / 10,
        "adaptive {:.3e} in {} calls, fixed {:.3e} in {}",
        adaptive.error,
        adaptive.do_steps,
        same_cost.error,
        same_cost.do_steps
    );
    assert!(adaptive.error < 0.05 * coarse.error);
    // The fixed step as accurate takes half as many calls again (1.5x).
    let as_accurate = run(chain(0.00625, None));
    eprintln!(
        "fixed 0.00625 s: error {:.3e} in {} calls",
        as_accurate.error, as_accurate.do_steps
    );
    assert!(adaptive.error < 1.1 * as_accurate.error);
    assert!(adaptive.do_steps * 10 < as_accurate.do_steps * 7);
}

#[test]
fn the_units_own_error_estimate_alone_chooses_the_step_as_well() {
    let units_only = |displacement: f64| AdaptiveStep {
        interface: false,
        displacement: Some(displacement),
        ..adaptive(1e-3, STEP / 64.0)
    };
    let loose = run(chain(STEP, Some(units_only(1e-4))));
    let tight = run(chain(STEP, Some(units_only(1e-5))));
    let sizes = tight.sizes.as_ref().expect("adaptive counters");
    eprintln!(
        "1e-4 m: error {:.3e} in {} calls; 1e-5 m: error {:.3e} in {} calls, {sizes:?}",
        loose.error, loose.do_steps, tight.error, tight.do_steps
    );
    assert!(sizes.largest_at.starts_with("unit `"), "{sizes:?}");
    assert!(tight.error < 0.3 * loose.error);
    let first: u64 = tight.steps_per_sync[..10].iter().sum();
    let last: u64 = tight.steps_per_sync[tight.steps_per_sync.len() - 10..]
        .iter()
        .sum();
    assert!(first >= 4 * last, "first second {first} steps, last {last}");
}

#[test]
fn a_tighter_tolerance_gives_a_smaller_error_at_more_steps() {
    let loose = run(chain(STEP, Some(adaptive(1e-2, STEP / 64.0))));
    let tight = run(chain(STEP, Some(adaptive(1e-4, STEP / 64.0))));
    eprintln!(
        "1e-2: error {:.3e} in {} calls; 1e-4: error {:.3e} in {} calls",
        loose.error, loose.do_steps, tight.error, tight.do_steps
    );
    assert!(tight.error < 0.25 * loose.error);
    assert!(tight.do_steps > loose.do_steps);
}

/// How a mock unit behaves.
#[derive(Copy, Clone, PartialEq)]
enum Behaviour {
    /// Its step fails when longer than 20 ms between 0.5 s and 0.8 s (a
    /// solver that does not converge in a hard phase); its output is its time.
    Fragile,
    /// `y = (h / 20 ms) u + cos(t)` at the step's end: a loop of two
    /// converges by plain iteration only where (h / 20 ms)^2 < 1, as a stiff
    /// coupling does at short steps only.
    Stiff,
}

/// A mock unit keeping its time (its state) and its last step's gain.
struct Mock {
    description: UnitDescription,
    behaviour: Behaviour,
    time: f64,
    gain: f64,
}

impl Mock {
    fn new(behaviour: Behaviour, rollback: bool) -> Mock {
        let output = match behaviour {
            Behaviour::Fragile => Port::output("time", PortKind::Generic),
            Behaviour::Stiff => Port::output("y", PortKind::Generic).with_feedthrough(&[0]),
        };
        Mock {
            description: UnitDescription {
                kind: "mock".into(),
                inputs: vec![Port::input("u", PortKind::Generic)],
                outputs: vec![output],
                capabilities: Capabilities {
                    rollback,
                    ..Capabilities::default()
                },
            },
            behaviour,
            time: 0.0,
            gain: 0.0,
        }
    }
}

impl Unit for Mock {
    fn description(&self) -> &UnitDescription {
        &self.description
    }
    fn initialize(&mut self, t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.time = t0.as_secs();
        Ok(())
    }
    fn do_step(&mut self, t: Time, h: Time, _i: Inputs<'_>) -> Result<StepReport, UnitError> {
        let start = t.as_secs();
        let hard = (0.5..0.8).contains(&start) && h.as_secs() > 0.02;
        if self.behaviour == Behaviour::Fragile && hard {
            return Err(UnitError::Numerical(format!("no convergence at {start} s")));
        }
        self.time = (t + h).as_secs();
        self.gain = h.as_secs() / 0.02;
        Ok(StepReport::default())
    }
    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        out[0] = match self.behaviour {
            Behaviour::Fragile => self.time,
            Behaviour::Stiff => self.gain * inputs.end()[0] + self.time.cos(),
        };
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

fn fragile(rollback: bool, adaptive: Option<AdaptiveStep>) -> Result<Master, String> {
    fragile_unit(Mock::new(Behaviour::Fragile, rollback), adaptive)
}

fn fragile_unit(unit: Mock, adaptive: Option<AdaptiveStep>) -> Result<Master, String> {
    let mut system = System::new();
    system
        .add_unit("fragile", Box::new(unit))
        .map_err(|e| e.to_string())?;
    let mut settings = MasterSettings::new(Scheme::Jacobi);
    settings.adaptive = adaptive;
    let step = Time::from_secs(STEP).expect("a step");
    Master::new(system, settings, step).map_err(|e| e.to_string())
}

#[test]
fn a_step_that_fails_is_repeated_at_half_the_size_and_the_step_comes_back() {
    let mut master = fragile(true, Some(adaptive(1e-3, STEP / 64.0))).expect("a master");
    master.initialize(Time::ZERO).expect("initialised");
    for _ in 0..20 {
        master.step().expect("the adaptive step gets through");
    }
    assert!((master.time().as_secs() - 2.0).abs() < 1e-12);
    let sizes = master.counters().adaptive.expect("adaptive counters");
    eprintln!("{sizes:?}");
    assert!(sizes.failed >= 3, "{sizes:?}");
    assert!(sizes.accepted[0] >= 8, "back at the full step: {sizes:?}");
    assert!(sizes.accepted[3] > 0, "down to 12.5 ms: {sizes:?}");
    // At a fixed step the same run stops at 0.5 s.
    let mut fixed = fragile(true, None).expect("a master");
    fixed.initialize(Time::ZERO).expect("initialised");
    let failed = (0..20).find_map(|_| fixed.step().err()).expect("a failure");
    assert!(
        failed.to_string().contains("no convergence at 0.5"),
        "{failed}"
    );
}

#[test]
fn bad_adaptive_settings_are_refused_with_the_key_and_what_was_expected() {
    let cases = [
        (
            adaptive(1e-3, 0.2),
            "adaptive.min_step 0.2 s: expected at most the synchronisation step",
        ),
        (
            adaptive(0.0, 0.01),
            "adaptive.tolerance 0: expected a relative error in (0, 1)",
        ),
        (
            adaptive(1e-3, -1.0),
            "adaptive.min_step -1: expected a step > 0",
        ),
        (
            AdaptiveStep {
                displacement: Some(0.0),
                ..adaptive(1e-3, 0.01)
            },
            "adaptive.displacement 0: expected a local displacement error > 0 in metres",
        ),
        (
            AdaptiveStep {
                interface: false,
                ..adaptive(1e-3, 0.01)
            },
            "adaptive.interface = false: expected adaptive.displacement",
        ),
        (
            AdaptiveStep {
                calm_steps: 0,
                ..adaptive(1e-3, 0.01)
            },
            "adaptive.calm_steps 0: expected at least 1",
        ),
    ];
    for (settings, expected) in cases {
        let error = fragile(true, Some(settings)).err().expect("refused");
        assert!(error.contains(expected), "{error}");
    }
    let error = fragile(false, Some(adaptive(1e-3, 0.01)))
        .err()
        .expect("refused");
    assert!(
        error.contains("the adaptive step repeats steps, but unit `fragile` cannot roll back"),
        "{error}"
    );
    let mut fixed_step = Mock::new(Behaviour::Fragile, true);
    fixed_step.description.capabilities.variable_step = false;
    let error = fragile_unit(fixed_step, Some(adaptive(1e-3, 0.01)))
        .err()
        .expect("refused");
    assert!(
        error.contains("unit `fragile` cannot take a variable step"),
        "{error}"
    );
    // 0.1 s halved down to 1e-9 s leaves whole nanoseconds after a few halvings only.
    let error = fragile(true, Some(adaptive(1e-3, 1e-9)))
        .err()
        .expect("refused");
    assert!(
        error.contains("not a whole number of nanoseconds"),
        "{error}"
    );
}

#[test]
fn a_step_whose_iteration_does_not_converge_is_repeated_shorter_and_leaves_no_residual() {
    let stiff = || Mock::new(Behaviour::Stiff, true);
    let mut system = System::new();
    system
        .add_unit("one", Box::new(stiff()))
        .and(system.add_unit("two", Box::new(stiff())))
        .and(system.connect("two.y", "one.u", Link::default()))
        .and(system.connect("one.y", "two.u", Link::default()))
        .expect("the loop");
    let mut settings = MasterSettings::new(Scheme::IterativeGaussSeidel);
    settings.max_iterations = 30;
    // Its fixed point moves with the step: judged by failures alone (the
    // units give no estimate of their own).
    settings.adaptive = Some(AdaptiveStep {
        calm_steps: 2,
        interface: false,
        displacement: Some(1.0),
        ..adaptive(1e-3, STEP / 16.0)
    });
    let step = Time::from_secs(STEP).expect("a step");
    let mut master = Master::new(system, settings, step).expect("a master");
    master.initialize(Time::ZERO).expect("initialised");
    for _ in 0..10 {
        master.step().expect("the adaptive step gets through");
    }
    let counters = master.counters();
    let sizes = counters.adaptive.clone().expect("adaptive counters");
    eprintln!("{sizes:?}, largest residual {}", counters.max_residual);
    assert!(sizes.failed > 0, "{sizes:?}");
    // Only 12.5 ms and 6.25 ms converge: (h / 20 ms)^2 < 1.
    assert_eq!(sizes.accepted[..3].iter().sum::<u64>(), 0, "{sizes:?}");
    assert!(counters.max_residual <= 1.0, "{}", counters.max_residual);
}
