//! A coupled system: named units and the connections between their ports.

use crate::error::did_you_mean;
use slender_contract::names::NameError;
use slender_contract::{Causality, Port, PortKind, Unit};
use std::collections::HashMap;
use thiserror::Error;

/// A port name that the unit does not have, with the ones it has.
#[derive(Debug, Error, Clone, PartialEq)]
#[error(
    "`{path}`: unit `{unit}` (kind {kind}) has no {wanted} `{port}`{hint}; its {wanted}s are: {ports}"
)]
pub struct UnknownPort {
    /// The port path as written ("unit.port").
    pub path: String,
    /// The unit's name.
    pub unit: String,
    /// The unit's kind.
    pub kind: String,
    /// The port name that was not found.
    pub port: String,
    /// "input" or "output".
    pub wanted: &'static str,
    /// "; did you mean ...?" or "".
    pub hint: String,
    /// The unit's ports of that causality, comma-separated.
    pub ports: String,
}

/// Why a unit, a connection or a start value was refused.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum SystemError {
    /// A unit or port name that is not a valid name.
    #[error(transparent)]
    Name(#[from] NameError),
    /// Two units with one name.
    #[error("unit name `{0}` is used twice")]
    DuplicateUnit(String),
    /// A port path without a unit and a port.
    #[error("`{path}`: expected \"unit.port\", e.g. \"left.displacement\"")]
    NotAPortPath {
        /// The path as written.
        path: String,
    },
    /// A port path naming a unit the system does not have.
    #[error("`{path}`: no unit named `{unit}`{hint}")]
    UnknownUnit {
        /// The path as written.
        path: String,
        /// The unit it names.
        unit: String,
        /// "; did you mean ...?" or "".
        hint: String,
    },
    /// An output where an input is wanted, or the other way round.
    #[error("`{path}`: `{port}` is not an {wanted} of unit `{unit}` (it is the other way round)")]
    WrongCausality {
        /// The path as written.
        path: String,
        /// The port it names.
        port: String,
        /// The unit's name.
        unit: String,
        /// "input" or "output".
        wanted: &'static str,
    },
    /// A port the unit does not have.
    #[error(transparent)]
    UnknownPort(Box<UnknownPort>),
    /// A connection's gain or offset that is not finite.
    #[error("{label}: gain {gain} and offset {offset} must be finite")]
    NonFiniteLink {
        /// The connection, "unit.port -> unit.port".
        label: String,
        /// Its gain.
        gain: f64,
        /// Its offset (unit of the destination port).
        offset: f64,
    },
    /// A connection's tolerance that is not a finite value > 0.
    #[error("{label}: tolerance {tolerance} is not a finite value > 0")]
    BadTolerance {
        /// The connection, "unit.port -> unit.port".
        label: String,
        /// The tolerance given.
        tolerance: f64,
    },
    /// An output of one kind connected to an input of another.
    #[error(
        "{label}: cannot connect a {from_kind} output ({from_unit}) to a {to_kind} input ({to_unit})"
    )]
    KindMismatch {
        /// The connection, "unit.port -> unit.port".
        label: String,
        /// The output's kind.
        from_kind: PortKind,
        /// The output's unit of measure.
        from_unit: String,
        /// The input's kind.
        to_kind: PortKind,
        /// The input's unit of measure.
        to_unit: String,
    },
    /// An output and an input in different units of measure.
    #[error("{label}: units of measure differ ({from_unit} vs {to_unit})")]
    UnitMismatch {
        /// The connection, "unit.port -> unit.port".
        label: String,
        /// The output's unit of measure.
        from_unit: String,
        /// The input's unit of measure.
        to_unit: String,
    },
    /// An input driven by two connections.
    #[error("{label}: input `{to}` is already driven by `{existing}`")]
    AlreadyDriven {
        /// The second connection, "unit.port -> unit.port".
        label: String,
        /// The input.
        to: String,
        /// The output already driving it.
        existing: String,
    },
    /// A start value of an input that is not finite.
    #[error("{to}: start value {value} is not finite")]
    NonFiniteStart {
        /// The input, "unit.port".
        to: String,
        /// The value given.
        value: f64,
    },
}

/// A port of a unit in the system, by indices.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct PortRef {
    /// The unit's index in the system.
    pub unit: usize,
    /// The port's index among the unit's inputs or outputs.
    pub port: usize,
}

/// Options of a connection: the value passed is `gain * output + offset`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Link {
    /// Multiplies the output.
    pub gain: f64,
    /// Added after the gain (unit of the destination port).
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
    /// The output.
    pub from: PortRef,
    /// The input it drives.
    pub to: PortRef,
    /// Gain, offset and tolerance.
    pub link: Link,
    /// Kind of the destination port (selects the default tolerance).
    pub kind: PortKind,
    /// "unit.port -> unit.port", for messages and reports.
    pub label: String,
}

/// A unit of the system with its name and the constant values of its inputs that no
/// connection drives (also the first guess for inputs fed through a loop).
pub struct NamedUnit {
    /// Its name in the system.
    pub name: String,
    /// The unit.
    pub unit: Box<dyn Unit>,
    /// One value per input, in the unit's input order.
    pub start_inputs: Vec<f64>,
}

/// Units and connections, checked as they are added.
#[derive(Default)]
pub struct System {
    pub(crate) units: Vec<NamedUnit>,
    pub(crate) connections: Vec<Connection>,
    /// Unit index by name, and the connection driving each input: lookups in
    /// constant time, so a system of 100 000 units builds in linear time.
    by_name: HashMap<String, usize>,
    driven: HashMap<PortRef, usize>,
    /// Inputs whose start value the scene gave (`set_start_input`).
    given: std::collections::HashSet<PortRef>,
}

