//! Exporting a unit as an FMI 2.0 co-simulation FMU: what the FMU carries, how its
//! variables map onto the unit, and the packaging.
//!
//! An exported FMU holds one shared library (the `slender-fmu` crate, the same for
//! every unit) and `resources/slender-unit.toml`, the unit's scene section
//! ([`ExportConfig`]). The library rebuilds the unit from that file, so the model
//! description written here and the variables the library serves come from the
//! same [`Layout`].
//!
//! Variables, with one value-reference numbering across types: the unit's inputs
//! (Real, `input`), its outputs (Real, `output`), then its parameters flattened to
//! scalars (`parameter`, `fixed`): numbers, integers, booleans and strings of the
//! scene's parameter table (nested tables as `a.b`) and each effect the kind can
//! switch as Boolean `effects.<name>`. Arrays stay fixed data.

use crate::measure::si_definition;
use crate::model_description::{
    About, CoSimulation, DefaultExperiment, LogCategory, ModelDescription, ScalarVariable, Unknown,
    Value, VariableCausality,
};
use serde::{Deserialize, Serialize};
use slender_contract::{Field, Hold, UnitDescription};
use std::collections::BTreeMap;
use std::path::Path;

/// Why an FMU's configuration, a parameter of it, or its packaging failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PackageError {
    /// The configuration (`resources/slender-unit.toml`) does not read or write.
    #[error("{CONFIG_FILE}: {0}")]
    Config(String),
    /// A parameter value does not fit its variable.
    #[error("{0}")]
    Parameter(String),
    /// A file (the FMU library, the FMU being written) and what went wrong.
    #[error("{path}: {problem}")]
    File {
        /// The file.
        path: String,
        /// What went wrong.
        problem: String,
    },
}

fn file_error(path: &Path, problem: String) -> PackageError {
    PackageError::File {
        path: path.display().to_string(),
        problem,
    }
}

/// Name of the unit's data inside the FMU's `resources/` folder.
pub const CONFIG_FILE: &str = "slender-unit.toml";

/// The unit an FMU wraps: its scene section and the scene's time window.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ExportConfig {
    /// Unit name in the scene.
    pub name: String,
    /// The unit's kind (its scene `kind`).
    pub kind: String,
    /// The effects switched on.
    #[serde(default)]
    pub effects: Vec<String>,
    /// How the unit's inputs are held over a step, when not the kind's default.
    #[serde(default)]
    pub hold: Option<Hold>,
    /// Start values of inputs by port name: the values the scene's master settled
    /// on at initialisation, so the FMU starts in the scene's initial state.
    #[serde(default)]
    pub inputs: BTreeMap<String, f64>,
    /// The unit's parameter table, as the scene gives it.
    #[serde(default)]
    pub parameters: toml::Table,
    /// The scene's time window (s), for the default experiment.
    pub start_time: f64,
    /// Stop time (s).
    pub stop_time: f64,
    /// Communication step (s).
    pub step: f64,
    /// The FMU's GUID (a hash of everything above), checked at instantiation.
    #[serde(default)]
    pub guid: String,
}

/// Where a parameter variable writes.
#[derive(Clone, Debug, PartialEq)]
pub enum ParameterTarget {
    /// A key path into the parameter table.
    Table(Vec<String>),
    /// Whether an effect is included.
    Effect(String),
}

/// One parameter variable of the FMU.
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterVariable {
    /// The variable's name (a parameter's key path, or `effect.<name>`).
    pub name: String,
    /// Its value reference.
    pub value_reference: u32,
    /// What setting it changes.
    pub target: ParameterTarget,
    /// Type and start value.
    pub start: Value,
}

/// What a kind's documentation says of one parameter (by its top-level key).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParameterInfo {
    /// Unit of measure as written ("kg/m"; empty when none).
    pub unit: String,
    /// What the parameter is.
    pub meaning: String,
    /// The documented range of a number, inclusive.
    pub min: Option<f64>,
    /// Upper bound, inclusive.
    pub max: Option<f64>,
}

