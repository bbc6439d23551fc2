//! Convergence and cost studies: vary any scene key by its path (or seed 000
//! Appendix B's short names), one key at a time around the scene or as a grid of
//! every combination, run the runs in parallel, and report the relative error of
//! the indicator signals against the reference run (eqs. 10-11: the finest value
//! of a step, tolerance or element count, else the first value given), the
//! observed order of convergence where the key is a step or an element count,
//! iterations per step and cost per simulated second.

pub mod report;
pub mod setting;

use crate::indicators::{indicator, interpolate};
use crate::run::{RunOptions, run_scene};
use serde::Serialize;
use setting::{Refinement, Setting, label, numeric, parse_value};
use slender_scene::Scene;
use std::path::Path;
use std::str::FromStr;

pub use report::{to_csv, to_markdown};

/// An indicator's name and its recorded signal columns.
type IndicatorColumns = (String, Vec<Vec<f64>>);

/// One sweep: a setting and its values.
#[derive(Clone, Debug)]
pub struct Sweep {
    pub setting: Setting,
    pub values: Vec<toml::Value>,
}

impl FromStr for Sweep {
    type Err = String;
    /// `KEY=v1,v2,...`
    fn from_str(s: &str) -> Result<Sweep, String> {
        let (name, list) = s.split_once('=').ok_or_else(|| {
            format!("`{s}`: expected KEY=V1,V2,..., e.g. elements=20,40,80 or master.scheme=jacobi,gauss_seidel")
        })?;
        let setting: Setting = name.parse()?;
        let values: Vec<toml::Value> = list.split(',').map(parse_value).collect();
        if values.len() < 2 {
            return Err(format!("`{s}`: a sweep needs at least two values"));
        }
        if let Some(twice) = values
            .iter()
            .enumerate()
            .find(|(i, v)| values[..*i].contains(v))
        {
            return Err(format!(
                "`{s}`: {} is given twice; a sweep needs distinct values",
                label(twice.1)
            ));
        }
        if setting.refinement() != Refinement::None {
            for v in &values {
                if !numeric(v).is_some_and(|x| x.is_finite() && x > 0.0) {
                    return Err(format!("`{s}`: `{}` is not a number > 0", label(v)));
                }
            }
        }
        if setting.refinement() == Refinement::Larger
            && values.iter().any(|v| !matches!(v, toml::Value::Integer(_)))
        {
            return Err(format!("`{s}`: element counts must be whole numbers"));
        }
        Ok(Sweep { setting, values })
    }
}

impl Sweep {
    /// The reference value: the finest, or the first given.
    fn reference(&self) -> &toml::Value {
        let by = |pick: fn(f64, f64) -> bool| {
            self.values.iter().fold(&self.values[0], |best, v| {
                if pick(
                    numeric(v).unwrap_or(f64::NAN),
                    numeric(best).unwrap_or(f64::NAN),
                ) {
                    v
                } else {
                    best
                }
            })
        };
        match self.setting.refinement() {
            Refinement::Smaller => by(|a, b| a < b),
            Refinement::Larger => by(|a, b| a > b),
            Refinement::None => &self.values[0],
        }
    }
}

/// How the sweeps combine.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Design {
    /// Each sweep alone, the other keys as the scene has them.
    #[default]
    OneAtATime,
    /// Every combination of the sweeps' values.
    Grid,
}

/// What a study runs.
#[derive(Clone, Debug)]
pub struct StudyPlan {
    pub sweeps: Vec<Sweep>,
    pub design: Design,
    /// Simulated time of each run (s); the scene's when `None`.
    pub duration: Option<f64>,
    /// Runs at once (1: one after the other).
    pub jobs: usize,
}

/// One run of a study.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    /// The sweep (one-at-a-time) or `grid`.
    pub group: String,
    /// Each varied key and its value as given.
    pub settings: Vec<(String, String)>,
    /// The first varied key's value as a number (NaN when it is not one).
    pub value: f64,
    /// Whether this run is the reference of its group.
    pub reference: bool,
    /// Relative error epsilon of each indicator against the reference run.
    pub errors: Vec<(String, f64)>,
    /// Observed order of convergence of each indicator between this run and the
    /// next finer one (NaN where it does not apply).
    pub orders: Vec<(String, f64)>,
    pub iterations_per_step: f64,
    pub cost_per_simulated_second: f64,
    pub error: Option<String>,
}

