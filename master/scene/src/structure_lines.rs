//! Lines of the user's file for errors about a `[structure]`: the units a
//! structure writes out point at its `[structure]` header, so an error found
//! in one of them is placed at the model parameter or the section it is
//! about; an error of the structure's own checks at the key it names.

use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The line (1-based) of the dotted key `path` in `source` (e.g.
/// `structure.sections.laid.fidelity`, `structure.sections[0].to`,
/// `structure.model.rayleigh_stiffness`): of the deepest part of it the file
/// writes (a section's own line where its `fidelity` is left to the default).
/// A name after an array picks the element whose `name` it is.
pub(crate) fn key_line(source: &str, path: &str) -> Option<usize> {
    locate(source, path).map(|(line, _)| line)
}

/// The line of `path` only where the file writes all of it.
fn exact_key_line(source: &str, path: &str) -> Option<usize> {
    locate(source, path)
        .filter(|&(_, whole)| whole)
        .map(|(line, _)| line)
}

/// The line of the deepest part of `path` the file writes, and whether that
/// is all of it.
fn locate(source: &str, path: &str) -> Option<(usize, bool)> {
    let document = DeTable::parse(source).ok()?;
    let mut table = document.get_ref();
    let mut array: Option<&[Spanned<DeValue>]> = None;
    let mut found = None;
    let parts = split(path);
    let mut reached = 0;
    for part in &parts {
        let part = *part;
        let value = match (array, part.strip_prefix('[')) {
            (Some(items), Some(index)) => {
                items.get(index.trim_end_matches(']').parse::<usize>().ok()?)
            }
            (Some(items), None) => items.iter().find(|item| named(item, part)),
            (None, _) => table
                .iter()
                .find(|(k, _)| k.get_ref() == part)
                .map(|(k, v)| {
                    found = Some(k.span().start);
                    v
                }),
        };
        let Some(value) = value else { break };
        reached += 1;
        if array.is_some() {
            found = Some(value.span().start);
        }
        array = None;
        match value.get_ref() {
            DeValue::Table(t) => table = t,
            DeValue::Array(items) => array = Some(&items[..]),
            _ => break,
        }
    }
    let line = |offset: usize| source[..offset.min(source.len())].matches('\n').count() + 1;
    found.map(|offset| (line(offset), reached == parts.len()))
}

/// The byte range of the top-level `key` in `source` (the `[structure]` or
/// `[mooring]` header), where the file writes it: what the units it writes
/// out point at.
pub(crate) fn key_span(source: &str, key: &str) -> Option<std::ops::Range<usize>> {
    let document = DeTable::parse(source).ok()?;
    let table = document.get_ref();
    (table.iter())
        .find(|(k, _)| k.get_ref() == key)
        .map(|(k, _)| k.span())
}

/// The parts of a dotted key, an index `[i]` its own part.
fn split(path: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    for piece in path.split('.') {
        match piece.find('[') {
            Some(i) if i > 0 => {
                parts.push(&piece[..i]);
                parts.push(&piece[i..]);
            }
            _ => parts.push(piece),
        }
    }
    parts
}

/// Whether an array element is a table whose `name` is `name`.
fn named(item: &Spanned<DeValue>, name: &str) -> bool {
    let DeValue::Table(t) = item.get_ref() else {
        return false;
    };
    t.iter().any(|(k, v)| {
        k.get_ref() == "name" && matches!(v.get_ref(), DeValue::String(s) if s == name)
    })
}

/// Every key under `top` that `message` names in backticks, in order.
pub(crate) fn named_keys<'a>(message: &'a str, top: &str) -> impl Iterator<Item = &'a str> {
    (message.split('`').skip(1).step_by(2))
        .filter(move |k| k.starts_with(top))
        .map(|k| k.split(" = ").next().unwrap_or(k))
}

/// The line of the `structure.model` parameter a message names
/// (`parameter `x``), where the file writes it.
pub(crate) fn model_parameter_line(source: &str, message: &str) -> Option<usize> {
    let parameter = message
        .split("parameter `")
        .nth(1)
        .and_then(|rest| rest.split('`').next())
        .map(|p| p.split('.').next().unwrap_or(p))?;
    exact_key_line(source, &format!("structure.model.{parameter}"))
}

/// Where in the user's file an error found in the units a `[structure]`
/// writes out is about: a model parameter it names (`parameter `x``) in
/// `structure.model`, else the section whose unit (`<name>_<section>`) it
/// names, else the `[structure]` table.
pub(crate) fn generated_unit_line(
    source: &str,
    structure: &str,
    key: &str,
    message: &str,
) -> Option<usize> {
    if let Some(line) = model_parameter_line(source, message) {
        return Some(line);
    }
    let unit = key.split('"').nth(1).unwrap_or_default();
    if let Some(section) = unit.strip_prefix(&format!("{structure}_"))
        && let Some(line) = key_line(source, &format!("structure.sections.{section}"))
    {
        return Some(line);
    }
    key_line(source, "structure")
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "[simulation]\nduration = 1.0\n\n[structure]\nname = \"pipe\"\n[structure.model]\nrayleigh_stiffness = -1.0\nsegments = [{ length = 30.0 }]\n\n[[structure.sections]]\nname = \"lower\"\nto = 10.0\n[[structure.sections]]\nname = \"upper\"\nfidelity = \"beam\"\n";

    #[test]
    fn a_key_is_found_on_its_line_also_through_named_sections() {
        assert_eq!(key_line(SCENE, "structure"), Some(4));
        assert_eq!(
            key_line(SCENE, "structure.model.rayleigh_stiffness"),
            Some(7)
        );
        assert_eq!(
            key_line(SCENE, "structure.sections.upper.fidelity"),
            Some(15)
        );
        assert_eq!(key_line(SCENE, "structure.sections[0].to"), Some(12));
        // Left to its default: the section's own table.
        assert_eq!(
            key_line(SCENE, "structure.sections.lower.fidelity"),
            Some(10)
        );
        assert_eq!(
            named_keys(
                "`structure.sections.upper.fidelity` = \"beam\": no, `mooring.x`",
                "structure"
            )
            .collect::<Vec<_>>(),
            ["structure.sections.upper.fidelity"]
        );
        let message = "parameter `rayleigh_stiffness` = -1: expected a finite value >= 0";
        assert_eq!(
            generated_unit_line(
                SCENE,
                "pipe",
                "units[0] (\"pipe_lower\").parameters",
                message
            ),
            Some(7)
        );
        assert_eq!(
            generated_unit_line(SCENE, "pipe", "units[1] (\"pipe_upper\")", "bad"),
            Some(13)
        );
    }
}
