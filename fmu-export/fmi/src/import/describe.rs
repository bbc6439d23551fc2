//! What an FMU offers slender, read from its model description: Real inputs and
//! outputs as ports (with kinds from their units), scalar Integer outputs as
//! generic ports after them (a counter, a mode), and the start values a scene
//! gives its parameters.

use super::*;

/// The unit description of an FMU: Real inputs and outputs as ports, an
/// array one port per element (`name[1]`, ... row-major), then the scalar
/// Integer outputs (their values as reals: exact up to 2^53).
pub(super) fn describe(
    model: &ModelDescription,
    label: &str,
) -> Result<UnitDescription, LoadError> {
    let ports_of = |causality, integer| ports(model, causality, integer);
    let inputs = ports_of(VariableCausality::Input, false);
    let mut outputs = Vec::new();
    let output_ports = ports_of(VariableCausality::Output, false)
        .into_iter()
        .chain(ports_of(VariableCausality::Output, true));
    for (i, port) in output_ports {
        let deps = model
            .outputs
            .iter()
            .find(|u| u.index == i + 1)
            .map(|u| u.dependencies.clone());
        let depends_on: Vec<usize> = match deps.flatten() {
            None => (0..inputs.len()).collect(),
            Some(list) => (0..inputs.len())
                .filter(|&k| list.contains(&(inputs[k].0 + 1)))
                .collect(),
        };
        outputs.push(port.with_feedthrough(&depends_on));
    }
    let cs = model
        .co_simulation
        .as_ref()
        .ok_or_else(|| LoadError::NotCoSimulation {
            fmu: label.to_owned(),
        })?;
    Ok(UnitDescription {
        kind: "fmu".into(),
        inputs: inputs.into_iter().map(|(_, p)| p).collect(),
        outputs,
        capabilities: Capabilities {
            rollback: cs.can_get_and_set_fmu_state,
            variable_step: cs.can_handle_variable_communication_step_size,
            output_derivative_order: 0,
            hold: if cs.can_interpolate_inputs {
                HoldSupport::Any
            } else {
                HoldSupport::ZeroOrderOnly
            },
            // The step Jacobian only through slender's extension, set where
            // the binary exports it (`FmuUnit::load`).
            step_jacobian: false,
            step_correction: false,
        },
    })
}

/// The ports of the variables of `causality` with each variable's index:
/// the Real ones (an array one port per element, `name[1]`, ... row-major;
/// an input with its declared start value), or with `integer` the scalar
/// Integer outputs.
fn ports(
    model: &ModelDescription,
    causality: VariableCausality,
    integer: bool,
) -> Vec<(usize, Port)> {
    let mut ports = Vec::new();
    for i in 0..model.variables.len() {
        let port = if integer {
            causality == VariableCausality::Output && is_integer_output(model, i)
        } else {
            is_real(model, i, causality)
        };
        if !port {
            continue;
        }
        let v = &model.variables[i];
        let (kind, unit) = kind_of(model, v.unit.as_deref());
        for k in 0..v.len() {
            let element = |name: &String| {
                if v.dimensions.is_empty() {
                    name.clone()
                } else {
                    format!("{name}[{}]", k + 1)
                }
            };
            let name = element(&v.name);
            let port = if causality == VariableCausality::Input {
                // Its declared start value, where nothing drives it.
                let mut input = Port::input(&name, kind);
                if let (Value::Real(Some(start)), true) = (&v.value, v.dimensions.is_empty()) {
                    input.start = Some(*start);
                }
                input
            } else {
                Port::output(&name, kind)
            };
            let mut port = port.with_unit(&unit);
            port.aliases = v.aliases.iter().map(element).collect();
            ports.push((i, port));
        }
    }
    ports
}

pub(super) fn is_real(model: &ModelDescription, i: usize, causality: VariableCausality) -> bool {
    let v = &model.variables[i];
    v.causality == causality && matches!(v.value, Value::Real(_))
}

/// Whether variable `i` is a scalar Integer (FMI 3.0: Int32) output.
pub(super) fn is_integer_output(model: &ModelDescription, i: usize) -> bool {
    let v = &model.variables[i];
    v.causality == VariableCausality::Output
        && matches!(v.value, Value::Integer(_))
        && v.dimensions.is_empty()
}

