//! The start check (issue 30): a unit that solves its statics under a coupled
//! load (its [`Unit::static_inputs`](slender_contract::Unit::static_inputs)) starts
//! in equilibrium with the value the other side reported at the start. If the
//! other side then reports something else after the first step, the unit's
//! static state was solved under a load that does not persist: the section
//! started off its equilibrium (a damping reaction taken as load, an end motion
//! started at full speed, an initialisation left unconverged). The master
//! measures the largest such change after the first step and refuses the run
//! when it exceeds `[master] start_tolerance`.

use super::Master;
use crate::error::MasterError;
use serde::Serialize;

/// The coupled load with the largest change over the first step, among those
/// a unit's static state was solved under.
#[derive(Clone, Debug, Serialize)]
pub struct StartLoad {
    /// "unit.port -> unit.port".
    pub connection: String,
    #[serde(skip)]
    connection_index: usize,
    /// The value the receiving unit's statics were solved under (N or N m).
    pub used: f64,
    /// What the sending unit reported after the first step (N or N m).
    pub after_first_step: f64,
    /// |after - used| over the larger magnitude of the two (at least a
    /// thousand times the connection's tolerance, so a load that is zero to
    /// round-off does not count as a change).
    pub relative_change: f64,
}

impl Master {
    /// The connections into a static input with the value each unit was
    /// initialised under (after initialisation).
    pub(super) fn record_static_loads(&mut self) {
        self.static_loads.clear();
        // Each unit asked once; its static inputs found through the wiring.
        for (u, unit) in self.units.iter().enumerate() {
            for port in unit.static_inputs() {
                if let Some(c) = self.input_connection[u].get(port).copied().flatten() {
                    self.static_loads.push((c, unit.inputs[port]));
                }
            }
        }
        // In connection order, so that of equal changes the first is kept.
        self.static_loads.sort_by_key(|&(c, _)| c);
    }

    /// After the first step: the largest relative change of a static load,
    /// kept in the counters; an error beyond the start tolerance.
    pub(super) fn check_start(&mut self) -> Result<(), MasterError> {
        let mut worst: Option<StartLoad> = None;
        for &(c, used) in &self.static_loads {
            let after = self.value[c];
            let floor = 1e3 * self.tolerance[c];
            let relative = (after - used).abs() / used.abs().max(after.abs()).max(floor);
            if worst.as_ref().is_none_or(|w| relative > w.relative_change) {
                worst = Some(StartLoad {
                    connection: self.connections[c].label.clone(),
                    connection_index: c,
                    used,
                    after_first_step: after,
                    relative_change: relative,
                });
            }
        }
        self.counters.start_load = worst.clone();
        let tolerance = self.settings.start_tolerance;
        match worst {
            Some(w) if w.relative_change > tolerance => {
                let c = &self.connections[w.connection_index];
                Err(MasterError::StartOffEquilibrium {
                    from: format!(
                        "{}.{}",
                        self.units[c.from.unit].name,
                        self.units[c.from.unit].description().outputs[c.from.port].name
                    ),
                    to: format!(
                        "{}.{}",
                        self.units[c.to.unit].name,
                        self.units[c.to.unit].description().inputs[c.to.port].name
                    ),
                    used: w.used,
                    after: w.after_first_step,
                    percent: 100.0 * w.relative_change,
                    tolerance,
                })
            }
            _ => Ok(()),
        }
    }
}
