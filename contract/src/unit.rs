//! The unit contract: what every substructure model offers the master.
//!
//! # Call order
//! A unit is always driven through a [`Driver`](super::Driver), which owns its held
//! inputs (count, finiteness, hold, rollback of the step's start values) and calls
//! the unit in this order, and nothing else:
//! 1. `description`, any number of times;
//! 2. `initialize(t0, inputs)`: the unit finds its initial state (static
//!    equilibrium, initial conditions) with the inputs held constant. It may be
//!    repeated while the master settles the initial values of a loop;
//! 3. per synchronisation step: `do_step(t, h, inputs)` with the inputs' values at
//!    the step's start and END, then `outputs(inputs, out)` (values at `t + h`);
//! 4. `save_state` before a step and `restore_state` to repeat it, when the unit
//!    declares rollback. Restoring then stepping with the same inputs must give
//!    bit-identical outputs.
//!
//! Errors are values: a unit never panics on bad input or a failed solve.

use crate::StateSlot;
use crate::Time;
use crate::{Causality, Inputs, Port, PortKind};
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
    /// Which input holds the unit honours.
    pub hold: HoldSupport,
    /// `step_jacobian` gives the derivative of the outputs after a step with
    /// respect to that step's end inputs; without it a master that needs the
    /// derivative takes it by finite differences from a rolled-back state.
    pub step_jacobian: bool,
    /// `correct_step` moves the last step's end state to first order in a
    /// change of its end inputs, by the derivatives `step_jacobian` solved for:
    /// a master may then close a step after one sweep (`newton.one_sweep`).
    pub step_correction: bool,
}

/// Which input holds a unit honours (the driver applies a scene's `hold` by it).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum HoldSupport {
    /// Ramp or zero-order, per input.
    Any,
    /// Only zero-order: a requested ramp is held instead (FMUs that cannot
    /// interpolate inputs).
    ZeroOrderOnly,
    /// The unit reads only end values; choosing a hold is refused.
    Fixed,
}

impl Default for Capabilities {
    /// What native units offer: rollback and variable steps, values only.
    fn default() -> Self {
        Capabilities {
            rollback: true,
            variable_step: true,
            output_derivative_order: 0,
            hold: HoldSupport::Any,
            step_jacobian: false,
            step_correction: false,
        }
    }
}

/// The static description of a unit: its kind, its ports and its capabilities.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitDescription {
    /// Model kind as named in scene files, e.g. "oscillator".
    pub kind: String,
    /// Input ports, in the order of the input values.
    pub inputs: Vec<Port>,
    /// Output ports, in the order of `outputs` values.
    pub outputs: Vec<Port>,
    /// What the unit offers beyond stepping (rollback, holds, Jacobians).
    pub capabilities: Capabilities,
}

