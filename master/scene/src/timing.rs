//! The scene's simulated time checked once: the start, the step and the
//! duration in whole nanoseconds (the master's time), a whole number of
//! steps within `simulation.max_steps`.

use crate::{Scene, SceneError, spec};
use slender_units::Time;

impl Scene {
    pub(crate) fn check_time(&mut self) -> Result<(), SceneError> {
        let sim = &self.spec.simulation;
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(sim.step) {
            return Err(self.error(
                None,
                "simulation.step",
                format!("{}: expected a finite value > 0 (s)", sim.step),
            ));
        }
        if !positive(sim.duration) {
            return Err(self.error(
                None,
                "simulation.duration",
                format!("{}: expected a finite value > 0 (s)", sim.duration),
            ));
        }
        let range = format!(
            "simulation time is kept in integer nanoseconds: from {:e} to {:e} s",
            -Time::MAX.as_secs(),
            Time::MAX.as_secs()
        );
        let start = Time::from_secs(sim.start).ok_or_else(|| {
            self.error(
                None,
                "simulation.start",
                format!(
                    "{}: expected a finite time within range ({range})",
                    sim.start
                ),
            )
        })?;
        // Time is kept in whole nanoseconds: a step between two (1/3 ms) was
        // rounded, and a unit or an FMU counting its own time fell behind.
        let nanos = sim.step * 1e9;
        if (nanos - nanos.round()).abs() > 1e-3 {
            return Err(self.error(
                None,
                "simulation.step",
                format!(
                    "{} s is not a whole number of nanoseconds (slender keeps time in integer ns, and a rounded step lets the units' clocks drift): give e.g. {:e} s",
                    sim.step,
                    nanos.round().max(1.0) * 1e-9
                ),
            ));
        }
        let step = Time::from_secs(sim.step)
            .filter(|s| *s > Time::ZERO)
            .ok_or_else(|| {
                self.error(
                    None,
                    "simulation.step",
                    format!("{}: expected at least 1 ns", sim.step),
                )
            })?;
        let duration = Time::from_secs(sim.duration)
            .filter(|d| start.checked_add(*d).is_some())
            .ok_or_else(|| {
                self.error(
                    None,
                    "simulation.duration",
                    format!(
                        "start {} s + duration {} s ends beyond the representable range ({range})",
                        sim.start, sim.duration
                    ),
                )
            })?;
        let steps = self.steps_in(duration, step)?;
        self.start = start;
        self.step = step;
        self.steps = steps;
        Ok(())
    }

    /// The steps of `step` in `duration`: at least one, a whole number, and
    /// within `simulation.max_steps`.
    fn steps_in(&self, duration: Time, step: Time) -> Result<i64, SceneError> {
        let sim = &self.spec.simulation;
        if duration < step {
            // A duration under 1 ns rounds to none: no step, and a run that
            // "completed" with nothing in it.
            return Err(self.error(
                None,
                "simulation.duration",
                format!(
                    "{} s is shorter than one step of {} s",
                    sim.duration, sim.step
                ),
            ));
        }
        if duration.as_nanos() % step.as_nanos() != 0 {
            return Err(self.error(
                None,
                "simulation.duration",
                format!(
                    "{} s is not a whole number of steps of {} s",
                    sim.duration, sim.step
                ),
            ));
        }
        let steps = duration.as_nanos() / step.as_nanos();
        let bound = sim.max_steps.unwrap_or(spec::DEFAULT_MAX_STEPS);
        if steps as u64 > bound {
            return Err(self.error(
                None,
                "simulation.duration",
                format!(
                    "{} s in steps of {} s is {steps} steps, more than the bound of {bound}; give `simulation.max_steps` to go past it",
                    sim.duration, sim.step
                ),
            ));
        }
        Ok(steps)
    }
}
