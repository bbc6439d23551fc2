//! What a fidelity study varies and measures ([`Subject`]): a `[structure]`'s
//! sections, or a `[mooring]`'s lines' sections (`super::mooring`); the
//! study itself does not know which.

use super::structure_runs::run_table;
use super::{Choice, Structure, quantities, rows};
use slender_scene::structure::SectionLayout;
use toml::{Table, Value};

/// Reads a run's recording as the quantities' series, in their order.
pub(super) type Reader =
    Box<dyn Fn(&crate::record::Recorder) -> Result<Vec<Vec<f64>>, String> + Send>;

/// A section a plan may name, its choice as the scene writes it, and
/// whether that is a bare fidelity word.
pub(super) struct SectionName {
    pub(super) name: String,
    pub(super) choice: String,
    pub(super) plain: bool,
    /// The model's own element count over the section.
    pub(super) mesh: usize,
}

impl SectionName {
    /// A section of a layout under `name`.
    pub(super) fn of(name: String, section: &SectionLayout) -> SectionName {
        SectionName {
            name,
            choice: section.choice.clone(),
            plain: section.plain,
            mesh: section.mesh,
        }
    }
}

/// What a study varies and measures: a `[structure]`'s sections, or a
/// `[mooring]`'s lines' sections.
pub(super) trait Subject: Sync {
    /// The sections a plan may name.
    fn sections(&self) -> Vec<SectionName>;
    /// The quantities' names.
    fn quantities(&self) -> Vec<String>;
    /// The quantities judged when the plan names none.
    fn default_judged(&self) -> Vec<String> {
        self.quantities()
    }
    /// Takes out of the scene what the runs must not carry (twins).
    fn prepare(&self, table: &mut Table);
    /// The scene of one run (the reference for `None`) and how to read its
    /// quantities.
    fn run_table(
        &self,
        table: &Table,
        combination: Option<&[(String, Choice)]>,
    ) -> Result<(Table, Reader), String>;
    /// Every section's choice in a run: the combination's, else the scene's.
    fn labels(&self, combination: Option<&[(String, Choice)]>) -> Vec<(String, String)>;
}

impl Subject for Structure {
    fn sections(&self) -> Vec<SectionName> {
        (self.layout.sections.iter())
            .map(|s| SectionName::of(s.name.clone(), s))
            .collect()
    }

    fn quantities(&self) -> Vec<String> {
        quantities::names(&self.features)
    }

    fn prepare(&self, table: &mut Table) {
        if let Some(s) = table.get_mut("structure").and_then(Value::as_table_mut) {
            s.remove("reference");
        }
    }

    fn run_table(
        &self,
        table: &Table,
        combination: Option<&[(String, Choice)]>,
    ) -> Result<(Table, Reader), String> {
        let (table, units) = run_table(table, self, combination)?;
        let features = self.features.clone();
        let names = quantities::names(&features);
        let reader: Reader = Box::new(move |recorder| {
            (names.iter())
                .map(|n| quantities::series(n, &units, &features, recorder))
                .collect()
        });
        Ok((table, reader))
    }

    fn labels(&self, combination: Option<&[(String, Choice)]>) -> Vec<(String, String)> {
        rows::combination_of(self, combination)
    }
}
