//! A run's analysis of its recorded signals, as `[output] statistics` and
//! `[[output.fatigue]]` ask for it (issue 50): each signal's statistics over
//! the window, its most probable maximum over a longer duration, its power
//! spectrum, and the fatigue damage of the tensions and stresses named. What
//! the scene does not ask for is not computed.

use crate::extremes::{self, Extremes};
use crate::fatigue::{self, Damage};
use crate::plot::PlotError;
use crate::record::Recorder;
use crate::spectrum::{self, SpectralSummary, Spectrum};
use crate::statistics::{self, Statistics};
use serde::Serialize;
use slender_scene::Scene;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What `summary.json` holds of the analysis, per signal (per fatigue entry).
#[derive(Debug, Default, Serialize)]
pub struct Analysis {
    /// With `[output] statistics`: each signal's statistics over the window.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub statistics: BTreeMap<String, Statistics>,
    /// With `statistics.extremes`: each signal's most probable maximum.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub extremes: BTreeMap<String, Extremes>,
    /// With `statistics.spectra`: each signal's spectral moments and periods
    /// (the densities are in `spectra.csv`).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub spectra: BTreeMap<String, SpectralSummary>,
    /// With `[[output.fatigue]]`: each entry's damage over its window.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub fatigue: BTreeMap<String, Damage>,
    /// With `[output] envelopes`: each unit field's extremes along the unit
    /// (the envelopes themselves are in `envelopes.csv`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub envelopes: Vec<crate::envelopes::EnvelopeExtremes>,
}

/// The analysis of `recorder` and the spectra themselves (for the CSV and
/// the figure); a window that holds too little to analyse is said in
/// `warnings`.
pub fn of(
    scene: &Scene,
    recorder: &Recorder,
    envelopes: &[crate::envelopes::Envelope],
    warnings: &mut Vec<String>,
) -> (Analysis, Vec<(String, Spectrum)>) {
    let mut analysis = Analysis {
        envelopes: envelopes.iter().map(|e| e.extremes()).collect(),
        ..Analysis::default()
    };
    let mut spectra = Vec::new();
    let end = recorder.time.last().copied().unwrap_or(f64::NAN);
    let asked = scene.spec.output.statistics;
    let statistics_from = statistics_from(scene);
    if asked.is_some() || !scene.spec.output.fatigue.is_empty() {
        warnings.extend(scene.sea_repeat_warnings(statistics_from));
    }
    if let Some(asked) = asked {
        if statistics_from >= end || end.is_nan() {
            warnings.push(format!(
                "output.statistics.from = {statistics_from} s is not before the recording's end ({end} s): no statistics"
            ));
        }
        for (name, column) in recorder.names.iter().zip(&recorder.columns) {
            let time = &recorder.time;
            if let Some(s) = statistics::of(time, column, statistics_from) {
                analysis.statistics.insert(name.clone(), s);
            }
            if let Some(e) = asked.extremes
                && let Some(x) =
                    extremes::of((time, column), statistics_from, (e.duration, e.threshold))
            {
                analysis.extremes.insert(name.clone(), x);
            }
            if let Some(p) = asked.spectra
                && let Some(s) = spectrum_of(time, column, statistics_from, p.segment)
            {
                analysis.spectra.insert(name.clone(), s.summary());
                spectra.push((name.clone(), s));
            }
        }
        if asked.spectra.is_some() && spectra.is_empty() && !recorder.names.is_empty() {
            warnings.push(
                "output.statistics.spectra: the window holds fewer samples than a segment: no spectra"
                    .into(),
            );
        }
    }
    for f in &scene.spec.output.fatigue {
        let from = f.from.unwrap_or(statistics_from);
        let first = recorder.time.partition_point(|&t| t < from);
        let column = |name: &str| recorder.column(name).map(|c| &c[first.min(c.len())..]);
        let (Some(tension), moment) = (column(&f.tension), f.moment.as_deref().map(column)) else {
            continue;
        };
        if tension.len() < 2 {
            warnings.push(format!(
                "output.fatigue `{}`: fewer than two samples after {from} s: no damage",
                f.name
            ));
            continue;
        }
        let window = end - recorder.time[first];
        let d = fatigue::damage(f, tension, moment.flatten(), window);
        analysis.fatigue.insert(f.name.clone(), d);
    }
    (analysis, spectra)
}

/// The start (s) of the envelopes' window: theirs, else the statistics', else
/// the run's start.
pub fn envelopes_from(scene: &Scene) -> Option<f64> {
    let asked = scene.spec.output.envelopes?;
    Some(asked.from.unwrap_or(statistics_from(scene)))
}

/// The start (s) of the statistics' window: `[output] statistics.from`, else
/// the run's start. Extremes, spectra, fatigue and envelopes default to it.
pub fn statistics_from(scene: &Scene) -> f64 {
    let from = scene.spec.output.statistics.and_then(|s| s.from);
    from.unwrap_or(scene.start.as_secs())
}

