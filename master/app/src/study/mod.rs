//! Convergence and cost studies: vary any scene key by its path (or seed 000
//! Appendix B's short names), one key at a time around the scene or as a grid of
//! every combination, run the runs in parallel, and report the relative error of
//! the indicator signals against the reference run (eqs. 10-11: the finest value
//! of a step, tolerance or element count, else the first value given; or the run
//! of another scene, its indicators matched by name), the observed order of
//! convergence where the key is a step or an element count, iterations per step
//! and cost per simulated second (of the whole run, or of chosen units). An
//! indicator with reference signals of its own is measured inside each run.

mod check;
mod errors;
mod orders;
#[cfg(test)]
mod orders_tests;
pub mod report;
pub mod setting;
mod tasks;
pub mod twin_error;

use crate::AppError;
use crate::resume::Kept;
use crate::run::{RunOptions, run_scene};
use serde::Serialize;
use setting::{Refinement, Setting, label, numeric, parse_value};
use slender_scene::spec::Norm;
use slender_scene::{Draft, Scene};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use tasks::{Assignment, costliest_first, groups};

pub use report::{to_csv, to_markdown, tradeoff};
pub use twin_error::{TwinError, twin_error};

/// An indicator's name and its recorded signal columns.
type IndicatorColumns = (String, Vec<Vec<f64>>);

/// One sweep: a setting and its values.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The key varied.
    pub setting: Setting,
    /// Its values.
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
    /// The sweeps.
    pub sweeps: Vec<Sweep>,
    /// Every combination, or one sweep at a time.
    pub design: Design,
    /// Simulated time of each run (s); the scene's when `None`.
    pub duration: Option<f64>,
    /// Runs at once (1: one after the other).
    pub jobs: usize,
    /// Units whose own stepping time is the cost (their `do_step`, inputs and
    /// outputs); empty: the whole run's wall time.
    pub cost_units: Vec<String>,
    /// Another scene whose run is the reference of every run (its indicators
    /// matched by name, run for `duration` too); none: each group's reference run.
    pub reference: Option<PathBuf>,
    /// The most runs the study may start (`--max-runs`).
    pub max_runs: usize,
    /// Times each run is timed (`--repeats`): its cost is their median.
    pub repeats: usize,
    /// Scene keys set over the file before the study's own settings
    /// (`KEY=VALUE`, `--set`); not applied to `reference`, another scene.
    pub overrides: Vec<String>,
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
    /// Coupling iterations per synchronisation step.
    pub iterations_per_step: f64,
    /// The master's start check: the largest relative change over the first
    /// step of a load a section's statics were solved under.
    pub start_change: Option<f64>,
    /// The median of the run's timed repeats.
    pub cost_per_simulated_second: f64,
    /// (max - min) / median of the repeats' costs (NaN for one).
    pub cost_spread: f64,
    /// Why the run failed, when it did.
    pub error: Option<String>,
    /// `indicator: signal` of each component judged against its indicator's
    /// largest, its reference being round-off against it (a free end's force).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub floored: Vec<String>,
}

/// A run's outcome before errors are computed (kept to resume a study).
#[derive(Serialize, serde::Deserialize)]
struct Outcome {
    time: Vec<f64>,
    columns: Vec<IndicatorColumns>,
    /// The indicators measured inside the run (against reference signals of its own).
    own: Vec<crate::indicators::Indicator>,
    iterations_per_step: f64,
    start_change: Option<f64>,
    cost: f64,
    cost_spread: f64,
    error: Option<String>,
}

/// An indicator as a study judges it.
struct Judged {
    name: String,
    norm: Norm,
    /// Against reference signals inside the run.
    in_run: bool,
    /// The indicator's signals, to name a component judged against its largest.
    signals: Vec<String>,
    /// The time (s) its error is measured from (`from`).
    from: Option<f64>,
}

/// Runs the plan on the scene at `path` and reports one row per run, grouped and
/// sorted by value. A run that cannot be set up or fails is a row with its error
/// and the study goes on; `Err` when the study cannot start (the scene does not
/// load, has no indicators, a key or cost unit does not apply to it, `duration`
/// does not fit its step, or the reference scene lacks an indicator or fails).
/// Rows do not depend on `jobs`.
pub fn run_study(
    path: &Path,
    plan: &StudyPlan,
    progress: impl Fn(&str) + Sync,
) -> Result<Vec<StudyRow>, AppError> {
    run_study_resuming(path, plan, None, progress)
}

