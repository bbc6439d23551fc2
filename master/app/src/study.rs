//! Convergence and cost studies (seed 000 Appendix B): vary one setting at a time,
//! run the scene for each value, and report the relative error of the indicator
//! signals against the finest value (eqs. 10-11), iterations per step and cost per
//! simulated second.

use crate::indicators::{indicator, interpolate};
use crate::run::{RunOptions, run_scene};
use serde::Serialize;
use slender_scene::Scene;
use std::fmt;
use std::str::FromStr;

/// A setting a study can vary.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Knob {
    /// `elements` of every `cable` unit (finest: largest).
    Elements,
    /// `simulation.step` (finest: smallest).
    Step,
    /// `master.tolerances.velocity` (finest: smallest).
    VelocityTolerance,
    /// `master.tolerances.force` (finest: smallest).
    ForceTolerance,
}

impl FromStr for Knob {
    type Err = String;
    fn from_str(s: &str) -> Result<Knob, String> {
        match s {
            "elements" => Ok(Knob::Elements),
            "step" => Ok(Knob::Step),
            "velocity_tolerance" => Ok(Knob::VelocityTolerance),
            "force_tolerance" => Ok(Knob::ForceTolerance),
            other => Err(format!(
                "unknown study setting `{other}`{}: expected elements, step, velocity_tolerance or force_tolerance",
                slender_coupling::error::did_you_mean(
                    other,
                    ["elements", "step", "velocity_tolerance", "force_tolerance"].into_iter()
                )
            )),
        }
    }
}

impl fmt::Display for Knob {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Knob::Elements => "elements",
            Knob::Step => "step",
            Knob::VelocityTolerance => "velocity_tolerance",
            Knob::ForceTolerance => "force_tolerance",
        })
    }
}

/// An indicator's name and its recorded signal columns.
type IndicatorColumns = (String, Vec<Vec<f64>>);

/// One sweep: a setting and its values.
#[derive(Clone, Debug)]
pub struct Sweep {
    pub knob: Knob,
    pub values: Vec<f64>,
}

impl FromStr for Sweep {
    type Err = String;
    /// `name=v1,v2,...`
    fn from_str(s: &str) -> Result<Sweep, String> {
        let (name, list) = s
            .split_once('=')
            .ok_or_else(|| format!("`{s}`: expected SETTING=V1,V2,..., e.g. elements=20,40,80"))?;
        let knob: Knob = name.trim().parse()?;
        let values = list
            .split(',')
            .map(|v| {
                v.trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite() && *x > 0.0)
                    .ok_or_else(|| format!("`{s}`: `{v}` is not a number > 0"))
            })
            .collect::<Result<Vec<f64>, String>>()?;
        if values.len() < 2 {
            return Err(format!("`{s}`: a sweep needs at least two values"));
        }
        if let Some(twice) = values
            .iter()
            .enumerate()
            .find(|(i, v)| values[..*i].contains(v))
            .map(|(_, v)| v)
        {
            return Err(format!(
                "`{s}`: {twice} is given twice; a sweep needs distinct values"
            ));
        }
        if knob == Knob::Elements && values.iter().any(|v| v.fract() != 0.0) {
            return Err(format!("`{s}`: element counts must be whole numbers"));
        }
        Ok(Sweep { knob, values })
    }
}

/// One run of a sweep.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    pub setting: Knob,
    pub value: f64,
    /// Relative error epsilon of each indicator against the finest run.
    pub errors: Vec<(String, f64)>,
    pub iterations_per_step: f64,
    pub cost_per_simulated_second: f64,
    pub error: Option<String>,
}

impl StudyRow {
    /// A run that could not be set up or run.
    fn failed(setting: Knob, value: f64, scene: &Scene, error: String) -> StudyRow {
        StudyRow {
            setting,
            value,
            errors: scene
                .spec
                .output
                .indicators
                .iter()
                .map(|i| (i.name.clone(), f64::NAN))
                .collect(),
            iterations_per_step: f64::NAN,
            cost_per_simulated_second: f64::NAN,
            error: Some(error),
        }
    }
}

