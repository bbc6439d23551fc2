//! `slender cases`: a load-case matrix (issue 50). A scene's sea (every wave
//! `spectrum` table it holds: the same sea drives every unit) is set to each
//! sea state of a scatter, each heading and each seed in turn; every case is
//! a run whose analysis (`[output] statistics`, `extremes`,
//! `[[output.fatigue]]`) becomes a row of `cases.csv`; the rows aggregate
//! into a design value per signal and a fatigue life over the scatter
//! (`aggregate`). Runs go on a few threads, or as shards of a Slurm job array
//! merged afterwards: the rows are the same whatever the split.

pub mod aggregate;
pub mod markdown;
pub mod table;

use crate::AppError;
use crate::run::{RunOptions, run_scene};
use serde::Deserialize;
use slender_scene::spec::{CasesHeading, CasesSpec};
use slender_scene::{Draft, Scene};
use std::path::Path;
use std::sync::Mutex;

/// A sea state of the scatter: its significant height (m), peak period (s)
/// and probability of occurrence.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeaState {
    /// Significant wave height Hs (m).
    pub significant_height: f64,
    /// Peak period Tp (s).
    pub peak_period: f64,
    /// Probability of occurrence, in [0, 1].
    pub probability: f64,
}

/// A wave heading (degrees, the scene's `heading_deg`) and its probability.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Heading {
    /// Heading (deg).
    pub degrees: f64,
    /// Probability of the heading, in [0, 1].
    pub probability: f64,
}

/// What a matrix runs.
#[derive(Clone, Debug)]
pub struct CasesPlan {
    /// The sea states of the scatter.
    pub seas: Vec<SeaState>,
    /// The headings; none: the scene's own.
    pub headings: Vec<Heading>,
    /// The seeds of each sea state and heading: 1 to `seeds`.
    pub seeds: u64,
    /// Runs at once.
    pub jobs: usize,
    /// Simulated time of each run (s); the scene's when `None`.
    pub duration: Option<f64>,
    /// Run only shard K of N (1-based): the cases whose index is K - 1 modulo N.
    pub shard: Option<(usize, usize)>,
    /// The most runs the matrix may have (`--max-runs`).
    pub max_runs: usize,
    /// Scene keys set over the file first (`KEY=VALUE`, `--set`).
    pub overrides: Vec<String>,
}

/// One case: indices into the plan's seas and headings, and its seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Case {
    /// Index into the plan's sea states.
    pub sea: usize,
    /// Index into the plan's headings; none: the scene's own.
    pub heading: Option<usize>,
    /// The sea's seed (1 to the plan's `seeds`).
    pub seed: u64,
}

impl CasesPlan {
    /// Every case, sea states outermost, then headings, then seeds.
    pub fn cases(&self) -> Vec<Case> {
        let headings: Vec<Option<usize>> = if self.headings.is_empty() {
            vec![None]
        } else {
            (0..self.headings.len()).map(Some).collect()
        };
        let mut cases = Vec::new();
        for sea in 0..self.seas.len() {
            for &heading in &headings {
                cases.extend((1..=self.seeds).map(|seed| Case { sea, heading, seed }));
            }
        }
        cases
    }

    /// The case in words, as a change's origin and a row's label.
    pub fn describe(&self, case: &Case) -> String {
        let s = &self.seas[case.sea];
        let heading = case.heading.map_or(String::new(), |h| {
            format!(", heading {} deg", self.headings[h].degrees)
        });
        format!(
            "Hs {} m, Tp {} s{heading}, seed {}",
            s.significant_height, s.peak_period, case.seed
        )
    }
}

/// One case's values (NaN where it failed) and why it failed.
pub type Row = (Vec<f64>, Option<String>);

/// A matrix's scene checked before its first run: the draft its cases
/// change, and the columns of a row.
pub struct Checked {
    draft: Draft,
    /// The columns every case gives (`table::columns`).
    pub columns: Vec<String>,
    /// Each run's window and the storm its extremes are for.
    pub durations: aggregate::Durations,
}

