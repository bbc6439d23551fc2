//! `slender uq`: a whole study, one shard of it, the merge of the shards, or
//! the Slurm scripts that run the shards as a job array and merge them.

use super::analysis::study_folder;
use super::cluster::{ArrayJob, shell_word};
use super::runs_csv::{RunsCsv, write_report_files};
use super::{CliError, SceneArg, report_written};
use slender_app::plot::PlotError;
use slender_app::uq::{self, Run, UqPlan};

use std::path::{Path, PathBuf};

/// How `slender uq` was asked to run.
pub(super) enum Mode {
    /// Every run and the expansion (after a merge, the shards' runs reused).
    Whole { merge: bool },
    /// Shard K of N: its runs only, in `<out>/shard-K-of-N/runs.csv`.
    Shard(usize, usize),
    /// Write the Slurm scripts for N shards and their merge.
    Slurm(usize),
}

/// Runs the command. A whole study writes runs.csv, uq.json, uq.md,
/// sobol.svg (like seed 000's Fig. 11), convergence.svg (Fig. 9's moments
/// against the design size), distribution.svg (Fig. 9's distribution: the runs'
/// histogram and the expansion's density) and scatter.svg (like its Fig. 8).
pub(super) fn uq(
    path: &Path,
    plan: &UqPlan,
    out: Option<PathBuf>,
    mode: Mode,
) -> Result<(), CliError> {
    let arg = SceneArg::new(path.to_owned(), &plan.overrides);
    let (dir, scene) = study_folder(&arg, out, "-uq", (plan.duration, plan.jobs))?;
    let spec =
        scene.spec.uncertainty.clone().ok_or_else(|| {
            CliError::input(format!("{}: no `[uncertainty]` table", path.display()))
        })?;
    // The inputs' keys first, so that a design refused for its size was
    // otherwise valid.
    let inputs = uq::check_inputs(path, plan).map_err(CliError::of)?;
    check_size(plan, spec.samples)?;
    let names: Vec<String> = spec.inputs.iter().map(|i| i.name.clone()).collect();
    let header = uq::report::header(&names, &spec.outputs);
    let read = |csv: &Path| match std::fs::read_to_string(csv) {
        Ok(text) if text.starts_with(&header) => {
            uq::report::read_runs(&text, names.len(), spec.outputs.len())
        }
        _ => Vec::new(),
    };
    match mode {
        Mode::Slurm(n) => slurm_scripts(path, plan, &dir, n),
        Mode::Shard(k, n) => {
            let shard_dir = dir.join(format!("shard-{k}-of-{n}"));
            let _lock = super::results_folder(&shard_dir)?;
            let csv = shard_dir.join("runs.csv");
            let earlier = read(&csv);
            let plan = UqPlan {
                shard: Some((k, n)),
                ..plan.clone()
            };
            let (_, runs) = run_appending((path, &inputs), &plan, &csv, &header, earlier)?;
            println!(
                "shard {k} of {n}: {} runs",
                runs.iter().filter(|r| !r.inputs.is_empty()).count()
            );
            Ok(())
        }
        Mode::Whole { merge } => {
            let _lock = super::lock::lock(&dir)?;
            let csv = dir.join("runs.csv");
            let mut earlier = read(&csv);
            if merge {
                earlier = merged(&dir, &read)?;
                println!(
                    "merging: {} runs from the shards",
                    earlier.iter().filter(|r| !r.inputs.is_empty()).count()
                );
            }
            let (report, runs) = run_appending((path, &inputs), plan, &csv, &header, earlier)?;
            let report = report.ok_or_else(|| CliError::failure("no report from a whole study"))?;
            write_study(&dir, path, csv, &report, &runs)
        }
    }
}

/// Writes a whole study's files into `dir` beside its complete `csv` (in
/// index order): uq.json, uq.md, the figures and report.html; prints the
/// Markdown and any caution on a poor fit.
fn write_study(
    dir: &Path,
    path: &Path,
    csv: PathBuf,
    report: &uq::UqReport,
    runs: &[uq::Run],
) -> Result<(), CliError> {
    // runs.csv is already complete and in index order.
    let markdown = uq::report::to_markdown(report);
    let mut files = vec![csv];
    files.extend(write_report_files(dir, "uq", report, &markdown)?);
    let drawn = figures(dir, report, runs)?;
    let mut parts = vec![slender_app::report::Part::Markdown(markdown.clone())];
    parts.extend(
        drawn
            .iter()
            .map(|f| slender_app::report::Part::figure(f, Vec::new())),
    );
    files.extend(drawn);
    let title = format!("Uncertainty study of {}", path.display());
    files.push(super::write_report(dir, &title, &parts)?);
    print!("{markdown}");
    for caution in report.outputs.iter().filter_map(uq::report::poor_fit) {
        eprintln!("warning: {caution}");
    }
    report_written(&files);
    Ok(())
}

