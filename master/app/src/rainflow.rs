//! Rainflow counting of a load history by ASTM E1049-85 (reapproved 2017),
//! section 5.4.4: the history is reduced to its reversals, ranges are taken
//! off a stack of three points at a time, and the ranges left at the end
//! each count as half a cycle. Checked on the standard's own example (its
//! figure 6) and against the `rainflow` Python package in
//! `tests/python/analysis_checks.py`.

/// A range counted by rainflow: its size (the signal's unit), its mean and
/// whether it is a whole cycle or half of one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cycle {
    /// Peak to valley (the signal's unit).
    pub range: f64,
    /// The mean of its two extremes.
    pub mean: f64,
    /// 1 for a full cycle, 0.5 for a half cycle.
    pub count: f64,
}

/// The reversals of `values`: the first and last samples and every local
/// extremum between them (plateaus and monotone runs collapsed).
pub fn reversals(values: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for &v in values {
        match out.len() {
            0 => out.push(v),
            1 => {
                if v != out[0] {
                    out.push(v);
                }
            }
            n => {
                let (a, b) = (out[n - 2], out[n - 1]);
                if v == b {
                    continue;
                }
                // Still going the same way: the last point was no reversal.
                if (b - a) * (v - b) > 0.0 {
                    out[n - 1] = v;
                } else {
                    out.push(v);
                }
            }
        }
    }
    out
}

/// The cycles of `values` by ASTM E1049's rainflow counting.
pub fn count(values: &[f64]) -> Vec<Cycle> {
    let mut cycles = Vec::new();
    let mut stack: Vec<f64> = Vec::new();
    for point in reversals(values) {
        stack.push(point);
        while stack.len() >= 3 {
            let n = stack.len();
            let x = (stack[n - 1] - stack[n - 2]).abs();
            let y = (stack[n - 2] - stack[n - 3]).abs();
            if x < y {
                break;
            }
            let mean = 0.5 * (stack[n - 2] + stack[n - 3]);
            if n == 3 {
                // Y holds the starting point: half a cycle, the start dropped.
                cycles.push(Cycle {
                    range: y,
                    mean,
                    count: 0.5,
                });
                stack.remove(0);
            } else {
                cycles.push(Cycle {
                    range: y,
                    mean,
                    count: 1.0,
                });
                stack.drain(n - 3..n - 1);
            }
        }
    }
    cycles.extend(stack.windows(2).map(|w| Cycle {
        range: (w[1] - w[0]).abs(),
        mean: 0.5 * (w[0] + w[1]),
        count: 0.5,
    }));
    cycles
}

#[cfg(test)]
mod tests {
    use super::{count, reversals};

    /// The counts per range, ranges ascending, half cycles added up.
    fn table(values: &[f64]) -> Vec<(f64, f64)> {
        let mut rows: Vec<(f64, f64)> = Vec::new();
        for c in count(values) {
            match rows.iter_mut().find(|r| r.0 == c.range) {
                Some(r) => r.1 += c.count,
                None => rows.push((c.range, c.count)),
            }
        }
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        rows
    }

    #[test]
    fn the_standards_example_gives_its_cycle_table() {
        // ASTM E1049-85 figure 6: -2, 1, -3, 5, -1, 3, -4, 4, -2; its table:
        // range 3: 0.5, 4: 1.5, 6: 0.5, 8: 1.0, 9: 0.5 cycles.
        let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
        assert_eq!(
            table(&history),
            vec![(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]
        );
    }

    #[test]
    fn samples_between_reversals_do_not_count() {
        // The same history sampled finely: straight lines between reversals,
        // with a plateau; the same table.
        let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
        let mut fine = Vec::new();
        for w in history.windows(2) {
            fine.extend((0..10).map(|k| w[0] + (w[1] - w[0]) * k as f64 / 10.0));
            fine.push(w[1]);
        }
        fine.push(-2.0);
        assert_eq!(reversals(&fine), history.to_vec());
        assert_eq!(table(&fine), table(&history));
    }

    #[test]
    fn a_constant_amplitude_signal_counts_one_cycle_per_period() {
        // 50 periods of amplitude 2 about 7: 49.5 full cycles of range 4
        // (whole cycles inside, half ones at the ends) and the start and end
        // half ranges of 2.
        let values: Vec<f64> = (0..=5000)
            .map(|k| 7.0 + 2.0 * (2.0 * std::f64::consts::PI * k as f64 / 100.0).sin())
            .collect();
        let cycles = count(&values);
        let full: f64 = (cycles.iter())
            .filter(|c| (c.range - 4.0).abs() < 1e-9)
            .map(|c| c.count)
            .sum();
        assert!((full - 49.5).abs() < 1e-12, "{full}");
        assert!(cycles.iter().all(|c| (c.mean - 7.0).abs() < 1.0 + 1e-9));
        assert!(count(&[3.0, 3.0, 3.0]).is_empty());
    }
}
