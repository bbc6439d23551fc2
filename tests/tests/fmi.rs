//! FMI 2.0 export and import without Python: exported units through slender's own
//! importer against the native units, scenes of exported FMUs against the native
//! scenes, every way an FMU can be wrong, the entry points' guards, and a
//! mutation fuzz of the model-description parser over a kept corpus.
//! (FMPy and pythonfmu cross-checks: fmi_python.rs.)

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use slender_fmi::export::ExportConfig;
use slender_fmi::model_description::{ModelDescription, Value, VariableCausality};
use slender_scene::export::{ExportedUnit, SceneExport};
use slender_tests::fmu::import;
use slender_tests::{fmu, load, root, run};
use slender_units::{Driver, Hold, Time, Unit};
use std::path::PathBuf;

fn temp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temporary folder")
}

#[test]
fn the_model_description_lists_ports_units_parameters_and_true_dependencies() {
    let dir = temp();
    let file = fmu::export("examples/b1_two_masses.toml", "left", dir.path());
    let unit = import(&file).unwrap();
    let md = unit.model_description();
    assert_eq!(md.fmi_version, "2.0");
    let cs = md.co_simulation.as_ref().unwrap();
    assert_eq!(cs.model_identifier, "slender_left");
    assert!(cs.can_get_and_set_fmu_state && cs.can_serialize_fmu_state);
    assert!(cs.can_handle_variable_communication_step_size && cs.can_interpolate_inputs);
    let var = |name: &str| md.variables.iter().find(|v| v.name == name).unwrap();
    assert_eq!(
        var("coupling_displacement").causality,
        VariableCausality::Input
    );
    assert_eq!(var("coupling_force").unit.as_deref(), Some("N"));
    assert_eq!(var("mass").value, Value::Real(Some(1.0)));
    assert_eq!(
        var("initial_displacement").causality,
        VariableCausality::Parameter
    );
    for unit_name in ["m", "m/s", "N"] {
        assert!(
            md.unit(unit_name).is_some(),
            "UnitDefinitions lack {unit_name}"
        );
    }
    // Displacement and velocity have no direct feedthrough; the coupling force
    // of B1's undamped spring follows the other end's displacement (variable 1)
    // only, not its velocity.
    let deps = |name: &str| {
        let index = md.variables.iter().position(|v| v.name == name).unwrap() + 1;
        md.outputs
            .iter()
            .find(|u| u.index == index)
            .unwrap()
            .dependencies
            .clone()
    };
    assert_eq!(deps("displacement"), Some(vec![]));
    assert_eq!(deps("coupling_force"), Some(vec![1]));
    let d = unit.description();
    assert!(d.capabilities.rollback);
    assert_eq!(d.outputs[2].depends_on, vec![0]);
    let de = md.default_experiment.as_ref().unwrap();
    assert_eq!((de.stop_time, de.step_size), (Some(1.0), Some(0.01)));
}

/// Drives a unit alone with a sine force and returns its outputs at every step.
fn drive<U: Unit>(unit: &mut Driver<U>, hold: Hold, steps: usize) -> Vec<Vec<f64>> {
    let h = Time::from_secs(0.01).unwrap();
    let force = |t: f64| 5.0 * (3.0 * t).sin() + 1.0;
    unit.set_hold(0, hold).unwrap();
    unit.set_inputs(&[force(0.0)]).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    let mut out = vec![0.0; unit.description().outputs.len()];
    let mut all = Vec::new();
    for n in 0..steps {
        let t = h * n as i64;
        unit.set_inputs(&[force((t + h).as_secs())]).unwrap();
        unit.do_step(t, h).unwrap();
        unit.outputs(&mut out).unwrap();
        all.push(out.clone());
    }
    all
}

#[test]
fn an_exported_unit_through_the_importer_matches_the_native_unit() {
    let dir = temp();
    let scene = load("examples/b3_force_displacement.toml");
    let config = ExportConfig::from_scene(&scene, "b").unwrap();
    let file = fmu::export("examples/b3_force_displacement.toml", "b", dir.path());
    // Zero-order hold: the value sent is the value held; bit-identical.
    let native = drive(&mut config.driver().unwrap(), Hold::ZeroOrder, 500);
    let through_fmi = drive(
        &mut Driver::new(import(&file).unwrap()),
        Hold::ZeroOrder,
        500,
    );
    assert_eq!(native, through_fmi);
    // Ramp hold: start value and slope cross the interface, the end value is
    // rebuilt as u + h du/dt; round-off only.
    let native = drive(&mut config.driver().unwrap(), Hold::Ramp, 500);
    let through_fmi = drive(&mut Driver::new(import(&file).unwrap()), Hold::Ramp, 500);
    let scale = native.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = native
        .iter()
        .flatten()
        .zip(through_fmi.iter().flatten())
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!("ramp hold: worst difference {worst:.2e} on a scale of {scale:.2e}");
    assert!(worst <= 1e-13 * scale, "{worst:e}");
}

