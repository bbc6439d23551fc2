//! The unit kinds a scene can name, and how each is built from its parameters:
//! the registry on its own (below the scene crate), so an exported FMU, which
//! builds its one unit from a kind and a parameter table, links the units and
//! this registry but no scene, coupling, study or command-line code.
pub mod exported;
pub mod fields;
pub mod reference;
pub mod words;

use crate::fields::field_names;
use serde::de::DeserializeOwned;
use slender_fmi::import::{FmuParams, FmuUnit, LoadError};
use slender_units::beam::touchdown::{TouchdownEstimate, TouchdownParams};
use slender_units::beam::{Beam, BeamParams};
use slender_units::benchmark::algebraic_loop::{
    LinearPair, LinearPairParams, SphereClosure, SphereParams,
};
use slender_units::benchmark::oscillator::{Oscillator, OscillatorParams};
use slender_units::body::{Body, BodyParams};
use slender_units::cable::{Cable, CableParams, Effects};
use slender_units::chord::{Chord, ChordParams};
use slender_units::line3d::catenary_section::CatenarySection;
use slender_units::line3d::{Line3d, Line3dParams};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::reduced::unit::{ReducedParams, ReducedUnit};
use slender_units::signal::artefact::{Artefact, ArtefactParams};
use slender_units::signal::characteristic_load::{CharacteristicLoad, CharacteristicLoadParams};
use slender_units::signal::compensation::{Compensation, CompensationParams};
use slender_units::signal::source::{Signal, SignalParams};
use slender_units::span::coupling::{SpanCoupling, SpanCouplingParams};
use slender_units::span::unit::{SpanParams, SpanUnit};
use slender_units::static_section::{StaticSection, StaticSectionParams};
use slender_units::{Unit, UnitError};
use std::any::Any;
use std::path::Path;

/// What a builder needs besides the parameter table.
pub struct BuildContext<'a> {
    /// The effects the scene asks for (checked against the kind's list).
    pub effects: &'a [String],
    /// Folder that relative file names in parameters are resolved against (the
    /// scene file's folder).
    pub base_dir: &'a Path,
}

/// Builds a unit from its parameters and the context.
type Builder = fn(Given, &BuildContext) -> Result<Box<dyn Unit>, BuildError>;

/// A unit's parameters as its builder receives them: the table a scene (or
/// an FMU's configuration) gives, read into the kind's own type by serde, or
/// that type already made (the units a `[structure]` writes out), taken as
/// it is, so nothing is written as TOML and read back on a run.
pub enum Given {
    /// The parameters as a TOML table.
    Table(toml::Table),
    /// The kind's own parameter type (`NonlinearParams`, ...), boxed.
    Typed(Box<dyn Any + Send>),
}

/// Why a unit could not be built from its scene section.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// An effect asked of a kind that switches none.
    #[error("effect `{effect}`: kind `{kind}` has no switchable effects")]
    NoEffects {
        /// The effect as the scene names it.
        effect: String,
        /// The unit's kind.
        kind: &'static str,
    },
    /// An effect the kind does not offer.
    #[error("effect `{effect}`: kind `{kind}` offers {offered}")]
    UnknownEffect {
        /// The effect as the scene names it.
        effect: String,
        /// The unit's kind.
        kind: &'static str,
        /// The effects it offers, listed.
        offered: String,
    },
    /// The parameter table does not fit the kind's parameters (serde's message:
    /// the unknown or missing key, or the wrong type).
    #[error("{0}")]
    Parameters(String),
    /// The unit refused a parameter value.
    #[error(transparent)]
    Unit(#[from] UnitError),
    /// An external FMU that could not be loaded.
    #[error(transparent)]
    Fmu(#[from] LoadError),
    /// No kind of this name (an FMU's configuration names one).
    #[error("unknown unit kind `{0}`")]
    UnknownKind(String),
}

/// A unit kind: its scene name, what it is, and the effects it can switch.
pub struct Kind {
    /// Its name in scenes (`kind = "cable"`).
    pub name: &'static str,
    /// The top-level keys of its parameter table, from the parameter struct.
    pub parameters: fn() -> &'static [&'static str],
    /// What it models, in a line (`slender kinds`).
    pub summary: &'static str,
    /// The effects a scene may switch on (`effects = [...]`).
    pub effects: &'static [&'static str],
    build: Builder,
}