/// Applies `value` of `knob` to the scene.
fn apply(scene: &mut Scene, knob: Knob, value: f64) -> Result<(), String> {
    match knob {
        Knob::Elements => {
            let mut found = false;
            for u in &mut scene.spec.units {
                if u.kind.get_ref() == "cable"
                    && let Some(p) = &mut u.parameters
                {
                    p.get_mut()
                        .insert("elements".into(), toml::Value::Integer(value as i64));
                    found = true;
                }
            }
            if !found {
                return Err("the scene has no `cable` unit whose elements could vary".into());
            }
            Ok(())
        }
        Knob::Step => scene.set_step(value).map_err(|e| e.to_string()),
        Knob::VelocityTolerance => {
            scene.spec.master.tolerances.velocity = value;
            Ok(())
        }
        Knob::ForceTolerance => {
            scene.spec.master.tolerances.force = value;
            Ok(())
        }
    }
}

/// Runs every sweep on the scene at `path` (each value on a fresh copy of the
/// scene) and reports one row per run. A run that cannot be set up or fails is a
/// row with its error, and the study goes on; `Err` only when the study itself
/// cannot start (the scene does not load, has no indicators, or `duration` does
/// not fit its step).
pub fn run_study(
    path: &std::path::Path,
    sweeps: &[Sweep],
    duration: Option<f64>,
    mut progress: impl FnMut(&StudyRow),
) -> Result<Vec<StudyRow>, String> {
    let base = Scene::load(path).map_err(|e| e.to_string())?;
    if base.spec.output.indicators.is_empty() {
        return Err(format!(
            "{}: a study compares the signals of [[output.indicators]]; the scene has none",
            path.display()
        ));
    }
    let mut rows = Vec::new();
    for sweep in sweeps {
        let ordered = finest_first(sweep);
        let mut reference: Option<(Vec<f64>, Vec<IndicatorColumns>)> = None;
        let mut sweep_rows = Vec::new();
        for value in ordered {
            let mut scene = Scene::load(path).map_err(|e| e.to_string())?;
            if let Some(d) = duration {
                scene.spec.simulation.duration = d;
                let step = scene.spec.simulation.step;
                scene.set_step(step).map_err(|e| e.to_string())?;
            }
            let options = RunOptions {
                output_dir: None,
                progress: false,
            };
            let result = match apply(&mut scene, sweep.knob, value)
                .and_then(|()| run_scene(&scene, &options).map_err(|e| e.to_string()))
            {
                Ok(result) => result,
                Err(e) => {
                    let row = StudyRow::failed(sweep.knob, value, &scene, e);
                    progress(&row);
                    sweep_rows.push(row);
                    continue;
                }
            };
            let rec = result.recorder;
            let columns = indicator_columns(&scene, &rec);
            let errors = match &reference {
                None => columns.iter().map(|(n, _)| (n.clone(), 0.0)).collect(),
                Some((ref_time, ref_cols)) => {
                    relative_errors(&rec.time, &columns, ref_time, ref_cols)
                }
            };
            let row = StudyRow {
                setting: sweep.knob,
                value,
                errors,
                iterations_per_step: result.summary.counters.mean_iterations(),
                cost_per_simulated_second: result.summary.cost_per_simulated_second,
                error: result.summary.error.clone(),
            };
            progress(&row);
            if reference.is_none() {
                reference = Some((rec.time.clone(), columns));
            }
            sweep_rows.push(row);
        }
        sweep_rows.sort_by(|a, b| a.value.total_cmp(&b.value));
        rows.extend(sweep_rows);
    }
    Ok(rows)
}

