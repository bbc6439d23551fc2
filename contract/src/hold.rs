//! Held inputs: the input values of a unit between two synchronisation points.
//!
//! The master's side ([`Driver`](super::Driver)) owns a unit's [`HeldInputs`] and
//! hands the unit an [`Inputs`] view at every call, so units never store, check or
//! roll back their inputs themselves.

use crate::Hold;

/// Input values at the start and at the end of the current step, and how to fill
/// in between. The start values are the last accepted inputs: the driver saves and
/// restores them with the unit's state.
#[derive(Debug, PartialEq)]
pub struct HeldInputs {
    holds: Vec<Hold>,
    start: Vec<f64>,
    end: Vec<f64>,
}

impl HeldInputs {
    /// Inputs with the given holds, all zero.
    pub fn new(holds: Vec<Hold>) -> HeldInputs {
        let n = holds.len();
        HeldInputs {
            holds,
            start: vec![0.0; n],
            end: vec![0.0; n],
        }
    }

    /// Number of inputs.
    pub fn len(&self) -> usize {
        self.end.len()
    }

    /// Whether the unit has no inputs.
    pub fn is_empty(&self) -> bool {
        self.end.is_empty()
    }

    /// Changes the hold of input `port`.
    pub fn set_hold(&mut self, port: usize, hold: Hold) {
        self.holds[port] = hold;
    }

    /// The hold of every input.
    pub fn holds(&self) -> &[Hold] {
        &self.holds
    }

    /// Sets the values for the end of the next step.
    pub fn set_end(&mut self, values: &[f64]) {
        self.end.copy_from_slice(values);
    }

    /// Moves the end value of input `port` by `delta` (finite differences).
    pub fn nudge_end(&mut self, port: usize, delta: f64) {
        self.end[port] += delta;
    }

    /// Makes the end values the start values too: used at initialisation, where the
    /// inputs are constant.
    pub fn settle(&mut self) {
        self.start.copy_from_slice(&self.end);
    }

    /// Accepts the step: its end values are the start of the next one.
    pub fn advance(&mut self) {
        self.settle();
    }

    /// The start values (the last accepted inputs).
    pub fn start(&self) -> &[f64] {
        &self.start
    }

    /// Sets the start values (restoring a saved step start).
    pub fn set_start(&mut self, values: &[f64]) {
        self.start.copy_from_slice(values);
    }

    /// The end values (the last values set).
    pub fn end(&self) -> &[f64] {
        &self.end
    }

    /// What a unit sees of these inputs.
    pub fn view(&self) -> Inputs<'_> {
        Inputs {
            holds: &self.holds,
            start: &self.start,
            end: &self.end,
        }
    }
}

/// A unit's inputs over one step, read-only: the values at the step's start (last
/// accepted) and end, and each port's hold. During `initialize` start and end are
/// equal.
#[derive(Copy, Clone, Debug)]
pub struct Inputs<'a> {
    holds: &'a [Hold],
    start: &'a [f64],
    end: &'a [f64],
}

impl<'a> Inputs<'a> {
    /// A view of given holds and start and end values (equal lengths): for a
    /// unit that drives another inside itself.
    pub fn new(holds: &'a [Hold], start: &'a [f64], end: &'a [f64]) -> Inputs<'a> {
        debug_assert!(holds.len() == start.len() && start.len() == end.len());
        Inputs { holds, start, end }
    }

    /// Number of inputs.
    pub fn len(&self) -> usize {
        self.end.len()
    }

    /// Whether there are no inputs.
    pub fn is_empty(&self) -> bool {
        self.end.is_empty()
    }

    /// Value of input `port` at fraction `s` in [0, 1] of the step.
    #[inline]
    pub fn at(&self, port: usize, s: f64) -> f64 {
        match self.holds[port] {
            Hold::ZeroOrder => self.end[port],
            Hold::Ramp => self.start[port] + s * (self.end[port] - self.start[port]),
        }
    }

    /// Rate of change of input `port` inside the step (unit per second) for step
    /// length `h` in seconds: zero under a zero-order hold.
    #[inline]
    pub fn rate(&self, port: usize, h: f64) -> f64 {
        match self.holds[port] {
            Hold::ZeroOrder => 0.0,
            Hold::Ramp => (self.end[port] - self.start[port]) / h,
        }
    }

    /// The hold of input `port`.
    pub fn hold(&self, port: usize) -> Hold {
        self.holds[port]
    }

    /// The values at the step's end.
    pub fn end(&self) -> &'a [f64] {
        self.end
    }

    /// The values at the step's start (the last accepted inputs).
    pub fn start(&self) -> &'a [f64] {
        self.start
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_goes_from_last_accepted_to_new_value_and_zero_order_holds_the_new_one() {
        let mut h = HeldInputs::new(vec![Hold::Ramp, Hold::ZeroOrder]);
        h.set_end(&[1.0, 1.0]);
        h.settle();
        h.set_end(&[3.0, 3.0]);
        let v = h.view();
        assert_eq!(v.at(0, 0.0), 1.0);
        assert_eq!(v.at(0, 0.5), 2.0);
        assert_eq!(v.at(0, 1.0), 3.0);
        assert_eq!(v.at(1, 0.0), 3.0);
        assert_eq!(v.rate(0, 0.5), 4.0);
        assert_eq!(v.rate(1, 0.5), 0.0);
        h.advance();
        assert_eq!(h.view().at(0, 0.0), 3.0);
    }
}
