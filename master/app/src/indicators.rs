//! Accuracy indicators of recorded signals against reference signals:
//! seed 000's fidelity phi (eqs. 7-8) and relative error epsilon (eqs. 10-11).
//!
//! Both come from `S = sum_i int (x_i - r_i)^2 dt / int r_i^2 dt` over the
//! components i: `phi = -1/2 log10 S` (infinite when identical) and
//! `epsilon = sqrt(S)`. Integrals use the trapezoidal rule on the recorded times.

use serde::Serialize;

/// One indicator's value.
#[derive(Clone, Debug, Serialize)]
pub struct Indicator {
    pub name: String,
    /// -1/2 log10 S.
    pub fidelity: f64,
    /// sqrt(S).
    pub relative_error: f64,
}

/// Trapezoidal integral of f(t)^2 ... over samples, for `f` given per sample.
fn integral(time: &[f64], f: impl Fn(usize) -> f64) -> f64 {
    (1..time.len())
        .map(|k| 0.5 * (time[k] - time[k - 1]) * (f(k - 1) + f(k)))
        .sum()
}

/// S for signals `x` against references `r` (same times, one column each).
pub fn normalized_error(time: &[f64], x: &[&[f64]], r: &[&[f64]]) -> f64 {
    x.iter()
        .zip(r)
        .map(|(x, r)| {
            let num = integral(time, |k| (x[k] - r[k]).powi(2));
            let den = integral(time, |k| r[k].powi(2));
            num / den
        })
        .sum()
}

/// The indicator called `name` from S.
pub fn indicator(name: &str, s: f64) -> Indicator {
    Indicator {
        name: name.to_owned(),
        fidelity: -0.5 * s.log10(),
        relative_error: s.sqrt(),
    }
}

/// Linear interpolation of (time, values) at `t` (clamped at the ends).
pub fn interpolate(time: &[f64], values: &[f64], t: f64) -> f64 {
    let i = time.partition_point(|&s| s <= t);
    if i == 0 {
        return values[0];
    }
    if i >= time.len() {
        return values[time.len() - 1];
    }
    let (t0, t1) = (time[i - 1], time[i]);
    values[i - 1] + (values[i] - values[i - 1]) * (t - t0) / (t1 - t0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ten_percent_error_has_fidelity_one() {
        let t: Vec<f64> = (0..=1000).map(|k| k as f64 * 0.01).collect();
        let r: Vec<f64> = t.iter().map(|t| t.sin()).collect();
        let x: Vec<f64> = r.iter().map(|v| 1.1 * v).collect();
        let s = normalized_error(&t, &[&x], &[&r]);
        let i = indicator("phi", s);
        assert!((i.relative_error - 0.1).abs() < 1e-12);
        assert!((i.fidelity - 1.0).abs() < 1e-12);
        assert_eq!(interpolate(&t, &r, 0.005), 0.5 * (r[0] + r[1]));
    }
}
