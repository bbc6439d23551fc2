//! `slender cases`: a load-case matrix run whole, one shard of it, the merge
//! of the shards, or the Slurm scripts that run the shards and merge them.

use super::analysis::study_folder;
use super::cluster::{ArrayJob, shell_word, slurm_scripts};
use super::runs_csv::{RunsCsv, write_report_files};
use super::uq::Mode;
use super::{CliError, SceneArg, report_written};
use slender_app::cases::{self, CasesPlan, Row, table};
use std::path::{Path, PathBuf};

/// Runs the command. A whole matrix writes cases.csv, cases.json, cases.md
/// and report.html.
pub(super) fn cases(
    path: &Path,
    plan: &CasesPlan,
    out: Option<PathBuf>,
    mode: Mode,
) -> Result<(), CliError> {
    let arg = SceneArg::new(path.to_owned(), &plan.overrides);
    let (dir, _) = study_folder(&arg, out, "-cases", (plan.duration, plan.jobs))?;
    let checked = cases::check(path, plan).map_err(CliError::of)?;
    let read = |csv: &Path| match std::fs::read_to_string(csv) {
        Ok(text) => table::read(&text, plan, &checked.columns),
        Err(_) => vec![None; plan.cases().len()],
    };
    match mode {
        Mode::Slurm(n) => slurm_scripts(&ArrayJob {
            command: "cases",
            scene: path,
            dir: &dir,
            args: arguments(plan),
            jobs: plan.jobs,
            shards: n,
        }),
        Mode::Shard(k, n) => {
            let shard_dir = dir.join(format!("shard-{k}-of-{n}"));
            let _lock = super::results_folder(&shard_dir)?;
            let csv = shard_dir.join("cases.csv");
            let plan = CasesPlan {
                shard: Some((k, n)),
                ..plan.clone()
            };
            let (rows, _) = run_appending(&plan, &checked, &csv, read(&csv))?;
            println!("shard {k} of {n}: {} cases", rows.iter().flatten().count());
            Ok(())
        }
        Mode::Whole { merge } => {
            let _lock = super::lock::lock(&dir)?;
            let csv = dir.join("cases.csv");
            let mut earlier = read(&csv);
            if merge {
                earlier = merged(&dir, &read, earlier)?;
            }
            let (rows, failed) = run_appending(plan, &checked, &csv, earlier)?;
            let scene = path.display().to_string();
            let checked_ = (checked.columns.as_slice(), checked.durations);
            let report = cases::aggregate::report(scene, plan, checked_, &rows, failed);
            write_matrix(&dir, path, csv, &report)
        }
    }
}

/// The plan's arguments as shell words, for the Slurm scripts.
fn arguments(plan: &CasesPlan) -> Vec<String> {
    let mut args: Vec<String> = (plan.seas.iter())
        .map(|s| {
            format!(
                "--sea {},{},{}",
                s.significant_height, s.peak_period, s.probability
            )
        })
        .collect();
    args.extend(
        (plan.headings.iter()).map(|h| format!("--heading {},{}", h.degrees, h.probability)),
    );
    args.push(format!("--seeds {}", plan.seeds));
    if let Some(d) = plan.duration {
        args.push(format!("--duration {d}"));
    }
    args.extend(
        plan.overrides
            .iter()
            .map(|o| format!("--set {}", shell_word(o))),
    );
    args
}

/// The cases that failed in this run: their index and why.
type Failures = Vec<(usize, String)>;

/// Runs the plan, appending each new row to `csv` as it finishes, then
/// rewrites the file in case order; the rows and the failures of this run.
fn run_appending(
    plan: &CasesPlan,
    checked: &cases::Checked,
    csv: &Path,
    earlier: Vec<Option<Row>>,
) -> Result<(Vec<Option<Row>>, Failures), CliError> {
    let header = table::header(&checked.columns);
    let rows_text = |rows: &[Option<Row>]| -> String {
        (rows.iter().enumerate())
            .filter_map(|(k, r)| r.as_ref().map(|r| table::row(plan, k, r)))
            .collect()
    };
    let log = RunsCsv::start(csv, &header, &rows_text(&earlier))?;
    let failed = std::sync::Mutex::new(Vec::new());
    let rows = cases::run_checked(plan, checked, &earlier, |k, row, progress| {
        log.append(&table::row(plan, k, row));
        let case = plan.describe(&plan.cases()[k]);
        match &row.1 {
            None => println!("{progress} case {k} ({case}): completed"),
            Some(why) => {
                println!("{progress} case {k} ({case}): failed: {why}");
                let mut failed = failed.lock().unwrap_or_else(|e| e.into_inner());
                failed.push((k, why.clone()));
            }
        }
    })
    .map_err(CliError::of)?;
    log.finish(&rows_text(&rows))?;
    let mut failed = failed.into_inner().unwrap_or_else(|e| e.into_inner());
    failed.sort();
    Ok((rows, failed))
}

/// Every shard's completed rows under `dir`, over `earlier`.
fn merged(
    dir: &Path,
    read: &dyn Fn(&Path) -> Vec<Option<Row>>,
    mut all: Vec<Option<Row>>,
) -> Result<Vec<Option<Row>>, CliError> {
    for folder in super::cluster::shard_folders(dir, "cases")? {
        for (k, row) in read(&folder.join("cases.csv")).into_iter().enumerate() {
            if row.is_some() {
                all[k] = row;
            }
        }
    }
    println!(
        "merging: {} cases from the shards",
        all.iter().flatten().count()
    );
    Ok(all)
}

/// Writes cases.json, cases.md, cases.svg and report.html beside the
/// complete `csv`, prints the Markdown.
fn write_matrix(
    dir: &Path,
    path: &Path,
    csv: PathBuf,
    report: &cases::aggregate::CasesReport,
) -> Result<(), CliError> {
    let markdown = cases::markdown::to_markdown(report);
    let mut files = vec![csv];
    files.extend(write_report_files(dir, "cases", report, &markdown)?);
    let title = format!("Load-case matrix of {}", path.display());
    let svg = dir.join("cases.svg");
    slender_app::whole::through(&svg, |f| {
        slender_app::figures::cases::cases(f, &title, report)
    })
    .map_err(CliError::failure)?;
    let parts = vec![
        slender_app::report::Part::Markdown(markdown.clone()),
        slender_app::report::Part::figure(&svg, Vec::new()),
    ];
    files.push(svg);
    files.push(super::write_report(dir, &title, &parts)?);
    print!("{markdown}");
    report_written(&files);
    if !report.failed.is_empty() {
        return Err(CliError::failure(format!(
            "{} of {} cases failed (cases.md lists them)",
            report.failed.len(),
            report.cases
        )));
    }
    Ok(())
}
