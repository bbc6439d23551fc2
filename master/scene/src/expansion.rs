//! A scene's `[structure]` written out as typed units and connections: the
//! structure's generator (`structure::expand`) gives them as tables, which are
//! typed here (`UnitSpec`, `ConnectionSpec`) and appended to the scene's own,
//! so the scene is read once, from the user's text, and every span points
//! into it (the units a structure writes out point at its `[structure]`
//! header). The TOML text of the whole expanded scene is still made, for
//! `slender expand` to print and for exporting a section's unit, but it is not
//! read again.

use crate::spec::{ConnectionSpec, UnitSpec};
use crate::{SceneError, structure, structure_lines};
use serde::de::DeserializeOwned;
use slender_units::Hold;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;
use toml::{Spanned, Table, Value};

/// What a `[structure]` writes out.
pub(crate) struct Expansion {
    /// `structure.name`: the prefix of its units' names.
    pub name: String,
    pub units: Vec<UnitSpec>,
    pub connections: Vec<ConnectionSpec>,
    /// The whole scene as TOML text with the structure written out.
    pub text: String,
    /// What its sections' models follow poorly.
    pub advisories: Vec<String>,
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

/// The `[structure]` of the scene text `source` written out; None without
/// one (or when the text does not parse: the spec parser reports that with
/// its line). An error names the line of the key it is about in `source`.
pub(crate) fn expand(path: &Path, source: &str) -> Result<Option<Expansion>, SceneError> {
    if !source.contains("structure") {
        return Ok(None);
    }
    let error = |message: String| SceneError {
        file: path.to_owned(),
        line: structure_lines::model_parameter_line(source, &message)
            .or_else(|| {
                structure_lines::structure_key(&message)
                    .and_then(|key| structure_lines::key_line(source, key))
            })
            .or_else(|| structure_lines::key_line(source, "structure")),
        key: "structure".into(),
        message,
    };
    let Ok(mut table) = toml::from_str::<Table>(source) else {
        return Ok(None);
    };
    let name = (table.get("structure"))
        .and_then(|s| s.get("name"))
        .and_then(Value::as_str)
        .map(str::to_owned)
        .unwrap_or_default();
    let Some(written) = structure::expand(&mut table).map_err(error)? else {
        return Ok(None);
    };
    let span = structure_lines::structure_span(source).unwrap_or(0..0);
    let units = (written.units.iter())
        .map(|u| unit_spec(u, &span))
        .collect::<Result<_, _>>()
        .map_err(error)?;
    let connections = (written.connections.iter())
        .map(|c| connection_spec(c, &span))
        .collect::<Result<_, _>>()
        .map_err(error)?;
    let text = toml::to_string(&table).map_err(|e| error(e.to_string()))?;
    Ok(Some(Expansion {
        name,
        units,
        connections,
        text,
        advisories: written.advisories,
    }))
}

/// The keys a written-out unit may have.
const UNIT_KEYS: [&str; 7] = [
    "name",
    "kind",
    "parameters",
    "effects",
    "hold",
    "substeps",
    "inputs",
];

/// A written-out unit as the scene's type, its name, kind and parameters
/// spanned at `span`.
fn unit_spec(unit: &Value, span: &Range<usize>) -> Result<UnitSpec, String> {
    let t = unit.as_table().ok_or("a written-out unit is not a table")?;
    if let Some(key) = t.keys().find(|k| !UNIT_KEYS.contains(&k.as_str())) {
        return Err(format!("a written-out unit has the key `{key}`"));
    }
    let parameters = t.get("parameters").and_then(Value::as_table);
    Ok(UnitSpec {
        name: Spanned::new(span.clone(), text(t, "name")?),
        kind: Spanned::new(span.clone(), text(t, "kind")?),
        parameters: parameters.map(|p| Spanned::new(span.clone(), p.clone())),
        effects: typed::<Vec<String>>(t, "effects")?.unwrap_or_default(),
        hold: typed::<Hold>(t, "hold")?,
        substeps: typed::<u32>(t, "substeps")?,
        inputs: typed::<BTreeMap<String, f64>>(t, "inputs")?.unwrap_or_default(),
    })
}

/// A written-out connection as the scene's type, its ends spanned at `span`.
fn connection_spec(link: &Value, span: &Range<usize>) -> Result<ConnectionSpec, String> {
    let t = link
        .as_table()
        .ok_or("a written-out connection is not a table")?;
    const KEYS: [&str; 5] = ["from", "to", "gain", "offset", "tolerance"];
    if let Some(key) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(format!("a written-out connection has the key `{key}`"));
    }
    Ok(ConnectionSpec {
        from: Spanned::new(span.clone(), text(t, "from")?),
        to: Spanned::new(span.clone(), text(t, "to")?),
        gain: typed::<f64>(t, "gain")?.unwrap_or(1.0),
        offset: typed::<f64>(t, "offset")?.unwrap_or(0.0),
        tolerance: typed::<f64>(t, "tolerance")?,
    })
}

fn text(t: &Table, key: &str) -> Result<String, String> {
    (t.get(key).and_then(Value::as_str))
        .map(str::to_owned)
        .ok_or(format!("a written-out unit or connection has no `{key}`"))
}

/// `t[key]` as a `T`, where present.
fn typed<T: DeserializeOwned>(t: &Table, key: &str) -> Result<Option<T>, String> {
    (t.get(key).cloned())
        .map(|v| v.try_into::<T>())
        .transpose()
        .map_err(|e| format!("a written-out `{key}`: {e}"))
}
