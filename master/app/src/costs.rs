//! Costs a user can trust: one wall-clock sample of a run can be off 2-5x on a
//! shared machine, so a study can time each run several times (`--repeats N`)
//! and report the median and the spread ((max - min) / median), and warns when
//! the spread is wide (the machine was busy: repeat with fewer jobs or more
//! repeats).

/// A spread above this (20 %) makes the cost of a run untrustworthy.
pub const WIDE_SPREAD: f64 = 0.2;

/// The median and the relative spread of cost samples (s per simulated s);
/// the spread is NaN for one sample, and both are NaN for none.
pub fn median_and_spread(samples: &[f64]) -> (f64, f64) {
    let mut sorted: Vec<f64> = samples.iter().copied().filter(|c| c.is_finite()).collect();
    if sorted.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    };
    let spread = if n == 1 {
        f64::NAN
    } else {
        (sorted[n - 1] - sorted[0]) / median
    };
    (median, spread)
}

/// The cost of a run timed `repeats` times: `first` and `again()` for the
/// rest, as (median, spread).
pub fn repeated(repeats: usize, first: f64, mut again: impl FnMut() -> f64) -> (f64, f64) {
    let mut samples = vec![first];
    samples.extend((1..repeats).map(|_| again()));
    median_and_spread(&samples)
}

/// A cost for a table: the value, and its spread where it was repeated
/// ("3.25e-3 (spread 4 %)").
pub fn cell(cost: f64, spread: f64) -> String {
    if spread.is_finite() {
        format!("{cost:.3e} (spread {:.0} %)", 100.0 * spread)
    } else {
        format!("{cost:.3e}")
    }
}

/// A spread for CSV: empty where the run was timed once.
pub fn csv(spread: f64) -> String {
    if spread.is_finite() {
        format!("{spread:e}")
    } else {
        String::new()
    }
}

/// A warning when any run's cost spread is wide, naming how many and the
/// widest; none otherwise.
pub fn spread_warning(spreads: impl Iterator<Item = f64>) -> Option<String> {
    let wide: Vec<f64> = spreads.filter(|s| *s > WIDE_SPREAD).collect();
    let widest = wide.iter().copied().fold(0.0f64, f64::max);
    (!wide.is_empty()).then(|| {
        format!(
            "warning: the cost of {} run(s) spread over more than {:.0} % of its median (widest {:.0} %): the machine was busy; repeat with --jobs 1 or more --repeats before comparing costs",
            wide.len(),
            100.0 * WIDE_SPREAD,
            100.0 * widest
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_and_spread_of_odd_even_single_and_failed_samples() {
        let (m, s) = median_and_spread(&[3.0, 1.0, 2.0]);
        assert_eq!((m, s), (2.0, 1.0));
        let (m, s) = median_and_spread(&[1.0, 2.0, 3.0, 10.0]);
        assert_eq!((m, s), (2.5, 9.0 / 2.5));
        let (m, s) = median_and_spread(&[4.0]);
        assert!(m == 4.0 && s.is_nan());
        let (m, s) = median_and_spread(&[f64::NAN]);
        assert!(m.is_nan() && s.is_nan());
    }

    #[test]
    fn a_wide_spread_is_named_and_a_narrow_one_is_not() {
        assert!(spread_warning([0.05, f64::NAN].into_iter()).is_none());
        let w = spread_warning([0.05, 0.3, 0.5].into_iter()).unwrap();
        assert!(w.contains("2 run(s)") && w.contains("50 %"), "{w}");
        let mut calls = 0;
        let (m, s) = repeated(3, 1.0, || {
            calls += 1;
            1.0 + calls as f64
        });
        assert_eq!((m, s, calls), (2.0, 1.0, 2));
    }
}
