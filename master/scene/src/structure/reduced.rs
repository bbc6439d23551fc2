//! The `reduced` fidelity of a section. Started from the structure's static
//! equilibrium, the section's `nonlinear` unit reduced about that state
//! (`reduced_modes`: modes of its tangent there, attachment and constraint
//! vectors, the forces through its elements); from the stress-free state, the
//! `reduced` unit of seed 002, loaded at its cuts (the generator orients them
//! so).

use super::Built;
use super::layout::SectionOutputs;
use super::model::{CutNeeds, Place, SectionAt, SectionModel, outputs_of};
use super::nonlinear::{section_outputs, section_unit};
use super::sections::Cut;
use toml::{Table, Value};

/// The `reduced` fidelity.
pub(super) struct Reduced;

/// The keys of `{ kind = "reduced", ... }`: the `reduced` unit's basis, and
/// about the static state the sampling of its forces.
const KEYS: [&str; 8] = [
    "kind",
    "elements",
    "modes",
    "derivatives",
    "attachments",
    "integrator",
    "training",
    "tolerance",
];

impl SectionModel for Reduced {
    fn name(&self) -> &'static str {
        "reduced"
    }
    fn option_keys(&self) -> &'static [&'static str] {
        &KEYS
    }
    fn count_key(&self) -> &'static str {
        "modes"
    }
    /// Sampled forces cannot hold a stinger's rollers.
    fn refuse(&self, built: &Built, cut: &Cut) -> Result<(), String> {
        built.refuse_sampling_on_stinger(cut)
    }
    fn contact_state_kept(&self) -> Option<&'static str> {
        Some(
            "a reduced section follows poorly: its basis holds the nodes in contact where they lay",
        )
    }
    /// About the stress-free state (seed 002's unit) it is loaded at both its
    /// cuts; about the equilibrium it is coupled as a `nonlinear` section.
    fn cut_needs(&self, place: Place) -> CutNeeds {
        match place.static_start {
            true => CutNeeds::default(),
            false => CutNeeds {
                below: Some(false),
                above: Some(true),
                all: None,
            },
        }
    }
    /// About the equilibrium, the `nonlinear` unit's outputs; about the
    /// stress-free state, its end forces.
    fn outputs(
        &self,
        fmu: bool,
        seabed: bool,
        stinger: bool,
        static_start: bool,
    ) -> SectionOutputs {
        match static_start {
            true => section_outputs(fmu, seabed, stinger),
            false => outputs_of(["start", "end"], false, None, false, (seabed, stinger)),
        }
    }
    fn unit(&self, at: &SectionAt) -> Result<Table, String> {
        let (built, cut) = (at.built, at.cut());
        if built.statics.is_some() {
            return reduced_unit(built.section_unit(cut, at.ends)?, cut, true);
        }
        let section = section_unit(&built.name, &built.model, &built.segments, cut, at.ends)?;
        reduced_unit(section, cut, false)
    }
}

/// Modes in the basis when the scene gives none.
const DEFAULT_MODES: i64 = 6;

/// The keys a section reduced about its static state takes besides `kind`
/// and `elements` (seed 002's `derivatives`, `attachments` and `integrator`
/// belong to the reduction about the stress-free state): its modes, and the
/// training window (s) and tolerance of its sampled forces.
const STATIC_KEYS: [&str; 3] = ["modes", "training", "tolerance"];

/// The keys only a section reduced about its static state takes.
const SAMPLING_KEYS: [&str; 2] = ["training", "tolerance"];

/// The reduced unit of one section from its `nonlinear` unit: `modes`
/// (default 6) and, about the stress-free state, `derivatives` (default
/// "taylor": the modes' derivatives follow the modal coordinates, so the
/// critical step is the modes' own) from the fidelity, the section's
/// parameters as its `section`.
pub(super) fn reduced_unit(
    mut section: Table,
    cut: &Cut,
    static_start: bool,
) -> Result<Table, String> {
    let key = format!("structure.sections.{}.fidelity", cut.name);
    let options = cut.options.clone().unwrap_or_default();
    if static_start {
        return about_static_state(section, &key, &options);
    }
    if let Some(other) = options.keys().find(|k| SAMPLING_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "`{key}.{other}`: sampled forces are for a section reduced about the structure's static equilibrium (a `[structure]` with a static start); seed 002's reduced section samples none"
        ));
    }
    let parameters = section
        .remove("parameters")
        .ok_or(format!("`{key}`: the section has no parameters"))?;
    let mut reduced = options;
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

/// The section's `nonlinear` unit with `reduced_modes`: reduced about the
/// equilibrium it starts from.
fn about_static_state(mut section: Table, key: &str, options: &Table) -> Result<Table, String> {
    if let Some(other) = options.keys().find(|k| !STATIC_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "`{key}.{other}`: a section reduced about the structure's static equilibrium takes `modes`, `training` and `tolerance` only (its basis: modes of the tangent there with attachment and constraint vectors, stepped by the section's own integrator; its forces sampled after `training` seconds)"
        ));
    }
    let modes = options
        .get("modes")
        .cloned()
        .unwrap_or(Value::Integer(DEFAULT_MODES));
    let parameters = section
        .get_mut("parameters")
        .and_then(Value::as_table_mut)
        .ok_or(format!("`{key}`: the section has no parameters"))?;
    parameters.insert("reduced_modes".into(), modes);
    if let Some(training) = options.get("training") {
        let mut sampling = Table::new();
        sampling.insert("training".into(), training.clone());
        if let Some(tolerance) = options.get("tolerance") {
            sampling.insert("tolerance".into(), tolerance.clone());
        }
        parameters.insert("reduced_sampling".into(), Value::Table(sampling));
    } else if options.contains_key("tolerance") {
        return Err(format!(
            "`{key}.tolerance`: with `training` (the seconds the section runs on every element before its forces are sampled)"
        ));
    }
    Ok(section)
}
