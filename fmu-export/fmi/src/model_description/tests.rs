//! Writing and reading model descriptions back.

use super::*;

fn sample() -> ModelDescription {
    ModelDescription {
        fmi_version: "2.0".into(),
        model_name: "m".into(),
        guid: "{1}".into(),
        description: "a & b".into(),
        generation_tool: "slender".into(),
        about: About {
            author: "a".into(),
            version: "0.1.0".into(),
            copyright: String::new(),
            license: "MIT OR Apache-2.0".into(),
            generation_date_and_time: Some("2026-12-03T10:00:00Z".into()),
        },
        log_categories: vec![LogCategory {
            name: "logAll".into(),
            description: "every message".into(),
        }],
        co_simulation: Some(CoSimulation {
            model_identifier: "m".into(),
            can_handle_variable_communication_step_size: true,
            can_interpolate_inputs: true,
            max_output_derivative_order: 0,
            can_get_and_set_fmu_state: true,
            can_serialize_fmu_state: true,
            provides_directional_derivative: true,
        }),
        units: vec![UnitDefinition {
            name: "N".into(),
            exponents: [1, 1, -2, 0, 0, 0, 0, 0],
            factor: 1.0,
            offset: 0.0,
        }],
        variables: sample_variables(),
        outputs: vec![Unknown {
            index: 2,
            dependencies: Some(vec![]),
        }],
        initial_unknowns: vec![Unknown {
            index: 2,
            dependencies: Some(vec![1]),
        }],
        default_experiment: Some(DefaultExperiment {
            start_time: Some(0.0),
            stop_time: Some(10.0),
            tolerance: None,
            step_size: Some(0.01),
        }),
        clocks: Vec::new(),
    }
}

fn sample_variables() -> Vec<ScalarVariable> {
    vec![
        ScalarVariable {
            name: "f".into(),
            value_reference: 0,
            description: String::new(),
            causality: VariableCausality::Input,
            variability: "continuous".into(),
            initial: None,
            value: Value::Real(Some(0.1)),
            unit: Some("N".into()),
            min: Some(-1.0),
            max: Some(2.5e6),
            dimensions: Vec::new(),
            sized_by: None,
            aliases: Vec::new(),
        },
        ScalarVariable {
            name: "x".into(),
            value_reference: 1,
            description: String::new(),
            causality: VariableCausality::Output,
            variability: "continuous".into(),
            initial: Some("calculated".into()),
            value: Value::Real(None),
            unit: None,
            min: None,
            max: None,
            dimensions: Vec::new(),
            sized_by: None,
            aliases: Vec::new(),
        },
        ScalarVariable {
            name: "label".into(),
            value_reference: 2,
            description: "<\"quoted\">".into(),
            causality: VariableCausality::Parameter,
            variability: "fixed".into(),
            initial: Some("exact".into()),
            value: Value::String(Some("a<b".into())),
            unit: None,
            min: None,
            max: None,
            dimensions: Vec::new(),
            sized_by: None,
            aliases: Vec::new(),
        },
    ]
}

#[test]
fn written_descriptions_parse_back_identically() {
    let md = sample();
    assert_eq!(ModelDescription::parse(&md.to_xml()).unwrap(), md);
}