/// A unit's step Jacobian after `steps` steps with zero-order held inputs
/// nudged from `start` (a driver that steps its unit once per call).
fn jacobian_after<U: Unit>(unit: &mut Driver<U>, start: &[f64], steps: i64) -> Vec<f64> {
    let h = Time::from_secs(0.01).unwrap();
    for p in 0..start.len() {
        unit.set_hold(p, Hold::ZeroOrder).unwrap();
    }
    unit.set_inputs(start).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    for k in 0..steps {
        let nudged: Vec<f64> = start
            .iter()
            .map(|u| u + 1e-3 * (k + 1) as f64 * u.abs().max(1.0))
            .collect();
        unit.set_inputs(&nudged).unwrap();
        unit.do_step(h * k, h).unwrap();
    }
    let d = unit.description();
    let mut jacobian = vec![0.0; d.outputs.len() * d.inputs.len()];
    unit.step_jacobian(&mut jacobian).unwrap();
    jacobian
}

#[test]
fn an_imported_fmu_gives_the_native_step_jacobian_through_slenders_step_derivative() {
    let dir = temp();
    for (scene, unit) in [
        ("examples/b1_two_masses.toml", "left"),
        ("examples/structure_mooring.toml", "line_upper"),
        ("examples/structure_slay_fidelity.toml", "pipe_suspended"),
    ] {
        let config = ExportConfig::from_scene(&load(scene), unit).unwrap();
        let file = fmu::export(scene, unit, dir.path());
        let md = slender_fmi::import::FmuUnit::load(
            &slender_fmi::import::FmuParams {
                file: file.clone(),
                start: Default::default(),
                preload: Vec::new(),
                logging: false,
            },
            std::path::Path::new("."),
        )
        .unwrap();
        let cs = md.model_description().co_simulation.clone().unwrap();
        let mut native = config.driver().unwrap();
        // The standard's derivative at an instant is declared where it is
        // zero (no feedthrough); the step Jacobian comes by the extension.
        assert_eq!(
            cs.provides_directional_derivative,
            !native.description().has_feedthrough(),
            "{unit}"
        );
        assert!(md.description().capabilities.step_jacobian, "{unit}");
        let start: Vec<f64> = native
            .description()
            .inputs
            .iter()
            .map(|p| config.inputs.get(&p.name).copied().unwrap_or(0.0))
            .collect();
        let own = jacobian_after(&mut native, &start, 5);
        let through_fmi = jacobian_after(&mut Driver::new(md), &start, 5);
        let given = own.iter().filter(|v| v.is_finite()).count();
        println!("{unit}: {given} of {} entries given", own.len());
        assert!(given > 0);
        for (a, b) in own.iter().zip(&through_fmi) {
            // Entries the unit gives cross the interface bit for bit; the
            // others (a section's stations) are refused, NaN on both sides.
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{unit}: {a} against {b}"
            );
        }
    }
    // A unit without a step Jacobian (the sensor artefact) says so through
    // the extension, though its binary exports it.
    let file = fmu::export("examples/truncation_table2.toml", "sensor", dir.path());
    let sensor = import(&file).unwrap();
    assert!(!sensor.description().capabilities.step_jacobian);
}

/// Largest difference between two runs' recorded signals, relative to each
/// signal's largest magnitude.
fn worst_relative_difference(a: &slender_tests::Series, b: &slender_tests::Series) -> f64 {
    assert_eq!(a.names, b.names);
    assert_eq!(a.time, b.time);
    a.columns
        .iter()
        .zip(&b.columns)
        .map(|(x, y)| {
            let scale = x.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
            x.iter()
                .zip(y)
                .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs() / scale))
        })
        .fold(0.0, f64::max)
}