/// Every kind, in the order `slender kinds` lists them.
pub const KINDS: &[Kind] = &[
    Kind {
        name: "cable",
        parameters: field_names::<CableParams>,
        summary: "2D bar-element cable, static equilibrium + linear dynamics with exact drag; full line or a section",
        effects: &Effects::NAMES,
        build: |p, context| {
            let effects = Effects::from_names(context.effects)?;
            Ok(Box::new(Cable::new(parameters(p)?, effects)?))
        },
    },
    Kind {
        name: "beam",
        parameters: field_names::<BeamParams>,
        summary: "Euler-Bernoulli pipe section: Hermite elements, HHT-alpha, two conditions per end, contact with a surface",
        effects: &[],
        build: |p, _| Ok(Box::new(Beam::new(parameters(p)?)?)),
    },
    Kind {
        name: "nonlinear",
        parameters: field_names::<NonlinearParams>,
        summary: "geometrically nonlinear planar section: co-rotational or seed 002 beam-columns (EA, EI), weight, drag, added mass, contact; static Newton, HHT-alpha, energy-conserving or central differences",
        effects: &[],
        build: |p, _| Ok(Box::new(NonlinearSection::new(parameters(p)?)?)),
    },
    Kind {
        name: "line3d",
        parameters: field_names::<Line3dParams>,
        summary: "a slender line in 3D (mooring line, riser): rotation-free nodes, EA and EI (no torsion), Morison drag and added mass, current by depth and heading, Airy waves, sloped seabed with axial and lateral friction; static Newton from the elastic catenary, HHT-alpha",
        effects: &[],
        build: |p, _| Ok(Box::new(Line3d::new(parameters(p)?)?)),
    },
    Kind {
        name: "catenary3d",
        parameters: field_names::<Line3dParams>,
        summary: "a 3D line as its elastic catenary from an anchor (flat seabed at the anchor or none): quasi-static, the end force each step from the closed form (a 3D structure's `static` section)",
        effects: &[],
        build: |p, _| Ok(Box::new(CatenarySection::new(parameters(p)?)?)),
    },
    Kind {
        name: "body",
        parameters: field_names::<BodyParams>,
        summary: "a rigid body in 6 DOF (a floater): quaternion rotations, mass and inertia, added mass, linear hydrostatics, linear and quadratic damping, fairleads whose motion is an output and whose force an input; or a prescribed 6-DOF motion",
        effects: &[],
        build: |p, _| Ok(Box::new(Body::new(parameters(p)?)?)),
    },
    Kind {
        name: "span",
        parameters: field_names::<SpanParams>,
        summary: "seed 004 ch. 5: suspended span from upper rotation to lower deflection as an order-N rational transfer function",
        effects: &[],
        build: |p, _| Ok(Box::new(SpanUnit::new(parameters(p)?)?)),
    },
    Kind {
        name: "span_coupling",
        parameters: field_names::<SpanCouplingParams>,
        summary: "seed 004 ch. 5: suspended span between two sections, the full 4x4 transfer matrix (end motions and loads) as a common-pole rational fit",
        effects: &[],
        build: |p, _| Ok(Box::new(SpanCoupling::new(parameters(p)?)?)),
    },
    Kind {
        name: "touchdown_estimate",
        parameters: field_names::<TouchdownParams>,
        summary: "seed 004 sec. 6.6: touchdown point x_C = -3 y(0) / y'(0) from a section's end values (valid for y > 0, y' < 0)",
        effects: &[],
        build: |p, _| Ok(Box::new(TouchdownEstimate::new(parameters(p)?)?)),
    },
    Kind {
        name: "chord",
        parameters: field_names::<ChordParams>,
        summary: "a section as a small-deflection model (`beam` or the span's transfer matrix) about its chord in the equilibrium, with the frame changes at its cuts (the `beam` and `span` fidelities of a structure's section)",
        effects: &[],
        build: |p, _| Ok(Box::new(Chord::new(parameters(p)?)?)),
    },
    Kind {
        name: "static_section",
        parameters: field_names::<StaticSectionParams>,
        summary: "a section as its linearised static response at its free end: end force, moment and start reaction from constant stiffnesses (the `static` fidelity of a structure's section)",
        effects: &[],
        build: |p, _| Ok(Box::new(StaticSection::new(parameters(p)?)?)),
    },
    Kind {
        name: "characteristic_load",
        parameters: field_names::<CharacteristicLoadParams>,
        summary: "seed 000 top load: static tension + low- and wave-frequency sweeps (source, outputs force_x, force_z)",
        effects: &[],
        build: |p, _| Ok(Box::new(CharacteristicLoad::new(parameters(p)?)?)),
    },
    Kind {
        name: "signal",
        parameters: field_names::<SignalParams>,
        summary: "a prescribed signal (source, output value of a chosen quantity): offset, sines faded in, steps; drives the unit a study measures",
        effects: &[],
        build: |p, _| Ok(Box::new(Signal::new(parameters(p)?)?)),
    },
    Kind {
        name: "artefact",
        parameters: field_names::<ArtefactParams>,
        summary: "control-system artefacts on a signal: scale, bias, noise, delay, first-order lag, signal loss, zero-order hold",
        effects: &[],
        build: |p, _| Ok(Box::new(Artefact::new(parameters(p)?)?)),
    },
    Kind {
        name: "reduced",
        parameters: field_names::<ReducedParams>,
        summary: "a seed 002 section reduced about its stress-free state: modes, derivatives as coordinates (linear) or following them (taylor); loaded ends only",
        effects: &[],
        build: |p, _| Ok(Box::new(ReducedUnit::new(parameters(p)?)?)),
    },
    Kind {
        name: "delay_compensation",
        parameters: field_names::<CompensationParams>,
        summary: "actuator delay compensation: each channel predicted `lead` seconds ahead by a polynomial through its last values",
        effects: &[],
        build: |p, _| Ok(Box::new(Compensation::new(parameters(p)?)?)),
    },
    Kind {
        name: "oscillator",
        parameters: field_names::<OscillatorParams>,
        summary: "mass on a spring-damper to ground, coupled by a spring-damper or a force (B1-B3)",
        effects: &[],
        build: |p, _| Ok(Box::new(Oscillator::new(parameters(p)?)?)),
    },
    Kind {
        name: "fmu",
        parameters: field_names::<FmuParams>,
        summary: "an FMI 2.0 co-simulation FMU (file = \"x.fmu\"): ports from its model description, rollback if it declares FMU state",
        effects: &[],
        build: |p, context| {
            let params: FmuParams = parameters(p)?;
            Ok(Box::new(FmuUnit::load(&params, context.base_dir)?))
        },
    },
    Kind {
        name: "loop_linear_pair",
        parameters: field_names::<LinearPairParams>,
        summary: "B6 unit A: a + b + c = 0 and 2a - 3b + 2c = 9, input c, outputs a, b",
        effects: &[],
        build: |p, _| Ok(Box::new(LinearPair::new(parameters(p)?))),
    },
    Kind {
        name: "loop_sphere",
        parameters: field_names::<SphereParams>,
        summary: "B6 unit B: c from a^2 + b^2 + c^2 = r^2, inputs a, b, output c",
        effects: &[],
        build: |p, _| Ok(Box::new(SphereClosure::new(parameters(p)?)?)),
    },
];

