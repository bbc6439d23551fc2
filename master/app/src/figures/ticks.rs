//! Tick positions and labels that read: log axes at decades (or 1-2-5 within a
//! decade), linear axes at 1-2-5 steps with the decimals of the step, zero
//! written `0` (not `-1.11e-16`), and few enough labels not to run into each
//! other.

/// The tick values of a log axis over [lo, hi] (both > 0): the decades inside
/// where three or more are, else the 1-2-5 values, else 1..9 times the
/// decades; at most `most` of them (every other decade when there are more).
pub fn log_ticks(lo: f64, hi: f64, most: usize) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    for mantissas in [
        &[1.0][..],
        &[1.0, 2.0, 5.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ] {
        let inside: Vec<f64> = (first..=last)
            .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
            .filter(|v| (lo..=hi).contains(v))
            .collect();
        if inside.len() >= 3 || (inside.len() == 2 && mantissas.len() > 1) {
            let every = inside.len().div_ceil(most.max(2));
            return inside.into_iter().step_by(every).collect();
        }
    }
    vec![lo, hi]
}

/// A log tick's label: plain between 0.001 and 9999 ("0.05", "200"), else
/// scientific with the mantissa's digits ("1e-6", "2.5e7").
pub fn log_label(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exponent = exponent_of(v);
    let mantissa = v / 10f64.powi(exponent);
    let mantissa_digits = short(mantissa, 3);
    if (-3..4).contains(&exponent) {
        let decimals = (-exponent).max(0) as usize + decimals_of(&mantissa_digits);
        trim(format!("{v:.decimals$}"))
    } else {
        format!("{mantissa_digits}e{exponent}")
    }
}

/// Ticks of a linear axis over [lo, hi]: multiples of a 1-2-5 step, about
/// `target` of them, and the step.
pub fn linear_ticks(lo: f64, hi: f64, target: usize) -> (Vec<f64>, f64) {
    if !(hi > lo && lo.is_finite() && hi.is_finite()) {
        return (vec![lo], 1.0);
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let decade = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|s| *s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * decade);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    ((first..=last).map(|i| i as f64 * step).collect(), step)
}

/// A linear tick's label with the decimals its step needs: `0` at zero (to the
/// step's round-off), scientific where the values are large or the step tiny.
pub fn linear_label(v: f64, step: f64) -> String {
    if v.abs() < step * 1e-6 {
        return "0".into();
    }
    let step_exponent = exponent_of(step);
    let exponent = exponent_of(v);
    if exponent >= 5 || step_exponent <= -4 {
        let digits = (exponent - step_exponent).max(0) as usize;
        let mantissa = v / 10f64.powi(exponent);
        format!("{}e{exponent}", trim(format!("{mantissa:.digits$}")))
    } else {
        let decimals = (-step_exponent).max(0) as usize;
        trim(format!("{v:.decimals$}"))
    }
}

/// The decimal exponent of a non-zero number, robust to 1e-8 computed as
/// 9.999999999999999e-9.
fn exponent_of(v: f64) -> i32 {
    (v.abs().log10() + 1e-9).floor() as i32
}

/// `v` to at most `digits` significant digits, trailing zeros dropped.
fn short(v: f64, digits: usize) -> String {
    trim(format!("{v:.prec$}", prec = digits.saturating_sub(1)))
}

/// The decimals written in a number's text.
fn decimals_of(text: &str) -> usize {
    text.split_once('.').map_or(0, |(_, d)| d.len())
}

/// Drops trailing zeros after a decimal point, and the point itself.
fn trim(text: String) -> String {
    if text.contains('.') && !text.contains('e') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axes_tick_at_decades_with_readable_labels() {
        let ticks = log_ticks(3e-9, 2e-2, 4);
        let labels: Vec<String> = ticks.iter().map(|v| log_label(*v)).collect();
        assert_eq!(labels, ["1e-8", "1e-6", "1e-4", "0.01"]);
        let narrow: Vec<String> = log_ticks(0.012, 0.06, 8)
            .iter()
            .map(|v| log_label(*v))
            .collect();
        assert_eq!(narrow, ["0.02", "0.05"]);
        assert_eq!(log_label(2.5e7), "2.5e7");
        assert_eq!(log_label(300.0), "300");
    }

    #[test]
    fn linear_axes_label_zero_and_keep_the_step_decimals() {
        let (ticks, step) = linear_ticks(-1.11e-16, 0.3, 6);
        assert_eq!(step, 0.05);
        let labels: Vec<String> = ticks.iter().map(|v| linear_label(*v, step)).collect();
        assert_eq!(labels, ["0", "0.05", "0.1", "0.15", "0.2", "0.25", "0.3"]);
        let (ticks, step) = linear_ticks(2.0e6, 2.3e6, 4);
        let labels: Vec<String> = ticks.iter().map(|v| linear_label(*v, step)).collect();
        assert_eq!(labels, ["2e6", "2.1e6", "2.2e6", "2.3e6"]);
        assert_eq!(linear_label(-5.551115123125783e-17, 0.5), "0");
    }
}