#[test]
fn errors_name_the_element_attribute_and_line() {
    let xml = sample()
        .to_xml()
        .replace(r#"valueReference="1""#, r#"valueReference="x""#);
    let e = ModelDescription::parse(&xml).unwrap_err();
    assert!(e.message.contains("<ScalarVariable>") && e.message.contains("valueReference"));
    assert!(e.line > 5, "{e}");
    let xml = sample().to_xml().replace(r#" guid="{1}""#, "");
    let e = ModelDescription::parse(&xml).unwrap_err().to_string();
    assert!(e.contains("guid"), "{e}");
    let xml = sample().to_xml().replace(r#" start="1e-1""#, "");
    let e = ModelDescription::parse(&xml).unwrap_err().to_string();
    assert!(e.contains("no start value"), "{e}");
    let e = ModelDescription::parse("<a><b></a>")
        .unwrap_err()
        .to_string();
    assert!(e.contains("not well-formed") || e.contains("root"), "{e}");
}

#[test]
fn fmi3_descriptions_parse_back_to_the_same_variables_and_structure() {
    let md = sample();
    let three = ModelDescription::parse(&md.to_xml_fmi3()).unwrap();
    assert_eq!(three.fmi_version, "3.0");
    assert_eq!(three.guid, md.guid);
    assert_eq!(three.variables[..md.variables.len()], md.variables[..]);
    let time = &three.variables[md.variables.len()];
    assert_eq!(
        (time.name.as_str(), time.causality),
        ("time", VariableCausality::Independent)
    );
    assert_eq!(
        (&three.outputs, &three.initial_unknowns),
        (&md.outputs, &md.initial_unknowns)
    );
    let (cs, cs3) = (md.co_simulation.unwrap(), three.co_simulation.unwrap());
    assert_eq!(
        (cs3.can_get_and_set_fmu_state, cs3.can_serialize_fmu_state),
        (cs.can_get_and_set_fmu_state, cs.can_serialize_fmu_state)
    );
    assert!(cs3.provides_directional_derivative && !cs3.can_interpolate_inputs);
}

/// An FMI 3.0 description with what slender reads and what it leaves out.
const FMI3: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="3.0" modelName="m" instantiationToken="{t}">
  <CoSimulation modelIdentifier="m" canGetAndSetFMUState="true" providesDirectionalDerivatives="false"/>
  <ModelVariables>
    <Float64 name="time" valueReference="0" causality="independent" variability="continuous"/>
    <Int32 name="n" valueReference="1" causality="structuralParameter" variability="fixed" start="4"/>
    <Float64 name="u" valueReference="2" causality="input" start="1.5" unit="N"/>
    <Float32 name="y32" valueReference="3" causality="output"/>
    <Float64 name="y" valueReference="4" causality="output"><Dimension valueReference="1"/></Float64>
    <Float64 name="grid" valueReference="5" causality="parameter" variability="fixed" start="1 2 3 4 5 6"><Dimension start="2"/><Dimension start="3"/></Float64>
    <String name="label" valueReference="6" causality="parameter" variability="fixed"><Start value="a&lt;b"/></String>
    <Clock name="tick" valueReference="7" causality="input"/>
  </ModelVariables>
  <ModelStructure>
    <Output valueReference="3" dependencies="2"/>
    <Output valueReference="4" dependencies="2 7"/>
    <InitialUnknown valueReference="4" dependencies=""/>
  </ModelStructure>
</fmiModelDescription>
"#;

#[test]
fn fmi3_arrays_are_sized_and_unread_types_left_out() {
    let md = ModelDescription::parse(FMI3).unwrap();
    assert_eq!(md.guid, "{t}");
    let names: Vec<&str> = md.variables.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, ["time", "n", "u", "y", "grid", "label"]);
    assert_eq!(
        md.variables[1].causality,
        VariableCausality::StructuralParameter
    );
    let (y, grid) = (&md.variables[3], &md.variables[4]);
    assert_eq!((y.dimensions.clone(), y.len()), (vec![4], 4));
    assert_eq!((y.sized_by, grid.sized_by), (Some(1), None));
    assert_eq!((grid.dimensions.clone(), grid.len()), (vec![2, 3], 6));
    assert_eq!(grid.value, Value::Real(Some(1.0)));
    assert_eq!(md.variables[5].value, Value::String(Some("a<b".into())));
    // y32 (Float32) is left out with its output; y depends on u (index 3),
    // the clock is left out of its dependencies.
    assert_eq!(md.outputs.len(), 1);
    assert_eq!(md.outputs[0].index, 4);
    assert_eq!(md.outputs[0].dependencies, Some(vec![3]));
    assert_eq!(md.initial_unknowns[0].dependencies, Some(vec![]));
    assert!(md.co_simulation.unwrap().can_get_and_set_fmu_state);
    // Its clock is listed, for the importer to refuse the FMU by it.
    assert_eq!(md.clocks, ["tick"]);
    let clocked = FMI3.replacen(
        r#"<Clock name="tick""#,
        r#"<Float64 name="sampled" valueReference="70" causality="output" clocks="7"/>
    <Clock name="tick""#,
        1,
    );
    let md = ModelDescription::parse(&clocked).unwrap();
    assert_eq!(md.clocks, ["sampled (clocked by 7)", "tick"]);
    // FMI 2.0 has none.
    assert!(
        ModelDescription::parse(&sample().to_xml())
            .unwrap()
            .clocks
            .is_empty()
    );
}

#[test]
fn fmi3_errors_name_the_element_and_line() {
    let bad = FMI3.replace(
        r#"<Dimension valueReference="1"/>"#,
        r#"<Dimension valueReference="2"/>"#,
    );
    let e = ModelDescription::parse(&bad).unwrap_err();
    assert!(e.message.contains("<Dimension>") && e.line == 9, "{e}");
    let bad = FMI3.replace(
        r#"name="u" valueReference="2" causality="input" start="1.5""#,
        r#"name="u" valueReference="2" causality="input""#,
    );
    let e = ModelDescription::parse(&bad).unwrap_err().to_string();
    assert!(e.contains("no start value") && e.contains("`u`"), "{e}");
    let huge = FMI3.replace(
        r#"<Dimension start="3"/>"#,
        r#"<Dimension start="18446744073709551615"/>"#,
    );
    let e = ModelDescription::parse(&huge).unwrap_err().to_string();
    assert!(e.contains("`grid`") && e.contains("more than"), "{e}");
    let old = FMI3.replace(r#"fmiVersion="3.0""#, r#"fmiVersion="1.0""#);
    let e = ModelDescription::parse(&old).unwrap_err().to_string();
    assert!(e.contains("FMI 2.0 and 3.0 are supported"), "{e}");
}
