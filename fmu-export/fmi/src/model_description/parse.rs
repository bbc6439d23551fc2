//! Reading `modelDescription.xml` (quick-xml): the element path, located errors,
//! and the checks a co-simulation master relies on.

use super::*;
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// What a parse has read so far: the description, and the variable and unit
/// definition being read.
#[derive(Default)]
struct ParseState {
    md: Option<ModelDescription>,
    variable: Option<(Attributes, Option<ScalarVariable>)>,
    unit: Option<UnitDefinition>,
    /// What only an FMI 3.0 description needs.
    fmi3: Option<fmi3::Pending>,
}

mod fmi3;

/// The state of one parse: the reader, and the element path.
pub(super) struct Parser<'a> {
    xml: &'a str,
    reader: Reader<&'a [u8]>,
    path: Vec<String>,
}

/// The attributes of one element, by name.
#[derive(Clone)]
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

    /// A whitespace-separated list of numbers (`None` when the attribute is
    /// absent, which a model structure reads differently from an empty list).
    fn list<T: std::str::FromStr>(
        &self,
        name: &str,
        expected: &str,
    ) -> Result<Option<Vec<T>>, DescriptionError> {
        let Some(list) = self.optional(name) else {
            return Ok(None);
        };
        let item = |d: &str| {
            d.parse()
                .map_err(|_| self.error(format!("{name}: `{d}` is not {expected}")))
        };
        list.split_whitespace()
            .map(item)
            .collect::<Result<_, _>>()
            .map(Some)
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
    pub(super) fn new(xml: &'a str) -> Parser<'a> {
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

    pub(super) fn run(mut self) -> Result<ModelDescription, DescriptionError> {
        let mut state = ParseState::default();
        loop {
            let event = self
                .reader
                .read_event()
                .map_err(|e| self.error_here(format!("not well-formed XML ({e})")))?;
            let (element, is_empty) = match &event {
                Event::Start(e) => (e.clone(), false),
                Event::Empty(e) => (e.clone(), true),
                Event::End(_) => {
                    let closed = self.path.pop().unwrap_or_default();
                    self.close(&closed, &mut state)?;
                    continue;
                }
                Event::Eof => break,
                _ => continue,
            };
            let attrs = self.attributes(&element)?;
            let name = attrs.element.clone();
            let opened = self.element(attrs, is_empty, &mut state)?;
            if opened {
                self.path.push(name);
            }
        }
        if let (Some(md), Some(mut pending)) = (state.md.as_mut(), state.fmi3.take()) {
            pending.last_line = self.line(self.xml.len() as u64);
            pending.resolve(md)?;
        }
        let md = state.md.ok_or_else(|| DescriptionError {
            line: 1,
            message: "no <fmiModelDescription> element".into(),
        })?;
        Self::check(&md, self.line(self.xml.len() as u64))?;
        Ok(md)
    }

    /// The end of an element: a variable or unit definition is complete.
    fn close(&mut self, closed: &str, state: &mut ParseState) -> Result<(), DescriptionError> {
        if state.fmi3.is_some() && self.path.last().is_some_and(|p| p == "ModelVariables") {
            self.finish_variable3(state)?;
        } else if closed == "ScalarVariable" {
            self.finish_variable(&mut state.md, state.variable.take())?;
        } else if closed == "Unit"
            && let (Some(m), Some(u)) = (state.md.as_mut(), state.unit.take())
        {
            m.units.push(u);
        }
        Ok(())
    }

    /// The root element (which says the FMI version), or an element of an
    /// FMI 3.0 description where it differs from FMI 2.0: whether it stays
    /// open, or `None` when it is read as FMI 2.0 reads it.
    fn root_or_fmi3(
        &mut self,
        parent: &str,
        attrs: &Attributes,
        is_empty: bool,
        state: &mut ParseState,
    ) -> Result<Option<bool>, DescriptionError> {
        if state.fmi3.is_some() {
            return self.element3(parent, attrs.clone(), is_empty, state);
        }
        match (parent, attrs.element.as_str()) {
            ("", "fmiModelDescription") => {}
            ("", other) => {
                return Err(attrs.error(format!(
                    "the root element must be <fmiModelDescription>, found <{other}>"
                )));
            }
            _ => return Ok(None),
        }
        let md = Self::root(attrs)?;
        if md.fmi_version.starts_with("3.") {
            state.fmi3 = Some(fmi3::Pending::default());
        }
        state.md = Some(md);
        Ok(Some(!is_empty))
    }

    /// One element start (or empty element); whether it stays open.
    fn element(
        &mut self,
        attrs: Attributes,
        is_empty: bool,
        state: &mut ParseState,
    ) -> Result<bool, DescriptionError> {
        let name = attrs.element.clone();
        let parent = self.path.last().cloned().unwrap_or_default();
        if let Some(open) = self.root_or_fmi3(&parent, &attrs, is_empty, state)? {
            return Ok(open);
        }
        let (md, current_variable, current_unit) =
            (&mut state.md, &mut state.variable, &mut state.unit);
        match (parent.as_str(), name.as_str()) {
            ("fmiModelDescription", "CoSimulation") => {
                if let Some(m) = md.as_mut() {
                    m.co_simulation = Some(Self::co_simulation(&attrs)?);
                }
            }
            ("fmiModelDescription", "DefaultExperiment") => {
                if let Some(m) = md.as_mut() {
                    m.default_experiment = Some(Self::default_experiment(&attrs)?);
                }
            }
            ("UnitDefinitions", "Unit") => {
                *current_unit = Some(UnitDefinition {
                    name: attrs.required("name")?.to_owned(),
                    exponents: [0; 8],
                    factor: 1.0,
                    offset: 0.0,
                });
                if is_empty && let (Some(m), Some(u)) = (md.as_mut(), current_unit.take()) {
                    m.units.push(u);
                }
            }
            ("LogCategories", "Category") => {
                if let Some(m) = md.as_mut() {
                    m.log_categories.push(LogCategory {
                        name: attrs.required("name")?.to_owned(),
                        description: attrs.optional("description").unwrap_or("").to_owned(),
                    });
                }
            }
            ("Unit", "BaseUnit") => {
                if let Some(u) = current_unit.as_mut() {
                    Self::base_unit(u, &attrs)?;
                }
            }
            ("ModelVariables", "ScalarVariable") => {
                *current_variable = Some((attrs, None));
                if is_empty {
                    self.finish_variable(md, current_variable.take())?;
                    return Ok(false);
                }
            }
            ("ScalarVariable", "Real" | "Integer" | "Boolean" | "String" | "Enumeration") => {
                if let Some((sv_attrs, typed)) = current_variable.as_mut() {
                    if typed.is_some() {
                        return Err(attrs.error("a ScalarVariable has two type elements".into()));
                    }
                    *typed = Some(Self::variable(sv_attrs, &attrs)?);
                }
            }
            ("Outputs" | "InitialUnknowns" | "Derivatives", "Unknown") => {
                let unknown = Self::unknown(&attrs)?;
                if let Some(m) = md.as_mut() {
                    match parent.as_str() {
                        "Outputs" => m.outputs.push(unknown),
                        "InitialUnknowns" => m.initial_unknowns.push(unknown),
                        _ => {}
                    }
                }
            }
            _ => {}
        }
        Ok(!is_empty)
    }

    fn default_experiment(attrs: &Attributes) -> Result<DefaultExperiment, DescriptionError> {
        Ok(DefaultExperiment {
            start_time: attrs.parsed("startTime", "a number")?,
            stop_time: attrs.parsed("stopTime", "a number")?,
            tolerance: attrs.parsed("tolerance", "a number")?,
            step_size: attrs.parsed("stepSize", "a number")?,
        })
    }

    fn co_simulation(attrs: &Attributes) -> Result<CoSimulation, DescriptionError> {
        Ok(CoSimulation {
            model_identifier: attrs.required("modelIdentifier")?.to_owned(),
            can_handle_variable_communication_step_size: attrs
                .flag("canHandleVariableCommunicationStepSize")?,
            can_interpolate_inputs: attrs.flag("canInterpolateInputs")?,
            max_output_derivative_order: attrs
                .parsed("maxOutputDerivativeOrder", "an unsigned integer")?
                .unwrap_or(0),
            can_get_and_set_fmu_state: attrs.flag("canGetAndSetFMUstate")?,
            can_serialize_fmu_state: attrs.flag("canSerializeFMUstate")?,
            provides_directional_derivative: attrs.flag("providesDirectionalDerivative")?,
        })
    }

    fn base_unit(u: &mut UnitDefinition, attrs: &Attributes) -> Result<(), DescriptionError> {
        for (i, base) in BASE_UNITS.iter().enumerate() {
            u.exponents[i] = attrs.parsed(base, "an integer")?.unwrap_or(0);
        }
        u.factor = attrs.parsed("factor", "a number")?.unwrap_or(1.0);
        u.offset = attrs.parsed("offset", "a number")?.unwrap_or(0.0);
        Ok(())
    }

    /// An `<Unknown>` of ModelStructure: its index and dependencies.
    fn unknown(attrs: &Attributes) -> Result<Unknown, DescriptionError> {
        let index = attrs
            .parsed("index", "a 1-based variable index")?
            .ok_or_else(|| attrs.error("missing required attribute `index`".into()))?;
        let dependencies = attrs.list("dependencies", "a variable index")?;
        Ok(Unknown {
            index,
            dependencies,
        })
    }

    fn root(a: &Attributes) -> Result<ModelDescription, DescriptionError> {
        let version = a.required("fmiVersion")?;
        let token = match version {
            "2.0" => "guid",
            v if v == "3.0" || v.starts_with("3.0.") => "instantiationToken",
            _ => {
                return Err(a.error(format!(
                    "fmiVersion = \"{version}\": FMI 2.0 and 3.0 are supported"
                )));
            }
        };
        Ok(ModelDescription {
            fmi_version: version.to_owned(),
            model_name: a.required("modelName")?.to_owned(),
            guid: a.required(token)?.to_owned(),
            description: a.optional("description").unwrap_or("").to_owned(),
            generation_tool: a.optional("generationTool").unwrap_or("").to_owned(),
            about: About {
                author: a.optional("author").unwrap_or("").to_owned(),
                version: a.optional("version").unwrap_or("").to_owned(),
                copyright: a.optional("copyright").unwrap_or("").to_owned(),
                license: a.optional("license").unwrap_or("").to_owned(),
                generation_date_and_time: a.optional("generationDateAndTime").map(str::to_owned),
            },
            co_simulation: None,
            units: Vec::new(),
            log_categories: Vec::new(),
            variables: Vec::new(),
            outputs: Vec::new(),
            initial_unknowns: Vec::new(),
            default_experiment: None,
            clocks: Vec::new(),
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
            "Real" | "Float64" => Value::Real(t.parsed("start", "a real number")?),
            "Integer" | "Int32" => Value::Integer(t.parsed("start", "a 32-bit integer")?),
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
            min: t.parsed("min", "a number")?,
            max: t.parsed("max", "a number")?,
            dimensions: Vec::new(),
            sized_by: None,
            aliases: Vec::new(),
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
            VariableCausality::Input
                | VariableCausality::Parameter
                | VariableCausality::StructuralParameter
        );
        if needs_start && !variable.value.has_start() {
            return Err(attrs.error(format!(
                "{} `{}` has no start value (FMI requires one for inputs and parameters)",
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
        // A name (a variable's or an FMI 3.0 alias) stands for one variable.
        let mut names = HashMap::new();
        for (i, v) in md.variables.iter().enumerate() {
            for name in std::iter::once(&v.name).chain(&v.aliases) {
                if let Some(j) = names.insert(name.as_str(), i)
                    && j != i
                {
                    return Err(error(format!(
                        "the name `{name}` is used by two variables (`{}` and `{}`); each name, alias or not, names one variable",
                        md.variables[j].name, v.name
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
