//! A prescribed signal as a source unit (kind `signal`): an offset, a sum of
//! sines (given, or a sea state's) faded in, and steps, evaluated at the end of every step. Studies drive
//! the unit they measure with it (the span studies' end motions), so the motion
//! is part of the scene, not of the study's code.

use super::prescribed::{Prescribed, Source};
use crate::contract::{
    Port, PortKind, UnitError, require_finite, require_non_negative, require_positive,
};
use crate::sea::SeaState;
use serde::Deserialize;

pub use super::sine::Sine;

/// How the sines start.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FadeShape {
    /// `1 - exp(-t / time)`.
    Exponential,
    /// `x^3 (10 - 15 x + 6 x^2)`, x = min(t / time, 1): smooth to the second
    /// derivative, complete at `time`.
    Smoothstep,
}

/// The factor the sines are multiplied by.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FadeIn {
    /// How the factor rises from 0 to 1.
    pub shape: FadeShape,
    /// Time constant or duration (s).
    pub time: f64,
}

impl FadeIn {
    fn factor(&self, t: f64) -> f64 {
        match self.shape {
            FadeShape::Exponential => 1.0 - (-t / self.time).exp(),
            FadeShape::Smoothstep => {
                let x = (t / self.time).min(1.0);
                x * x * x * (10.0 - 15.0 * x + 6.0 * x * x)
            }
        }
    }
}

/// A step of `size` from `time` on.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Step {
    /// s
    pub time: f64,
    /// In the output's unit of measure.
    pub size: f64,
}

/// Parameters (scene kind `signal`).
#[derive(Clone, Debug, Deserialize)]
#[serde(from = "SignalSpec")]
pub struct SignalParams {
    /// The output's physical kind (its unit of measure), e.g. "rotation".
    pub quantity: PortKind,
    /// Constant part (the quantity's SI unit).
    pub offset: f64,
    /// The sines given, then the sea state's.
    pub sines: Vec<Sine>,
    /// Applied to the sines only; none: the sines start at full size.
    pub fade_in: Option<FadeIn>,
    /// Steps added at given times.
    pub steps: Vec<Step>,
    /// The sea state whose sines were added to `sines` (kept to be checked).
    pub sea: Option<SeaState>,
}

/// The parameters as a scene writes them.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SignalSpec {
    quantity: PortKind,
    #[serde(default)]
    offset: f64,
    #[serde(default)]
    sines: Vec<Sine>,
    #[serde(default)]
    fade_in: Option<FadeIn>,
    #[serde(default)]
    steps: Vec<Step>,
    #[serde(default)]
    sea: Option<SeaState>,
}

impl From<SignalSpec> for SignalParams {
    fn from(spec: SignalSpec) -> SignalParams {
        let mut sines = spec.sines;
        sines.extend(spec.sea.iter().flat_map(SeaState::sines));
        SignalParams {
            quantity: spec.quantity,
            offset: spec.offset,
            sines,
            fade_in: spec.fade_in,
            steps: spec.steps,
            sea: spec.sea,
        }
    }
}

impl SignalParams {
    fn validate(&self) -> Result<(), UnitError> {
        require_finite("offset", self.offset)?;
        for (i, s) in self.sines.iter().enumerate() {
            s.check(&format!("sines.{i}"))?;
            require_non_negative(&format!("sines.{i}.angular_frequency"), s.angular_frequency)?;
        }
        if let Some(fade) = &self.fade_in {
            require_positive("fade_in.time", fade.time)?;
        }
        if let Some(sea) = &self.sea {
            sea.validate("sea")?;
        }
        for (i, s) in self.steps.iter().enumerate() {
            require_finite(&format!("steps.{i}.time"), s.time)?;
            require_finite(&format!("steps.{i}.size"), s.size)?;
        }
        Ok(())
    }

    /// The signal at time t (s).
    pub fn value(&self, t: f64) -> f64 {
        let sines: f64 = self.sines.iter().map(|s| s.eval(t)[0]).sum();
        let fade = self.fade_in.as_ref().map_or(1.0, |f| f.factor(t));
        let steps: f64 = self
            .steps
            .iter()
            .filter(|s| t >= s.time)
            .map(|s| s.size)
            .sum();
        self.offset + fade * sines + steps
    }
}

/// The source: no inputs, one output `value`; non-finite values and a fade of no
/// duration are refused.
pub type Signal = Source<SignalParams>;

impl Prescribed for SignalParams {
    const KIND: &'static str = "signal";

    fn validate(&self) -> Result<(), UnitError> {
        SignalParams::validate(self)
    }

    fn outputs(&self) -> Vec<Port> {
        vec![Port::output("value", self.quantity)]
    }

    fn write(&self, t: f64, out: &mut [f64]) {
        out[0] = self.value(t);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(fade_in: Option<FadeIn>) -> SignalParams {
        SignalParams {
            quantity: PortKind::Rotation,
            offset: 0.5,
            sines: vec![Sine {
                amplitude: 2.0,
                angular_frequency: 3.0,
                phase: 0.25,
                decay: 0.0,
            }],
            fade_in,
            steps: vec![Step {
                time: 1.0,
                size: -1.0,
            }],
            sea: None,
        }
    }

    #[test]
    fn offset_faded_sines_and_steps_add_up() {
        let p = params(None);
        let sine = |t: f64| 2.0 * (3.0 * t + 0.25).sin();
        assert_eq!(p.value(0.5), 0.5 + sine(0.5));
        assert_eq!(p.value(1.0), 0.5 + sine(1.0) - 1.0);
        let smooth = params(Some(FadeIn {
            shape: FadeShape::Smoothstep,
            time: 2.0,
        }));
        assert_eq!(smooth.value(0.0), 0.5);
        assert!((smooth.value(1.0) - (0.5 + 0.5 * sine(1.0) - 1.0)).abs() < 1e-15);
        assert_eq!(smooth.value(3.0), p.value(3.0));
        let exponential = params(Some(FadeIn {
            shape: FadeShape::Exponential,
            time: 2.0,
        }));
        let factor = 1.0 - (-0.5f64).exp();
        assert!((exponential.value(1.0) - (0.5 + factor * sine(1.0) - 1.0)).abs() < 1e-15);
    }

    #[test]
    fn a_fade_of_no_duration_is_refused_by_name() {
        let p = params(Some(FadeIn {
            shape: FadeShape::Exponential,
            time: 0.0,
        }));
        let err = Signal::new(p)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.contains("fade_in.time"), "{err}");
    }
}
