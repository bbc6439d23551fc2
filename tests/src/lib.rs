//! Shared helpers of the workspace-level tests: loading scenes, running them in
//! memory, analytic and monolithic reference solutions of the coupling benchmarks.

use nalgebra::{DMatrix, DVector};
use slender_app::run::{RunOptions, run_scene};
use slender_coupling::settings::{Scheme, Solver};
use slender_scene::Scene;
use slender_units::integrators::newmark::LinearNewmark;
use std::path::{Path, PathBuf};

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The connections that neither start nor end at a port of `unit`.
pub fn links_away_from(links: &[toml::Value], unit: &str) -> Vec<toml::Value> {
    let prefix = format!("{unit}.");
    links
        .iter()
        .filter(|l| {
            let at = |end: &str| l[end].as_str().is_some_and(|p| p.starts_with(&prefix));
            !at("from") && !at("to")
        })
        .cloned()
        .collect()
}

/// A scene's units after `[structure]` is written out (by name, in order) and
/// its connections.
pub fn units_and_links(scene: &Scene) -> (Vec<(String, toml::Value)>, Vec<toml::Value>) {
    let t: toml::Table =
        toml::from_str(scene.source().expect("the expanded scene")).expect("the expanded scene");
    let units = t["units"]
        .as_array()
        .expect("units")
        .iter()
        .map(|u| (u["name"].as_str().expect("a name").to_owned(), u.clone()))
        .collect();
    (
        units,
        t["connections"].as_array().expect("connections").clone(),
    )
}