/// Welch's spectrum of `values` at `time` from `from` on, with segments of
/// `segment` seconds (default an eighth of the window).
fn spectrum_of(time: &[f64], values: &[f64], from: f64, segment: Option<f64>) -> Option<Spectrum> {
    let first = time.partition_point(|&t| t < from);
    let n = values.len().min(time.len());
    if first + 8 > n {
        return None;
    }
    let dt = (time[n - 1] - time[first]) / (n - 1 - first) as f64;
    let samples = match segment {
        Some(s) => (s / dt).round() as usize,
        None => (n - first) / 8,
    };
    spectrum::welch(&values[first..n], dt, samples)
}

/// Writes `spectra.csv` (frequency and each signal's density) and
/// `spectra.svg` (a panel per signal) into `dir`; nothing without spectra.
pub fn write_spectra(
    dir: &Path,
    scene: &Scene,
    recorder: &Recorder,
    spectra: &[(String, Spectrum)],
) -> Result<Vec<PathBuf>, PlotError> {
    let Some((_, first)) = spectra.first() else {
        return Ok(Vec::new());
    };
    let density_unit = |name: &str| match recorder.unit(name).unwrap_or("") {
        "" => "1/Hz".to_owned(),
        u => format!("({u})^2/Hz"),
    };
    let names: Vec<String> = spectra.iter().map(|(n, _)| n.clone()).collect();
    let units: Vec<String> = names.iter().map(|n| density_unit(n)).collect();
    let mut csv = crate::record::header(&names, &units).replacen("time [s]", "frequency [Hz]", 1);
    for (k, f) in first.frequency_hz.iter().enumerate() {
        csv += &format!("\n{f}");
        for (_, s) in spectra {
            csv += &format!(",{}", s.density.get(k).copied().unwrap_or(f64::NAN));
        }
    }
    csv.push('\n');
    let csv_path = dir.join("spectra.csv");
    crate::whole::write(&csv_path, csv).map_err(|e| PlotError::new(&csv_path, &e))?;
    let svg_path = dir.join("spectra.svg");
    let title = format!("{}: power spectral densities (Welch)", scene.spec.title);
    // The sea states' own spectra first, on the same frequencies, beside the
    // motions they drive.
    let seas: Vec<(String, Spectrum)> = (scene.sea_spectra().iter())
        .map(|sea| (sea_label(sea), sea_density(sea, &first.frequency_hz)))
        .collect();
    let mut panels: Vec<(&str, &str, &Spectrum)> = seas
        .iter()
        .map(|(n, s)| (n.as_str(), "m^2/Hz", s))
        .collect();
    panels.extend((spectra.iter().zip(&units)).map(|((n, s), u)| (n.as_str(), u.as_str(), s)));
    crate::whole::through(&svg_path, |p| crate::plot::spectra(p, &title, &panels))?;
    Ok(vec![csv_path, svg_path])
}

/// A sea state as the figure names it.
fn sea_label(sea: &slender_units::sea::spectrum::Spectrum) -> String {
    format!(
        "sea state: {:?} Hs {} m, Tp {} s (the scene's spectrum)",
        sea.kind, sea.significant_height, sea.peak_period
    )
}

/// The sea state's one-sided density per Hz (2 pi S(w), m^2/Hz) at
/// `frequency_hz`.
fn sea_density(sea: &slender_units::sea::spectrum::Spectrum, frequency_hz: &[f64]) -> Spectrum {
    let two_pi = 2.0 * std::f64::consts::PI;
    Spectrum {
        frequency_hz: frequency_hz.to_vec(),
        density: frequency_hz
            .iter()
            .map(|f| two_pi * sea.density(two_pi * f))
            .collect(),
        segments: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::sea_density;

    #[test]
    fn the_sea_states_density_per_hz_holds_its_variance() {
        // JONSWAP Hs 4 m, Tp 10 s: m0 = Hs^2 / 16 within 2 % (A_gamma's
        // normalisation), integrated per Hz on a fine grid to 1 Hz.
        let sea: slender_units::sea::spectrum::Spectrum =
            toml::from_str("kind = \"jonswap\"\nsignificant_height = 4.0\npeak_period = 10.0")
                .unwrap();
        let df = 1e-4;
        let f: Vec<f64> = (0..=10_000).map(|k| k as f64 * df).collect();
        let s = sea_density(&sea, &f);
        let m0: f64 = s.density.iter().sum::<f64>() * df;
        assert!((m0 / 1.0 - 1.0).abs() < 0.02, "{m0}");
        let peak = (s.density.iter().enumerate())
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(k, _)| f[k])
            .unwrap();
        assert!((peak - 0.1).abs() < 2e-4, "{peak}");
    }
}
