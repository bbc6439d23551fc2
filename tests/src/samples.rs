//! One sample unit per registry kind (and per kind a structure's sections
//! become), configured as an example scene's master settles it or from an
//! inline parameter table: what the contract tests drive.

use crate::{fmu, load};
use slender_fmi::export::ExportConfig;
use slender_scene::export::{ExportedUnit, SceneExport};
use slender_units::{Driver, Time};
use std::collections::BTreeMap;
use std::path::Path;

/// A unit of an example scene, configured as the scene's master settles it.
pub fn from_scene(scene: &str, unit: &str) -> ExportConfig {
    ExportConfig::from_scene(&load(scene), unit).unwrap_or_else(|e| panic!("{scene}: {e}"))
}

/// A unit from an inline parameter table, started with zero inputs.
pub fn inline(kind: &str, parameters: &str) -> ExportConfig {
    ExportConfig {
        name: kind.into(),
        kind: kind.into(),
        effects: Vec::new(),
        hold: None,
        inputs: BTreeMap::new(),
        parameters: parameters.parse().expect("parameter table"),
        start_time: 0.0,
        stop_time: 1.0,
        step: 0.01,
        guid: String::new(),
    }
}

/// A 3D line with a coupled velocity end, seabed friction, a current and
/// waves: every switch of `line3d` on.
pub const LINE3D_SAMPLE: &str = r#"
length = 60.0
elements = 12
axial_stiffness = 1e8
bending_stiffness = 1e4
mass_per_length = 20.0
submerged_weight = 150.0
diameter = 0.1
drag_normal = 1.2
drag_tangential = 0.01
added_mass_normal = 1.0
start = { position = [0.0, 0.0, -30.0] }
end = { position = [40.0, 5.0, -2.0], condition = "velocity" }
seabed = { depth = 30.0, stiffness = 1e6, damping = 1e3, friction_axial = 0.5, friction_lateral = 0.8 }
current = [{ depth = 0.0, speed = 0.5, heading_deg = 60.0 }, { depth = 30.0, speed = 0.1, heading_deg = 20.0 }]
waves = { sines = [{ amplitude = 1.0, angular_frequency = 0.8 }], heading_deg = 30.0, water_depth = 30.0 }
"#;

/// A hanging line with every effect on: weight, drag in a current, added mass,
/// Rayleigh damping, contact, a coupled velocity and a coupled force.
pub const NONLINEAR_SAMPLE: &str = r#"
segments = [{ length = 10.0, angle_deg = -60.0, elements = 8, axial_stiffness = 1e7, bending_stiffness = 1e3, mass_per_length = 10.0, submerged_weight = 50.0, diameter = 0.1, drag_normal = 1.0, drag_tangential = 0.1, added_mass_normal = 1.0 }]
ends.start = { kind = "pinned", x = "velocity" }
ends.end = { z = { force = "input" } }
current = { z = [-20.0, 0.0], velocity = [0.0, 0.5] }
contact = { method = { kind = "penalty", penalty = 1e5 }, surface = { shape = { kind = "flat", height = -8.5 } } }
stinger = { method = { kind = "augmented_lagrangian", penalty = 1e5 }, surface = { shape = { kind = "rollers", positions = [2.0], tops = [-3.44], radius = 0.3 } } }
rayleigh_stiffness = 0.001
stations = [5.0]
"#;

