//! Unstable design points of a UQ study (issue 49 #2). A hybrid loop with
//! long delays can go unstable: its answer grows until a unit gives up or the
//! run ends with an answer no longer of the physics. Such a point is not a
//! failure of the software to be dropped but the worst fidelity of the study:
//! it is detected as such (its error grown far past the reference), counted,
//! and the inputs that drive it are named by Monte Carlo filtering.

use super::Run;
use serde::Serialize;
use slender_scene::Scene;
use slender_uq::filtering::{ks_distance, ks_p_value, wilson};

/// How far a run's answer grew beyond what it should be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Divergence {
    /// The largest growth found: an output's error over its reference's
    /// peak, or a recorded signal's last window peak over its median one.
    pub ratio: f64,
    /// When that growth set in (s).
    pub onset: f64,
}

/// The windows a recorded signal's growth is judged over.
const WINDOWS: usize = 20;

/// The divergence of a recorded run: the larger of (a) the error of each
/// component of the indicators named `outputs` over its reference's peak
/// (the whole record, build-up included; set in when the error first passed
/// the peak) and, for a run a unit `stopped`, (b) each recorded signal's
/// growth up to the stop: its peak in the last of [`WINDOWS`] equal windows
/// over the median of the windows' peaks (set in where the last run of
/// windows above twice the median starts). (b) sees the interface values a
/// hybrid loop feeds back, which grow long before the outputs at the line's
/// ends do: on the truncation example the runs that stop end at 14-45 times
/// their median peak. It is not asked of a run that ran to its end: a
/// signal-loss burst that dies out reaches 12-26 times the median in mid-run
/// and is part of the run's fidelity, not a loop gone unstable. `None` with
/// nothing to judge by.
pub fn divergence(
    scene: &Scene,
    recorder: &crate::record::Recorder,
    (outputs, stopped): (&[String], bool),
) -> Option<Divergence> {
    let mut found: Vec<Divergence> = Vec::new();
    let indicators = scene.spec.output.indicators.iter();
    for spec in indicators.filter(|s| outputs.contains(&s.name)) {
        let Some((x, r)) = crate::indicators::components(spec, recorder) else {
            continue;
        };
        found.extend(
            (x.iter().zip(&r)).filter_map(|(x, r)| against_reference(&recorder.time, x, r)),
        );
    }
    if stopped {
        found.extend((recorder.columns.iter()).filter_map(|c| growth(&recorder.time, c)));
    }
    found.into_iter().max_by(|a, b| a.ratio.total_cmp(&b.ratio))
}

/// One component's error against its reference; `None` when the reference
/// is zero throughout.
fn against_reference(time: &[f64], x: &[f64], r: &[f64]) -> Option<Divergence> {
    let peak = r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if peak == 0.0 || !peak.is_finite() {
        return None;
    }
    let errors = || x.iter().zip(r).map(|(x, r)| (x - r).abs());
    // A non-finite answer has left any range.
    let largest = errors().fold(
        0.0f64,
        |a, e| if e.is_nan() { f64::INFINITY } else { a.max(e) },
    );
    let onset = errors()
        .position(|e| e > peak || e.is_nan())
        .map_or(f64::NAN, |k| time[k]);
    Some(Divergence {
        ratio: largest / peak,
        onset,
    })
}

