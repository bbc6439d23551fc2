//! SSP 1.0 system structures (`SystemStructure.ssd`): FMUs as components, their
//! connectors, the connections between them with the linear transformations a
//! cut needs (`end = factor * start + offset`), parameter values bound to a
//! component, the default experiment and the fixed step (as libcosim reads it,
//! the `com.opensimulationplatform` annotation). Written by `slender fmu wrap
//! X.ssp`, read by `slender run X.ssp`, also for SSPs other tools made.

use quick_xml::Reader;
use quick_xml::escape::escape;
use quick_xml::events::{BytesStart, Event};
use std::collections::BTreeMap;
use std::fmt::Write as _;

pub mod archive;
mod parse;

/// Where an element or connector sits: an input or an output of a component.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ConnectorKind {
    /// An input of its FMU.
    Input,
    /// An output of its FMU.
    Output,
    /// A parameter, or a kind slender does not couple (`calculatedParameter`,
    /// `inout`): kept, not coupled.
    Other,
}

/// One connector of a component (a variable of its FMU).
#[derive(Clone, Debug, PartialEq)]
pub struct Connector {
    /// The variable's name.
    pub name: String,
    /// Input, output or neither.
    pub kind: ConnectorKind,
    /// Its unit of measure (an SI name such as "N" or "m/s", declared in the
    /// description's `Units`); `None` where it has none or slender does not
    /// know its symbol.
    pub unit: Option<String>,
}

/// One component: an FMU in the archive (`source`, relative to its root).
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    /// The component's name in the system.
    pub name: String,
    /// The FMU, relative to the archive's root.
    pub source: String,
    /// Its connectors.
    pub connectors: Vec<Connector>,
    /// Parameter values bound to it (inline `ssv:ParameterValues`), by name.
    pub parameters: BTreeMap<String, toml::Value>,
}

/// One connection: `end = factor * start + offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct Connection {
    /// The component the value comes from.
    pub start_element: String,
    /// Its connector.
    pub start_connector: String,
    /// The component the value goes to.
    pub end_element: String,
    /// Its connector.
    pub end_connector: String,
    /// Linear transformation's factor (1 when none).
    pub factor: f64,
    /// Linear transformation's offset (0 when none).
    pub offset: f64,
}

/// A system structure: one system of FMU components.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemStructure {
    /// The system's name.
    pub name: String,
    /// Its components.
    pub components: Vec<Component>,
    /// Its connections.
    pub connections: Vec<Connection>,
    /// `DefaultExperiment` (s).
    pub start_time: Option<f64>,
    /// Stop time (s).
    pub stop_time: Option<f64>,
    /// The fixed step (s) of the OSP annotation (in the default experiment, as
    /// libcosim reads it), when given.
    pub step: Option<f64>,
    /// `generationTool`.
    pub generation_tool: String,
}

