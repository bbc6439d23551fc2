//! What the expansion makes of a structure, for the tools that read its runs
//! (`slender fidelity`): each section's unit, where it starts and ends, its
//! fidelity as written, and which of its outputs carry its end forces, its
//! touchdown point and its moments. Read from the same parse as the expansion
//! (no statics are solved), so the names and the outputs of a fidelity are
//! written once, here, and a tool does not derive them again.

use super::sections::{Cut, Fidelity};
use super::spec::Spec;
use toml::{Table, Value};

/// A structure as its runs show it.
#[derive(Clone, Debug)]
pub struct Layout {
    /// `structure.name`: the prefix of its units' names.
    pub name: String,
    /// Its sections, from the structure's start.
    pub sections: Vec<SectionLayout>,
    /// The model has seabed contact (a touchdown point, a sag bend).
    pub seabed: bool,
    /// The model has a stinger (an overbend).
    pub stinger: bool,
    /// The model is planar (x, z): its cuts' forces are read from stations.
    pub planar: bool,
}

/// One section as its runs show it.
#[derive(Clone, Debug)]
pub struct SectionLayout {
    /// The section's name (`[[structure.sections]] name`).
    pub name: String,
    /// The unit the expansion writes for it.
    pub unit: String,
    /// Arc length of its start (m).
    pub from: f64,
    /// Arc length of its end (m).
    pub to: f64,
    /// Its fidelity as the command line writes a choice: the fidelity's name
    /// (`fmu` for an external FMU), its count after `:` (elements; modes of a
    /// `reduced` section, order of a `span` fit) and its sub-steps after `/`.
    pub choice: String,
    /// Written as a bare fidelity word: no count, sub-steps or options.
    pub plain: bool,
    /// The model's own element count over the section: what a fidelity that
    /// [`takes_model_mesh`] is given without a count.
    pub mesh: usize,
    /// Which of its unit's outputs carry what a study measures.
    pub outputs: SectionOutputs,
}

/// Where a section's unit reports what a study measures (output names
/// without the unit's).
#[derive(Clone, Debug)]
pub struct SectionOutputs {
    /// The force's components (x, z; x, y, z in 3D; N) at its start.
    pub start_force: Vec<String>,
    /// The same at its end; none where that force is a coupled input (a
    /// cable's top, a chord's loaded end), so the force at the cut above is
    /// read from the section above.
    pub end_force: Option<Vec<String>>,
    /// Its touchdown point (m of arc from its start), interpolated where the
    /// seabed gap crosses zero; none where the model has no seabed contact.
    pub touchdown: Option<String>,
    /// Its largest sag-bend moment (N m).
    pub sagbend_moment: Option<String>,
    /// Its largest overbend moment (N m), on the stinger.
    pub overbend_moment: Option<String>,
    /// It takes the model's `stations` (internal forces `force_<k>` at arc
    /// lengths the model names): a native `nonlinear` unit.
    pub stations: bool,
}

impl SectionOutputs {
    /// Every output named: the end forces, then the touchdown point and the
    /// moments where the section has them.
    pub fn names(&self) -> Vec<&String> {
        let mut names: Vec<&String> = self.start_force.iter().collect();
        names.extend(self.end_force.iter().flatten());
        let optional = [&self.touchdown, &self.sagbend_moment, &self.overbend_moment];
        names.extend(optional.into_iter().flatten());
        names
    }
}

/// The name of the unit the expansion writes for section `section` of
/// structure `structure`.
pub fn unit_name(structure: &str, section: &str) -> String {
    format!("{structure}_{section}")
}

/// The name of the structure's monolithic twin (`structure.reference`).
pub fn reference_name(structure: &str) -> String {
    format!("{structure}_reference")
}

