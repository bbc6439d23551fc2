//! Artefacts of a control system on a coupled signal (seed 000 sec. 3.3, Fig. 3,
//! Table 2): calibration error (scale), bias, white noise, time delay, signal
//! loss and zero-order hold, in any combination, on one or more channels that
//! travel together (e.g. the x and z components of a measured force).
//!
//! Per synchronisation step, in this order: each channel's sample is
//! `scale * input + bias + noise`; the samples are delayed by `delay` seconds
//! (linear interpolation between samples, so any delay works, fractions of a step
//! included) and, with `lag`, pass a first-order lag (with the delay, an
//! emulated actuator); a signal loss freezes all channels at their last output; a
//! zero-order hold then updates the output only every `hold_period` seconds.
//!
//! Randomness comes from a seeded ChaCha8 generator that is part of the unit's
//! state: repeating a step after rollback draws the same numbers, so the
//! iterations of one step see the same artefacts.

use crate::contract::{
    Capabilities, HoldSupport, Inputs, PortKind, StepReport, Time, Unit, UnitDescription,
    UnitError, require_finite, require_non_negative,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Exp, StandardNormal};
use serde::{Deserialize, Serialize};

/// Parameters (scene kind `artefact`).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ArtefactParams {
    /// Port kind of the signal: force, velocity, displacement, rotation, moment or
    /// generic (sets the ports' unit of measure and the master's tolerance).
    pub quantity: PortKind,
    /// Channel names; ports are `in_<name>` and `out_<name>`. Default ["x", "z"].
    #[serde(default = "super::two_channels")]
    pub channels: Vec<String>,
    /// Calibration factor per channel (default 1).
    #[serde(default)]
    pub scale: Option<Vec<f64>>,
    /// Bias per channel, in the signal's unit (default 0).
    #[serde(default)]
    pub bias: Option<Vec<f64>>,
    /// White-noise variance per channel, in the unit squared (default 0).
    #[serde(default)]
    pub noise_variance: Option<Vec<f64>>,
    /// Time delay (s), >= 0.
    #[serde(default)]
    pub delay: f64,
    /// Time constant of a first-order lag after the delay (s), >= 0; 0: none.
    /// With `delay`, an emulated actuator: y' = (u(t - delay) - y) / lag.
    #[serde(default)]
    pub lag: f64,
    /// Zero-order hold period (s); 0: no hold.
    #[serde(default)]
    pub hold_period: f64,
    /// Probability that a signal loss starts at a synchronisation step, in [0, 1).
    #[serde(default)]
    pub loss_probability: f64,
    /// Or: probability that a signal loss starts within one second, in [0, 1);
    /// a step of h seconds then starts one with probability 1 - (1 - p)^h, so
    /// the loss rate does not depend on the synchronisation step.
    #[serde(default)]
    pub loss_probability_per_second: f64,
    /// Mean duration of a signal loss (s); durations are exponential. (Seed 000's
    /// zeta2 read as seconds: see docs/active-truncation.md.)
    #[serde(default)]
    pub loss_duration_mean: f64,
    /// The other reading of seed 000's zeta2: durations in synchronisation steps
    /// with density zeta2 exp(-zeta2 d), mean 1 / zeta2 steps (1/steps). Give
    /// this or `loss_duration_mean`, not both.
    #[serde(default)]
    pub loss_duration_rate: f64,
    /// Seed of the random generator.
    #[serde(default = "one")]
    pub seed: u64,
}

fn one() -> u64 {
    1
}

crate::state_struct! {
    /// Everything that changes while stepping (cloned on save, so the generator
    /// rewinds on restore).
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct ArtefactState {
        rng: ChaCha8Rng,
        /// Samples after scale, bias and noise: time then one value per channel.
        history: Vec<f64>,
        /// The first-order lag's output per channel.
        lagged: Vec<f64>,
        output: Vec<f64>,
        /// The loss lasts until this time (s); NEG_INFINITY when none.
        lost_until: f64,
        /// Next time the hold samples (s).
        next_hold: f64,
        /// Steps lost and losses started (for statistics).
        lost_steps: u64,
        losses: u64,
    }
}

