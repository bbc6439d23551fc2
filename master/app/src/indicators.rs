//! Accuracy indicators of recorded signals against reference signals:
//! seed 000's fidelity phi (eqs. 7-8) and relative error epsilon (eqs. 10-11).
//!
//! Both come from `S = sum_i int (x_i - r_i)^2 dt / int r_i^2 dt` over the
//! components i: `phi = -1/2 log10 S` (infinite when identical) and
//! `epsilon = sqrt(S)`. Integrals use the trapezoidal rule on the recorded times.
//! Under the `peak` norm epsilon is instead the largest difference relative to the
//! reference's peak (the worst component), and phi = -log10 epsilon alike.

use serde::Serialize;
use slender_scene::spec::Norm;
use std::borrow::Cow;

/// One indicator's value.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Indicator {
    /// The indicator's name as the scene gives it.
    pub name: String,
    /// -1/2 log10 S.
    pub fidelity: f64,
    /// sqrt(S).
    pub relative_error: f64,
    /// The signals whose reference is round-off against the indicator's
    /// largest (a free end's force), each judged against that largest
    /// component's energy instead of its own (`ROUND_OFF_ENERGY`); the run
    /// states them so that no epsilon is read against a scale it does not have.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub floored: Vec<String>,
}

/// Trapezoidal integral of f(t)^2 ... over samples, for `f` given per sample.
pub(crate) fn integral(time: &[f64], f: impl Fn(usize) -> f64) -> f64 {
    (1..time.len())
        .map(|k| 0.5 * (time[k] - time[k - 1]) * (f(k - 1) + f(k)))
        .sum()
}

/// A component's reference energy below this fraction of the indicator's
/// largest (1e-6 in amplitude) is round-off: a free end's 1e-8 N against a
/// 1e4 N load. Such a component is judged against the largest component's
/// energy instead (issue 27: an exact partition was called 88 % off).
pub const ROUND_OFF_ENERGY: f64 = 1e-12;

/// Each reference component's energy `int r_i^2 dt`, and the largest.
fn energies(time: &[f64], r: &[&[f64]]) -> (Vec<f64>, f64) {
    let energy: Vec<f64> = r.iter().map(|r| integral(time, |k| r[k].powi(2))).collect();
    let largest = energy.iter().copied().fold(0.0f64, f64::max);
    (energy, largest)
}

/// The components of references `r` whose energy is round-off against the
/// largest's (each judged against the largest by [`normalized_error`]).
pub fn round_off_components(time: &[f64], r: &[&[f64]]) -> Vec<usize> {
    let (energy, largest) = energies(time, r);
    (0..energy.len())
        .filter(|&i| energy[i] < ROUND_OFF_ENERGY * largest)
        .collect()
}

/// S for signals `x` against references `r` (same times, one column each):
/// each component's squared error over its reference's energy, or over the
/// largest component's where its own is round-off (`ROUND_OFF_ENERGY`).
pub fn normalized_error(time: &[f64], x: &[&[f64]], r: &[&[f64]]) -> f64 {
    let (energy, largest) = energies(time, r);
    x.iter()
        .zip(r)
        .zip(&energy)
        .map(|((x, r), &den)| {
            let num = integral(time, |k| (x[k] - r[k]).powi(2));
            let den = if den < ROUND_OFF_ENERGY * largest {
                largest
            } else {
                den
            };
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
        floored: Vec::new(),
    }
}

/// The samples of `time` at or after `from` (s) and the same rows of each of
/// `columns`: the window an indicator judges, the build-up before it left out.
pub fn window<'a>(
    time: &'a [f64],
    columns: &[&'a [f64]],
    from: Option<f64>,
) -> (&'a [f64], Vec<&'a [f64]>) {
    let first = from.map_or(0, |from| time.partition_point(|&t| t < from));
    let rows = |c: &'a [f64]| &c[first.min(c.len())..];
    (&time[first..], columns.iter().map(|c| rows(c)).collect())
}

/// The indicator called `name` of signals `x` (named `signals`) against
/// references `r` (same times, one column each) under `norm`; under the RMS
/// norm it names the signals judged against the largest component.
pub fn measure(
    (name, signals): (&str, &[String]),
    norm: Norm,
    time: &[f64],
    x: &[&[f64]],
    r: &[&[f64]],
) -> Indicator {
    match norm {
        Norm::Rms => Indicator {
            floored: (round_off_components(time, r).into_iter())
                .filter_map(|k| signals.get(k).cloned())
                .collect(),
            ..indicator(name, normalized_error(time, x, r))
        },
        Norm::Peak => {
            let e = x
                .iter()
                .zip(r)
                .map(|(x, r)| peak_error(x, r))
                .fold(0.0f64, f64::max);
            Indicator {
                name: name.to_owned(),
                fidelity: -e.log10(),
                relative_error: e,
                floored: Vec::new(),
            }
        }
    }
}

/// Largest |x - r| relative to the largest |r|.
pub fn peak_error(x: &[f64], r: &[f64]) -> f64 {
    let peak = r.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
    x.iter()
        .zip(r)
        .fold(0.0f64, |a, (x, r)| a.max((x - r).abs()))
        / peak
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

/// An indicator's components on the recording: its signals and its
/// references, each combined as the indicator asks (`combine`); `None`
/// when one of them is not recorded.
pub type Components<'a> = (Vec<Cow<'a, [f64]>>, Vec<Cow<'a, [f64]>>);

/// [`Components`] of indicator `spec` in `recorder`.
pub fn components<'a>(
    spec: &slender_scene::spec::IndicatorSpec,
    recorder: &'a crate::record::Recorder,
) -> Option<Components<'a>> {
    let columns = |names: &[String]| -> Option<Vec<&'a [f64]>> {
        names.iter().map(|n| recorder.column(n)).collect()
    };
    let (x, r) = (columns(&spec.signals)?, columns(&spec.reference)?);
    Some((spec.combine.apply(x), spec.combine.apply(r)))
}

