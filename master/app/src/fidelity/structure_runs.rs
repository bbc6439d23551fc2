//! The scene of one run of a `[structure]`'s fidelity study: the
//! combination's choices written on its sections, or the whole structure as
//! one section (the reference); stations placed at the cuts so that every run
//! gives the force there the same way; the `[output]` its quantities read.

use super::Structure;
use super::choice::Choice;
use super::quantities::{self, Features, SectionUnit};
use slender_scene::structure::{Layout, SectionLayout};
use toml::{Table, Value};

/// The scene of one run: the combination's choices on the sections, or (for
/// the reference, `None`) the whole structure as one section; and its sections'
/// units, as the run's layout names them.
pub(super) fn run_table(
    table: &Table,
    structure: &Structure,
    combination: Option<&[(String, Choice)]>,
) -> Result<(Table, Vec<SectionUnit>), String> {
    let mut table = table.clone();
    let s = table
        .get_mut("structure")
        .and_then(Value::as_table_mut)
        .ok_or("no `[structure]`")?;
    let sections = s
        .get_mut("sections")
        .and_then(Value::as_array_mut)
        .ok_or("`structure.sections`: expected a list")?;
    let Some(combination) = combination else {
        let mut whole = Table::new();
        whole.insert("name".into(), Value::String("monolithic".into()));
        *sections = vec![Value::Table(whole)];
        let planar = structure.layout.planar;
        let first = planar
            .then(|| add_cut_stations(s, &structure.layout))
            .transpose()?;
        let mut units = run_sections(&table)?;
        if let [whole] = units.as_mut_slice() {
            whole.cut_stations = first;
        }
        return finish(table, units, &structure.features);
    };
    for (name, choice) in combination {
        let section = sections
            .iter_mut()
            .filter_map(Value::as_table_mut)
            .find(|t| t.get("name").and_then(Value::as_str) == Some(name))
            .ok_or(format!("no section `{name}`"))?;
        slender_scene::structure::write_choice(
            section,
            &choice.fidelity,
            choice.elements,
            choice.substeps,
        )?;
        if let Some(t) = choice.training {
            slender_scene::structure::write_training(section, t)?;
        }
    }
    let mut units = run_sections(&table)?;
    let end_stations = add_end_stations(&mut table, &units)?;
    for (unit, ends) in units.iter_mut().zip(end_stations) {
        unit.end_stations = ends;
    }
    finish(table, units, &structure.features)
}

/// The sections' units of a run's scene, from its layout.
fn run_sections(table: &Table) -> Result<Vec<SectionUnit>, String> {
    let layout = slender_scene::structure::layout(table)?.ok_or("no `[structure]`")?;
    Ok(layout.sections.into_iter().map(SectionUnit::new).collect())
}

impl SectionUnit {
    /// A section of a run, before its stations are placed.
    fn new(section: SectionLayout) -> SectionUnit {
        SectionUnit {
            unit: section.unit,
            from: section.from,
            outputs: section.outputs,
            cut_stations: None,
            end_stations: [None, None],
        }
    }
}

/// The structure model's `stations` list (made empty when there is none).
fn model_stations(structure_table: &mut Table) -> Result<&mut Vec<Value>, String> {
    structure_table
        .get_mut("model")
        .and_then(Value::as_table_mut)
        .ok_or("`structure.model`: expected a table")?
        .entry("stations")
        .or_insert_with(|| Value::Array(Vec::new()))
        .as_array_mut()
        .ok_or_else(|| "`structure.model.stations`: expected a list".to_owned())
}

/// Puts stations in the elements on both sides of every cut between two
/// sections that take stations (native `nonlinear` units), just below the
/// cut in the lower section and at the cut in the upper one (a section holds
/// the model's stations in [from, to), numbered from 1 in the model's order);
/// returns each section's numbers of its first- and last-element stations.
fn add_end_stations(
    table: &mut Table,
    sections: &[SectionUnit],
) -> Result<Vec<[Option<usize>; 2]>, String> {
    let n = sections.len();
    let mut ends = vec![[None, None]; n];
    if !sections.iter().any(|s| s.outputs.stations) {
        return Ok(ends);
    }
    let structure_table = table
        .get_mut("structure")
        .and_then(Value::as_table_mut)
        .ok_or("no `[structure]`")?;
    let stations = model_stations(structure_table)?;
    let arc = |v: &Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
    let mut count = vec![0usize; n];
    let section_of = |s: f64| sections.iter().rposition(|section| section.from <= s);
    for s in stations.iter().filter_map(arc) {
        if let Some(k) = section_of(s) {
            count[k] += 1;
        }
    }
    for k in 0..n.saturating_sub(1) {
        if !sections[k].outputs.stations || !sections[k + 1].outputs.stations {
            continue;
        }
        let cut = sections[k + 1].from;
        // Inside the lower section's last element, clear of round-off.
        stations.push(Value::Float(cut - 1e-6 * cut.abs().max(1.0)));
        count[k] += 1;
        ends[k][1] = Some(count[k]);
        stations.push(Value::Float(cut));
        count[k + 1] += 1;
        ends[k + 1][0] = Some(count[k + 1]);
    }
    Ok(ends)
}

/// Puts a station at each cut on the whole structure's model (the reference),
/// after the model's own; returns the number of the first.
fn add_cut_stations(structure_table: &mut Table, layout: &Layout) -> Result<usize, String> {
    let stations = model_stations(structure_table)?;
    let first = stations.len() + 1;
    stations.extend((layout.sections.iter().skip(1)).map(|section| Value::Float(section.from)));
    Ok(first)
}

/// Adds the `[output]` that records the quantities' signals.
fn finish(
    mut table: Table,
    units: Vec<SectionUnit>,
    features: &Features,
) -> Result<(Table, Vec<SectionUnit>), String> {
    let signals = quantities::signals(&units, features);
    let mut output = Table::new();
    output.insert(
        "signals".into(),
        Value::Array(signals.into_iter().map(Value::String).collect()),
    );
    table.insert("output".into(), Value::Table(output));
    Ok((table, units))
}
