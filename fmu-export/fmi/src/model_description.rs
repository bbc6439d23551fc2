//! FMI 2.0 `modelDescription.xml`: the parts slender reads and writes.
//!
//! Parsing is strict where a co-simulation master needs the information (variable
//! names, value references, causality, types, start values, ModelStructure) and
//! lenient elsewhere (unknown elements and attributes are skipped, as the standard
//! allows vendor extensions). Every error names the element, the attribute and
//! the line.

use quick_xml::escape::escape;
use std::collections::HashMap;
use std::fmt::Write as _;
use thiserror::Error;

/// A problem in a model description, with the 1-based line where it was found.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("modelDescription.xml:{line}: {message}")]
pub struct DescriptionError {
    /// 1-based line of the problem.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// Where a variable sits in the model: FMI 2.0 `causality`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum VariableCausality {
    /// A parameter.
    Parameter,
    /// An FMI 3.0 structural parameter: one that sizes arrays (FMI 2.0 has
    /// none; its description leaves them out).
    StructuralParameter,
    /// A parameter the FMU computes.
    CalculatedParameter,
    /// An input.
    Input,
    /// An output.
    Output,
    /// A local variable.
    Local,
    /// The independent variable (time).
    Independent,
}

impl VariableCausality {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "parameter" => Self::Parameter,
            "structuralParameter" => Self::StructuralParameter,
            "calculatedParameter" => Self::CalculatedParameter,
            "input" => Self::Input,
            "output" => Self::Output,
            "local" => Self::Local,
            "independent" => Self::Independent,
            _ => return None,
        })
    }

    fn name(self) -> &'static str {
        match self {
            Self::Parameter => "parameter",
            Self::StructuralParameter => "structuralParameter",
            Self::CalculatedParameter => "calculatedParameter",
            Self::Input => "input",
            Self::Output => "output",
            Self::Local => "local",
            Self::Independent => "independent",
        }
    }
}

/// A variable's type and start value (FMI 2.0 type elements).
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A real (FMI 3.0: Float64), with its start.
    Real(Option<f64>),
    /// An integer (FMI 3.0: Int32), with its start.
    Integer(Option<i32>),
    /// A Boolean, with its start.
    Boolean(Option<bool>),
    /// A string, with its start.
    String(Option<String>),
    /// An enumeration (an integer underneath).
    Enumeration(Option<i32>),
}

impl Value {
    /// The FMI type element's name.
    pub fn type_name(&self) -> &'static str {
        match self {
            Value::Real(_) => "Real",
            Value::Integer(_) => "Integer",
            Value::Boolean(_) => "Boolean",
            Value::String(_) => "String",
            Value::Enumeration(_) => "Enumeration",
        }
    }

    fn has_start(&self) -> bool {
        match self {
            Value::Real(v) => v.is_some(),
            Value::Integer(v) | Value::Enumeration(v) => v.is_some(),
            Value::Boolean(v) => v.is_some(),
            Value::String(v) => v.is_some(),
        }
    }
}

/// One `ScalarVariable`.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalarVariable {
    /// The variable's name (flat naming).
    pub name: String,
    /// Its value reference.
    pub value_reference: u32,
    /// What it is.
    pub description: String,
    /// Its causality.
    pub causality: VariableCausality,
    /// FMI `variability` ("constant", "fixed", "tunable", "discrete", "continuous").
    pub variability: String,
    /// FMI `initial` ("exact", "approx", "calculated"), when given.
    pub initial: Option<String>,
    /// Its type and start value.
    pub value: Value,
    /// Unit of measure of a Real, by name (see [`UnitDefinition`]).
    pub unit: Option<String>,
    /// Bounds of a Real's value, when stated (inclusive).
    pub min: Option<f64>,
    /// Upper bound of a Real's value, inclusive.
    pub max: Option<f64>,
    /// An FMI 3.0 array's length in each dimension, row-major (empty: a
    /// scalar; FMI 2.0 has none). The FMI 2.0 description leaves arrays out.
    pub dimensions: Vec<usize>,
    /// The value reference of the structural parameter that sizes a
    /// one-dimensional array (`dimensions` then holds its start).
    pub sized_by: Option<u32>,
    /// FMI 3.0 `<Alias>` names: other names of the same variable.
    pub aliases: Vec<String>,
}

