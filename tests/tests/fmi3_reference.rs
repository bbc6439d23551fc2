//! slender's FMI 3.0 importer on FMUs it did not write: three of the Modelica
//! Association's Reference FMUs (`tests/reference-fmus/`), compiled here with
//! the C compiler. Stair counts seconds by time events and asks to end the
//! simulation at 9 s (built as FMI 2.0 too, for `fmi2Terminated`). StateSpace has array inputs and outputs sized by
//! structural parameters and a known solution (explicit Euler at 1 ms on
//! dx/dt = x + u, y = x + u); Feedthrough has one variable of every FMI 3.0
//! type, of which slender reads the Float64 ones as ports and sets the others
//! from start values.

use slender_fmi::import::{FmuParams, FmuUnit};
use slender_tests::root;
use slender_units::{Driver, DriverSlot, Time};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Compiles Reference FMU `model` into `dir/<model>.fmu` (FMI 3.0).
fn build(model: &str, dir: &Path) -> PathBuf {
    build_version(model, dir, 3)
}

/// Compiles Reference FMU `model` into `dir/<model>.fmu` for FMI `version`
/// (2 or 3).
fn build_version(model: &str, dir: &Path, version: u8) -> PathBuf {
    let xml = root().join(format!("tests/reference-fmus/{model}/FMI{version}.xml"));
    build_described(model, dir, version, &std::fs::read_to_string(xml).unwrap())
}

/// [`build_version`] with the model description `xml`.
fn build_described(model: &str, dir: &Path, version: u8, xml: &str) -> PathBuf {
    let source = root().join("tests/reference-fmus");
    let library = dir.join(format!("{model}.so"));
    let compiler = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&compiler)
        .args(["-shared", "-fPIC", "-O2", "-DDISABLE_PREFIX"])
        .arg(format!("-DFMI_VERSION={version}"))
        .arg(format!("-I{}", source.join("include").display()))
        .arg(format!("-I{}", source.join(model).display()))
        .arg(source.join(model).join("model.c"))
        .arg(source.join(format!("src/fmi{version}Functions.c")))
        .arg(source.join("src/cosimulation.c"))
        .arg("-o")
        .arg(&library)
        .arg("-lm")
        .status()
        .unwrap_or_else(|e| panic!("{compiler}: {e} (a C compiler builds the Reference FMUs)"));
    assert!(status.success(), "compiling {model}");
    let fmu = dir.join(format!("{model}.fmu"));
    let platform = if version == 2 {
        "linux64"
    } else {
        "x86_64-linux"
    };
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&fmu).unwrap());
    let options = zip::write::SimpleFileOptions::default();
    for (name, bytes) in [
        ("modelDescription.xml".to_owned(), xml.as_bytes().to_vec()),
        (
            format!("binaries/{platform}/{model}.so"),
            std::fs::read(library).unwrap(),
        ),
    ] {
        zip.start_file(name, options).unwrap();
        zip.write_all(&bytes).unwrap();
    }
    zip.finish().unwrap();
    fmu
}

/// The FMU at `fmu` loaded with start values `start` (TOML).
fn loaded(fmu: &Path, start: &str) -> Result<FmuUnit, slender_fmi::import::LoadError> {
    let params = FmuParams {
        file: fmu.to_owned(),
        start: toml::from_str(start).unwrap(),
        preload: Vec::new(),
        logging: false,
    };
    FmuUnit::load(&params, Path::new("."))
}

/// Why the FMU at `fmu` does not load with start values `start`.
fn load_error(fmu: &Path, start: &str) -> String {
    loaded(fmu, start).err().expect("refused").to_string()
}

fn load(fmu: &Path, start: &str) -> Driver<FmuUnit> {
    Driver::new(loaded(fmu, start).unwrap_or_else(|e| panic!("{e}")))
}

fn names(ports: &[slender_units::Port]) -> Vec<&str> {
    ports.iter().map(|p| p.name.as_str()).collect()
}

