//! What a `[structure]` (or a `[mooring]`) writes out, typed: its units (each
//! with its kind's own parameter type, `SectionUnit`) and its connections
//! (`Link`). The scene takes them as they are; they become TOML tables only
//! for the text `slender expand` prints (`to_value`).

use super::SectionUnit;
use toml::{Table, Value};

/// What a `[structure]` writes out: its units and connections, and the
/// advisories on what its sections' models follow poorly.
#[derive(Debug, Default)]
pub(crate) struct Written {
    /// The units, in the order the scene adds them.
    pub units: Vec<SectionUnit>,
    /// The connections between them (and to the structure's loads).
    pub connections: Vec<Link>,
    /// What its sections' models follow poorly (said by `check` and a run).
    pub advisories: Vec<String>,
}

impl Written {
    /// Adds `other`'s units, connections and advisories after its own.
    pub(crate) fn append(&mut self, mut other: Written) {
        self.units.append(&mut other.units);
        self.connections.append(&mut other.connections);
        self.advisories.append(&mut other.advisories);
    }

    /// An FMU exported from a `nonlinear` unit names its end inputs
    /// `<port>_in` (each has an output of the same name, and FMI names are
    /// unique): the connections into `unit` and its first guesses take
    /// those names.
    pub(super) fn fmu_input_names(&mut self, unit: &str) {
        let prefix = format!("{unit}.");
        for link in &mut self.connections {
            if link.to.starts_with(&prefix) {
                link.to.push_str("_in");
            }
        }
        if let Some(ours) = self.units.iter_mut().find(|u| u.name == unit) {
            ours.inputs = std::mem::take(&mut ours.inputs)
                .into_iter()
                .map(|(k, v)| (format!("{k}_in"), v))
                .collect();
        }
    }
}

/// A connection a structure writes out: `to = from + offset`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Link {
    /// The output, "unit.port".
    pub from: String,
    /// The input it drives, "unit.port".
    pub to: String,
    /// Added on the way: the equilibrium value the input's port counts
    /// from, where the two ports count from different states.
    pub offset: Option<f64>,
}

impl Link {
    /// The output `from` driving the input `to` as it is.
    pub(crate) fn new(from: String, to: String) -> Link {
        Link {
            from,
            to,
            offset: None,
        }
    }

    /// The same link adding `offset` on the way.
    pub(crate) fn with_offset(self, offset: f64) -> Link {
        Link {
            offset: Some(offset),
            ..self
        }
    }

    /// As a table of the scene's `[[connections]]`.
    pub(crate) fn to_value(&self) -> Value {
        let mut t = Table::new();
        t.insert("from".into(), Value::String(self.from.clone()));
        t.insert("to".into(), Value::String(self.to.clone()));
        if let Some(offset) = self.offset {
            t.insert("offset".into(), Value::Float(offset));
        }
        Value::Table(t)
    }
}