/// A sweep's values, the finest first (the reference of the others), then in
/// increasing order.
fn finest_first(sweep: &Sweep) -> Vec<f64> {
    let finest = match sweep.knob {
        Knob::Elements => sweep
            .values
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max),
        _ => sweep.values.iter().copied().fold(f64::INFINITY, f64::min),
    };
    let mut ordered = sweep.values.clone();
    ordered.sort_by(|a, b| {
        if (*a == finest) == (*b == finest) {
            a.total_cmp(b)
        } else if *a == finest {
            std::cmp::Ordering::Less
        } else {
            std::cmp::Ordering::Greater
        }
    });
    ordered
}

/// Each indicator's recorded signal columns of a run.
fn indicator_columns(scene: &Scene, rec: &crate::record::Recorder) -> Vec<IndicatorColumns> {
    scene
        .spec
        .output
        .indicators
        .iter()
        .map(|i| {
            let cols = i
                .signals
                .iter()
                .map(|s| rec.column(s).map(<[f64]>::to_vec).unwrap_or_default())
                .collect();
            (i.name.clone(), cols)
        })
        .collect()
}

/// epsilon of each indicator: the run's signals against the reference run's,
/// interpolated at the run's recorded times.
fn relative_errors(
    time: &[f64],
    columns: &[IndicatorColumns],
    ref_time: &[f64],
    reference: &[IndicatorColumns],
) -> Vec<(String, f64)> {
    columns
        .iter()
        .zip(reference)
        .map(|((name, cols), (_, ref_cols))| {
            let resampled: Vec<Vec<f64>> = ref_cols
                .iter()
                .map(|r| time.iter().map(|&t| interpolate(ref_time, r, t)).collect())
                .collect();
            let x: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
            let r: Vec<&[f64]> = resampled.iter().map(Vec::as_slice).collect();
            let s = crate::indicators::normalized_error(time, &x, &r);
            (name.clone(), indicator(name, s).relative_error)
        })
        .collect()
}

/// The rows as CSV.
pub fn to_csv(rows: &[StudyRow]) -> String {
    let names: Vec<&str> = rows
        .first()
        .map(|r| r.errors.iter().map(|(n, _)| n.as_str()).collect())
        .unwrap_or_default();
    let mut out = format!(
        "setting,value,{},iterations_per_step,cost_per_simulated_second,error\n",
        names
            .iter()
            .map(|n| format!("epsilon_{n}"))
            .collect::<Vec<_>>()
            .join(",")
    );
    for r in rows {
        let eps: Vec<String> = r.errors.iter().map(|(_, e)| format!("{e:e}")).collect();
        out += &format!(
            "{},{},{},{},{:e},{}\n",
            r.setting,
            r.value,
            eps.join(","),
            r.iterations_per_step,
            r.cost_per_simulated_second,
            r.error.as_deref().unwrap_or("").replace(',', ";")
        );
    }
    out
}

/// The rows as a Markdown table.
pub fn to_markdown(rows: &[StudyRow]) -> String {
    let names: Vec<&str> = rows
        .first()
        .map(|r| r.errors.iter().map(|(n, _)| n.as_str()).collect())
        .unwrap_or_default();
    let mut out = format!(
        "| setting | value | {} | iterations/step | cost (s per simulated s) |\n|---|---|{}---|---|\n",
        names
            .iter()
            .map(|n| format!("epsilon {n}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(names.len())
    );
    for r in rows {
        let eps: Vec<String> = r
            .errors
            .iter()
            .map(|(_, e)| {
                if *e == 0.0 {
                    "reference".into()
                } else {
                    format!("{e:.2e}")
                }
            })
            .collect();
        out += &format!(
            "| {} | {} | {} | {:.2} | {:.2e} |{}\n",
            r.setting,
            r.value,
            eps.join(" | "),
            r.iterations_per_step,
            r.cost_per_simulated_second,
            r.error
                .as_ref()
                .map(|e| format!(" failed: {e}"))
                .unwrap_or_default()
        );
    }
    out
}
