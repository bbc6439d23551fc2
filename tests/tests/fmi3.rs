//! FMI 3.0 import without Python: slender's FMI 3.0 FMUs through slender's own
//! importer against their FMI 2.0 twins and the native units (outputs, state,
//! directional derivatives), a section's fields as array outputs, and scenes of
//! FMI 3.0 FMUs against the native scenes. (FMPy's view: fmi_python.rs.)

use slender_fmi::export::ExportConfig;
use slender_fmi::import::FmuUnit;
use slender_scene::export::{ExportedUnit, FmiVersion, SceneExport, package_version};
use slender_tests::{fmu, load, run};
use slender_units::{Driver, DriverSlot, Hold, Time, Unit};
use std::path::{Path, PathBuf};

/// Exports `unit` of `scene` into `dir` as FMI `version`.
fn export(scene: &str, unit: &str, dir: &Path, version: FmiVersion) -> PathBuf {
    let config = ExportConfig::from_scene(&load(scene), unit).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join(format!("{unit}-{version:?}.fmu"));
    package_version(&config, &fmu::library(), &out, version).unwrap_or_else(|e| panic!("{e}"));
    out
}

/// Imports an FMU with every input held zero-order (FMI 3.0 co-simulation
/// passes no input derivatives).
fn imported(file: &Path) -> Driver<FmuUnit> {
    let mut unit = Driver::new(fmu::import(file).unwrap_or_else(|e| panic!("{e}")));
    for p in 0..unit.description().inputs.len() {
        unit.set_hold(p, Hold::ZeroOrder).unwrap();
    }
    unit
}

/// The inputs at step `k`: the start inputs nudged by a slow sine.
fn inputs_at(start: &[f64], k: usize) -> Vec<f64> {
    start
        .iter()
        .enumerate()
        .map(|(i, u)| u + 1e-3 * (1.0 + u.abs()) * (0.3 * k as f64 + i as f64).sin())
        .collect()
}

/// Steps `unit` from step `first` for `steps` steps; its outputs after each.
fn steps<U: Unit>(
    unit: &mut Driver<U>,
    start: &[f64],
    first: usize,
    steps: usize,
) -> Vec<Vec<f64>> {
    let h = Time::from_secs(0.01).unwrap();
    let mut out = vec![0.0; unit.description().outputs.len()];
    let mut all = Vec::new();
    for k in first..first + steps {
        unit.set_inputs(&inputs_at(start, k + 1)).unwrap();
        unit.do_step(h * k as i64, h).unwrap();
        unit.outputs(&mut out).unwrap();
        all.push(out.clone());
    }
    all
}

/// The inputs an exported unit starts from: those the scene settled on.
fn start_inputs<U: Unit>(config: &ExportConfig, unit: &Driver<U>) -> Vec<f64> {
    let inputs = &unit.description().inputs;
    let start = |p: &slender_units::Port| config.inputs.get(&p.name).copied();
    inputs.iter().map(|p| start(p).unwrap_or(0.0)).collect()
}

fn column(unit: &Driver<FmuUnit>, name: &str) -> usize {
    unit.description()
        .output_index(name)
        .unwrap_or_else(|| panic!("no output `{name}`"))
}

/// The FMI 3.0 import has the FMI 2.0 twin's ports, then one output per
/// element of each field (x and z per node, the tension per element, the
/// moment per node).
fn check_ports(two: &Driver<FmuUnit>, three: &Driver<FmuUnit>, nodes: usize) {
    let scalars = two.description().outputs.len();
    let names = |u: &Driver<FmuUnit>| -> Vec<String> {
        let outputs = &u.description().outputs;
        outputs.iter().map(|p| p.name.clone()).collect()
    };
    assert_eq!(names(two), names(three)[..scalars]);
    let arrays = &names(three)[scalars..];
    assert_eq!(arrays.len(), 4 * nodes - 1);
    assert_eq!((&*arrays[0], &*arrays[nodes]), ("x[1]", "z[1]"));
    assert_eq!(&*arrays[3 * nodes - 2], "tension[15]");
    assert_eq!(arrays.last(), Some(&format!("moment[{nodes}]")));
    // The same inputs; FMI 3.0's held zero-order (no input derivatives).
    let inputs = |u: &Driver<FmuUnit>| -> Vec<(String, String)> {
        let ports = &u.description().inputs;
        ports
            .iter()
            .map(|p| (p.name.clone(), p.unit.clone()))
            .collect()
    };
    assert_eq!(inputs(two), inputs(three));
    let holds = three.description().inputs.iter().map(|p| p.hold);
    assert!(holds.into_iter().all(|h| h == Hold::ZeroOrder));
}

