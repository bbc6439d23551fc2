//! The one place that drives a unit through the contract: it owns the unit's held
//! inputs, checks their count and finiteness, applies the hold a scene asks for,
//! enforces the call order, and saves and restores the step's start values with
//! the unit's state. The master's adapter, the FMU entry points, the studies and
//! the tests all step units through it, so no unit repeats this.

use crate::{
    HeldInputs, Hold, HoldSupport, Inputs, ModalAnalysis, StateSlot, StepReport, Time, Unit,
    UnitDescription, UnitError,
};

/// A saved driver state: the unit's state and the inputs accepted at the step's
/// start. Reused from step to step, so saving allocates nothing after the first
/// time for units whose state `clone_from` reuses memory.
#[derive(Default)]
pub struct DriverSlot {
    unit: StateSlot,
    start: Vec<f64>,
    initialized: bool,
    saved: bool,
}

impl DriverSlot {
    /// An empty slot.
    pub fn new() -> DriverSlot {
        DriverSlot::default()
    }

    /// Whether a state has been saved into it.
    pub fn is_empty(&self) -> bool {
        !self.saved
    }

    /// The saved state as bytes: the start inputs, then the unit's state (postcard).
    pub fn to_bytes(&self) -> Result<Vec<u8>, UnitError> {
        if !self.saved {
            return Err(UnitError::State("no state saved".into()));
        }
        let unit = self.unit.to_bytes()?;
        postcard::to_stdvec(&(self.initialized, &self.start, unit))
            .map_err(|e| UnitError::State(format!("serialising: {e}")))
    }

    /// A slot from bytes written by [`DriverSlot::to_bytes`].
    pub fn from_bytes(bytes: &[u8]) -> Result<DriverSlot, UnitError> {
        let (initialized, start, unit): (bool, Vec<f64>, Vec<u8>) = postcard::from_bytes(bytes)
            .map_err(|e| UnitError::State(format!("the serialised state does not decode ({e})")))?;
        Ok(DriverSlot {
            unit: StateSlot::from_bytes(unit),
            start,
            initialized,
            saved: true,
        })
    }
}

/// A unit with its held inputs (see the module docs).
pub struct Driver<U: Unit = Box<dyn Unit>> {
    unit: U,
    held: HeldInputs,
    initialized: bool,
    /// Unit steps per call of `do_step` (multi-rate), 1 by default.
    substeps: u32,
    /// The inputs over one sub-step (scratch).
    sub: HeldInputs,
    sub_values: Vec<f64>,
}

impl<U: Unit> Driver<U> {
    /// Drives `unit`, with each input's hold as its port declares.
    pub fn new(unit: U) -> Driver<U> {
        let holds: Vec<Hold> = unit.description().inputs.iter().map(|p| p.hold).collect();
        Driver {
            unit,
            sub_values: vec![0.0; holds.len()],
            sub: HeldInputs::new(holds.clone()),
            held: HeldInputs::new(holds),
            initialized: false,
            substeps: 1,
        }
    }

    /// Multi-rate stepping (seed 002 sec. 3.4): each `do_step` of h advances the
    /// unit in `n` sub-steps of h / n, its inputs interpolated between the
    /// step's start and end values as each port's hold says (a zero-order hold
    /// keeps the start value). The step must split into whole nanoseconds.
    pub fn set_substeps(&mut self, n: u32) -> Result<(), UnitError> {
        if n == 0 {
            return Err(UnitError::parameter("substeps", 0, "expected at least 1"));
        }
        self.substeps = n;
        Ok(())
    }

    /// Unit steps per `do_step`.
    pub fn substeps(&self) -> u32 {
        self.substeps
    }

    /// The unit's description (ports as the unit declares them; the holds in force
    /// are [`Driver::holds`]).
    pub fn description(&self) -> &UnitDescription {
        self.unit.description()
    }

    /// The unit itself, for kind-specific queries.
    pub fn unit(&self) -> &U {
        &self.unit
    }

    /// The unit, mutable, with the inputs it sees (kind-specific changes after
    /// `initialize` that depend on the inputs, e.g. a beam's initial shape).
    pub fn unit_mut_with_inputs(&mut self) -> (&mut U, Inputs<'_>) {
        (&mut self.unit, self.held.view())
    }

    /// Whether `initialize` has succeeded.
    pub fn is_initialized(&self) -> bool {
        self.initialized
    }

    /// The hold in force for each input.
    pub fn holds(&self) -> &[Hold] {
        self.held.holds()
    }

