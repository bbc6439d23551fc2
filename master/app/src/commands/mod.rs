//! What each command does. Every command returns `Result<(), CliError>`: bad input
//! (a scene, an argument, a path) exits with code 2, a failure on the way (a run,
//! a write) with code 1, as the README and the user guide promise.

mod analysis;
mod cases;
mod cluster;
mod decay;
mod fmu;
mod lock;
mod request;
mod runs_csv;
mod scene;
mod span;
mod statics;
mod uq;

use crate::cli::{Cli, Command};
use slender_scene::Scene;
use std::path::{Path, PathBuf};

/// Why a command stopped, and its exit code.
#[derive(Debug)]
pub(crate) struct CliError {
    pub code: u8,
    pub message: String,
}

impl CliError {
    /// Bad input: exit code 2.
    pub(crate) fn input(message: impl std::fmt::Display) -> CliError {
        CliError {
            code: 2,
            message: message.to_string(),
        }
    }

    /// The library's error: bad input (the scene, what was asked) exits 2,
    /// a file that could not be read or written 1, Ctrl-C 130.
    pub(crate) fn of(error: slender_app::AppError) -> CliError {
        let code = match error {
            slender_app::AppError::Interrupted { .. } => 130,
            _ if error.is_input() => 2,
            _ => 1,
        };
        CliError {
            code,
            message: error.to_string(),
        }
    }

    /// A run's error: the scene or a bound it states is bad input (2),
    /// Ctrl-C 130, anything else a failure on the way (1: a unit, the
    /// coupling, a results file that could not be written).
    pub(crate) fn of_run(error: slender_app::run::RunError) -> CliError {
        use slender_app::run::RunError;
        let code = match error {
            RunError::Scene(_) | RunError::Bound(_) => 2,
            RunError::Interrupted(_) => 130,
            _ => 1,
        };
        CliError {
            code,
            message: error.to_string(),
        }
    }

    /// A failure on the way: exit code 1.
    pub(crate) fn failure(message: impl std::fmt::Display) -> CliError {
        CliError {
            code: 1,
            message: message.to_string(),
        }
    }
}

/// A study's design from `--grid`.
fn design(grid: bool) -> slender_app::study::Design {
    if grid {
        slender_app::study::Design::Grid
    } else {
        slender_app::study::Design::OneAtATime
    }
}

/// `--jobs`, default the machine's cores.
fn jobs_or_cores(jobs: Option<usize>) -> usize {
    jobs.unwrap_or_else(|| {
        std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
    })
}

/// The study commands: their plans from the arguments (`set`: `--set`).
fn studies(command: Command, set: &[String]) -> Result<(), CliError> {
    let overrides = set.to_vec();
    match command {
        Command::Study {
            scene,
            sweeps,
            grid,
            runs,
            reference,
            cost_units,
            out,
        } => {
            let plan = slender_app::study::StudyPlan {
                max_runs: runs.max_runs,
                sweeps,
                design: design(grid),
                duration: runs.duration,
                jobs: runs.jobs.unwrap_or(1),
                cost_units,
                reference,
                repeats: runs.repeats,
                overrides,
            };
            analysis::study(&scene, &plan, (out, runs.fresh))
        }
        Command::Fidelity {
            scene,
            sections,
            grid,
            tolerance,
            quantities,
            from,
            reference,
            refinements,
            runs,
            out,
        } => {
            let plan = slender_app::fidelity::FidelityPlan {
                reference,
                max_refinements: refinements,
                from,
                max_runs: runs.max_runs,
                sections,
                design: design(grid),
                duration: runs.duration,
                jobs: runs.jobs.unwrap_or(1),
                tolerance,
                judged: quantities,
                repeats: runs.repeats,
                overrides,
            };
            analysis::fidelity(&scene, &plan, (out, runs.fresh))
        }
        Command::Uq {
            scene,
            samples,
            out,
            runs,
        } => {
            let plan = slender_app::uq::UqPlan {
                max_runs: runs.max_runs,
                samples,
                jobs: jobs_or_cores(runs.jobs),
                duration: runs.duration,
                shard: None,
                overrides,
            };
            uq::uq(&scene, &plan, out, uq_mode(&runs)?)
        }
        c @ Command::Cases { .. } => load_cases(c, overrides),
        _ => Err(CliError::failure("not a study command")),
    }
}

