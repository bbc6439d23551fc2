//! Running a scene end to end: initialise, step to the end with a progress bar,
//! record, and write `timeseries.csv`, `summary.json` and SVG plots.

use crate::plot::{self, PlotError};
use crate::realtime::{Pacer, RealtimeReport};
use crate::record::Recorder;
use crate::watch::Watch;
use crate::whole;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use slender_coupling::counters::Counters;
use slender_coupling::coupler::Master;
use slender_coupling::error::MasterError;
use slender_scene::{Scene, SceneError};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How to run a scene.
pub struct RunOptions {
    /// Results folder; `None`: record in memory only, write nothing.
    pub output_dir: Option<PathBuf>,
    /// Show a progress bar once the run has lasted a second.
    pub progress: bool,
    /// Pace every step against the wall clock and report the computing times
    /// (`--realtime`; no progress bar then).
    pub realtime: bool,
}

/// What `summary.json` holds.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// The scene file.
    pub scene: String,
    /// Keys set over the scene file (`run --set`), as given.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub overrides: Vec<String>,
    /// The scene's title.
    pub title: String,
    /// "completed", "failed" or "interrupted" (Ctrl-C, at a step boundary).
    pub status: String,
    /// Why the run failed, when it did.
    pub error: Option<String>,
    /// Start time (s).
    pub start_s: f64,
    /// Synchronisation step (s).
    pub step_s: f64,
    /// Simulated time actually covered (s).
    pub simulated_s: f64,
    /// Wall time of the run (s).
    pub wall_time_s: f64,
    /// Wall time per simulated second (s/s).
    pub cost_per_simulated_second: f64,
    /// The units in the master's order.
    pub order: Vec<String>,
    /// The master's settings as run.
    pub settings: slender_coupling::settings::MasterSettings,
    /// The master's counters (steps, iterations, rollbacks, ...).
    pub counters: Counters,
    /// Indicators of `[[output.indicators]]` over the recorded time.
    pub indicators: Vec<crate::indicators::Indicator>,
    /// With `[output] statistics` and `[[output.fatigue]]`: each recorded
    /// signal's statistics, extremes and spectrum over the window asked for
    /// (the build-up left out), and the fatigue damage asked for.
    #[serde(flatten)]
    pub analysis: crate::analysis::Analysis,
    /// The unit of measure of each recorded signal (the timeseries.csv
    /// columns; `""` for a dimensionless one).
    pub units: BTreeMap<String, String>,
    /// The computing time per step of a paced run (`--realtime`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub realtime: Option<RealtimeReport>,
    /// The scene's advisories (`Scene::advisories`) and the plausibility
    /// watch's warnings (`crate::watch`), when any.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// The outcome of a run: the summary, the recording and the files written.