#[test]
fn the_state_space_reference_fmu_runs_with_array_ports_to_its_known_solution() {
    let dir = tempfile::tempdir().unwrap();
    let mut unit = load(&build("StateSpace", dir.path()), "");
    let d = unit.description();
    assert_eq!(names(&d.inputs), ["u[1]", "u[2]", "u[3]"]);
    assert_eq!(names(&d.outputs), ["y[1]", "y[2]", "y[3]"]);
    // No `dependencies`: every output depends on every input (y = C x + D u).
    assert!(d.outputs.iter().all(|p| p.depends_on == [0, 1, 2]));
    assert!(d.capabilities.rollback);
    let u = [1.0, 2.0, -3.0];
    unit.set_inputs(&u).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    let mut y = [0.0; 3];
    unit.outputs(&mut y).unwrap();
    assert_eq!(y, u, "y = x0 + u with x0 = 0");
    // Explicit Euler at 1 ms, ten steps per 10 ms communication step:
    // x_k = u ((1.001)^k - 1), y_k = u 1.001^k.
    let h = Time::from_secs(0.01).unwrap();
    let mut worst = 0.0_f64;
    let mut slot = DriverSlot::new();
    let mut after_save = Vec::new();
    for n in 0..100 {
        if n == 50 {
            unit.save(&mut slot).unwrap();
        }
        unit.do_step(h * n, h).unwrap();
        unit.outputs(&mut y).unwrap();
        if n >= 50 {
            after_save.push(y);
        }
        let growth = 1.001_f64.powi(10 * (n as i32 + 1));
        for (yi, ui) in y.iter().zip(u) {
            worst = worst.max((yi - ui * growth).abs() / (ui * growth).abs());
        }
    }
    println!(
        "StateSpace: 100 steps, worst relative difference to Euler's solution {worst:.2e}; y(1 s) = {y:?} (e u = {:?})",
        u.map(|v| v * 1f64.exp())
    );
    assert!(worst < 1e-12, "{worst:e}");
    // Rollback through fmi3GetFMUState / fmi3SetFMUState.
    unit.restore(&slot).unwrap();
    for (k, n) in (50..100).enumerate() {
        unit.do_step(h * n, h).unwrap();
        unit.outputs(&mut y).unwrap();
        assert_eq!(y, after_save[k], "step {n} after the restore");
    }
}

#[test]
fn the_feedthrough_reference_fmu_passes_its_float64s_and_takes_every_start_type() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = build("Feedthrough", dir.path());
    let starts = r#"
        Float64_fixed_parameter = 2.5
        Int32_input = 7
        Boolean_input = true
        String_input = "slender"
    "#;
    let mut unit = load(&fmu, starts);
    let d = unit.description();
    // Float32, the integer widths, Boolean, String, Binary and Enumeration
    // variables are not ports, but for an Int32 output (after the Float64s).
    assert_eq!(
        names(&d.inputs),
        ["Float64_continuous_input", "Float64_discrete_input"]
    );
    assert_eq!(
        names(&d.outputs),
        [
            "Float64_continuous_output",
            "Float64_discrete_output",
            "Int32_output"
        ]
    );
    assert_eq!(
        (&d.outputs[0].depends_on, &d.outputs[1].depends_on),
        (&vec![0], &vec![1])
    );
    unit.set_inputs(&[1.25, -3.5]).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    let mut y = [0.0; 3];
    unit.outputs(&mut y).unwrap();
    // The Int32 output passes the Int32 input's start value through.
    assert_eq!(y, [1.25, -3.5, 7.0]);
    let h = Time::from_secs(0.1).unwrap();
    for n in 0..20 {
        let x = (n as f64).sin();
        unit.set_inputs(&[x, 0.5]).unwrap();
        unit.do_step(h * n, h).unwrap();
        unit.outputs(&mut y).unwrap();
        assert_eq!(y[0], x, "step {n}: continuous output follows its input");
    }
    // A start value of the wrong type is refused with the variable's name.
    let error = load_error(&fmu, "Int32_input = 1.5");
    assert!(
        error.contains("Int32_input") && error.contains("Integer"),
        "{error}"
    );
}

