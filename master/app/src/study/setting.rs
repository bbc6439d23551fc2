//! What a study varies: a scene key by its path (`simulation.step`,
//! `master.scheme`, `master.acceleration.kind`,
//! `units.<name>.parameters.segments.0.elements`, ...) or one of the short names
//! of seed 000's Appendix B study, and the values it takes. A value is applied to
//! the scene's TOML before the scene is checked, so any key the scene reference
//! documents can vary.

use crate::AppError;
use std::fmt;
use std::str::FromStr;

/// The short names: `elements` sets every `cable` unit's element count; the
/// others name a master or simulation key.
const SHORT: [(&str, &str); 4] = [
    ("elements", ""),
    ("step", "simulation.step"),
    ("velocity_tolerance", "master.tolerances.velocity"),
    ("force_tolerance", "master.tolerances.force"),
];

/// Which value of a sweep is the reference of the others.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Refinement {
    /// The smallest value is the finest (steps, tolerances): errors shrink with it.
    Smaller,
    /// The largest value is the finest (element counts).
    Larger,
    /// No order: the first value given is the reference.
    None,
}

/// A varied key.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Setting {
    /// As the user wrote it (a short name or a dotted path).
    pub name: String,
    /// The dotted path; empty for `elements` (every cable unit).
    path: Vec<String>,
}

impl Setting {
    /// How the setting's values are ordered by fineness.
    pub fn refinement(&self) -> Refinement {
        let last = self.path.last().map_or(self.name.as_str(), String::as_str);
        if last == "elements" || self.name == "elements" {
            Refinement::Larger
        } else if last == "step"
            || last.ends_with("tolerance")
            || self.path.iter().any(|p| p == "tolerances")
        {
            Refinement::Smaller
        } else {
            Refinement::None
        }
    }

    /// Sets `value` in the scene (its keys, before the scene is checked).
    /// `units.<name>` finds a unit by its name, a number indexes an array, and
    /// missing tables are made (a parameter left at its default can vary).
    /// An error says where the key path does not apply.
    pub fn apply(&self, scene: &mut toml::Table, value: &toml::Value) -> Result<(), AppError> {
        self.set(scene, value).map_err(AppError::Asked)
    }

    fn set(&self, scene: &mut toml::Table, value: &toml::Value) -> Result<(), String> {
        if self.path.is_empty() {
            return set_cable_elements(scene, value);
        }
        scheme_preset(&self.path, scene, value);
        let (last, parents) = self.path.split_last().ok_or("an empty key")?;
        let mut here: &mut toml::Table = scene;
        let mut walked = String::new();
        let mut i = 0;
        while i < parents.len() {
            let part = &parents[i];
            walked = if walked.is_empty() {
                part.clone()
            } else {
                format!("{walked}.{part}")
            };
            let entry = here
                .entry(part.clone())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            here = match entry {
                toml::Value::Table(t) => t,
                toml::Value::Array(items) => {
                    let Some(next) = parents.get(i + 1) else {
                        // The key ends in an index into a list of values.
                        return set_item(items, last, value, &walked);
                    };
                    walked = format!("{walked}.{next}");
                    i += 1;
                    element(items, next, &walked)?
                }
                _ => return Err(format!("`{walked}` is a value, not a table")),
            };
            i += 1;
        }
        here.insert(last.clone(), value.clone());
        Ok(())
    }
}

/// What a coupling scheme's keys imply for the others, so that a study
/// comparing schemes runs each at its defaults: a new acceleration kind
/// starts from its own defaults (an IQN-ILS `reuse_steps` would be refused by
/// Aitken), and a non-iterative scheme drops the acceleration and Newton it
/// cannot take. The kind the scene has already keeps the scene's settings (a
/// sweep over kinds that includes the scene's own ran it at other settings).
fn scheme_preset(path: &[String], scene: &mut toml::Table, value: &toml::Value) {
    let Some(toml::Value::Table(master)) = scene.get_mut("master") else {
        return;
    };
    let kind = |m: &toml::Table| {
        let acceleration = m.get("acceleration");
        acceleration.and_then(|a| a.get("kind")).cloned()
    };
    match path {
        [m, a, k] if m == "master" && a == "acceleration" && k == "kind" => {
            if kind(master).as_ref() == Some(value) {
                return;
            }
            master.remove("acceleration");
            master.remove("newton");
        }
        [m, s] if m == "master" && s == "scheme" => {
            if matches!(value.as_str(), Some("jacobi" | "gauss_seidel")) {
                master.remove("acceleration");
                master.remove("newton");
            }
        }
        _ => {}
    }
}

/// Sets item `index` of a list of values (e.g. `scale.0` of an artefact).
fn set_item(
    items: &mut [toml::Value],
    index: &str,
    value: &toml::Value,
    walked: &str,
) -> Result<(), String> {
    let count = items.len();
    let item = index
        .parse::<usize>()
        .ok()
        .and_then(|k| items.get_mut(k))
        .ok_or_else(|| {
            format!("`{walked}.{index}`: the list has {count} entries, give an index 0..{count}")
        })?;
    *item = value.clone();
    Ok(())
}

