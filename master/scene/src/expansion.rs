//! A scene's `[structure]` written out as typed units and connections: the
//! structure's generator (`structure::expand`) gives them in the units' own
//! parameter types, taken here as the scene's (`UnitSpec`, `ConnectionSpec`)
//! and appended to the scene's own,
//! so the scene is read once, from the user's text, and every span points
//! into it (the units a structure writes out point at its `[structure]`
//! header). The TOML text of the whole expanded scene (`expanded_text`) is made only
//! when asked for: by `slender expand`, which prints it, and by the export of
//! a section's unit; it is never read back.

use crate::spec::{ConnectionSpec, UnitSpec};
use crate::structure::{self, Link, Parameters, SectionUnit, StructureError, Written};
use crate::{SceneError, structure_lines};
use slender_units::Time;
use std::ops::Range;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use toml::{Spanned, Table, Value};

/// What a `[structure]` writes out.
#[derive(Debug)]
pub(crate) struct Expansion {
    /// `structure.name`: the prefix of its units' names.
    pub name: String,
    pub units: Vec<UnitSpec>,
    pub connections: Vec<ConnectionSpec>,
    /// The same units and connections as the tables of the scene's text,
    /// and the advisories on what its sections' models follow poorly.
    pub written: Written,
}

/// Appends what the `expansions` write out to the scene `spec`'s units and
/// connections; returns them together and their advisories.
pub(crate) fn append(
    spec: &mut crate::spec::SceneSpec,
    expansions: impl Iterator<Item = Expansion>,
) -> (Option<Written>, Vec<String>) {
    let mut written: Option<Written> = None;
    let mut advisories = Vec::new();
    for mut x in expansions {
        spec.units.extend(x.units);
        spec.connections.extend(x.connections);
        advisories.append(&mut x.written.advisories);
        match &mut written {
            Some(w) => w.append(x.written),
            None => written = Some(x.written),
        }
    }
    (written, advisories)
}

/// Scene texts written out in this process (`texts_written`).
static TEXTS_WRITTEN: AtomicUsize = AtomicUsize::new(0);

/// How many expanded scene texts this process has written (`slender
/// expand`, an FMU's export): what a test counts to show that a run and a
/// study make none.
pub fn texts_written() -> usize {
    TEXTS_WRITTEN.load(Ordering::Relaxed)
}

/// The scene text `source` (its keys as `edited`, where changed) as it
/// runs: its `[structure]` and `[mooring]` replaced by the units and
/// connections they write out, when they do (what `slender expand` prints).
pub(crate) fn expanded_text(
    source: &str,
    edited: Option<&Table>,
    written: Option<&Written>,
) -> Result<String, String> {
    TEXTS_WRITTEN.fetch_add(1, Ordering::Relaxed);
    let mut table: Table = match edited {
        Some(table) => table.clone(),
        None => toml::from_str(source).map_err(|e| e.to_string())?,
    };
    let Some(written) = written else {
        return toml::to_string(&table).map_err(|e| e.to_string());
    };
    table.remove("structure");
    table.remove("mooring");
    let units = (written.units.iter())
        .map(SectionUnit::to_value)
        .collect::<Result<Vec<_>, _>>()?;
    let connections = written.connections.iter().map(Link::to_value);
    for (key, items) in [("units", units), ("connections", connections.collect())] {
        let list = table
            .entry(key.to_owned())
            .or_insert_with(|| Value::Array(Vec::new()))
            .as_array_mut()
            .ok_or(format!("`{key}`: expected a list"))?;
        list.extend(items);
    }
    toml::to_string(&table).map_err(|e| e.to_string())
}

/// An error about a unit the structure `name` writes out (its key names the
/// unit, `units[k] ("<name>_...")`) located at the model parameter or the
/// section it is about in `source`, else the `[structure]` table.
pub(crate) fn locate(source: &str, name: Option<&str>, mut e: SceneError) -> SceneError {
    if let Some(name) = name
        && e.key.contains(&format!("(\"{name}_"))
    {
        e.line = structure_lines::generated_unit_line(source, name, &e.key, &e.message).or(e.line);
    }
    e
}