/// A floater on two fairleads, its centre of gravity off the reference,
/// moving and damped (linear and quadratic).
pub const BODY_SAMPLE: &str = r#"
mass = 2e6
inertia = [3e8, 4e8, 1e8]
centre_of_gravity = [0.5, 0.0, -20.0]
displaced_volume = 2100.0
hydrostatic_stiffness = [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 3e5, 0, 0, 0], [0, 0, 0, 2e8, 0, 0], [0, 0, 0, 0, 2e8, 0], [0, 0, 0, 0, 0, 0]]
additional_stiffness = [[5e4, 0, 0, 0, 0, 0], [0, 5e4, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 1e7]]
added_mass = [[1e6, 0, 0, 0, -5e6, 0], [0, 1e6, 0, 5e6, 0, 0], [0, 0, 1e5, 0, 0, 0], [0, 5e6, 0, 1e8, 0, 0], [-5e6, 0, 0, 0, 1e8, 0], [0, 0, 0, 0, 0, 1e6]]
damping_linear = [[1e4, 0, 0, 0, 0, 0], [0, 1e4, 0, 0, 0, 0], [0, 0, 1e4, 0, 0, 0], [0, 0, 0, 1e6, 0, 0], [0, 0, 0, 0, 1e6, 0], [0, 0, 0, 0, 0, 1e6]]
damping_quadratic = [[1e5, 0, 0, 0, 0, 0], [0, 1e5, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]
initial_offset = [2.0, -1.0, 0.3, 0.02, 0.03, 0.1]
initial_velocity = [0.1, 0.0, 0.0, 0.0, 0.01, 0.0]
fairleads = [{ name = "a", position = [5.0, 0.0, -30.0] }, { name = "b", position = [-2.5, 4.3, -30.0] }]
"#;

/// The 3D line sample linearised about its statics.
fn line3d_linear() -> String {
    format!("{LINE3D_SAMPLE}linear = true\n")
}

/// The nonlinear sample linearised about its start (`linear = true`; no
/// stinger, which a linear section refuses).
pub fn linear_sample() -> String {
    let without_stinger: Vec<&str> = NONLINEAR_SAMPLE
        .lines()
        .filter(|l| !l.starts_with("stinger"))
        .collect();
    format!("{}\nlinear = true\n", without_stinger.join("\n"))
}

/// The nonlinear sample reduced about its start (`reduced_modes = 4`: four
/// modes, the attachment vector of its loaded end, the modal derivatives and
/// the constraint modes of its held ends; no stinger, whose augmented
/// Lagrangian a reduced section refuses).
pub fn reduced_sample() -> String {
    let without_stinger: Vec<&str> = NONLINEAR_SAMPLE
        .lines()
        .filter(|l| !l.starts_with("stinger"))
        .collect();
    format!("{}\nreduced_modes = 4\n", without_stinger.join("\n"))
}

/// The reduced sample with its forces sampled after a training window of
/// 30 ms (`reduced_sampling`): three steps on every element, then on the
/// trained sample.
pub fn sampled_sample() -> String {
    format!(
        "{}reduced_sampling = {{ training = 0.03 }}\n",
        reduced_sample()
    )
}

/// One sample per registry kind (an FMU sample needs a folder to export into).
pub fn samples(dir: &Path) -> Vec<(&'static str, ExportConfig)> {
    let exported = fmu::export("examples/b3_force_displacement.toml", "b", dir);
    let fmu_table = format!("file = {:?}", exported.display().to_string());
    vec![
        (
            "cable",
            from_scene("examples/truncation_substructured.toml", "n"),
        ),
        (
            "beam",
            from_scene("examples/pipe_span_coupling.toml", "upper"),
        ),
        ("nonlinear", inline("nonlinear", NONLINEAR_SAMPLE)),
        ("line3d", from_scene("examples/riser_3d.toml", "riser")),
        ("line3d coupled", inline("line3d", LINE3D_SAMPLE)),
        ("line3d linear", inline("line3d", &line3d_linear())),
        ("catenary3d", inline("catenary3d", LINE3D_SAMPLE)),
        ("body", inline("body", BODY_SAMPLE)),
        ("nonlinear linear", inline("nonlinear", &linear_sample())),
        ("nonlinear reduced", inline("nonlinear", &reduced_sample())),
        ("nonlinear sampled", inline("nonlinear", &sampled_sample())),
        (
            "span",
            inline(
                "span",
                "flexural_rigidity = 1e4\nmass_per_length = 1e2\ndamping_per_length = 5.0\nlength = 10.0\norder = 8",
            ),
        ),
        (
            "span_coupling",
            from_scene("examples/pipe_span_coupling.toml", "span"),
        ),
        (
            "touchdown_estimate",
            from_scene("examples/pipe_static_contact.toml", "estimate"),
        ),
        (
            "characteristic_load",
            from_scene("examples/truncation_substructured.toml", "load"),
        ),
        (
            "signal",
            inline(
                "signal",
                "quantity = \"rotation\"\noffset = 0.1\nsines = [{ amplitude = 0.01, angular_frequency = 2.0 }]\nfade_in = { shape = \"smoothstep\", time = 1.0 }\nsteps = [{ time = 0.5, size = 0.02 }]",
            ),
        ),
        (
            "artefact",
            from_scene("examples/truncation_table2.toml", "sensor"),
        ),
        (
            "oscillator",
            from_scene("examples/b1_two_masses.toml", "left"),
        ),
        (
            "reduced",
            from_scene("examples/seed002_frame_reduced.toml", "reduced"),
        ),
        (
            "delay_compensation",
            from_scene("examples/hybrid_oscillator.toml", "compensation_x"),
        ),
        ("fmu", inline("fmu", &fmu_table)),
        // The units a structure's sections become.
    ]
    .into_iter()
    .chain(section_samples())
    .chain([
        (
            "loop_linear_pair",
            from_scene("examples/b6_algebraic_loop.toml", "pair"),
        ),
        (
            "loop_sphere",
            from_scene("examples/b6_algebraic_loop.toml", "sphere"),
        ),
    ])
    .collect()
}

/// Samples of the units a structure's sections are written as.
pub fn section_samples() -> Vec<(&'static str, ExportConfig)> {
    vec![
        (
            "static_section",
            inline(
                "static_section",
                "stiffness = [[-2.7e7, 100.0, -30.0], [3.0, -2.0e6, 2.7e6], [-30.0, 2.5e6, -7.8e6]]\nforce = [-8.2e4, 5.8, -14.7]\nstart_stiffness = [[2.7e7, -115.0, 29.0], [-2.2e3, 0.01, 0.0]]\nstart_force = [8.2e4, -1.0e3]",
            ),
        ),
        (
            // Taking force at its end and holding the section above, with its
            // static touchdown estimate.
            "static_section",
            inline(
                "static_section",
                "stiffness = [[-2.7e7, 100.0, -30.0], [3.0, -2.0e6, 2.7e6], [-30.0, 2.5e6, -7.8e6]]\nforce = [-8.2e4, 5.8, -14.7]\nforce_input = true\nquantities = [{ name = \"touchdown\", unit = \"m\", value = 126.0, gradient = [1.0e2, -20.0, 3.0] }]",
            ),
        ),
        (
            // The S-lay's suspended span as a beam about its chord.
            "chord",
            from_scene("examples/structure_slay_fidelity.toml", "pipe_suspended"),
        ),
        (
            // A span about its chord (the transfer matrix inside): its step
            // Jacobian comes through the inner model's.
            "chord",
            inline(
                "chord",
                "model = \"span\"\nmoving = \"start\"\nstart = [0.0, 0.0]\nend = [48.0, 14.0]\nweight = 9.0e3\nweight_at = [24.0, 7.0]\nloaded_end_displacement = [0.0, 0.0, 0.0]\nflexural_rigidity = 1.0e7\nmass_per_length = 150.0\ndamping_per_length = 20.0\ntension = 1.0e5\norder = 16\naxial_stiffness = 1.0e6\naxial_mass = 100.0",
            ),
        ),
        (
            // Loaded at its cut, with attachment vectors and end forces.
            "reduced",
            from_scene("examples/structure_frame_reduced.toml", "frame_corner"),
        ),
        (
            // The same on a linear basis (its step Jacobian by the
            // tangent-linear central-difference sub-steps)...
            "reduced",
            reduced_corner("central_difference"),
        ),
        (
            // ... and by the trapezoidal rule's Newton matrix.
            "reduced",
            reduced_corner("trapezoidal"),
        ),
    ]
}

/// The reduced corner of the frame structure on a linear basis (3 modes and
/// their derivatives), stepped by `integrator`.
fn reduced_corner(integrator: &str) -> ExportConfig {
    let mut config = from_scene("examples/structure_frame_reduced.toml", "frame_corner");
    let p = &mut config.parameters;
    p.insert("modes".into(), toml::Value::Integer(3));
    p.insert("derivatives".into(), toml::Value::String("linear".into()));
    p.insert("integrator".into(), toml::Value::String(integrator.into()));
    config
}

/// The start inputs of a sample, in port order.
pub fn start_inputs(config: &ExportConfig, driver: &Driver) -> Vec<f64> {
    driver
        .description()
        .inputs
        .iter()
        .map(|p| config.inputs.get(&p.name).copied().unwrap_or(0.0))
        .collect()
}

/// Inputs for step `k`: the start inputs, nudged a little.
pub fn inputs_at(start: &[f64], k: i64) -> Vec<f64> {
    start
        .iter()
        .map(|u| u + 1e-3 * k as f64 * u.abs().max(1.0))
        .collect()
}

/// A driver of the sample, initialised and stepped `steps` times.
pub fn started(config: &ExportConfig, steps: i64) -> (Driver, Vec<f64>, Time) {
    let mut driver = config
        .driver()
        .unwrap_or_else(|e| panic!("{}: {e}", config.kind));
    let start = start_inputs(config, &driver);
    let h = Time::from_secs(config.step).expect("step");
    driver.set_inputs(&start).unwrap();
    driver
        .initialize(Time::ZERO)
        .unwrap_or_else(|e| panic!("{}: initialize: {e}", config.kind));
    for k in 0..steps {
        driver.set_inputs(&inputs_at(&start, k + 1)).unwrap();
        driver
            .do_step(h * k, h)
            .unwrap_or_else(|e| panic!("{}: step {k}: {e}", config.kind));
    }
    (driver, start, h)
}

/// Outputs after one step from `slot` over `(t, h)` with end inputs `inputs`.
pub fn outputs_after(
    driver: &mut Driver,
    slot: &slender_units::DriverSlot,
    (t, h): (Time, Time),
    inputs: &[f64],
) -> Vec<f64> {
    driver.restore(slot).unwrap();
    driver.set_inputs(inputs).unwrap();
    driver.do_step(t, h).unwrap();
    let mut out = vec![0.0; driver.description().outputs.len()];
    driver.outputs(&mut out).unwrap();
    out
}

/// A sample stepped three times, saved at the start of its fourth step, and
/// that step taken with `inputs` (outputs `base`): where the contract tests
/// of a step's derivatives start.
pub struct SteppedSample {
    /// The sample's name (`samples`).
    pub kind: &'static str,
    /// Its driver, after the fourth step.
    pub driver: Driver,
    /// Its state at the fourth step's start.
    pub slot: slender_units::DriverSlot,
    /// The fourth step's start and length.
    pub step: (Time, Time),
    /// The fourth step's end inputs.
    pub inputs: Vec<f64>,
    /// The outputs after it.
    pub base: Vec<f64>,
}

/// Every sample whose capabilities `declares` accepts, as [`SteppedSample`].
pub fn stepped_samples(
    dir: &Path,
    declares: impl Fn(&slender_units::Capabilities) -> bool,
) -> Vec<SteppedSample> {
    let mut stepped = Vec::new();
    for (kind, config) in samples(dir) {
        let (mut driver, start, h) = started(&config, 3);
        if !declares(&driver.description().capabilities) {
            continue;
        }
        let step = (h * 3, h);
        let inputs = inputs_at(&start, 4);
        let mut slot = slender_units::DriverSlot::new();
        driver.save(&mut slot).unwrap();
        let base = outputs_after(&mut driver, &slot, step, &inputs);
        stepped.push(SteppedSample {
            kind,
            driver,
            slot,
            step,
            inputs,
            base,
        });
    }
    stepped
}
