//! Two stateless units that form an algebraic loop (benchmark B6):
//!
//! - [`LinearPair`] (kind `loop_linear_pair`): given `c`, solves
//!   `a + b + c = 0` and `2a - 3b + 2c = 9` for `a` and `b`;
//! - [`SphereClosure`] (kind `loop_sphere`): given `a` and `b`, returns the `c` with
//!   `a^2 + b^2 + c^2 = r^2` (r^2 = 5 by default) on the chosen branch.
//!
//! Coupled, `c` solves `c^2 - 1.8 c + 0.74 = 0`: c = 0.6354 or c = 1.1646. The
//! fixed-point map `c -> sphere(pair(c))` has slope 1.83 at the smaller root, which
//! plain iteration therefore cannot reach; Newton on the interface can.

use crate::contract::{
    Capabilities, HoldSupport, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit,
    UnitDescription, UnitError, require_positive,
};
use serde::Deserialize;

/// Ports of a loop unit: generic inputs, and outputs with the inputs each
/// follows directly (it is stateless: at a communication point too).
fn describe(kind: &str, inputs: &[&str], outputs: &[(&str, &[usize])]) -> UnitDescription {
    UnitDescription {
        kind: kind.into(),
        inputs: inputs
            .iter()
            .map(|n| Port::input(n, PortKind::Generic))
            .collect(),
        outputs: outputs
            .iter()
            .map(|(n, depends_on)| Port::output(n, PortKind::Generic).with_feedthrough(depends_on))
            .collect(),
        capabilities: Capabilities {
            hold: HoldSupport::Fixed,
            ..Capabilities::default()
        },
    }
}

/// Parameters of `loop_linear_pair`: none.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinearPairParams {}

/// Unit A of B6: `a + b + c = 0`, `2a - 3b + 2c = 9`.
pub struct LinearPair {
    description: UnitDescription,
    /// Outputs computed from the last inputs (the whole state).
    outputs: Vec<f64>,
}

impl LinearPair {
    /// Builds the unit.
    pub fn new(_params: LinearPairParams) -> LinearPair {
        LinearPair {
            // b = -9/5 whatever c is (the two equations fix it): only a follows c.
            description: describe("loop_linear_pair", &["c"], &[("a", &[0]), ("b", &[])]),
            outputs: vec![0.0; 2],
        }
    }

    fn solve(&mut self, inputs: &[f64]) {
        self.outputs.copy_from_slice(&Self::values(inputs));
    }

    /// (a, b) for the input c.
    fn values(inputs: &[f64]) -> [f64; 2] {
        let c = inputs[0];
        // [1 1; 2 -3] [a; b] = [-c; 9 - 2c], by Cramer's rule (determinant -5).
        let (r1, r2) = (-c, 9.0 - 2.0 * c);
        let det = 1.0 * -3.0 - 1.0 * 2.0;
        [(r1 * -3.0 - 1.0 * r2) / det, (1.0 * r2 - 2.0 * r1) / det]
    }
}

/// Which root `loop_sphere` returns.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// The root with the larger value.
    #[default]
    Positive,
    /// The root with the smaller value.
    Negative,
}

/// Parameters of `loop_sphere`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereParams {
    /// r^2 in a^2 + b^2 + c^2 = r^2, default 5.
    #[serde(default = "five")]
    pub radius_squared: f64,
    /// `positive` (default) or `negative` root for c.
    #[serde(default)]
    pub branch: Branch,
}

fn five() -> f64 {
    5.0
}

impl Default for SphereParams {
    fn default() -> Self {
        SphereParams {
            radius_squared: 5.0,
            branch: Branch::Positive,
        }
    }
}

/// Unit B of B6: `c` from `a^2 + b^2 + c^2 = r^2`.
pub struct SphereClosure {
    params: SphereParams,
    description: UnitDescription,
    /// Outputs computed from the last inputs (the whole state).
    outputs: Vec<f64>,
}

