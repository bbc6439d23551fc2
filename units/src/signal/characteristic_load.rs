//! The characteristic top load of seed 000 sec. 2.3: a static top tension plus a
//! low-frequency component acting along the static direction and a wave-frequency
//! component whose direction turns at a constant rate.
//!
//! The source does not print the sweep law or the duration; this unit uses a
//! linear frequency sweep (chirp) from 0 Hz to the maximum frequency over
//! `sweep_duration`, continuing at the maximum frequency afterwards:
//! `A sin(pi f_max t^2 / T)` for t <= T. Starting at zero frequency, the load
//! starts smoothly from its static value.

use super::prescribed::{Prescribed, Source};
use crate::contract::{
    Port, PortKind, UnitError, require_finite, require_non_negative, require_positive,
};
use serde::Deserialize;

/// Parameters (scene kind `characteristic_load`); defaults are seed 000's values.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CharacteristicLoadParams {
    /// Static top tension (N).
    pub static_tension: f64,
    /// Angle of the static tension from the vertical (deg).
    pub static_angle_from_vertical_deg: f64,
    /// Low-frequency amplitude (N), along the static direction.
    pub lf_amplitude: f64,
    /// Low-frequency sweep end (Hz).
    pub lf_max_frequency: f64,
    /// Wave-frequency amplitude (N).
    pub wf_amplitude: f64,
    /// Wave-frequency sweep end (Hz).
    pub wf_max_frequency: f64,
    /// Duration of both sweeps (s).
    pub sweep_duration: f64,
    /// Direction of the wave-frequency load at t = 0, from the x axis (deg).
    pub wf_initial_direction_deg: f64,
    /// Turning rate of the wave-frequency direction (deg/s); default one turn per
    /// sweep.
    pub wf_direction_rate_deg_per_s: Option<f64>,
}

impl Default for CharacteristicLoadParams {
    fn default() -> Self {
        CharacteristicLoadParams {
            static_tension: 2.5e6,
            static_angle_from_vertical_deg: 50.0,
            lf_amplitude: 1.0e6,
            lf_max_frequency: 0.02,
            wf_amplitude: 2.5e5,
            wf_max_frequency: 0.2,
            sweep_duration: 200.0,
            wf_initial_direction_deg: 0.0,
            wf_direction_rate_deg_per_s: None,
        }
    }
}

impl CharacteristicLoadParams {
    fn validate(&self) -> Result<(), UnitError> {
        require_non_negative("static_tension", self.static_tension)?;
        let angle = self.static_angle_from_vertical_deg;
        require_finite("static_angle_from_vertical_deg", angle)?;
        // 400 deg was taken as 40: an angle past a half-turn is a slip.
        if angle.abs() > 180.0 {
            return Err(UnitError::parameter(
                "static_angle_from_vertical_deg",
                angle,
                "an angle from the vertical within +-180 deg",
            ));
        }
        require_non_negative("lf_amplitude", self.lf_amplitude)?;
        require_non_negative("lf_max_frequency", self.lf_max_frequency)?;
        require_non_negative("wf_amplitude", self.wf_amplitude)?;
        require_non_negative("wf_max_frequency", self.wf_max_frequency)?;
        require_positive("sweep_duration", self.sweep_duration)?;
        require_finite("wf_initial_direction_deg", self.wf_initial_direction_deg)?;
        if let Some(r) = self.wf_direction_rate_deg_per_s {
            require_finite("wf_direction_rate_deg_per_s", r)?;
        }
        Ok(())
    }

    /// Phase (rad) of a sweep from 0 to `f_max` over the sweep duration, at time t.
    fn phase(&self, f_max: f64, t: f64) -> f64 {
        let big_t = self.sweep_duration;
        let pi = std::f64::consts::PI;
        if t <= big_t {
            pi * f_max * t * t / big_t
        } else {
            pi * f_max * big_t + 2.0 * pi * f_max * (t - big_t)
        }
    }

    /// The load [fx, fz] (N) at time t (s).
    pub fn force(&self, t: f64) -> [f64; 2] {
        let a = self.static_angle_from_vertical_deg.to_radians();
        let axis = [a.sin(), a.cos()];
        let lf =
            self.static_tension + self.lf_amplitude * self.phase(self.lf_max_frequency, t).sin();
        let rate = self
            .wf_direction_rate_deg_per_s
            .unwrap_or(360.0 / self.sweep_duration);
        let dir = (self.wf_initial_direction_deg + rate * t).to_radians();
        let wf = self.wf_amplitude * self.phase(self.wf_max_frequency, t).sin();
        [lf * axis[0] + wf * dir.cos(), lf * axis[1] + wf * dir.sin()]
    }
}

/// The load source: no inputs, outputs `force_x`, `force_z` (N).
pub type CharacteristicLoad = Source<CharacteristicLoadParams>;

impl Prescribed for CharacteristicLoadParams {
    const KIND: &'static str = "characteristic_load";

    fn validate(&self) -> Result<(), UnitError> {
        CharacteristicLoadParams::validate(self)
    }

    fn outputs(&self) -> Vec<Port> {
        vec![
            Port::output("force_x", PortKind::Force),
            Port::output("force_z", PortKind::Force),
        ]
    }

    fn write(&self, t: f64, out: &mut [f64]) {
        let f = self.force(t);
        out[0] = f[0];
        out[1] = f[1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_at_the_static_tension_and_stays_within_the_amplitudes() {
        let p = CharacteristicLoadParams::default();
        let f0 = p.force(0.0);
        assert!((f0[0] - 2.5e6 * 50f64.to_radians().sin()).abs() < 1e-6);
        assert!((f0[1] - 2.5e6 * 50f64.to_radians().cos()).abs() < 1e-6);
        for i in 0..4000 {
            let f = p.force(i as f64 * 0.05);
            let dev = ((f[0] - f0[0]).powi(2) + (f[1] - f0[1]).powi(2)).sqrt();
            assert!(dev <= 1.25e6 + 1e-6);
        }
    }

    #[test]
    fn an_angle_past_a_half_turn_is_refused() {
        for angle in [400.0, -181.0] {
            let p = CharacteristicLoadParams {
                static_angle_from_vertical_deg: angle,
                ..CharacteristicLoadParams::default()
            };
            let e = p.validate().unwrap_err().to_string();
            assert!(
                e.contains("static_angle_from_vertical_deg") && e.contains("180"),
                "{e}"
            );
        }
        let p = CharacteristicLoadParams {
            static_angle_from_vertical_deg: -30.0,
            ..CharacteristicLoadParams::default()
        };
        assert!(p.validate().is_ok());
    }
}