/// Checks the plan and the scene: at least one sea state, positive heights,
/// periods and probabilities, a scene with a wave spectrum, an `[output]
/// statistics` window, and a first case that builds (a heading the scene's
/// sea does not take is refused here, before any run).
pub fn check(path: &Path, plan: &CasesPlan) -> Result<Checked, AppError> {
    check_plan(plan)?;
    let draft = crate::study::draft_of(path, &plan.overrides)?;
    let cases = plan.cases();
    if cases.len() > plan.max_runs {
        return Err(crate::too_many_runs("the matrix", cases.len(), plan.max_runs).into());
    }
    // Each heading's first case builds (a heading the scene's sea or body
    // does not cover is refused before any run); the first gives the columns.
    for case in cases.iter().filter(|c| c.sea == 0 && c.seed == 1).skip(1) {
        crate::study::scene_of(&case_draft(&draft, plan, case)?, plan.duration)?;
    }
    let probe = case_draft(&draft, plan, &cases[0])?;
    let scene = crate::study::scene_of(&probe, plan.duration)?;
    if scene.spec.output.statistics.is_none() {
        return Err(AppError::Asked(
            "a load-case matrix judges each case by its statistics: give the scene `[output] statistics = { from = S }` (with `extremes = { duration = D }` and `[[output.fatigue]]` for the design values and the fatigue life)".into(),
        ));
    }
    let master = scene.build().map_err(AppError::Scene)?;
    let columns = table::columns(&scene, &scene.signals(&master));
    let (from, end) = (
        crate::analysis::statistics_from(&scene),
        scene.end().as_secs(),
    );
    if end <= from {
        return Err(AppError::Asked(format!(
            "the statistics start at {from} s (`[output] statistics.from`), at or after the runs' end at {end} s: every case's extremes and damage would be NaN; give a --duration that reaches past {from} s"
        )));
    }
    let durations = aggregate::Durations {
        window_s: end - from,
        storm_s: (scene.spec.output.statistics)
            .and_then(|s| s.extremes)
            .map(|e| e.duration),
    };
    Ok(Checked {
        draft,
        columns,
        durations,
    })
}

/// `plan` with the scene's `[cases]` (with `plan.overrides` set) where the
/// command line gave no sea state: its seas, its headings unless the command
/// line gave some, and its seeds unless `seeds` (the command line's) is
/// given; a scene without the table is refused with what to give.
pub fn with_scene_matrix(
    path: &Path,
    mut plan: CasesPlan,
    seeds: Option<u64>,
) -> Result<CasesPlan, AppError> {
    plan.seeds = seeds.unwrap_or(1);
    if !plan.seas.is_empty() {
        return Ok(plan);
    }
    // Only the table is read here: `check` builds the scene, once.
    let draft = crate::study::draft_of(path, &plan.overrides)?;
    let table = draft.table().get("cases").cloned();
    let read = table.map(CasesSpec::deserialize).transpose();
    let Some(matrix) = read.map_err(|e| AppError::Asked(format!("`cases`: {e}")))? else {
        return Err(AppError::Asked(format!(
            "no sea state: give at least one --sea HS,TP,PROBABILITY, or a `[cases]` table (`seas = [[HS, TP, P], ...]`) in {}",
            path.display()
        )));
    };
    plan.seas = (matrix.seas.iter())
        .map(|&[hs, tp, p]| SeaState {
            significant_height: hs,
            peak_period: tp,
            probability: p,
        })
        .collect();
    if plan.headings.is_empty() {
        plan.headings = scene_headings(&matrix.headings)?;
    }
    plan.seeds = seeds.or(matrix.seeds).unwrap_or(1);
    Ok(plan)
}

/// `[cases] headings`: all with their probability or none (equal shares).
fn scene_headings(given: &[CasesHeading]) -> Result<Vec<Heading>, AppError> {
    let weighted = given
        .iter()
        .filter(|h| matches!(h, CasesHeading::Weighted(_)))
        .count();
    if weighted != 0 && weighted != given.len() {
        return Err(AppError::Asked(
            "`cases.headings`: give every heading as [DEG, PROBABILITY] or every one as DEG (equal shares)".into(),
        ));
    }
    let equal = 1.0 / given.len().max(1) as f64;
    Ok((given.iter())
        .map(|h| match *h {
            CasesHeading::Shared(degrees) => Heading {
                degrees,
                probability: equal,
            },
            CasesHeading::Weighted([degrees, probability]) => Heading {
                degrees,
                probability,
            },
        })
        .collect())
}

/// Positive heights, periods and probabilities; seeds and sea states given.
fn check_plan(plan: &CasesPlan) -> Result<(), AppError> {
    let bad = |what: String| Err(AppError::Asked(what));
    if plan.seas.is_empty() {
        return bad("no sea state: give at least one --sea HS,TP,PROBABILITY".into());
    }
    if plan.seeds == 0 {
        return bad("seeds = 0 (--seeds or `cases.seeds`): expected at least 1".into());
    }
    let positive = |v: f64| v.is_finite() && v > 0.0;
    for s in &plan.seas {
        if !(positive(s.significant_height) && positive(s.peak_period) && positive(s.probability)) {
            return bad(format!(
                "sea state {},{},{} (--sea or `cases.seas`): expected a positive height (m), period (s) and probability",
                s.significant_height, s.peak_period, s.probability
            ));
        }
    }
    for h in &plan.headings {
        if !(h.degrees.is_finite() && positive(h.probability)) {
            return bad(format!(
                "heading {},{} (--heading or `cases.headings`): expected a heading (deg) and a positive probability",
                h.degrees, h.probability
            ));
        }
    }
    Ok(())
}

