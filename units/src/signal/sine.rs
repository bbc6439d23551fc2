//! One sine `amplitude exp(-decay t) sin(angular_frequency t + phase)`: the
//! wave component a signal, an end motion and a sea state are sums of (with a
//! decay, a damped free vibration, as the analytic solutions of the benchmark
//! scenes have them).

use super::series::SineSeries;
use crate::contract::{UnitError, require_finite, require_non_negative};
use serde::{Deserialize, Serialize};

/// One sine `amplitude exp(-decay t) sin(angular_frequency t + phase)`.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sine {
    /// In the unit of measure of what it is added to.
    pub amplitude: f64,
    /// rad/s
    pub angular_frequency: f64,
    /// rad
    pub phase: f64,
    /// 1/s: the amplitude falls as exp(-decay t); 0 (default) a steady sine.
    pub decay: f64,
}

impl Sine {
    /// Value and its first two time derivatives at t (s).
    pub fn eval(&self, t: f64) -> [f64; 3] {
        let (w, a) = (self.angular_frequency, self.amplitude);
        let arg = w * t + self.phase;
        if self.decay == 0.0 {
            return [a * arg.sin(), a * w * arg.cos(), -a * w * w * arg.sin()];
        }
        let d = self.decay;
        let (sin, cos) = arg.sin_cos();
        let e = a * (-d * t).exp();
        [
            e * sin,
            e * (w * cos - d * sin),
            e * ((d * d - w * w) * sin - 2.0 * d * w * cos),
        ]
    }

    /// Refuses a field that is not finite or a negative decay (which would
    /// grow without bound), naming the field under `key`.
    pub fn check(&self, key: &str) -> Result<(), UnitError> {
        require_finite(&format!("{key}.amplitude"), self.amplitude)?;
        require_finite(&format!("{key}.angular_frequency"), self.angular_frequency)?;
        require_finite(&format!("{key}.phase"), self.phase)?;
        require_non_negative(&format!("{key}.decay"), self.decay)
    }
}

/// The fade-in factor over `duration` (s) at `t` and its two derivatives:
/// (1 - cos(pi t / duration)) / 2, then 1.
pub fn fade(duration: f64, t: f64) -> [f64; 3] {
    if duration <= 0.0 || t >= duration {
        return [1.0, 0.0, 0.0];
    }
    let w = std::f64::consts::PI / duration;
    let (s, c) = (w * t.max(0.0)).sin_cos();
    [0.5 * (1.0 - c), 0.5 * w * s, 0.5 * w * w * c]
}

/// The quintic smoothstep over `duration` (s) at t and its first two time
/// derivatives; 1 from `duration` on (and for a zero duration).
pub fn smoothstep(t: f64, duration: f64) -> [f64; 3] {
    if duration <= 0.0 || t >= duration {
        return [1.0, 0.0, 0.0];
    }
    let x = t.max(0.0) / duration;
    [
        x * x * x * (10.0 - 15.0 * x + 6.0 * x * x),
        30.0 * x * x * (1.0 - x) * (1.0 - x) / duration,
        60.0 * x * (1.0 - x) * (1.0 - 2.0 * x) / (duration * duration),
    ]
}

/// `base` plus the sum of `sines` faded in over `fade_in` (s) at `t`, and
/// its two time derivatives: a prescribed motion's position, velocity and
/// acceleration.
pub fn faded_sum(base: f64, sines: &[Sine], fade_in: f64, t: f64) -> [f64; 3] {
    let [r, dr, ddr] = fade(fade_in, t);
    let mut out = [base, 0.0, 0.0];
    for s in sines {
        let [x, v, a] = s.eval(t);
        out[0] += r * x;
        out[1] += dr * x + r * v;
        out[2] += ddr * x + 2.0 * dr * v + r * a;
    }
    out
}

/// [`faded_sum`] of a series (a sea's components summed by phasors):
/// (r x)' = r' x + r v, (r x)'' = r'' x + 2 r' v + r a.
pub fn faded_series(base: f64, series: &SineSeries, fade_in: f64, t: f64) -> [f64; 3] {
    let [r, dr, ddr] = fade(fade_in, t);
    let [x, v, a] = series.eval(t);
    [base + r * x, dr * x + r * v, ddr * x + 2.0 * dr * v + r * a]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_decaying_sine_s_rates_are_its_derivatives() {
        let s = Sine {
            amplitude: 0.3,
            angular_frequency: 7.0,
            phase: 0.4,
            decay: 1.5,
        };
        let h = 1e-6;
        for t in [0.0, 0.3, 1.1] {
            let [v, dv, ddv] = s.eval(t);
            let (before, after) = (s.eval(t - h), s.eval(t + h));
            assert!((dv - (after[0] - before[0]) / (2.0 * h)).abs() < 1e-7 * 7.0);
            assert!((ddv - (after[1] - before[1]) / (2.0 * h)).abs() < 1e-6 * 49.0);
            let expected = 0.3 * (-1.5 * t).exp() * (7.0 * t + 0.4).sin();
            assert!((v - expected).abs() < 1e-15);
        }
        let bad = Sine { decay: -1.0, ..s };
        let e = bad.check("sines.2").unwrap_err().to_string();
        assert!(e.contains("sines.2.decay"), "{e}");
    }
}
