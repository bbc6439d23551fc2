//! `[structure]` parsed once, before any statics are solved: its name, the
//! model as written, its segments and sections, the top load, the hang-off
//! angle, the water and the twin asked for. Every key is checked here, so a
//! scene with a wrong key is refused without a static solve; the expansion
//! solves the statics from it (`Built::new`) and the layout reads it as it is.

use super::cable::Water;
use super::hang_off::HangOff;
use super::load::{TopLoad, TopLoadFile};
use super::sections::{Cut, Fidelity, SectionFile, Segment, cuts_of, segments_of};
use serde::Deserialize;
use serde::de::DeserializeOwned;
use slender_units::nonlinear::NonlinearParams;
use toml::{Table, Value};

/// `[structure]` as written: its keys and their types, checked by serde (a
/// key it does not take, or a value of the wrong type, is refused naming its
/// path), the model as the `nonlinear` unit's own parameters.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StructureFile {
    name: String,
    model: NonlinearParams,
    #[serde(default)]
    sections: Vec<SectionFile>,
    reference: Option<Value>,
    water_depth: Option<f64>,
    seabed: Option<f64>,
    top_load: Option<TopLoadFile>,
    hang_off: Option<HangOff>,
}

/// `table`, found at `key`, as a `T`; an error names the key path where it
/// went wrong and says what was expected in a scene author's words.
pub(crate) fn typed<T: DeserializeOwned>(key: &str, table: &Table) -> Result<T, String> {
    serde_path_to_error::deserialize(Value::Table(table.clone())).map_err(|e| {
        let message = slender_kinds::words::in_words(e.inner().message().trim());
        match e.path().to_string().as_str() {
            "" | "." => format!("`{key}`: {message}"),
            path => format!("`{key}.{path}`: {message}"),
        }
    })
}

/// A `[structure]` as written, checked.
pub(super) struct Spec {
    /// The prefix of its units' names.
    pub name: String,
    /// `structure.model`: a `nonlinear` unit's parameters.
    pub model: NonlinearParams,
    pub segments: Vec<Segment>,
    /// Its sections, by arc length.
    pub sections: Vec<Cut>,
    /// Its stress-free length (m).
    pub length: f64,
    pub top_load: Option<TopLoad>,
    /// `structure.model.static_start`: the whole structure's equilibrium is
    /// solved once and every section starts from it.
    pub static_start: bool,
    /// The hang-off angle of the top (deg from the vertical), which places
    /// the end in the equilibrium.
    pub hang_off: Option<f64>,
    pub water: Option<Water>,
    /// The monolithic twin's fidelity (`structure.reference`), if any.
    pub reference: Option<Fidelity>,
}

impl Spec {
    /// Reads `[structure]`; the error names the key.
    pub(super) fn parse(structure: &Table) -> Result<Spec, String> {
        let file: StructureFile = typed("structure", structure)?;
        let (name, model) = (file.name, file.model);
        let top_load = (file.top_load.map(|t| TopLoad::of(t, &model))).transpose()?;
        let static_start = model.static_start;
        let hang_off = file.hang_off.map(|h| h.angle()).transpose()?;
        if hang_off.is_some() && (!static_start || top_load.is_some()) {
            return Err("`structure.hang_off`: the top is placed in the static equilibrium, so the structure needs `structure.model.static_start = true` and its end held (not a `top_load`)".into());
        }
        let segments = segments_of(&model)?;
        let length: f64 = segments.iter().map(|s| s.length).sum();
        let sections = cuts_of(&file.sections, length)?;
        Ok(Spec {
            water: Water::of(file.seabed, file.water_depth)?,
            reference: reference_of(file.reference.as_ref())?,
            name,
            model,
            segments,
            sections,
            length,
            top_load,
            static_start,
            hang_off,
        })
    }
}

/// `structure.reference`: true or "nonlinear" (the model as one unit), or
/// "cable" (the whole structure as one cable); None without a twin.
fn reference_of(reference: Option<&Value>) -> Result<Option<Fidelity>, String> {
    let fidelity = match reference {
        None | Some(Value::Boolean(false)) => return Ok(None),
        Some(Value::Boolean(true)) => Fidelity::Nonlinear,
        Some(Value::String(word)) => Fidelity::parse("structure.reference", word)?,
        Some(other) => {
            return Err(format!(
                "`structure.reference` = {other}: expected true, false or a fidelity ({})",
                Fidelity::NAMES.join(", ")
            ));
        }
    };
    match fidelity {
        Fidelity::Nonlinear | Fidelity::Cable => Ok(Some(fidelity)),
        _ => Err(format!(
            "`structure.reference` = \"{}\": the reference is the whole structure at full fidelity; expected true, \"nonlinear\" or \"cable\"",
            fidelity.name()
        )),
    }
}
