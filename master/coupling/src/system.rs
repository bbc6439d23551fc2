//! A coupled system: named units and the connections between their ports.

use crate::error::did_you_mean;
use slender_units::{Causality, Port, PortKind, Unit};

/// A port of a unit in the system, by indices.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct PortRef {
    pub unit: usize,
    pub port: usize,
}

/// Options of a connection: the value passed is `gain * output + offset`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Link {
    pub gain: f64,
    pub offset: f64,
    /// Absolute convergence tolerance (unit of the destination port); `None`: the
    /// master's tolerance for the destination port's kind.
    pub tolerance: Option<f64>,
}

impl Default for Link {
    fn default() -> Self {
        Link {
            gain: 1.0,
            offset: 0.0,
            tolerance: None,
        }
    }
}

/// An output feeding an input.
#[derive(Clone, Debug, PartialEq)]
pub struct Connection {
    pub from: PortRef,
    pub to: PortRef,
    pub link: Link,
    /// Kind of the destination port (selects the default tolerance).
    pub kind: PortKind,
    /// "unit.port -> unit.port", for messages and reports.
    pub label: String,
}

/// A unit of the system with its name and the constant values of its inputs that no
/// connection drives (also the first guess for inputs fed through a loop).
pub struct NamedUnit {
    pub name: String,
    pub unit: Box<dyn Unit>,
    pub start_inputs: Vec<f64>,
}

/// Units and connections, checked as they are added.
#[derive(Default)]
pub struct System {
    pub(crate) units: Vec<NamedUnit>,
    pub(crate) connections: Vec<Connection>,
}

impl System {
    /// An empty system.
    pub fn new() -> System {
        System::default()
    }

    /// Adds a unit under a unique name; returns its index.
    pub fn add_unit(&mut self, name: &str, unit: Box<dyn Unit>) -> Result<usize, String> {
        slender_units::contract::names::check_name("unit name", name)?;
        if self.unit_index(name).is_some() {
            return Err(format!("unit name `{name}` is used twice"));
        }
        let start_inputs = vec![0.0; unit.description().inputs.len()];
        self.units.push(NamedUnit {
            name: name.to_owned(),
            unit,
            start_inputs,
        });
        Ok(self.units.len() - 1)
    }

    /// Index of the unit called `name`.
    pub fn unit_index(&self, name: &str) -> Option<usize> {
        self.units.iter().position(|u| u.name == name)
    }

    /// Names of the units, in the order they were added.
    pub fn unit_names(&self) -> impl Iterator<Item = &str> {
        self.units.iter().map(|u| u.name.as_str())
    }

    /// The units, in the order they were added.
    pub fn units(&self) -> &[NamedUnit] {
        &self.units
    }

    /// The connections, in the order they were added.
    pub fn connections(&self) -> &[Connection] {
        &self.connections
    }

    /// Resolves "unit.port" with the given causality, with a "did you mean" hint.
    pub fn resolve(&self, path: &str, causality: Causality) -> Result<PortRef, String> {
        let (unit_name, port_name) = path.split_once('.').ok_or_else(|| {
            format!("`{path}`: expected \"unit.port\", e.g. \"left.displacement\"")
        })?;
        let unit = self.unit_index(unit_name).ok_or_else(|| {
            format!(
                "`{path}`: no unit named `{unit_name}`{}",
                did_you_mean(unit_name, self.unit_names())
            )
        })?;
        let description = self.units[unit].unit.description();
        let (ports, other) = match causality {
            Causality::Input => (&description.inputs, &description.outputs),
            Causality::Output => (&description.outputs, &description.inputs),
        };
        if let Some(port) = ports.iter().position(|p| p.name == port_name) {
            return Ok(PortRef { unit, port });
        }
        let wanted = match causality {
            Causality::Input => "input",
            Causality::Output => "output",
        };
        if other.iter().any(|p| p.name == port_name) {
            return Err(format!(
                "`{path}`: `{port_name}` is not an {wanted} of unit `{unit_name}` (it is the other way round)"
            ));
        }
        Err(format!(
            "`{path}`: unit `{unit_name}` (kind {}) has no {wanted} `{port_name}`{}; its {wanted}s are: {}",
            description.kind,
            did_you_mean(port_name, ports.iter().map(|p| p.name.as_str())),
            ports
                .iter()
                .map(|p| p.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ))
    }

    /// The port behind a reference.
    pub fn port(&self, causality: Causality, r: PortRef) -> &Port {
        let d = self.units[r.unit].unit.description();
        match causality {
            Causality::Input => &d.inputs[r.port],
            Causality::Output => &d.outputs[r.port],
        }
    }

    /// Connects output `from` ("unit.port") to input `to`, checking that both exist,
    /// that their kinds and units of measure agree and that `to` is not driven yet.
    pub fn connect(&mut self, from: &str, to: &str, link: Link) -> Result<usize, String> {
        let source = self.resolve(from, Causality::Output)?;
        let target = self.resolve(to, Causality::Input)?;
        if !(link.gain.is_finite() && link.offset.is_finite()) {
            return Err(format!(
                "{from} -> {to}: gain {} and offset {} must be finite",
                link.gain, link.offset
            ));
        }
        if let Some(tol) = link.tolerance
            && !(tol.is_finite() && tol > 0.0)
        {
            return Err(format!(
                "{from} -> {to}: tolerance {tol} is not a finite value > 0"
            ));
        }
        let out = self.port(Causality::Output, source);
        let inp = self.port(Causality::Input, target);
        let generic = out.kind == PortKind::Generic || inp.kind == PortKind::Generic;
        if !generic && out.kind != inp.kind {
            return Err(format!(
                "{from} -> {to}: cannot connect a {} output ({}) to a {} input ({})",
                out.kind, out.unit, inp.kind, inp.unit
            ));
        }
        // Units of measure are compared whenever both ports declare one (FMU
        // ports of a kind slender does not know are generic but keep their unit).
        let declared = !out.unit.is_empty() && !inp.unit.is_empty();
        if declared && !slender_units::contract::measure::same_unit(&out.unit, &inp.unit) {
            return Err(format!(
                "{from} -> {to}: units of measure differ ({} vs {})",
                out.unit, inp.unit
            ));
        }
        let kind = inp.kind;
        if let Some(existing) = self.connections.iter().find(|c| c.to == target) {
            return Err(format!(
                "{from} -> {to}: input `{to}` is already driven by `{}`",
                existing.label
            ));
        }
        self.connections.push(Connection {
            from: source,
            to: target,
            link,
            kind,
            label: format!("{from} -> {to}"),
        });
        Ok(self.connections.len() - 1)
    }

    /// Sets the constant value of input `to` ("unit.port"): used as is when nothing
    /// drives it, and as the first guess when a loop drives it.
    pub fn set_start_input(&mut self, to: &str, value: f64) -> Result<(), String> {
        if !value.is_finite() {
            return Err(format!("{to}: start value {value} is not finite"));
        }
        let r = self.resolve(to, Causality::Input)?;
        self.units[r.unit].start_inputs[r.port] = value;
        Ok(())
    }
}
