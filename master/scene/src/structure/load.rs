//! `[structure.top_load]`: the structure's top end loaded by outputs of other
//! scene units (seed 000's characteristic load, a vessel model, an FMU), in x
//! and z, whatever fidelity the last section has. The static force at t = 0
//! (`static`, N) holds the structure in its equilibrium.

use super::cuts::port;
use super::sections::Fidelity;
use super::unit::SectionUnit;
use super::written::Link;
use serde::Deserialize;
use slender_units::beam::boundary::{InputMarker, TimeFunction};
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::{DofCondition, EndKind};

/// `[structure.top_load]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TopLoadFile {
    /// The output driving the top's x force, "unit.port".
    x: String,
    /// The output driving the top's z force, "unit.port".
    z: String,
    /// The load at rest [fx, fz] (N).
    #[serde(rename = "static")]
    at_rest: [f64; 2],
}

/// The top load: the outputs driving x and z, and the force at rest.
#[derive(Clone, Debug)]
pub(super) struct TopLoad {
    x: String,
    z: String,
    at_rest: [f64; 2],
}

impl TopLoad {
    /// `structure.top_load` checked; the model's own end must leave x and z
    /// to it.
    pub(super) fn of(file: TopLoadFile, model: &NonlinearParams) -> Result<TopLoad, String> {
        for (k, output) in [("x", &file.x), ("z", &file.z)] {
            if !output.contains('.') {
                return Err(format!(
                    "`structure.top_load.{k}` = \"{output}\": expected the output driving the top's {k} force, \"unit.port\""
                ));
            }
        }
        if !file.at_rest.iter().all(|f| f.is_finite()) {
            return Err(
                "`structure.top_load.static`: expected [fx, fz], the load at rest (N)".into(),
            );
        }
        let end = &model.ends.end;
        let given = [
            ("kind", end.kind != EndKind::Free),
            ("x", end.x.is_some()),
            ("z", end.z.is_some()),
        ];
        if let Some((k, _)) = given.into_iter().find(|(_, given)| *given) {
            return Err(format!(
                "`structure.model.ends.end.{k}`: the top's x and z are loaded by `structure.top_load`; leave them out"
            ));
        }
        Ok(TopLoad {
            x: file.x,
            z: file.z,
            at_rest: file.at_rest,
        })
    }

    /// The model loaded at its top by the force at rest (for its equilibrium).
    pub(super) fn held_at_rest(&self, model: &NonlinearParams) -> NonlinearParams {
        let mut model = model.clone();
        let [fx, fz] = self.at_rest.map(TimeFunction::Constant);
        set_end(&mut model, fx, fz);
        model
    }

    /// The model as the units take it: the top force a coupled input.
    pub(super) fn take_input(&self, model: &mut NonlinearParams) {
        let input = || TimeFunction::Input(InputMarker::Input);
        set_end(model, input(), input());
    }

    /// The connections from the load to a unit's top.
    pub(super) fn links(&self, unit: &str, fidelity: Fidelity) -> Vec<Link> {
        vec![
            Link::new(self.x.clone(), port(unit, fidelity, true, "force_x")),
            Link::new(self.z.clone(), port(unit, fidelity, true, "force_z")),
        ]
    }

    /// The force at rest as the first guess of the unit's top-force inputs.
    pub(super) fn first_guess(&self, unit: &mut SectionUnit, fidelity: Fidelity) {
        let side = fidelity.model().end_names()[1];
        unit.first_guess_force(side, self.at_rest);
    }
}

/// The model's top loaded by the forces `fx` and `fz` (N).
fn set_end(model: &mut NonlinearParams, fx: TimeFunction, fz: TimeFunction) {
    model.ends.end.x = Some(DofCondition::Force(fx));
    model.ends.end.z = Some(DofCondition::Force(fz));
}
