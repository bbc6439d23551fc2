//! Reading `SystemStructure.ssd` (quick-xml, names without their namespace
//! prefix): what slender can run of it, and a located error for the rest
//! (nested systems, connections to the system's own connectors, mappings,
//! parameter files outside the description).

use super::*;

/// The attributes of one element, by local name.
type Attributes = BTreeMap<String, String>;

/// The state of one parse.
struct Parser<'a> {
    xml: &'a str,
    reader: Reader<&'a [u8]>,
    path: Vec<String>,
    structure: SystemStructure,
    /// The parameter being read (its name), inside a component's bindings.
    parameter: Option<String>,
}

fn local(name: &[u8]) -> String {
    let name = String::from_utf8_lossy(name);
    name.rsplit(':').next().unwrap_or_default().to_owned()
}

impl SystemStructure {
    /// Parses a system structure description.
    pub fn parse(xml: &str) -> Result<SystemStructure, SspError> {
        let mut parser = Parser {
            xml,
            reader: Reader::from_str(xml),
            path: Vec::new(),
            structure: SystemStructure {
                name: String::new(),
                components: Vec::new(),
                connections: Vec::new(),
                start_time: None,
                stop_time: None,
                step: None,
                generation_tool: String::new(),
            },
            parameter: None,
        };
        parser.run()?;
        let s = parser.structure;
        if s.components.is_empty() {
            return Err(SspError {
                line: 1,
                message: "no <ssd:Component>: nothing to run".into(),
            });
        }
        Ok(s)
    }
}