    /// Chooses the hold of input `port` for the next steps, as far as the unit
    /// honours holds (see [`HoldSupport`]). (The master sets holds before
    /// initialisation; an exported FMU switches between steps as its host does or
    /// does not send input derivatives.)
    pub fn set_hold(&mut self, port: usize, hold: Hold) -> Result<(), UnitError> {
        if port >= self.held.len() {
            return Err(UnitError::Unsupported(format!("no input {port}")));
        }
        let hold = match self.unit.description().capabilities.hold {
            HoldSupport::Any => hold,
            HoldSupport::ZeroOrderOnly => Hold::ZeroOrder,
            HoldSupport::Fixed => {
                return Err(UnitError::Unsupported("changing the input hold".into()));
            }
        };
        self.held.set_hold(port, hold);
        self.sub.set_hold(port, hold);
        Ok(())
    }

    /// Sets the input values: before `initialize` the constant start values,
    /// afterwards the values at the end of the next step. Refuses a wrong count and
    /// non-finite values, naming the port.
    pub fn set_inputs(&mut self, values: &[f64]) -> Result<(), UnitError> {
        if values.len() != self.held.len() {
            return Err(UnitError::InputCount {
                expected: self.held.len(),
                got: values.len(),
            });
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(UnitError::InvalidInput {
                port: self.unit.description().inputs[i].name.clone(),
                value: values[i],
                reason: "not finite".into(),
            });
        }
        self.held.set_end(values);
        Ok(())
    }

