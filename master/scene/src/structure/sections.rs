//! The structure's description: its segments (the stress-free shape), its
//! sections (cuts by arc length) and each section's fidelity.

use super::model::SectionModel;
use serde::Deserialize;
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::Segment as ModelSegment;
use toml::{Table, Value};

/// A straight segment of the stress-free shape: the model's segment as
/// written (its section properties, typed) and where it starts.
#[derive(Clone, Debug)]
pub(crate) struct Segment {
    /// Arc length of its start (m).
    pub from: f64,
    pub length: f64,
    pub angle_deg: f64,
    pub elements: f64,
    /// The segment as the model gives it.
    pub properties: ModelSegment,
}

impl Segment {
    /// Length (m) of the segment inside [from, to].
    pub(super) fn overlap(&self, from: f64, to: f64) -> f64 {
        ((self.from + self.length).min(to) - self.from.max(from)).max(0.0)
    }

    /// The model's own element count on the part of the segment inside
    /// [from, to]: its share of the segment's elements, rounded, at least 1;
    /// None where the segment does not reach into it (by more than 1e-12 of
    /// its length). What a section's `nonlinear` unit is written with.
    pub(super) fn elements_over(&self, from: f64, to: f64) -> Option<f64> {
        let length = self.overlap(from, to);
        (length > 1e-12 * self.length)
            .then(|| (self.elements * (length / self.length)).round().max(1.0))
    }
}

/// The model's segments placed along the structure's arc.
pub(super) fn segments_of(model: &NonlinearParams) -> Result<Vec<Segment>, String> {
    if model.segments.is_empty() {
        return Err("`structure.model.segments`: expected a list of at least one segment".into());
    }
    let mut from = 0.0;
    Ok((model.segments.iter())
        .map(|s| {
            let segment = Segment {
                from,
                length: s.length,
                angle_deg: s.angle_deg,
                elements: s.elements as f64,
                properties: s.clone(),
            };
            from += segment.length;
            segment
        })
        .collect())
}

/// One section: its name, arc-length range (m), fidelity and element count
/// (None: as the model's segments).
#[derive(Clone, Debug)]
pub(crate) struct Cut {
    pub name: String,
    pub from: f64,
    pub to: f64,
    pub fidelity: Fidelity,
    pub elements: Option<usize>,
    /// Sub-steps of the section's unit per coupling step (multi-rate).
    pub substeps: Option<usize>,
    /// A physical section's artefacts (`sensor`, `actuator`).
    pub physical: Option<Table>,
    /// The `fmu` parameters of an external FMU in place of the section's unit.
    pub fmu: Option<Table>,
    /// The fidelity's own keys: a reduced section's basis (`modes`,
    /// `derivatives`, ...), a chord section's model settings (`alpha`, ...).
    pub options: Option<Table>,
}

/// The fidelities a section can take, as written in scenes.
pub const FIDELITIES: [&str; COUNT] = Fidelity::NAMES;