pub struct RunResult {
    /// What `summary.json` holds.
    pub summary: Summary,
    /// The recorded signals.
    pub recorder: Recorder,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Runs `scene`. A failure of the simulation itself is reported in the summary
/// (status "failed") with the results recorded up to it; `Err` is returned only
/// when nothing could be run or written.
pub fn run_scene(scene: &Scene, options: &RunOptions) -> Result<RunResult, RunError> {
    let mut master = scene.build()?;
    let mut files = Vec::new();
    let csv_path = fresh_csv_in(options.output_dir.as_deref())?;
    let signals = scene.signals(&master);
    check_output_size(scene, signals.len())?;
    let mut recorder = Recorder::new(
        &master,
        signals,
        scene.spec.output.every,
        csv_path.as_deref(),
    )?;
    if let Some(from) = crate::analysis::envelopes_from(scene) {
        recorder.envelope_from(from);
    }
    let started = Instant::now();
    // The scene's advisories first, then the plausibility watch's.
    let mut warnings = scene.advisories.clone();
    if let Some(unit) = master.one_sweep_blocked_by() {
        warnings.push(format!(
            "master.newton.one_sweep: unit `{unit}` cannot correct its step (its kind offers no linear correction, or it steps in sub-steps): every step is iterated as without one_sweep"
        ));
    }
    let (outcome, realtime) = simulate(scene, &mut master, &mut recorder, (options, &mut warnings));
    let wall = started.elapsed().as_secs_f64();
    recorder.finish()?;
    if let Some(p) = csv_path {
        files.push(p);
    }
    let simulated = (master.time() - scene.start).as_secs();
    // Plots before the summary: a run whose figures cannot be written is not
    // reported as completed.
    let mut outcome = outcome.map_err(|e| e.to_string());
    let analysis = analyse_and_draw(
        scene,
        &mut recorder,
        options.output_dir.as_deref(),
        (&mut outcome, &mut files),
        &mut warnings,
    );
    let indicators = crate::indicators::of_scene(scene, &recorder, &mut warnings);
    let summary = Summary {
        scene: scene.path.display().to_string(),
        overrides: scene.overrides.clone(),
        title: scene.spec.title.clone(),
        status: status_of(&outcome).into(),
        error: outcome.err(),
        start_s: scene.start.as_secs(),
        step_s: scene.step.as_secs(),
        simulated_s: simulated,
        wall_time_s: wall,
        cost_per_simulated_second: if simulated > 0.0 {
            wall / simulated
        } else {
            f64::NAN
        },
        order: master.order().into_iter().map(String::from).collect(),
        settings: master.settings().clone(),
        counters: master.counters(),
        indicators,
        analysis,
        units: (recorder.names.iter().cloned())
            .zip(recorder.units.iter().cloned())
            .collect(),
        realtime,
        warnings,
    };
    if let (Some(dir), Some(report)) = (&options.output_dir, &summary.realtime) {
        files.push(write_overruns(dir, report)?);
    }
    if let Some(dir) = &options.output_dir {
        write_summary(dir, &summary, &mut files)?;
    }
    Ok(RunResult {
        summary,
        recorder,
        files,
    })
}

/// Writes `summary.json` and the run's report page into `dir`.
fn write_summary(dir: &Path, summary: &Summary, files: &mut Vec<PathBuf>) -> Result<(), RunError> {
    let path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(summary)?;
    whole::write(&path, text).map_err(|e| RunError::file(&path, &e))?;
    files.push(report_page(dir, summary, files)?);
    files.push(path);
    Ok(())
}

/// Writes the run's `report.html` (its summary and figures) into `dir`.
fn report_page(dir: &Path, summary: &Summary, files: &[PathBuf]) -> Result<PathBuf, RunError> {
    let figures: Vec<PathBuf> = (files.iter())
        .filter(|f| f.extension().is_some_and(|e| e == "svg"))
        .cloned()
        .collect();
    let parts = crate::report::run_page::parts(summary, &figures);
    let title = format!("Run of {}", summary.scene);
    let html = crate::report::page(&title, &crate::report::command_line(), &parts);
    let path = dir.join("report.html");
    whole::write(&path, html).map_err(|e| RunError::file(&path, &e))?;
    Ok(path)
}

/// A run's status from its outcome: `completed`, `interrupted` (Ctrl-C) or `failed`.
fn status_of(outcome: &Result<(), String>) -> &'static str {
    match outcome {
        Ok(()) => "completed",
        Err(_) if crate::interrupt::requested() => "interrupted",
        Err(_) => "failed",
    }
}