/// At every step the arrays end at the section's end positions, their
/// largest tension is its `max_tension` output, bit for bit, and no node
/// moment (the mean of two element ends) exceeds its `max_moment`.
fn check_arrays(three: &Driver<FmuUnit>, outputs: &[Vec<f64>], scalars: usize, nodes: usize) {
    let bits = |v: &f64| v.to_bits();
    for (k, b) in outputs.iter().enumerate() {
        let at = |name: &str| b[column(three, name)];
        let x = &b[scalars..scalars + nodes];
        let z = &b[scalars + nodes..scalars + 2 * nodes];
        let tension = &b[scalars + 2 * nodes..scalars + 3 * nodes - 1];
        let moment = &b[scalars + 3 * nodes - 1..];
        assert_eq!(moment.len(), nodes);
        let bending = moment.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(bending <= at("max_moment"), "step {k}");
        assert_eq!(bits(&x[0]), bits(&at("start_position_x")));
        assert_eq!(bits(&x[nodes - 1]), bits(&at("end_position_x")));
        assert_eq!(bits(&z[0]), bits(&at("start_position_z")));
        assert_eq!(bits(&z[nodes - 1]), bits(&at("end_position_z")));
        let largest = tension.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(bits(&largest), bits(&at("max_tension")), "step {k}");
        assert!(
            x.windows(2).all(|w| w[1] > w[0]),
            "step {k}: nodes in order"
        );
    }
}

#[test]
fn an_fmi3_section_steps_as_its_fmi2_twin_and_gives_its_fields_as_arrays() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "examples/structure_mooring.toml";
    let (two, three) = (
        export(scene, "line_upper", dir.path(), FmiVersion::Two),
        export(scene, "line_upper", dir.path(), FmiVersion::Three),
    );
    let (mut two, mut three) = (imported(&two), imported(&three));
    let config = ExportConfig::from_scene(&load(scene), "line_upper").unwrap();
    let mut native = config.driver().unwrap();
    let nodes = native.unit().fields()[0].len;
    assert_eq!(nodes, 16);
    check_ports(&two, &three, nodes);
    let scalars = two.description().outputs.len();

    let start = start_inputs(&config, &native);
    for p in 0..start.len() {
        native.set_hold(p, Hold::ZeroOrder).unwrap();
    }
    native.set_inputs(&start).unwrap();
    native.initialize(Time::ZERO).unwrap();
    for unit in [&mut two, &mut three] {
        unit.set_inputs(&start).unwrap();
        unit.initialize(Time::ZERO).unwrap();
    }
    let reference = steps(&mut native, &start, 0, 60);
    assert_eq!(reference, steps(&mut two, &start, 0, 60));
    let through_three = steps(&mut three, &start, 0, 60);
    for (k, (a, b)) in reference.iter().zip(&through_three).enumerate() {
        assert_eq!(a[..], b[..scalars], "step {k}: FMI 3.0 against native");
    }
    check_arrays(&three, &through_three, scalars, nodes);
    println!(
        "line_upper: 60 steps, FMI 3.0 import bit-identical to native and FMI 2.0; top tension {:.6e} N",
        through_three[59][column(&three, "max_tension")]
    );

    // Rollback through fmi3GetFMUState / fmi3SetFMUState.
    let mut slot = DriverSlot::new();
    three.save(&mut slot).unwrap();
    let first = steps(&mut three, &start, 60, 20);
    three.restore(&slot).unwrap();
    let again = steps(&mut three, &start, 60, 20);
    assert_eq!(first, again, "FMI 3.0 state restored");

    // Step derivatives through slender's extension (slenderGetStepDerivative): the
    // scalar outputs' rows as the FMI 2.0 twin gives them, the arrays' rows
    // refused (NaN: a master differences them if it couples one).
    let n_in = start.len();
    let mut j2 = vec![0.0; scalars * n_in];
    let mut j3 = vec![0.0; three.description().outputs.len() * n_in];
    assert_eq!(steps(&mut two, &start, 60, 21)[19], again[19][..scalars]);
    steps(&mut three, &start, 80, 1);
    two.step_jacobian(&mut j2).unwrap();
    three.step_jacobian(&mut j3).unwrap();
    let same = |a: &f64, b: &f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
    assert!(j2.iter().zip(&j3).all(|(a, b)| same(a, b)));
    assert!(j2.iter().any(|v| v.is_finite() && *v != 0.0));
    assert!(j3[scalars * n_in..].iter().all(|v| v.is_nan()));
}

