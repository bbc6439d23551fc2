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
use super::unit::{Parameters, SectionUnit};
use slender_units::nonlinear::NonlinearParams;
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
    fn unit(&self, at: &SectionAt) -> Result<SectionUnit, String> {
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
    mut section: SectionUnit,
    cut: &Cut,
    static_start: bool,
) -> Result<SectionUnit, String> {
    let key = format!("structure.sections.{}.fidelity", cut.name);
    let options = cut.options.clone().unwrap_or_default();
    if static_start {
        let parameters = section
            .nonlinear_mut()
            .ok_or(format!("`{key}`: the section is not a `nonlinear` unit"))?;
        about_static_state(parameters, &key, &options)?;
        return Ok(section);
    }
    if let Some(other) = options.keys().find(|k| SAMPLING_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "`{key}.{other}`: sampled forces are for a section reduced about the structure's static equilibrium (a `[structure]` with a static start); seed 002's reduced section samples none"
        ));
    }
    let parameters = Value::try_from(section.section_parameters(&key)?)
        .map_err(|e| format!("`{key}`: the section's parameters as TOML: {e}"))?;
    let mut reduced = options;
    reduced
        .entry("modes")
        .or_insert(Value::Integer(DEFAULT_MODES));
    reduced
        .entry("derivatives")
        .or_insert(Value::String("taylor".into()));
    reduced.insert("section".into(), parameters);
    section.kind = "reduced";
    section.parameters = Parameters::Table(reduced);
    Ok(section)
}

/// The section's `nonlinear` unit's `parameters` with `reduced_modes`
/// (and `reduced_sampling` after `training`): reduced about the equilibrium
/// it starts from.
fn about_static_state(
    parameters: &mut NonlinearParams,
    key: &str,
    options: &Table,
) -> Result<(), String> {
    if let Some(other) = options.keys().find(|k| !STATIC_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "`{key}.{other}`: a section reduced about the structure's static equilibrium takes `modes`, `training` and `tolerance` only (its basis: modes of the tangent there with attachment and constraint vectors, stepped by the section's own integrator; its forces sampled after `training` seconds)"
        ));
    }
    let modes = match options.get("modes") {
        None => DEFAULT_MODES as usize,
        Some(v) => v
            .as_integer()
            .and_then(|n| usize::try_from(n).ok())
            .ok_or(format!(
                "`{key}.modes` = {v}: expected a whole number of modes"
            ))?,
    };
    parameters.reduced_modes = Some(modes);
    if let Some(training) = options.get("training") {
        let mut sampling = Table::new();
        sampling.insert("training".into(), training.clone());
        if let Some(tolerance) = options.get("tolerance") {
            sampling.insert("tolerance".into(), tolerance.clone());
        }
        let sampling = Value::Table(sampling)
            .try_into()
            .map_err(|e| format!("`{key}`: `training` and `tolerance`: {e}"))?;
        parameters.reduced_sampling = Some(sampling);
    } else if options.contains_key("tolerance") {
        return Err(format!(
            "`{key}.tolerance`: with `training` (the seconds the section runs on every element before its forces are sampled)"
        ));
    }
    Ok(())
}
