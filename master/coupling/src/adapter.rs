//! The master's side of a unit: cached port values, counters, NaN checks.
//!
//! Model authors implement the small [`Unit`] trait; the master only talks to units
//! through this adapter. It drives the unit through a [`Driver`], which owns the
//! held inputs and enforces the call order written in the trait's documentation;
//! the adapter adds the port values the sweeps read and write, output NaN checks
//! and counters (the sweep times the calls).

use crate::counters::UnitCounters;
use crate::error::MasterError;
use slender_contract::{Driver, DriverSlot, Hold, Time, Unit, UnitError};
use std::time::{Duration, Instant};

/// A unit as the master holds it.
pub struct UnitAdapter {
    /// The unit's name in the system.
    pub name: String,
    driver: Driver,
    /// Input values for the next `initialize` or step.
    pub inputs: Vec<f64>,
    /// Output values after the last `initialize` or `do_step`.
    pub outputs: Vec<f64>,
    /// Constant values of inputs nothing drives (first guess for looped inputs).
    pub start_inputs: Vec<f64>,
    saved: DriverSlot,
    /// What the unit was asked to do in the run.
    pub counters: UnitCounters,
    /// Wall time charged to this unit by the master's sweeps and Jacobians.
    pub step_time: Duration,
    /// The unit's interface Jacobian of its last step, row-major `outputs x
    /// inputs` (filled by [`UnitAdapter::step_jacobian`]).
    pub jacobian: Vec<f64>,
    /// Scratch of finite differences: the perturbed step's outputs.
    probe: Vec<f64>,
    /// A failure of this unit in a parallel sweep, until the master reads it.
    pub failure: Option<MasterError>,
    /// Per input: the tolerance of the connection feeding it (a finite
    /// difference moves the input by at least ten of them).
    pub input_tolerance: Vec<f64>,
    /// The outputs that feed connections: the rows a Jacobian must give.
    pub coupled_outputs: Vec<usize>,
    /// Scratch: the finite-difference steps of the inputs.
    delta: Vec<f64>,
    /// The last `step_jacobian` was the unit's own (not finite differences).
    pub own_jacobian: bool,
    /// The master will close its steps by correcting them (`newton.one_sweep`):
    /// the unit is told it may leave each step's end pending
    /// ([`slender_contract::Unit::defer_step_end`]).
    pub defer_end: bool,
    /// The last step was taken with `defer_end`: its end may be pending until
    /// a correction or [`UnitAdapter::complete_step`].
    end_deferred: bool,
}

impl UnitAdapter {
    /// The unit `unit` named `name`, its undriven inputs at `start_inputs`.
    pub fn new(name: String, unit: Box<dyn Unit>, start_inputs: Vec<f64>) -> UnitAdapter {
        let n_out = unit.description().outputs.len();
        let n_in = unit.description().inputs.len();
        UnitAdapter {
            counters: UnitCounters {
                name: name.clone(),
                ..UnitCounters::default()
            },
            name,
            driver: Driver::new(unit),
            inputs: start_inputs.clone(),
            outputs: vec![0.0; n_out],
            start_inputs,
            saved: DriverSlot::new(),
            step_time: Duration::ZERO,
            jacobian: vec![0.0; n_out * n_in],
            probe: vec![0.0; n_out],
            failure: None,
            input_tolerance: vec![0.0; n_in],
            coupled_outputs: Vec::new(),
            delta: vec![0.0; n_in],
            own_jacobian: false,
            defer_end: false,
            end_deferred: false,
        }
    }

    /// The wrapped unit's description.
    pub fn description(&self) -> &slender_contract::UnitDescription {
        self.driver.description()
    }

    /// The quantities along the unit it can report (`Unit::fields`).
    pub fn fields(&self) -> Vec<slender_contract::Field> {
        self.driver.unit().fields()
    }

    /// The unit's estimate of its last step's local displacement error (m).
    pub fn local_error(&self) -> Option<f64> {
        self.driver.unit().local_error()
    }

    /// The current values of the unit's field `index` into `out`.
    pub fn field_values(
        &self,
        index: usize,
        out: &mut [f64],
    ) -> Result<(), slender_contract::UnitError> {
        self.driver.unit().field_values(index, out)
    }

    /// The inputs whose values at `initialize` set the unit's static state.
    pub fn static_inputs(&self) -> Vec<usize> {
        self.driver.unit().static_inputs()
    }

    /// The hold in force for each input.
    pub fn holds(&self) -> &[Hold] {
        self.driver.holds()
    }