impl ScalarVariable {
    /// A scalar of `causality` holding `value`, continuous, with no `initial`,
    /// unit, bounds, dimensions or aliases: the fields that differ are set
    /// over it (`ScalarVariable { unit, ..ScalarVariable::new(..) }`).
    pub fn new(
        name: String,
        value_reference: u32,
        description: String,
        causality: VariableCausality,
        value: Value,
    ) -> ScalarVariable {
        ScalarVariable {
            name,
            value_reference,
            description,
            causality,
            variability: "continuous".into(),
            initial: None,
            value,
            unit: None,
            min: None,
            max: None,
            dimensions: Vec::new(),
            sized_by: None,
            aliases: Vec::new(),
        }
    }

    /// A continuous output the FMU calculates (a Real with no start value).
    pub fn calculated_output(
        name: String,
        value_reference: u32,
        description: String,
    ) -> ScalarVariable {
        ScalarVariable {
            initial: Some("calculated".into()),
            ..ScalarVariable::new(
                name,
                value_reference,
                description,
                VariableCausality::Output,
                Value::Real(None),
            )
        }
    }

    /// The variable fixed at instantiation, its start value exact (a
    /// parameter or a structural parameter).
    pub fn fixed(self) -> ScalarVariable {
        ScalarVariable {
            variability: "fixed".into(),
            initial: Some("exact".into()),
            ..self
        }
    }

    /// How many values the variable holds (1 for a scalar).
    pub fn len(&self) -> usize {
        self.dimensions.iter().product()
    }

    /// Whether it holds no value (an array with a zero dimension).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Who made a model and under what terms: the optional attributes of
/// `fmiModelDescription` (empty strings are left out).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct About {
    /// `author`.
    pub author: String,
    /// The model's version.
    pub version: String,
    /// `copyright`.
    pub copyright: String,
    /// `license`.
    pub license: String,
    /// `generationDateAndTime` (xs:dateTime, UTC).
    pub generation_date_and_time: Option<String>,
}

/// A log category the FMU sends messages in (`LogCategories/Category`).
#[derive(Clone, Debug, PartialEq)]
pub struct LogCategory {
    /// The category's name (e.g. `logStatusError`).
    pub name: String,
    /// What messages it holds.
    pub description: String,
}

/// A unit of measure: its name and SI base-unit exponents, factor and offset.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitDefinition {
    /// The unit's name as variables refer to it (e.g. `N/m`).
    pub name: String,
    /// Exponents of kg, m, s, A, K, mol, cd, rad.
    pub exponents: [i32; 8],
    /// Factor to the SI base units: value_SI = factor value + offset.
    pub factor: f64,
    /// Offset to the SI base units.
    pub offset: f64,
}

/// The exponent attribute names of `BaseUnit`, in [`UnitDefinition::exponents`] order.
pub const BASE_UNITS: [&str; 8] = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"];

/// The `CoSimulation` element.
#[derive(Clone, Debug, PartialEq)]
pub struct CoSimulation {
    /// `modelIdentifier`: the binary's name.
    pub model_identifier: String,
    /// `canHandleVariableCommunicationStepSize`.
    pub can_handle_variable_communication_step_size: bool,
    /// `canInterpolateInputs` (FMI 2.0).
    pub can_interpolate_inputs: bool,
    /// `maxOutputDerivativeOrder`.
    pub max_output_derivative_order: u32,
    /// `canGetAndSetFMUstate`: rollback.
    pub can_get_and_set_fmu_state: bool,
    /// `canSerializeFMUstate`.
    pub can_serialize_fmu_state: bool,
    /// `fmi2GetDirectionalDerivative` answers (for slender's FMUs: the step
    /// Jacobian of the last `fmi2DoStep`).
    pub provides_directional_derivative: bool,
}

