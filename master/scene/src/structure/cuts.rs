//! What crosses a cut between two sections: one side moves with the other's
//! velocity (x, z, and rotation where both bend) and the other carries the force
//! (and moment) the moving side exerts, in the global frame. A cut next to a
//! section without bending (a cable) is pinned: no rotation or moment crosses it
//! and the bending side's end turns freely. Next to a physical section the
//! signals pass through artefact units, as in a hybrid test: what the physical
//! side emits through its sensor, what it receives through its actuator.

use super::sections::Fidelity;
use super::spec::typed;
use super::unit::{Parameters, SectionUnit};
use super::written::Link;
use slender_units::UnitError;
use slender_units::beam::boundary::{InputMarker, TimeFunction};
use slender_units::nonlinear::params::{DofCondition, End as ModelEnd, EndKind};
use slender_units::signal::artefact::{Artefact, ArtefactParams};
use toml::{Table, Value};

/// How a section's end at a cut is coupled.
#[derive(Copy, Clone, Debug)]
pub(super) struct End {
    /// It moves with the other side's velocity (else it carries its force).
    pub moving: bool,
    /// Rotation and moment do not cross the cut (one side does not bend).
    pub pinned: bool,
    /// A moving end follows the other side's displacement rather than its
    /// velocity (the other side is a chord section).
    pub by_displacement: bool,
}

/// A section as its cut sees it: its name, unit name, fidelity, and the
/// artefacts of a physical section (`sensor`, `actuator`: `artefact`
/// parameters without `quantity`).
pub(super) struct Side<'a> {
    pub section: &'a str,
    pub unit: String,
    pub fidelity: Fidelity,
    pub physical: Option<&'a Table>,
}

/// The end condition of a section's end at a cut, as `End` couples it: the
/// other side's velocity (`moving`), its displacement (`by_displacement`:
/// next to a chord section) or its force and moment (loaded); a pinned cut's
/// rotation is free.
pub(super) fn coupled_end(end: End) -> ModelEnd {
    let input = || TimeFunction::Input(InputMarker::Input);
    let (translation, rotation) = match end {
        End {
            moving: true,
            by_displacement: true,
            ..
        } => {
            let d = DofCondition::Displacement(input());
            (d.clone(), d)
        }
        End { moving: true, .. } => (DofCondition::Velocity, DofCondition::Velocity),
        End { moving: false, .. } => (DofCondition::Force(input()), DofCondition::Force(input())),
    };
    let free_rotation = end.pinned && !(end.moving && end.by_displacement);
    ModelEnd {
        kind: EndKind::Free,
        x: Some(translation.clone()),
        z: Some(translation),
        rotation: Some(if free_rotation {
            DofCondition::Free
        } else {
            rotation
        }),
    }
}

/// A section's port at one of its ends (`at_end`: its end, else its start) for
/// a quantity `velocity_x`, `force_z`, `angular_velocity`, `moment`, ...: the
/// `nonlinear` unit's `end_force_x`, the `cable` unit's `top_force_x` (its end
/// is its top).
pub(super) fn port(unit: &str, fidelity: Fidelity, at_end: bool, quantity: &str) -> String {
    let side = fidelity.model().end_names()[usize::from(at_end)];
    format!("{unit}.{side}_{quantity}")
}