/// The artefact unit.
pub struct Artefact {
    params: ArtefactParams,
    scale: Vec<f64>,
    bias: Vec<f64>,
    noise_sd: Vec<f64>,
    description: UnitDescription,
    state: ArtefactState,
    delayed: Vec<f64>,
}

/// The signal-loss parameters: probabilities in [0, 1), one of per step or per
/// second, and one duration reading when losses can start.
fn check_losses(params: &ArtefactParams) -> Result<(), UnitError> {
    require_non_negative("loss_duration_mean", params.loss_duration_mean)?;
    if !(0.0..1.0).contains(&params.loss_probability) {
        return Err(UnitError::parameter(
            "loss_probability",
            params.loss_probability,
            "expected a value in [0, 1)",
        ));
    }
    if !(0.0..1.0).contains(&params.loss_probability_per_second) {
        return Err(UnitError::parameter(
            "loss_probability_per_second",
            params.loss_probability_per_second,
            "expected a value in [0, 1)",
        ));
    }
    if params.loss_probability > 0.0 && params.loss_probability_per_second > 0.0 {
        return Err(UnitError::parameter(
            "loss_probability_per_second",
            params.loss_probability_per_second,
            "expected loss_probability (per step) or loss_probability_per_second, not both",
        ));
    }
    require_non_negative("loss_duration_rate", params.loss_duration_rate)?;
    let readings = [params.loss_duration_mean, params.loss_duration_rate];
    let losses = params.loss_probability + params.loss_probability_per_second > 0.0;
    if losses && readings.iter().filter(|&&v| v > 0.0).count() != 1 {
        return Err(UnitError::parameter(
            "loss_duration_mean",
            format!("{readings:?}"),
            "expected one of loss_duration_mean (s) or loss_duration_rate (1/steps) > 0 when losses can start",
        ));
    }
    Ok(())
}

impl Artefact {
    /// Builds the unit; fails with the first bad parameter.
    pub fn new(params: ArtefactParams) -> Result<Artefact, UnitError> {
        let n = params.channels.len();
        let (inputs, outputs) = super::channel_ports(&params.channels, params.quantity)?;
        let per_channel =
            |name: &str, v: &Option<Vec<f64>>, default: f64| per_channel(name, v, default, n);
        let scale = per_channel("scale", &params.scale, 1.0)?;
        let bias = per_channel("bias", &params.bias, 0.0)?;
        let variance = per_channel("noise_variance", &params.noise_variance, 0.0)?;
        for v in &variance {
            require_non_negative("noise_variance", *v)?;
        }
        require_non_negative("delay", params.delay)?;
        require_non_negative("hold_period", params.hold_period)?;
        require_non_negative("lag", params.lag)?;
        check_losses(&params)?;
        Ok(Artefact {
            noise_sd: variance.iter().map(|v| v.sqrt()).collect(),
            scale,
            bias,
            description: UnitDescription {
                kind: "artefact".into(),
                inputs,
                outputs,
                capabilities: Capabilities {
                    hold: HoldSupport::Fixed,
                    ..Capabilities::default()
                },
            },
            state: ArtefactState {
                rng: ChaCha8Rng::seed_from_u64(params.seed),
                history: Vec::new(),
                lagged: vec![0.0; n],
                output: vec![0.0; n],
                lost_until: f64::NEG_INFINITY,
                next_hold: 0.0,
                lost_steps: 0,
                losses: 0,
            },
            delayed: vec![0.0; n],
            params,
        })
    }

    /// Steps spent in a loss and losses started so far.
    pub fn loss_statistics(&self) -> (u64, u64) {
        (self.state.lost_steps, self.state.losses)
    }

    fn channels(&self) -> usize {
        self.scale.len()
    }

    /// Appends the sample at time t from the current inputs (with noise).
    fn push_sample(&mut self, inputs: &[f64], t: f64, noise: bool) {
        let s = &mut self.state;
        s.history.push(t);
        for (c, input) in inputs.iter().enumerate().take(self.scale.len()) {
            let mut v = self.scale[c] * input + self.bias[c];
            if noise && self.noise_sd[c] > 0.0 {
                let z: f64 = StandardNormal.sample(&mut s.rng);
                v += self.noise_sd[c] * z;
            }
            s.history.push(v);
        }
    }