/// Largest difference between two runs' recorded signals, relative to each
/// signal's largest magnitude.
fn worst_relative_difference(a: &slender_tests::Series, b: &slender_tests::Series) -> f64 {
    assert_eq!(a.names, b.names);
    assert_eq!(a.time, b.time);
    let worst = |(x, y): (&Vec<f64>, &Vec<f64>)| {
        let scale = x.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
        x.iter()
            .zip(y)
            .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs() / scale))
    };
    a.columns
        .iter()
        .zip(&b.columns)
        .map(worst)
        .fold(0.0, f64::max)
}

#[test]
fn scenes_of_fmi3_fmus_match_the_native_scenes_with_rollback() {
    for scene in [
        // Iterative Gauss-Seidel with rollback.
        "examples/b1_two_masses.toml",
        // Aitken-accelerated, force/displacement coupling.
        "examples/b3_force_displacement.toml",
        // Three nonlinear sections, Newton on the cuts with the units'
        // Jacobians through slender's extension slenderGetStepDerivative.
        "examples/structure_mooring.toml",
    ] {
        let dir = tempfile::tempdir().unwrap();
        let native = run(&load(scene));
        let wrapped = run(&fmu::wrapped_version(scene, dir.path(), FmiVersion::Three));
        assert!(native.error.is_none() && wrapped.error.is_none(), "{scene}");
        let worst = worst_relative_difference(&native, &wrapped);
        println!(
            "{scene} through FMI 3.0: worst relative difference {worst:.2e}; iterations {} vs {}, rollbacks {} vs {}",
            native.counters.iterations,
            wrapped.counters.iterations,
            native.counters.rollbacks,
            wrapped.counters.rollbacks
        );
        // Round-off: the wrapped scene starts from its settled inputs as
        // written in its file.
        assert!(worst <= 1e-12, "{scene}: {worst:e}");
        assert_eq!(native.counters.iterations, wrapped.counters.iterations);
        assert_eq!(native.counters.rollbacks, wrapped.counters.rollbacks);
        assert!(wrapped.counters.rollbacks > 0, "{scene}: no rollback");
    }
}

#[test]
fn an_fmi3_fmu_without_its_platform_binary_says_where_it_looked() {
    let dir = tempfile::tempdir().unwrap();
    let file = export(
        "examples/b3_force_displacement.toml",
        "b",
        dir.path(),
        FmiVersion::Three,
    );
    let reader = zip::ZipArchive::new(std::fs::File::open(&file).unwrap()).unwrap();
    let broken = dir.path().join("no-binary.fmu");
    let mut writer = zip::ZipWriter::new(std::fs::File::create(&broken).unwrap());
    let mut reader = reader;
    for i in 0..reader.len() {
        let entry = reader.by_index(i).unwrap();
        if !entry.name().starts_with("binaries/") {
            writer.raw_copy_file(entry).unwrap();
        }
    }
    writer.finish().unwrap();
    let error = fmu::import(&broken).err().expect("refused");
    assert!(
        error.contains("binaries/x86_64-linux/") && error.contains("no binaries at all"),
        "{error}"
    );
}

