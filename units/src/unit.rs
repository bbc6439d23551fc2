//! The unit contract: what every substructure model offers the master.
//!
//! # Call order
//! The master calls a unit in this order, and nothing else:
//! 1. `description`, any number of times; `set_hold` for any input, before `initialize`;
//! 2. `set_inputs` (start values), then `initialize(t0)`: the unit finds its initial
//!    state (static equilibrium, initial conditions) with the inputs held constant.
//!    Both may be repeated while the master settles the initial values of a loop;
//! 3. per synchronisation step: `set_inputs` (values at the END of the step), then
//!    `do_step(t, h)`, then `outputs` (values at `t + h`);
//! 4. `save_state` before a step and `restore_state` to repeat it, when the unit
//!    declares rollback. Restoring then stepping with the same inputs must give
//!    bit-identical outputs.
//!
//! Errors are values: a unit never panics on bad input or a failed solve.

use crate::port::{Causality, Hold, Port};
use crate::state::StateSlot;
use crate::time::Time;
use thiserror::Error;

/// What a unit can do, declared rather than assumed.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Capabilities {
    /// `save_state`/`restore_state` work, so iterative schemes can repeat a step.
    pub rollback: bool,
    /// The unit accepts a different `h` at every step.
    pub variable_step: bool,
    /// Highest time derivative of its outputs the unit can provide (0: values only).
    pub output_derivative_order: u32,
}

impl Default for Capabilities {
    /// What native units offer: rollback and variable steps, values only.
    fn default() -> Self {
        Capabilities {
            rollback: true,
            variable_step: true,
            output_derivative_order: 0,
        }
    }
}

/// The static description of a unit: its kind, its ports and its capabilities.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitDescription {
    /// Model kind as named in scene files, e.g. "oscillator".
    pub kind: String,
    /// Input ports, in the order of `set_inputs` values.
    pub inputs: Vec<Port>,
    /// Output ports, in the order of `outputs` values.
    pub outputs: Vec<Port>,
    pub capabilities: Capabilities,
}

impl UnitDescription {
    /// Index of the input called `name`.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|p| p.name == name)
    }

    /// Index of the output called `name`.
    pub fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs.iter().position(|p| p.name == name)
    }

    /// The port called `name` with the given causality.
    pub fn port(&self, causality: Causality, name: &str) -> Option<&Port> {
        match causality {
            Causality::Input => self.inputs.iter().find(|p| p.name == name),
            Causality::Output => self.outputs.iter().find(|p| p.name == name),
        }
    }

    /// Whether any output depends directly on an input.
    pub fn has_feedthrough(&self) -> bool {
        self.outputs.iter().any(|p| !p.depends_on.is_empty())
    }
}

/// What a unit reports about one `do_step`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Internal solver iterations spent (e.g. Newton iterations); 0 for explicit
    /// or linear units.
    pub solver_iterations: u32,
}

/// Why a unit call failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum UnitError {
    /// A parameter is out of its admissible range.
    #[error("parameter `{name}` = {value}: {expected}")]
    InvalidParameter {
        name: String,
        value: String,
        expected: String,
    },
    /// An input value cannot be used (e.g. NaN or outside the model's domain).
    #[error("input `{port}` = {value}: {reason}")]
    InvalidInput {
        port: String,
        value: f64,
        reason: String,
    },
    /// A numerical solve failed (no equilibrium, singular matrix, NaN produced).
    #[error("{0}")]
    Numerical(String),
    /// Saving or restoring state failed.
    #[error("state: {0}")]
    State(String),
    /// The unit does not offer what was asked (e.g. rollback).
    #[error("not supported: {0}")]
    Unsupported(String),
    /// `set_inputs` got the wrong number of values.
    #[error("expected {expected} input values, got {got}")]
    InputCount { expected: usize, got: usize },
}