impl Parser<'_> {
    fn error(&self, message: String) -> SspError {
        let end = (self.reader.buffer_position() as usize).min(self.xml.len());
        let line = 1 + self.xml.as_bytes()[..end]
            .iter()
            .filter(|b| **b == b'\n')
            .count();
        SspError { line, message }
    }

    fn attributes(&self, e: &BytesStart) -> Result<Attributes, SspError> {
        let mut values = BTreeMap::new();
        for a in e.attributes() {
            let a = a.map_err(|err| self.error(format!("malformed attribute ({err})")))?;
            let value = a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| self.error(format!("an attribute does not unescape ({err})")))?;
            values.insert(local(a.key.as_ref()), value.into_owned());
        }
        Ok(values)
    }

    fn run(&mut self) -> Result<(), SspError> {
        loop {
            let event = self
                .reader
                .read_event()
                .map_err(|e| self.error(format!("not well-formed XML ({e})")))?;
            let (element, empty) = match &event {
                Event::Start(e) => (e.clone(), false),
                Event::Empty(e) => (e.clone(), true),
                Event::End(_) => {
                    self.path.pop();
                    continue;
                }
                Event::Eof => return Ok(()),
                _ => continue,
            };
            let name = local(element.name().as_ref());
            let attrs = self.attributes(&element)?;
            self.element(&name, &attrs)?;
            if !empty {
                self.path.push(name);
            }
        }
    }

    fn number(&self, attrs: &Attributes, key: &str) -> Result<Option<f64>, SspError> {
        attrs
            .get(key)
            .map(|v| {
                v.trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| self.error(format!("`{key}` = \"{v}\": expected a number")))
            })
            .transpose()
    }

    fn required(&self, attrs: &Attributes, element: &str, key: &str) -> Result<String, SspError> {
        attrs
            .get(key)
            .cloned()
            .ok_or_else(|| self.error(format!("<{element}> without `{key}`")))
    }

    fn element(&mut self, name: &str, attrs: &Attributes) -> Result<(), SspError> {
        let parent = self.path.last().map_or("", String::as_str).to_owned();
        match (parent.as_str(), name) {
            ("", "SystemStructureDescription") => {
                self.structure.name = attrs.get("name").cloned().unwrap_or_default();
                self.structure.generation_tool =
                    attrs.get("generationTool").cloned().unwrap_or_default();
            }
            ("Elements", "System") => {
                return Err(self.error(
                    "a nested <ssd:System>: slender runs one system of FMU components".into(),
                ));
            }
            ("Elements", "Component") => self.component(attrs)?,
            ("Elements", "SignalDictionaryReference") => {
                return Err(self.error("signal dictionaries are not supported".into()));
            }
            ("Connectors", "Connector") if self.in_component() => self.connector(attrs)?,
            // A connector's type: its unit of measure, when it names one.
            ("Connector", "Real") if self.in_component() => {
                let connector =
                    (self.structure.components.last_mut()).and_then(|c| c.connectors.last_mut());
                if let Some(connector) = connector {
                    connector.unit = attrs.get("unit").cloned();
                }
            }
            ("Connections", "Connection") => self.connection(attrs)?,
            ("Connection", "LinearTransformation") => {
                let factor = self.number(attrs, "factor")?.unwrap_or(1.0);
                let offset = self.number(attrs, "offset")?.unwrap_or(0.0);
                if let Some(c) = self.structure.connections.last_mut() {
                    (c.factor, c.offset) = (factor, offset);
                }
            }
            ("Connection", other) if other.ends_with("Transformation") => {
                return Err(self.error(format!(
                    "<{other}>: slender couples Real connectors, with a linear transformation at most"
                )));
            }
            ("ParameterBindings", "ParameterBinding") => {
                if !self.in_component() {
                    return Err(self.error(
                        "parameter bindings of the system: bind the values to its components"
                            .into(),
                    ));
                }
                if attrs.contains_key("source") {
                    return Err(self.error(
                        "a parameter binding from a file (`source`): inline its values in the description".into(),
                    ));
                }
            }
            ("ParameterBinding", "ParameterMapping") => {
                return Err(self.error("parameter mappings are not supported".into()));
            }
            ("Parameters", "Parameter") => {
                self.parameter = Some(self.required(attrs, "Parameter", "name")?);
            }
            ("Parameter", "Real" | "Integer" | "Boolean" | "String" | "Enumeration") => {
                self.parameter_value(name, attrs)?;
            }
            ("SystemStructureDescription", "DefaultExperiment") => {
                self.structure.start_time = self.number(attrs, "startTime")?;
                self.structure.stop_time = self.number(attrs, "stopTime")?;
            }
            (_, "FixedStepAlgorithm") => {
                self.structure.step = self.number(attrs, "baseStepSize")?;
            }
            _ => {}
        }
        Ok(())
    }

    /// A component's connector: its name and kind (its unit follows in its
    /// type element).
    fn connector(&mut self, attrs: &Attributes) -> Result<(), SspError> {
        let kind = match attrs.get("kind").map(String::as_str) {
            Some("input") => ConnectorKind::Input,
            Some("output") => ConnectorKind::Output,
            _ => ConnectorKind::Other,
        };
        let name = self.required(attrs, "Connector", "name")?;
        if let Some(c) = self.structure.components.last_mut() {
            c.connectors.push(Connector {
                name,
                kind,
                unit: None,
            });
        }
        Ok(())
    }

    /// Whether the element being read lies inside a component.
    fn in_component(&self) -> bool {
        self.path.iter().any(|p| p == "Component")
    }

    fn component(&mut self, attrs: &Attributes) -> Result<(), SspError> {
        let kind = attrs.get("type").map(String::as_str);
        if !matches!(kind, None | Some("application/x-fmu-sharedlibrary")) {
            return Err(self.error(format!(
                "component type \"{}\": slender runs FMUs (application/x-fmu-sharedlibrary)",
                kind.unwrap_or_default()
            )));
        }
        let component = Component {
            name: self.required(attrs, "Component", "name")?,
            source: self.required(attrs, "Component", "source")?,
            connectors: Vec::new(),
            parameters: BTreeMap::new(),
        };
        self.structure.components.push(component);
        Ok(())
    }

    fn connection(&mut self, attrs: &Attributes) -> Result<(), SspError> {
        let (Some(start), Some(end)) = (attrs.get("startElement"), attrs.get("endElement")) else {
            return Err(self.error(
                "a connection to the system's own connectors (no startElement or endElement): slender connects components only".into(),
            ));
        };
        self.structure.connections.push(Connection {
            start_element: start.clone(),
            start_connector: self.required(attrs, "Connection", "startConnector")?,
            end_element: end.clone(),
            end_connector: self.required(attrs, "Connection", "endConnector")?,
            factor: 1.0,
            offset: 0.0,
        });
        Ok(())
    }

    /// A bound parameter's value (`<ssv:Real value="..."/>` and the like).
    fn parameter_value(&mut self, kind: &str, attrs: &Attributes) -> Result<(), SspError> {
        let Some(name) = self.parameter.clone() else {
            return Ok(());
        };
        let text = self.required(attrs, kind, "value")?;
        let value = match kind {
            "Real" => self.number(attrs, "value")?.map(toml::Value::Float),
            "Integer" | "Enumeration" => text.trim().parse().ok().map(toml::Value::Integer),
            "Boolean" => match text.trim() {
                "true" | "1" => Some(toml::Value::Boolean(true)),
                "false" | "0" => Some(toml::Value::Boolean(false)),
                _ => None,
            },
            _ => Some(toml::Value::String(text.clone())),
        }
        .ok_or_else(|| self.error(format!("parameter `{name}`: `{text}` is not a {kind}")))?;
        let in_component = self.in_component();
        if let Some(c) = self.structure.components.last_mut()
            && in_component
        {
            c.parameters.insert(name, value);
        }
        Ok(())
    }
}