/// `slender cases`: its plan from the arguments.
fn load_cases(command: Command, overrides: Vec<String>) -> Result<(), CliError> {
    let Command::Cases {
        scene,
        seas,
        headings,
        seeds,
        out,
        runs,
    } = command
    else {
        return Err(CliError::failure("not the cases command"));
    };
    let plan = slender_app::cases::CasesPlan {
        seas: (seas.into_iter())
            .map(|(hs, tp, p)| slender_app::cases::SeaState {
                significant_height: hs,
                peak_period: tp,
                probability: p,
            })
            .collect(),
        headings: headings_of(&headings)?,
        seeds: 1,
        jobs: jobs_or_cores(runs.jobs),
        duration: runs.duration,
        shard: None,
        max_runs: runs.max_runs,
        overrides,
    };
    let plan = slender_app::cases::with_scene_matrix(&scene, plan, seeds).map_err(CliError::of)?;
    cases::cases(&scene, &plan, out, uq_mode(&runs)?)
}

/// The headings with their probabilities: all given, or none (equal shares).
fn headings_of(given: &[(f64, Option<f64>)]) -> Result<Vec<slender_app::cases::Heading>, CliError> {
    let shares = given.iter().filter(|h| h.1.is_some()).count();
    if shares != 0 && shares != given.len() {
        return Err(CliError::input(
            "--heading: give every heading's probability (DEG,P) or none (equal shares)",
        ));
    }
    let equal = 1.0 / given.len().max(1) as f64;
    Ok((given.iter())
        .map(|&(degrees, p)| slender_app::cases::Heading {
            degrees,
            probability: p.unwrap_or(equal),
        })
        .collect())
}

/// How a `slender uq` or `cases` runs: a shard, through Slurm, or whole
/// (merging shards).
fn uq_mode(runs: &crate::cli::SplitRuns) -> Result<uq::Mode, CliError> {
    let (shard, slurm, merge) = (runs.shard, runs.slurm, runs.merge);
    Ok(match (shard, slurm) {
        (Some((k, n)), _) => uq::Mode::Shard(k, n),
        (_, Some(0)) => return Err(CliError::input("--slurm 0: expected at least one shard")),
        (_, Some(n)) => uq::Mode::Slurm(n),
        _ => uq::Mode::Whole { merge },
    })
}

/// Runs one command; `--set` on a command that reads no scene is bad input.
pub(crate) fn dispatch(cli: Cli) -> Result<(), CliError> {
    let set = &cli.set;
    if !set.is_empty() && !reads_a_scene(&cli.command) {
        return Err(CliError::input(format!(
            "--set {}: this command reads no scene",
            set.join(" --set ")
        )));
    }
    match cli.command {
        Command::Run {
            scene,
            out,
            quiet,
            realtime,
            duration,
        } => scene::run(&SceneArg::new(scene, set), out, (quiet, realtime), duration),
        Command::Check { scene } => scene::check(&SceneArg::new(scene, set)),
        Command::Expand { scene } => scene::expand(&SceneArg::new(scene, set)),
        Command::Bench {
            scene,
            repeats,
            json,
        } => scene::bench(&SceneArg::new(scene, set), repeats, json),
        Command::Modes {
            scene,
            unit,
            count,
            out,
            plot,
        } => analysis::modes(&SceneArg::new(scene, set), &unit, count, out, plot),
        Command::Decay { scene, out } => decay::decay_test(&SceneArg::new(scene, set), out),
        Command::Statics {
            scene,
            out,
            range,
            yaw,
            points,
        } => statics::statics(
            &SceneArg::new(scene, set),
            out,
            statics::Sweep { range, yaw, points },
        ),
        c @ (Command::Study { .. }
        | Command::Fidelity { .. }
        | Command::Uq { .. }
        | Command::Cases { .. }) => studies(c, set),
        Command::Span {
            action,
            flexural_rigidity,
            mass_per_length,
            damping,
            length,
            out,
        } => {
            let span = slender_units::span::transfer::Span {
                flexural_rigidity,
                mass_per_length,
                damping_per_length: damping,
                length,
                // The Taylor and Pade forms the span commands compare are the
                // tension-free span's.
                tension: 0.0,
            };
            span::span(&span, action, &out)
        }
        Command::Fmu { action } => fmu::fmu(action, set),
        Command::Kinds => {
            scene::kinds();
            Ok(())
        }
    }
}