    /// The inputs as the unit sees them now.
    pub fn inputs(&self) -> Inputs<'_> {
        self.held.view()
    }

    /// Finds the initial state at `t0` with the inputs held at their set values.
    pub fn initialize(&mut self, t0: Time) -> Result<(), UnitError> {
        self.held.settle();
        self.initialized = false;
        self.unit.initialize(t0, self.held.view())?;
        self.initialized = true;
        Ok(())
    }

    /// Advances from `t` to `t + h`; the step's end inputs become the next start.
    pub fn do_step(&mut self, t: Time, h: Time) -> Result<StepReport, UnitError> {
        if !self.initialized {
            return Err(UnitError::State("do_step called before initialize".into()));
        }
        let report = if self.substeps == 1 {
            self.unit.do_step(t, h, self.held.view())?
        } else {
            self.sub_steps(t, h)?
        };
        self.held.advance();
        Ok(report)
    }

    /// The step in `substeps` sub-steps, inputs interpolated; the last report.
    fn sub_steps(&mut self, t: Time, h: Time) -> Result<StepReport, UnitError> {
        let n = self.substeps;
        let hk = h.split(n).ok_or_else(|| {
            UnitError::Unsupported(format!(
                "{n} sub-steps of a {h} s step: expected a step that splits into whole nanoseconds"
            ))
        })?;
        let mut report = StepReport::default();
        let view = self.held.view();
        let at = |s: f64, out: &mut Vec<f64>| {
            for (p, v) in out.iter_mut().enumerate() {
                *v = view.at(p, s);
            }
        };
        at(0.0, &mut self.sub_values);
        self.sub.set_start(&self.sub_values);
        for k in 0..n {
            at(f64::from(k + 1) / f64::from(n), &mut self.sub_values);
            self.sub.set_end(&self.sub_values);
            report = self
                .unit
                .do_step(t + hk * i64::from(k), hk, self.sub.view())?;
            self.sub.advance();
        }
        Ok(report)
    }

    /// Writes the outputs at the current time into `out` (one per output port).
    pub fn outputs(&self, out: &mut [f64]) -> Result<(), UnitError> {
        let expected = self.unit.description().outputs.len();
        if out.len() != expected {
            return Err(UnitError::State(format!(
                "outputs: {expected} values expected, a buffer of {} given",
                out.len()
            )));
        }
        self.unit.outputs(self.held.view(), out);
        Ok(())
    }

    /// Saves the unit's state and the step's start inputs.
    pub fn save(&self, slot: &mut DriverSlot) -> Result<(), UnitError> {
        self.unit.save_state(&mut slot.unit)?;
        slot.start.clear();
        slot.start.extend_from_slice(self.held.start());
        slot.initialized = self.initialized;
        slot.saved = true;
        Ok(())
    }

    /// Restores a state saved by [`Driver::save`].
    pub fn restore(&mut self, slot: &DriverSlot) -> Result<(), UnitError> {
        if !slot.saved {
            return Err(UnitError::State(
                "restore_state called before save_state".into(),
            ));
        }
        if slot.start.len() != self.held.len() {
            return Err(UnitError::State(format!(
                "the saved state has {} inputs, the unit {}",
                slot.start.len(),
                self.held.len()
            )));
        }
        self.unit.restore_state(&slot.unit)?;
        self.held.set_start(&slot.start);
        self.initialized = slot.initialized;
        Ok(())
    }

    /// Restores `slot` and hints the unit that its next step repeats the last
    /// one ([`Unit::warm_repeat`]); a unit in sub-steps gets no hint (its last
    /// sub-step is not the step repeated).
    pub fn restore_warm(&mut self, slot: &DriverSlot) -> Result<(), UnitError> {
        self.restore(slot)?;
        if self.substeps == 1 {
            self.unit.warm_repeat();
        }
        Ok(())
    }

    /// The unit's interface Jacobian of the last step (see
    /// [`Unit::step_jacobian`]), row-major `outputs x inputs`. Refused when the
    /// unit does not declare it, or steps in sub-steps (its Jacobian would be the
    /// last sub-step's, not the coupling step's).
    pub fn step_jacobian(&mut self, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let d = self.unit.description();
        if !d.capabilities.step_jacobian || self.substeps > 1 {
            return Err(self.unsupported("the step Jacobian"));
        }
        let expected = d.outputs.len() * d.inputs.len();
        if jacobian.len() != expected {
            return Err(UnitError::State(format!(
                "step_jacobian: {expected} values expected, a buffer of {} given",
                jacobian.len()
            )));
        }
        self.unit.step_jacobian(self.held.view(), jacobian)
    }

    /// `what` refused: the unit does not declare it, or steps in sub-steps
    /// (what it would give is its last sub-step's, not the coupling step's).
    fn unsupported(&self, what: &str) -> UnitError {
        let sub_steps = if self.substeps > 1 {
            " in sub-steps"
        } else {
            ""
        };
        UnitError::Unsupported(format!(
            "{what} of a `{}` unit{sub_steps}",
            self.unit.description().kind
        ))
    }

    /// Whether the unit can correct its last step ([`Unit::correct_step`]):
    /// it declares it and steps in one step per coupling step.
    pub fn can_correct_step(&self) -> bool {
        self.unit.description().capabilities.step_correction && self.substeps == 1
    }

    /// The last step taken again with its end inputs moved by `change`, to
    /// first order ([`Unit::correct_step`]): the moved inputs become the
    /// step's end values and the next step's start. Refused as
    /// [`Driver::step_jacobian`] is, and for a unit that does not declare it.
    pub fn correct_step(&mut self, change: &[f64]) -> Result<(), UnitError> {
        if !self.can_correct_step() {
            return Err(self.unsupported("the step correction"));
        }
        if change.len() != self.held.len() {
            return Err(UnitError::InputCount {
                expected: self.held.len(),
                got: change.len(),
            });
        }
        for (p, d) in change.iter().enumerate() {
            self.held.nudge_end(p, *d);
        }
        self.held.advance();
        self.unit.correct_step(self.held.view(), change)
    }

    /// Hints the unit that the next step will be corrected
    /// ([`Unit::defer_step_end`]); only a unit that can correct its step is
    /// told, so one in sub-steps never defers.
    pub fn defer_step_end(&mut self, coupled: &[usize]) {
        if self.can_correct_step() {
            self.unit.defer_step_end(coupled);
        }
    }

    /// Takes a deferred step end ([`Unit::complete_step`]); whether one was
    /// pending.
    pub fn complete_step(&mut self) -> Result<bool, UnitError> {
        self.unit.complete_step()
    }

    /// The same derivative by forward differences of the unit's own step: for
    /// each input `j`, the step from `start` (a state saved at the step's start)
    /// is repeated with end inputs `end` but `end[j] + delta[j]`, and the
    /// outputs' change over `delta[j]` is column `j`; `base` holds the outputs of
    /// the step with `end`. Leaves the unit after the last perturbed step (the
    /// caller restores it). `scratch` takes the perturbed outputs.
    pub fn finite_difference_jacobian(
        &mut self,
        start: &DriverSlot,
        (t, h): (Time, Time),
        (end, delta): (&[f64], &[f64]),
        base: &[f64],
        (jacobian, scratch): (&mut [f64], &mut Vec<f64>),
    ) -> Result<(), UnitError> {
        let n_in = end.len();
        scratch.resize(base.len(), 0.0);
        for j in 0..n_in {
            self.restore(start)?;
            self.set_inputs(end)?;
            self.held.nudge_end(j, delta[j]);
            self.do_step(t, h)?;
            self.outputs(scratch)?;
            for (i, (&y, &y0)) in scratch.iter().zip(base).enumerate() {
                jacobian[i * n_in + j] = (y - y0) / delta[j];
            }
        }
        Ok(())
    }

    /// The first `count` modes about the initial state (after `initialize`).
    pub fn modes(&self, count: usize) -> Result<ModalAnalysis, UnitError> {
        if !self.initialized {
            return Err(UnitError::State("modal analysis before initialize".into()));
        }
        self.unit.modes(count)
    }
}

/// Read access to the unit's own queries (a beam's energies, a cable's static
/// state) through the driver; stepping goes through the driver's methods.
impl<U: Unit> std::ops::Deref for Driver<U> {
    type Target = U;

    fn deref(&self) -> &U {
        &self.unit
    }
}
