//! Held inputs: the input values of a unit between two synchronisation points.

use crate::port::Hold;

/// Input values at the start and at the end of the current step, and how to fill in
/// between. Units embed it in their saved state: the start values are the last
/// accepted inputs, so rollback must restore them.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HeldInputs {
    holds: Vec<Hold>,
    start: Vec<f64>,
    end: Vec<f64>,
}

impl HeldInputs {
    /// `n` inputs, all with the same hold, all zero.
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

    /// Sets the values for the end of the next step.
    pub fn set_end(&mut self, values: &[f64]) {
        self.end.copy_from_slice(values);
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
    pub fn rate(&self, port: usize, h: f64) -> f64 {
        match self.holds[port] {
            Hold::ZeroOrder => 0.0,
            Hold::Ramp => (self.end[port] - self.start[port]) / h,
        }
    }

    /// The end values (the last values set).
    pub fn end(&self) -> &[f64] {
        &self.end
    }
}

impl Clone for HeldInputs {
    fn clone(&self) -> Self {
        HeldInputs {
            holds: self.holds.clone(),
            start: self.start.clone(),
            end: self.end.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.holds.clone_from(&source.holds);
        self.start.clone_from(&source.start);
        self.end.clone_from(&source.end);
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
        assert_eq!(h.at(0, 0.0), 1.0);
        assert_eq!(h.at(0, 0.5), 2.0);
        assert_eq!(h.at(0, 1.0), 3.0);
        assert_eq!(h.at(1, 0.0), 3.0);
        assert_eq!(h.rate(0, 0.5), 4.0);
        assert_eq!(h.rate(1, 0.5), 0.0);
        h.advance();
        assert_eq!(h.at(0, 0.0), 3.0);
    }
}
