//! What the scene reference (`docs/scene-reference.md`, compiled in) says of
//! each kind's parameters: unit, meaning and documented range, for an exported
//! FMU's model description. One source: `tests/tests/scenes.rs` checks that the
//! reference has a row for every parameter of every kind.

use slender_fmi::export::ParameterInfo;
use slender_units::contract::measure::si_exponents;
use std::collections::BTreeMap;

const REFERENCE: &str = include_str!("../../docs/scene-reference.md");

/// The documented parameters of `kind`, by top-level key (empty when the
/// reference has no parameter table for it).
pub fn parameters(kind: &str) -> BTreeMap<String, ParameterInfo> {
    let mut found = BTreeMap::new();
    let heading = format!("### Kind `{kind}`");
    let Some(start) = REFERENCE.find(&heading) else {
        return found;
    };
    let section = &REFERENCE[start + heading.len()..];
    let section = &section[..section.find("\n#").unwrap_or(section.len())];
    let mut header: Option<Vec<String>> = None;
    for line in section.lines() {
        if line.starts_with("| parameter ") {
            header = Some(cells(line));
            continue;
        }
        let Some(columns) = &header else { continue };
        if !line.starts_with('|') {
            break;
        }
        if line.starts_with("|---") {
            continue;
        }
        let row = cells(line);
        let column = |name: &str| {
            columns
                .iter()
                .position(|c| c == name)
                .and_then(|i| row.get(i))
                .map_or("", String::as_str)
        };
        let keys = quoted(&row[0]);
        let units: Vec<&str> = column("unit").split(", ").collect();
        for (k, key) in keys.iter().enumerate() {
            let unit = if units.len() == keys.len() {
                units[k]
            } else {
                units[0]
            };
            found.insert(key.clone(), info(unit, column("meaning")));
        }
    }
    found
}

/// A parameter's information from its row: the unit when slender knows it as
/// a unit of measure, the meaning, and a range written "A to B".
fn info(unit: &str, meaning: &str) -> ParameterInfo {
    let unit = if si_exponents(unit).is_some() {
        unit
    } else {
        ""
    };
    let words: Vec<&str> = meaning.split_whitespace().collect();
    let number = |w: &str| {
        w.trim_end_matches([',', ';', ')', '.'])
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
    };
    let range = words.windows(3).find_map(|w| match w {
        [a, "to", b] => Some((number(a)?, number(b)?)),
        _ => None,
    });
    ParameterInfo {
        unit: unit.to_owned(),
        meaning: meaning.replace('`', ""),
        min: range.map(|r| r.0),
        max: range.map(|r| r.1),
    }
}

/// The cells of a Markdown table row, trimmed.
fn cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
    inner.split('|').map(|c| c.trim().to_owned()).collect()
}

/// The `quoted` names in a cell.
fn quoted(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .filter(|name| name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
        .map(str::to_owned)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cable_s_rows_give_units_meanings_and_ranges() {
        let cable = parameters("cable");
        let length = &cable["length"];
        assert_eq!(length.unit, "m");
        assert_eq!((length.min, length.max), (Some(1e-2), Some(1e5)));
        assert!(length.meaning.contains("unstretched length"));
        // Two keys in one row, each with its unit.
        assert_eq!(cable["rayleigh_mass"].unit, "1/s");
        assert_eq!(cable["rayleigh_stiffness"].unit, "s");
        // "required" is no unit; a table is none either.
        assert_eq!(cable["current"].unit, "");
        assert!(parameters("no_such_kind").is_empty());
        // The chord's units were in its prose alone (issue 49 #15).
        let chord = parameters("chord");
        assert_eq!(chord["tension"].unit, "N");
        assert_eq!(chord["flexural_rigidity"].unit, "N m^2");
        assert_eq!(chord["axial_stiffness"].unit, "N/m");
        assert_eq!(chord["band"].unit, "rad/s");
        assert_eq!(chord["elements"].unit, "");
    }
}
