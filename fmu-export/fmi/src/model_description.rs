//! FMI 2.0 `modelDescription.xml`: the parts slender reads and writes.
//!
//! Parsing is strict where a co-simulation master needs the information (variable
//! names, value references, causality, types, start values, ModelStructure) and
//! lenient elsewhere (unknown elements and attributes are skipped, as the standard
//! allows vendor extensions). Every error names the element, the attribute and
//! the line.

use quick_xml::Reader;
use quick_xml::escape::escape;
use quick_xml::events::{BytesStart, Event};
use std::collections::HashMap;
use std::fmt::Write as _;
use thiserror::Error;

/// A problem in a model description, with the 1-based line where it was found.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("modelDescription.xml:{line}: {message}")]
pub struct DescriptionError {
    pub line: usize,
    pub message: String,
}

/// Where a variable sits in the model: FMI 2.0 `causality`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum VariableCausality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    Local,
    Independent,
}

impl VariableCausality {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "parameter" => Self::Parameter,
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
    Real(Option<f64>),
    Integer(Option<i32>),
    Boolean(Option<bool>),
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
    pub name: String,
    pub value_reference: u32,
    pub description: String,
    pub causality: VariableCausality,
    /// FMI `variability` ("constant", "fixed", "tunable", "discrete", "continuous").
    pub variability: String,
    /// FMI `initial` ("exact", "approx", "calculated"), when given.
    pub initial: Option<String>,
    pub value: Value,
    /// Unit of measure of a Real, by name (see [`UnitDefinition`]).
    pub unit: Option<String>,
}

/// A unit of measure: its name and SI base-unit exponents, factor and offset.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitDefinition {
    pub name: String,
    /// Exponents of kg, m, s, A, K, mol, cd, rad.
    pub exponents: [i32; 8],
    pub factor: f64,
    pub offset: f64,
}

/// The exponent attribute names of `BaseUnit`, in [`UnitDefinition::exponents`] order.
pub const BASE_UNITS: [&str; 8] = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"];

/// The `CoSimulation` element.
#[derive(Clone, Debug, PartialEq)]
pub struct CoSimulation {
    pub model_identifier: String,
    pub can_handle_variable_communication_step_size: bool,
    pub can_interpolate_inputs: bool,
    pub max_output_derivative_order: u32,
    pub can_get_and_set_fmu_state: bool,
    pub can_serialize_fmu_state: bool,
}

/// One `Unknown` of the ModelStructure: a variable (1-based index into the
/// variables) and the variables it depends on directly (`None`: on all of them,
/// the standard's meaning of a missing `dependencies` attribute).
#[derive(Clone, Debug, PartialEq)]
pub struct Unknown {
    pub index: usize,
    pub dependencies: Option<Vec<usize>>,
}

/// `DefaultExperiment` (s).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DefaultExperiment {
    pub start_time: Option<f64>,
    pub stop_time: Option<f64>,
    pub tolerance: Option<f64>,
    pub step_size: Option<f64>,
}