/// The `[structure]` table `structure` of the scene text `source` written
/// out, its statics solved at the simulation's start `start` (s). An error
/// names the line of the key it is about in `source`.
pub(crate) fn expand(
    path: &Path,
    source: &str,
    structure: &Value,
    start: f64,
) -> Result<Expansion, SceneError> {
    let name = (structure.get("name"))
        .and_then(Value::as_str)
        .map(str::to_owned)
        .unwrap_or_default();
    written_out(path, source, "structure", name, start, |t0| {
        structure::expand(structure, t0)
    })
}

/// The `[mooring]` table `mooring` of `source` written out at `start` (s).
pub(crate) fn expand_mooring(
    path: &Path,
    source: &str,
    mooring: &Value,
    start: f64,
) -> Result<Expansion, SceneError> {
    written_out(path, source, "mooring", String::new(), start, |t0| {
        crate::mooring::Mooring::parse(mooring)?.expand(t0)
    })
}

/// What the table `key` (named `name`) of `source` writes out by `write`
/// at `start` (s), typed; an error names the line of the key it is about.
fn written_out(
    path: &Path,
    source: &str,
    key: &str,
    name: String,
    start: f64,
    write: impl FnOnce(Time) -> Result<Written, StructureError>,
) -> Result<Expansion, SceneError> {
    // The line of the model parameter the error names, else of its key,
    // else of the table.
    let error = |e: StructureError| SceneError {
        file: path.to_owned(),
        line: structure_lines::model_parameter_line(source, &e.message)
            .or_else(|| (e.key.as_deref()).and_then(|k| structure_lines::key_line(source, k)))
            .or_else(|| structure_lines::key_line(source, key)),
        key: key.into(),
        message: e.message,
    };
    let t0 = Time::from_secs(start)
        .ok_or_else(|| error("`simulation.start`: expected a time in seconds".into()))?;
    let written = write(t0).map_err(error)?;
    let span = structure_lines::key_span(source, key).unwrap_or(0..0);
    let units = (written.units.iter())
        .map(|u| unit_spec(u, &span))
        .collect::<Result<_, String>>()
        .map_err(|m| error(m.into()))?;
    let connections = (written.connections.iter())
        .map(|c| connection_spec(c, &span))
        .collect();
    Ok(Expansion {
        name,
        units,
        connections,
        written,
    })
}

/// A written-out unit as the scene's type, its name and kind spanned at
/// `span`, its parameters in its kind's own type (an external FMU's as its
/// table).
fn unit_spec(unit: &SectionUnit, span: &Range<usize>) -> Result<UnitSpec, String> {
    let substeps = (unit.substeps.map(u32::try_from).transpose())
        .map_err(|_| format!("unit `{}`: too many sub-steps", unit.name))?;
    let (parameters, written) = match &unit.parameters {
        Parameters::Fmu(table) => (Some(Spanned::new(span.clone(), table.clone())), None),
        typed => (None, Some(typed.clone())),
    };
    Ok(UnitSpec {
        name: Spanned::new(span.clone(), unit.name.clone()),
        kind: Spanned::new(span.clone(), unit.parameters.kind().to_owned()),
        parameters,
        effects: (unit.effects.iter().flatten())
            .map(|e| (*e).to_owned())
            .collect(),
        hold: None,
        substeps,
        inputs: unit.inputs.clone(),
        written,
    })
}

/// A written-out connection as the scene's type, its ends spanned at `span`.
fn connection_spec(link: &Link, span: &Range<usize>) -> ConnectionSpec {
    ConnectionSpec {
        from: Spanned::new(span.clone(), link.from.clone()),
        to: Spanned::new(span.clone(), link.to.clone()),
        gain: 1.0,
        offset: link.offset.unwrap_or(0.0),
        tolerance: None,
    }
}