/// The kind called `name`.
pub fn find(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.name == name)
}

impl Kind {
    /// Builds a unit of this kind, checking the effects against the kind's list.
    pub fn build(
        &self,
        params: Given,
        context: &BuildContext,
    ) -> Result<Box<dyn Unit>, BuildError> {
        if let Some(bad) = context
            .effects
            .iter()
            .find(|e| !self.effects.contains(&e.as_str()))
        {
            return Err(if self.effects.is_empty() {
                BuildError::NoEffects {
                    effect: bad.clone(),
                    kind: self.name,
                }
            } else {
                BuildError::UnknownEffect {
                    effect: bad.clone(),
                    kind: self.name,
                    offered: self.effects.join(", "),
                }
            });
        }
        (self.build)(params, context)
    }
}

/// A kind's typed parameters from what its builder is given: a table read
/// by serde (an error names the key path where it went wrong,
/// `sines.0.phase`), or the type itself.
fn parameters<T: DeserializeOwned + 'static>(given: Given) -> Result<T, BuildError> {
    let table = match given {
        Given::Table(table) => table,
        Given::Typed(typed) => {
            return typed.downcast::<T>().map(|p| *p).map_err(|_| {
                BuildError::Parameters(format!(
                    "the parameters given are not a `{}`",
                    std::any::type_name::<T>()
                ))
            });
        }
    };
    serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
        let message = words::in_words(e.inner().message().trim());
        let path = e.path().to_string();
        BuildError::Parameters(if path.is_empty() || path == "." {
            message
        } else {
            format!("`{path}`: {message}")
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message of building `kind` from `parameters` (TOML text).
    fn refusal(kind: &str, parameters: &str) -> String {
        let context = BuildContext {
            effects: &[],
            base_dir: Path::new("."),
        };
        let table: toml::Table = parameters.parse().expect("TOML");
        match find(kind)
            .expect("a kind")
            .build(Given::Table(table), &context)
        {
            Ok(_) => panic!("{kind} accepted {parameters}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn a_parameter_that_does_not_read_is_named_by_its_key_path() {
        let e = refusal(
            "oscillator",
            "mass = 1.0\nstiffness = 1.0\ncoupling_stiffness = [1, 2]",
        );
        assert!(
            e.starts_with("`coupling_stiffness`: ") && e.contains("an array"),
            "{e}"
        );
        let e = refusal(
            "signal",
            "quantity = \"force\"\nsines = [{ amplitude = 1.0, angular_frequency = 1.0, phase = \"up\" }]",
        );
        assert!(
            e.starts_with("`sines[0].phase`: ") && e.contains("a number"),
            "{e}"
        );
    }
}