/// [`run_study`] that reads back the runs `kept` holds instead of running
/// them again, and keeps each run it finishes without error (see
/// [`crate::resume`]); the reference scene's run is not kept.
pub fn run_study_resuming(
    path: &Path,
    plan: &StudyPlan,
    kept: Option<&Kept>,
    progress: impl Fn(&str) + Sync,
) -> Result<Vec<StudyRow>, AppError> {
    let reference = match &plan.reference {
        Some(r) => Some(run_reference(r, plan.duration)?),
        None => None,
    };
    run_study_kept(path, plan, (reference.as_ref(), kept), progress)
}

/// The run of a reference scene, to measure several studies against (see
/// [`StudyPlan::reference`]).
pub struct ReferenceRun {
    path: PathBuf,
    indicators: Vec<String>,
    outcome: Outcome,
}

/// Runs the reference scene at `path` (for `duration` when given); `Err` when it
/// does not load or its run fails.
pub fn run_reference(path: &Path, duration: Option<f64>) -> Result<ReferenceRun, AppError> {
    let scene = scene_of(&draft_of(path, &[])?, duration)?;
    let outcome = outcome_of(&scene, &[]);
    if let Some(e) = &outcome.error {
        return Err(AppError::Asked(format!(
            "reference {}: {e}",
            path.display()
        )));
    }
    Ok(ReferenceRun {
        path: path.to_owned(),
        indicators: scene
            .spec
            .output
            .indicators
            .iter()
            .map(|i| i.name.clone())
            .collect(),
        outcome,
    })
}

/// [`run_study`] with its reference run given (`plan.reference` is then not
/// read): every run against `reference`, or against its group's reference run.
pub fn run_study_against(
    path: &Path,
    plan: &StudyPlan,
    reference: Option<&ReferenceRun>,
    progress: impl Fn(&str) + Sync,
) -> Result<Vec<StudyRow>, AppError> {
    run_study_kept(path, plan, (reference, None), progress)
}

/// [`run_study_against`], reading back and keeping runs in `kept` as
/// [`run_study_resuming`] does.
fn run_study_kept(
    path: &Path,
    plan: &StudyPlan,
    (reference, kept): (Option<&ReferenceRun>, Option<&Kept>),
    progress: impl Fn(&str) + Sync,
) -> Result<Vec<StudyRow>, AppError> {
    // The scene as written (a `[structure]` still a structure, so its keys
    // vary), with the user's `--set` over it.
    let draft = draft_of(path, &plan.overrides)?;
    let base = scene_of(&draft, None)?;
    let judged = judged_of(path, &base)?;
    check::check_plan(path, &base, &draft, plan, reference.is_some())?;
    if let Some(r) = reference {
        if let Some(j) = judged
            .iter()
            .find(|j| !j.in_run && !r.indicators.contains(&j.name))
        {
            return Err(AppError::Asked(format!(
                "reference {}: no indicator `{}` to compare the study's with",
                r.path.display(),
                j.name
            )));
        }
    }
    if let Some(kept) = kept {
        kept.claim()?;
    }
    let external = reference.map(|r| &r.outcome);
    let groups = groups(plan);
    let all: Vec<&Vec<Assignment>> = groups.iter().flat_map(|(_, runs)| runs).collect();
    let order = costliest_first(&all);
    // Each finished run says which of how many it is, and the time left.
    let counter = crate::progress::Progress::new(all.len());
    let mut outcomes = crate::parallel::run_all(&all, &order, plan.jobs, |assignments| {
        let what: Vec<String> = assignments
            .iter()
            .map(|(s, v)| format!("{s}={}", label(v)))
            .collect();
        let what = what.join(" ");
        let fetched = crate::resume::run_or_reuse(
            kept,
            &what,
            |o: &Outcome| o.error.is_none(),
            || run_one(&draft, assignments, plan, &judged),
        );
        let (o, reused) = (fetched.outcome, fetched.note);
        let k = counter.tick(!fetched.reused);
        let how = match &o.error {
            Some(e) => format!("FAILED: {e}"),
            None => format!(
                "{:.2} it/step, {} s per simulated s{reused}",
                o.iterations_per_step,
                crate::costs::cell(o.cost, o.cost_spread)
            ),
        };
        progress(&format!("{k} {what}: {how}"));
        o
    });
    crate::interrupt::stop_if_requested(&outcomes, |o| o.error.is_none())?;
    let mut rows = Vec::new();
    for (group, runs) in &groups {
        let rest = outcomes.split_off(runs.len());
        let mut group_rows = rows_of(group, runs, &outcomes, external, &judged);
        outcomes = rest;
        group_rows.sort_by(|a, b| a.value.total_cmp(&b.value));
        rows.extend(group_rows);
    }
    Ok(rows)
}