/// The element of a list by index, or the table whose `name` is `key`
/// (`units.<name>`, `structure.sections.<name>`).
fn element<'a>(
    items: &'a mut [toml::Value],
    key: &str,
    walked: &str,
) -> Result<&'a mut toml::Table, String> {
    let count = items.len();
    let names: Vec<String> = items
        .iter()
        .filter_map(|u| {
            u.get("name")
                .and_then(toml::Value::as_str)
                .map(str::to_owned)
        })
        .collect();
    let found = match key.parse::<usize>() {
        Ok(k) => items.get_mut(k),
        Err(_) => items
            .iter_mut()
            .find(|u| u.get("name").and_then(toml::Value::as_str) == Some(key)),
    };
    found.and_then(toml::Value::as_table_mut).ok_or_else(|| {
        if names.is_empty() {
            format!("`{walked}`: the list has {count} entries, give an index 0..{count}")
        } else {
            format!(
                "`{walked}`: no entry named `{key}`; the list has {}",
                names.join(", ")
            )
        }
    })
}

fn set_cable_elements(scene: &mut toml::Table, value: &toml::Value) -> Result<(), String> {
    let units = scene.get_mut("units").and_then(toml::Value::as_array_mut);
    let mut found = false;
    for unit in units.into_iter().flatten() {
        if unit.get("kind").and_then(toml::Value::as_str) == Some("cable") {
            let parameters = unit
                .as_table_mut()
                .ok_or("a unit is not a table")?
                .entry("parameters")
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            if let Some(p) = parameters.as_table_mut() {
                p.insert("elements".into(), value.clone());
                found = true;
            }
        }
    }
    if found {
        Ok(())
    } else {
        Err("the scene has no `cable` unit whose elements could vary".into())
    }
}

impl FromStr for Setting {
    type Err = String;
    fn from_str(s: &str) -> Result<Setting, String> {
        let name = s.trim();
        if let Some((_, path)) = SHORT.iter().find(|(short, _)| *short == name) {
            let path = path
                .split('.')
                .filter(|p| !p.is_empty())
                .map(str::to_owned)
                .collect();
            return Ok(Setting {
                name: name.to_owned(),
                path,
            });
        }
        let path = key_parts(name).ok_or_else(|| {
            format!(
                "`{name}`: a bracket holds a whole index and closes, as in segments[0].elements"
            )
        })?;
        let known = [
            "simulation",
            "master",
            "units",
            "connections",
            "output",
            "structure",
            "mooring",
            "uncertainty",
        ];
        if path.len() < 2 || path.iter().any(String::is_empty) || !known.contains(&path[0].as_str())
        {
            let shorts = SHORT.iter().map(|(s, _)| *s);
            return Err(format!(
                "unknown setting `{name}`{}: expected a scene key path under simulation, master, units, connections, output, structure, mooring or uncertainty, down to a value (master.scheme, not master; units.<name>.parameters.<key>), or a short name: elements, step, velocity_tolerance, force_tolerance",
                slender_coupling::error::did_you_mean(name, shorts)
            ));
        }
        Ok(Setting {
            name: name.to_owned(),
            path,
        })
    }
}

/// The parts of a key path, an array's entry written `segments[1]` or
/// `segments.1`; None where a bracket does not hold a whole index and close
/// (`segments[0.elements` was read as `segments.0.elements`).
fn key_parts(name: &str) -> Option<Vec<String>> {
    let mut parts = Vec::new();
    for dotted in name.split('.') {
        let mut pieces = dotted.split('[');
        parts.push(pieces.next()?.to_owned());
        for piece in pieces {
            let index = piece.strip_suffix(']')?;
            let whole = !index.is_empty() && index.bytes().all(|b| b.is_ascii_digit());
            parts.push(whole.then(|| index.to_owned())?);
        }
    }
    (!parts.iter().any(|p| p.contains(']'))).then_some(parts)
}

impl fmt::Display for Setting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)
    }
}

/// A command-line value as TOML: an integer, a float, true/false, else a string.
pub fn parse_value(text: &str) -> toml::Value {
    let t = text.trim();
    if let Ok(i) = t.parse::<i64>() {
        toml::Value::Integer(i)
    } else if let Ok(x) = t.parse::<f64>() {
        toml::Value::Float(x)
    } else if let Ok(b) = t.parse::<bool>() {
        toml::Value::Boolean(b)
    } else {
        toml::Value::String(t.to_owned())
    }
}

/// `KEY=VALUE` of `slender run --set`: a scene key by its path (as a study
/// varies it) and a TOML value (`0.5`, `true`, `[1, 2]`, `{ kind = "none" }`;
/// a bare word is a string).
pub fn parse_override(text: &str) -> Result<(Setting, toml::Value), AppError> {
    let (key, value) = text.split_once('=').ok_or_else(|| {
        format!("`{text}`: expected KEY=VALUE, e.g. simulation.duration=10 or master.scheme=jacobi")
    })?;
    let setting: Setting = key.trim().parse()?;
    let written = format!("v = {}", value.trim());
    let value = match toml::from_str::<toml::Table>(&written) {
        Ok(mut t) => t.remove("v").unwrap_or_else(|| parse_value(value)),
        Err(_) => parse_value(value),
    };
    Ok((setting, value))
}

