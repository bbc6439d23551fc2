//! Actuator delay compensation (seed 002 sec. 3.4; Horiuchi et al. 1996): a
//! command is sent `lead` seconds ahead of the time it is computed for, by the
//! polynomial through its last `order + 1` values at the synchronisation steps,
//! so an actuator that lags by about `lead` puts the command where it belongs.
//! A pure delay tau adds the negative damping k tau to a spring tested through
//! it; the prediction removes it (tests/tests/delay_compensation.rs).
//!
//! Kind `delay_compensation`: inputs `in_<channel>`, outputs `out_<channel>`
//! (direct feedthrough); before `order + 1` samples exist the polynomial uses
//! the ones there are.

use crate::contract::{
    Capabilities, HoldSupport, Inputs, PortKind, StepReport, Time, Unit, UnitDescription,
    UnitError, require_non_negative,
};
use serde::Deserialize;

/// Parameters (scene kind `delay_compensation`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationParams {
    /// Port kind of the command (displacement, velocity, force, ...).
    pub quantity: PortKind,
    /// Channel names (default `["x", "z"]`).
    #[serde(default = "super::two_channels")]
    pub channels: Vec<String>,
    /// How far ahead the command is predicted (s), >= 0: the actuator's delay
    /// plus its lag's time constant.
    pub lead: f64,
    /// Degree of the extrapolating polynomial, 0 to 3 (default 2).
    #[serde(default = "two")]
    pub order: usize,
}

fn two() -> usize {
    2
}

crate::state_struct! {
    /// The last samples: time then one value per channel, oldest first.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct CompensationState {
        samples: Vec<f64>,
        output: Vec<f64>,
    }
}

/// The compensation unit.
pub struct Compensation {
    params: CompensationParams,
    description: UnitDescription,
    state: CompensationState,
}

impl Compensation {
    /// Builds the unit; fails with the first bad parameter.
    pub fn new(params: CompensationParams) -> Result<Compensation, UnitError> {
        let n = params.channels.len();
        let (inputs, outputs) = super::channel_ports(&params.channels, params.quantity)?;
        require_non_negative("lead", params.lead)?;
        if params.order > 3 {
            return Err(UnitError::parameter(
                "order",
                params.order,
                "expected 0 to 3",
            ));
        }
        Ok(Compensation {
            description: UnitDescription {
                kind: "delay_compensation".into(),
                inputs,
                outputs,
                capabilities: Capabilities {
                    hold: HoldSupport::Fixed,
                    ..Capabilities::default()
                },
            },
            state: CompensationState {
                samples: Vec::with_capacity((n + 1) * (params.order + 2)),
                output: vec![0.0; n],
            },
            params,
        })
    }

    /// Adds the sample at `t` (keeping the last `order + 1`) and predicts.
    fn sample(&mut self, t: f64, values: &[f64]) {
        let stride = 1 + self.params.channels.len();
        let s = &mut self.state;
        s.samples.push(t);
        s.samples.extend_from_slice(&values[..stride - 1]);
        let keep = (self.params.order + 1) * stride;
        if s.samples.len() > keep {
            s.samples.drain(..s.samples.len() - keep);
        }
        let count = s.samples.len() / stride;
        let target = t + self.params.lead;
        for c in 0..stride - 1 {
            // Lagrange's form through the kept samples.
            let mut value = 0.0;
            for i in 0..count {
                let ti = s.samples[i * stride];
                let weight: f64 = (0..count)
                    .filter(|&j| j != i)
                    .map(|j| {
                        let tj = s.samples[j * stride];
                        (target - tj) / (ti - tj)
                    })
                    .product();
                value += weight * s.samples[i * stride + 1 + c];
            }
            s.output[c] = value;
        }
    }
}

impl Unit for Compensation {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.state.samples.clear();
        self.sample(t0.as_secs(), inputs.end());
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.sample((t + h).as_secs(), inputs.end());
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        out.copy_from_slice(&self.state.output);
    }

    slender_contract::state_in_field!(state: CompensationState);
}
