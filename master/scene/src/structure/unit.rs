//! A unit a structure writes out for one of its sections (or its twin): its
//! name, parameters, effects, first guesses and sub-steps. Its parameters
//! are its kind's own type (`NonlinearParams`, `CableParams`, ...: the type
//! the unit deserialises), so the statics and the fidelities set fields, not
//! TOML keys; only an external FMU's are the table the scene gives. The
//! scene builds the unit from that type as it is (`Parameters::given`); it
//! becomes a `[[units]]` table only for the expanded text (`to_value`).

use slender_kinds::Given;
use slender_units::body::BodyParams;
use slender_units::cable::CableParams;
use slender_units::chord::ChordParams;
use slender_units::line3d::Line3dParams;
use slender_units::nonlinear::NonlinearParams;
use slender_units::reduced::unit::ReducedParams;
use slender_units::signal::artefact::ArtefactParams;
use slender_units::static_section::StaticSectionParams;
use std::collections::BTreeMap;
use toml::{Table, Value};

/// The parameters of a written-out unit: each kind's own type (the one its
/// unit deserialises), or an external FMU's table as the scene gives it.
#[derive(Clone, Debug)]
pub(crate) enum Parameters {
    /// A `nonlinear` unit's (`nonlinear`, `linear`, `reduced` about the
    /// equilibrium, the twin).
    Nonlinear(Box<NonlinearParams>),
    /// A `cable` unit's.
    Cable(Box<CableParams>),
    /// A `static_section` unit's.
    Static(Box<StaticSectionParams>),
    /// A `chord` unit's (`beam`, `span`).
    Chord(Box<ChordParams>),
    /// Seed 002's `reduced` unit's (`reduced` about the stress-free state).
    Reduced(Box<ReducedParams>),
    /// A `line3d` unit's (a 3D line's `nonlinear` and `linear` sections, its twin).
    Line3d(Box<Line3dParams>),
    /// A `catenary3d` unit's (a 3D line's `static` first section).
    Catenary3d(Box<Line3dParams>),
    /// A `body` unit's (a `[mooring]`'s body).
    Body(Box<BodyParams>),
    /// An `artefact` unit's (a physical section's sensor or actuator).
    Artefact(Box<ArtefactParams>),
    /// An external FMU's `fmu` parameters, as the scene gives them.
    Fmu(Table),
}

impl Parameters {
    /// The kind of unit that takes them.
    pub(crate) fn kind(&self) -> &'static str {
        match self {
            Parameters::Nonlinear(_) => "nonlinear",
            Parameters::Cable(_) => "cable",
            Parameters::Static(_) => "static_section",
            Parameters::Chord(_) => "chord",
            Parameters::Reduced(_) => "reduced",
            Parameters::Line3d(_) => "line3d",
            Parameters::Catenary3d(_) => "catenary3d",
            Parameters::Body(_) => "body",
            Parameters::Artefact(_) => "artefact",
            Parameters::Fmu(_) => "fmu",
        }
    }

    /// As its builder takes them: the kind's own type, or an FMU's table.
    pub(crate) fn given(self) -> Given {
        match self {
            Parameters::Nonlinear(p) => Given::Typed(p),
            Parameters::Cable(p) => Given::Typed(p),
            Parameters::Static(p) => Given::Typed(p),
            Parameters::Chord(p) => Given::Typed(p),
            Parameters::Reduced(p) => Given::Typed(p),
            Parameters::Line3d(p) | Parameters::Catenary3d(p) => Given::Typed(p),
            Parameters::Body(p) => Given::Typed(p),
            Parameters::Artefact(p) => Given::Typed(p),
            Parameters::Fmu(t) => Given::Table(t),
        }
    }

    /// As the unit's `parameters` table (the expanded text, an FMU's
    /// configuration).
    pub(crate) fn to_table(&self) -> Result<Table, toml::ser::Error> {
        match self {
            Parameters::Nonlinear(p) => Table::try_from(&**p),
            Parameters::Cable(p) => Table::try_from(&**p),
            Parameters::Static(p) => Table::try_from(&**p),
            Parameters::Chord(p) => Table::try_from(&**p),
            Parameters::Reduced(p) => Table::try_from(&**p),
            Parameters::Line3d(p) | Parameters::Catenary3d(p) => Table::try_from(&**p),
            Parameters::Body(p) => Table::try_from(&**p),
            Parameters::Artefact(p) => Table::try_from(&**p),
            Parameters::Fmu(t) => Ok(t.clone()),
        }
    }
}

/// A unit a structure writes out.
#[derive(Clone, Debug)]
pub(crate) struct SectionUnit {
    /// The unit's name in the scene (`<structure>_<section>`).
    pub name: String,
    /// Its parameters (they say its kind).
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
        SectionUnit::new(name, Parameters::Nonlinear(Box::new(parameters)))
    }

    /// A unit named `name` with `parameters`.
    pub(crate) fn new(name: String, parameters: Parameters) -> SectionUnit {
        SectionUnit {
            name,
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
            _ => None,
        }
    }

    /// Its `nonlinear` parameters, or the error that names `key`.
    pub(super) fn section_parameters(&self, key: &str) -> Result<&NonlinearParams, String> {
        match &self.parameters {
            Parameters::Nonlinear(p) => Ok(p),
            _ => Err(format!("`{key}`: the section is not a `nonlinear` unit")),
        }
    }

    /// Sets `<side>_force_x` and `<side>_force_z` (N) in its first guesses.
    pub(super) fn first_guess_force(&mut self, side: &str, force: [f64; 2]) {
        self.inputs.insert(format!("{side}_force_x"), force[0]);
        self.inputs.insert(format!("{side}_force_z"), force[1]);
    }

    /// The unit as a table of the scene's `[[units]]` (the expanded text
    /// `slender expand` prints).
    pub(crate) fn to_value(&self) -> Result<Value, String> {
        let kind = self.parameters.kind();
        let parameters = (self.parameters.to_table())
            .map_err(|e| format!("unit `{}`: its parameters as TOML: {e}", self.name))?;
        let mut unit = Table::new();
        unit.insert("name".into(), Value::String(self.name.clone()));
        unit.insert("kind".into(), Value::String(kind.into()));
        if let Some(effects) = &self.effects {
            let words = effects.iter().map(|e| Value::String((*e).into()));
            unit.insert("effects".into(), Value::Array(words.collect()));
        }
        unit.insert("parameters".into(), Value::Table(parameters));
        if !self.inputs.is_empty() {
            let inputs = (self.inputs.iter()).map(|(k, v)| (k.clone(), Value::Float(*v)));
            unit.insert("inputs".into(), Value::Table(inputs.collect()));
        }
        if let Some(n) = self.substeps {
            unit.insert("substeps".into(), Value::Integer(n as i64));
        }
        Ok(Value::Table(unit))
    }
}