/// A value as a number, when it is one.
pub fn numeric(value: &toml::Value) -> Option<f64> {
    match value {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(x) => Some(*x),
        _ => None,
    }
}

/// A value as the table shows it.
pub fn label(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> toml::Table {
        toml::from_str(
            r#"
[simulation]
step = 0.01
[master]
scheme = "jacobi"
[[units]]
name = "a"
kind = "cable"
parameters = { elements = 10 }
[[units]]
name = "b"
kind = "nonlinear"
[units.parameters]
segments = [{ length = 1.0, elements = 4 }, { length = 2.0, elements = 8 }]
"#,
        )
        .unwrap()
    }

    fn set(key: &str, value: &str) -> Result<toml::Table, String> {
        let mut t = scene();
        let setting = key.parse::<Setting>()?;
        setting.set(&mut t, &parse_value(value))?;
        Ok(t)
    }

    #[test]
    fn paths_reach_units_by_name_arrays_by_index_and_make_missing_tables() {
        let t = set("units.b.parameters.segments.1.elements", "16").unwrap();
        assert_eq!(
            t["units"][1]["parameters"]["segments"][1]["elements"].as_integer(),
            Some(16)
        );
        // The same entry written with brackets.
        let t = set("units.b.parameters.segments[0].elements", "6").unwrap();
        assert_eq!(
            t["units"][1]["parameters"]["segments"][0]["elements"].as_integer(),
            Some(6)
        );
        let t = set("master.acceleration.kind", "aitken").unwrap();
        assert_eq!(t["master"]["acceleration"]["kind"].as_str(), Some("aitken"));
        let t = set("step", "0.005").unwrap();
        assert_eq!(t["simulation"]["step"].as_float(), Some(0.005));
        let t = set("elements", "40").unwrap();
        assert_eq!(
            t["units"][0]["parameters"]["elements"].as_integer(),
            Some(40)
        );
        assert!(t["units"][1]["parameters"].get("elements").is_none());
    }

    #[test]
    fn bad_paths_say_what_is_there() {
        assert!(
            set("units.c.parameters.x", "1")
                .unwrap_err()
                .contains("no entry named `c`; the list has a, b")
        );
        assert!(
            set("units.b.parameters.segments.5.elements", "1")
                .unwrap_err()
                .contains("the list has 2 entries")
        );
        assert!(
            set("master.scheme.kind", "1")
                .unwrap_err()
                .contains("is a value")
        );
        assert!(
            set("nonsense", "1")
                .unwrap_err()
                .contains("unknown setting")
        );
    }

    #[test]
    fn refinement_follows_the_key() {
        let r = |k: &str| k.parse::<Setting>().unwrap().refinement();
        assert_eq!(r("simulation.step"), Refinement::Smaller);
        assert_eq!(r("master.tolerances.force"), Refinement::Smaller);
        assert_eq!(
            r("units.b.parameters.segments.0.elements"),
            Refinement::Larger
        );
        assert_eq!(r("master.scheme"), Refinement::None);
    }

    #[test]
    fn coupling_schemes_compare_at_their_defaults() {
        let mut t: toml::Table = toml::from_str(
            "[master]\nscheme = \"iterative_jacobi\"\nacceleration = { kind = \"iqn_ils\", reuse_steps = 8 }",
        )
        .unwrap();
        let set = |t: &mut toml::Table, key: &str, value: &str| {
            let s: Setting = key.parse().unwrap();
            s.apply(t, &toml::Value::String(value.into())).unwrap();
        };
        // The scene's own kind keeps its settings.
        set(&mut t, "master.acceleration.kind", "iqn_ils");
        assert_eq!(
            t["master"]["acceleration"]["reuse_steps"].as_integer(),
            Some(8)
        );
        set(&mut t, "master.acceleration.kind", "aitken");
        assert_eq!(
            t["master"]["acceleration"].to_string(),
            "{ kind = \"aitken\" }"
        );
        set(&mut t, "master.scheme", "iterative_gauss_seidel");
        assert!(t["master"].get("acceleration").is_some());
        set(&mut t, "master.scheme", "jacobi");
        assert!(t["master"].get("acceleration").is_none() && t["master"].get("newton").is_none());
    }

    #[test]
    fn a_bracket_that_is_not_a_whole_index_is_refused() {
        for bad in [
            "structure.model.segments[0.elements",
            "units.a[x].b",
            "units.a]0.b",
            "units.a[].b",
        ] {
            let error = bad.parse::<Setting>().expect_err(bad);
            assert!(
                error.contains("a bracket holds a whole index"),
                "{bad}: {error}"
            );
        }
        let good: Setting = "structure.model.segments[1].elements"
            .parse()
            .expect("a path");
        assert_eq!(
            good.path,
            ["structure", "model", "segments", "1", "elements"]
        );
        let dotted: Setting = "structure.model.segments.1.elements"
            .parse()
            .expect("a path");
        assert_eq!(dotted.path, good.path);
    }
}