/// A run's outcome before errors are computed.
struct Outcome {
    time: Vec<f64>,
    columns: Vec<IndicatorColumns>,
    iterations_per_step: f64,
    cost: f64,
    error: Option<String>,
}

/// Runs the plan on the scene at `path` and reports one row per run, grouped and
/// sorted by value. A run that cannot be set up or fails is a row with its error
/// and the study goes on; `Err` when the study cannot start (the scene does not
/// load, has no indicators, a key does not apply to it, or `duration` does not
/// fit its step). Rows do not depend on `jobs`.
pub fn run_study(
    path: &Path,
    plan: &StudyPlan,
    progress: impl Fn(&StudyRow) + Sync,
) -> Result<Vec<StudyRow>, String> {
    let base = Scene::load(path).map_err(|e| e.to_string())?;
    if base.spec.output.indicators.is_empty() {
        return Err(format!(
            "{}: a study compares the signals of [[output.indicators]]; the scene has none",
            path.display()
        ));
    }
    // The scene as written (a `[structure]` still a structure, so its keys vary).
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| e.to_string())?;
    let indicators: Vec<String> = base
        .spec
        .output
        .indicators
        .iter()
        .map(|i| i.name.clone())
        .collect();
    // A key that does not apply (a typo, a unit that is not there) is bad input.
    for sweep in &plan.sweeps {
        let mut probe = table.clone();
        sweep
            .setting
            .apply(&mut probe, sweep.reference())
            .map_err(|e| format!("{}: {e}", sweep.setting))?;
        scene_with(path, &probe, plan.duration)
            .map_err(|e| format!("{} = {}: {e}", sweep.setting, label(sweep.reference())))?;
    }
    let groups = groups(plan);
    let all: Vec<&Vec<Assignment>> = groups.iter().flat_map(|(_, runs)| runs).collect();
    let order = costliest_first(&all);
    let mut outcomes = crate::parallel::run_all(&all, &order, plan.jobs, |assignments| {
        run_one(path, &table, assignments, plan.duration, &indicators)
    });
    let mut rows = Vec::new();
    for (group, runs) in &groups {
        let rest = outcomes.split_off(runs.len());
        let mut group_rows = rows_of(group, runs, &outcomes, &indicators);
        outcomes = rest;
        for r in &group_rows {
            progress(r);
        }
        group_rows.sort_by(|a, b| a.value.total_cmp(&b.value));
        rows.extend(group_rows);
    }
    Ok(rows)
}

/// A varied key with its value.
type Assignment = (Setting, toml::Value);

/// Task indices by likely cost, descending: a run's cost grows with its element
/// counts and falls with its step.
fn costliest_first(tasks: &[&Vec<Assignment>]) -> Vec<usize> {
    let weight = |task: &Vec<Assignment>| {
        task.iter()
            .fold(1.0f64, |w, (s, v)| match (s.refinement(), numeric(v)) {
                (Refinement::Larger, Some(x)) => w * x,
                (Refinement::Smaller, Some(x)) if s.to_string().contains("step") => w / x,
                _ => w,
            })
    };
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| weight(tasks[b]).total_cmp(&weight(tasks[a])));
    order
}

/// The runs of each group, the reference first.
fn groups(plan: &StudyPlan) -> Vec<(String, Vec<Vec<Assignment>>)> {
    match plan.design {
        Design::OneAtATime => plan
            .sweeps
            .iter()
            .map(|s| {
                let mut values: Vec<&toml::Value> = vec![s.reference()];
                values.extend(s.values.iter().filter(|v| *v != s.reference()));
                let runs = values
                    .into_iter()
                    .map(|v| vec![(s.setting.clone(), v.clone())])
                    .collect();
                (s.setting.to_string(), runs)
            })
            .collect(),
        Design::Grid => {
            let mut runs: Vec<Vec<Assignment>> = vec![Vec::new()];
            for s in &plan.sweeps {
                let mut values: Vec<&toml::Value> = vec![s.reference()];
                values.extend(s.values.iter().filter(|v| *v != s.reference()));
                runs = runs
                    .into_iter()
                    .flat_map(|run| {
                        values.iter().map(move |v| {
                            let mut next = run.clone();
                            next.push((s.setting.clone(), (*v).clone()));
                            next
                        })
                    })
                    .collect();
            }
            vec![("grid".into(), runs)]
        }
    }
}