impl SphereClosure {
    /// Builds the unit; r^2 must be positive.
    pub fn new(params: SphereParams) -> Result<SphereClosure, UnitError> {
        require_positive("radius_squared", params.radius_squared)?;
        Ok(SphereClosure {
            params,
            description: describe("loop_sphere", &["a", "b"], &[("c", &[0, 1])]),
            outputs: vec![0.0; 1],
        })
    }

    fn solve(&mut self, inputs: &[f64]) -> Result<(), UnitError> {
        self.outputs[0] = self.root(inputs)?;
        Ok(())
    }

    /// c on the chosen branch for the inputs (a, b).
    fn root(&self, inputs: &[f64]) -> Result<f64, UnitError> {
        let (a, b) = (inputs[0], inputs[1]);
        let rest = self.params.radius_squared - a * a - b * b;
        if rest.is_nan() || rest < 0.0 {
            return Err(UnitError::InvalidInput {
                port: "a".into(),
                value: a,
                reason: format!(
                    "a^2 + b^2 = {} exceeds radius_squared = {}: no real c (b = {b})",
                    a * a + b * b,
                    self.params.radius_squared
                ),
            });
        }
        let sign = match self.params.branch {
            Branch::Positive => 1.0,
            Branch::Negative => -1.0,
        };
        Ok(sign * rest.sqrt())
    }
}

macro_rules! stateless_unit {
    ($unit:ty, $solve:expr, $evaluate:expr) => {
        impl Unit for $unit {
            fn description(&self) -> &UnitDescription {
                &self.description
            }

            fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
                $solve(self, inputs.end())
            }

            fn do_step(
                &mut self,
                _t: Time,
                _h: Time,
                inputs: Inputs<'_>,
            ) -> Result<StepReport, UnitError> {
                $solve(self, inputs.end())?;
                Ok(StepReport::default())
            }

            /// From the inputs as they are now: stateless, every output
            /// follows its inputs at a communication point too.
            fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
                $evaluate(self, inputs.end(), out)
            }

            fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
                slot.store(&self.outputs);
                Ok(())
            }

            fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
                let saved = slot.load::<Vec<f64>>()?;
                if saved.len() != self.outputs.len() {
                    return Err(UnitError::State(format!(
                        "the saved state has {} outputs, the unit {}",
                        saved.len(),
                        self.outputs.len()
                    )));
                }
                self.outputs.copy_from_slice(&saved);
                Ok(())
            }
        }
    };
}

stateless_unit!(
    LinearPair,
    |u: &mut LinearPair, inputs: &[f64]| {
        u.solve(inputs);
        Ok::<(), UnitError>(())
    },
    |_: &LinearPair, inputs: &[f64], out: &mut [f64]| {
        out.copy_from_slice(&LinearPair::values(inputs))
    }
);
// Outside the sphere there is no c: NaN, which the master reports (the step
// with those inputs has already failed with the reason).
stateless_unit!(
    SphereClosure,
    SphereClosure::solve,
    |u: &SphereClosure, inputs: &[f64], out: &mut [f64]| {
        out[0] = u.root(inputs).unwrap_or(f64::NAN)
    }
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pair_satisfies_both_equations() {
        let mut u = crate::Driver::new(LinearPair::new(LinearPairParams {}));
        u.set_inputs(&[0.7]).unwrap();
        u.initialize(Time::ZERO).unwrap();
        let mut out = [0.0; 2];
        u.outputs(&mut out).unwrap();
        let [a, b] = out;
        assert!((a + b + 0.7).abs() < 1e-14);
        assert!((2.0 * a - 3.0 * b + 1.4 - 9.0).abs() < 1e-14);
    }

    #[test]
    fn the_sphere_refuses_points_outside_it() {
        let mut u = crate::Driver::new(SphereClosure::new(SphereParams::default()).unwrap());
        u.set_inputs(&[2.0, 1.5]).unwrap();
        let err = u.initialize(Time::ZERO).unwrap_err();
        assert!(err.to_string().contains("no real c"), "{err}");
    }
}
