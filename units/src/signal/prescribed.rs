//! A source unit whose outputs are a function of time only (a prescribed load or
//! motion): no inputs, its state the time of its outputs. The kinds
//! `characteristic_load` and `signal` are this unit over their parameters.

use crate::contract::{Capabilities, StepReport, Unit, UnitDescription, UnitError};
use crate::contract::{Inputs, Port, StateSlot, Time};

/// What a prescribed source needs from its parameters.
pub trait Prescribed: Send {
    /// The scene kind, e.g. "signal".
    const KIND: &'static str;
    /// Refuses parameters that cannot give finite outputs, naming the key.
    fn validate(&self) -> Result<(), UnitError>;
    /// The output ports (no inputs).
    fn outputs(&self) -> Vec<Port>;
    /// The outputs at time t (s), one per output port.
    fn write(&self, t: f64, out: &mut [f64]);
}

/// The source unit over parameters `P`.
pub struct Source<P> {
    params: P,
    description: UnitDescription,
    time: f64,
}

impl<P: Prescribed> Source<P> {
    /// Builds the source; fails with the first bad parameter.
    pub fn new(params: P) -> Result<Source<P>, UnitError> {
        params.validate()?;
        Ok(Source {
            description: UnitDescription {
                kind: P::KIND.into(),
                inputs: Vec::new(),
                outputs: params.outputs(),
                capabilities: Capabilities::default(),
            },
            params,
            time: 0.0,
        })
    }

    /// The parameters it was built with.
    pub fn params(&self) -> &P {
        &self.params
    }
}

impl<P: Prescribed> Unit for Source<P> {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.time = t0.as_secs();
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, _inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.time = (t + h).as_secs();
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        self.params.write(self.time, out);
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.time);
        Ok(())
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.time = *slot.load::<f64>()?;
        Ok(())
    }
}