/// The links of a cut (and the artefact units of a physical side): velocity
/// from the loaded side to the moving side and force back (`force_on_upper`:
/// the upper section's end is the loaded side); rotation and moment too unless
/// one side does not bend.
pub(super) fn cut_connections(
    upper: &Side<'_>,
    lower: &Side<'_>,
    force_on_upper: bool,
) -> Result<(Vec<Link>, Vec<SectionUnit>), String> {
    let ((loaded, loaded_at_end), (moving, moving_at_end)) = if force_on_upper {
        ((upper, true), (lower, false))
    } else {
        ((lower, false), (upper, true))
    };
    if upper.physical.is_some() && lower.physical.is_some() {
        return Err(format!(
            "`{}` and `{}` are both physical: a cut needs a numerical side",
            upper.unit, lower.unit
        ));
    }
    let bends = upper.fidelity.bends() && lower.fidelity.bends();
    let mut links = Vec::new();
    let mut units = Vec::new();
    for (motion, load) in [
        ("velocity_x", "force_x"),
        ("velocity_z", "force_z"),
        ("angular_velocity", "moment"),
    ] {
        if motion == "angular_velocity" && !bends {
            continue;
        }
        links.push(Link::new(
            port(&loaded.unit, loaded.fidelity, loaded_at_end, motion),
            port(&moving.unit, moving.fidelity, moving_at_end, motion),
        ));
        links.push(Link::new(
            port(&moving.unit, moving.fidelity, moving_at_end, load),
            port(&loaded.unit, loaded.fidelity, loaded_at_end, load),
        ));
    }
    for (side, at_end) in [(upper, true), (lower, false)] {
        if let Some(physical) = side.physical {
            let prefix = format!("{}_{}", side.unit, if at_end { "end" } else { "start" });
            let moving_side = std::ptr::eq(side, moving);
            units.extend(through_artefacts(
                &mut links,
                side,
                &prefix,
                physical,
                moving_side,
            )?);
        }
    }
    Ok((links, units))
}

/// Puts the physical section `side`'s x and z links through a sensor (what
/// it emits: force when it is the moving side, velocity otherwise) and an
/// actuator (what it receives); returns the two artefact units
/// `<prefix>_sensor` and `<prefix>_actuator`, checked here so that an error
/// names the user's key. Rotation and moment pass untouched.
fn through_artefacts(
    links: &mut Vec<Link>,
    side: &Side<'_>,
    prefix: &str,
    physical: &Table,
    moving: bool,
) -> Result<Vec<SectionUnit>, String> {
    let (emits, receives) = if moving {
        ("force", "velocity")
    } else {
        ("velocity", "force")
    };
    let unit = &side.unit;
    let mut units = Vec::new();
    for (role, quantity) in [("sensor", emits), ("actuator", receives)] {
        let name = format!("{prefix}_{role}");
        let key = format!("structure.sections.{}.physical.{role}", side.section);
        let mut parameters = match physical.get(role) {
            None => Table::new(),
            Some(Value::Table(t)) => t.clone(),
            Some(_) => {
                return Err(format!(
                    "`{key}`: expected a table of `artefact` parameters"
                ));
            }
        };
        if parameters.contains_key("quantity") || parameters.contains_key("channels") {
            return Err(format!(
                "`{key}`: `quantity` and `channels` follow from the cut; leave them out"
            ));
        }
        parameters.insert("quantity".into(), Value::String(quantity.into()));
        let artefact: ArtefactParams = typed(&key, &parameters)?;
        Artefact::new(artefact.clone()).map_err(|e| artefact_refusal(&key, &e))?;
        let artefact = Parameters::Artefact(Box::new(artefact));
        units.push(SectionUnit::new(name.clone(), artefact));
        // The x and z links of this quantity into or out of the physical unit.
        for axis in ["x", "z"] {
            let suffix = format!("_{quantity}_{axis}");
            let Some(l) = links.iter_mut().find(|l| {
                let ours = if role == "sensor" { &l.from } else { &l.to };
                ours.starts_with(&format!("{unit}.")) && ours.ends_with(&suffix)
            }) else {
                continue;
            };
            let to = std::mem::replace(&mut l.to, format!("{name}.in_{axis}"));
            links.push(Link::new(format!("{name}.out_{axis}"), to));
        }
    }
    Ok(units)
}

/// An artefact's refusal of its parameters at `key` (a physical section's
/// `sensor` or `actuator`), naming the parameter's own key.
fn artefact_refusal(key: &str, e: &UnitError) -> String {
    match e {
        UnitError::InvalidParameter {
            name,
            value,
            expected,
        } => format!("`{key}.{name}` = {value}: {expected}"),
        other => format!("`{key}`: {other}"),
    }
}