    fn fail(&self, call: &'static str, t: Time, iteration: u32, source: UnitError) -> MasterError {
        MasterError::Unit {
            unit: self.name.clone(),
            call,
            time: t.as_secs(),
            iteration,
            source,
        }
    }

    /// Sets the hold of every input (before initialisation only).
    /// Steps the unit in `n` sub-steps per synchronisation step (multi-rate),
    /// before initialisation.
    pub fn set_substeps(&mut self, n: u32) -> Result<(), MasterError> {
        if self.driver.is_initialized() {
            return Err(MasterError::Invalid(format!(
                "unit `{}`: the sub-steps can only change before initialisation",
                self.name
            )));
        }
        self.driver
            .set_substeps(n)
            .map_err(|e| self.fail("set_substeps", Time::ZERO, 0, e))
    }

    /// Sets how every input of the unit is held within a step.
    pub fn set_hold_all(&mut self, hold: Hold) -> Result<(), MasterError> {
        if self.driver.is_initialized() {
            return Err(MasterError::Invalid(format!(
                "unit `{}`: the input hold can only change before initialisation",
                self.name
            )));
        }
        for port in 0..self.inputs.len() {
            self.driver
                .set_hold(port, hold)
                .map_err(|e| self.fail("set_hold", Time::ZERO, 0, e))?;
        }
        Ok(())
    }

    /// Sets `self.inputs` as the start values, then `initialize(t0)`, then reads the
    /// outputs; may be repeated while the master makes looped initial values
    /// consistent.
    pub fn initialize(&mut self, t0: Time, iteration: u32) -> Result<(), MasterError> {
        self.driver
            .set_inputs(&self.inputs)
            .map_err(|e| self.fail("set_inputs", t0, iteration, e))?;
        self.driver
            .initialize(t0)
            .map_err(|e| self.fail("initialize", t0, iteration, e))?;
        self.read_outputs(t0, iteration)
    }

    /// Sets `self.inputs` as the step's end values, `do_step(t, h)`, then reads the
    /// outputs at `t + h`.
    pub fn step(&mut self, t: Time, h: Time, iteration: u32) -> Result<(), MasterError> {
        if !self.driver.is_initialized() {
            return Err(MasterError::Invalid(format!(
                "unit `{}`: do_step called before initialize",
                self.name
            )));
        }
        self.own_jacobian = false;
        self.driver
            .set_inputs(&self.inputs)
            .map_err(|e| self.fail("set_inputs", t + h, iteration, e))?;
        if self.defer_end {
            self.driver.defer_step_end(&self.coupled_outputs);
        }
        self.end_deferred = self.defer_end;
        let result = self.driver.do_step(t, h);
        self.counters.do_step_calls += 1;
        let report = result.map_err(|e| self.fail("do_step", t + h, iteration, e))?;
        self.counters.solver_iterations += u64::from(report.solver_iterations);
        self.read_outputs(t + h, iteration)
    }

    fn read_outputs(&mut self, t: Time, iteration: u32) -> Result<(), MasterError> {
        self.driver
            .outputs(&mut self.outputs)
            .map_err(|e| self.fail("outputs", t, iteration, e))?;
        if let Some(port) = self.outputs.iter().position(|v| !v.is_finite()) {
            return Err(MasterError::NonFinite {
                unit: self.name.clone(),
                port: self.driver.description().outputs[port].name.clone(),
                value: self.outputs[port],
                time: t.as_secs(),
                iteration,
            });
        }
        Ok(())
    }

    /// The unit's modes about its initial state.
    pub fn modes(&self, count: usize) -> Result<slender_contract::ModalAnalysis, MasterError> {
        if !self.driver.is_initialized() {
            return Err(MasterError::Invalid(format!(
                "unit `{}`: modal analysis before initialize",
                self.name
            )));
        }
        self.driver
            .modes(count)
            .map_err(|e| self.fail("modes", Time::ZERO, 0, e))
    }