/// An input nothing drives takes its start value (the scene's, else the
/// FMU's declared one), not 0: the master sent 0 over a start value of 2.5
/// given to the Feedthrough FMU, which then put out 0 (issue 49 #10).
#[test]
fn an_undriven_input_of_an_imported_fmu_takes_its_start_value() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = build("Feedthrough", dir.path());
    let scene = format!(
        r#"
[simulation]
duration = 0.3
step = 0.1

[master]
scheme = "jacobi"

[[units]]
name = "through"
kind = "fmu"
parameters = {{ file = "{}", start = {{ Float64_continuous_input = 2.5 }} }}

[output]
signals = ["through.Float64_continuous_output", "through.Float64_discrete_output"]
"#,
        fmu.display()
    );
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, scene).unwrap();
    let scene = slender_scene::Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let series = slender_tests::run(&scene);
    assert!(series.error.is_none(), "{:?}", series.error);
    // The scene's start value on the continuous input, the FMU's declared
    // one (0) on the discrete input.
    for y in series.get("through.Float64_continuous_output") {
        assert_eq!(*y, 2.5);
    }
    for y in series.get("through.Float64_discrete_output") {
        assert_eq!(*y, 0.0);
    }
}

/// `xml` with an `<Alias name="{alias}"/>` in the empty Float64 element of
/// `variable`.
fn alias(xml: &str, variable: &str, alias: &str) -> String {
    let open = format!("<Float64 name=\"{variable}\"");
    let at = xml.find(&open).unwrap();
    let end = at + xml[at..].find("/>").unwrap();
    format!(
        "{}><Alias name=\"{alias}\"/></Float64>{}",
        &xml[..end],
        &xml[end + 2..]
    )
}

/// FMI 3.0 aliases are other names of the same variable (issue 49 #14:
/// they could not be used): a scene drives the Feedthrough FMU's input by
/// its alias, records its output by its alias and sets a start value by an
/// alias; a description whose alias names another variable is refused.
#[test]
fn fmi3_aliases_name_the_same_ports() {
    let dir = tempfile::tempdir().unwrap();
    let xml =
        std::fs::read_to_string(root().join("tests/reference-fmus/Feedthrough/FMI3.xml")).unwrap();
    let xml = alias(&xml, "Float64_continuous_input", "u");
    let xml = alias(&xml, "Float64_continuous_output", "y");
    let xml = alias(&xml, "Float64_discrete_input", "v");
    let fmu = build_described("Feedthrough", dir.path(), 3, &xml);
    // The scene by the aliases (u, v, y) and by the variables' own names.
    let run = |(u, v, y): (&str, &str, &str)| {
        let scene = format!(
            r#"
[simulation]
duration = 0.3
step = 0.1

[master]
scheme = "jacobi"

[[units]]
name = "source"
kind = "signal"
parameters = {{ quantity = "displacement", sines = [{{ amplitude = 1.5, angular_frequency = 6.0 }}] }}

[[units]]
name = "through"
kind = "fmu"
parameters = {{ file = "{}", start = {{ {v} = 4.0 }} }}

[[connections]]
from = "source.value"
to = "through.{u}"

[output]
signals = ["source.value", "through.{y}", "through.Float64_discrete_output"]
"#,
            fmu.display()
        );
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, scene).unwrap();
        let scene = slender_scene::Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let series = slender_tests::run(&scene);
        assert!(series.error.is_none(), "{:?}", series.error);
        (
            series.get(&format!("through.{y}")).to_vec(),
            series.get("through.Float64_discrete_output").to_vec(),
        )
    };
    let by_alias = run(("u", "v", "y"));
    let by_name = run((
        "Float64_continuous_input",
        "Float64_discrete_input",
        "Float64_continuous_output",
    ));
    assert_eq!(by_alias, by_name);
    assert!(by_alias.0.iter().any(|y| *y != 0.0), "{by_alias:?}");
    assert!(by_alias.1.iter().all(|y| *y == 4.0), "{by_alias:?}");
    // An alias may not name another variable.
    let clash = alias(
        &std::fs::read_to_string(root().join("tests/reference-fmus/Feedthrough/FMI3.xml")).unwrap(),
        "Float64_continuous_input",
        "Float64_continuous_output",
    );
    let error = slender_fmi::model_description::ModelDescription::parse(&clash)
        .expect_err("a clash")
        .to_string();
    assert!(
        error.contains("`Float64_continuous_output` is used by two variables"),
        "{error}"
    );
}