#[test]
fn a_cable_s_fields_end_at_its_end_tensions() {
    let scene = "examples/truncation_substructured.toml";
    let config = ExportConfig::from_scene(&load(scene), "p").unwrap();
    let mut cable = config.driver().unwrap();
    let fields = cable.unit().fields();
    let names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["x", "z", "tension"]);
    assert_eq!(fields[0].len, fields[2].len + 1);
    let start = start_inputs(&config, &cable);
    assert!(
        cable.unit().field_values(2, &mut [0.0]).is_err(),
        "before initialisation"
    );
    cable.set_inputs(&start).unwrap();
    cable.initialize(Time::ZERO).unwrap();
    let outputs = steps(&mut cable, &start, 0, 40);
    let index = |name: &str| cable.description().output_index(name).unwrap();
    let mut tension = vec![0.0; fields[2].len];
    let mut z = vec![0.0; fields[1].len];
    cable.unit().field_values(2, &mut tension).unwrap();
    cable.unit().field_values(1, &mut z).unwrap();
    let last = &outputs[39];
    assert_eq!(tension.last().copied(), Some(last[index("top_tension")]));
    assert_eq!(tension[0], last[index("bottom_tension")]);
    assert!(
        z.windows(2).all(|w| w[1] > w[0]),
        "a hanging line rises to its top"
    );
    assert!(
        cable.unit().field_values(2, &mut z).is_err(),
        "wrong length refused"
    );
}

/// A section's arrays are sized by FMI 3.0 structural parameters (`n_nodes`,
/// `n_elements`: UInt64, fixed, after the arrays) so that a mesh changed
/// through the parameters can be read; the FMI 2.0 description has neither.
#[test]
fn fmi3_arrays_are_sized_by_structural_parameters_fmi2_leaves_them_out() {
    use slender_fmi::model_description::{ModelDescription, VariableCausality};
    let config = ExportConfig::from_scene(&load("examples/structure_mooring.toml"), "line_upper")
        .unwrap_or_else(|e| panic!("{e}"));
    let layout = config.layout().unwrap_or_else(|e| panic!("{e}"));
    let sizes: Vec<(&str, usize)> = (layout.sizes.iter())
        .map(|s| (s.name.as_str(), s.start))
        .collect();
    assert_eq!(sizes, [("n_nodes", 16), ("n_elements", 15)]);
    let xml = layout.model.to_xml_fmi3();
    for size in &layout.sizes {
        let declared = format!(
            r#"<UInt64 name="{}" valueReference="{}""#,
            size.name, size.value_reference
        );
        assert!(xml.contains(&declared), "{declared}");
    }
    let structural =
        layout.model.variables.iter().filter(|v| {
            v.causality == VariableCausality::StructuralParameter && v.value_reference > 0
        });
    assert_eq!(structural.count(), 2);
    // Read back (slender's reader keeps a UInt64 only to size the arrays).
    let read = ModelDescription::parse(&xml).unwrap_or_else(|e| panic!("{e}"));
    let by_name = |name: &str| read.variables.iter().find(|v| v.name == name).unwrap();
    for (array, k, len) in [("x", 0, 16), ("tension", 1, 15), ("moment", 0, 16)] {
        let array = by_name(array);
        let size = &layout.sizes[k];
        assert_eq!(array.sized_by, Some(size.value_reference), "{}", array.name);
        assert_eq!(array.len(), len, "{}", array.name);
    }
    let two = layout.model.to_xml();
    assert!(!two.contains("n_nodes") && !two.contains("structuralParameter"));
}