/// The scene's draft with `case`'s sea set in every wave spectrum it holds.
fn case_draft(draft: &Draft, plan: &CasesPlan, case: &Case) -> Result<Draft, AppError> {
    let mut changed = draft.clone();
    let sea = plan.seas[case.sea];
    let heading = case.heading.map(|h| plan.headings[h].degrees);
    changed.edit(format!("case {}", plan.describe(case)), |table| {
        match set_sea(table, &sea, heading, case.seed) {
            0 => Err(AppError::Asked(
                "the scene holds no wave `spectrum` table for the sea states to set (a `[mooring.waves]`, a line's `waves` or a signal's `sea`)".into(),
            )),
            _ => Ok(()),
        }
    })?;
    Ok(changed)
}

/// Sets the sea state, seed and heading in every `spectrum` table (one with
/// a `kind`) under `table`, the heading as `heading_deg` beside it; returns
/// how many it set.
fn set_sea(table: &mut toml::Table, sea: &SeaState, heading: Option<f64>, seed: u64) -> usize {
    let mut count = 0;
    let is_spectrum = |v: &toml::Value| v.as_table().is_some_and(|t| t.contains_key("kind"));
    if let Some(toml::Value::Table(spectrum)) = table.get_mut("spectrum")
        && spectrum.contains_key("kind")
    {
        spectrum.insert("significant_height".into(), sea.significant_height.into());
        spectrum.insert("peak_period".into(), sea.peak_period.into());
        spectrum.insert("seed".into(), toml::Value::Integer(seed as i64));
        count += 1;
        if let Some(h) = heading {
            table.insert("heading_deg".into(), h.into());
        }
    }
    for (key, value) in table.iter_mut() {
        if key == "spectrum" && is_spectrum(value) {
            continue;
        }
        match value {
            toml::Value::Table(inner) => count += set_sea(inner, sea, heading, seed),
            toml::Value::Array(items) => {
                for item in items.iter_mut() {
                    if let toml::Value::Table(inner) = item {
                        count += set_sea(inner, sea, heading, seed);
                    }
                }
            }
            _ => {}
        }
    }
    count
}

/// Runs the cases the plan holds (a shard's, or all), reusing the completed
/// rows of `earlier` and calling `done` with each new row as it finishes.
pub fn run_checked(
    plan: &CasesPlan,
    checked: &Checked,
    earlier: &[Option<Row>],
    done: impl Fn(usize, &Row, &str) + Sync,
) -> Result<Vec<Option<Row>>, AppError> {
    let cases = plan.cases();
    let order: Vec<usize> = match plan.shard {
        Some((k, n)) if k >= 1 && k <= n => (k - 1..cases.len()).step_by(n).collect(),
        Some((k, n)) => {
            return Err(AppError::Asked(format!(
                "--shard {k}/{n}: expected K in 1..=N"
            )));
        }
        None => (0..cases.len()).collect(),
    };
    let kept = |k: usize| {
        earlier
            .get(k)
            .and_then(Option::as_ref)
            .filter(|r| r.1.is_none())
    };
    let counter =
        crate::progress::Progress::new(order.iter().filter(|&&k| kept(k).is_none()).count());
    let fresh = Mutex::new(());
    let tasks: Vec<usize> = (0..order.len()).collect();
    let rows = crate::parallel::run_all(&order, &tasks, plan.jobs, |&k| {
        if let Some(row) = kept(k) {
            return row.clone();
        }
        let row = run_case(plan, checked, &cases[k]);
        let _turn = fresh.lock().unwrap_or_else(|e| e.into_inner());
        done(k, &row, &counter.tick(row.1.is_none()));
        row
    });
    crate::interrupt::stop_if_requested(&rows, |r| r.1.is_none())?;
    let mut all = vec![None; cases.len()];
    for (&k, row) in order.iter().zip(rows) {
        all[k] = Some(row);
    }
    Ok(all)
}

/// One case run: its row of values, or NaNs and the reason it failed.
fn run_case(plan: &CasesPlan, checked: &Checked, case: &Case) -> Row {
    let failed = |why: String| (vec![f64::NAN; checked.columns.len()], Some(why));
    let scene: Scene = match case_draft(&checked.draft, plan, case)
        .and_then(|d| crate::study::scene_of(&d, plan.duration))
    {
        Ok(scene) => scene,
        Err(e) => return failed(e.to_string()),
    };
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    match run_scene(&scene, &options) {
        Ok(result) if result.summary.status == "completed" => (
            table::values(&checked.columns, &result.summary.analysis),
            None,
        ),
        Ok(result) => failed(result.summary.error.unwrap_or(result.summary.status)),
        Err(e) => failed(e.to_string()),
    }
}

#[cfg(test)]
mod tests;