/// A model description.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelDescription {
    pub fmi_version: String,
    pub model_name: String,
    pub guid: String,
    pub description: String,
    pub generation_tool: String,
    pub co_simulation: Option<CoSimulation>,
    pub units: Vec<UnitDefinition>,
    pub variables: Vec<ScalarVariable>,
    pub outputs: Vec<Unknown>,
    pub initial_unknowns: Vec<Unknown>,
    pub default_experiment: Option<DefaultExperiment>,
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

    /// Parses a model description, checking what a co-simulation master relies on.
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
            r#"<fmiModelDescription fmiVersion="{}" modelName="{}" guid="{}" description="{}" generationTool="{}" variableNamingConvention="flat" numberOfEventIndicators="0">"#,
            e(&self.fmi_version),
            e(&self.model_name),
            e(&self.guid),
            e(&self.description),
            e(&self.generation_tool)
        );
        if let Some(cs) = &self.co_simulation {
            let _ = writeln!(
                x,
                r#"  <CoSimulation modelIdentifier="{}" canHandleVariableCommunicationStepSize="{}" canInterpolateInputs="{}" maxOutputDerivativeOrder="{}" canGetAndSetFMUstate="{}" canSerializeFMUstate="{}" canNotUseMemoryManagementFunctions="true" canBeInstantiatedOnlyOncePerProcess="false" needsExecutionTool="false"/>"#,
                e(&cs.model_identifier),
                cs.can_handle_variable_communication_step_size,
                cs.can_interpolate_inputs,
                cs.max_output_derivative_order,
                cs.can_get_and_set_fmu_state,
                cs.can_serialize_fmu_state
            );
        }
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
        x.push_str("  <ModelVariables>\n");
        for (i, v) in self.variables.iter().enumerate() {
            let _ = write!(
                x,
                r#"    <!-- {} --><ScalarVariable name="{}" valueReference="{}" description="{}" causality="{}" variability="{}""#,
                i + 1,
                e(&v.name),
                v.value_reference,
                e(&v.description),
                v.causality.name(),
                e(&v.variability)
            );
            if let Some(initial) = &v.initial {
                let _ = write!(x, r#" initial="{}""#, e(initial));
            }
            let _ = write!(x, "><{}", v.value.type_name());
            if let Some(unit) = &v.unit {
                let _ = write!(x, r#" unit="{}""#, e(unit));
            }
            match &v.value {
                Value::Real(Some(s)) => {
                    let _ = write!(x, r#" start="{s:e}""#);
                }
                Value::Integer(Some(s)) | Value::Enumeration(Some(s)) => {
                    let _ = write!(x, r#" start="{s}""#);
                }
                Value::Boolean(Some(s)) => {
                    let _ = write!(x, r#" start="{s}""#);
                }
                Value::String(Some(s)) => {
                    let _ = write!(x, r#" start="{}""#, e(s));
                }
                _ => {}
            }
            x.push_str("/></ScalarVariable>\n");
        }
        x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
        for (tag, list) in [
            ("Outputs", &self.outputs),
            ("InitialUnknowns", &self.initial_unknowns),
        ] {
            if list.is_empty() {
                continue;
            }
            let _ = writeln!(x, "    <{tag}>");
            for u in list {
                let _ = write!(x, r#"      <Unknown index="{}""#, u.index);
                if let Some(deps) = &u.dependencies {
                    let deps: Vec<String> = deps.iter().map(|d| d.to_string()).collect();
                    let _ = write!(x, r#" dependencies="{}""#, deps.join(" "));
                }
                x.push_str("/>\n");
            }
            let _ = writeln!(x, "    </{tag}>");
        }
        x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
        x
    }
}

/// The state of one parse: the reader, and the element path.
struct Parser<'a> {
    xml: &'a str,
    reader: Reader<&'a [u8]>,
    path: Vec<String>,
}

/// The attributes of one element, by name.
struct Attributes {
    element: String,
    line: usize,
    values: HashMap<String, String>,
}

impl Attributes {
    fn error(&self, message: String) -> DescriptionError {
        DescriptionError {
            line: self.line,
            message: format!("<{}>: {message}", self.element),
        }
    }

    fn optional(&self, name: &str) -> Option<&str> {
        self.values.get(name).map(String::as_str)
    }

    fn required(&self, name: &str) -> Result<&str, DescriptionError> {
        self.optional(name)
            .ok_or_else(|| self.error(format!("missing required attribute `{name}`")))
    }

    fn parsed<T: std::str::FromStr>(
        &self,
        name: &str,
        expected: &str,
    ) -> Result<Option<T>, DescriptionError> {
        match self.optional(name) {
            None => Ok(None),
            Some(v) => v.trim().parse().map(Some).map_err(|_| {
                self.error(format!("attribute `{name}` = \"{v}\": expected {expected}"))
            }),
        }
    }

    fn flag(&self, name: &str) -> Result<bool, DescriptionError> {
        match self.optional(name) {
            None | Some("false") | Some("0") => Ok(false),
            Some("true") | Some("1") => Ok(true),
            Some(v) => Err(self.error(format!(
                "attribute `{name}` = \"{v}\": expected true or false"
            ))),
        }
    }
}

impl<'a> Parser<'a> {
    fn new(xml: &'a str) -> Parser<'a> {
        Parser {
            xml,
            reader: Reader::from_str(xml),
            path: Vec::new(),
        }
    }

    fn line(&self, position: u64) -> usize {
        let end = (position as usize).min(self.xml.len());
        self.xml.as_bytes()[..end]
            .iter()
            .filter(|b| **b == b'\n')
            .count()
            + 1
    }

    fn error_here(&self, message: String) -> DescriptionError {
        DescriptionError {
            line: self.line(self.reader.buffer_position()),
            message,
        }
    }

    fn attributes(&self, e: &BytesStart) -> Result<Attributes, DescriptionError> {
        let element = String::from_utf8_lossy(e.name().as_ref()).into_owned();
        let line = self.line(self.reader.buffer_position());
        let mut values = HashMap::new();
        for a in e.attributes() {
            let a = a.map_err(|err| DescriptionError {
                line,
                message: format!("<{element}>: malformed attribute ({err})"),
            })?;
            let key = String::from_utf8_lossy(a.key.as_ref()).into_owned();
            let value = a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| DescriptionError {
                    line,
                    message: format!("<{element}>: attribute `{key}` does not unescape ({err})"),
                })?;
            values.insert(key, value.into_owned());
        }
        Ok(Attributes {
            element,
            line,
            values,
        })
    }

    fn run(mut self) -> Result<ModelDescription, DescriptionError> {
        let mut md: Option<ModelDescription> = None;
        let mut current_variable: Option<(Attributes, Option<ScalarVariable>)> = None;
        let mut current_unit: Option<UnitDefinition> = None;
        loop {
            let event = self
                .reader
                .read_event()
                .map_err(|e| self.error_here(format!("not well-formed XML ({e})")))?;
            let (element, is_empty) = match &event {
                Event::Start(e) => (Some(e.clone()), false),
                Event::Empty(e) => (Some(e.clone()), true),
                Event::End(_) => {
                    let closed = self.path.pop().unwrap_or_default();
                    if closed == "ScalarVariable" {
                        self.finish_variable(&mut md, current_variable.take())?;
                    } else if closed == "Unit"
                        && let (Some(m), Some(u)) = (md.as_mut(), current_unit.take())
                    {
                        m.units.push(u);
                    }
                    continue;
                }
                Event::Eof => break,
                _ => continue,
            };
            let Some(element) = element else { continue };
            let attrs = self.attributes(&element)?;
            let name = attrs.element.clone();
            let parent = self.path.last().map(String::as_str).unwrap_or("");
            match (parent, name.as_str()) {
                ("", "fmiModelDescription") => md = Some(Self::root(&attrs)?),
                ("", other) => {
                    return Err(attrs.error(format!(
                        "the root element must be <fmiModelDescription>, found <{other}>"
                    )));
                }
                ("fmiModelDescription", "CoSimulation") => {
                    if let Some(m) = md.as_mut() {
                        m.co_simulation = Some(CoSimulation {
                            model_identifier: attrs.required("modelIdentifier")?.to_owned(),
                            can_handle_variable_communication_step_size: attrs
                                .flag("canHandleVariableCommunicationStepSize")?,
                            can_interpolate_inputs: attrs.flag("canInterpolateInputs")?,
                            max_output_derivative_order: attrs
                                .parsed("maxOutputDerivativeOrder", "an unsigned integer")?
                                .unwrap_or(0),
                            can_get_and_set_fmu_state: attrs.flag("canGetAndSetFMUstate")?,
                            can_serialize_fmu_state: attrs.flag("canSerializeFMUstate")?,
                        });
                    }
                }
                ("fmiModelDescription", "DefaultExperiment") => {
                    if let Some(m) = md.as_mut() {
                        m.default_experiment = Some(DefaultExperiment {
                            start_time: attrs.parsed("startTime", "a number")?,
                            stop_time: attrs.parsed("stopTime", "a number")?,
                            tolerance: attrs.parsed("tolerance", "a number")?,
                            step_size: attrs.parsed("stepSize", "a number")?,
                        });
                    }
                }
                ("UnitDefinitions", "Unit") => {
                    current_unit = Some(UnitDefinition {
                        name: attrs.required("name")?.to_owned(),
                        exponents: [0; 8],
                        factor: 1.0,
                        offset: 0.0,
                    });
                    if is_empty && let (Some(m), Some(u)) = (md.as_mut(), current_unit.take()) {
                        m.units.push(u);
                    }
                }
                ("Unit", "BaseUnit") => {
                    if let Some(u) = current_unit.as_mut() {
                        for (i, base) in BASE_UNITS.iter().enumerate() {
                            u.exponents[i] = attrs.parsed(base, "an integer")?.unwrap_or(0);
                        }
                        u.factor = attrs.parsed("factor", "a number")?.unwrap_or(1.0);
                        u.offset = attrs.parsed("offset", "a number")?.unwrap_or(0.0);
                    }
                }
                ("ModelVariables", "ScalarVariable") => {
                    current_variable = Some((attrs, None));
                    if is_empty {
                        self.finish_variable(&mut md, current_variable.take())?;
                        continue;
                    }
                }
                ("ScalarVariable", "Real" | "Integer" | "Boolean" | "String" | "Enumeration") => {
                    if let Some((sv_attrs, typed)) = current_variable.as_mut() {
                        if typed.is_some() {
                            return Err(
                                attrs.error("a ScalarVariable has two type elements".into())
                            );
                        }
                        *typed = Some(Self::variable(sv_attrs, &attrs)?);
                    }
                }
                ("Outputs" | "InitialUnknowns" | "Derivatives", "Unknown") => {
                    let unknown = Unknown {
                        index: attrs
                            .parsed("index", "a 1-based variable index")?
                            .ok_or_else(|| {
                                attrs.error("missing required attribute `index`".into())
                            })?,
                        dependencies: match attrs.optional("dependencies") {
                            None => None,
                            Some(list) => Some(
                                list.split_whitespace()
                                    .map(|d| {
                                        d.parse().map_err(|_| {
                                            attrs.error(format!(
                                                "dependencies: `{d}` is not a variable index"
                                            ))
                                        })
                                    })
                                    .collect::<Result<Vec<usize>, _>>()?,
                            ),
                        },
                    };
                    if let Some(m) = md.as_mut() {
                        match parent {
                            "Outputs" => m.outputs.push(unknown),
                            "InitialUnknowns" => m.initial_unknowns.push(unknown),
                            _ => {}
                        }
                    }
                }
                _ => {}
            }
            if !is_empty {
                self.path.push(name);
            }
        }
        let md = md.ok_or_else(|| DescriptionError {
            line: 1,
            message: "no <fmiModelDescription> element".into(),
        })?;
        Self::check(&md, self.line(self.xml.len() as u64))?;
        Ok(md)
    }

    fn root(a: &Attributes) -> Result<ModelDescription, DescriptionError> {
        let version = a.required("fmiVersion")?;
        if version != "2.0" {
            return Err(a.error(format!(
                "fmiVersion = \"{version}\": only FMI 2.0 is supported"
            )));
        }
        Ok(ModelDescription {
            fmi_version: version.to_owned(),
            model_name: a.required("modelName")?.to_owned(),
            guid: a.required("guid")?.to_owned(),
            description: a.optional("description").unwrap_or("").to_owned(),
            generation_tool: a.optional("generationTool").unwrap_or("").to_owned(),
            co_simulation: None,
            units: Vec::new(),
            variables: Vec::new(),
            outputs: Vec::new(),
            initial_unknowns: Vec::new(),
            default_experiment: None,
        })
    }

    fn variable(sv: &Attributes, t: &Attributes) -> Result<ScalarVariable, DescriptionError> {
        let causality_text = sv.optional("causality").unwrap_or("local");
        let causality = VariableCausality::parse(causality_text).ok_or_else(|| {
            sv.error(format!(
                "causality = \"{causality_text}\": expected parameter, calculatedParameter, input, output, local or independent"
            ))
        })?;
        let value = match t.element.as_str() {
            "Real" => Value::Real(t.parsed("start", "a real number")?),
            "Integer" => Value::Integer(t.parsed("start", "a 32-bit integer")?),
            "Enumeration" => Value::Enumeration(t.parsed("start", "a 32-bit integer")?),
            "Boolean" => Value::Boolean(match t.optional("start") {
                None => None,
                Some("true") | Some("1") => Some(true),
                Some("false") | Some("0") => Some(false),
                Some(v) => {
                    return Err(t.error(format!("start = \"{v}\": expected true or false")));
                }
            }),
            _ => Value::String(t.optional("start").map(str::to_owned)),
        };
        Ok(ScalarVariable {
            name: sv.required("name")?.to_owned(),
            value_reference: sv
                .parsed("valueReference", "an unsigned 32-bit integer")?
                .ok_or_else(|| sv.error("missing required attribute `valueReference`".into()))?,
            description: sv.optional("description").unwrap_or("").to_owned(),
            causality,
            variability: sv
                .optional("variability")
                .unwrap_or("continuous")
                .to_owned(),
            initial: sv.optional("initial").map(str::to_owned),
            unit: t.optional("unit").map(str::to_owned),
            value,
        })
    }

    fn finish_variable(
        &self,
        md: &mut Option<ModelDescription>,
        current: Option<(Attributes, Option<ScalarVariable>)>,
    ) -> Result<(), DescriptionError> {
        let Some((attrs, typed)) = current else {
            return Ok(());
        };
        let variable = typed.ok_or_else(|| {
            attrs.error(format!(
                "variable `{}` has no type element (Real, Integer, Boolean, String or Enumeration)",
                attrs.optional("name").unwrap_or("?")
            ))
        })?;
        let needs_start = matches!(
            variable.causality,
            VariableCausality::Input | VariableCausality::Parameter
        );
        if needs_start && !variable.value.has_start() {
            return Err(attrs.error(format!(
                "{} `{}` has no start value (FMI 2.0 requires one for inputs and parameters)",
                variable.causality.name(),
                variable.name
            )));
        }
        if let Some(m) = md.as_mut() {
            m.variables.push(variable);
        }
        Ok(())
    }

    /// Checks across elements: unique value references per type, indices in range,
    /// declared units.
    fn check(md: &ModelDescription, last_line: usize) -> Result<(), DescriptionError> {
        let error = |message: String| DescriptionError {
            line: last_line,
            message,
        };
        let mut seen = HashMap::new();
        for v in &md.variables {
            if let Some(other) = seen.insert((v.value.type_name(), v.value_reference), &v.name) {
                // Aliases share a value reference legitimately; only report when
                // one of them is an input, which the master would write twice.
                if v.causality == VariableCausality::Input {
                    return Err(error(format!(
                        "input `{}` shares value reference {} with `{other}`",
                        v.name, v.value_reference
                    )));
                }
            }
        }
        let n = md.variables.len();
        for (tag, list) in [
            ("Outputs", &md.outputs),
            ("InitialUnknowns", &md.initial_unknowns),
        ] {
            for u in list {
                if u.index == 0 || u.index > n {
                    return Err(error(format!(
                        "ModelStructure/{tag}: index {} is outside 1..={n}",
                        u.index
                    )));
                }
                if let Some(bad) = u
                    .dependencies
                    .iter()
                    .flatten()
                    .find(|d| **d == 0 || **d > n)
                {
                    return Err(error(format!(
                        "ModelStructure/{tag}: dependency {bad} of index {} is outside 1..={n}",
                        u.index
                    )));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> ModelDescription {
        ModelDescription {
            fmi_version: "2.0".into(),
            model_name: "m".into(),
            guid: "{1}".into(),
            description: "a & b".into(),
            generation_tool: "slender".into(),
            co_simulation: Some(CoSimulation {
                model_identifier: "m".into(),
                can_handle_variable_communication_step_size: true,
                can_interpolate_inputs: true,
                max_output_derivative_order: 0,
                can_get_and_set_fmu_state: true,
                can_serialize_fmu_state: true,
            }),
            units: vec![UnitDefinition {
                name: "N".into(),
                exponents: [1, 1, -2, 0, 0, 0, 0, 0],
                factor: 1.0,
                offset: 0.0,
            }],
            variables: vec![
                ScalarVariable {
                    name: "f".into(),
                    value_reference: 0,
                    description: String::new(),
                    causality: VariableCausality::Input,
                    variability: "continuous".into(),
                    initial: None,
                    value: Value::Real(Some(0.1)),
                    unit: Some("N".into()),
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
                },
            ],
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
        }
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
}
