//! Peaks over a threshold: a generalised Pareto distribution (GPD) fitted to
//! the excesses of the peaks over a high threshold, and the most probable
//! maximum over a storm from it (DNV-RP-C205 3.5.11's peak-over-threshold
//! method; Coles, *An Introduction to Statistical Modeling of Extreme
//! Values*, 2001, ch. 4). The tail alone is fitted, so a response whose large
//! peaks do not follow the bulk's law (a slack-taut line, drag) is
//! extrapolated from its own tail.
//!
//! The fit is by probability-weighted moments (Hosking and Wallis,
//! *Technometrics* 29, 1987): closed form, unbiased enough for the few dozen
//! to few hundred excesses a run gives, valid for shapes below 1/2. Its
//! quality is the Kolmogorov-Smirnov distance between the excesses and the
//! fitted law.

use serde::Serialize;

/// A GPD fit of the peaks' excesses over a threshold.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GpdFit {
    /// The threshold (the signal's unit): the mean plus `threshold_sd`
    /// standard deviations.
    pub threshold: f64,
    /// The peaks above it.
    pub exceedances: usize,
    /// The shape xi (0: an exponential tail, as a Gaussian process's peaks
    /// approach; below 0: a bounded tail; above 0: a heavy one).
    pub shape: f64,
    /// The scale sigma (the signal's unit).
    pub scale: f64,
    /// The largest difference between the excesses' empirical distribution
    /// and the fitted one (0: a perfect fit; about 1.36 / sqrt(exceedances)
    /// is the 5 % critical value).
    pub ks_distance: f64,
    /// The most probable maximum over the duration.
    pub mpm: f64,
}

/// Shape and scale of a GPD fitted to `excesses` (all positive) by
/// probability-weighted moments; None with fewer than 10 or a fit outside
/// the method's range (shape 1/2 or more).
pub fn gpd_fit(excesses: &[f64]) -> Option<(f64, f64)> {
    if excesses.len() < 10 {
        return None;
    }
    let mut sorted = excesses.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    let a0 = sorted.iter().sum::<f64>() / n;
    // a1 = E[Y (1 - F(Y))], plotting positions (i - 0.35) / n.
    let a1 = (sorted.iter().enumerate())
        .map(|(i, y)| (1.0 - (i as f64 + 0.65) / n) * y)
        .sum::<f64>()
        / n;
    let denominator = a0 - 2.0 * a1;
    if denominator <= 0.0 {
        return None;
    }
    // Hosking and Wallis's k is -xi.
    let k = a0 / denominator - 2.0;
    let scale = 2.0 * a0 * a1 / denominator;
    let shape = -k;
    (shape < 0.5 && scale > 0.0 && scale.is_finite()).then_some((shape, scale))
}

/// The GPD's distribution function of an excess `y` >= 0.
pub fn gpd_cdf(y: f64, shape: f64, scale: f64) -> f64 {
    if shape.abs() < 1e-9 {
        return 1.0 - (-y / scale).exp();
    }
    let base = 1.0 + shape * y / scale;
    if base <= 0.0 {
        return 1.0;
    }
    1.0 - base.powf(-1.0 / shape)
}

/// The level an excess passes once in `n` of them: the (1 - 1/n) quantile,
/// the most probable largest of n for large n.
pub fn gpd_level(n: f64, shape: f64, scale: f64) -> f64 {
    if shape.abs() < 1e-9 {
        scale * n.ln()
    } else {
        scale / shape * (n.powf(shape) - 1.0)
    }
}

/// The one-sample Kolmogorov-Smirnov distance of `sorted` excesses (in
/// ascending order) from the GPD.
fn ks_distance(sorted: &[f64], shape: f64, scale: f64) -> f64 {
    let n = sorted.len() as f64;
    (sorted.iter().enumerate())
        .map(|(i, &y)| {
            let f = gpd_cdf(y, shape, scale);
            (f - i as f64 / n).abs().max(((i + 1) as f64 / n - f).abs())
        })
        .fold(0.0, f64::max)
}

/// The peaks-over-threshold fit of `peaks` (one per up-crossing cycle) over
/// `mean + threshold_sd * sigma`, and its most probable maximum over a
/// storm of `storm_cycles` cycles when the window held `cycles` of them.
pub fn over_threshold(
    peaks: &[f64],
    (mean, sigma, threshold_sd): (f64, f64, f64),
    (cycles, storm_cycles): (f64, f64),
) -> Option<GpdFit> {
    let threshold = mean + threshold_sd * sigma;
    let mut excesses: Vec<f64> = (peaks.iter())
        .map(|p| p - threshold)
        .filter(|y| *y > 0.0)
        .collect();
    excesses.sort_by(f64::total_cmp);
    let (shape, scale) = gpd_fit(&excesses)?;
    // Exceedances expected in the storm: the window's rate carried to it.
    let expected = (excesses.len() as f64 * storm_cycles / cycles).max(1.0);
    Some(GpdFit {
        threshold,
        exceedances: excesses.len(),
        shape,
        scale,
        ks_distance: ks_distance(&excesses, shape, scale),
        mpm: threshold + gpd_level(expected, shape, scale),
    })
}
