//! The most probable maximum of a signal over a longer duration than the run
//! (a 3-hour storm from a shorter simulation, issue 50), two ways, as
//! DNV-RP-C205 (section 3.5.11, short-term extremes) and DNV-OS-E301 (Ch.2
//! Sec.2, characteristic tension) describe:
//! - **Rayleigh**: for a narrow-band Gaussian process the peaks are
//!   Rayleigh-distributed and the most probable largest of N is
//!   mean + sigma sqrt(2 ln N), N the duration over the zero-up-crossing period;
//! - **Weibull**: a two-parameter Weibull fitted by least squares on the
//!   Weibull plot to the peaks' heights above the mean, its most probable
//!   largest of N peaks mean + scale (ln N)^(1/shape), with the fit's R^2; a
//!   non-Gaussian response (a slack-taut line, drag) bends the plot and moves
//!   the shape away from Rayleigh's 2;
//! - **peaks over a threshold** ([`pot`]): a generalised Pareto distribution
//!   fitted to the peaks' excesses over the mean plus a number of standard
//!   deviations, the tail alone, its most probable maximum and the fit's
//!   Kolmogorov-Smirnov distance.
//!
//! A peak is the largest sample between two successive up-crossings of the
//! mean (one per wave cycle).

pub mod pot;

use serde::Serialize;

/// The extremes of one signal over `[from, end]`, extrapolated to `duration_s`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Extremes {
    /// The duration the maxima are for (s).
    pub duration_s: f64,
    /// The peaks counted in the window (one per up-crossing cycle).
    pub peaks: usize,
    /// The largest sample in the window.
    pub largest_seen: f64,
    /// The most probable maximum over the duration by Rayleigh's law.
    pub rayleigh_mpm: f64,
    /// The Weibull fit of the peaks, with at least 10 of them.
    pub weibull: Option<WeibullFit>,
    /// The generalised Pareto fit of the peaks over the threshold, with at
    /// least 10 above it.
    pub gpd: Option<pot::GpdFit>,
}

/// A two-parameter Weibull fit of the peaks' heights above the mean.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WeibullFit {
    /// The shape (2 for Rayleigh-distributed peaks).
    pub shape: f64,
    /// The scale (the signal's unit).
    pub scale: f64,
    /// The coefficient of determination on the Weibull plot (1: a straight line).
    pub r_squared: f64,
    /// The most probable maximum over the duration.
    pub mpm: f64,
}

/// The extremes of `values` sampled at `time` (s) from `from` (s) on, over a
/// duration of `duration` (s), the peaks over threshold above the mean plus
/// `threshold_sd` standard deviations; None with fewer than two up-crossing
/// cycles.
pub fn of(
    (time, values): (&[f64], &[f64]),
    from: f64,
    (duration, threshold_sd): (f64, f64),
) -> Option<Extremes> {
    let first = time.partition_point(|&t| t < from);
    let n = values.len().min(time.len());
    if first + 2 > n {
        return None;
    }
    let (time, values) = (&time[first..n], &values[first..n]);
    let count = values.len() as f64;
    let mean = values.iter().sum::<f64>() / count;
    let sigma = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / count).sqrt();
    let (peaks, cycles_s) = peaks_between_up_crossings(time, values, mean)?;
    let mean_period = cycles_s / peaks.len() as f64;
    let expected_peaks = (duration / mean_period).max(1.0);
    let largest_seen = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let heights: Vec<f64> = peaks
        .iter()
        .map(|p| p - mean)
        .filter(|h| *h > 0.0)
        .collect();
    Some(Extremes {
        duration_s: duration,
        peaks: peaks.len(),
        largest_seen,
        rayleigh_mpm: mean + sigma * (2.0 * expected_peaks.ln()).sqrt(),
        weibull: weibull_fit(&heights).map(|(shape, scale, r_squared)| WeibullFit {
            shape,
            scale,
            r_squared,
            mpm: mean + scale * expected_peaks.ln().powf(1.0 / shape),
        }),
        gpd: pot::over_threshold(
            &peaks,
            (mean, sigma, threshold_sd),
            (peaks.len() as f64, expected_peaks),
        ),
    })
}

/// The largest value between each pair of successive up-crossings of
/// `level`, and the time from the first crossing to the last (s); None with
/// fewer than two crossings.
fn peaks_between_up_crossings(time: &[f64], values: &[f64], level: f64) -> Option<(Vec<f64>, f64)> {
    let crossings: Vec<usize> = (1..values.len())
        .filter(|&k| values[k - 1] < level && values[k] >= level)
        .collect();
    let (&first, &last) = (crossings.first()?, crossings.last()?);
    if first == last {
        return None;
    }
    let peaks = crossings
        .windows(2)
        .map(|w| {
            values[w[0]..w[1]]
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect();
    Some((peaks, time[last] - time[first]))
}

/// Shape, scale and R^2 of a Weibull fitted to `heights` (all positive) by
/// least squares of ln(-ln(1 - F)) on ln h, F = i / (n + 1) the i-th
/// smallest's plotting position; None with fewer than 10 heights.
pub fn weibull_fit(heights: &[f64]) -> Option<(f64, f64, f64)> {
    if heights.len() < 10 {
        return None;
    }
    let mut sorted = heights.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    let points: Vec<(f64, f64)> = (sorted.iter().enumerate())
        .map(|(i, h)| {
            let f = (i + 1) as f64 / (n + 1.0);
            (h.ln(), (-(1.0 - f).ln()).ln())
        })
        .collect();
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let syy: f64 = points.iter().map(|(_, y)| (y - my).powi(2)).sum();
    let shape = sxy / sxx;
    // y = shape (ln h - ln scale): the intercept is -shape ln scale.
    let scale = (mx - my / shape).exp();
    let r_squared = sxy * sxy / (sxx * syy);
    (shape.is_finite() && shape > 0.0).then_some((shape, scale, r_squared))
}

#[cfg(test)]
mod tests;
