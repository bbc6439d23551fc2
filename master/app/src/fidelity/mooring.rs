//! `slender fidelity` on a `[mooring]`: its lines' sections at chosen
//! fidelities, judged against a run with every line whole at its model's
//! mesh (the body's motion and every line's pull change together, so the
//! reference is a whole run, not a twin in the same run).
//!
//! A section is named `LINE.SECTION` (one line's) or `SECTION` (that section
//! in every line that has it: a spread of alike lines studied alike). The
//! quantities are each line's fairlead tension (`<line>_tension`, N) and the
//! body's six motions (`<body>_surge` ... `<body>_yaw`, m and rad, the
//! reference point's position and the z-y'-x'' angles); the tensions are
//! judged unless `--quantities` names others.

use super::Choice;
use super::subject::{Reader, SectionName, Subject};
use slender_scene::mooring::Mooring;
use slender_scene::structure::{Layout, write_choice};
use toml::{Table, Value};

/// The body's motions: the quantities' suffixes and the body's outputs.
const MOTIONS: [(&str, &str); 6] = [
    ("surge", "x"),
    ("sway", "y"),
    ("heave", "z"),
    ("roll", "roll"),
    ("pitch", "pitch"),
    ("yaw", "yaw"),
];

/// A mooring's lines as a fidelity study sees them.
pub(super) struct MooringLines {
    body: String,
    /// Each line's name and its sections as the scene writes them.
    lines: Vec<(String, Layout)>,
}

impl MooringLines {
    /// The scene's `[mooring]` read; the error names the key.
    pub(super) fn of(table: &Table) -> Result<MooringLines, String> {
        let mooring = Mooring::parse(table.get("mooring").ok_or("no `[mooring]`")?)?;
        let lines = mooring.line_layouts();
        Ok(MooringLines {
            body: mooring.name,
            lines,
        })
    }

    /// The lines a plan's section name reaches, with the section's name.
    fn reached<'a>(&'a self, name: &'a str) -> impl Iterator<Item = (&'a str, &'a str)> + 'a {
        let (line, section) = match name.split_once('.') {
            Some((line, section)) => (Some(line), section),
            None => (None, name),
        };
        (self.lines.iter())
            .filter(move |(l, layout)| {
                line.is_none_or(|wanted| wanted == l)
                    && layout.sections.iter().any(|s| s.name == section)
            })
            .map(move |(l, _)| (l.as_str(), section))
    }
}

/// The `[[mooring.lines]]` tables of a scene.
fn line_tables(table: &mut Table) -> Result<&mut Vec<Value>, String> {
    table
        .get_mut("mooring")
        .and_then(Value::as_table_mut)
        .and_then(|m| m.get_mut("lines"))
        .and_then(Value::as_array_mut)
        .ok_or_else(|| "`mooring.lines`: expected a list".to_owned())
}

/// The name of a line's table.
fn name_of(line: &Value) -> Option<&str> {
    line.get("name").and_then(Value::as_str)
}

impl Subject for MooringLines {
    fn sections(&self) -> Vec<SectionName> {
        let mut out = Vec::new();
        for (line, layout) in &self.lines {
            for s in &layout.sections {
                out.push(SectionName::of(format!("{line}.{}", s.name), s));
            }
        }
        // A bare section name: plain where every line writes it alike.
        let mut shared: Vec<SectionName> = Vec::new();
        for (_, layout) in &self.lines {
            for s in &layout.sections {
                match shared.iter_mut().find(|n| n.name == s.name) {
                    Some(n) => n.plain &= n.choice == s.choice && s.plain,
                    None => shared.push(SectionName::of(s.name.clone(), s)),
                }
            }
        }
        out.extend(shared);
        out
    }

    fn quantities(&self) -> Vec<String> {
        let tensions = self.lines.iter().map(|(l, _)| format!("{l}_tension"));
        let motions = MOTIONS.iter().map(|(m, _)| format!("{}_{m}", self.body));
        tensions.chain(motions).collect()
    }

    fn default_judged(&self) -> Vec<String> {
        self.lines
            .iter()
            .map(|(l, _)| format!("{l}_tension"))
            .collect()
    }

    fn prepare(&self, table: &mut Table) {
        if let Ok(lines) = line_tables(table) {
            for line in lines.iter_mut().filter_map(Value::as_table_mut) {
                line.remove("reference");
            }
        }
    }

    fn run_table(
        &self,
        table: &Table,
        combination: Option<&[(String, Choice)]>,
    ) -> Result<(Table, Reader), String> {
        let mut table = table.clone();
        let lines = line_tables(&mut table)?;
        match combination {
            // Every line whole: one section at the model's mesh.
            None => {
                for line in lines.iter_mut().filter_map(Value::as_table_mut) {
                    line.insert("sections".into(), Value::Array(Vec::new()));
                }
            }
            Some(combination) => {
                for (name, choice) in combination {
                    for (line, section) in self.reached(name) {
                        write_line_choice(lines, line, section, choice)?;
                    }
                }
            }
        }
        let mooring = Mooring::parse(table.get("mooring").ok_or("no `[mooring]`")?)?;
        let tops = (mooring.line_layouts().into_iter())
            .map(|(_, layout)| {
                let top = layout.sections.last().ok_or("a line without sections")?;
                Ok(format!("{}.end_tension", top.unit))
            })
            .collect::<Result<Vec<String>, String>>()?;
        let motions = MOTIONS.iter().map(|(_, o)| format!("{}.{o}", self.body));
        let signals: Vec<String> = tops.into_iter().chain(motions).collect();
        let mut output = Table::new();
        let list = signals.iter().cloned().map(Value::String).collect();
        output.insert("signals".into(), Value::Array(list));
        table.insert("output".into(), Value::Table(output));
        let reader: Reader = Box::new(move |recorder| {
            (signals.iter())
                .map(|s| {
                    recorder
                        .column(s)
                        .map(<[f64]>::to_vec)
                        .ok_or(format!("the run recorded no `{s}`"))
                })
                .collect()
        });
        Ok((table, reader))
    }

    fn labels(&self, combination: Option<&[(String, Choice)]>) -> Vec<(String, String)> {
        let Some(combination) = combination else {
            return vec![("every line".into(), "nonlinear".into())];
        };
        let mut out = Vec::new();
        for (line, layout) in &self.lines {
            for s in &layout.sections {
                let chosen = (combination.iter())
                    .find(|(name, _)| {
                        self.reached(name)
                            .any(|r| r == (line.as_str(), s.name.as_str()))
                    })
                    .map(|(_, c)| c.label());
                let label = chosen.unwrap_or_else(|| s.choice.clone());
                out.push((format!("{line}.{}", s.name), label));
            }
        }
        out
    }
}

/// Writes `choice` on section `section` of line `line` among `lines`.
fn write_line_choice(
    lines: &mut [Value],
    line: &str,
    section: &str,
    choice: &Choice,
) -> Result<(), String> {
    let sections = (lines.iter_mut())
        .find(|l| name_of(l) == Some(line))
        .and_then(Value::as_table_mut)
        .and_then(|l| l.get_mut("sections"))
        .and_then(Value::as_array_mut)
        .ok_or(format!("`mooring.lines.{line}.sections`: expected a list"))?;
    let table = (sections.iter_mut())
        .filter_map(Value::as_table_mut)
        .find(|t| t.get("name").and_then(Value::as_str) == Some(section))
        .ok_or(format!("no section `{line}.{section}`"))?;
    Ok(write_choice(
        table,
        &choice.fidelity,
        choice.elements,
        choice.substeps,
    )?)
}
