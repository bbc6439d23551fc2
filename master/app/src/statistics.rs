//! Statistics of a recorded signal over a window that leaves out the
//! build-up (issue 50): mean, standard deviation, skewness, kurtosis,
//! extremes and the mean zero-up-crossing period, as a design report quotes
//! them for a tension or a motion (DNV-OS-E301's short-term statistics).
//!
//! Moments weigh every recorded sample alike (the recorder samples at a
//! constant interval); the standard deviation divides by the number of
//! samples (the signal's own over the window, not an estimate of a wider
//! population); the kurtosis is not in excess (a Gaussian process's is 3, a
//! sine's 1.5). Asked for by `[output] statistics = { from = S }`; a scene
//! that does not ask pays nothing.

use serde::Serialize;

/// The statistics of one signal over `[from, end]` of a run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Statistics {
    /// The samples in the window.
    pub samples: usize,
    /// The mean (the signal's unit).
    pub mean: f64,
    /// The standard deviation about the mean (the signal's unit).
    pub std_dev: f64,
    /// The third standardised moment (0 for a symmetric signal); NaN for a
    /// constant one.
    pub skewness: f64,
    /// The fourth standardised moment (3 for a Gaussian process, 1.5 for a
    /// sine); NaN for a constant signal.
    pub kurtosis: f64,
    /// The smallest sample.
    pub min: f64,
    /// The largest sample.
    pub max: f64,
    /// The mean period between up-crossings of the mean level (s), the
    /// crossing times interpolated between samples; None with fewer than two
    /// crossings.
    pub zero_up_crossing_period: Option<f64>,
}

/// The statistics of `values` sampled at `time` (s) over the samples at or
/// after `from` (s); None when the window holds fewer than two samples.
pub fn of(time: &[f64], values: &[f64], from: f64) -> Option<Statistics> {
    let first = time.partition_point(|&t| t < from);
    let (time, values) = (&time[first..], &values[first.min(values.len())..]);
    let n = values.len().min(time.len());
    if n < 2 {
        return None;
    }
    let (time, values) = (&time[..n], &values[..n]);
    let count = n as f64;
    let mean = values.iter().sum::<f64>() / count;
    let central = |power: i32| values.iter().map(|v| (v - mean).powi(power)).sum::<f64>() / count;
    let (m2, m3, m4) = (central(2), central(3), central(4));
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    Some(Statistics {
        samples: n,
        mean,
        std_dev: m2.sqrt(),
        skewness: m3 / m2.powf(1.5),
        kurtosis: m4 / (m2 * m2),
        min,
        max,
        zero_up_crossing_period: zero_up_crossing_period(time, values, mean),
    })
}