/// Declares the fidelities: the enum `Fidelity` (which model a section is),
/// their names as written in scenes (`NAMES`), every one of them (`ALL`) and
/// each one's model (`model`). A fidelity is one line here and its own file.
macro_rules! fidelities {
    ($($(#[doc = $doc:literal])* $variant:ident = $name:literal => $model:expr,)+) => {
        /// Which model a section is.
        #[derive(Copy, Clone, Debug, PartialEq, Eq)]
        pub(crate) enum Fidelity {
            $($(#[doc = $doc])* $variant,)+
        }

        /// How many fidelities there are.
        const COUNT: usize = [$($name),+].len();

        impl Fidelity {
            /// The fidelities' names as written in scenes (each its model's `name`).
            pub(super) const NAMES: [&'static str; COUNT] = [$($name),+];

            /// Every fidelity, in the order of `NAMES`.
            pub(super) const ALL: [Fidelity; COUNT] = [$(Fidelity::$variant),+];

            /// The fidelity's model: what it writes, refuses and reports.
            pub(super) fn model(self) -> &'static dyn SectionModel {
                match self {
                    $(Fidelity::$variant => &$model,)+
                }
            }
        }
    };
}

fidelities! {
    /// The geometrically nonlinear section (`nonlinear` unit).
    Nonlinear = "nonlinear" => super::nonlinear::NONLINEAR,
    /// The same section linearised about its start (`nonlinear` unit with
    /// `linear = true`): the seabed as springs where it lies, one
    /// back-substitution a step.
    Linear = "linear" => super::nonlinear::LINEAR,
    /// Seed 000's cable, linear about its static state, no bending (`cable` unit).
    Cable = "cable" => super::cable::Cable,
    /// The section's linearised static response at its end (`static_section`
    /// unit): a laid pipe below the touchdown region.
    Static = "static" => super::static_fidelity::Static,
    /// The section reduced about its stress-free state (`reduced` unit, seed
    /// 002): loaded at its cuts.
    Reduced = "reduced" => super::reduced::Reduced,
    /// Seed 004's FE beam with tension about the section's chord in the
    /// equilibrium (`chord` unit).
    Beam = "beam" => super::chord::BEAM,
    /// The span's transfer matrix with tension about the chord (`chord` unit).
    Span = "span" => super::chord::SPAN,
}

impl Fidelity {
    /// The fidelity written `word` at `key`.
    pub(super) fn parse(key: &str, word: &str) -> Result<Fidelity, String> {
        Fidelity::ALL
            .into_iter()
            .find(|f| f.name() == word)
            .ok_or(format!(
                "`{key}` = \"{word}\": expected one of {}",
                Fidelity::NAMES.join(", ")
            ))
    }

    /// The name as written in scenes.
    pub(super) fn name(self) -> &'static str {
        self.model().name()
    }

    /// Whether the section is a `nonlinear` unit (stepped whole or linear):
    /// the same ports, stations and outputs.
    pub(super) fn is_section_unit(self) -> bool {
        self.model().is_section_unit()
    }

    /// Whether the model carries bending (rotation and moment at its cuts).
    pub(super) fn bends(self) -> bool {
        self.model().bends()
    }

    /// Whether the section is a small-deflection model about its chord.
    pub(super) fn is_chord(self) -> bool {
        self.model().is_chord()
    }

    /// Whether the model has no seabed contact (a section lying on the
    /// seabed in the equilibrium cannot be it).
    pub(super) fn lacks_seabed(self) -> bool {
        !self.model().has_seabed()
    }
}

/// A `[[structure.sections]]` entry as written (its keys checked by serde;
/// its fidelity, a name or a table, read by `fidelity_of`).
#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SectionFile {
    name: String,
    /// Where it ends (m of arc length); none for the last.
    to: Option<f64>,
    fidelity: Option<Value>,
    elements: Option<i64>,
    substeps: Option<i64>,
    physical: Option<Value>,
}

impl SectionFile {
    /// One section named `name` over the whole structure at its model's
    /// fidelity.
    pub(crate) fn whole(name: &str) -> SectionFile {
        SectionFile {
            name: name.into(),
            to: None,
            fidelity: None,
            elements: None,
            substeps: None,
            physical: None,
        }
    }
}

/// The sections of `[structure]` as cuts of its `length` (m).
pub(super) fn cuts_of(list: &[SectionFile], length: f64) -> Result<Vec<Cut>, String> {
    if list.is_empty() {
        return Err("`structure.sections`: expected at least one section".into());
    }
    let mut cuts = Vec::new();
    let mut from = 0.0;
    for (i, t) in list.iter().enumerate() {
        let key = format!("structure.sections[{i}]");
        let model = fidelity_of(&key, t.fidelity.as_ref())?;
        let (fidelity, fidelity_elements) = (model.fidelity, model.elements);
        let last = i + 1 == list.len();
        let to = match t.to {
            Some(to) if !last && to > from && to < length => to,
            None if last => length,
            Some(to) if last && (to - length).abs() <= 1e-9 * length => length,
            other => {
                let written = other.map_or("none".to_owned(), |to| to.to_string());
                return Err(format!(
                    "`{key}.to` = {written}: expected an arc length in ({from}, {length}) m, increasing, and none (or the length) for the last section"
                ));
            }
        };
        let elements = match (t.elements, fidelity_elements) {
            (None, elements) => elements,
            (Some(n), None) => Some(at_least_one(&format!("{key}.elements"), Some(n))?),
            (Some(_), Some(_)) => {
                return Err(format!(
                    "`{key}`: the element count is given twice (`elements` and `fidelity.elements`)"
                ));
            }
        };
        let substeps = t
            .substeps
            .map(|n| at_least_one(&format!("{key}.substeps"), Some(n)))
            .transpose()?;
        let physical = match &t.physical {
            None => None,
            Some(Value::Table(p)) => Some(p.clone()),
            Some(_) => {
                return Err(format!(
                    "`{key}.physical`: expected a table {{ sensor = {{ ... }}, actuator = {{ ... }} }} of `artefact` parameters"
                ));
            }
        };
        cuts.push(Cut {
            name: t.name.clone(),
            from,
            to,
            fidelity,
            elements,
            substeps,
            physical,
            fmu: model.fmu,
            options: model.options,
        });
        from = to;
    }
    Ok(cuts)
}

/// A section's `fidelity`: a name, or a table `{ kind = NAME, elements = N }`
/// (default: nonlinear; `reduced`, `beam` and `span` also take their own keys), or
/// `{ kind = "fmu", file, ports, ... }`: an external FMU in place of the unit,
/// with the ports of the `ports` fidelity (default nonlinear) and the `fmu`
/// kind's parameters.
fn fidelity_of(section: &str, value: Option<&Value>) -> Result<WrittenModel, String> {
    let key = format!("{section}.fidelity");
    let native = |fidelity, elements| WrittenModel {
        fidelity,
        elements,
        fmu: None,
        options: None,
    };
    match value {
        None => Ok(native(Fidelity::Nonlinear, None)),
        Some(Value::String(written)) => {
            let (word, count) = short_form(&key, written)?;
            let fidelity = Fidelity::parse(&key, word)?;
            match (count, fidelity.count_key()) {
                (None, _) => Ok(native(fidelity, None)),
                (Some(n), "elements") => Ok(native(fidelity, Some(n))),
                // A count with its own key (a reduced section's modes, a
                // span's order): as the table the command line writes.
                (Some(n), count_key) => {
                    let mut table = Table::new();
                    table.insert("kind".into(), Value::String(word.into()));
                    table.insert(count_key.into(), Value::Integer(n as i64));
                    fidelity_of(section, Some(&Value::Table(table)))
                }
            }
        }
        Some(Value::Table(t)) if t.get("kind").and_then(Value::as_str) == Some("fmu") => {
            fmu_of(&key, t)
        }
        Some(Value::Table(t)) if let Some(fidelity) = own_keys(t) => options_of(&key, t, fidelity),
        Some(Value::Table(t)) => {
            if let Some(unknown) = t.keys().find(|k| *k != "kind" && *k != "elements") {
                return Err(format!(
                    "`{key}.{unknown}`: unknown key; expected `kind` and optionally `elements`"
                ));
            }
            let word = t.get("kind").and_then(Value::as_str).ok_or(format!(
                "`{key}.kind`: expected one of {}, fmu",
                Fidelity::NAMES.join(", ")
            ))?;
            let elements = t
                .get("elements")
                .map(|v| whole(&format!("{key}.elements"), v))
                .transpose()?;
            Ok(native(
                Fidelity::parse(&format!("{key}.kind"), word)?,
                elements,
            ))
        }
        Some(_) => Err(format!(
            "`{key}`: expected a name ({}) or a table {{ kind, elements }}",
            Fidelity::NAMES.join(", ")
        )),
    }
}

/// A fidelity written as the command line writes a choice, `name:count`
/// (e.g. `"nonlinear:16"`): the name and the count; a bare name has none.
/// Sub-steps (`/k`) have their own key in a scene, `substeps`.
fn short_form<'a>(key: &str, word: &'a str) -> Result<(&'a str, Option<usize>), String> {
    if word.contains('/') || word.contains('@') {
        return Err(format!(
            "`{key}` = \"{word}\": in a scene, sub-steps are the section's `substeps` key and a reduced section's options a table; write the fidelity as `name` or `name:count`"
        ));
    }
    let Some((name, count)) = word.split_once(':') else {
        return Ok((word, None));
    };
    match count.parse::<usize>() {
        Ok(n) if n >= 1 => Ok((name, Some(n))),
        _ => Err(format!(
            "`{key}` = \"{word}\": the count after `:` is a whole number of at least 1"
        )),
    }
}

/// A section's model: the fidelity its ports follow, its element count, the
/// `fmu` parameters of an external FMU in its place, and the fidelity's own
/// keys.
struct WrittenModel {
    fidelity: Fidelity,
    elements: Option<usize>,
    fmu: Option<Table>,
    options: Option<Table>,
}

/// The fidelity `{ kind = NAME, ... }` names where it has keys of its own.
fn own_keys(t: &Table) -> Option<Fidelity> {
    let word = t.get("kind").and_then(Value::as_str)?;
    let fidelity = Fidelity::parse("kind", word).ok()?;
    (!fidelity.model().option_keys().is_empty()).then_some(fidelity)
}

/// `{ kind, elements, ... }` of a fidelity with keys of its own: those
/// besides `kind` and `elements` go to the unit, checked when it is built.
fn options_of(key: &str, t: &Table, fidelity: Fidelity) -> Result<WrittenModel, String> {
    let keys = fidelity.model().option_keys();
    if let Some(unknown) = t.keys().find(|k| !keys.contains(&k.as_str())) {
        return Err(format!(
            "`{key}.{unknown}`: unknown key; a {} section takes {}",
            fidelity.name(),
            keys.join(", ")
        ));
    }
    let elements = t
        .get("elements")
        .map(|v| whole(&format!("{key}.elements"), v))
        .transpose()?;
    let mut basis = t.clone();
    basis.remove("kind");
    basis.remove("elements");
    Ok(WrittenModel {
        fidelity,
        elements,
        fmu: None,
        options: Some(basis),
    })
}

/// `{ kind = "fmu", file = "x.fmu", ports = "nonlinear" | "cable", start, preload, logging }`.
fn fmu_of(key: &str, t: &Table) -> Result<WrittenModel, String> {
    const KEYS: [&str; 6] = ["kind", "file", "ports", "start", "preload", "logging"];
    if let Some(unknown) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(format!(
            "`{key}.{unknown}`: unknown key; an FMU section takes {}",
            KEYS.join(", ")
        ));
    }
    if t.get("file").and_then(Value::as_str).is_none() {
        return Err(format!(
            "`{key}.file`: expected the FMU file (relative to the scene's folder)"
        ));
    }
    let fidelity = match t.get("ports") {
        None => Fidelity::Nonlinear,
        Some(v) => Fidelity::parse(
            &format!("{key}.ports"),
            v.as_str()
                .ok_or(format!("`{key}.ports`: expected a fidelity's name"))?,
        )?,
    };
    let mut fmu = t.clone();
    fmu.remove("kind");
    fmu.remove("ports");
    Ok(WrittenModel {
        fidelity,
        elements: None,
        fmu: Some(fmu),
        options: None,
    })
}

/// A whole number >= 1 at `key`.
fn whole(key: &str, v: &Value) -> Result<usize, String> {
    at_least_one(key, v.as_integer())
}

/// `n`, read at `key`, as a count >= 1.
fn at_least_one(key: &str, n: Option<i64>) -> Result<usize, String> {
    n.filter(|&n| n >= 1)
        .map(|n| n as usize)
        .ok_or(format!("`{key}`: expected a whole number >= 1"))
}