#[test]
fn scenes_of_exported_fmus_match_the_native_scenes_with_rollback() {
    let mut rollbacks = 0;
    // (scene, bound on the relative difference, whether the iteration counts
    // must be equal).
    for (scene, bound, same_iterations) in [
        // Iterative Gauss-Seidel with rollback.
        ("examples/b1_two_masses.toml", 1e-13, true),
        // Aitken-accelerated, force/displacement coupling.
        ("examples/b3_force_displacement.toml", 1e-11, true),
        // Newton on an algebraic loop (solved at initialisation).
        ("examples/b6_algebraic_loop.toml", 1e-13, true),
        // Active truncation: four units, IQN-ILS, 200 s.
        ("examples/truncation_substructured.toml", 1e-11, true),
        // Beam sections and the 4x4 span; beam inputs that share a name with an
        // output are renamed `<name>_in` in the FMUs and the scene follows. Here
        // the ramp's round-off (u + h du/dt) tips 2 of 36 610 convergence checks
        // the other way, so the runs differ by what the master accepts: the
        // displacement tolerance, 1e-9 m on a 0.4 m peak (2.5e-9).
        ("examples/pipe_span_coupling.toml", 2.5e-9, false),
    ] {
        let dir = temp();
        let native = run(&load(scene));
        let wrapped = run(&fmu::wrapped(scene, dir.path()));
        assert!(native.error.is_none() && wrapped.error.is_none());
        let worst = worst_relative_difference(&native, &wrapped);
        println!(
            "{scene}: worst relative difference {worst:.2e}; iterations {} vs {}, rollbacks {} vs {}",
            native.counters.iterations,
            wrapped.counters.iterations,
            native.counters.rollbacks,
            wrapped.counters.rollbacks
        );
        assert!(worst <= bound, "{scene}: {worst:e}");
        if same_iterations {
            assert_eq!(native.counters.iterations, wrapped.counters.iterations);
            assert_eq!(native.counters.rollbacks, wrapped.counters.rollbacks);
        } else {
            let (a, b) = (native.counters.iterations, wrapped.counters.iterations);
            assert!(a.abs_diff(b) * 1000 <= a, "{scene}: {a} vs {b} iterations");
        }
        rollbacks += wrapped.counters.rollbacks;
    }
    assert!(rollbacks > 0, "no rollback exercised");
}

#[test]
fn a_failing_step_names_the_fmu_the_call_and_the_reason() {
    let dir = temp();
    let file = fmu::export("examples/b6_algebraic_loop.toml", "sphere", dir.path());
    let mut unit = Driver::new(import(&file).unwrap());
    unit.set_inputs(&[0.1, 0.1]).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    unit.set_inputs(&[100.0, 0.0]).unwrap();
    let h = Time::from_secs(0.1).unwrap();
    let e = unit.do_step(Time::ZERO, h).unwrap_err().to_string();
    assert!(
        e.contains("sphere.fmu") && e.contains("fmi2DoStep") && e.contains("fmi2Error"),
        "{e}"
    );
    assert!(
        e.contains("no real c"),
        "the FMU's logged reason is missing: {e}"
    );
}

#[test]
fn entry_points_reject_null_and_foreign_arguments_without_crashing() {
    use slender_fmi::ffi::*;
    use std::ptr::{null, null_mut};
    // SAFETY: the calls are made with arguments FMI forbids, which is the point:
    // the entry points must refuse them with fmi2Error instead of crashing.
    unsafe {
        assert_eq!(slender_fmu::fmi2DoStep(null_mut(), 0.0, 0.1, 0), FMI2_ERROR);
        assert_eq!(slender_fmu::fmi2Terminate(null_mut()), FMI2_ERROR);
        assert_eq!(
            slender_fmu::fmi2GetReal(null_mut(), null(), 1, null_mut()),
            FMI2_ERROR
        );
        slender_fmu::fmi2FreeInstance(null_mut());
        let none = slender_fmu::fmi2Instantiate(
            c"x".as_ptr(),
            FMI2_CO_SIMULATION,
            c"{}".as_ptr(),
            c"file:///nonexistent".as_ptr(),
            null(),
            0,
            0,
        );
        assert!(none.is_null());
        let callbacks = fmi2CallbackFunctions {
            logger: None,
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: null_mut(),
        };
        let missing = slender_fmu::fmi2Instantiate(
            c"x".as_ptr(),
            FMI2_CO_SIMULATION,
            c"{}".as_ptr(),
            c"file:///nonexistent".as_ptr(),
            &callbacks,
            0,
            0,
        );
        assert!(missing.is_null());
        let model_exchange = slender_fmu::fmi2Instantiate(
            c"x".as_ptr(),
            FMI2_MODEL_EXCHANGE,
            c"{}".as_ptr(),
            c"file:///nonexistent".as_ptr(),
            &callbacks,
            0,
            0,
        );
        assert!(model_exchange.is_null());
    }
}

