//! Monte Carlo filtering (Saltelli et al., *Global Sensitivity Analysis: The
//! Primer*, 2008, ch. 5): which inputs drive an outcome that splits the runs in
//! two (here a coupled loop that goes unstable). Each input's values among the
//! runs with the outcome are compared with those among the runs without it by
//! the two-sample Kolmogorov-Smirnov distance; an input that does not matter
//! has the same distribution in both groups. The outcome's probability comes
//! with a Wilson score interval, which stays inside [0, 1] for few events.

/// The two-sample Kolmogorov-Smirnov distance: the largest difference between
/// the empirical CDFs of `a` and `b` (0 when they coincide, 1 when every value
/// of one lies below every value of the other); NaN when either is empty.
pub fn ks_distance(a: &[f64], b: &[f64]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return f64::NAN;
    }
    let sorted = |v: &[f64]| {
        let mut v = v.to_vec();
        v.sort_by(f64::total_cmp);
        v
    };
    let (a, b) = (sorted(a), sorted(b));
    let (mut i, mut j, mut largest) = (0, 0, 0.0f64);
    while i < a.len() && j < b.len() {
        // Step past every value equal to the smaller one in both samples.
        let x = a[i].min(b[j]);
        while i < a.len() && a[i] <= x {
            i += 1;
        }
        while j < b.len() && b[j] <= x {
            j += 1;
        }
        let gap = i as f64 / a.len() as f64 - j as f64 / b.len() as f64;
        largest = largest.max(gap.abs());
    }
    largest
}

/// The asymptotic p-value of a two-sample Kolmogorov-Smirnov distance `d`
/// between samples of `n` and `m` values: the probability of a distance at
/// least this large when both come from one distribution (Kolmogorov's
/// series with Stephens' small-sample correction, as in Numerical Recipes
/// sec. 14.3). Small values say the input matters.
pub fn ks_p_value(d: f64, n: usize, m: usize) -> f64 {
    if !d.is_finite() || n == 0 || m == 0 {
        return f64::NAN;
    }
    let ne = (n * m) as f64 / (n + m) as f64;
    let lambda = (ne.sqrt() + 0.12 + 0.11 / ne.sqrt()) * d;
    if lambda < 0.2 {
        return 1.0;
    }
    // The terms fall as exp(-2 k^2 lambda^2): 100 are far past convergence.
    let sum: f64 = (1..=100)
        .map(|k| {
            let sign = if k % 2 == 1 { 1.0 } else { -1.0 };
            sign * (-2.0 * (k * k) as f64 * lambda * lambda).exp()
        })
        .sum();
    (2.0 * sum).clamp(0.0, 1.0)
}

/// The Wilson score interval of a probability from `events` out of `trials`
/// at the standard normal quantile `z` (1.96 for 95 %): (low, high), inside
/// [0, 1] even with no event; NaN without trials.
pub fn wilson(events: usize, trials: usize, z: f64) -> (f64, f64) {
    if trials == 0 {
        return (f64::NAN, f64::NAN);
    }
    let n = trials as f64;
    let p = events as f64 / n;
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_is_zero_for_one_sample_and_one_for_separated_ones() {
        let a = [0.1, 0.4, 0.3, 0.2];
        assert_eq!(ks_distance(&a, &a), 0.0);
        assert_eq!(ks_distance(&a, &[0.5, 0.9]), 1.0);
        // Half of b lies below every value of a: the CDFs differ by 1/2 there.
        assert!((ks_distance(&a, &[0.0, 0.95]) - 0.5).abs() < 1e-15);
        // Ties step together.
        assert_eq!(ks_distance(&[1.0, 1.0, 2.0], &[1.0, 2.0, 2.0]), 1.0 / 3.0);
        assert!(ks_distance(&[], &a).is_nan());
    }

    #[test]
    fn p_values_follow_kolmogorovs_law() {
        // The 5 % critical value of the one-sided large-sample law is 1.358.
        let n = 10_000;
        let ne = (n * n) as f64 / (2 * n) as f64;
        let d = 1.358 / (ne.sqrt() + 0.12 + 0.11 / ne.sqrt());
        assert!((ks_p_value(d, n, n) - 0.05).abs() < 5e-4);
        assert_eq!(ks_p_value(0.0, 10, 10), 1.0);
        assert!(ks_p_value(1.0, 50, 50) < 1e-20);
        assert!(ks_p_value(f64::NAN, 5, 5).is_nan());
    }

    #[test]
    fn wilsons_interval_holds_the_estimate_and_stays_in_the_unit_interval() {
        // 19 of 208 (issue 49's unstable points): about 5.9 % to 13.9 %.
        let (low, high) = wilson(19, 208, 1.96);
        assert!(low < 19.0 / 208.0 && 19.0 / 208.0 < high);
        assert!((low - 0.0592).abs() < 1e-3 && (high - 0.1384).abs() < 1e-3);
        let (low, high) = wilson(0, 20, 1.96);
        assert_eq!(low, 0.0);
        assert!(high > 0.1 && high < 0.2, "{high}");
        assert!(wilson(0, 0, 1.96).0.is_nan());
    }
}