/// One `Unknown` of the ModelStructure: a variable (1-based index into the
/// variables) and the variables it depends on directly (`None`: on all of them,
/// the standard's meaning of a missing `dependencies` attribute).
#[derive(Clone, Debug, PartialEq)]
pub struct Unknown {
    /// The variable (1-based index).
    pub index: usize,
    /// The variables it depends on directly (1-based); `None`: all.
    pub dependencies: Option<Vec<usize>>,
}

/// `DefaultExperiment` (s).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DefaultExperiment {
    /// `startTime` (s).
    pub start_time: Option<f64>,
    /// `stopTime` (s).
    pub stop_time: Option<f64>,
    /// `tolerance` (relative).
    pub tolerance: Option<f64>,
    /// `stepSize` (s).
    pub step_size: Option<f64>,
}

/// A model description.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelDescription {
    /// `fmiVersion` ("2.0" or "3.0").
    pub fmi_version: String,
    /// `modelName`.
    pub model_name: String,
    /// `guid` (FMI 3.0: `instantiationToken`).
    pub guid: String,
    /// `description`.
    pub description: String,
    /// `generationTool`.
    pub generation_tool: String,
    /// The optional attributes on who made it.
    pub about: About,
    /// The `CoSimulation` element, when the FMU offers co-simulation.
    pub co_simulation: Option<CoSimulation>,
    /// `UnitDefinitions`.
    pub units: Vec<UnitDefinition>,
    /// `LogCategories`.
    pub log_categories: Vec<LogCategory>,
    /// The variables, in the description's order.
    pub variables: Vec<ScalarVariable>,
    /// `ModelStructure/Outputs`.
    pub outputs: Vec<Unknown>,
    /// `ModelStructure/InitialUnknowns`.
    pub initial_unknowns: Vec<Unknown>,
    /// `DefaultExperiment`, when given.
    pub default_experiment: Option<DefaultExperiment>,
    /// FMI 3.0 clocks and the variables they tick (`name`, or `name (clocked
    /// by ...)`): slender does not run clocked FMUs, and refuses them by these.
    pub clocks: Vec<String>,
}

impl ModelDescription {
    /// The variable with this value reference and type name ("Real", ...).
    pub fn variable(&self, value_reference: u32, type_name: &str) -> Option<&ScalarVariable> {
        self.variables
            .iter()
            .find(|v| v.value_reference == value_reference && v.value.type_name() == type_name)
    }

    /// The unit definition called `name`.
    pub fn unit(&self, name: &str) -> Option<&UnitDefinition> {
        self.units.iter().find(|u| u.name == name)
    }

    /// Parses a model description (FMI 2.0 or 3.0), checking what a
    /// co-simulation master relies on. FMI 3.0's Float64, Int32, Boolean and
    /// String variables are read (arrays with their dimensions); variables of
    /// other types are left out, and the model structure refers to variables
    /// by index as FMI 2.0 does.
    pub fn parse(xml: &str) -> Result<ModelDescription, DescriptionError> {
        Parser::new(xml).run()
    }

