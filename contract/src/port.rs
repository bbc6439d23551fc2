//! Ports: the named, typed interface variables of a unit.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Whether the master writes the port (input) or reads it (output).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Causality {
    /// The unit reads it (set by the master or a host before a step).
    Input,
    /// The unit writes it (read after a step).
    Output,
}

/// The physical kind of a port. Connections join ports of the same kind (or a
/// `Generic` port to anything), and the master's default convergence tolerance is
/// chosen per kind.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PortKind {
    /// N
    Force,
    /// m/s
    Velocity,
    /// m
    Displacement,
    /// rad
    Rotation,
    /// N m
    Moment,
    /// Anything else, including dimensionless signals.
    Generic,
}

impl PortKind {
    /// Every kind, in the order used by tables and documentation.
    pub const ALL: [PortKind; 6] = [
        PortKind::Force,
        PortKind::Velocity,
        PortKind::Displacement,
        PortKind::Rotation,
        PortKind::Moment,
        PortKind::Generic,
    ];

    /// The SI unit of measure ports of this kind use ("" for generic).
    pub fn si_unit(self) -> &'static str {
        match self {
            PortKind::Force => "N",
            PortKind::Velocity => "m/s",
            PortKind::Displacement => "m",
            PortKind::Rotation => "rad",
            PortKind::Moment => "N.m",
            PortKind::Generic => "",
        }
    }

    /// Lower-case name as used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            PortKind::Force => "force",
            PortKind::Velocity => "velocity",
            PortKind::Displacement => "displacement",
            PortKind::Rotation => "rotation",
            PortKind::Moment => "moment",
            PortKind::Generic => "generic",
        }
    }
}

impl fmt::Display for PortKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How a unit fills the inside of a step from the input values it is given for the
/// step's end.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Hold {
    /// The new value applies over the whole step.
    ZeroOrder,
    /// Linear ramp from the last accepted value (start of step) to the new value
    /// (end of step), as in seed 000 Algorithm 1.
    #[default]
    Ramp,
}

/// One port of a unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Port {
    /// Name, unique among the unit's ports of the same causality (e.g. "top_force_x").
    pub name: String,
    /// Whether the unit reads or writes it.
    pub causality: Causality,
    /// The physical quantity it carries, which sets its coupling tolerance.
    pub kind: PortKind,
    /// SI unit of measure, e.g. "N" or "m/s" ("" for dimensionless).
    pub unit: String,
    /// For outputs: indices of the inputs this output depends on directly (within
    /// the same instant). Empty means no direct feedthrough. Unused for inputs.
    pub depends_on: Vec<usize>,
    /// For inputs: how the unit holds it inside a step. Unused for outputs.
    pub hold: Hold,
    /// For inputs: the value it takes where nothing drives it and the scene
    /// gives none (an imported FMU's declared start value); `None`: 0.
    pub start: Option<f64>,
    /// Other names the port answers to in a scene (an imported FMI 3.0
    /// variable's `<Alias>`es): the same port, not another one.
    pub aliases: Vec<String>,
}

impl Port {
    /// An input port with the SI unit of its kind and a ramp hold.
    pub fn input(name: &str, kind: PortKind) -> Port {
        Port::of(name, Causality::Input, kind)
    }

    /// An output port with the SI unit of its kind and no direct feedthrough.
    pub fn output(name: &str, kind: PortKind) -> Port {
        Port::of(name, Causality::Output, kind)
    }

    /// A port of the SI unit of its kind, no feedthrough, a ramp hold, no
    /// start value and no aliases.
    fn of(name: &str, causality: Causality, kind: PortKind) -> Port {
        Port {
            name: name.to_owned(),
            causality,
            kind,
            unit: kind.si_unit().to_owned(),
            depends_on: Vec::new(),
            hold: Hold::Ramp,
            start: None,
            aliases: Vec::new(),
        }
    }

    /// This output depends directly on the given inputs (by index).
    pub fn with_feedthrough(mut self, inputs: &[usize]) -> Port {
        self.depends_on = inputs.to_vec();
        self
    }

    /// Whether the port is called `name`, by its name or an alias.
    pub fn answers_to(&self, name: &str) -> bool {
        self.name == name || self.aliases.iter().any(|a| a == name)
    }

    /// Use another unit of measure than the kind's SI default (e.g. "" for a ratio).
    pub fn with_unit(mut self, unit: &str) -> Port {
        self.unit = unit.to_owned();
        self
    }
}