/// What a layout needs to know of a unit's kind.
pub struct KindInfo<'a> {
    /// One line on the kind, for the model description.
    pub summary: &'a str,
    /// The effects the kind can switch (each becomes a Boolean parameter).
    pub effects: &'a [&'a str],
    /// Its documented parameters, by top-level key.
    pub parameters: BTreeMap<String, ParameterInfo>,
}

/// The log categories an exported FMU sends messages in (see the FMU
/// library's logger).
pub const LOG_CATEGORIES: [(&str, &str); 3] = [
    ("logAll", "every message: progress and the unit's notes"),
    (
        "logStatusWarning",
        "warnings: a call that went on with a caveat",
    ),
    (
        "logStatusError",
        "errors: a call that failed, with the reason",
    ),
];

/// The FMU's variables and model description for one configuration.
pub struct Layout {
    /// The unit's own description (ports, feedthrough, capabilities).
    pub unit: UnitDescription,
    /// The parameter variables, in value-reference order.
    pub parameters: Vec<ParameterVariable>,
    /// The unit's fields, FMI 3.0 array outputs with value references from
    /// `first_field_reference` (after every scalar).
    pub fields: Vec<Field>,
    /// Value reference of the first field (array) output.
    pub first_field_reference: u32,
    /// The FMI 3.0 structural parameters that size the fields' arrays (after
    /// the fields).
    pub sizes: Vec<ArraySize>,
    /// The model description written into the FMU.
    pub model: ModelDescription,
}

impl ExportConfig {
    /// Reads the configuration an FMU carries.
    pub fn from_toml(text: &str) -> Result<ExportConfig, PackageError> {
        toml::from_str(text).map_err(|e| PackageError::Config(e.message().trim().to_owned()))
    }

    /// The configuration as TOML.
    pub fn to_toml(&self) -> Result<String, PackageError> {
        toml::to_string(self).map_err(|e| PackageError::Config(e.to_string()))
    }