/// The layout of the scene's `[structure]`; None when it has none. The error
/// names the key, as the expansion's does.
pub fn layout(scene: &Table) -> Result<Option<Layout>, super::StructureError> {
    let Some(structure) = scene.get("structure") else {
        return Ok(None);
    };
    let structure = structure
        .as_table()
        .ok_or("`structure`: expected a table")?;
    if super::line3d::is_3d(structure) {
        return Ok(super::line3d::layout(structure).map(Some)?);
    }
    let spec = Spec::parse(structure)?;
    let name = &spec.name;
    let seabed = spec.model.contact.is_some();
    let stinger = spec.model.stinger.is_some();
    let sections = (spec.sections.iter())
        .map(|cut| SectionLayout {
            name: cut.name.clone(),
            unit: unit_name(name, &cut.name),
            from: cut.from,
            to: cut.to,
            choice: choice_of(cut),
            plain: cut.elements.is_none()
                && cut.substeps.is_none()
                && cut.options.is_none()
                && cut.fmu.is_none(),
            mesh: (spec.segments.iter())
                .filter_map(|s| s.elements_over(cut.from, cut.to))
                .sum::<f64>() as usize,
            outputs: (cut.fidelity.model()).outputs(
                cut.fmu.is_some(),
                seabed,
                stinger,
                spec.static_start,
            ),
        })
        .collect();
    Ok(Some(Layout {
        name: name.clone(),
        sections,
        seabed,
        stinger,
        planar: true,
    }))
}

/// A section's fidelity in the command line's form (`nonlinear:16/4`).
pub(super) fn choice_of(cut: &Cut) -> String {
    let word = if cut.fmu.is_some() {
        "fmu"
    } else {
        cut.fidelity.name()
    };
    let count = match cut.fidelity.count_key() {
        "elements" => cut.elements,
        key => (cut.options.as_ref())
            .and_then(|o| o.get(key))
            .and_then(Value::as_integer)
            .and_then(|n| usize::try_from(n).ok()),
    };
    let mut choice = match count {
        Some(n) => format!("{word}:{n}"),
        None => word.to_owned(),
    };
    let training = (cut.options.as_ref()).and_then(|o| o.get("training"));
    if let Some(t) = training.and_then(|t| t.as_float().or(t.as_integer().map(|i| i as f64))) {
        choice += &format!("@{t}");
    }
    if let Some(n) = cut.substeps {
        choice += &format!("/{n}");
    }
    choice
}

/// Whether the fidelity `word` without a count takes the model's own mesh
/// over the section (`SectionLayout::mesh` elements), so that `nonlinear`
/// and `nonlinear:N` with N that mesh are the same choice.
pub fn takes_model_mesh(word: &str) -> bool {
    Fidelity::parse("fidelity", word)
        .is_ok_and(|f| f.count_key() == "elements" && f.model().is_section_unit())
}

/// Writes a choice onto the section table `section` of `[[structure.sections]]`
/// in place of its own: the fidelity `word` (checked), its count (elements; a
/// `reduced` section's modes, a `span`'s order) and its sub-steps.
pub fn write_choice(
    section: &mut Table,
    word: &str,
    count: Option<usize>,
    substeps: Option<u32>,
) -> Result<(), super::StructureError> {
    let fidelity = Fidelity::parse("fidelity", word)?;
    section.remove("elements");
    section.remove("substeps");
    match (fidelity.count_key(), count) {
        (_, None) => {
            section.insert("fidelity".into(), Value::String(word.into()));
        }
        ("elements", Some(n)) => {
            section.insert("fidelity".into(), Value::String(word.into()));
            section.insert("elements".into(), Value::Integer(n as i64));
        }
        (key, Some(n)) => {
            let mut table = Table::new();
            table.insert("kind".into(), Value::String(word.into()));
            table.insert(key.into(), Value::Integer(n as i64));
            section.insert("fidelity".into(), Value::Table(table));
        }
    }
    if let Some(n) = substeps {
        section.insert("substeps".into(), Value::Integer(i64::from(n)));
    }
    Ok(())
}

/// Writes a training window (s) onto a section written as `reduced` by
/// [`write_choice`] (`reduced:6@5` on the command line): its forces sampled
/// after `training` seconds.
pub fn write_training(section: &mut Table, training: f64) -> Result<(), super::StructureError> {
    let mut table = match section.get("fidelity") {
        Some(Value::String(w)) if w == "reduced" => Table::new(),
        Some(Value::Table(t)) if t.get("kind").and_then(Value::as_str) == Some("reduced") => {
            t.clone()
        }
        _ => {
            return Err(format!(
                "`@{training}`: a training window is for a `reduced` section (its forces sampled after it, e.g. reduced:6@5)"
            )
            .into());
        }
    };
    table.insert("kind".into(), Value::String("reduced".into()));
    table.insert("training".into(), Value::Float(training));
    section.insert("fidelity".into(), Value::Table(table));
    Ok(())
}

