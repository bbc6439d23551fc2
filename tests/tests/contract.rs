//! One contract test over every unit kind in the registry: byte-equal rollback
//! (outputs and serialised state after restore and repeat), no allocation on
//! rollback, refusal of wrong input counts, non-finite inputs and calls out of
//! order, and determinism (the same configuration gives the same bytes).
//!
//! Each kind is driven from a sample: a unit of an example scene (with the start
//! inputs its master settles on) or an inline parameter table. A kind added to the
//! registry without a sample fails `every_registry_kind_has_a_contract_sample`.

use slender_fmi::export::ExportConfig;
use slender_scene::export::SceneExport;
use slender_scene::kinds::KINDS;
use slender_tests::{fmu, load};
use slender_units::{Driver, DriverSlot, Time, UnitError};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::collections::BTreeMap;
use std::path::Path;

/// Counts this thread's allocations (tests run on several threads).
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded to the system allocator with the caller's layout.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

/// A unit of an example scene, configured as the scene's master settles it.
fn from_scene(scene: &str, unit: &str) -> ExportConfig {
    ExportConfig::from_scene(&load(scene), unit).unwrap_or_else(|e| panic!("{scene}: {e}"))
}

/// A unit from an inline parameter table, started with zero inputs.
fn inline(kind: &str, parameters: &str) -> ExportConfig {
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

/// A hanging line with every effect on: weight, drag in a current, added mass,
/// Rayleigh damping, contact, a coupled velocity and a coupled force.
const NONLINEAR_SAMPLE: &str = r#"
segments = [{ length = 10.0, angle = -60.0, elements = 8, axial_stiffness = 1e7, bending_stiffness = 1e3, mass_per_length = 10.0, submerged_weight = 50.0, diameter = 0.1, drag_normal = 1.0, drag_tangential = 0.1, added_mass_normal = 1.0 }]
ends.start = { kind = "pinned", x = "velocity" }
ends.end = { z = { force = "input" } }
current = { z = [-20.0, 0.0], velocity = [0.0, 0.5] }
contact = { method = { kind = "penalty", penalty = 1e5 }, surface = { shape = { kind = "flat", height = -8.5 } } }
stinger = { method = { kind = "augmented_lagrangian", penalty = 1e5 }, surface = { shape = { kind = "rollers", positions = [2.0], tops = [-3.44], radius = 0.3 } } }
rayleigh_stiffness = 0.001
stations = [5.0]
"#;

/// One sample per registry kind (an FMU sample needs a folder to export into).
fn samples(dir: &Path) -> Vec<(&'static str, ExportConfig)> {
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
fn section_samples() -> Vec<(&'static str, ExportConfig)> {
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
            // Loaded at its cut, with attachment vectors and end forces.
            "reduced",
            from_scene("examples/structure_frame_reduced.toml", "frame_corner"),
        ),
    ]
}

/// The start inputs of a sample, in port order.
fn start_inputs(config: &ExportConfig, driver: &Driver) -> Vec<f64> {
    driver
        .description()
        .inputs
        .iter()
        .map(|p| config.inputs.get(&p.name).copied().unwrap_or(0.0))
        .collect()
}

/// Inputs for step `k`: the start inputs, nudged a little.
fn inputs_at(start: &[f64], k: i64) -> Vec<f64> {
    start
        .iter()
        .map(|u| u + 1e-3 * k as f64 * u.abs().max(1.0))
        .collect()
}