/// One signal's growth up to the end of its record (its last window's peak
/// over the median window peak); `None` for a record too short to split or
/// a signal whose median window peak is zero.
fn growth(time: &[f64], values: &[f64]) -> Option<Divergence> {
    let (start, end) = (*time.first()?, *time.last()?);
    if time.len() < 2 * WINDOWS || end <= start {
        return None;
    }
    let width = (end - start) / WINDOWS as f64;
    let mut peaks = [0.0f64; WINDOWS];
    for (t, v) in time.iter().zip(values) {
        let w = (((t - start) / width) as usize).min(WINDOWS - 1);
        peaks[w] = if v.is_finite() {
            peaks[w].max(v.abs())
        } else {
            f64::INFINITY
        };
    }
    let mut sorted = peaks;
    sorted.sort_by(f64::total_cmp);
    let median = 0.5 * (sorted[WINDOWS / 2 - 1] + sorted[WINDOWS / 2]);
    if median == 0.0 {
        return None;
    }
    let last = peaks[WINDOWS - 1];
    let first_high = WINDOWS
        - peaks
            .iter()
            .rev()
            .take_while(|&&p| p > 2.0 * median)
            .count();
    Some(Divergence {
        ratio: last / median,
        onset: start + first_high as f64 * width,
    })
}

/// What the runs say about the loop's stability over the inputs.
#[derive(Clone, Debug, Serialize)]
pub struct Stability {
    /// Runs whose loop went unstable.
    pub unstable_runs: usize,
    /// Runs that ran to their end on a stable loop.
    pub stable_runs: usize,
    /// The probability of instability over the inputs: unstable over stable
    /// and unstable runs (the failed ones, for other reasons, left out).
    pub probability: f64,
    /// Its 95 % Wilson interval.
    pub interval: (f64, f64),
    /// The growth past which a run counts as unstable (`unstable_growth`).
    pub growth: f64,
    /// The phi an unstable run counts as in the expansions.
    pub counted_as: f64,
    /// Each unstable run's design index and when its growth set in (s).
    pub onsets: Vec<(usize, f64)>,
    /// Each input's part in it, the most telling first.
    pub drivers: Vec<Driver>,
}

/// One input's part in the instability (Monte Carlo filtering).
#[derive(Clone, Debug, Serialize)]
pub struct Driver {
    /// The input's name.
    pub input: String,
    /// The Kolmogorov-Smirnov distance between its values at the unstable
    /// points and at the stable ones (0: it does not matter; 1: it decides).
    pub distance: f64,
    /// The distance's p-value (small: not by chance).
    pub p_value: f64,
    /// Its mean at the unstable points.
    pub mean_unstable: f64,
    /// Its mean at the stable points.
    pub mean_stable: f64,
}