/// Why a run could not be set up or stopped early: the scene does not build, the
/// coupled simulation failed, or its results could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RunError {
    /// The scene does not read or build.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The master failed.
    #[error(transparent)]
    Master(Box<MasterError>),
    /// A results file or folder and what went wrong.
    #[error("{path}: {reason}")]
    File {
        /// The file or folder.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// A figure could not be drawn.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// `summary.json` could not be written.
    #[error("summary.json: {0}")]
    Summary(#[from] serde_json::Error),
    /// Ctrl-C (`interrupt`): the run stopped at a step boundary.
    #[error("interrupted (Ctrl-C) at t = {0} s")]
    Interrupted(f64),
    /// A paced run overran its deadlines more than `max_overruns` times.
    #[error("{0}")]
    Pace(String),
    /// A bound on work stated in the scene would be exceeded.
    #[error("{0}")]
    Bound(String),
}

impl RunError {
    /// A file error naming the file.
    pub fn file(path: &Path, reason: &dyn std::fmt::Display) -> RunError {
        RunError::File {
            path: path.display().to_string(),
            reason: reason.to_string(),
        }
    }
}

/// `timeseries.csv` in the results folder (made if need be), if there is one.
/// An earlier run's `summary.json`, `timeseries.csv`, `overruns.csv` and `report.html` there
/// are removed first: a run stopped outright must not leave an older run's
/// complete-looking results beside its own partial ones.
fn fresh_csv_in(dir: Option<&Path>) -> Result<Option<PathBuf>, RunError> {
    let Some(dir) = dir else {
        return Ok(None);
    };
    std::fs::create_dir_all(dir).map_err(|e| RunError::file(dir, &e))?;
    for name in [
        "summary.json",
        "timeseries.csv",
        "overruns.csv",
        "report.html",
    ] {
        let old = dir.join(name);
        match std::fs::remove_file(&old) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(RunError::file(&old, &e));
            }
            _ => {}
        }
    }
    Ok(Some(dir.join("timeseries.csv")))
}

/// Refuses a run whose time series would exceed `output.max_bytes`: its
/// rows (every `output.every`-th step and the start) times its columns, 24 B
/// a number as written.
pub fn check_output_size(scene: &Scene, signals: usize) -> Result<(), RunError> {
    let out = &scene.spec.output;
    let rows = (scene.steps as u64) / u64::from(out.every.max(1)) + 1;
    let bytes = rows.saturating_mul(signals as u64 + 1).saturating_mul(24);
    let bound = out
        .max_bytes
        .unwrap_or(slender_scene::spec::DEFAULT_MAX_OUTPUT_BYTES);
    if bytes > bound {
        return Err(RunError::Bound(format!(
            "the time series would take about {:.3e} B ({rows} rows of {} columns), more than output.max_bytes = {bound}; record fewer signals, every n-th step (`output.every`), or give `output.max_bytes` to go past it",
            bytes as f64,
            signals + 1
        )));
    }
    Ok(())
}

impl From<MasterError> for RunError {
    fn from(e: MasterError) -> Self {
        RunError::Master(Box::new(e))
    }
}

/// The overruns a paced run kept (the first `KEPT_OVERRUNS`) as
/// `overruns.csv` in `dir`.
fn write_overruns(dir: &Path, report: &RealtimeReport) -> Result<PathBuf, RunError> {
    let path = dir.join("overruns.csv");
    let mut text = String::from("step,time_s,compute_s,late_s\n");
    for o in &report.overruns {
        text += &format!("{},{},{},{}\n", o.step, o.time_s, o.compute_s, o.late_s);
    }
    whole::write(&path, text).map_err(|e| RunError::file(&path, &e))?;
    Ok(path)
}

/// Steps the whole scene; with `realtime`, paced against the wall clock, and
/// the computing times of the steps done; the plausibility watch's warnings
/// into `warnings`.
fn simulate(
    scene: &Scene,
    master: &mut Master,
    recorder: &mut Recorder,
    (options, warnings): (&RunOptions, &mut Vec<String>),
) -> (Result<(), RunError>, Option<RealtimeReport>) {
    let mut pacer = options.realtime.then(|| {
        let sim = &scene.spec.simulation;
        let max_overruns = sim
            .max_overruns
            .unwrap_or(slender_scene::spec::DEFAULT_MAX_OVERRUNS);
        Pacer::new(scene.step.as_secs(), max_overruns)
    });
    let outcome = step_all(
        scene,
        (master, recorder),
        options.progress && !options.realtime,
        pacer.as_mut(),
        warnings,
    );
    (outcome, pacer.map(|p| p.report()))
}

/// Initialises and steps the whole run, recording every step; on a thread of
/// the master's pool when it has one ([`Master::on_pool`]).
fn step_all(
    scene: &Scene,
    (master, recorder): (&mut Master, &mut Recorder),
    progress: bool,
    pacer: Option<&mut Pacer>,
    warnings: &mut Vec<String>,
) -> Result<(), RunError> {
    master.on_pool(|master| step_all_here(scene, (master, recorder), progress, pacer, warnings))
}

