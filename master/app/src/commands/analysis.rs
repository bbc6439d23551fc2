//! `slender modes` and `slender study`.

use super::{
    CliError, SceneArg, count_in, load, made_folder, positive, report_written, results_folder,
};
use slender_app::fidelity::{self, FidelityPlan};
use slender_app::report::Part;
use slender_app::study::{self, StudyPlan};
use slender_app::{figures, whole};
use std::path::{Path, PathBuf};

/// Modes of a unit about its initial state: a table on screen, modes.csv and
/// modes.svg.
pub(super) fn modes(
    arg: &SceneArg,
    unit: &str,
    count: usize,
    out: Option<PathBuf>,
    plot: usize,
) -> Result<(), CliError> {
    let count = count_in("--count", count, 1, 10_000)?;
    let path = &arg.path;
    let scene = load(arg)?;
    let dir = out.unwrap_or_else(|| scene.default_output_dir());
    let _lock = results_folder(&dir)?;
    let mut master = scene.build().map_err(|e| CliError::input(e.to_string()))?;
    master
        .initialize(scene.start)
        .map_err(|e| CliError::failure(e.to_string()))?;
    // An unknown unit or one without modes is bad input.
    let analysis = master
        .modes(unit, count)
        .map_err(|e| CliError::input(e.to_string()))?;
    println!(
        "modes of `{unit}` in {} about its initial state",
        path.display()
    );
    println!("{:>5} {:>12} {:>12}", "mode", "period (s)", "freq (Hz)");
    for (i, m) in analysis.modes.iter().enumerate() {
        println!("{:>5} {:>12.4} {:>12.5}", i + 1, m.period, 1.0 / m.period);
    }
    let csv = dir.join("modes.csv");
    let mut text = String::from("mode,period_s,node,x_m,z_m,shape_x,shape_z\n");
    for (i, m) in analysis.modes.iter().enumerate() {
        for (j, (p, d)) in analysis.positions.iter().zip(&m.shape).enumerate() {
            text += &format!(
                "{},{},{j},{},{},{},{}\n",
                i + 1,
                m.period,
                p[0],
                p[1],
                d[0],
                d[1]
            );
        }
    }
    slender_app::whole::write(&csv, text)
        .map_err(|e| CliError::failure(format!("{}: {e}", csv.display())))?;
    let svg = dir.join("modes.svg");
    let shown = slender_units::ModalAnalysis {
        positions: analysis.positions.clone(),
        modes: analysis.modes.iter().take(plot).cloned().collect(),
    };
    let title = format!("Mode shapes of `{unit}`");
    whole::through(&svg, |f| slender_app::plot::mode_shapes(f, &title, &shown))
        .map_err(CliError::failure)?;
    report_written(&[csv, svg]);
    Ok(())
}

