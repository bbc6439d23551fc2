//! A watch on physical plausibility (issue 27): a run can end "completed"
//! with results no structure of its kind could give. After every step it
//! checks each section's largest tension against the structure's at the
//! start and a breaking load ([`tension`]), and each section's energy
//! balance against the energy exchanged ([`energy`]). What goes beyond a
//! bound is a warning with the unit, port, value and time (once per port),
//! kept in `summary.json`; with `stop` it ends the run instead.

mod energy;
mod tension;

use slender_coupling::coupler::Master;
use slender_scene::spec::WatchSpec;

/// The watch over a run.
pub struct Watch {
    tension: tension::TensionWatch,
    energy: energy::EnergyWatch,
    stop: bool,
}

impl Watch {
    /// The watched outputs (after `Master::initialize`).
    pub fn new(master: &Master, spec: WatchSpec) -> Watch {
        Watch {
            tension: tension::TensionWatch::new(master, &spec),
            energy: energy::EnergyWatch::new(master, &spec),
            stop: spec.stop,
        }
    }

    /// Checks the outputs after a step at simulated time `t` (s), adding a
    /// warning to `warnings` per port the first time it goes beyond its
    /// bound; `Err` with the first such warning when the watch stops the run.
    pub fn observe(
        &mut self,
        master: &Master,
        t: f64,
        warnings: &mut Vec<String>,
    ) -> Result<(), crate::run::RunError> {
        let before = warnings.len();
        self.tension.observe(master, t, warnings);
        self.energy.observe(master, t, warnings);
        match warnings.get(before).cloned() {
            Some(first) if self.stop => {
                warnings.truncate(before);
                Err(crate::run::RunError::Bound(first))
            }
            _ => Ok(()),
        }
    }
}
