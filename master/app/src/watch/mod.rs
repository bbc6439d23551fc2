//! A watch on physical plausibility (issue 27): a run can end "completed"
//! with results no structure of its kind could give. After every step it
//! checks each section's largest tension against the structure's at the
//! start and a breaking load ([`tension`]), and each section's energy
//! balance against the energy exchanged ([`energy`]). What goes beyond a
//! bound is a warning with the unit, port, value and time (once per port),
//! kept in `summary.json`; with `stop` it ends the run instead. It also says
//! where a section that held the touchdown point lost it ([`touchdown`]),
//! a warning that never stops the run.

mod energy;
mod tension;
mod touchdown;

use slender_coupling::coupler::Master;

/// The watch over a run.
pub struct Watch {
    tension: tension::TensionWatch,
    energy: energy::EnergyWatch,
    touchdown: touchdown::TouchdownWatch,
    stop: bool,
}

impl Watch {
    /// The watched outputs of `scene` (after `Master::initialize`).
    pub fn new(master: &Master, scene: &slender_scene::Scene) -> Watch {
        let spec = scene.spec.output.watch;
        Watch {
            tension: tension::TensionWatch::new(master, &spec),
            energy: energy::EnergyWatch::new(master, &spec),
            touchdown: touchdown::TouchdownWatch::new(master, touchdown::guarded(scene)),
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
        let first = warnings.get(before).cloned();
        self.touchdown.observe(master, t, warnings);
        match first {
            Some(first) if self.stop => {
                warnings.truncate(before);
                Err(crate::run::RunError::Bound(first))
            }
            _ => Ok(()),
        }
    }
}