/// A convergence and cost study; the rows are written even when some runs fail
/// (those are marked FAILED with their reason), and the command then exits 1.
pub(super) fn study(
    path: &Path,
    plan: &StudyPlan,
    (out, fresh): (Option<PathBuf>, bool),
) -> Result<(), CliError> {
    count_in("--repeats", plan.repeats, 1, 1000)?;
    let scene = SceneArg::new(path.to_owned(), &plan.overrides);
    let (dir, _) = study_folder(&scene, out, "-study", (plan.duration, plan.jobs))?;
    let _lock = super::lock::lock(&dir)?;
    // What shapes a run besides the scene and its own settings.
    let options = format!(
        "duration {:?}, repeats {}, cost units {:?}, set {:?}",
        plan.duration, plan.repeats, plan.cost_units, plan.overrides
    );
    let request = super::request::study(path, plan);
    let kept = kept_runs(&dir, path, (&options, &request), fresh)?;
    let rows = study::run_study_resuming(path, plan, Some(&kept), |line| println!("{line}"))
        .map_err(CliError::of)?;
    println!(
        "{:<28} {:>14}  epsilon vs reference       it/step   s per sim. s",
        "setting", "value"
    );
    rows.iter().for_each(print_row);
    let failed = rows.iter().filter(|r| r.error.is_some()).count();
    // The twin's own error, when the indicators judge against one.
    let twin = study::twin_error(path, plan).map_err(CliError::of)?;
    let twin_text = twin.as_ref().map(study::twin_error::to_markdown);
    if let Some(text) = &twin_text {
        println!("{}", text.trim());
    }
    let markdown = study::to_markdown(&rows) + twin_text.as_deref().unwrap_or("");
    let csv = dir.join("study.csv");
    slender_app::whole::write(&csv, study::to_csv(&rows))
        .map_err(|e| CliError::failure(format!("{}: {e}", csv.display())))?;
    let md = dir.join("study.md");
    slender_app::whole::write(&md, markdown.clone())
        .map_err(|e| CliError::failure(format!("{}: {e}", md.display())))?;
    let svg = dir.join("study.svg");
    let title = format!("Convergence and cost: {}", path.display());
    let scene = (std::fs::read_to_string(path).ok())
        .and_then(|text| text.parse::<toml::Table>().ok())
        .unwrap_or_default();
    let unit_of = |key: &str| figures::units::setting_unit(&scene, key);
    whole::through(&svg, |f| figures::study::study(f, &title, &rows, &unit_of))
        .map_err(CliError::failure)?;
    let tradeoff = dir.join("error_cost.svg");
    let title = format!("Error against cost: {}", path.display());
    let figure = study::tradeoff(&rows, &title);
    let mut hover = Vec::new();
    whole::through(&tradeoff, |f| {
        hover = figures::tradeoff::draw(f, &figure)?;
        Ok::<(), slender_app::plot::PlotError>(())
    })
    .map_err(CliError::failure)?;
    let parts = [
        Part::Markdown(markdown),
        Part::figure(&svg, Vec::new()),
        Part::figure(&tradeoff, hover),
    ];
    let page = super::write_report(&dir, &format!("Study of {}", path.display()), &parts)?;
    report_written(&[csv, md, svg, tradeoff, page]);
    if let Some(w) = slender_app::costs::spread_warning(rows.iter().map(|r| r.cost_spread)) {
        eprintln!("{w}");
    }
    runs_failed(failed, rows.len(), "marked FAILED above and in study.csv")
}

/// Every row is written; where runs failed the command still exits with code 1
/// (a script must not take a study with failed runs for a complete one), and
/// says which and where they are marked.
fn runs_failed(failed: usize, runs: usize, marked: &str) -> Result<(), CliError> {
    match failed {
        0 => Ok(()),
        _ => Err(CliError::failure(format!(
            "{failed} of {runs} runs failed ({marked}; every row is written)"
        ))),
    }
}

/// A study's results folder: `out`, else the scene's with `suffix`, made but
/// not held (the caller holds it, or each shard its own); the scene must load
/// (returned with it), `--duration` be positive and `--jobs` sensible.
pub(super) fn study_folder(
    scene: &SceneArg,
    out: Option<PathBuf>,
    suffix: &str,
    (duration, jobs): (Option<f64>, usize),
) -> Result<(PathBuf, slender_scene::Scene), CliError> {
    if let Some(d) = duration {
        positive("--duration", d)?;
    }
    count_in("--jobs", jobs, 1, 1024)?;
    let scene = load(scene)?;
    let dir = out.unwrap_or_else(|| {
        let mut d = scene.default_output_dir().into_os_string();
        d.push(suffix);
        PathBuf::from(d)
    });
    made_folder(&dir)?;
    Ok((dir, scene))
}

