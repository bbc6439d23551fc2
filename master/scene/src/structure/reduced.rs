//! The `reduced` fidelity of a section: the section's `nonlinear` parameters
//! reduced about their stress-free state by the `reduced` unit (seed 002), loaded
//! at its cuts (the generator orients them so).

use super::sections::Cut;
use toml::{Table, Value};

/// Modes in the basis when the scene gives none.
const DEFAULT_MODES: i64 = 6;

/// The `reduced` unit of one section from its `nonlinear` unit: `modes` (default
/// 6) and `derivatives` (default "taylor": the modes' derivatives follow the
/// modal coordinates, so the critical step is the modes' own) from the
/// fidelity, the section's parameters as its `section`.
pub(super) fn reduced_unit(
    mut section: Table,
    cut: &Cut,
    static_start: bool,
) -> Result<Table, String> {
    let key = format!("structure.sections.{}.fidelity", cut.name);
    if static_start {
        return Err(format!(
            "`{key}` = \"reduced\": a reduced section is expanded about its stress-free state, so the structure cannot start from its static equilibrium; leave out `structure.model.static_start`"
        ));
    }
    let parameters = section
        .remove("parameters")
        .ok_or(format!("`{key}`: the section has no parameters"))?;
    let mut reduced = cut.options.clone().unwrap_or_default();
    reduced
        .entry("modes")
        .or_insert(Value::Integer(DEFAULT_MODES));
    reduced
        .entry("derivatives")
        .or_insert(Value::String("taylor".into()));
    reduced.insert("section".into(), parameters);
    section.insert("kind".into(), Value::String("reduced".into()));
    section.insert("parameters".into(), Value::Table(reduced));
    Ok(section)
}