    /// The samples delayed to time t, into `self.delayed`; drops samples no longer
    /// needed.
    fn delayed_at(&mut self, t: f64) {
        let stride = 1 + self.channels();
        let h = &mut self.state.history;
        let target = t - self.params.delay;
        let samples = h.len() / stride;
        // Index of the last sample at or before the target.
        let mut i = 0;
        while i + 1 < samples && h[(i + 1) * stride] <= target {
            i += 1;
        }
        for c in 0..stride - 1 {
            let (t0, v0) = (h[i * stride], h[i * stride + 1 + c]);
            self.delayed[c] = if i + 1 < samples && target > t0 {
                let (t1, v1) = (h[(i + 1) * stride], h[(i + 1) * stride + 1 + c]);
                v0 + (v1 - v0) * (target - t0) / (t1 - t0)
            } else {
                v0
            };
        }
        if i > 0 {
            h.drain(..i * stride);
        }
    }
}

/// One finite value per channel (`n` of them), or `default` for every channel.
fn per_channel(
    name: &str,
    v: &Option<Vec<f64>>,
    default: f64,
    n: usize,
) -> Result<Vec<f64>, UnitError> {
    match v {
        None => Ok(vec![default; n]),
        Some(v) if v.len() == n => {
            for x in v {
                require_finite(name, *x)?;
            }
            Ok(v.clone())
        }
        Some(v) => Err(UnitError::parameter(
            name,
            format!("{v:?}"),
            &format!("expected one value per channel ({n})"),
        )),
    }
}

impl Unit for Artefact {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let t = t0.as_secs();
        self.state.rng = ChaCha8Rng::seed_from_u64(self.params.seed);
        self.state.history.clear();
        self.state.lost_until = f64::NEG_INFINITY;
        self.state.next_hold = t + self.params.hold_period;
        self.state.lost_steps = 0;
        self.state.losses = 0;
        self.push_sample(inputs.end(), t, false);
        self.delayed_at(t);
        self.state.lagged.copy_from_slice(&self.delayed);
        self.state.output.copy_from_slice(&self.delayed);
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let t_end = (t + h).as_secs();
        self.push_sample(inputs.end(), t_end, true);
        self.delayed_at(t_end);
        if self.params.lag > 0.0 {
            // Exact for an input held over the step.
            let a = 1.0 - (-h.as_secs() / self.params.lag).exp();
            for (y, u) in self.state.lagged.iter_mut().zip(self.delayed.iter_mut()) {
                *y += a * (*u - *y);
                *u = *y;
            }
        }
        let p = &self.params;
        let s = &mut self.state;
        let per_step = if p.loss_probability_per_second > 0.0 {
            1.0 - (1.0 - p.loss_probability_per_second).powf(h.as_secs())
        } else {
            p.loss_probability
        };
        if per_step > 0.0 && t_end >= s.lost_until {
            let u: f64 = s.rng.random();
            if u < per_step {
                // Seconds (mean loss_duration_mean), or steps of this length
                // (mean 1 / loss_duration_rate).
                let (rate, seconds_per_unit) = if p.loss_duration_rate > 0.0 {
                    (p.loss_duration_rate, h.as_secs())
                } else {
                    (1.0 / p.loss_duration_mean, 1.0)
                };
                let exp = Exp::new(rate)
                    .map_err(|e| UnitError::Numerical(format!("loss duration law: {e}")))?;
                s.lost_until = t_end + exp.sample(&mut s.rng) * seconds_per_unit;
                s.losses += 1;
            }
        }
        let lost = t_end < s.lost_until;
        if lost {
            s.lost_steps += 1;
        }
        let hold_due = p.hold_period <= 0.0 || t_end + 1e-12 >= s.next_hold;
        if hold_due && p.hold_period > 0.0 {
            while s.next_hold <= t_end + 1e-12 {
                s.next_hold += p.hold_period;
            }
        }
        if !lost && hold_due {
            s.output.copy_from_slice(&self.delayed);
        }
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        out.copy_from_slice(&self.state.output);
    }

    slender_contract::state_in_field!(state: ArtefactState);
}
