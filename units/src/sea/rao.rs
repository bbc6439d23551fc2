//! A vessel's response amplitude operator for one motion: amplitude and phase
//! of the motion per metre of wave amplitude, against wave frequency.

use crate::signal::sine::Sine;
use serde::{Deserialize, Serialize};

/// A table of the response per metre of wave amplitude.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Rao {
    /// Rows `[angular frequency (rad/s), amplitude (the motion's unit per m),
    /// phase (rad, the motion's lead on the wave)]`, frequencies increasing.
    /// Between rows amplitude and phase are interpolated linearly (give the
    /// phase unwrapped); outside the table the response is zero.
    pub table: Vec<[f64; 3]>,
}

impl Rao {
    /// Checks the table: at least two rows, finite, frequencies increasing
    /// from > 0, amplitudes >= 0. The refusal names the row.
    pub fn validate(&self) -> Result<(), (String, String, &'static str)> {
        if self.table.len() < 2 {
            return Err((
                "table".into(),
                format!("{} rows", self.table.len()),
                "at least two rows [omega, amplitude, phase]",
            ));
        }
        for (i, row) in self.table.iter().enumerate() {
            let key = format!("table[{i}]");
            let value = format!("{row:?}");
            if !row.iter().all(|v| v.is_finite()) || row[0] <= 0.0 || row[1] < 0.0 {
                return Err((
                    key,
                    value,
                    "finite [omega > 0 rad/s, amplitude >= 0, phase rad]",
                ));
            }
            if i > 0 && row[0] <= self.table[i - 1][0] {
                return Err((key, value, "frequencies increasing from row to row"));
            }
        }
        Ok(())
    }

    /// Amplitude and phase of the response at `omega` (zero outside the table).
    pub fn response(&self, omega: f64) -> (f64, f64) {
        let k = self.table.partition_point(|row| row[0] <= omega);
        if k == 0 || (k == self.table.len() && omega > self.table[k - 1][0]) {
            return (0.0, 0.0);
        }
        let a = self.table[k - 1];
        let Some(b) = self.table.get(k) else {
            return (a[1], a[2]);
        };
        let x = (omega - a[0]) / (b[0] - a[0]);
        (a[1] + x * (b[1] - a[1]), a[2] + x * (b[2] - a[2]))
    }

    /// The motion the wave components make: each scaled by the amplitude and
    /// advanced by the phase at its frequency.
    pub fn apply(&self, waves: &[Sine]) -> Vec<Sine> {
        waves
            .iter()
            .map(|w| {
                let (amplitude, phase) = self.response(w.angular_frequency);
                Sine {
                    amplitude: w.amplitude * amplitude,
                    angular_frequency: w.angular_frequency,
                    phase: w.phase + phase,
                    decay: w.decay,
                }
            })
            .collect()
    }
}
