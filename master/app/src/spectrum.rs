//! The power spectral density of a recorded signal by Welch's method (issue
//! 50): half-overlapping segments, each with its mean removed and a periodic
//! Hann window, their one-sided periodograms averaged. The same estimate as
//! `scipy.signal.welch` with its defaults (checked against it in
//! `tests/python/analysis_checks.py`), so a user's own post-processing and
//! slender's agree. From the spectrum its moments: m0 (the variance), the peak
//! period and the mean zero-crossing period sqrt(m0 / m2).

use realfft::RealFftPlanner;
use serde::Serialize;

/// A one-sided power spectral density.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// The frequencies (Hz), from 0 to the Nyquist frequency in steps of
    /// 1 / segment length.
    pub frequency_hz: Vec<f64>,
    /// The density at each frequency (the signal's unit squared per Hz).
    pub density: Vec<f64>,
    /// The number of segments averaged.
    pub segments: usize,
}

/// What a design report quotes of a spectrum.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpectralSummary {
    /// The zeroth moment: the variance (the signal's unit squared).
    pub m0: f64,
    /// The period of the largest density (s); None for a flat zero spectrum.
    pub peak_period_s: Option<f64>,
    /// 2 pi sqrt(m0 / m2) with the moments in rad/s (s): Rice's mean
    /// zero-up-crossing period of a Gaussian process with this spectrum.
    pub zero_crossing_period_s: Option<f64>,
    /// The frequency resolution (Hz).
    pub resolution_hz: f64,
    /// The number of segments averaged (more: a steadier estimate).
    pub segments: usize,
}

/// Welch's estimate from `values` sampled every `dt` seconds with segments of
/// `segment` samples (at least 4, at most the samples); None otherwise.
pub fn welch(values: &[f64], dt: f64, segment: usize) -> Option<Spectrum> {
    if segment < 4 || segment > values.len() || dt.is_nan() || dt <= 0.0 {
        return None;
    }
    let window: Vec<f64> = (0..segment)
        .map(|k| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * k as f64 / segment as f64).cos())
        .collect();
    let window_power: f64 = window.iter().map(|w| w * w).sum();
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(segment);
    let (mut input, mut output) = (fft.make_input_vec(), fft.make_output_vec());
    let mut density = vec![0.0; output.len()];
    let stride = segment - segment / 2;
    let segments = (values.len() - segment) / stride + 1;
    for s in 0..segments {
        let piece = &values[s * stride..s * stride + segment];
        let mean = piece.iter().sum::<f64>() / segment as f64;
        for ((x, v), w) in input.iter_mut().zip(piece).zip(&window) {
            *x = (v - mean) * w;
        }
        fft.process(&mut input, &mut output).ok()?;
        for (d, c) in density.iter_mut().zip(&output) {
            *d += c.norm_sqr();
        }
    }
    // One-sided: every bin but 0 and (for an even segment) Nyquist doubled.
    let scale = dt / (window_power * segments as f64);
    let last = density.len() - 1;
    for (k, d) in density.iter_mut().enumerate() {
        let doubled = k != 0 && !(segment % 2 == 0 && k == last);
        *d *= if doubled { 2.0 * scale } else { scale };
    }
    let df = 1.0 / (segment as f64 * dt);
    Some(Spectrum {
        frequency_hz: (0..density.len()).map(|k| k as f64 * df).collect(),
        density,
        segments,
    })
}

