//! A long recorded series thinned to what a figure can show: per column of
//! pixels its lowest and highest value, in the order they came. The drawn
//! line looks the same (every peak is kept) while the SVG stays small: a
//! paced run of 1 ns steps wrote a 31 MB figure for 1 ms of simulated time.

/// Columns a time-series panel is thinned to (its plot area is under 1000
/// pixels wide).
pub(crate) const COLUMNS: usize = 1000;

/// The points of `values` against `time`, thinned to at most two per column
/// of `columns` equal index spans (all of them when there are few); values
/// that are not finite are left out, as the chart would not draw them.
pub(crate) fn thinned(time: &[f64], values: &[f64], columns: usize) -> Vec<(f64, f64)> {
    let n = time.len().min(values.len());
    let finite = |k: &usize| values[*k].is_finite();
    if n <= 2 * columns.max(1) {
        return (0..n)
            .filter(finite)
            .map(|k| (time[k], values[k]))
            .collect();
    }
    let mut out = Vec::with_capacity(2 * columns);
    for c in 0..columns {
        let span = (c * n / columns)..((c + 1) * n / columns);
        let mut lowest: Option<usize> = None;
        let mut highest: Option<usize> = None;
        for k in span.filter(finite) {
            if lowest.is_none_or(|l| values[k] < values[l]) {
                lowest = Some(k);
            }
            if highest.is_none_or(|h| values[k] > values[h]) {
                highest = Some(k);
            }
        }
        let (Some(a), Some(b)) = (lowest, highest) else {
            continue;
        };
        let (first, second) = (a.min(b), a.max(b));
        out.push((time[first], values[first]));
        if second != first {
            out.push((time[second], values[second]));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_series_keeps_its_peaks_in_two_points_a_column() {
        let n = 1_000_000;
        let time: Vec<f64> = (0..n).map(|k| k as f64 * 1e-9).collect();
        let mut values: Vec<f64> = (0..n).map(|k| (k as f64 * 1e-3).sin()).collect();
        values[123_457] = 7.0;
        values[654_321] = -9.0;
        values[10] = f64::NAN;
        let points = thinned(&time, &values, COLUMNS);
        assert!(points.len() <= 2 * COLUMNS, "{}", points.len());
        let highest = points.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        let lowest = points.iter().map(|p| p.1).fold(f64::MAX, f64::min);
        assert_eq!((highest, lowest), (7.0, -9.0));
        assert!(points.windows(2).all(|w| w[0].0 < w[1].0), "in time order");
        assert!(points.iter().all(|p| p.1.is_finite()));
        // A short series is drawn as it is.
        assert_eq!(thinned(&time[..50], &values[..50], COLUMNS).len(), 49);
    }
}