/// Loads a scene by path relative to the workspace root.
pub fn load(relative: &str) -> Scene {
    let path = root().join(relative);
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// An example's text with its motions' `fade_in` and its indicators' `from`
/// taken out: the mooring and S-lay examples as they were before they faded
/// their motions in, at full speed from t = 0. The tests of the cuts'
/// coupling and of a section's start keep that impulsive start: the harder
/// case for the iterations at a cut, and the one their figures were measured
/// on.
pub fn impulsive(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines().filter(|l| !l.starts_with("from = ")) {
        let mut rest = line;
        while let Some(at) = rest.find(", fade_in = ") {
            out.push_str(&rest[..at]);
            let value = &rest[at + ", fade_in = ".len()..];
            let end = value
                .find(|c: char| !(c.is_ascii_digit() || c == '.'))
                .unwrap_or(value.len());
            rest = &value[end..];
        }
        out.push_str(rest);
        out.push('\n');
    }
    out
}

/// Recorded time and signals of a run kept in memory.
pub struct Series {
    /// Recorded times (s).
    pub time: Vec<f64>,
    /// The signals' names.
    pub names: Vec<String>,
    /// One column per signal.
    pub columns: Vec<Vec<f64>>,
    /// The master's counters.
    pub counters: slender_coupling::counters::Counters,
    /// Why the run failed, when it did.
    pub error: Option<String>,
    /// The scene's indicators.
    pub indicators: Vec<slender_app::indicators::Indicator>,
    /// The run's warnings (the scene's advisories, the master's, the watch's).
    pub warnings: Vec<String>,
}

impl Series {
    /// The column of `name`.
    pub fn get(&self, name: &str) -> &[f64] {
        let i = self
            .names
            .iter()
            .position(|n| n == name)
            .unwrap_or_else(|| panic!("no recorded signal {name}"));
        &self.columns[i]
    }

    /// The last value of `name`.
    pub fn last(&self, name: &str) -> f64 {
        *self.get(name).last().expect("nothing recorded")
    }
}

/// Runs a scene in memory (nothing written).
pub fn run(scene: &Scene) -> Series {
    let result = run_scene(
        scene,
        &RunOptions {
            output_dir: None,
            progress: false,
            realtime: false,
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    Series {
        time: result.recorder.time.clone(),
        names: result.recorder.names.clone(),
        columns: result.recorder.columns.clone(),
        counters: result.summary.counters,
        error: result.summary.error,
        indicators: result.summary.indicators,
        warnings: result.summary.warnings,
    }
}

/// Runs `scene` with another scheme, acceleration and step.
pub fn run_with(scene: &mut Scene, scheme: Scheme, solver: impl Into<Solver>, step: f64) -> Series {
    scene.spec.master.scheme = scheme;
    scene.spec.master.set_solver(solver);
    scene.set_step(step).unwrap_or_else(|e| panic!("{e}"));
    run(scene)
}

/// Every scheme, without acceleration.
pub const SCHEMES: [Scheme; 4] = [
    Scheme::Jacobi,
    Scheme::GaussSeidel,
    Scheme::IterativeJacobi,
    Scheme::IterativeGaussSeidel,
];

/// B1 exact solution (u1, u2) at time t: m = 1, k_outer = 4 pi^2, k_middle = 16 pi^2,
/// u0 = (1, 0), v0 = 0; modes at 2 pi and 6 pi rad/s.
pub fn b1_exact(t: f64) -> (f64, f64) {
    let pi = std::f64::consts::PI;
    let (a, b) = ((2.0 * pi * t).cos(), (6.0 * pi * t).cos());
    (0.5 * (a + b), 0.5 * (a - b))
}

/// A two-mass chain: masses, springs and dampers to ground, coupling spring-damper.
#[derive(Clone, Copy, Debug)]
pub struct Chain {
    /// Masses (kg).
    pub m: [f64; 2],
    /// Springs to ground (N/m).
    pub k: [f64; 2],
    /// Dampers to ground (N s/m).
    pub c: [f64; 2],
    /// Coupling spring (N/m).
    pub kc: f64,
    /// Coupling damper (N s/m).
    pub dc: f64,
    /// Start displacements (m).
    pub u0: [f64; 2],
    /// Start velocities (m/s).
    pub v0: [f64; 2],
}

/// Benchmark B3's two masses (force/displacement coupling, stiff coupling
/// spring kc = 3e4 N/m), as `examples/b3_force_displacement.toml` has them.
pub fn b3_chain() -> Chain {
    Chain {
        m: [1.0, 1.0],
        k: [100.0, 100.0],
        c: [1.0, 1.0],
        kc: 3.0e4,
        dc: 10.0,
        u0: [0.01, 0.0],
        v0: [0.0, 0.0],
    }
}

impl Chain {
    /// Displacements and velocities `[u1, u2, v1, v2]` after each of `steps` steps of
    /// the monolithic system, integrated with the same Newmark scheme as the units.
    pub fn monolithic(&self, h: f64, steps: usize) -> Vec<[f64; 4]> {
        let m = DMatrix::from_diagonal(&DVector::from_row_slice(&self.m));
        let k = DMatrix::from_row_slice(
            2,
            2,
            &[self.k[0] + self.kc, -self.kc, -self.kc, self.k[1] + self.kc],
        );
        let c = DMatrix::from_row_slice(
            2,
            2,
            &[self.c[0] + self.dc, -self.dc, -self.dc, self.c[1] + self.dc],
        );
        let mut integrator = LinearNewmark::new(m, c, k, h).expect("valid chain");
        let f = DVector::zeros(2);
        let mut state = integrator
            .initial_state(
                DVector::from_row_slice(&self.u0),
                DVector::from_row_slice(&self.v0),
                &f,
            )
            .expect("valid chain");
        (0..steps)
            .map(|_| {
                integrator.step(&mut state, &f);
                [state.u[0], state.u[1], state.v[0], state.v[1]]
            })
            .collect()
    }

    /// Total mechanical energy (J) of state `[u1, u2, v1, v2]`.
    pub fn energy(&self, s: [f64; 4]) -> f64 {
        0.5 * (self.m[0] * s[2] * s[2] + self.m[1] * s[3] * s[3])
            + 0.5 * (self.k[0] * s[0] * s[0] + self.k[1] * s[1] * s[1])
            + 0.5 * self.kc * (s[0] - s[1]).powi(2)
    }
}

/// Root mean square of a series.
pub fn rms(x: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = x.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    (sum / n.max(1) as f64).sqrt()
}

/// Observed order of convergence from errors at steps h and h/2.
pub fn order(error_h: f64, error_half: f64) -> f64 {
    (error_h / error_half).log2()
}

/// A scriptable test unit: integrates its input `u` (`y' = u`, exact for the
/// hold it is given), echoes the input it saw on `u_seen` (direct feedthrough), and
/// misbehaves on cue.
pub mod buoy;
pub mod edited;
pub mod elf;
pub mod exact;
pub mod samples;

/// A unit that misbehaves on cue, for the master's failure paths.
pub mod probe {
    use slender_units::{
        Capabilities, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
        UnitError,
    };

    /// What the probe does at a step, decided from the step's end time (s) and the
    /// number of `do_step` calls so far (rollbacks do not reset it).
    pub enum Act {
        /// Steps normally.
        Behave,
        /// Fails with this message.
        Fail(&'static str),
        /// Outputs NaN.
        ProduceNan,
    }

    #[derive(Clone, serde::Serialize, serde::Deserialize)]
    struct State {
        y: f64,
    }

    /// The probe: one output following its input, scripted by [`Act`].
    pub struct Probe {
        description: UnitDescription,
        state: State,
        calls: u64,
        nan: bool,
        script: Box<dyn Fn(f64, u64) -> Act + Send>,
    }

    impl Probe {
        /// A well-behaved probe.
        pub fn new(rollback: bool) -> Probe {
            Probe::scripted(rollback, |_, _| Act::Behave)
        }

        /// A probe following `script`.
        pub fn scripted(
            rollback: bool,
            script: impl Fn(f64, u64) -> Act + Send + 'static,
        ) -> Probe {
            Probe {
                description: UnitDescription {
                    kind: "probe".into(),
                    inputs: vec![Port::input("u", PortKind::Generic)],
                    outputs: vec![
                        Port::output("y", PortKind::Generic),
                        Port::output("u_seen", PortKind::Generic).with_feedthrough(&[0]),
                    ],
                    capabilities: Capabilities {
                        rollback,
                        ..Capabilities::default()
                    },
                },
                state: State { y: 0.0 },
                calls: 0,
                nan: false,
                script: Box::new(script),
            }
        }
    }

    impl Unit for Probe {
        fn description(&self) -> &UnitDescription {
            &self.description
        }
        fn initialize(&mut self, _t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
            self.state.y = 0.0;
            Ok(())
        }
        fn do_step(&mut self, t: Time, h: Time, i: Inputs<'_>) -> Result<StepReport, UnitError> {
            self.calls += 1;
            match (self.script)((t + h).as_secs(), self.calls) {
                Act::Behave => {}
                Act::Fail(why) => return Err(UnitError::Numerical(why.into())),
                Act::ProduceNan => self.nan = true,
            }
            let h = h.as_secs();
            self.state.y += h * 0.5 * (i.at(0, 0.0) + i.at(0, 1.0));
            Ok(StepReport::default())
        }
        fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
            out[0] = if self.nan { f64::NAN } else { self.state.y };
            out[1] = inputs.end()[0];
        }
        fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
            if !self.description.capabilities.rollback {
                return Err(UnitError::Unsupported("rollback".into()));
            }
            slot.store(&self.state);
            Ok(())
        }
        fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
            self.state = slot.load::<State>()?.into_owned();
            Ok(())
        }
    }
}

/// The published reference figures (copied from the project's shared reference).
pub fn published() -> toml::Table {
    let text = std::fs::read_to_string(root().join("tests/reference/published.toml"))
        .expect("reference file");
    text.parse().expect("reference parses")
}

pub mod fmu;

/// Seed 002's structures ([`slender_units::nonlinear::seed002`]) and what
/// the tests do with them: a section made from their text, random states.
pub mod seed002 {
    use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
    use slender_units::{Driver, Time};

    pub use slender_units::nonlinear::seed002::{cable, frame, steel};

    /// The section of `text`, initialised at t = 0.
    pub fn section(text: &str) -> Driver<NonlinearSection> {
        let params: NonlinearParams = toml::from_str(text).expect("parameters parse");
        let mut driver = Driver::new(NonlinearSection::new(params).expect("valid parameters"));
        driver.initialize(Time::ZERO).expect("initialize");
        driver
    }
}

/// 500 m of the steel catenary riser's pipe hanging between a pinned foot at
/// (0, -300) and a pinned top 50 m back from the stress-free end, started
/// from its statics: `parameters` adds unit parameters (e.g. `linear = true`),
/// `heave` is the top's z displacement table, `drag` the normal drag
/// coefficient, `output` the `[output]` body.
pub fn hanging_pipe(
    (duration, parameters): (f64, &str),
    (heave, drag): (&str, f64),
    output: &str,
) -> slender_scene::Scene {
    let text = hanging_pipe_text((duration, parameters), (heave, drag), output);
    slender_scene::Scene::parse(&root().join("hanging.toml"), text).expect("the hanging pipe")
}

/// The text of [`hanging_pipe`]'s scene (to test what its parsing refuses).
pub fn hanging_pipe_text(
    (duration, parameters): (f64, &str),
    (heave, drag): (&str, f64),
    output: &str,
) -> String {
    format!(
        r#"
title = "hanging steel pipe"
[simulation]
duration = {duration:?}
step = 0.05
[master]
scheme = "gauss_seidel"
[[units]]
name = "pipe"
kind = "nonlinear"
[units.parameters]
static_start = true
{parameters}
start_shape = "catenary"
start = [0.0, -300.0]
segments = [{{ length = 500.0, angle_deg = 37.0, elements = 50, axial_stiffness = 4.0631e9, bending_stiffness = 4.6937e7, mass_per_length = 154.08, submerged_weight = 683.05, diameter = 0.3239, drag_normal = {drag:?}, added_mass_normal = 1.0 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned", x = {{ displacement = -50.0 }}, z = {{ displacement = {heave} }} }}
integrator = {{ kind = "hht", alpha = 0.1 }}
[output]
{output}
"#
    )
}