impl UnitError {
    /// An `InvalidParameter` error.
    pub fn parameter(name: &str, value: impl ToString, expected: &str) -> UnitError {
        UnitError::InvalidParameter {
            name: name.to_owned(),
            value: value.to_string(),
            expected: expected.to_owned(),
        }
    }
}

/// One mode of a structural unit linearised about its initial state.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// Period (s).
    pub period: f64,
    /// Nodal displacement [x, z] of the mode, scaled to a largest component of 1.
    pub shape: Vec<[f64; 2]>,
}

/// Modes of a structural unit and the node positions (m) they refer to.
#[derive(Clone, Debug, PartialEq)]
pub struct ModalAnalysis {
    pub positions: Vec<[f64; 2]>,
    /// Longest period first.
    pub modes: Vec<Mode>,
}

/// A substructure model with an FMI-like stepping contract (see the module docs for
/// the call order).
pub trait Unit: Send {
    /// Kind, ports and capabilities; constant over the unit's life.
    fn description(&self) -> &UnitDescription;

    /// Chooses the hold of input `port` (by index). Units that cannot change it
    /// return `Unsupported`.
    fn set_hold(&mut self, port: usize, hold: Hold) -> Result<(), UnitError> {
        let _ = (port, hold);
        Err(UnitError::Unsupported("changing the input hold".into()))
    }

    /// Sets the input values; before `initialize` they are the constant start
    /// values, afterwards the values at the end of the next step.
    fn set_inputs(&mut self, values: &[f64]) -> Result<(), UnitError>;

    /// Finds the initial state at `t0` with the inputs held at their set values.
    /// Each call starts again from the parameters: the master may call it several
    /// times with different inputs while it makes looped initial values consistent.
    fn initialize(&mut self, t0: Time) -> Result<(), UnitError>;

    /// Advances from `t` to `t + h`, holding the inputs as their ports say.
    fn do_step(&mut self, t: Time, h: Time) -> Result<StepReport, UnitError>;

    /// Writes the output values at the current time into `out` (one per output port).
    fn outputs(&self, out: &mut [f64]);

    /// Saves everything that influences the next step into `slot`.
    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError>;

    /// Restores a state saved by `save_state`.
    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError>;

    /// The first `count` modes about the initial state, for structural units
    /// (after `initialize`); others return `Unsupported`.
    fn modes(&self, count: usize) -> Result<ModalAnalysis, UnitError> {
        let _ = count;
        Err(UnitError::Unsupported(format!(
            "modal analysis of a `{}` unit",
            self.description().kind
        )))
    }
}

/// Checks the number of input values given to `set_inputs`.
pub fn check_input_count(expected: usize, values: &[f64]) -> Result<(), UnitError> {
    if values.len() == expected {
        Ok(())
    } else {
        Err(UnitError::InputCount {
            expected,
            got: values.len(),
        })
    }
}

/// Checks that every input value is finite, naming the port of the first that is
/// not.
pub fn check_finite_inputs(description: &UnitDescription, values: &[f64]) -> Result<(), UnitError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(UnitError::InvalidInput {
            port: description
                .inputs
                .get(i)
                .map_or_else(|| format!("input {i}"), |p| p.name.clone()),
            value: values[i],
            reason: "not finite".into(),
        }),
    }
}

/// Checks that a parameter is finite and strictly positive.
pub fn require_positive(name: &str, value: f64) -> Result<(), UnitError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(UnitError::parameter(
            name,
            value,
            "expected a finite value > 0",
        ))
    }
}

/// Checks that a parameter is finite and not negative.
pub fn require_non_negative(name: &str, value: f64) -> Result<(), UnitError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(UnitError::parameter(
            name,
            value,
            "expected a finite value >= 0",
        ))
    }
}

/// Checks that a parameter is finite.
pub fn require_finite(name: &str, value: f64) -> Result<(), UnitError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(UnitError::parameter(
            name,
            value,
            "expected a finite number",
        ))
    }
}