impl System {
    /// An empty system.
    pub fn new() -> System {
        System::default()
    }

    /// Adds a unit under a unique name; returns its index.
    pub fn add_unit(&mut self, name: &str, unit: Box<dyn Unit>) -> Result<usize, SystemError> {
        slender_contract::names::check_name("unit name", name)?;
        if self.unit_index(name).is_some() {
            return Err(SystemError::DuplicateUnit(name.to_owned()));
        }
        // An input takes its declared start value (an FMU's), else 0, while
        // nothing drives it (see `connect`).
        let start_inputs = (unit.description().inputs.iter())
            .map(|p| p.start.filter(|v| v.is_finite()).unwrap_or(0.0))
            .collect();
        self.by_name.insert(name.to_owned(), self.units.len());
        self.units.push(NamedUnit {
            name: name.to_owned(),
            unit,
            start_inputs,
        });
        Ok(self.units.len() - 1)
    }

    /// Index of the unit called `name`.
    pub fn unit_index(&self, name: &str) -> Option<usize> {
        self.by_name.get(name).copied()
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
    pub fn resolve(&self, path: &str, causality: Causality) -> Result<PortRef, SystemError> {
        let (unit_name, port_name) =
            path.split_once('.')
                .ok_or_else(|| SystemError::NotAPortPath {
                    path: path.to_owned(),
                })?;
        let unit = self
            .unit_index(unit_name)
            .ok_or_else(|| SystemError::UnknownUnit {
                path: path.to_owned(),
                unit: unit_name.to_owned(),
                hint: did_you_mean(unit_name, self.unit_names()),
            })?;
        let description = self.units[unit].unit.description();
        let (ports, other) = match causality {
            Causality::Input => (&description.inputs, &description.outputs),
            Causality::Output => (&description.outputs, &description.inputs),
        };
        if let Some(port) = ports.iter().position(|p| p.answers_to(port_name)) {
            return Ok(PortRef { unit, port });
        }
        let wanted = match causality {
            Causality::Input => "input",
            Causality::Output => "output",
        };
        if other.iter().any(|p| p.answers_to(port_name)) {
            return Err(SystemError::WrongCausality {
                path: path.to_owned(),
                port: port_name.to_owned(),
                unit: unit_name.to_owned(),
                wanted,
            });
        }
        Err(SystemError::UnknownPort(Box::new(UnknownPort {
            path: path.to_owned(),
            unit: unit_name.to_owned(),
            kind: description.kind.clone(),
            port: port_name.to_owned(),
            wanted,
            hint: did_you_mean(port_name, ports.iter().map(|p| p.name.as_str())),
            ports: ports
                .iter()
                .map(|p| p.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        })))
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
    pub fn connect(&mut self, from: &str, to: &str, link: Link) -> Result<usize, SystemError> {
        let source = self.resolve(from, Causality::Output)?;
        let target = self.resolve(to, Causality::Input)?;
        let label = format!("{from} -> {to}");
        if !(link.gain.is_finite() && link.offset.is_finite()) {
            return Err(SystemError::NonFiniteLink {
                label,
                gain: link.gain,
                offset: link.offset,
            });
        }
        if let Some(tolerance) = link.tolerance
            && !(tolerance.is_finite() && tolerance > 0.0)
        {
            return Err(SystemError::BadTolerance { label, tolerance });
        }
        let out = self.port(Causality::Output, source);
        let inp = self.port(Causality::Input, target);
        let generic = out.kind == PortKind::Generic || inp.kind == PortKind::Generic;
        if !generic && out.kind != inp.kind {
            return Err(SystemError::KindMismatch {
                label,
                from_kind: out.kind,
                from_unit: out.unit.clone(),
                to_kind: inp.kind,
                to_unit: inp.unit.clone(),
            });
        }
        // Units of measure are compared whenever both ports declare one (FMU
        // ports of a kind slender does not know are generic but keep their unit).
        let declared = !out.unit.is_empty() && !inp.unit.is_empty();
        if declared && !slender_contract::measure::same_unit(&out.unit, &inp.unit) {
            return Err(SystemError::UnitMismatch {
                label,
                from_unit: out.unit.clone(),
                to_unit: inp.unit.clone(),
            });
        }
        let kind = inp.kind;
        if let Some(&existing) = self.driven.get(&target) {
            return Err(SystemError::AlreadyDriven {
                label,
                to: to.to_owned(),
                existing: self.connections[existing].label.clone(),
            });
        }
        self.driven.insert(target, self.connections.len());
        // A driven input's first guess is the scene's, else 0 as a native
        // unit's (a declared start is for an input nothing drives).
        if !self.given.contains(&target) {
            self.units[target.unit].start_inputs[target.port] = 0.0;
        }
        self.connections.push(Connection {
            from: source,
            to: target,
            link,
            kind,
            label,
        });
        Ok(self.connections.len() - 1)
    }

    /// Sets the constant value of input `to` ("unit.port"): used as is when nothing
    /// drives it, and as the first guess when a loop drives it.
    pub fn set_start_input(&mut self, to: &str, value: f64) -> Result<(), SystemError> {
        if !value.is_finite() {
            return Err(SystemError::NonFiniteStart {
                to: to.to_owned(),
                value,
            });
        }
        let r = self.resolve(to, Causality::Input)?;
        self.units[r.unit].start_inputs[r.port] = value;
        self.given.insert(r);
        Ok(())
    }
}