impl UnitDescription {
    /// Index of the input called `name` (by its name or an alias).
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|p| p.answers_to(name))
    }

    /// The inputs that are loads (forces and moments), in port order.
    pub fn load_inputs(&self) -> Vec<usize> {
        let is_load = |p: &Port| matches!(p.kind, PortKind::Force | PortKind::Moment);
        (0..self.inputs.len())
            .filter(|&i| is_load(&self.inputs[i]))
            .collect()
    }

    /// [`Unit::static_inputs`] of a unit that solves its statics under its
    /// load inputs when it has a `static_start`: those inputs, else none.
    pub fn static_load_inputs(&self, static_start: bool) -> Vec<usize> {
        if static_start {
            self.load_inputs()
        } else {
            Vec::new()
        }
    }

    /// Index of the output called `name` (by its name or an alias).
    pub fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs.iter().position(|p| p.answers_to(name))
    }

    /// The port called `name` with the given causality.
    pub fn port(&self, causality: Causality, name: &str) -> Option<&Port> {
        match causality {
            Causality::Input => self.inputs.iter().find(|p| p.answers_to(name)),
            Causality::Output => self.outputs.iter().find(|p| p.answers_to(name)),
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
        /// The parameter's key, as the scene names it.
        name: String,
        /// Its value as written.
        value: String,
        /// What was expected, in the scene author's words.
        expected: String,
    },
    /// An input value cannot be used (e.g. NaN or outside the model's domain).
    #[error("input `{port}` = {value}: {reason}")]
    InvalidInput {
        /// The input port's name.
        port: String,
        /// The value it was given.
        value: f64,
        /// Why it cannot be used.
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
    /// The unit asked to end the simulation (an FMU's `terminateSimulation`,
    /// FMI 2.0's `fmi2Terminated`): not a failure; the master's caller ends
    /// the run at its last completed step.
    #[error("asked to end the simulation: {0}")]
    EndRequested(String),
    /// The driver was given the wrong number of input values.
    #[error("expected {expected} input values, got {got}")]
    InputCount {
        /// The unit's input ports.
        expected: usize,
        /// The values given.
        got: usize,
    },
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

/// A quantity along a unit, one value per node or per element (node
/// positions, the tension along the line): what an FMI 3.0 export declares as
/// an array output. Its length is fixed when the unit is built.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    /// Name, e.g. "tension".
    pub name: String,
    /// SI unit of measure, e.g. "N" ("" for dimensionless).
    pub unit: String,
    /// What the values are and where (e.g. "per element, from the first end").
    pub description: String,
    /// Number of values.
    pub len: usize,
    /// What it has one value for: its length follows the unit's mesh (an
    /// FMI 3.0 export sizes its array by the structural parameter counting
    /// these).
    pub per: FieldSupport,
}

/// What a field has one value for.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum FieldSupport {
    /// One value per node of the unit's mesh.
    Node,
    /// One value per element of the unit's mesh.
    Element,
}

impl FieldSupport {
    /// What it counts, in the plural ("nodes", "elements").
    pub fn counted(self) -> &'static str {
        match self {
            FieldSupport::Node => "nodes",
            FieldSupport::Element => "elements",
        }
    }
}

impl Field {
    /// A field called `name` in `unit` with one value per node (`nodes`).
    pub fn per_node(name: &str, unit: &str, description: &str, nodes: usize) -> Field {
        Field::new(name, unit, description, nodes, FieldSupport::Node)
    }

    /// A field called `name` in `unit` with one value per element
    /// (`elements`).
    pub fn per_element(name: &str, unit: &str, description: &str, elements: usize) -> Field {
        Field::new(name, unit, description, elements, FieldSupport::Element)
    }

    fn new(name: &str, unit: &str, description: &str, len: usize, per: FieldSupport) -> Field {
        Field {
            name: name.to_owned(),
            unit: unit.to_owned(),
            description: description.to_owned(),
            len,
            per,
        }
    }
}

/// Modes of a structural unit and the node positions (m) they refer to.
#[derive(Clone, Debug, PartialEq)]
pub struct ModalAnalysis {
    /// The nodes' positions (x, z; m) the mode shapes are given at.
    pub positions: Vec<[f64; 2]>,
    /// Longest period first.
    pub modes: Vec<Mode>,
}

/// A substructure model with an FMI-like stepping contract (see the module docs for
/// the call order).
pub trait Unit: Send {
    /// Kind, ports and capabilities; constant over the unit's life.
    fn description(&self) -> &UnitDescription;

    /// Finds the initial state at `t0` with the inputs held at their values (start
    /// and end are equal). Each call starts again from the parameters: the master
    /// may call it several times with different inputs while it makes looped initial
    /// values consistent.
    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError>;

    /// Advances from `t` to `t + h`, filling the inputs inside the step as their
    /// holds say (`inputs.at(port, s)`).
    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError>;