#[cfg(test)]
mod tests {
    use crate::tests::{HANGING_PIPE, line_of, parse};

    #[test]
    fn the_expanded_text_is_made_only_when_asked_for() {
        let scene = parse(HANGING_PIPE).expect("the example");
        assert!(scene.expanded.get().is_none(), "text made on load");
        let text = scene.source().expect("the text");
        assert!(scene.expanded.get().is_some());
        let table: toml::Table = toml::from_str(text).expect("TOML");
        assert!(!table.contains_key("structure"));
        let units = table["units"].as_array().expect("units");
        // Three sections and the twin, typed in the spec the same.
        assert_eq!(units.len(), scene.spec.units.len());
        assert_eq!(units.len(), 4);
    }

    #[test]
    fn a_scene_without_structure_is_its_own_text() {
        let text = HANGING_PIPE.replace("[structure", "[unused");
        let plain = "[simulation]\nduration = 1.0\nstep = 0.5\n[master]\nscheme = \"jacobi\"\n\n[[units]]\nname = \"m\"\nkind = \"oscillator\"\nparameters = { mass = 1.0, stiffness = 1.0 }\n";
        let scene = parse(plain).expect("an empty scene");
        assert_eq!(scene.source().expect("the text"), plain);
        let error = parse(&text).expect_err("unknown table").to_string();
        assert!(error.contains("unused"), "{error}");
    }

    /// The model is read once, typed as the `nonlinear` unit's parameters:
    /// a wrong model key is refused at the model's own key and line, before
    /// any statics are solved or units written (it was found in the first
    /// section's unit, `units[0] ("pipe_upper").parameters`, at the
    /// `[structure]` header's line).
    #[test]
    fn a_wrong_model_key_is_refused_at_the_users_line() {
        for (written, expected) in [
            (
                "mass_per_length = \"x\"",
                "invalid type: string \"x\", expected a number",
            ),
            ("mass_per_lenth = 50.0", "unknown field `mass_per_lenth`"),
        ] {
            let text = HANGING_PIPE.replacen("mass_per_length = 50.0", written, 1);
            let error = parse(&text).expect_err(written).to_string();
            let line = line_of(&text, written);
            assert!(
                error.starts_with(&format!(
                    "pipe.toml:{line}: structure: `structure.model.segments[0]."
                )),
                "{error}"
            );
            assert!(error.contains(expected), "{error}");
        }
    }

    #[test]
    fn a_structure_error_names_the_users_line() {
        let text = HANGING_PIPE.replacen(
            "[[structure.sections]]",
            "[[structure.sections]]\nfidelity = \"wrong\"",
            1,
        );
        let error = parse(&text).expect_err("a wrong fidelity").to_string();
        let line = line_of(&text, "\"wrong\"");
        assert!(error.starts_with(&format!("pipe.toml:{line}:")), "{error}");
        assert!(error.contains("wrong"), "{error}");
    }

    /// A physical section's artefacts are checked where the structure is
    /// written out: a wrong key or value is refused at its own line (both
    /// were placed at the `[structure]` header or the first section).
    #[test]
    fn a_physical_sections_artefact_is_refused_at_the_users_line() {
        let truncation = include_str!("../../../examples/structure_truncation.toml");
        let sensor_delay = "delay = 0.026                      # theta7 (s)";
        for (written, expected) in [
            (
                "delayy = 0.026",
                "`structure.sections.upper.physical.sensor.delayy`: unknown field `delayy`",
            ),
            (
                "delay = -1.0",
                "`structure.sections.upper.physical.sensor.delay` = -1: expected",
            ),
        ] {
            let text = truncation.replacen(sensor_delay, written, 1);
            let error = parse(&text).expect_err(written).to_string();
            let line = line_of(&text, written);
            assert!(
                error.starts_with(&format!("pipe.toml:{line}: structure: {expected}")),
                "{error}"
            );
        }
    }
}