/// What a study judges: the scene's indicators (`Err` when it has none).
fn judged_of(path: &Path, scene: &Scene) -> Result<Vec<Judged>, String> {
    let indicators = &scene.spec.output.indicators;
    if indicators.is_empty() {
        return Err(format!(
            "{}: a study compares the signals of [[output.indicators]]; the scene has none",
            path.display()
        ));
    }
    Ok(indicators
        .iter()
        .map(|i| Judged {
            name: i.name.clone(),
            norm: i.norm,
            in_run: !i.reference.is_empty(),
            signals: i.signals.clone(),
            from: i.from,
        })
        .collect())
}

/// The scene file at `path` as written (a `[structure]` still a structure, so
/// the studies vary its keys), read once, with `overrides` (`KEY=VALUE`,
/// `--set`) set over it; an error names the override.
pub(crate) fn draft_of(path: &Path, overrides: &[String]) -> Result<Draft, AppError> {
    if slender_scene::ssp::is_ssp(path) {
        return Err(AppError::Asked(format!(
            "{}: an SSP is a packaged system, not a scene file, so --set and studies cannot change its keys; set them in the scene it was wrapped from and wrap it again",
            path.display()
        )));
    }
    let mut draft = Draft::read(path)?;
    for text in overrides {
        let (setting, value) = setting::parse_override(text).map_err(|e| format!("--set {e}"))?;
        draft
            .edit(format!("--set {text}"), |t| setting.apply(t, &value))
            .map_err(|e| format!("--set {text}: {e}"))?;
    }
    Ok(draft)
}

/// The scene at `path` with `overrides` (`KEY=VALUE`, `--set`) set over the
/// file; an error names the user's line, or the override it is about.
pub fn scene_with_overrides(path: &Path, overrides: &[String]) -> Result<Scene, AppError> {
    if overrides.is_empty() {
        return Ok(Scene::load(path)?);
    }
    let mut scene = scene_of(&draft_of(path, overrides)?, None)?;
    scene.overrides = overrides.to_vec();
    Ok(scene)
}

/// The scene of `draft`, for `duration` (s) when given. An error names the
/// user's line, or the change it is about.
pub(crate) fn scene_of(draft: &Draft, duration: Option<f64>) -> Result<Scene, AppError> {
    let mut scene = draft.scene()?;
    if let Some(d) = duration {
        scene.spec.simulation.duration = d;
        let step = scene.spec.simulation.step;
        scene.set_step(step)?;
    }
    Ok(scene)
}

/// A study's assignments as the changes they make: `--vary KEY=VALUE`.
fn vary(assignments: &[Assignment]) -> String {
    let with: Vec<String> = (assignments.iter())
        .map(|(s, v)| format!("{s}={}", label(v)))
        .collect();
    format!("--vary {}", with.join(" "))
}

fn run_one(
    draft: &Draft,
    assignments: &[Assignment],
    plan: &StudyPlan,
    judged: &[Judged],
) -> Outcome {
    let mut draft = draft.clone();
    let applied = draft.edit(vary(assignments), |table| {
        (assignments.iter()).try_for_each(|(setting, value)| setting.apply(table, value))
    });
    if let Err(e) = applied {
        return failed(judged, e.to_string());
    }
    match scene_of(&draft, plan.duration) {
        Ok(scene) => {
            let mut o = outcome_of(&scene, &plan.cost_units);
            if o.error.is_none() {
                let again = || {
                    run_scene(&scene, &QUIET)
                        .map_or(f64::NAN, |r| cost_of(&r.summary, &plan.cost_units))
                };
                (o.cost, o.cost_spread) = crate::costs::repeated(plan.repeats, o.cost, again);
            }
            o
        }
        Err(e) => failed(judged, e.to_string()),
    }
}