/// An FMU with clocks is refused by name when loaded (its clocks were
/// ignored without a word: issue 49 #14), before its binary is looked for.
#[test]
fn a_clocked_fmu_is_refused_naming_its_clocks() {
    let dir = tempfile::tempdir().unwrap();
    let xml = std::fs::read_to_string(root().join("tests/reference-fmus/Feedthrough/FMI3.xml"))
        .unwrap()
        .replacen(
            "<ModelVariables>",
            "<ModelVariables>\n    <Clock name=\"tick\" valueReference=\"999\" causality=\"input\"/>",
            1,
        );
    let fmu = dir.path().join("clocked.fmu");
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&fmu).unwrap());
    zip.start_file(
        "modelDescription.xml",
        zip::write::SimpleFileOptions::default(),
    )
    .unwrap();
    zip.write_all(xml.as_bytes()).unwrap();
    zip.finish().unwrap();
    let error = load_error(&fmu, "");
    assert!(
        error.contains("clocks") && error.contains("tick"),
        "{error}"
    );
}

/// The Stair Reference FMU (an Int32 counter, no Float64 port) asks to end
/// the simulation when its counter reaches 10, at t = 9 s: a run ends there,
/// completed with a warning naming it (it failed before, where FMI masters
/// end the simulation). Its counter is an output port (issue 49 #14: Integer
/// outputs were not ports), recorded as the seconds it counts.
#[test]
fn a_reference_fmu_that_asks_to_end_the_simulation_ends_the_run_there() {
    // FMI 3.0's terminateSimulation, and FMI 2.0's fmi2Discard with
    // fmi2GetBooleanStatus(fmi2Terminated).
    for version in [3, 2] {
        let dir = tempfile::tempdir().unwrap();
        stair_ends_the_run(&build_version("Stair", dir.path(), version), dir.path());
    }
}

/// Stair at `fmu` asks to end at 9 s, alone and in a scene (in `dir`).
fn stair_ends_the_run(fmu: &Path, dir: &Path) {
    let mut unit = load(fmu, "");
    assert!(unit.description().inputs.is_empty());
    let outputs: Vec<&str> = (unit.description().outputs.iter())
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(outputs, ["counter"]);
    unit.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.2).unwrap();
    let ended = (0..60).find_map(|n| unit.do_step(h * n, h).err().map(|e| (n, e)));
    let (n, e) = ended.expect("Stair asks to end the simulation");
    assert!(
        matches!(e, slender_units::UnitError::EndRequested(_)),
        "{e}"
    );
    assert_eq!(n, 44, "the step from 8.8 s reaches the event at 9 s");
    let text = format!(
        "[simulation]\nduration = 10.0\nstep = 0.2\n[master]\nscheme = \"jacobi\"\n[[units]]\nname = \"stair\"\nkind = \"fmu\"\nparameters = {{ file = {:?} }}\n",
        fmu.display().to_string()
    );
    let scene = slender_scene::Scene::parse(&dir.join("stair.toml"), text)
        .unwrap_or_else(|e| panic!("{e}"));
    let run = slender_tests::run(&scene);
    assert!(run.error.is_none(), "{:?}", run.error);
    let last = *run.time.last().unwrap();
    assert!((last - 8.8).abs() < 1e-9, "the run ends at {last} s");
    // One count a second from 1 (between the events, where the step's end
    // does not meet one).
    let counter = run.get("stair.counter");
    for (t, c) in run.time.iter().zip(counter) {
        if (t.fract() - 0.5).abs() < 0.35 {
            assert_eq!(*c, 1.0 + t.floor(), "at {t} s");
        }
    }
    assert_eq!(counter.last(), Some(&9.0));
    assert!(
        run.warnings
            .iter()
            .any(|w| w.contains("unit `stair` asked to end the simulation")),
        "{:?}",
        run.warnings
    );
}