/// The value references of the scalar Integer outputs, in the description's
/// order (their ports follow the Real outputs').
pub(super) fn integer_output_refs(model: &ModelDescription) -> Vec<u32> {
    (0..model.variables.len())
        .filter(|&i| is_integer_output(model, i))
        .map(|i| model.variables[i].value_reference)
        .collect()
}

/// The value references of the Real variables of `causality` and how many
/// values each holds.
pub(super) fn real_refs(
    model: &ModelDescription,
    causality: VariableCausality,
) -> (Vec<u32>, Vec<usize>) {
    (0..model.variables.len())
        .filter(|&i| is_real(model, i, causality))
        .map(|i| (model.variables[i].value_reference, model.variables[i].len()))
        .unzip()
}

/// The port kind and unit name for an FMU unit of measure: the kind whose SI unit
/// has the same base exponents (and factor 1), else generic with the FMU's name.
pub(super) fn kind_of(model: &ModelDescription, unit: Option<&str>) -> (PortKind, String) {
    let Some(name) = unit else {
        return (PortKind::Generic, String::new());
    };
    let definition = model.unit(name).cloned().or_else(|| si_definition(name));
    if let Some(def) = definition
        && def.factor == 1.0
        && def.offset == 0.0
    {
        for kind in PortKind::ALL {
            if let Some(si) = si_definition(kind.si_unit())
                && si.exponents == def.exponents
                && kind != PortKind::Generic
            {
                return (kind, kind.si_unit().to_owned());
            }
        }
    }
    (PortKind::Generic, name.to_owned())
}

pub(super) fn start_values(
    model: &ModelDescription,
    starts: &BTreeMap<String, toml::Value>,
    label: &str,
) -> Result<Vec<StartValue>, LoadError> {
    let mut out = Vec::new();
    for (name, value) in starts {
        let v = (model.variables.iter())
            .find(|v| &v.name == name || v.aliases.contains(name))
            .ok_or_else(|| LoadError::UnknownStart {
                fmu: label.to_owned(),
                name: name.clone(),
                hint: did_you_mean(name, model.variables.iter().map(|v| v.name.as_str())),
            })?;
        if !matches!(
            v.causality,
            VariableCausality::Parameter | VariableCausality::Input
        ) {
            return Err(LoadError::NotSettable {
                fmu: label.to_owned(),
                name: name.clone(),
                causality: v.causality,
            });
        }
        let wrong = || LoadError::WrongStartType {
            fmu: label.to_owned(),
            name: name.clone(),
            value: value.to_string(),
            expected: v.value.type_name(),
        };
        let vr = v.value_reference;
        out.push(match (&v.value, value) {
            (Value::Real(_), toml::Value::Float(x)) => StartValue::Real(vr, *x),
            (Value::Real(_), toml::Value::Integer(x)) => StartValue::Real(vr, *x as f64),
            (Value::Integer(_) | Value::Enumeration(_), toml::Value::Integer(x)) => {
                StartValue::Integer(vr, i32::try_from(*x).map_err(|_| wrong())?)
            }
            (Value::Boolean(_), toml::Value::Boolean(b)) => StartValue::Boolean(vr, *b),
            (Value::String(_), toml::Value::String(s)) => {
                StartValue::String(vr, CString::new(s.as_str()).map_err(|_| wrong())?)
            }
            _ => return Err(wrong()),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Real input's declared start value is its port's start (what it
    /// takes where nothing drives it); other ports have none.
    #[test]
    fn an_input_s_declared_start_is_its_port_s_start() {
        let xml = include_str!(
            "../../../../tests/fuzz/model_description/fmi3_reference_feedthrough.xml"
        )
        .replacen(
            r#"name="Float64_continuous_input" valueReference="7" causality="input" start="0""#,
            r#"name="Float64_continuous_input" valueReference="7" causality="input" start="2.5""#,
            1,
        );
        let model = ModelDescription::parse(&xml).unwrap();
        let d = describe(&model, "feedthrough").unwrap();
        let starts: Vec<Option<f64>> = d.inputs.iter().map(|p| p.start).collect();
        assert_eq!(starts, [Some(2.5), Some(0.0)]);
        assert!(d.outputs.iter().all(|p| p.start.is_none()));
    }
}