/// A system structure that cannot be read, and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("SystemStructure.ssd:{line}: {message}")]
pub struct SspError {
    /// 1-based line of the problem.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

const NAMESPACES: &str = r#"xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations""#;

impl SystemStructure {
    /// The description as SSP 1.0 XML.
    pub fn to_xml(&self) -> String {
        let e = |s: &str| escape(s).into_owned();
        let mut x = String::new();
        let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
        let _ = writeln!(
            x,
            r#"<ssd:SystemStructureDescription {NAMESPACES} version="1.0" name="{}" generationTool="{}">"#,
            e(&self.name),
            e(&self.generation_tool)
        );
        let _ = writeln!(x, r#"  <ssd:System name="{}">"#, e(&self.name));
        x.push_str("    <ssd:Elements>\n");
        for c in &self.components {
            write_component(&mut x, c);
        }
        x.push_str("    </ssd:Elements>\n    <ssd:Connections>\n");
        for c in &self.connections {
            let _ = write!(
                x,
                r#"      <ssd:Connection startElement="{}" startConnector="{}" endElement="{}" endConnector="{}""#,
                e(&c.start_element),
                e(&c.start_connector),
                e(&c.end_element),
                e(&c.end_connector)
            );
            if c.factor != 1.0 || c.offset != 0.0 {
                let _ = writeln!(
                    x,
                    r#"><ssc:LinearTransformation factor="{:e}" offset="{:e}"/></ssd:Connection>"#,
                    c.factor, c.offset
                );
            } else {
                x.push_str("/>\n");
            }
        }
        x.push_str("    </ssd:Connections>\n  </ssd:System>\n");
        write_units(&mut x, &self.components);
        x.push_str("  <ssd:DefaultExperiment");
        for (name, v) in [("startTime", self.start_time), ("stopTime", self.stop_time)] {
            if let Some(v) = v {
                let _ = write!(x, r#" {name}="{v:e}""#);
            }
        }
        // The fixed step where libcosim looks for it.
        match self.step {
            Some(step) => {
                let _ = writeln!(
                    x,
                    r#"><ssd:Annotations><ssc:Annotation type="com.opensimulationplatform"><osp:Algorithm><osp:FixedStepAlgorithm baseStepSize="{step:e}"/></osp:Algorithm></ssc:Annotation></ssd:Annotations></ssd:DefaultExperiment>"#
                );
            }
            None => x.push_str("/>\n"),
        }
        x.push_str("</ssd:SystemStructureDescription>\n");
        x
    }
}

/// One `<ssd:Component>` with its connectors and bound parameter values.
fn write_component(x: &mut String, c: &Component) {
    let e = |s: &str| escape(s).into_owned();
    let _ = writeln!(
        x,
        r#"      <ssd:Component name="{}" source="{}" type="application/x-fmu-sharedlibrary">"#,
        e(&c.name),
        e(&c.source)
    );
    x.push_str("        <ssd:Connectors>\n");
    for k in &c.connectors {
        let kind = match k.kind {
            ConnectorKind::Input => "input",
            ConnectorKind::Output => "output",
            ConnectorKind::Other => "parameter",
        };
        let unit = match known_unit(k) {
            Some(u) => format!(r#" unit="{}""#, e(u)),
            None => String::new(),
        };
        let _ = writeln!(
            x,
            r#"          <ssd:Connector name="{}" kind="{kind}"><ssc:Real{unit}/></ssd:Connector>"#,
            e(&k.name)
        );
    }
    x.push_str("        </ssd:Connectors>\n      </ssd:Component>\n");
}

/// A unit of measure as an SSD can declare it: the name where slender knows
/// its SI base units (so that `ssd:Units` can define it), else none.
pub fn ssd_unit(unit: &str) -> Option<&str> {
    slender_contract::measure::si_exponents(unit).map(|_| unit)
}

/// A connector's unit where the description can define it.
fn known_unit(c: &Connector) -> Option<&str> {
    c.unit.as_deref().and_then(ssd_unit)
}

/// `<ssd:Units>`: every unit the connectors name, once, in the order first
/// named, with its SI base-unit exponents (none when no connector has one).
fn write_units(x: &mut String, components: &[Component]) {
    let mut names: Vec<&str> = Vec::new();
    for c in components.iter().flat_map(|c| &c.connectors) {
        if let Some(u) = known_unit(c).filter(|u| !names.contains(u)) {
            names.push(u);
        }
    }
    if names.is_empty() {
        return;
    }
    x.push_str("  <ssd:Units>\n");
    const BASE: [&str; 8] = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"];
    for name in names {
        let exponents = slender_contract::measure::si_exponents(name).unwrap_or_default();
        let base: String = (BASE.iter().zip(exponents))
            .filter(|(_, p)| *p != 0)
            .map(|(b, p)| format!(r#" {b}="{p}""#))
            .collect();
        let _ = writeln!(
            x,
            r#"    <ssc:Unit name="{}"><ssc:BaseUnit{base}/></ssc:Unit>"#,
            escape(name)
        );
    }
    x.push_str("  </ssd:Units>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> SystemStructure {
        let connector = |name: &str, kind| Connector {
            name: name.into(),
            kind,
            unit: Some(if name.contains("force") { "N" } else { "m/s" }.into()),
        };
        SystemStructure {
            name: "cut & paste".into(),
            components: vec![
                Component {
                    name: "upper".into(),
                    source: "resources/upper.fmu".into(),
                    connectors: vec![
                        connector("start_velocity_x", ConnectorKind::Input),
                        connector("start_force_x", ConnectorKind::Output),
                    ],
                    parameters: BTreeMap::new(),
                },
                Component {
                    name: "lower".into(),
                    source: "resources/lower.fmu".into(),
                    connectors: vec![connector("end_velocity_x", ConnectorKind::Output)],
                    parameters: BTreeMap::new(),
                },
            ],
            connections: vec![Connection {
                start_element: "lower".into(),
                start_connector: "end_velocity_x".into(),
                end_element: "upper".into(),
                end_connector: "start_velocity_x".into(),
                factor: -1.0,
                offset: 2.5e3,
            }],
            start_time: Some(0.0),
            stop_time: Some(10.0),
            step: Some(0.05),
            generation_tool: "slender".into(),
        }
    }

    #[test]
    fn written_structures_parse_back_identically() {
        let s = sample();
        assert_eq!(SystemStructure::parse(&s.to_xml()).unwrap(), s);
        let mut plain = sample();
        plain.connections[0].factor = 1.0;
        plain.connections[0].offset = 0.0;
        plain.step = None;
        assert!(!plain.to_xml().contains("LinearTransformation"));
        assert_eq!(SystemStructure::parse(&plain.to_xml()).unwrap(), plain);
    }

    #[test]
    fn inline_parameter_values_bind_to_their_component() {
        let xml = sample().to_xml().replace(
            "</ssd:Connectors>\n      </ssd:Component>\n      <ssd:Component name=\"lower\"",
            "</ssd:Connectors><ssd:ParameterBindings><ssd:ParameterBinding><ssd:ParameterValues><ssv:ParameterSet version=\"1.0\" name=\"p\"><ssv:Parameters><ssv:Parameter name=\"mass\"><ssv:Real value=\"2.5\"/></ssv:Parameter><ssv:Parameter name=\"on\"><ssv:Boolean value=\"true\"/></ssv:Parameter></ssv:Parameters></ssv:ParameterSet></ssd:ParameterValues></ssd:ParameterBinding></ssd:ParameterBindings>\n      </ssd:Component>\n      <ssd:Component name=\"lower\"",
        );
        let s = SystemStructure::parse(&xml).unwrap();
        let p = &s.components[0].parameters;
        assert_eq!(p["mass"], toml::Value::Float(2.5));
        assert_eq!(p["on"], toml::Value::Boolean(true));
        assert!(s.components[1].parameters.is_empty());
    }

    #[test]
    fn what_slender_cannot_run_is_refused_with_its_line() {
        let xml = sample().to_xml();
        for (from, to, expected) in [
            (
                "<ssd:Elements>",
                "<ssd:Elements>\n<ssd:System name=\"inner\"/>",
                "nested",
            ),
            (r#"startElement="lower" "#, "", "system's own connectors"),
            (
                "<ssc:LinearTransformation",
                "<ssc:BooleanMappingTransformation/><ssc:LinearTransformation",
                "linear transformation at most",
            ),
            (
                r#"baseStepSize="5e-2""#,
                r#"baseStepSize="fast""#,
                "expected a number",
            ),
        ] {
            assert!(xml.contains(from), "{from}");
            let e = SystemStructure::parse(&xml.replacen(from, to, 1)).unwrap_err();
            assert!(e.to_string().contains(expected), "{e}");
            assert!(e.line > 1, "{e}");
        }
        let e = SystemStructure::parse("<ssd:SystemStructureDescription/>").unwrap_err();
        assert!(e.message.contains("no <ssd:Component>"), "{e}");
    }
}
