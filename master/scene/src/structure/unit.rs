//! A unit a structure writes out for one of its sections (or its twin): its
//! name, kind, parameters, effects, first guesses and sub-steps. A section of
//! the `nonlinear` unit (the `nonlinear` and `linear` fidelities, `reduced`
//! about the equilibrium, the twin) carries the unit's own typed parameters
//! (`NonlinearParams`, the type the unit deserialises): the statics and the
//! fidelities set its fields, not TOML keys. It becomes the scene's
//! `[[units]]` table once, when the structure hands its units to the scene
//! (`into_value`).

use slender_units::nonlinear::NonlinearParams;
use std::collections::BTreeMap;
use toml::{Table, Value};

/// The parameters of a written-out unit.
#[derive(Clone, Debug)]
pub(super) enum Parameters {
    /// A `nonlinear` unit's, typed.
    Nonlinear(Box<NonlinearParams>),
    /// Another kind's, as its parameter table (a cable, a static section, a
    /// chord, seed 002's reduced section, an external FMU).
    Table(Table),
}

/// A unit a structure writes out.
#[derive(Clone, Debug)]
pub(super) struct SectionUnit {
    /// The unit's name in the scene (`<structure>_<section>`).
    pub name: String,
    /// Its kind (`slender kinds`).
    pub kind: &'static str,
    pub parameters: Parameters,
    /// The effects it asks for, where its kind switches them.
    pub effects: Option<Vec<&'static str>>,
    /// First guesses of inputs fed through the master's loops, by port.
    pub inputs: BTreeMap<String, f64>,
    /// Sub-steps per coupling step (multi-rate).
    pub substeps: Option<usize>,
}

impl SectionUnit {
    /// A `nonlinear` unit named `name` with `parameters`.
    pub(super) fn nonlinear(name: String, parameters: NonlinearParams) -> SectionUnit {
        SectionUnit::with(
            name,
            "nonlinear",
            Parameters::Nonlinear(Box::new(parameters)),
        )
    }

    /// A unit of `kind` named `name` with the parameter table `parameters`.
    pub(super) fn of_table(name: String, kind: &'static str, parameters: Table) -> SectionUnit {
        SectionUnit::with(name, kind, Parameters::Table(parameters))
    }

    fn with(name: String, kind: &'static str, parameters: Parameters) -> SectionUnit {
        SectionUnit {
            name,
            kind,
            parameters,
            effects: None,
            inputs: BTreeMap::new(),
            substeps: None,
        }
    }

    /// The same unit asking for `effects`.
    pub(super) fn with_effects(mut self, effects: Vec<&'static str>) -> SectionUnit {
        self.effects = Some(effects);
        self
    }

    /// Its `nonlinear` parameters, where it is a `nonlinear` unit.
    pub(super) fn nonlinear_mut(&mut self) -> Option<&mut NonlinearParams> {
        match &mut self.parameters {
            Parameters::Nonlinear(p) => Some(p),
            Parameters::Table(_) => None,
        }
    }

    /// Its `nonlinear` parameters, or the error that names `key`.
    pub(super) fn section_parameters(&self, key: &str) -> Result<&NonlinearParams, String> {
        match &self.parameters {
            Parameters::Nonlinear(p) => Ok(p),
            Parameters::Table(_) => Err(format!("`{key}`: the section is not a `nonlinear` unit")),
        }
    }

    /// Sets `<side>_force_x` and `<side>_force_z` (N) in its first guesses.
    pub(super) fn first_guess_force(&mut self, side: &str, force: [f64; 2]) {
        self.inputs.insert(format!("{side}_force_x"), force[0]);
        self.inputs.insert(format!("{side}_force_z"), force[1]);
    }

    /// The unit as a table of the scene's `[[units]]`: the one place its
    /// typed parameters are written as TOML values.
    pub(super) fn into_value(self) -> Result<Value, String> {
        let parameters = match self.parameters {
            Parameters::Nonlinear(p) => Table::try_from(&*p)
                .map_err(|e| format!("unit `{}`: its parameters as TOML: {e}", self.name))?,
            Parameters::Table(t) => t,
        };
        let mut unit = Table::new();
        unit.insert("name".into(), Value::String(self.name));
        unit.insert("kind".into(), Value::String(self.kind.into()));
        if let Some(effects) = self.effects {
            let words = effects.into_iter().map(|e| Value::String(e.into()));
            unit.insert("effects".into(), Value::Array(words.collect()));
        }
        unit.insert("parameters".into(), Value::Table(parameters));
        if !self.inputs.is_empty() {
            let inputs = self.inputs.into_iter().map(|(k, v)| (k, Value::Float(v)));
            unit.insert("inputs".into(), Value::Table(inputs.collect()));
        }
        if let Some(n) = self.substeps {
            unit.insert("substeps".into(), Value::Integer(n as i64));
        }
        Ok(Value::Table(unit))
    }
}