    /// Writes the description as FMI 2.0 XML.
    pub fn to_xml(&self) -> String {
        let mut x = String::new();
        let e = |s: &str| escape(s).into_owned();
        let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
        let _ = writeln!(
            x,
            r#"<fmiModelDescription fmiVersion="{}" {} variableNamingConvention="flat" numberOfEventIndicators="0">"#,
            e(&self.fmi_version),
            self.root_attributes("guid"),
        );
        if let Some(cs) = &self.co_simulation {
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{}" canHandleVariableCommunicationStepSize="{}" canInterpolateInputs="{}" maxOutputDerivativeOrder="{}" canGetAndSetFMUstate="{}" canSerializeFMUstate="{}" providesDirectionalDerivative="{}" canNotUseMemoryManagementFunctions="true" canBeInstantiatedOnlyOncePerProcess="false" needsExecutionTool="false"/>"#,
                e(&cs.model_identifier),
                cs.can_handle_variable_communication_step_size,
                cs.can_interpolate_inputs,
                cs.max_output_derivative_order,
                cs.can_get_and_set_fmu_state,
                cs.can_serialize_fmu_state,
                cs.provides_directional_derivative
            );
        }
        self.write_declarations(&mut x);
        // Arrays and the structural parameters that size them are FMI 3.0's
        // and come after every scalar, so leaving them out keeps the
        // scalars' indices.
        for (i, v) in self.variables.iter().enumerate() {
            if v.dimensions.is_empty() && v.causality != VariableCausality::StructuralParameter {
                write_variable(&mut x, i, v);
            }
        }
        x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
        self.write_structure(&mut x);
        x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
        x
    }

    /// The [`About`] attributes that are given, each with a leading space.
    /// The root element's `modelName`, the token (FMI 2.0 `guid`, FMI 3.0
    /// `instantiationToken`), `description`, `generationTool` and the
    /// attributes on who made it, escaped.
    fn root_attributes(&self, token: &str) -> String {
        let e = |s: &str| escape(s).into_owned();
        format!(
            r#"modelName="{}" {token}="{}" description="{}" generationTool="{}"{}"#,
            e(&self.model_name),
            e(&self.guid),
            e(&self.description),
            e(&self.generation_tool),
            self.about_attributes()
        )
    }

    fn about_attributes(&self) -> String {
        let a = &self.about;
        let date = a.generation_date_and_time.as_deref().unwrap_or("");
        [
            ("author", a.author.as_str()),
            ("version", a.version.as_str()),
            ("copyright", a.copyright.as_str()),
            ("license", a.license.as_str()),
            ("generationDateAndTime", date),
        ]
        .iter()
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, v)| format!(r#" {k}="{}""#, escape(*v)))
        .collect()
    }

    /// What both versions write between `<CoSimulation>` and the variables:
    /// units, log categories and the default experiment, then the opening
    /// `<ModelVariables>`.
    pub(crate) fn write_declarations(&self, x: &mut String) {
        self.write_units(x);
        self.write_log_categories(x);
        self.write_default_experiment(x);
        x.push_str("  <ModelVariables>\n");
    }

    /// `<LogCategories>`, when any is declared.
    fn write_log_categories(&self, x: &mut String) {
        let e = |s: &str| escape(s).into_owned();
        if !self.log_categories.is_empty() {
            x.push_str("  <LogCategories>\n");
            for c in &self.log_categories {
                let _ = writeln!(
                    x,
                    r#"    <Category name="{}" description="{}"/>"#,
                    e(&c.name),
                    e(&c.description)
                );
            }
            x.push_str("  </LogCategories>\n");
        }
    }

    /// `<DefaultExperiment>`, when given.
    fn write_default_experiment(&self, x: &mut String) {
        if let Some(d) = &self.default_experiment {
            x.push_str("  <DefaultExperiment");
            for (name, v) in [
                ("startTime", d.start_time),
                ("stopTime", d.stop_time),
                ("tolerance", d.tolerance),
                ("stepSize", d.step_size),
            ] {
                if let Some(v) = v {
                    let _ = write!(x, r#" {name}="{v:e}""#);
                }
            }
            x.push_str("/>\n");
        }
    }

    /// `<UnitDefinitions>`, when any unit is declared.
    fn write_units(&self, x: &mut String) {
        let e = |s: &str| escape(s).into_owned();
        if !self.units.is_empty() {
            x.push_str("  <UnitDefinitions>\n");
            for u in &self.units {
                let _ = write!(x, r#"    <Unit name="{}"><BaseUnit"#, e(&u.name));
                for (name, exp) in BASE_UNITS.iter().zip(u.exponents) {
                    if exp != 0 {
                        let _ = write!(x, r#" {name}="{exp}""#);
                    }
                }
                if u.factor != 1.0 {
                    let _ = write!(x, r#" factor="{:e}""#, u.factor);
                }
                if u.offset != 0.0 {
                    let _ = write!(x, r#" offset="{:e}""#, u.offset);
                }
                x.push_str("/></Unit>\n");
            }
            x.push_str("  </UnitDefinitions>\n");
        }
    }

    /// `<ModelStructure>`'s outputs and initial unknowns.
    fn write_structure(&self, x: &mut String) {
        for (tag, list) in [
            ("Outputs", &self.outputs),
            ("InitialUnknowns", &self.initial_unknowns),
        ] {
            let scalar = |u: &&Unknown| self.variables[u.index - 1].dimensions.is_empty();
            if !list.iter().any(|u| scalar(&u)) {
                continue;
            }
            let _ = writeln!(x, "    <{tag}>");
            for u in list.iter().filter(scalar) {
                let _ = write!(x, r#"      <Unknown index="{}""#, u.index);
                if let Some(deps) = &u.dependencies {
                    let deps: Vec<String> = deps.iter().map(|d| d.to_string()).collect();
                    let _ = write!(x, r#" dependencies="{}""#, deps.join(" "));
                }
                x.push_str("/>\n");
            }
            let _ = writeln!(x, "    </{tag}>");
        }
    }
}

/// One `<ScalarVariable>` (numbered `i + 1` in a comment) with its type element.
fn write_variable(x: &mut String, i: usize, v: &ScalarVariable) {
    let e = |s: &str| escape(s).into_owned();
    let _ = write!(x, "    <!-- {} --><ScalarVariable", i + 1);
    write_variable_attributes(x, v);
    let _ = write!(x, "><{}{}", v.value.type_name(), type_attributes(v));
    if let Some(start) = start_text(&v.value) {
        let _ = write!(x, r#" start="{}""#, e(&start));
    }
    x.push_str("/></ScalarVariable>\n");
}

/// A variable's `name`, `valueReference`, `description`, `causality`,
/// `variability` and `initial` attributes (each with a leading space), the
/// same in FMI 2.0's `<ScalarVariable>` and FMI 3.0's variable element.
fn write_variable_attributes(x: &mut String, v: &ScalarVariable) {
    let e = |s: &str| escape(s).into_owned();
    let _ = write!(
        x,
        r#" name="{}" valueReference="{}" description="{}" causality="{}" variability="{}""#,
        e(&v.name),
        v.value_reference,
        e(&v.description),
        v.causality.name(),
        e(&v.variability)
    );
    if let Some(initial) = &v.initial {
        let _ = write!(x, r#" initial="{}""#, e(initial));
    }
}

/// A variable's `unit`, `min` and `max` attributes (each with a leading space),
/// the same in FMI 2.0's type element and FMI 3.0's variable element.
fn type_attributes(v: &ScalarVariable) -> String {
    let mut x = String::new();
    if let Some(unit) = &v.unit {
        let _ = write!(x, r#" unit="{}""#, escape(unit.as_str()));
    }
    for (name, bound) in [("min", v.min), ("max", v.max)] {
        if let Some(bound) = bound {
            let _ = write!(x, r#" {name}="{bound:e}""#);
        }
    }
    x
}

/// A start value as written (unescaped), when there is one.
fn start_text(value: &Value) -> Option<String> {
    match value {
        Value::Real(Some(s)) => Some(format!("{s:e}")),
        Value::Integer(Some(s)) | Value::Enumeration(Some(s)) => Some(s.to_string()),
        Value::Boolean(Some(s)) => Some(s.to_string()),
        Value::String(Some(s)) => Some(s.clone()),
        _ => None,
    }
}

mod fmi3;
mod parse;
use parse::Parser;

#[cfg(test)]
mod tests;