impl Fidelity {
    /// The key a count after `:` sets: `elements`, or a `reduced` section's
    /// `modes` and a `span` fit's `order`.
    pub(super) fn count_key(self) -> &'static str {
        self.model().count_key()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A three-section structure whose sections are written as `sections`.
    fn scene(sections: &str) -> Table {
        format!(
            "[structure]\nname = \"pipe\"\nmodel = {{ segments = [{{ length = 30.0, elements = 6, axial_stiffness = 1e9, bending_stiffness = 1e5, mass_per_length = 100.0 }}], contact = {{ method = {{ kind = \"penalty\", penalty = 1e6 }}, surface = {{ shape = {{ kind = \"flat\", height = -10.0 }} }} }} }}\n{sections}"
        )
        .parse()
        .unwrap()
    }

    #[test]
    fn a_choice_written_onto_a_section_reads_back_the_same() {
        for (word, count, substeps, label) in [
            ("nonlinear", Some(16), Some(4), "nonlinear:16/4"),
            ("reduced", Some(4), None, "reduced:4"),
            ("span", Some(24), Some(2), "span:24/2"),
            ("cable", None, None, "cable"),
        ] {
            let mut table = scene(
                "[[structure.sections]]\nname = \"a\"\nto = 10.0\nelements = 3\nsubsteps = 5\n[[structure.sections]]\nname = \"b\"\n",
            );
            let sections = table["structure"]["sections"].as_array_mut().unwrap();
            let a = sections[0].as_table_mut().unwrap();
            write_choice(a, word, count, substeps).unwrap();
            let layout = layout(&table).unwrap().unwrap();
            let a = &layout.sections[0];
            assert_eq!(a.choice, label);
            assert_eq!(a.plain, label == word, "{label}");
            assert_eq!((a.unit.as_str(), a.from, a.to), ("pipe_a", 0.0, 10.0));
        }
        let mut table = scene(
            "[[structure.sections]]\nname = \"a\"\nto = 10.0\n[[structure.sections]]\nname = \"b\"\n",
        );
        let sections = table["structure"]["sections"].as_array_mut().unwrap();
        let a = sections[0].as_table_mut().unwrap();
        write_choice(a, "reduced", Some(6), None).unwrap();
        write_training(a, 5.0).unwrap();
        assert_eq!(
            layout(&table).unwrap().unwrap().sections[0].choice,
            "reduced:6@5"
        );
        let mut section = Table::new();
        write_choice(&mut section, "cable", None, None).unwrap();
        let e = write_training(&mut section, 5.0).unwrap_err();
        assert!(e.message.contains("for a `reduced` section"), "{e}");
        let mut section = Table::new();
        let e = write_choice(&mut section, "coarse", None, None).unwrap_err();
        assert!(
            e.message.contains("expected one of nonlinear, linear"),
            "{e}"
        );
    }

    #[test]
    fn an_fmu_section_reads_as_its_ports_without_stations() {
        let table = scene(
            "[[structure.sections]]\nname = \"a\"\nto = 10.0\nfidelity = { kind = \"fmu\", file = \"a.fmu\", ports = \"linear\" }\n[[structure.sections]]\nname = \"b\"\n",
        );
        let layout = layout(&table).unwrap().unwrap();
        let (a, b) = (&layout.sections[0], &layout.sections[1]);
        assert_eq!((a.choice.as_str(), a.plain), ("fmu", false));
        assert_eq!(a.outputs.touchdown.as_deref(), Some("touchdown_arc"));
        assert!(!a.outputs.stations && b.outputs.stations);
        assert!(layout.seabed && !layout.stinger);
        assert_eq!(reference_name("pipe"), "pipe_reference");
    }
}