    /// Writes the output values at the current time into `out` (one per output
    /// port). `inputs` are the current ones, for outputs with direct feedthrough.
    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]);

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

    /// A hint from a master: the next `do_step` repeats the step last taken,
    /// from the same start (restored), with inputs that changed little; the
    /// unit may start its solve from that attempt's solution (the result is
    /// the same to its own solver's tolerance, not to the bit). Default: none.
    fn warm_repeat(&mut self) {}

    /// The inputs whose values at `initialize` set the unit's static state:
    /// the end loads (forces and moments) a static start is solved under (a
    /// cable's top force, a chord's loaded end). The master checks after the first step that the
    /// other side still reports them (issue 30: a section that solved its
    /// statics under a load the other side then leaves has started off its
    /// equilibrium). Default: none.
    fn static_inputs(&self) -> Vec<usize> {
        Vec::new()
    }

    /// The interface Jacobian of the last `do_step` (units that declare
    /// `Capabilities::step_jacobian`): the derivative of every output after the
    /// step with respect to every input's value at the step's END (its start
    /// value fixed), row-major, `outputs x inputs`, into `jacobian`. Called
    /// after `do_step` (and `outputs`), before any restore; computed from what
    /// the step already has (its factorised matrix: one back-substitution per
    /// input), so it costs a fraction of a step. Others return `Unsupported`.
    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let _ = (inputs, jacobian);
        Err(UnitError::Unsupported(format!(
            "the step Jacobian of a `{}` unit",
            self.description().kind
        )))
    }

    /// The last `do_step` with its end inputs moved by `change` (one value per
    /// input, in the inputs' units), to first order: the unit moves its end
    /// state by the derivatives its `step_jacobian` solved for, so that its
    /// outputs move by that Jacobian times `change`, and brings what it keeps
    /// of the step's end (forces, reactions, energy ledger) to the moved state.
    /// `inputs` are the step's corrected end inputs. Called after
    /// `step_jacobian` on the same step, by units that declare
    /// `Capabilities::step_correction`; others return `Unsupported`.
    fn correct_step(&mut self, inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
        let _ = (inputs, change);
        Err(UnitError::Unsupported(format!(
            "the step correction of a `{}` unit",
            self.description().kind
        )))
    }

    /// A hint from a master that closes the next step by `correct_step`
    /// (`newton.one_sweep`): the unit may leave the end of that step partly
    /// taken, with only `coupled` (the output indices the master reads before
    /// correcting) brought to the step's end, since the correction takes the
    /// end again at the moved state. The master then calls `correct_step` or
    /// `complete_step` before it reads the other outputs or saves the state;
    /// a restore drops a pending end. Default: ignored.
    fn defer_step_end(&mut self, coupled: &[usize]) {
        let _ = coupled;
    }

    /// Takes the end of a step left pending by [`Unit::defer_step_end`], at
    /// the state the step reached; returns whether one was pending (the
    /// outputs changed). Default: none is ever pending.
    fn complete_step(&mut self) -> Result<bool, UnitError> {
        Ok(false)
    }

    /// The quantities along the unit it can report (constant over its life,
    /// known before `initialize`). Default: none.
    fn fields(&self) -> Vec<Field> {
        Vec::new()
    }

    /// An estimate of the local error of the last `do_step` in the unit's
    /// displacements (m): the largest over its translational degrees of
    /// freedom, for a master that chooses its step from it
    /// (`[master.adaptive] displacement`). Default: `None` (no estimate).
    fn local_error(&self) -> Option<f64> {
        None
    }

    /// The current values of field `index` of [`Unit::fields`] into `out`
    /// (its length); after `initialize`. Default: `Unsupported`.
    fn field_values(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        let _ = out;
        Err(UnitError::Unsupported(format!(
            "field {index} of a `{}` unit",
            self.description().kind
        )))
    }
}

/// Checks that a parameter is finite and strictly positive.
pub fn require_positive(name: &str, value: f64) -> Result<(), UnitError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(UnitError::parameter(
            name,
            number(value),
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
            number(value),
            "expected a finite value >= 0",
        ))
    }
}