impl Spectrum {
    /// The moments, peak period and resolution of this spectrum.
    pub fn summary(&self) -> SpectralSummary {
        let df = self.frequency_hz.get(1).copied().unwrap_or(f64::NAN);
        let moment = |n: i32| -> f64 {
            (self.frequency_hz.iter().zip(&self.density))
                .map(|(f, s)| (2.0 * std::f64::consts::PI * f).powi(n) * s * df)
                .sum()
        };
        let (m0, m2) = (moment(0), moment(2));
        let peak = (self.density.iter().enumerate())
            .skip(1)
            .filter(|(_, s)| **s > 0.0)
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(k, _)| 1.0 / self.frequency_hz[k]);
        SpectralSummary {
            m0,
            peak_period_s: peak,
            zero_crossing_period_s: (m2 > 0.0)
                .then(|| 2.0 * std::f64::consts::PI * (m0 / m2).sqrt()),
            resolution_hz: df,
            segments: self.segments,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::welch;
    use std::f64::consts::PI;

    /// A seeded uniform generator on [0, 1) (a 64-bit LCG's high bits).
    fn uniform(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn a_sine_on_a_bin_puts_its_variance_at_its_frequency() {
        // 3 sin(2 pi 0.25 t), dt 0.1 s, segments of 400 samples (40 s):
        // 0.25 Hz is bin 10; the Hann window spreads it over bins 9-11.
        let dt = 0.1;
        let values: Vec<f64> = (0..8000)
            .map(|k| 3.0 * (2.0 * PI * 0.25 * k as f64 * dt).sin())
            .collect();
        let s = welch(&values, dt, 400).expect("spectrum");
        let summary = s.summary();
        assert!((summary.m0 / 4.5 - 1.0).abs() < 1e-9, "{summary:?}");
        assert!((summary.peak_period_s.unwrap() - 4.0).abs() < 1e-9);
        assert!((summary.zero_crossing_period_s.unwrap() / 4.0 - 1.0).abs() < 2e-3);
        assert_eq!(s.segments, 39);
        let away: f64 = s.density[13..].iter().sum();
        assert!(away < 1e-20, "{away}");
    }

    #[test]
    fn white_noise_has_a_flat_density_of_twice_its_variance_times_dt() {
        // Uniform noise on [-1, 1): variance 1/3; one-sided density 2 var dt.
        let (dt, mut seed) = (0.05, 7u64);
        let values: Vec<f64> = (0..200_000)
            .map(|_| 2.0 * uniform(&mut seed) - 1.0)
            .collect();
        let s = welch(&values, dt, 256).expect("spectrum");
        let expected = 2.0 / 3.0 * dt;
        // Bin 1 shares the Hann window's leakage with the removed mean.
        let inner = &s.density[2..s.density.len() - 1];
        let mean = inner.iter().sum::<f64>() / inner.len() as f64;
        assert!(
            (mean / expected - 1.0).abs() < 0.01,
            "{mean} against {expected}"
        );
        // Each bin averages ~1560 periodograms: within 10 % everywhere.
        for d in inner {
            assert!((d / expected - 1.0).abs() < 0.1, "{d} against {expected}");
        }
    }

    #[test]
    fn a_gaussian_process_returns_its_spectrum() {
        // 400 random-phase components of S(f) = f^2 exp(-f / 0.04) (one-sided,
        // per Hz) up to 0.5 Hz: the estimate matches S over its bulk within
        // the sampling error of ~120 averaged segments, and m0 within 2 %.
        let (dt, mut seed) = (0.25, 3u64);
        let density = |f: f64| f * f * (-f / 0.04).exp();
        let df = 0.5 / 400.0;
        let components: Vec<(f64, f64, f64)> = (1..=400)
            .map(|k| {
                let f = (k as f64 - uniform(&mut seed)) * df;
                (
                    (2.0 * density(f) * df).sqrt(),
                    2.0 * PI * f,
                    2.0 * PI * uniform(&mut seed),
                )
            })
            .collect();
        let m0: f64 = components.iter().map(|(a, _, _)| a * a / 2.0).sum();
        let values: Vec<f64> = (0..64_000)
            .map(|k| {
                let t = k as f64 * dt;
                components
                    .iter()
                    .map(|(a, w, p)| a * (w * t + p).sin())
                    .sum()
            })
            .collect();
        let s = welch(&values, dt, 1024).expect("spectrum");
        let summary = s.summary();
        assert!(
            (summary.m0 / m0 - 1.0).abs() < 0.02,
            "{summary:?} against {m0}"
        );
        assert!(
            (summary.peak_period_s.unwrap() - 12.5).abs() < 3.0,
            "{summary:?}"
        );
        for (f, d) in s.frequency_hz.iter().zip(&s.density) {
            if (0.04..=0.15).contains(f) {
                let exact = density(*f);
                assert!((d / exact - 1.0).abs() < 0.4, "{f} Hz: {d} against {exact}");
            }
        }
    }

    #[test]
    fn too_few_samples_give_no_spectrum() {
        assert!(welch(&[1.0; 10], 0.1, 20).is_none());
        assert!(welch(&[1.0; 10], 0.1, 2).is_none());
        assert!(welch(&[1.0; 10], 0.0, 8).is_none());
    }
}