/// The mean period between up-crossings of `level` by `values` sampled at
/// `time`: (last crossing - first) / (crossings - 1), each crossing time
/// interpolated linearly between the samples around it.
fn zero_up_crossing_period(time: &[f64], values: &[f64], level: f64) -> Option<f64> {
    let mut crossings = (1..values.len()).filter_map(|k| {
        let (a, b) = (values[k - 1] - level, values[k] - level);
        (a < 0.0 && b >= 0.0).then(|| time[k - 1] + (time[k] - time[k - 1]) * a / (a - b))
    });
    let first = crossings.next()?;
    let (count, last) = crossings.fold((1usize, first), |(c, _), t| (c + 1, t));
    (count >= 2).then(|| (last - first) / (count - 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::of;
    use std::f64::consts::PI;

    /// `f` sampled every `dt` seconds over [0, `duration`].
    fn sampled(duration: f64, dt: f64, f: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
        let n = (duration / dt).round() as usize;
        let time: Vec<f64> = (0..=n).map(|k| k as f64 * dt).collect();
        let values = time.iter().map(|&t| f(t)).collect();
        (time, values)
    }

    #[test]
    fn a_sine_has_its_closed_form_statistics() {
        // 2.5 + 1.5 sin(2 pi t / 8) over 100 whole periods, 400 samples each.
        let (time, values) = sampled(800.0, 0.02, |t| 2.5 + 1.5 * (2.0 * PI * t / 8.0).sin());
        // Leave out the closing sample, so the window is whole periods.
        let s = of(&time[..time.len() - 1], &values, 0.0).expect("samples");
        assert!((s.mean - 2.5).abs() < 1e-12, "{s:?}");
        assert!((s.std_dev - 1.5 / 2f64.sqrt()).abs() < 1e-12, "{s:?}");
        assert!(s.skewness.abs() < 1e-9, "{s:?}");
        assert!((s.kurtosis - 1.5).abs() < 1e-9, "{s:?}");
        assert!(
            (s.max - 4.0).abs() < 1e-9 && (s.min - 1.0).abs() < 1e-9,
            "{s:?}"
        );
        let period = s.zero_up_crossing_period.expect("crossings");
        assert!((period - 8.0).abs() < 1e-9, "{period}");
    }

    #[test]
    fn a_sum_of_sines_has_the_variance_of_its_amplitudes() {
        // Incommensurate periods: the cross terms average out over the run.
        let (a, b) = (1.2, 0.7);
        let (time, values) = sampled(20_000.0, 0.05, |t| {
            a * (2.0 * PI * t / 9.0).sin() + b * (2.0 * PI * t / 5.3 + 0.4).sin()
        });
        let s = of(&time, &values, 0.0).expect("samples");
        let variance = (a * a + b * b) / 2.0;
        assert!((s.std_dev.powi(2) / variance - 1.0).abs() < 1e-3, "{s:?}");
        assert!(s.mean.abs() < 1e-3, "{s:?}");
    }

    #[test]
    fn a_gaussian_sea_crosses_its_mean_at_rices_rate() {
        // 100 components of a Pierson-Moskowitz-like spectrum with seeded
        // phases: a Gaussian process whose m0 and m2 are known, so its
        // variance is m0 and its zero-up-crossing period 2 pi sqrt(m0 / m2)
        // (Rice), each within the sampling error of 10,000 s (~1000 waves).
        let mut seed = 12345u64;
        let mut uniform = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (wp, dw) = (2.0 * PI / 10.0, 0.01);
        let components: Vec<(f64, f64, f64)> = (1..=100)
            .map(|k| {
                // Off the grid: equally spaced frequencies repeat every 2 pi / dw.
                let w = 0.3 + (k as f64 - uniform()) * dw;
                let density = (w / wp).powi(-5) * (-1.25 * (w / wp).powi(-4)).exp();
                ((2.0 * density * dw).sqrt(), w, 2.0 * PI * uniform())
            })
            .collect();
        let m0: f64 = components.iter().map(|(a, _, _)| a * a / 2.0).sum();
        let m2: f64 = components.iter().map(|(a, w, _)| a * a * w * w / 2.0).sum();
        let (time, values) = sampled(10_000.0, 0.2, |t| {
            components
                .iter()
                .map(|(a, w, p)| a * (w * t + p).sin())
                .sum()
        });
        let s = of(&time, &values, 0.0).expect("samples");
        assert!(
            (s.std_dev.powi(2) / m0 - 1.0).abs() < 0.05,
            "{s:?} against m0 {m0}"
        );
        let rice = 2.0 * PI * (m0 / m2).sqrt();
        let period = s.zero_up_crossing_period.expect("crossings");
        assert!(
            (period / rice - 1.0).abs() < 0.03,
            "{period} against {rice}"
        );
        // Its shape: skewness 0, and the kurtosis of a sum of random-phase
        // sines, 3 - 1.5 sum a^4 / (sum a^2)^2 (below a Gaussian's 3, as a
        // few components carry most of the variance), to about 3 sampling sd.
        let a2: f64 = components.iter().map(|(a, _, _)| a * a).sum();
        let a4: f64 = components.iter().map(|(a, _, _)| a.powi(4)).sum();
        let kurtosis = 3.0 - 1.5 * a4 / (a2 * a2);
        assert!(s.skewness.abs() < 0.2, "{s:?}");
        assert!(
            (s.kurtosis - kurtosis).abs() < 0.15,
            "{s:?} against {kurtosis}"
        );
    }

    #[test]
    fn the_build_up_before_the_window_is_left_out() {
        // A start transient of 50 that has died out by 20 s.
        let (time, values) = sampled(200.0, 0.1, |t| {
            (2.0 * PI * t / 10.0).sin() + 50.0 * (-t).exp()
        });
        let whole = of(&time, &values, 0.0).expect("samples");
        let after = of(&time, &values, 20.0).expect("samples");
        assert!(whole.max > 40.0, "{whole:?}");
        assert!((after.max - 1.0).abs() < 1e-3, "{after:?}");
        assert_eq!(after.samples, 1801);
        assert!(
            of(&time, &values, 199.95).is_none(),
            "one sample is no statistic"
        );
    }

    #[test]
    fn a_constant_signal_has_no_shape_and_no_crossings() {
        let s = of(&[0.0, 1.0, 2.0], &[4.0, 4.0, 4.0], 0.0).expect("samples");
        assert_eq!((s.mean, s.std_dev, s.min, s.max), (4.0, 0.0, 4.0, 4.0));
        assert!(s.skewness.is_nan() && s.kurtosis.is_nan());
        assert_eq!(s.zero_up_crossing_period, None);
    }
}
