//! The same description written as FMI 3.0 (`modelDescription.xml` of an
//! FMI 3.0 co-simulation FMU): typed variable elements (`Float64`, `Int32`,
//! `Boolean`, `String`), value references instead of indices in the model
//! structure, the instantiation token, and the independent variable `time`
//! FMI 3.0 requires (value reference [`ModelDescription::time_reference`]).

use super::*;

impl ModelDescription {
    /// The value reference of FMI 3.0's independent variable `time`: one past
    /// the largest of the description's own.
    pub fn time_reference(&self) -> u32 {
        self.variables
            .iter()
            .map(|v| v.value_reference + 1)
            .max()
            .unwrap_or(0)
    }

    /// The description as FMI 3.0 XML.
    pub fn to_xml_fmi3(&self) -> String {
        let mut x = String::new();
        let e = |s: &str| escape(s).into_owned();
        let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
        let _ = writeln!(
            x,
            r#"<fmiModelDescription fmiVersion="3.0" {} variableNamingConvention="flat">"#,
            self.root_attributes("instantiationToken"),
        );
        if let Some(cs) = &self.co_simulation {
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{}" canHandleVariableCommunicationStepSize="{}" canGetAndSetFMUState="{}" canSerializeFMUState="{}" providesDirectionalDerivatives="{}" maxOutputDerivativeOrder="0" canReturnEarlyAfterIntermediateUpdate="false" hasEventMode="false" providesIntermediateUpdate="false" canBeInstantiatedOnlyOncePerProcess="false" needsExecutionTool="false"/>"#,
                e(&cs.model_identifier),
                cs.can_handle_variable_communication_step_size,
                cs.can_get_and_set_fmu_state,
                cs.can_serialize_fmu_state,
                cs.provides_directional_derivative
            );
        }
        self.write_declarations(&mut x);
        for v in &self.variables {
            write_variable3(&mut x, v);
        }
        // Last, so that the variables keep their FMI 2.0 indices when read back.
        let _ = writeln!(
            x,
            r#"    <Float64 name="time" valueReference="{}" causality="independent" variability="continuous" description="simulation time (s)"/>"#,
            self.time_reference()
        );
        x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
        let reference = |index: usize| self.variables[index - 1].value_reference;
        for (tag, list) in [
            ("Output", &self.outputs),
            ("InitialUnknown", &self.initial_unknowns),
        ] {
            for u in list {
                let _ = write!(x, r#"    <{tag} valueReference="{}""#, reference(u.index));
                if let Some(deps) = &u.dependencies {
                    let deps: Vec<String> =
                        deps.iter().map(|d| reference(*d).to_string()).collect();
                    let _ = write!(x, r#" dependencies="{}""#, deps.join(" "));
                }
                x.push_str("/>\n");
            }
        }
        x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
        x
    }
}

/// One variable as its FMI 3.0 type element.
fn write_variable3(x: &mut String, v: &ScalarVariable) {
    let e = |s: &str| escape(s).into_owned();
    let element = match &v.value {
        // FMI 3.0: a structural parameter that sizes an array is a UInt64.
        Value::Integer(_) if v.causality == VariableCausality::StructuralParameter => "UInt64",
        Value::Real(_) => "Float64",
        Value::Integer(_) | Value::Enumeration(_) => "Int32",
        Value::Boolean(_) => "Boolean",
        Value::String(_) => "String",
    };
    let _ = write!(x, "    <{element}");
    write_variable_attributes(x, v);
    x.push_str(&type_attributes(v));
    let mut children = String::new();
    match (&v.value, start_text(&v.value)) {
        (Value::String(_), Some(start)) => {
            let _ = write!(children, r#"<Start value="{}"/>"#, e(&start));
        }
        (_, Some(start)) => {
            let _ = write!(x, r#" start="{}""#, e(&start));
        }
        (_, None) => {}
    }
    match v.sized_by {
        Some(vr) => {
            let _ = write!(children, r#"<Dimension valueReference="{vr}"/>"#);
        }
        None => {
            for n in &v.dimensions {
                let _ = write!(children, r#"<Dimension start="{n}"/>"#);
            }
        }
    }
    if children.is_empty() {
        x.push_str("/>\n");
    } else {
        let _ = writeln!(x, ">{children}</{element}>");
    }
}