/// The stability of the study's `runs` (inputs named `names`); `None` when
/// no run went unstable.
pub fn assess(names: &[String], runs: &[Run], growth: f64, counted_as: f64) -> Option<Stability> {
    let unstable: Vec<&Run> = runs.iter().filter(|r| r.unstable()).collect();
    if unstable.is_empty() {
        return None;
    }
    let stable: Vec<&Run> = runs.iter().filter(|r| r.stable()).collect();
    let column =
        |group: &[&Run], i: usize| -> Vec<f64> { group.iter().map(|r| r.inputs[i]).collect() };
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let mut drivers: Vec<Driver> = (names.iter().enumerate())
        .map(|(i, input)| {
            let (u, s) = (column(&unstable, i), column(&stable, i));
            let distance = ks_distance(&u, &s);
            Driver {
                input: input.clone(),
                distance,
                p_value: ks_p_value(distance, u.len(), s.len()),
                mean_unstable: mean(&u),
                mean_stable: mean(&s),
            }
        })
        .collect();
    drivers.sort_by(|a, b| b.distance.total_cmp(&a.distance));
    let trials = unstable.len() + stable.len();
    Some(Stability {
        unstable_runs: unstable.len(),
        stable_runs: stable.len(),
        probability: unstable.len() as f64 / trials as f64,
        interval: wilson(unstable.len(), trials, 1.96),
        growth,
        counted_as,
        onsets: (runs.iter().enumerate())
            .filter_map(|(k, r)| r.unstable_from.map(|t| (k, t)))
            .collect(),
        drivers,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_growing_error_sets_in_where_it_passes_the_reference_peak() {
        let time: Vec<f64> = (0..=100).map(|k| k as f64 * 0.1).collect();
        let r: Vec<f64> = time.iter().map(|t| t.sin()).collect();
        // Stable: a 10 % error never passes the reference's peak.
        let x: Vec<f64> = r.iter().map(|r| 1.1 * r).collect();
        let d = against_reference(&time, &x, &r).unwrap();
        assert!(d.ratio < 0.11 && d.onset.is_nan(), "{d:?}");
        // Growing as exp(t - 5): past the peak (just under 1) from t = 5 on.
        let x: Vec<f64> = (time.iter().zip(&r))
            .map(|(t, r)| r + (t - 5.0).exp())
            .collect();
        let d = against_reference(&time, &x, &r).unwrap();
        assert!(d.ratio > 140.0, "{d:?}");
        assert!((d.onset - 5.0).abs() < 1e-12, "{d:?}");
        // A non-finite answer is infinitely far.
        let mut x = r.clone();
        x[50] = f64::NAN;
        assert_eq!(
            against_reference(&time, &x, &r).unwrap().ratio,
            f64::INFINITY
        );
        assert!(against_reference(&time, &x, &vec![0.0; time.len()]).is_none());
    }

    #[test]
    fn a_signal_that_grows_past_its_median_peak_is_found_with_its_onset() {
        let time: Vec<f64> = (0..=2000).map(|k| k as f64 * 0.1).collect();
        // Stable: a unit sine with one burst of fifty times its amplitude
        // that dies out.
        let burst: Vec<f64> = (time.iter())
            .map(|&t| t.sin() * if (50.0..52.0).contains(&t) { 50.0 } else { 1.0 })
            .collect();
        let g = growth(&time, &burst).unwrap();
        assert!((0.9..=1.1).contains(&g.ratio), "{g:?}");
        // Growing from t = 150 s on: the last five windows are high.
        let growing: Vec<f64> = (time.iter())
            .map(|&t| {
                t.sin()
                    * if t > 150.0 {
                        (0.1 * (t - 150.0)).exp()
                    } else {
                        1.0
                    }
            })
            .collect();
        let g = growth(&time, &growing).unwrap();
        assert!(g.ratio > 100.0, "{g:?}");
        assert_eq!(g.onset, 150.0, "{g:?}");
        assert!(growth(&time[..10], &growing[..10]).is_none());
        assert!(growth(&time, &vec![0.0; time.len()]).is_none());
    }

    fn run(inputs: [f64; 2], unstable_from: Option<f64>) -> Run {
        Run {
            inputs: inputs.to_vec(),
            outputs: vec![1.0],
            unstable_from,
        }
    }

    #[test]
    fn the_input_that_decides_ranks_first() {
        // Unstable wherever a > 0.7; b plays no part.
        let runs: Vec<Run> = (0..100)
            .map(|k| {
                let (a, b) = ((k as f64 + 0.5) / 100.0, ((k * 37) % 100) as f64 / 100.0);
                run([a, b], (a > 0.7).then_some(1.0))
            })
            .collect();
        let names = ["a".to_string(), "b".to_string()];
        let s = assess(&names, &runs, 10.0, 0.0).unwrap();
        assert_eq!((s.unstable_runs, s.stable_runs), (30, 70));
        assert!((s.probability - 0.3).abs() < 1e-12);
        assert!(s.interval.0 < 0.3 && 0.3 < s.interval.1);
        assert_eq!(s.drivers[0].input, "a");
        assert_eq!(s.drivers[0].distance, 1.0);
        assert!(s.drivers[0].p_value < 1e-6);
        assert!(s.drivers[1].distance < 0.3 && s.drivers[1].p_value > 0.05);
        assert!(s.drivers[0].mean_unstable > 0.8 && s.drivers[0].mean_stable < 0.4);
        assert_eq!(s.onsets.len(), 30);
        assert!(assess(&names, &runs[..50], 10.0, 0.0).is_none());
    }
}