/// The scene's indicators with references, measured on the recording; one
/// whose window (`from`) holds less than two samples (a run shortened by
/// `--duration`) is left out with a warning, not reported as NaN.
pub fn of_scene(
    scene: &slender_scene::Scene,
    recorder: &crate::record::Recorder,
    warnings: &mut Vec<String>,
) -> Vec<Indicator> {
    let end = recorder.time.last().copied().unwrap_or(f64::NAN);
    let mut measured = Vec::new();
    for spec in (scene.spec.output.indicators.iter()).filter(|s| !s.reference.is_empty()) {
        if window(&recorder.time, &[], spec.from).0.len() < 2 {
            if !recorder.time.is_empty() {
                warnings.push(format!(
                    "output.indicators `{}`: from = {} s leaves less than two recorded samples before the recording's end ({end} s): not measured",
                    spec.name,
                    spec.from.unwrap_or(0.0)
                ));
            }
            continue;
        }
        let Some((x, r)) = components(spec, recorder) else {
            continue;
        };
        let x: Vec<&[f64]> = x.iter().map(|c| &**c).collect();
        let r: Vec<&[f64]> = r.iter().map(|c| &**c).collect();
        let (time, x) = window(&recorder.time, &x, spec.from);
        let (_, r) = window(&recorder.time, &r, spec.from);
        let named = (spec.name.as_str(), spec.signals.as_slice());
        measured.push(measure(named, spec.norm, time, &x, &r));
    }
    measured
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_leaves_out_the_build_up() {
        // A start transient of 10 % that has died out by t = 2: the whole
        // run's error shows it, the window from 2 s does not.
        let t: Vec<f64> = (0..=1000).map(|k| k as f64 * 0.01).collect();
        let r: Vec<f64> = t.iter().map(|t| t.sin()).collect();
        let x: Vec<f64> = (t.iter().zip(&r))
            .map(|(t, r)| r + if *t < 2.0 { 0.1 } else { 0.0 })
            .collect();
        let whole = normalized_error(&t, &[&x], &[&r]);
        let (time, xs) = window(&t, &[&x], Some(2.0));
        let (_, rs) = window(&t, &[&r], Some(2.0));
        assert_eq!((time.len(), time[0]), (801, 2.0));
        assert!(whole > 1e-3, "{whole}");
        assert!(normalized_error(time, &xs, &rs) < 1e-15);
        assert_eq!(window(&t, &[&x], None).0.len(), t.len());
        assert!(window(&t, &[&x], Some(11.0)).0.is_empty());
    }

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

    #[test]
    fn a_component_at_round_off_is_judged_against_the_largest() {
        let t: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
        let load: Vec<f64> = t.iter().map(|t| 1e4 * (1.0 + t.sin())).collect();
        // A free end: 1e-8 N in the reference, 3e-8 N in the run.
        let (free_r, free_x) = (vec![1e-8; t.len()], vec![3e-8; t.len()]);
        let s = normalized_error(&t, &[&load, &free_x], &[&load, &free_r]);
        assert!(s.sqrt() < 1e-11, "{}", s.sqrt());
        // Against itself it would be 200 %.
        assert!((normalized_error(&t, &[&free_x], &[&free_r]).sqrt() - 2.0).abs() < 1e-12);
        assert_eq!(round_off_components(&t, &[&load, &free_r]), [1]);
        assert!(round_off_components(&t, &[&load, &load]).is_empty());
    }

    #[test]
    fn the_peak_norm_takes_the_worst_component_relative_to_its_peak() {
        let t = [0.0, 1.0, 2.0];
        let (r1, x1) = ([1.0, -4.0, 2.0], [1.0, -3.0, 2.0]);
        // 1 of 4 in the first component; 0.15 of 0.5 in the second, the worst.
        let (r2, x2) = ([0.5, 0.5, 0.5], [0.5, 0.65, 0.5]);
        let i = measure(("p", &[]), Norm::Peak, &t, &[&x1, &x2], &[&r1, &r2]);
        assert!((i.relative_error - 0.3).abs() < 1e-15);
        assert!((i.fidelity + 0.3f64.log10()).abs() < 1e-15);
    }
}