/// The scene of `table`, with `duration` when given.
pub(crate) fn scene_with(
    path: &Path,
    table: &toml::Table,
    duration: Option<f64>,
) -> Result<Scene, String> {
    let text = toml::to_string(table).map_err(|e| e.to_string())?;
    let mut scene = Scene::parse(path, text).map_err(|e| e.to_string())?;
    if let Some(d) = duration {
        scene.spec.simulation.duration = d;
        let step = scene.spec.simulation.step;
        scene.set_step(step).map_err(|e| e.to_string())?;
    }
    Ok(scene)
}

fn run_one(
    path: &Path,
    table: &toml::Table,
    assignments: &[Assignment],
    duration: Option<f64>,
    indicators: &[String],
) -> Outcome {
    let failed = |error: String| Outcome {
        time: Vec::new(),
        columns: indicators.iter().map(|n| (n.clone(), Vec::new())).collect(),
        iterations_per_step: f64::NAN,
        cost: f64::NAN,
        error: Some(error),
    };
    let mut table = table.clone();
    for (setting, value) in assignments {
        if let Err(e) = setting.apply(&mut table, value) {
            return failed(e);
        }
    }
    let scene = match scene_with(path, &table, duration) {
        Ok(s) => s,
        Err(e) => {
            let with: Vec<String> = assignments
                .iter()
                .map(|(s, v)| format!("{s} = {}", label(v)))
                .collect();
            // Line numbers refer to the scene as the study rewrote it.
            return failed(format!("with {}: {e}", with.join(", ")));
        }
    };
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    match run_scene(&scene, &options) {
        Ok(result) => Outcome {
            columns: indicator_columns(&scene, &result.recorder),
            time: result.recorder.time.clone(),
            iterations_per_step: result.summary.counters.mean_iterations(),
            cost: result.summary.cost_per_simulated_second,
            error: result.summary.error.clone(),
        },
        Err(e) => failed(e.to_string()),
    }
}

/// Rows of a group: errors against its first run (the reference) and orders.
fn rows_of(
    group: &str,
    runs: &[Vec<Assignment>],
    outcomes: &[Outcome],
    indicators: &[String],
) -> Vec<StudyRow> {
    let reference = &outcomes[0];
    let mut rows: Vec<StudyRow> = runs
        .iter()
        .zip(outcomes)
        .enumerate()
        .map(|(k, (assignments, o))| {
            let errors = if o.error.is_some() && o.time.is_empty() {
                indicators.iter().map(|n| (n.clone(), f64::NAN)).collect()
            } else if k == 0 {
                indicators.iter().map(|n| (n.clone(), 0.0)).collect()
            } else {
                relative_errors(&o.time, &o.columns, &reference.time, &reference.columns)
            };
            StudyRow {
                group: group.to_owned(),
                settings: assignments
                    .iter()
                    .map(|(s, v)| (s.to_string(), label(v)))
                    .collect(),
                value: numeric(&assignments[0].1).unwrap_or(f64::NAN),
                reference: k == 0,
                errors,
                orders: indicators.iter().map(|n| (n.clone(), f64::NAN)).collect(),
                iterations_per_step: o.iterations_per_step,
                cost_per_simulated_second: o.cost,
                error: o.error.clone(),
            }
        })
        .collect();
    if runs[0].len() == 1 {
        observed_orders(runs[0][0].0.refinement(), &mut rows);
    }
    rows
}

/// p = ln(e_i / e_j) / ln(h_i / h_j) between each non-reference run and the next
/// finer one (h the step, or 1 / elements).
fn observed_orders(refinement: Refinement, rows: &mut [StudyRow]) {
    let size = |v: f64| match refinement {
        Refinement::Smaller => v,
        Refinement::Larger => 1.0 / v,
        Refinement::None => f64::NAN,
    };
    if refinement == Refinement::None {
        return;
    }
    let mut order: Vec<usize> = (0..rows.len()).filter(|&k| !rows[k].reference).collect();
    order.sort_by(|&a, &b| size(rows[b].value).total_cmp(&size(rows[a].value)));
    for pair in order.windows(2) {
        let (coarse, fine) = (pair[0], pair[1]);
        let ratio = (size(rows[coarse].value) / size(rows[fine].value)).ln();
        for i in 0..rows[coarse].errors.len() {
            let p = (rows[coarse].errors[i].1 / rows[fine].errors[i].1).ln() / ratio;
            rows[coarse].orders[i].1 = if p.is_finite() { p } else { f64::NAN };
        }
    }
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
            if ref_time.is_empty() {
                return (name.clone(), f64::NAN);
            }
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