/// A fidelity study of a structure's sections; the rows are written even when
/// some combinations fail (those are marked FAILED with their reason), and the
/// command then exits 1.
pub(super) fn fidelity(
    path: &Path,
    plan: &FidelityPlan,
    (out, fresh): (Option<PathBuf>, bool),
) -> Result<(), CliError> {
    positive("--tolerance", plan.tolerance)?;
    count_in("--repeats", plan.repeats, 1, 1000)?;
    // Each halving costs about four times the level before it.
    count_in("--refinements", plan.max_refinements as usize, 1, 5)?;
    let scene = SceneArg::new(path.to_owned(), &plan.overrides);
    let (dir, _) = study_folder(&scene, out, "-fidelity", (plan.duration, plan.jobs))?;
    let _lock = super::lock::lock(&dir)?;
    let options = format!(
        "duration {:?}, repeats {}, set {:?}",
        plan.duration, plan.repeats, plan.overrides
    );
    let request = super::request::fidelity(path, plan);
    let kept = kept_runs(&dir, path, (&options, &request), fresh)?;
    let report = fidelity::run_fidelity_kept(path, plan, Some(&kept), |line| println!("{line}"))
        .map_err(CliError::of)?;
    let write = |name: &str, text: String| super::write_in(&dir, name, text);
    let json = serde_json::to_string_pretty(&report).map_err(CliError::failure)?;
    let files = vec![
        write("fidelity.csv", fidelity::report::to_csv(&report))?,
        write("fidelity.json", json)?,
        write("fidelity.md", fidelity::report::to_markdown(&report))?,
    ];
    let svg = dir.join("fidelity.svg");
    let title = format!("Fidelity and cost: {}", path.display());
    let mut hover = Vec::new();
    whole::through(&svg, |f| {
        hover = fidelity::report::plot(f, &title, &report)?;
        Ok::<(), slender_app::plot::PlotError>(())
    })
    .map_err(CliError::failure)?;
    println!("{}", fidelity::report::conclusion(&report));
    let parts = [
        Part::Markdown(fidelity::report::to_markdown(&report)),
        Part::figure(&svg, hover),
    ];
    let page = super::write_report(
        &dir,
        &format!("Fidelity study of {}", path.display()),
        &parts,
    )?;
    report_written(&[files, vec![svg, page]].concat());
    let spreads = report.rows.iter().map(|r| r.cost_spread);
    if let Some(w) = slender_app::costs::spread_warning(spreads) {
        eprintln!("{w}");
    }
    let failed = report.rows.iter().filter(|r| r.error.is_some()).count();
    runs_failed(
        failed,
        report.rows.len(),
        "marked FAILED in fidelity.md and fidelity.csv",
    )
}

/// The runs a study keeps in `dir/runs` to resume (emptied first when
/// `fresh`), keyed by the scene's text, this build's version and `options`.
/// The folder holds one study: the study claims it before its first run
/// (`Kept::claim`), and another one asked differently (`request`, in words)
/// is refused then unless `fresh`.
fn kept_runs(
    dir: &Path,
    scene: &Path,
    (options, request): (&str, &str),
    fresh: bool,
) -> Result<slender_app::resume::Kept, CliError> {
    let runs = dir.join("runs");
    if fresh && runs.is_dir() {
        std::fs::remove_dir_all(&runs)
            .map_err(|e| CliError::failure(format!("{}: {e}", runs.display())))?;
    }
    let options = format!("slender {}, {options}", env!("CARGO_PKG_VERSION"));
    let kept = slender_app::resume::Kept::new(dir, scene, &options).map_err(CliError::of)?;
    Ok(kept.asking(request.to_owned(), fresh))
}

/// One finished run (groups print when all their runs are done).
fn print_row(r: &study::StudyRow) {
    let eps: Vec<String> = r
        .errors
        .iter()
        .map(|(n, e)| format!("{n} {e:.2e}"))
        .collect();
    let (setting, value) = if r.settings.len() == 1 {
        (r.settings[0].0.clone(), r.settings[0].1.clone())
    } else {
        let keys: Vec<String> = r.settings.iter().map(|(k, v)| format!("{k}={v}")).collect();
        (keys.join(" "), String::new())
    };
    println!(
        "{:<28} {:>14}  {:<26} {:>6.2}   {:.3e}{}",
        setting,
        value,
        eps.join(", "),
        r.iterations_per_step,
        r.cost_per_simulated_second,
        r.error
            .as_ref()
            .map(|e| format!("  FAILED: {e}"))
            .unwrap_or_default()
    );
}