/// The study's figures, drawn into `dir`; their paths.
fn figures(dir: &Path, report: &uq::UqReport, runs: &[uq::Run]) -> Result<Vec<PathBuf>, CliError> {
    let figure = |name: &str, draw: &dyn Fn(&Path) -> Result<(), PlotError>| {
        slender_app::whole::through(&dir.join(name), draw).map_err(CliError::failure)
    };
    figure("sobol.svg", &|f| uq::plot::sobol_bars(f, report))?;
    figure("convergence.svg", &|f| uq::plot::convergence(f, report))?;
    figure("distribution.svg", &|f| {
        uq::plot::distribution(f, report, runs)
    })?;
    figure("scatter.svg", &|f| uq::plot::scatter(f, report, runs))?;
    Ok([
        "sobol.svg",
        "convergence.svg",
        "distribution.svg",
        "scatter.svg",
    ]
    .map(|name| dir.join(name))
    .to_vec())
}

/// Refuses a design of more runs than `--max-runs` before anything is
/// written (the scene's `samples` unless `--samples` says otherwise).
fn check_size(plan: &UqPlan, scene_samples: usize) -> Result<(), CliError> {
    let samples = plan.samples.unwrap_or(scene_samples);
    if samples > plan.max_runs {
        let refusal = slender_app::too_many_runs("the design", samples, plan.max_runs);
        return Err(CliError::input(refusal));
    }
    Ok(())
}

/// Runs the plan on the scene at `path` with its checked `inputs`, appending
/// each new run to `csv` as it finishes (a file with another header starts
/// afresh), then rewrites it in index order.
fn run_appending(
    (path, inputs): (&Path, &uq::CheckedInputs),
    plan: &UqPlan,
    csv: &Path,
    header: &str,
    earlier: Vec<Run>,
) -> Result<(Option<uq::UqReport>, Vec<Run>), CliError> {
    let rows_text = |runs: &[Run]| -> String {
        (runs.iter().enumerate())
            .filter(|(_, r)| !r.inputs.is_empty())
            .map(|(k, r)| uq::report::row(k, r))
            .collect()
    };
    let log = RunsCsv::start(csv, header, &rows_text(&earlier))?;
    let new_runs = std::sync::atomic::AtomicUsize::new(0);
    // Each finished run says how many are done and the time left (uq was
    // silent for minutes).
    let (report, runs) = uq::run_checked(path, plan, inputs, &earlier, |k, run, progress| {
        new_runs.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        log.append(&uq::report::row(k, run));
        println!("{progress} design point {k}: {}", uq::report::outcome(run));
    })
    .map_err(CliError::of)?;
    // Only the earlier runs at this design's points count (a design of
    // another size may place its points elsewhere).
    let made = runs.iter().filter(|r| !r.inputs.is_empty()).count();
    let reused = made.saturating_sub(new_runs.into_inner());
    if reused > 0 {
        println!("reused {reused} runs already in {}", csv.display());
    }
    log.finish(&rows_text(&runs))?;
    Ok((report, runs))
}

/// Every shard's runs under `dir`, by design index.
fn merged(dir: &Path, read: &dyn Fn(&Path) -> Vec<Run>) -> Result<Vec<Run>, CliError> {
    let mut all: Vec<Run> = Vec::new();
    for folder in super::cluster::shard_folders(dir, "uq")? {
        for (k, run) in read(&folder.join("runs.csv")).into_iter().enumerate() {
            if run.inputs.is_empty() {
                continue;
            }
            if all.len() <= k {
                all.resize(k + 1, Run::default());
            }
            all[k] = run;
        }
    }
    Ok(all)
}

/// `uq-shards.sbatch` (a job array, one shard per task) and `submit.sh` (it,
/// then the merge once every shard is done).
fn slurm_scripts(path: &Path, plan: &UqPlan, dir: &Path, n: usize) -> Result<(), CliError> {
    let mut args = Vec::new();
    if let Some(s) = plan.samples {
        args.push(format!("--samples {s}"));
    }
    if let Some(d) = plan.duration {
        args.push(format!("--duration {d}"));
    }
    args.extend(
        plan.overrides
            .iter()
            .map(|o| format!("--set {}", shell_word(o))),
    );
    super::cluster::slurm_scripts(&ArrayJob {
        command: "uq",
        scene: path,
        dir,
        args,
        jobs: plan.jobs,
        shards: n,
    })
}
