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

use crate::port::{Port, PortKind};
use crate::state::StateSlot;
use crate::time::Time;
use crate::unit::{
    Capabilities, StepReport, Unit, UnitDescription, UnitError, check_input_count, require_positive,
};
use serde::Deserialize;

/// Values of a stateless unit: its last inputs and the outputs computed from them.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(into = "ValueLists", try_from = "ValueLists")]
struct Values<const I: usize, const O: usize> {
    inputs: [f64; I],
    outputs: [f64; O],
}

/// `Values` as lists, for serialisation (serde has no const-generic arrays).
#[derive(serde::Serialize, serde::Deserialize)]
struct ValueLists {
    inputs: Vec<f64>,
    outputs: Vec<f64>,
}

impl<const I: usize, const O: usize> From<Values<I, O>> for ValueLists {
    fn from(v: Values<I, O>) -> Self {
        ValueLists {
            inputs: v.inputs.to_vec(),
            outputs: v.outputs.to_vec(),
        }
    }
}

impl<const I: usize, const O: usize> TryFrom<ValueLists> for Values<I, O> {
    type Error = String;

    fn try_from(v: ValueLists) -> Result<Self, String> {
        let lengths = || format!("expected {I} inputs and {O} outputs");
        Ok(Values {
            inputs: v.inputs.try_into().map_err(|_| lengths())?,
            outputs: v.outputs.try_into().map_err(|_| lengths())?,
        })
    }
}

impl<const I: usize, const O: usize> Default for Values<I, O> {
    fn default() -> Self {
        Values {
            inputs: [0.0; I],
            outputs: [0.0; O],
        }
    }
}

fn describe(kind: &str, inputs: &[&str], outputs: &[&str]) -> UnitDescription {
    let all_inputs: Vec<usize> = (0..inputs.len()).collect();
    UnitDescription {
        kind: kind.into(),
        inputs: inputs
            .iter()
            .map(|n| Port::input(n, PortKind::Generic))
            .collect(),
        outputs: outputs
            .iter()
            .map(|n| Port::output(n, PortKind::Generic).with_feedthrough(&all_inputs))
            .collect(),
        capabilities: Capabilities::default(),
    }
}

/// Parameters of `loop_linear_pair`: none.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinearPairParams {}

/// Unit A of B6: `a + b + c = 0`, `2a - 3b + 2c = 9`.
pub struct LinearPair {
    description: UnitDescription,
    values: Values<1, 2>,
}

impl LinearPair {
    /// Builds the unit.
    pub fn new(_params: LinearPairParams) -> LinearPair {
        LinearPair {
            description: describe("loop_linear_pair", &["c"], &["a", "b"]),
            values: Values::default(),
        }
    }

    fn solve(&mut self) {
        let c = self.values.inputs[0];
        // [1 1; 2 -3] [a; b] = [-c; 9 - 2c], by Cramer's rule (determinant -5).
        let (r1, r2) = (-c, 9.0 - 2.0 * c);
        let det = 1.0 * -3.0 - 1.0 * 2.0;
        self.values.outputs = [(r1 * -3.0 - 1.0 * r2) / det, (1.0 * r2 - 2.0 * r1) / det];
    }
}

/// Which root `loop_sphere` returns.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    #[default]
    Positive,
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
    values: Values<2, 1>,
}

impl SphereClosure {
    /// Builds the unit; r^2 must be positive.
    pub fn new(params: SphereParams) -> Result<SphereClosure, UnitError> {
        require_positive("radius_squared", params.radius_squared)?;
        Ok(SphereClosure {
            params,
            description: describe("loop_sphere", &["a", "b"], &["c"]),
            values: Values::default(),
        })
    }

    fn solve(&mut self) -> Result<(), UnitError> {
        let [a, b] = self.values.inputs;
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
        self.values.outputs = [sign * rest.sqrt()];
        Ok(())
    }
}

macro_rules! stateless_unit {
    ($unit:ty, $inputs:literal, $outputs:literal, $solve:expr) => {
        impl Unit for $unit {
            fn description(&self) -> &UnitDescription {
                &self.description
            }

            fn set_inputs(&mut self, values: &[f64]) -> Result<(), UnitError> {
                check_input_count($inputs, values)?;
                self.values.inputs.copy_from_slice(values);
                Ok(())
            }

            fn initialize(&mut self, _t0: Time) -> Result<(), UnitError> {
                $solve(self)
            }

            fn do_step(&mut self, _t: Time, _h: Time) -> Result<StepReport, UnitError> {
                $solve(self)?;
                Ok(StepReport::default())
            }

            fn outputs(&self, out: &mut [f64]) {
                out.copy_from_slice(&self.values.outputs);
            }

            fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
                slot.store(&self.values);
                Ok(())
            }

            fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
                self.values = slot.load::<Values<$inputs, $outputs>>()?.into_owned();
                Ok(())
            }
        }
    };
}

stateless_unit!(LinearPair, 1, 2, |u: &mut LinearPair| {
    u.solve();
    Ok::<(), UnitError>(())
});
stateless_unit!(SphereClosure, 2, 1, SphereClosure::solve);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pair_satisfies_both_equations() {
        let mut u = LinearPair::new(LinearPairParams {});
        u.set_inputs(&[0.7]).unwrap();
        u.do_step(Time::ZERO, Time::from_nanos(1)).unwrap();
        let mut out = [0.0; 2];
        u.outputs(&mut out);
        let [a, b] = out;
        assert!((a + b + 0.7).abs() < 1e-14);
        assert!((2.0 * a - 3.0 * b + 1.4 - 9.0).abs() < 1e-14);
    }

    #[test]
    fn the_sphere_refuses_points_outside_it() {
        let mut u = SphereClosure::new(SphereParams::default()).unwrap();
        u.set_inputs(&[2.0, 1.5]).unwrap();
        let err = u.do_step(Time::ZERO, Time::from_nanos(1)).unwrap_err();
        assert!(err.to_string().contains("no real c"), "{err}");
    }
}