    /// A GUID-shaped hash of the configuration (without its guid).
    pub fn fingerprint(&self) -> String {
        let mut plain = self.clone();
        plain.guid.clear();
        let text = plain.to_toml().unwrap_or_default();
        let hash = |seed: u64| {
            text.bytes().fold(seed, |h, b| {
                (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
            })
        };
        let (a, b) = (hash(0xcbf2_9ce4_8422_2325), hash(0x6c62_272e_07bb_0142));
        format!(
            "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
            a >> 32,
            (a >> 16) & 0xffff,
            a & 0xffff,
            b >> 48,
            b & 0xffff_ffff_ffff
        )
    }

    /// The FMU's model identifier (a C identifier): `slender_<unit name>`.
    pub fn model_identifier(&self) -> String {
        let name: String = self
            .name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        format!("slender_{name}")
    }

    /// Changes a parameter; the unit must be rebuilt afterwards.
    pub fn set_parameter(
        &mut self,
        target: &ParameterTarget,
        value: Value,
    ) -> Result<(), PackageError> {
        let refused = |m: String| PackageError::Parameter(m);
        match target {
            ParameterTarget::Effect(effect) => {
                let Value::Boolean(Some(on)) = value else {
                    return Err(refused(format!("effects.{effect}: expected a Boolean")));
                };
                self.effects.retain(|e| e != effect);
                if on {
                    self.effects.push(effect.clone());
                }
                Ok(())
            }
            ParameterTarget::Table(path) => {
                let (last, parents) = path
                    .split_last()
                    .ok_or_else(|| refused("empty parameter path".into()))?;
                let mut table = &mut self.parameters;
                for key in parents {
                    table = table
                        .get_mut(key)
                        .and_then(toml::Value::as_table_mut)
                        .ok_or_else(|| refused(format!("parameter table `{key}` is missing")))?;
                }
                let value = match value {
                    Value::Real(Some(v)) => toml::Value::Float(v),
                    Value::Integer(Some(v)) => toml::Value::Integer(i64::from(v)),
                    Value::Boolean(Some(v)) => toml::Value::Boolean(v),
                    Value::String(Some(v)) => toml::Value::String(v),
                    other => return Err(refused(format!("{}: no value", other.type_name()))),
                };
                table.insert(last.clone(), value);
                Ok(())
            }
        }
    }
}

impl Layout {
    /// The layout of `config`'s FMU for its unit's description `unit` (the ports
    /// with the holds in force), its fields and its kind.
    pub fn new(
        config: &ExportConfig,
        unit: UnitDescription,
        fields: Vec<Field>,
        kind: &KindInfo,
    ) -> Layout {
        let n_in = unit.inputs.len();
        let n_out = unit.outputs.len();
        let parameters = parameter_variables(config, kind, (n_in + n_out) as u32);
        let (variables, units) = variables(config, &unit, &parameters, kind);
        let outputs: Vec<Unknown> = unit
            .outputs
            .iter()
            .enumerate()
            .map(|(i, p)| Unknown {
                index: n_in + i + 1,
                dependencies: Some(p.depends_on.iter().map(|d| d + 1).collect()),
            })
            .collect();
        let caps = unit.capabilities;
        let mut model = ModelDescription {
            fmi_version: "2.0".into(),
            model_name: config.name.clone(),
            guid: config.guid.clone(),
            description: format!(
                "slender `{}` unit `{}`: {}",
                config.kind, config.name, kind.summary
            ),
            generation_tool: format!("slender {}", env!("CARGO_PKG_VERSION")),
            about: About {
                author: "slender".into(),
                version: env!("CARGO_PKG_VERSION").into(),
                copyright: String::new(),
                license: env!("CARGO_PKG_LICENSE").into(),
                generation_date_and_time: None,
            },
            log_categories: LOG_CATEGORIES
                .iter()
                .map(|(name, description)| LogCategory {
                    name: (*name).into(),
                    description: (*description).into(),
                })
                .collect(),
            co_simulation: Some(CoSimulation {
                model_identifier: config.model_identifier(),
                can_handle_variable_communication_step_size: caps.variable_step,
                can_interpolate_inputs: true,
                max_output_derivative_order: 0,
                can_get_and_set_fmu_state: caps.rollback,
                can_serialize_fmu_state: caps.rollback,
                // The standard's derivatives at an instant: zero without
                // feedthrough; the step Jacobian is the extension's.
                provides_directional_derivative: !unit.has_feedthrough(),
            }),
            units,
            variables,
            initial_unknowns: outputs.clone(),
            outputs,
            default_experiment: Some(DefaultExperiment {
                start_time: Some(config.start_time),
                stop_time: Some(config.stop_time),
                tolerance: None,
                step_size: Some(config.step),
            }),
            clocks: Vec::new(),
        };
        let first_field_reference = (n_in + n_out + parameters.len()) as u32;
        let sizes = arrays::add(&mut model, &fields, first_field_reference);
        Layout {
            unit,
            parameters,
            fields,
            first_field_reference,
            sizes,
            model,
        }
    }
}

mod arrays;
pub use arrays::{ArraySize, size_name};
mod binary;
mod describe;
mod package;
mod variables;
pub use binary::{check_binary, default_binary};
pub use package::{FmiVersion, package, package_version};
pub use variables::VARIABLES_FILE;

/// The parameter variables: the scalars of the parameter table, then a Boolean per
/// effect the kind can switch, numbered from value reference `first`.
fn parameter_variables(
    config: &ExportConfig,
    kind: &KindInfo,
    first: u32,
) -> Vec<ParameterVariable> {
    let mut parameters = Vec::new();
    flatten(&config.parameters, &mut Vec::new(), &mut parameters);
    for effect in kind.effects {
        parameters.push(ParameterVariable {
            name: format!("effects.{effect}"),
            value_reference: 0,
            target: ParameterTarget::Effect((*effect).to_owned()),
            start: Value::Boolean(Some(config.effects.iter().any(|e| e == effect))),
        });
    }
    for (i, p) in parameters.iter_mut().enumerate() {
        p.value_reference = first + i as u32;
    }
    parameters
}

/// The scalar variables (inputs, outputs, parameters) and the units of measure
/// they declare.
fn variables(
    config: &ExportConfig,
    unit: &UnitDescription,
    parameters: &[ParameterVariable],
    kind: &KindInfo,
) -> (
    Vec<ScalarVariable>,
    Vec<crate::model_description::UnitDefinition>,
) {
    let n_in = unit.inputs.len();
    let mut variables = Vec::new();
    let mut units = Vec::new();
    let mut unit_attribute = |name: &str| match si_definition(name) {
        Some(def) => {
            if !units
                .iter()
                .any(|u: &crate::model_description::UnitDefinition| u.name == name)
            {
                units.push(def);
            }
            Some(name.to_owned())
        }
        None => None,
    };
    for (i, p) in unit.inputs.iter().enumerate() {
        let start = config.inputs.get(&p.name).copied().unwrap_or(0.0);
        variables.push(ScalarVariable {
            unit: unit_attribute(&p.unit),
            ..ScalarVariable::new(
                input_variable_name(unit, i),
                i as u32,
                describe::input(p),
                VariableCausality::Input,
                Value::Real(Some(start)),
            )
        });
    }
    for (i, p) in unit.outputs.iter().enumerate() {
        let (name, reference) = (p.name.clone(), (n_in + i) as u32);
        variables.push(ScalarVariable {
            unit: unit_attribute(&p.unit),
            ..ScalarVariable::calculated_output(name, reference, describe::output(p))
        });
    }
    for p in parameters {
        let variable = parameter_variable(p, kind);
        let unit = variable.unit.as_deref().and_then(&mut unit_attribute);
        variables.push(ScalarVariable { unit, ..variable });
    }
    (variables, units)
}

/// A parameter variable, described as the kind's documentation describes its
/// top-level key; a number of its own key carries the documented unit (when
/// slender knows it) and range. Fixed: the unit is built from its parameters at
/// instantiation and takes no change between steps.
fn parameter_variable(p: &ParameterVariable, kind: &KindInfo) -> ScalarVariable {
    let (top, whole) = match &p.target {
        ParameterTarget::Table(path) => (path[0].as_str(), path.len() == 1),
        ParameterTarget::Effect(_) => ("", false),
    };
    let info = kind.parameters.get(top).cloned().unwrap_or_default();
    let number = whole && matches!(p.start, Value::Real(_));
    let mut description = match (&p.target, info.meaning.is_empty()) {
        (ParameterTarget::Effect(e), _) => format!("whether the effect `{e}` is computed"),
        (_, true) => "scene parameter".to_owned(),
        (_, false) if whole => info.meaning.clone(),
        (_, false) => format!("part of `{top}`: {}", info.meaning),
    };
    if !info.unit.is_empty() && whole {
        description.push_str(&format!(" [{}]", info.unit));
    }
    description.push_str("; fixed at instantiation");
    ScalarVariable {
        unit: (number && !info.unit.is_empty()).then(|| info.unit.clone()),
        min: info.min.filter(|_| number),
        max: info.max.filter(|_| number),
        ..ScalarVariable::new(
            p.name.clone(),
            p.value_reference,
            description,
            VariableCausality::Parameter,
            p.start.clone(),
        )
        .fixed()
    }
}

/// The FMI name of input `i`: its port name, or `<name>_in` when an output has
/// the same name (FMI names must be unique; a beam end driven in moment also
/// reports its moment as an output).
pub fn input_variable_name(unit: &UnitDescription, i: usize) -> String {
    let name = &unit.inputs[i].name;
    if unit.outputs.iter().any(|o| &o.name == name) {
        format!("{name}_in")
    } else {
        name.clone()
    }
}

/// Collects the scalar entries of a parameter table as parameter variables.
fn flatten(table: &toml::Table, path: &mut Vec<String>, out: &mut Vec<ParameterVariable>) {
    for (key, value) in table {
        path.push(key.clone());
        let start = match value {
            toml::Value::Float(v) => Some(Value::Real(Some(*v))),
            toml::Value::Integer(v) => i32::try_from(*v).ok().map(|v| Value::Integer(Some(v))),
            toml::Value::Boolean(v) => Some(Value::Boolean(Some(*v))),
            toml::Value::String(v) => Some(Value::String(Some(v.clone()))),
            toml::Value::Table(t) => {
                flatten(t, path, out);
                None
            }
            _ => None,
        };
        if let Some(start) = start {
            out.push(ParameterVariable {
                name: path.join("."),
                value_reference: 0,
                target: ParameterTarget::Table(path.clone()),
                start,
            });
        }
        path.pop();
    }
}