    /// Fills `self.jacobian` for the step from `t` over `h` just taken with
    /// `self.inputs`: the unit's own (`Unit::step_jacobian`) when it gives
    /// every coupled output's row finite, or forward differences of its step
    /// from the state saved at the step's start, each input moved by
    /// max(perturbation |u|, 10 x its connection's tolerance); then the unit is
    /// left after a perturbed step and must be restored before it steps again.
    /// Returns whether it was the unit's own. The time is charged to the unit.
    pub fn step_jacobian(
        &mut self,
        (t, h): (Time, Time),
        perturbation: f64,
        iteration: u32,
    ) -> Result<bool, MasterError> {
        let started = Instant::now();
        let n_in = self.inputs.len();
        let own = self.driver.step_jacobian(&mut self.jacobian).is_ok()
            && self.coupled_outputs.iter().all(|&o| {
                self.jacobian[o * n_in..(o + 1) * n_in]
                    .iter()
                    .all(|v| v.is_finite())
            });
        if !own {
            if self.saved.is_empty() {
                return Err(MasterError::Invalid(format!(
                    "unit `{}`: a Jacobian by finite differences needs a saved step start",
                    self.name
                )));
            }
            for ((d, u), tol) in self
                .delta
                .iter_mut()
                .zip(&self.inputs)
                .zip(&self.input_tolerance)
            {
                *d = (perturbation * u.abs()).max(10.0 * tol);
            }
            self.driver
                .finite_difference_jacobian(
                    &self.saved,
                    (t, h),
                    (&self.inputs, &self.delta),
                    &self.outputs,
                    (&mut self.jacobian, &mut self.probe),
                )
                .map_err(|e| self.fail("do_step (Jacobian probe)", t + h, iteration, e))?;
            self.counters.do_step_calls += n_in as u64;
        }
        self.step_time += started.elapsed();
        self.own_jacobian = own;
        Ok(own)
    }

    /// Whether the unit declares a step correction and steps whole.
    pub fn declares_step_correction(&self) -> bool {
        self.driver.can_correct_step()
    }

    /// Whether the unit can correct the step just taken to first order: it
    /// declares it and its last Jacobian was its own.
    pub fn can_correct_step(&self) -> bool {
        self.own_jacobian && self.driver.can_correct_step()
    }

    /// The step just taken with its end inputs moved by `change` to first
    /// order ([`slender_contract::Unit::correct_step`]); the moved inputs and
    /// the outputs at the moved state into `inputs` and `outputs`.
    pub fn correct_step(
        &mut self,
        change: &[f64],
        t_end: Time,
        iteration: u32,
    ) -> Result<(), MasterError> {
        let started = Instant::now();
        self.own_jacobian = false;
        self.end_deferred = false;
        self.driver
            .correct_step(change)
            .map_err(|e| self.fail("correct_step", t_end, iteration, e))?;
        for (u, d) in self.inputs.iter_mut().zip(change) {
            *u += d;
        }
        let read = self.read_outputs(t_end, iteration);
        self.step_time += started.elapsed();
        read
    }

    /// Takes the end of the last step if the unit left it pending (a step
    /// accepted without a correction), and reads the outputs at it.
    pub fn complete_step(&mut self, t_end: Time, iteration: u32) -> Result<(), MasterError> {
        if !std::mem::take(&mut self.end_deferred) {
            return Ok(());
        }
        let started = Instant::now();
        let pending = (self.driver.complete_step())
            .map_err(|e| self.fail("complete_step", t_end, iteration, e))?;
        let read = if pending {
            self.read_outputs(t_end, iteration)
        } else {
            Ok(())
        };
        self.step_time += started.elapsed();
        read
    }

    /// Saves the unit's state for a later `restore`.
    pub fn save(&mut self, t: Time) -> Result<(), MasterError> {
        if self.end_deferred {
            return Err(MasterError::Invalid(format!(
                "unit `{}`: state saved while its last step's end is pending",
                self.name
            )));
        }
        self.driver
            .save(&mut self.saved)
            .map_err(|e| self.fail("save_state", t, 0, e))
    }

    /// Restores the state saved by the last `save`; with `warm`, hints the unit
    /// that it repeats the step it last took ([`slender_contract::Unit::warm_repeat`]).
    pub fn restore_hinted(
        &mut self,
        t: Time,
        iteration: u32,
        warm: bool,
    ) -> Result<(), MasterError> {
        if self.saved.is_empty() {
            return Err(MasterError::Invalid(format!(
                "unit `{}`: restore_state called before save_state",
                self.name
            )));
        }
        self.end_deferred = false;
        let restored = if warm {
            self.driver.restore_warm(&self.saved)
        } else {
            self.driver.restore(&self.saved)
        };
        restored.map_err(|e| self.fail("restore_state", t, iteration, e))
    }

    /// Restores the state saved by the last `save`.
    pub fn restore(&mut self, t: Time, iteration: u32) -> Result<(), MasterError> {
        self.restore_hinted(t, iteration, false)
    }
}
