//! What the master checks and builds before its first step: the units'
//! adapters, valid settings and the rollback repeated steps need, an explicit
//! unit order.

use crate::adapter::UnitAdapter;
use crate::error::MasterError;
use crate::settings::MasterSettings;
use crate::system::{Connection, System};
use slender_contract::Time;

/// The master's side of every unit, with the tolerances of the connections
/// feeding its inputs and the outputs that feed connections.
pub(super) fn adapters(
    units: Vec<crate::system::NamedUnit>,
    connections: &[Connection],
    tolerance: &[f64],
    settings: &MasterSettings,
) -> Vec<UnitAdapter> {
    let mut units: Vec<UnitAdapter> = units
        .into_iter()
        .map(|u| UnitAdapter::new(u.name, u.unit, u.start_inputs))
        .collect();
    for unit in &mut units {
        unit.input_tolerance.fill(settings.tolerances.generic);
    }
    for (c, conn) in connections.iter().enumerate() {
        units[conn.to.unit].input_tolerance[conn.to.port] = tolerance[c];
        units[conn.from.unit].coupled_outputs.push(conn.from.port);
    }
    units
}

/// Iterative schemes repeat steps: every unit must roll back.
/// Valid settings, a step > 0, at least one unit, and rollback where steps
/// repeat.
pub(super) fn check_setup(
    system: &System,
    settings: &MasterSettings,
    step_size: Time,
) -> Result<(), MasterError> {
    settings.validate()?;
    if step_size <= Time::ZERO {
        return Err(MasterError::Invalid(format!(
            "synchronisation step {step_size}: expected > 0"
        )));
    }
    if system.units.is_empty() {
        return Err(MasterError::Invalid("the system has no units".into()));
    }
    if settings.adaptive.is_some()
        && let Some(u) =
            (system.units.iter()).find(|u| !u.unit.description().capabilities.variable_step)
    {
        return Err(MasterError::Invalid(format!(
            "the adaptive step changes the step size, but unit `{}` cannot take a variable step (an FMU's canHandleVariableCommunicationStepSize = false): remove [master.adaptive]",
            u.name
        )));
    }
    check_rollback(system, settings)
}

fn check_rollback(system: &System, settings: &MasterSettings) -> Result<(), MasterError> {
    if !settings.scheme.is_iterative() && settings.adaptive.is_none() {
        return Ok(());
    }
    match system
        .units
        .iter()
        .find(|u| !u.unit.description().capabilities.rollback)
    {
        Some(u) => Err(MasterError::RollbackUnsupported {
            unit: u.name.clone(),
            scheme: if settings.scheme.is_iterative() {
                format!("scheme `{}`", settings.scheme.name())
            } else {
                "the adaptive step".into()
            },
        }),
        None => Ok(()),
    }
}

pub(super) fn explicit_order(system: &System, names: &[String]) -> Result<Vec<usize>, MasterError> {
    let mut order = Vec::with_capacity(names.len());
    for name in names {
        let u = system.unit_index(name).ok_or_else(|| {
            MasterError::Invalid(format!(
                "order: no unit named `{name}`{}",
                crate::error::did_you_mean(name, system.unit_names())
            ))
        })?;
        if order.contains(&u) {
            return Err(MasterError::Invalid(format!(
                "order: unit `{name}` is listed twice"
            )));
        }
        order.push(u);
    }
    if order.len() != system.units.len() {
        let missing: Vec<&str> = system
            .unit_names()
            .enumerate()
            .filter(|(i, _)| !order.contains(i))
            .map(|(_, n)| n)
            .collect();
        return Err(MasterError::Invalid(format!(
            "order: every unit must be listed once; missing: {}",
            missing.join(", ")
        )));
    }
    Ok(order)
}
