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
use super::spec::typed;
use super::unit::{Parameters, SectionUnit};
use serde::Deserialize;
use slender_units::nonlinear::Sampling;
use slender_units::reduced::unit::{Derivatives, ReducedParams, Stepping};

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
const DEFAULT_MODES: usize = 6;

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
    let written = cut.options.clone().unwrap_or_default();
    let refused = match static_start {
        true => written.keys().find(|k| !STATIC_KEYS.contains(&k.as_str())),
        false => written.keys().find(|k| SAMPLING_KEYS.contains(&k.as_str())),
    };
    if let Some(other) = refused {
        return Err(match static_start {
            true => format!(
                "`{key}.{other}`: a section reduced about the structure's static equilibrium takes `modes`, `training` and `tolerance` only (its basis: modes of the tangent there with attachment and constraint vectors, stepped by the section's own integrator; its forces sampled after `training` seconds)"
            ),
            false => format!(
                "`{key}.{other}`: sampled forces are for a section reduced about the structure's static equilibrium (a `[structure]` with a static start); seed 002's reduced section samples none"
            ),
        });
    }
    let options: ReducedOptions = typed(&key, &written)?;
    let modes = options.modes.unwrap_or(DEFAULT_MODES);
    if static_start {
        let parameters = section
            .nonlinear_mut()
            .ok_or(format!("`{key}`: the section is not a `nonlinear` unit"))?;
        parameters.reduced_modes = Some(modes);
        parameters.reduced_sampling = options.sampling(&key)?;
        return Ok(section);
    }
    let reduced = ReducedParams {
        section: section.section_parameters(&key)?.clone(),
        modes,
        derivatives: options.derivatives.unwrap_or(Derivatives::Taylor),
        integrator: options.integrator.unwrap_or_default(),
        attachments: options.attachments.unwrap_or(true),
    };
    section.parameters = Parameters::Reduced(Box::new(reduced));
    Ok(section)
}

/// A `reduced` fidelity's own keys as the scene writes them (`kind` and
/// `elements` are read by the sections), checked by serde at the section's key.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ReducedOptions {
    /// Modes in the basis (default 6).
    modes: Option<usize>,
    /// Seed 002's modal derivatives (default "taylor").
    derivatives: Option<Derivatives>,
    /// Seed 002's integrator of the modal coordinates.
    integrator: Option<Stepping>,
    /// Seed 002's attachment vectors (default true).
    attachments: Option<bool>,
    /// About the equilibrium: the seconds the section runs on every element
    /// before its forces are sampled.
    training: Option<f64>,
    /// About the equilibrium: the sampled forces' relative residual.
    tolerance: Option<f64>,
}

impl ReducedOptions {
    /// The sampling of the forces after `training` seconds, if asked for.
    fn sampling(&self, key: &str) -> Result<Option<Sampling>, String> {
        match (self.training, self.tolerance) {
            (Some(training), tolerance) => Ok(Some(Sampling {
                training,
                tolerance: tolerance.unwrap_or(Sampling::DEFAULT_TOLERANCE),
            })),
            (None, Some(_)) => Err(format!(
                "`{key}.tolerance`: with `training` (the seconds the section runs on every element before its forces are sampled)"
            )),
            (None, None) => Ok(None),
        }
    }
}