/// Checks that a parameter lies in the closed range [`low`, `high`] (`unit` names
/// its unit of measure in the message), for parameters where "finite and positive"
/// would still admit nonsense that overflows the numerics.
pub fn require_in_range(
    name: &str,
    value: f64,
    low: f64,
    high: f64,
    unit: &str,
) -> Result<(), UnitError> {
    if value.is_finite() && (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(UnitError::parameter(
            name,
            number(value),
            &format!(
                "expected a value from {} to {} {unit}",
                number(low),
                number(high)
            ),
        ))
    }
}

/// A number as people write it: plain when moderate, in e-notation when very
/// large or small (so 1e125 does not print 126 digits).
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-3..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Checks a unit's state after a step: an error naming `quantity` (what the
/// values are, in the user's words) and the first non-finite entry, where one
/// overflowed or became NaN (extreme inputs or parameters, an unstable step),
/// so that a run stops with the unit, time and quantity rather than carrying
/// NaN on in values no output shows.
pub fn require_finite_state(quantity: &str, values: &[f64]) -> Result<(), UnitError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(k) => Err(UnitError::Numerical(format!(
            "{quantity} became non-finite ({} at entry {k} of {}): an overflow from extreme inputs or parameters, or an unstable step",
            values[k],
            values.len()
        ))),
    }
}

/// Checks that a unit can give its step Jacobian now (`ready`: it has
/// stepped and not been rolled back since); the error names the unit as
/// `what` ("a beam").
pub fn require_step_jacobian_ready(ready: bool, what: &str) -> Result<(), UnitError> {
    match ready {
        true => Ok(()),
        false => Err(UnitError::Unsupported(format!(
            "the step Jacobian of {what} before any step or after a rollback"
        ))),
    }
}

/// Checks that a parameter is finite.
pub fn require_finite(name: &str, value: f64) -> Result<(), UnitError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(UnitError::parameter(
            name,
            number(value),
            "expected a finite number",
        ))
    }
}

/// A boxed unit and a unit borrowed mutably are units too, so a
/// [`Driver`](super::Driver) holds a concrete unit, a `Box<dyn Unit>` or a `&mut dyn Unit`.
macro_rules! forward_unit {
    ($($pointer:ty),*) => {$(
        impl<U: Unit + ?Sized> Unit for $pointer {
            fn description(&self) -> &UnitDescription {
                (**self).description()
            }

            fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
                (**self).initialize(t0, inputs)
            }

            fn do_step(
                &mut self,
                t: Time,
                h: Time,
                inputs: Inputs<'_>,
            ) -> Result<StepReport, UnitError> {
                (**self).do_step(t, h, inputs)
            }

            fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
                (**self).outputs(inputs, out)
            }

            fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
                (**self).save_state(slot)
            }

            fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
                (**self).restore_state(slot)
            }

            fn modes(&self, count: usize) -> Result<ModalAnalysis, UnitError> {
                (**self).modes(count)
            }

            fn step_jacobian(
                &mut self,
                inputs: Inputs<'_>,
                jacobian: &mut [f64],
            ) -> Result<(), UnitError> {
                (**self).step_jacobian(inputs, jacobian)
            }

            fn warm_repeat(&mut self) {
                (**self).warm_repeat()
            }

            fn correct_step(&mut self, inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
                (**self).correct_step(inputs, change)
            }

            fn defer_step_end(&mut self, coupled: &[usize]) {
                (**self).defer_step_end(coupled)
            }

            fn complete_step(&mut self) -> Result<bool, UnitError> {
                (**self).complete_step()
            }

            fn static_inputs(&self) -> Vec<usize> {
                (**self).static_inputs()
            }

            fn fields(&self) -> Vec<Field> {
                (**self).fields()
            }

            fn local_error(&self) -> Option<f64> {
                (**self).local_error()
            }

            fn field_values(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
                (**self).field_values(index, out)
            }
        }
    )*};
}

forward_unit!(Box<U>, &mut U);
