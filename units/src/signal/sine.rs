//! One sine `amplitude sin(angular_frequency t + phase)`: the wave component a
//! signal, an end motion and a sea state are sums of.

use serde::Deserialize;

/// One sine `amplitude sin(angular_frequency t + phase)`.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sine {
    /// In the unit of measure of what it is added to.
    pub amplitude: f64,
    /// rad/s
    pub angular_frequency: f64,
    /// rad
    pub phase: f64,
}

impl Sine {
    /// Value and its first two time derivatives at t (s).
    pub fn eval(&self, t: f64) -> [f64; 3] {
        let (w, a) = (self.angular_frequency, self.amplitude);
        let arg = w * t + self.phase;
        [a * arg.sin(), a * w * arg.cos(), -a * w * w * arg.sin()]
    }
}
