//! Piecewise-linear tables (a current profile, a seabed's heights): one
//! lookup for every unit, held at the end values outside the table.

/// The value of the table (`xs` increasing, `ys` as many) at `x`, linear
/// between the points and held at the end values beyond them; NaN for a NaN
/// `x` (a state that became non-finite reaches the solver's check instead of
/// an index out of bounds).
pub fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let last = xs.len() - 1;
    if x.is_nan() {
        f64::NAN
    } else if x <= xs[0] {
        ys[0]
    } else if x >= xs[last] {
        ys[last]
    } else {
        let i = xs.partition_point(|&v| v <= x) - 1;
        let f = (x - xs[i]) / (xs[i + 1] - xs[i]);
        ys[i] + f * (ys[i + 1] - ys[i])
    }
}

#[cfg(test)]
mod tests {
    use super::interpolate;

    #[test]
    fn linear_inside_held_outside_nan_for_nan() {
        let (xs, ys) = ([0.0, 10.0, 20.0], [1.0, 3.0, -1.0]);
        assert_eq!(interpolate(&xs, &ys, 5.0), 2.0);
        assert_eq!(interpolate(&xs, &ys, 15.0), 1.0);
        assert_eq!(interpolate(&xs, &ys, 10.0), 3.0);
        assert_eq!(interpolate(&xs, &ys, -5.0), 1.0);
        assert_eq!(interpolate(&xs, &ys, 25.0), -1.0);
        assert!(interpolate(&xs, &ys, f64::NAN).is_nan());
    }
}