fn step_all_here(
    scene: &Scene,
    (master, recorder): (&mut Master, &mut Recorder),
    progress: bool,
    mut pacer: Option<&mut Pacer>,
    warnings: &mut Vec<String>,
) -> Result<(), RunError> {
    master.initialize(scene.start)?;
    recorder.observe(master)?;
    let mut watch = Watch::new(master, scene);
    let started = Instant::now();
    let mut bar: Option<ProgressBar> = None;
    for i in 0..scene.steps {
        if let Some(p) = pacer.as_deref_mut() {
            p.begin();
        }
        if crate::interrupt::requested() {
            return Err(RunError::Interrupted(master.time().as_secs()));
        }
        if let Err(e) = master.step() {
            match ended_by_unit(&e) {
                Some(warning) => {
                    warnings.push(warning);
                    break;
                }
                None => return Err(e.into()),
            }
        }
        recorder.observe(master)?;
        let t = master.time().as_secs();
        watch.observe(master, t, warnings)?;
        if let Some(p) = pacer.as_deref_mut() {
            let index = usize::try_from(i).unwrap_or(usize::MAX);
            p.end(index, (master.time() - scene.start).as_secs())?;
        }
        if progress && i % 64 == 0 {
            update_progress(&mut bar, started.elapsed(), i as u64, scene.steps as u64);
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(())
}

/// The warning for a unit that asked to end the simulation (an FMU's
/// `terminateSimulation`): not a failure, the run ends at its last completed
/// step, as FMI masters end it.
fn ended_by_unit(e: &MasterError) -> Option<String> {
    match e {
        MasterError::Unit {
            unit,
            time,
            source: slender_units::UnitError::EndRequested(why),
            ..
        } => Some(format!(
            "unit `{unit}` asked to end the simulation in the step from t = {time} s ({why}): the run ends there, at its last completed step"
        )),
        _ => None,
    }
}

fn update_progress(bar: &mut Option<ProgressBar>, elapsed: Duration, done: u64, total: u64) {
    if bar.is_none() && elapsed > Duration::from_secs(1) {
        let b = ProgressBar::new(total).with_elapsed(elapsed);
        if let Ok(style) =
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} steps, {msg}")
        {
            b.set_style(style);
        }
        *bar = Some(b);
    }
    if let Some(b) = bar {
        b.set_position(done);
        // indicatif's own estimate counts the jump to `done` when the bar appears.
        let remaining =
            elapsed.as_secs_f64() * (total.saturating_sub(done)) as f64 / done.max(1) as f64;
        b.set_message(format!("about {remaining:.0} s left"));
    }
}

/// The run's analysis of its recording (`crate::analysis`, the envelopes
/// placed on a structure's arc) and, with a results folder, the scene's
/// figures and the analysis's files; a figure that cannot be written fails
/// the run (`outcome`).
fn analyse_and_draw(
    scene: &Scene,
    recorder: &mut Recorder,
    dir: Option<&Path>,
    (outcome, files): (&mut Result<(), String>, &mut Vec<PathBuf>),
    warnings: &mut Vec<String>,
) -> crate::analysis::Analysis {
    let mut envelopes = recorder.take_envelopes();
    let structures = match envelopes.is_empty() {
        true => Vec::new(),
        false => scene.sectioned_structures(),
    };
    crate::envelopes::place(&mut envelopes, &structures);
    let (analysis, spectra) = crate::analysis::of(scene, recorder, &envelopes, warnings);
    if let Some(dir) = dir
        && recorder.time.len() > 1
    {
        let drawn = Drawn {
            spectra: &spectra,
            envelopes: &envelopes,
            structures: &structures,
        };
        match write_plots(scene, recorder, dir, &drawn) {
            Ok(plots) => files.extend(plots),
            Err(e) => {
                if outcome.is_ok() {
                    *outcome = Err(format!("writing the plots: {e}"));
                }
            }
        }
    }
    analysis
}

/// What the run's analysis writes beside the scene's figures.
struct Drawn<'a> {
    spectra: &'a [(String, crate::spectrum::Spectrum)],
    envelopes: &'a [crate::envelopes::Envelope],
    structures: &'a [crate::envelopes::Structure],
}

