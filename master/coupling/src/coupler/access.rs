//! What a master tells its callers: time, step, counters, settings, units,
//! port values and connections.

use super::Master;
use crate::counters::Counters;
use crate::error::MasterError;
use crate::settings::MasterSettings;
use slender_contract::{Causality, Time};

impl Master {
    /// Current synchronisation time.
    pub fn time(&self) -> Time {
        self.time
    }

    /// The synchronisation step.
    pub fn step_size(&self) -> Time {
        self.step_size
    }

    /// What the run did so far.
    pub fn counters(&self) -> Counters {
        let mut c = self.counters.clone();
        c.units = self
            .units
            .iter()
            .map(|u| {
                let mut uc = u.counters.clone();
                uc.step_time_s = u.step_time.as_secs_f64();
                uc
            })
            .collect();
        c.adaptive = self.adaptive.as_ref().map(|a| a.counters.clone());
        c
    }

    /// The settings in force.
    pub fn settings(&self) -> &MasterSettings {
        &self.settings
    }

    /// Unit names in the order they were added.
    pub fn unit_names(&self) -> impl Iterator<Item = &str> {
        self.units.iter().map(|u| u.name.as_str())
    }

    /// The order units are stepped in, by name.
    pub fn order(&self) -> Vec<&str> {
        self.order
            .iter()
            .map(|&u| self.units[u].name.as_str())
            .collect()
    }

    /// Output values of unit `unit` at the current time.
    pub fn outputs(&self, unit: usize) -> &[f64] {
        &self.units[unit].outputs
    }

    /// Input values of unit `unit` as last given to it (after `initialize`: the
    /// settled initial inputs).
    pub fn inputs(&self, unit: usize) -> &[f64] {
        &self.units[unit].inputs
    }

    /// Output value of "unit.port".
    pub fn output(&self, path: &str) -> Result<f64, MasterError> {
        let (unit, port) = self.find(path, Causality::Output)?;
        Ok(self.units[unit].outputs[port])
    }

    /// The unit of measure of output "unit.port" (`""` where it has none), for
    /// figures and headers.
    pub fn output_unit(&self, path: &str) -> Result<&str, MasterError> {
        let (unit, port) = self.find(path, Causality::Output)?;
        Ok(&self.units[unit].description().outputs[port].unit)
    }

    /// Unit and port indices of "unit.port".
    pub fn find(&self, path: &str, causality: Causality) -> Result<(usize, usize), MasterError> {
        let not_found = || MasterError::Invalid(format!("no port `{path}`"));
        let (u, p) = path.split_once('.').ok_or_else(not_found)?;
        let unit = self
            .units
            .iter()
            .position(|a| a.name == u)
            .ok_or_else(not_found)?;
        let d = self.units[unit].description();
        let port = match causality {
            Causality::Input => d.input_index(p),
            Causality::Output => d.output_index(p),
        }
        .ok_or_else(not_found)?;
        Ok((unit, port))
    }

    /// Labels and values of every connection, as accepted at the current time.
    pub fn connection_values(&self) -> impl Iterator<Item = (&str, f64)> {
        self.connections
            .iter()
            .zip(&self.accepted)
            .map(|(c, &v)| (c.label.as_str(), v))
    }

    /// Number of connections.
    pub fn connection_count(&self) -> usize {
        self.connections.len()
    }

    /// Modal analysis of the unit called `name` about its initial state (after
    /// `initialize`).
    pub fn modes(
        &self,
        name: &str,
        count: usize,
    ) -> Result<slender_contract::ModalAnalysis, MasterError> {
        let adapter = self.units.iter().find(|u| u.name == name).ok_or_else(|| {
            MasterError::Invalid(format!(
                "no unit named `{name}`{}",
                crate::error::did_you_mean(name, self.unit_names())
            ))
        })?;
        adapter.modes(count)
    }

    /// Description of unit `unit`.
    pub fn description(&self, unit: usize) -> &slender_contract::UnitDescription {
        self.units[unit].description()
    }
}