/// Whether `command` reads a scene (so `--set` applies to it).
fn reads_a_scene(command: &Command) -> bool {
    use crate::cli::FmuAction;
    !matches!(
        command,
        Command::Span { .. }
            | Command::Kinds
            | Command::Fmu {
                action: FmuAction::Info { .. }
            }
    )
}

/// A scene file and the keys `--set` sets over it.
struct SceneArg<'a> {
    path: PathBuf,
    set: &'a [String],
}

impl SceneArg<'_> {
    fn new(path: PathBuf, set: &[String]) -> SceneArg<'_> {
        SceneArg { path, set }
    }
}

/// Loads and checks a scene with its `--set` keys (bad input on failure).
fn load(scene: &SceneArg) -> Result<Scene, CliError> {
    slender_app::study::scene_with_overrides(&scene.path, scene.set).map_err(CliError::of)
}

/// Makes the results folder `dir` and holds it (one writer at a time,
/// `lock`) while the returned lock lives; naming an existing file, or a folder
/// with a symbolic link or another writer, is bad input.
fn results_folder(dir: &Path) -> Result<lock::FolderLock, CliError> {
    made_folder(dir)?;
    lock::lock(dir)
}

/// Makes the results folder `dir` without holding it (a study's folder whose
/// shards each hold their own); naming an existing file is bad input.
fn made_folder(dir: &Path) -> Result<(), CliError> {
    if dir.exists() && !dir.is_dir() {
        return Err(CliError::input(format!(
            "{}: is a file; expected a folder for the results",
            dir.display()
        )));
    }
    // A folder the user named that cannot be made (`--out /proc/x`) is bad
    // input: exit 2, as a misspelt scene.
    std::fs::create_dir_all(dir).map_err(|e| {
        CliError::input(format!("{}: cannot create the folder ({e})", dir.display()))
    })?;
    refuse_links(dir, 0)
}

/// Refuses a results folder holding a symbolic link (at any depth, up to
/// `MAX_DEPTH`): slender writes only regular files there, and a planted link
/// (`ln -s ../victim.txt out/summary.json`) would have it overwrite the file
/// the link points to (issue 27).
fn refuse_links(dir: &Path, depth: usize) -> Result<(), CliError> {
    const MAX_DEPTH: usize = 4;
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            continue;
        };
        if meta.file_type().is_symlink() {
            let target = std::fs::read_link(&path).unwrap_or_default();
            return Err(CliError::input(format!(
                "{}: a symbolic link (to {}) in the results folder; slender writes only regular files there, so remove it or choose another --out",
                path.display(),
                target.display()
            )));
        }
        if meta.is_dir() && depth < MAX_DEPTH {
            refuse_links(&path, depth + 1)?;
        }
    }
    Ok(())
}

/// A finite, positive value given on the command line, or bad input naming it.
fn positive(argument: &str, value: f64) -> Result<f64, CliError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CliError::input(format!(
            "{argument} {value}: expected a finite value > 0"
        )))
    }
}

/// A count given on the command line within [`low`, `high`], or bad input naming it.
fn count_in(argument: &str, value: usize, low: usize, high: usize) -> Result<usize, CliError> {
    if (low..=high).contains(&value) {
        Ok(value)
    } else {
        Err(CliError::input(format!(
            "{argument} {value}: expected {low} to {high}"
        )))
    }
}

/// Writes `text` to the file `name` in `dir`; the error names the file.
fn write_in(dir: &std::path::Path, name: &str, text: String) -> Result<PathBuf, CliError> {
    let file = dir.join(name);
    slender_app::whole::write(&file, text)
        .map_err(|e| CliError::failure(format!("{}: {e}", file.display())))?;
    Ok(file)
}

/// Writes `report.html` in `dir`: the page of `parts` under `title`, with
/// the command line that made it.
fn write_report(
    dir: &std::path::Path,
    title: &str,
    parts: &[slender_app::report::Part],
) -> Result<PathBuf, CliError> {
    let command = slender_app::report::command_line();
    write_in(
        dir,
        "report.html",
        slender_app::report::page(title, &command, parts),
    )
}

/// Prints the files written.
fn report_written(files: &[PathBuf]) {
    for f in files {
        println!("wrote {}", f.display());
    }
}