/// The outcome of a run that could not be set up.
fn failed(judged: &[Judged], error: String) -> Outcome {
    Outcome {
        time: Vec::new(),
        columns: judged
            .iter()
            .map(|j| (j.name.clone(), Vec::new()))
            .collect(),
        own: Vec::new(),
        iterations_per_step: f64::NAN,
        start_change: None,
        cost: f64::NAN,
        cost_spread: f64::NAN,
        error: Some(error),
    }
}

/// A run without output files, progress or pacing.
const QUIET: RunOptions = RunOptions {
    output_dir: None,
    progress: false,
    realtime: false,
};

/// A run's cost per simulated second: that of `cost_units` when given, else
/// the whole run's.
fn cost_of(s: &crate::run::Summary, cost_units: &[String]) -> f64 {
    if cost_units.is_empty() {
        return s.cost_per_simulated_second;
    }
    let time: f64 = s
        .counters
        .units
        .iter()
        .filter(|u| cost_units.contains(&u.name))
        .map(|u| u.step_time_s)
        .sum();
    time / s.simulated_s
}

/// Runs `scene`; its cost is that of `cost_units` when given, else the run's.
fn outcome_of(scene: &Scene, cost_units: &[String]) -> Outcome {
    match run_scene(scene, &QUIET) {
        Ok(result) => {
            let s = &result.summary;
            let cost = cost_of(s, cost_units);
            Outcome {
                columns: indicator_columns(scene, &result.recorder),
                time: result.recorder.time.clone(),
                own: s.indicators.clone(),
                iterations_per_step: s.counters.mean_iterations(),
                start_change: s.counters.start_load.as_ref().map(|l| l.relative_change),
                cost,
                cost_spread: f64::NAN,
                error: s.error.clone(),
            }
        }
        Err(e) => Outcome {
            error: Some(e.to_string()),
            ..failed(&[], String::new())
        },
    }
}

/// Rows of a group: errors against the reference scene's run, else against the
/// group's first run (its reference); indicators with reference signals of their
/// own as the run measured them; and orders.
fn rows_of(
    group: &str,
    runs: &[Vec<Assignment>],
    outcomes: &[Outcome],
    external: Option<&Outcome>,
    judged: &[Judged],
) -> Vec<StudyRow> {
    let reference = external.unwrap_or(&outcomes[0]);
    let mut rows: Vec<StudyRow> = runs
        .iter()
        .zip(outcomes)
        .enumerate()
        .map(|(k, (assignments, o))| {
            let is_reference = k == 0 && external.is_none();
            let measured: Vec<(f64, Vec<String>)> = judged
                .iter()
                .map(|j| errors::judged(j, o, (reference, is_reference)))
                .collect();
            let errors = judged.iter().zip(&measured);
            let floored = errors
                .clone()
                .flat_map(|(j, (_, f))| f.iter().map(move |s| format!("{}: {s}", j.name)))
                .collect();
            let errors = errors.map(|(j, (e, _))| (j.name.clone(), *e)).collect();
            StudyRow {
                group: group.to_owned(),
                settings: assignments
                    .iter()
                    .map(|(s, v)| (s.to_string(), label(v)))
                    .collect(),
                value: numeric(&assignments[0].1).unwrap_or(f64::NAN),
                reference: is_reference,
                errors,
                orders: judged.iter().map(|j| (j.name.clone(), f64::NAN)).collect(),
                iterations_per_step: o.iterations_per_step,
                start_change: o.start_change,
                cost_per_simulated_second: o.cost,
                cost_spread: o.cost_spread,
                error: o.error.clone(),
                floored,
            }
        })
        .collect();
    if runs[0].len() == 1 {
        orders::observed_orders(runs[0][0].0.refinement(), &mut rows);
    }
    rows
}

/// Each indicator's recorded signal columns of a run.
fn indicator_columns(scene: &Scene, rec: &crate::record::Recorder) -> Vec<IndicatorColumns> {
    scene
        .spec
        .output
        .indicators
        .iter()
        .map(|i| {
            let empty: &[f64] = &[];
            let cols = (i.signals.iter())
                .map(|s| rec.column(s).unwrap_or(empty))
                .collect();
            let combined = i.combine.apply(cols);
            (
                i.name.clone(),
                combined.into_iter().map(|c| c.into_owned()).collect(),
            )
        })
        .collect()
}