/// The scene's figures, and the spectra's and envelopes' tables and figures
/// when it asks for them.
fn write_plots(
    scene: &Scene,
    recorder: &Recorder,
    dir: &Path,
    drawn: &Drawn<'_>,
) -> Result<Vec<PathBuf>, PlotError> {
    let mut files = crate::analysis::write_spectra(dir, scene, recorder, drawn.spectra)?;
    let title = &scene.spec.title;
    files.extend(crate::envelopes::write(
        dir,
        title,
        drawn.envelopes,
        drawn.structures,
    )?);
    if scene.spec.output.plots.is_empty() {
        let path = dir.join("timeseries.svg");
        let panels: Vec<Vec<String>> = recorder.names.iter().map(|n| vec![n.clone()]).collect();
        whole::through(&path, |p| {
            plot::time_series(p, &scene.spec.title, recorder, &panels)
        })?;
        files.push(path);
    }
    for p in &scene.spec.output.plots {
        let path = dir.join(format!("{}.svg", p.name));
        let title = if p.title.is_empty() {
            &scene.spec.title
        } else {
            &p.title
        };
        whole::through(&path, |f| plot::time_series(f, title, recorder, &p.panels))?;
        files.push(path);
    }
    Ok(files)
}

/// Cost of a scene measured over repeated runs without recording.
#[derive(Debug, Serialize)]
pub struct Benchmark {
    /// Runs timed.
    pub repeats: usize,
    /// Median wall time per simulated second (s/s).
    pub median_cost_per_simulated_second: f64,
    /// Smallest wall time per simulated second (s/s).
    pub min_cost_per_simulated_second: f64,
    /// Simulated seconds per wall-clock second (1 / median cost).
    pub realtime_factor: f64,
    /// Synchronisation steps of one run.
    pub steps: u64,
    /// Coupling iterations of one run.
    pub iterations: u64,
    /// `do_step` calls of one run, all units.
    pub do_step_calls: u64,
    /// Rollbacks of one run.
    pub rollbacks: u64,
    /// Median over runs of (wall time - time charged to units) divided by
    /// (iterations x connections): an upper estimate of the master's own cost per
    /// connection per iteration (s), including the units' save/restore.
    pub master_overhead_per_connection_iteration_s: f64,
}

/// Runs `scene` `repeats` times (plus one warm-up) and reports the median cost of
/// stepping (initialisation excluded).
pub fn benchmark(scene: &Scene, repeats: usize) -> Result<Benchmark, RunError> {
    let repeats = repeats.max(1);
    let mut costs = Vec::with_capacity(repeats);
    let mut overheads = Vec::with_capacity(repeats);
    let mut last = Counters::default();
    for run in 0..=repeats {
        let mut master = scene.build()?;
        let connections = master.connection_count();
        master.initialize(scene.start)?;
        let started = Instant::now();
        master.on_pool(|master| {
            for _ in 0..scene.steps {
                master.step()?;
            }
            Ok::<(), RunError>(())
        })?;
        let wall = started.elapsed().as_secs_f64();
        if run == 0 {
            continue; // warm-up
        }
        last = master.counters();
        let simulated = (scene.step * scene.steps).as_secs();
        costs.push(wall / simulated);
        let master_time = wall - last.unit_time_s();
        let per = last.iterations as f64 * connections.max(1) as f64;
        overheads.push(master_time / per);
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let min = costs.iter().copied().fold(f64::INFINITY, f64::min);
    let med = median(&mut costs);
    Ok(Benchmark {
        repeats,
        median_cost_per_simulated_second: med,
        min_cost_per_simulated_second: min,
        realtime_factor: 1.0 / med,
        steps: last.steps,
        iterations: last.iterations,
        do_step_calls: last.do_step_calls(),
        rollbacks: last.rollbacks,
        master_overhead_per_connection_iteration_s: median(&mut overheads),
    })
}
