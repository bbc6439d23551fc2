//! Free-decay analysis of a recorded signal: its natural period and damping
//! ratio from the peaks of its deviation about where it settles, as a decay
//! test in a basin is read. The period is the mean spacing of successive
//! up-crossings of the settling value; the damping is the logarithmic
//! decrement between successive peaks of the same sign, averaged,
//! `zeta = delta / sqrt(4 pi^2 + delta^2)`.

/// What a decay record shows.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Decay {
    /// Mean period (s) of the cycles found.
    pub period: f64,
    /// Damping ratio (fraction of critical), from the peaks' decrement.
    pub damping_ratio: f64,
    /// The value it settles about (the signal's unit).
    pub settles_at: f64,
    /// The first deviation's amplitude (the signal's unit).
    pub amplitude: f64,
    /// Complete cycles the estimates rest on.
    pub cycles: usize,
}

/// The decay of `values` sampled at `time` (s), about `settles_at` (where
/// the motion ends: an equilibrium from statics, or the record's last
/// value); None when the record holds less than one cycle.
pub fn decay(time: &[f64], values: &[f64], settles_at: f64) -> Option<Decay> {
    let deviation: Vec<f64> = values.iter().map(|v| v - settles_at).collect();
    let crossings: Vec<f64> = (1..deviation.len())
        .filter(|&k| deviation[k - 1] < 0.0 && deviation[k] >= 0.0)
        .map(|k| {
            let (a, b) = (deviation[k - 1], deviation[k]);
            time[k - 1] + (time[k] - time[k - 1]) * (-a) / (b - a)
        })
        .collect();
    if crossings.len() < 2 {
        return None;
    }
    let cycles = crossings.len() - 1;
    let period = (crossings[cycles] - crossings[0]) / cycles as f64;
    let peaks = peaks(&deviation);
    let decrements: Vec<f64> = peaks
        .windows(3)
        .filter(|w| w[0].signum() == w[2].signum() && w[2].abs() > 0.0)
        .map(|w| (w[0] / w[2]).ln())
        .collect();
    let delta = decrements.iter().sum::<f64>() / decrements.len().max(1) as f64;
    Some(Decay {
        period,
        damping_ratio: delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt(),
        settles_at,
        amplitude: peaks.first().map_or(0.0, |p| p.abs()),
        cycles,
    })
}

/// The extreme deviation between each pair of sign changes, in order.
fn peaks(deviation: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let mut current = 0.0_f64;
    for &d in deviation {
        if d.signum() != current.signum() && current != 0.0 && d != 0.0 {
            out.push(current);
            current = d;
        } else if d.abs() > current.abs() {
            current = d;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_damped_oscillator_s_period_and_damping_come_back() {
        let (zeta, period): (f64, f64) = (0.05, 30.0);
        let omega = 2.0 * std::f64::consts::PI / period;
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let time: Vec<f64> = (0..20_000).map(|k| k as f64 * 0.01).collect();
        let x: Vec<f64> = (time.iter())
            .map(|&t| 3.0 + 2.0 * (-zeta * omega * t).exp() * (wd * t).cos())
            .collect();
        let d = decay(&time, &x, 3.0).unwrap();
        let damped = 2.0 * std::f64::consts::PI / wd;
        assert!((d.period - damped).abs() < 1e-3 * damped, "{d:?}");
        assert!((d.damping_ratio - zeta).abs() < 1e-3, "{d:?}");
        assert!((d.amplitude - 2.0).abs() < 1e-3, "{d:?}");
        assert!(d.cycles >= 5);
    }

    #[test]
    fn less_than_a_cycle_is_no_decay() {
        let time = [0.0, 1.0, 2.0];
        assert!(decay(&time, &[1.0, 0.5, 0.2], 0.0).is_none());
    }
}