#[test]
fn parameters_become_fmi_variables_and_effects_booleans() {
    let scene = load("examples/truncation_substructured.toml");
    let config = ExportConfig::from_scene(&scene, "n").unwrap();
    let layout = config.layout().unwrap();
    let names: Vec<&str> = layout.parameters.iter().map(|p| p.name.as_str()).collect();
    assert!(names.iter().any(|n| n.starts_with("effects.")), "{names:?}");
    let e = ExportConfig::from_scene(&scene, "nope").unwrap_err();
    assert!(
        matches!(&e, slender_scene::export::ExportError::NoUnit { unit, units, .. } if unit == "nope" && units.contains("emulated")),
        "{e}"
    );
    assert!(e.to_string().contains("no unit `nope`"), "{e}");
}

/// Model descriptions kept as the fuzz corpus.
fn corpus() -> Vec<(PathBuf, Vec<u8>)> {
    let dir = root().join("tests/fuzz/model_description");
    let mut files: Vec<(PathBuf, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect();
    files.sort();
    assert!(files.len() >= 4);
    files
}

#[test]
fn the_corpus_parses() {
    for (path, bytes) in corpus() {
        let text = String::from_utf8(bytes).unwrap();
        ModelDescription::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}

#[test]
fn mutated_model_descriptions_give_errors_never_panics() {
    const TOKENS: [&str; 16] = [
        "<",
        ">",
        "/>",
        "\"",
        "&amp;",
        "&#0;",
        "=",
        "index=\"0\"",
        "dependencies=\"9 x\"",
        "<ScalarVariable>",
        "</ModelVariables>",
        "\u{feff}",
        // FMI 3.0's arrays and value references.
        "<Dimension valueReference=\"99\"/>",
        "<Dimension start=\"18446744073709551615\"/>",
        "valueReference=\"4294967295\"",
        "<Float64 name=\"a\" valueReference=\"0\" causality=\"input\" start=\"1 2\">",
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let (mut parsed, mut rejected) = (0, 0);
    for (path, original) in corpus() {
        for _ in 0..2500 {
            let mut bytes = original.clone();
            for _ in 0..rng.random_range(1..4) {
                let at = rng.random_range(0..bytes.len().max(1));
                match rng.random_range(0..5) {
                    0 => {
                        let i = at.min(bytes.len() - 1);
                        bytes[i] ^= 1 << rng.random_range(0..8);
                    }
                    1 => {
                        let end = (at + rng.random_range(1..64)).min(bytes.len());
                        bytes.drain(at..end);
                    }
                    2 => bytes.truncate(at),
                    3 => {
                        let t = TOKENS[rng.random_range(0..TOKENS.len())].as_bytes();
                        bytes.splice(at..at, t.iter().copied());
                    }
                    _ => {
                        let end = (at + rng.random_range(1..200)).min(bytes.len());
                        let piece = bytes[at..end].to_vec();
                        let to = rng.random_range(0..bytes.len().max(1));
                        bytes.splice(to..to, piece);
                    }
                }
                if bytes.is_empty() {
                    break;
                }
            }
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let outcome = std::panic::catch_unwind(|| ModelDescription::parse(&text).is_ok());
            match outcome {
                Ok(true) => parsed += 1,
                Ok(false) => rejected += 1,
                Err(_) => {
                    let keep = root().join("target/fuzz-crashes");
                    std::fs::create_dir_all(&keep).unwrap();
                    let name = keep.join(format!("crash-{parsed}-{rejected}.xml"));
                    std::fs::write(&name, &bytes).unwrap();
                    panic!(
                        "the parser panicked on a mutation of {}; input kept in {} (add it to the corpus once fixed)",
                        path.display(),
                        name.display()
                    );
                }
            }
        }
    }
    println!("{parsed} mutations parsed, {rejected} rejected with an error");
    assert!(
        rejected > parsed / 10,
        "the mutations barely changed anything"
    );
}