/// A driver of the sample, initialised and stepped `steps` times.
fn started(config: &ExportConfig, steps: i64) -> (Driver, Vec<f64>, Time) {
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

/// Steps once from `t` with `inputs`; the outputs' bits and the serialised state.
fn step_bits(driver: &mut Driver, t: Time, h: Time, inputs: &[f64]) -> (Vec<u64>, Vec<u8>) {
    driver.set_inputs(inputs).unwrap();
    driver.do_step(t, h).unwrap();
    let mut out = vec![0.0; driver.description().outputs.len()];
    driver.outputs(&mut out).unwrap();
    let mut slot = DriverSlot::new();
    driver.save(&mut slot).unwrap();
    let state = slot.to_bytes().unwrap();
    (out.iter().map(|v| v.to_bits()).collect(), state)
}

#[test]
fn every_registry_kind_has_a_contract_sample() {
    let dir = tempfile::tempdir().unwrap();
    let covered: Vec<&str> = samples(dir.path()).iter().map(|(k, _)| *k).collect();
    for kind in KINDS {
        assert!(
            covered.contains(&kind.name),
            "kind `{}` has no sample in the contract test",
            kind.name
        );
    }
    for (kind, config) in samples(dir.path()) {
        assert_eq!(
            kind, config.kind,
            "sample for `{kind}` builds a `{}`",
            config.kind
        );
    }
}

#[test]
fn rollback_repeats_a_step_byte_for_byte_for_every_kind() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let (mut driver, start, h) = started(&config, 3);
        let t = h * 3;
        let mut slot = DriverSlot::new();
        driver.save(&mut slot).unwrap();
        let first = step_bits(&mut driver, t, h, &inputs_at(&start, 4));
        driver.restore(&slot).unwrap();
        step_bits(&mut driver, t, h, &inputs_at(&start, 9));
        driver.restore(&slot).unwrap();
        let repeat = step_bits(&mut driver, t, h, &inputs_at(&start, 4));
        assert_eq!(
            first.0, repeat.0,
            "{kind}: outputs of the repeated step differ"
        );
        // An FMU's serialised state is the FMU's own (a handle here): compared
        // through its outputs only.
        if kind != "fmu" {
            assert_eq!(first.1, repeat.1, "{kind}: state after the repeat differs");
        }
    }
}

#[test]
fn rollback_allocates_nothing_once_the_slot_is_filled() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let (mut driver, start, h) = started(&config, 3);
        let mut slot = DriverSlot::new();
        let mut cycle = |driver: &mut Driver, k: i64| {
            driver.save(&mut slot).unwrap();
            driver.set_inputs(&inputs_at(&start, 4 + k)).unwrap();
            driver.do_step(h * 3, h).unwrap();
            let before = allocations();
            driver.restore(&slot).unwrap();
            driver.save(&mut slot).unwrap();
            allocations() - before
        };
        // The first cycles size the slot and the unit's buffers.
        cycle(&mut driver, 0);
        cycle(&mut driver, 1);
        let counted = cycle(&mut driver, 2);
        assert_eq!(
            counted, 0,
            "{kind}: restore + save allocated {counted} times"
        );
    }
}

#[test]
fn wrong_input_counts_non_finite_inputs_and_calls_out_of_order_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let mut driver = config.driver().unwrap();
        let n = driver.description().inputs.len();
        let h = Time::from_secs(config.step).unwrap();
        let e = driver.do_step(Time::ZERO, h).unwrap_err();
        assert!(
            matches!(e, UnitError::State(_)),
            "{kind}: step before initialize: {e}"
        );
        let e = driver.restore(&DriverSlot::new()).unwrap_err();
        assert!(
            matches!(e, UnitError::State(_)),
            "{kind}: restore before save: {e}"
        );
        assert!(driver.modes(1).is_err(), "{kind}: modes before initialize");
        let e = driver.set_inputs(&vec![0.0; n + 1]).unwrap_err();
        assert!(
            matches!(e, UnitError::InputCount { expected, got } if expected == n && got == n + 1),
            "{kind}: {e}"
        );
        let mut out = vec![0.0; driver.description().outputs.len() + 1];
        assert!(driver.outputs(&mut out).is_err(), "{kind}: outputs buffer");
        if n > 0 {
            let mut bad = start_inputs(&config, &driver);
            bad[n - 1] = f64::NAN;
            let e = driver.set_inputs(&bad).unwrap_err();
            let port = &driver.description().inputs[n - 1].name;
            assert!(
                matches!(&e, UnitError::InvalidInput { port: p, .. } if p == port),
                "{kind}: {e}"
            );
        }
    }
}

#[test]
fn the_same_configuration_gives_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let run = || {
            let (mut driver, start, h) = started(&config, 5);
            step_bits(&mut driver, h * 5, h, &inputs_at(&start, 6))
        };
        let (a, b) = (run(), run());
        assert_eq!(a.0, b.0, "{kind}: outputs differ between two builds");
        if kind != "fmu" {
            assert_eq!(a.1, b.1, "{kind}: states differ between two builds");
        }
    }
}
