//! `slender`: run, check and benchmark co-simulation scenes.

use clap::{Parser, Subcommand};
use slender_app::run::{RunOptions, benchmark, run_scene};
use slender_scene::{Scene, kinds};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Co-simulation of substructured slender marine structures.
///
/// A scene file (TOML) lists the units (substructure models), how their ports are
/// connected, the master scheme that couples them and the time window. Start from
/// a file in examples/ and see docs/scene-reference.md.
#[derive(Parser)]
#[command(name = "slender", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum SpanAction {
    /// Bode plot of H_{U2 -> U5}: analytic, Taylor, term and function Pade of one
    /// order, and the FE span (seed 004 Figs. 5.1-5.2). Writes bode.svg.
    Bode {
        #[arg(long, default_value_t = 8)]
        order: usize,
        /// FE span elements.
        #[arg(long, default_value_t = 32)]
        elements: usize,
    },
    /// Time-domain error against cost per simulated second of span units (orders
    /// 2-16) and FE spans (4-64 elements, stepping with the master or with substeps)
    /// under a sum of sines and a step, against the continuum's response (a fine FE
    /// span with fine substeps). Writes span_study.md, span_study.json,
    /// accuracy_cost.svg.
    Study {
        /// Simulated time of each run (s).
        #[arg(long, default_value_t = 100.0)]
        duration: f64,
        /// Synchronisation step (s).
        #[arg(long, default_value_t = 0.01)]
        step: f64,
        /// Elements of the reference FE span.
        #[arg(long, default_value_t = 128)]
        reference_elements: usize,
        /// Substeps per synchronisation step of the reference FE span.
        #[arg(long, default_value_t = 64)]
        reference_substeps: usize,
        /// Substeps per synchronisation step of the FE spans compared.
        #[arg(long, value_delimiter = ',', default_value = "1,2,4,5,8,16")]
        fe_substeps: Vec<usize>,
    },
    /// The same for the span between two sections (kind `span_coupling`, the 4x4
    /// matrix, exact and trapezoidal stepping, orders 16-32) against FE spans with
    /// the same four end conditions, all four ends driven. Writes
    /// coupling_study.md, coupling_study.json, coupling_accuracy_cost.svg.
    Coupling {
        /// Simulated time of each run (s).
        #[arg(long, default_value_t = 10.0)]
        duration: f64,
        /// Synchronisation step (s).
        #[arg(long, default_value_t = 0.001)]
        step: f64,
        /// Elements of the reference FE span.
        #[arg(long, default_value_t = 128)]
        reference_elements: usize,
        /// Substeps per synchronisation step of the reference FE span.
        #[arg(long, default_value_t = 32)]
        reference_substeps: usize,
        /// Substeps per synchronisation step of the FE spans compared.
        #[arg(long, value_delimiter = ',', default_value = "1,2,4,8")]
        fe_substeps: Vec<usize>,
    },
}

#[derive(Subcommand)]
enum FmuAction {
    /// Export one unit of a scene as an FMI 2.0 co-simulation FMU (its parameters,
    /// effects, hold and start inputs; the scene's time window as default experiment).
    Export {
        scene: PathBuf,
        /// The unit to export (its name in the scene).
        #[arg(long)]
        unit: String,
        /// The .fmu to write (default: <unit>.fmu).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// The slender-fmu shared library (default: libslender_fmu.so next to this
        /// executable; build it with `cargo build --release -p slender-fmu`).
        #[arg(long)]
        binary: Option<PathBuf>,
    },
    /// Export every unit of a scene and write a copy of the scene that uses the
    /// FMUs (kind `fmu`): the same run through the FMI layer.
    Wrap {
        scene: PathBuf,
        /// Folder for the FMUs and the new scene (<scene>_fmu.toml).
        #[arg(long)]
        out: PathBuf,
        /// The slender-fmu shared library (default: next to this executable).
        #[arg(long)]
        binary: Option<PathBuf>,
    },
    /// Load an FMU as slender would and print its ports and capabilities.
    Info {
        fmu: PathBuf,
        /// Libraries to load globally first (libpython for pythonfmu FMUs).
        #[arg(long)]
        preload: Vec<PathBuf>,
    },
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene: prints a summary, writes timeseries.csv, summary.json and SVG plots.
    Run {
        /// The scene file, e.g. examples/b1_two_masses.toml.
        scene: PathBuf,
        /// Results folder (default: the scene's [output] directory, or results/<scene name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Check a scene without running it: parse, build every unit, resolve connections.
    Check { scene: PathBuf },
    /// Measure a scene's cost per simulated second (median of repeated runs, no output written).
    Bench {
        scene: PathBuf,
        /// Timed runs after one warm-up run.
        #[arg(long, default_value_t = 5)]
        repeats: usize,
        /// Print the figures as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Modal analysis of a structural unit about its initial (static) state:
    /// prints the periods, writes modes.csv and modes.svg.
    Modes {
        scene: PathBuf,
        /// The unit to analyse (e.g. `emulated`).
        #[arg(long)]
        unit: String,
        /// Number of modes.
        #[arg(long, default_value_t = 15)]
        count: usize,
        /// Folder for modes.csv and modes.svg (default: results/<scene name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Modes drawn in modes.svg.
        #[arg(long, default_value_t = 6)]
        plot: usize,
    },
    /// Convergence and cost study (seed 000 Appendix B): vary one setting at a time
    /// and report, per run, the relative error of the scene's indicator signals
    /// against the finest value, iterations per step and cost per simulated second.
    /// Writes study.csv, study.md and study.svg.
    Study {
        scene: PathBuf,
        /// SETTING=V1,V2,...; SETTING is elements, step, velocity_tolerance or
        /// force_tolerance. Repeat for several sweeps.
        #[arg(long = "vary", required = true)]
        sweeps: Vec<slender_app::study::Sweep>,
        /// Simulated time of each run (s); default: the scene's duration.
        #[arg(long)]
        duration: Option<f64>,
        /// Results folder (default: results/<scene name>-study).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The suspended span (seed 004 ch. 5): Bode plots and accuracy against cost.
    Span {
        #[command(subcommand)]
        action: SpanAction,
        /// EI (N m^2).
        #[arg(long, default_value_t = 1.0e4, global = true)]
        flexural_rigidity: f64,
        /// mu (kg/m).
        #[arg(long, default_value_t = 1.0e2, global = true)]
        mass_per_length: f64,
        /// c_d (N s/m^2).
        #[arg(long, default_value_t = 5.0, global = true)]
        damping: f64,
        /// L (m).
        #[arg(long, default_value_t = 10.0, global = true)]
        length: f64,
        /// Results folder.
        #[arg(long, default_value = "results/span", global = true)]
        out: PathBuf,
    },
    /// FMI 2.0 co-simulation: export a unit as an FMU, inspect an FMU.
    Fmu {
        #[command(subcommand)]
        action: FmuAction,
    },
    /// List the unit kinds a scene can use.
    Kinds,
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Run { scene, out, quiet } => run(scene, out, quiet),
        Command::Check { scene } => check(scene),
        Command::Bench {
            scene,
            repeats,
            json,
        } => bench(scene, repeats, json),
        Command::Modes {
            scene,
            unit,
            count,
            out,
            plot,
        } => modes(scene, &unit, count, out, plot),
        Command::Study {
            scene,
            sweeps,
            duration,
            out,
        } => study(scene, &sweeps, duration, out),
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
            };
            span_command(&span, action, &out)
        }
        Command::Fmu { action } => fmu_command(action),
        Command::Kinds => {
            for k in kinds::KINDS {
                let effects = if k.effects.is_empty() {
                    String::new()
                } else {
                    format!(" (effects: {})", k.effects.join(", "))
                };
                println!("{:<18} {}{effects}", k.name, k.summary);
            }
            ExitCode::SUCCESS
        }
    }
}

fn load(path: &Path) -> Result<Scene, ExitCode> {
    Scene::load(path).map_err(|e| {
        eprintln!("error: {e}");
        ExitCode::from(2)
    })
}

fn run(path: PathBuf, out: Option<PathBuf>, quiet: bool) -> ExitCode {
    let scene = match load(&path) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let dir = out.unwrap_or_else(|| scene.default_output_dir());
    let options = RunOptions {
        output_dir: Some(dir),
        progress: !quiet,
    };
    let result = match run_scene(&scene, &options) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let s = &result.summary;
    let c = &s.counters;
    if !s.title.is_empty() {
        println!("{}", s.title);
    }
    println!("scene        {}", s.scene);
    println!(
        "scheme       {} (acceleration {}), order {}",
        s.settings.scheme.name(),
        s.settings.acceleration.name(),
        s.order.join(" -> ")
    );
    println!(
        "simulated    {} s in {} steps of {} s",
        s.simulated_s, c.steps, s.step_s
    );
    println!(
        "cost         {:.3} s wall, {:.3e} s per simulated second ({:.0}x real time)",
        s.wall_time_s,
        s.cost_per_simulated_second,
        1.0 / s.cost_per_simulated_second
    );
    println!(
        "iterations   {:.2} per step (max {}), {} rollbacks, {} non-converged steps, largest residual at exit {:.3} x tolerance",
        c.mean_iterations(),
        c.iteration_histogram.len().saturating_sub(1),
        c.rollbacks,
        c.non_converged_steps,
        c.max_residual
    );
    for i in &s.indicators {
        println!(
            "indicator    {:<12} phi = {:.3}, epsilon = {:.3e}",
            i.name, i.fidelity, i.relative_error
        );
    }
    for u in &c.units {
        println!(
            "unit         {:<12} {} do_step calls, {:.3} s",
            u.name, u.do_step_calls, u.step_time_s
        );
    }
    for f in &result.files {
        println!("wrote        {}", f.display());
    }
    match &s.error {
        None => ExitCode::SUCCESS,
        Some(e) => {
            eprintln!(
                "error: the run stopped at t = {} s: {e}",
                s.start_s + s.simulated_s
            );
            eprintln!("(results up to that time are in the files above)");
            ExitCode::FAILURE
        }
    }
}

fn check(path: PathBuf) -> ExitCode {
    let scene = match load(&path) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let master = match scene.build() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    println!("{}: ok", path.display());
    for (u, name) in master.unit_names().enumerate() {
        let d = master.description(u);
        let ports = |ps: &[slender_units::Port]| {
            ps.iter()
                .map(|p| format!("{} [{}]", p.name, p.unit))
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!("unit {name} ({})", d.kind);
        println!("  in:  {}", ports(&d.inputs));
        println!("  out: {}", ports(&d.outputs));
    }
    for (label, _) in master.connection_values() {
        println!("connection {label}");
    }
    println!(
        "{} steps of {} s; scheme {}, order {}",
        scene.steps,
        scene.step.as_secs(),
        master.settings().scheme.name(),
        master.order().join(" -> ")
    );
    ExitCode::SUCCESS
}

fn bench(path: PathBuf, repeats: usize, json: bool) -> ExitCode {
    let scene = match load(&path) {
        Ok(s) => s,
        Err(code) => return code,
    };
    match benchmark(&scene, repeats) {
        Ok(b) => {
            if json {
                match serde_json::to_string_pretty(&b) {
                    Ok(t) => println!("{t}"),
                    Err(e) => eprintln!("error: {e}"),
                }
            } else {
                println!("scene                 {}", path.display());
                println!(
                    "cost                  {:.3e} s per simulated second (median of {}, min {:.3e}); {:.0}x real time",
                    b.median_cost_per_simulated_second,
                    b.repeats,
                    b.min_cost_per_simulated_second,
                    b.realtime_factor
                );
                println!(
                    "per run               {} steps, {} iterations, {} do_step calls, {} rollbacks",
                    b.steps, b.iterations, b.do_step_calls, b.rollbacks
                );
                println!(
                    "master overhead       {:.1} ns per connection per iteration",
                    b.master_overhead_per_connection_iteration_s * 1e9
                );
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn modes(path: PathBuf, unit: &str, count: usize, out: Option<PathBuf>, plot: usize) -> ExitCode {
    let scene = match load(&path) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let analysis = scene.build().map_err(|e| e.to_string()).and_then(|mut m| {
        m.initialize(scene.start).map_err(|e| e.to_string())?;
        m.modes(unit, count).map_err(|e| e.to_string())
    });
    let analysis = match analysis {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    println!(
        "modes of `{unit}` in {} about its initial state",
        path.display()
    );
    println!("{:>5} {:>12} {:>12}", "mode", "period (s)", "freq (Hz)");
    for (i, m) in analysis.modes.iter().enumerate() {
        println!("{:>5} {:>12.4} {:>12.5}", i + 1, m.period, 1.0 / m.period);
    }
    let dir = out.unwrap_or_else(|| scene.default_output_dir());
    let written = (|| -> Result<Vec<PathBuf>, String> {
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
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
        std::fs::write(&csv, text).map_err(|e| format!("{}: {e}", csv.display()))?;
        let svg = dir.join("modes.svg");
        let shown = slender_units::ModalAnalysis {
            positions: analysis.positions.clone(),
            modes: analysis.modes.iter().take(plot).cloned().collect(),
        };
        slender_app::plot::mode_shapes(&svg, &format!("Mode shapes of `{unit}`"), &shown)?;
        Ok(vec![csv, svg])
    })();
    report_written(written)
}

fn study(
    path: PathBuf,
    sweeps: &[slender_app::study::Sweep],
    duration: Option<f64>,
    out: Option<PathBuf>,
) -> ExitCode {
    use slender_app::study;
    let scene = match load(&path) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let dir = out.unwrap_or_else(|| {
        let mut d = scene.default_output_dir().into_os_string();
        d.push("-study");
        PathBuf::from(d)
    });
    println!(
        "{:<20} {:>10}  epsilon vs finest          it/step   s per sim. s",
        "setting", "value"
    );
    let rows = study::run_study(&path, sweeps, duration, |r| {
        let eps: Vec<String> = r
            .errors
            .iter()
            .map(|(n, e)| format!("{n} {e:.2e}"))
            .collect();
        println!(
            "{:<20} {:>10}  {:<26} {:>6.2}   {:.3e}{}",
            r.setting.to_string(),
            r.value,
            eps.join(", "),
            r.iterations_per_step,
            r.cost_per_simulated_second,
            r.error
                .as_ref()
                .map(|e| format!("  FAILED: {e}"))
                .unwrap_or_default()
        );
    });
    let rows = match rows {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let written = (|| -> Result<Vec<PathBuf>, String> {
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let csv = dir.join("study.csv");
        std::fs::write(&csv, study::to_csv(&rows))
            .map_err(|e| format!("{}: {e}", csv.display()))?;
        let md = dir.join("study.md");
        std::fs::write(&md, study::to_markdown(&rows))
            .map_err(|e| format!("{}: {e}", md.display()))?;
        let svg = dir.join("study.svg");
        slender_app::plot::study(
            &svg,
            &format!("Convergence and cost: {}", path.display()),
            &rows,
        )?;
        Ok(vec![csv, md, svg])
    })();
    report_written(written)
}

/// Prints the files written, or the error that stopped the writing.
fn report_written(written: Result<Vec<PathBuf>, String>) -> ExitCode {
    match written {
        Ok(files) => {
            for f in files {
                println!("wrote {}", f.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn span_command(
    span: &slender_units::span::transfer::Span,
    action: SpanAction,
    out: &Path,
) -> ExitCode {
    use slender_app::span_study;
    if let Err(e) = span.validate() {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    let written = (|| -> Result<Vec<PathBuf>, String> {
        std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
        match action {
            SpanAction::Bode { order, elements } => {
                let omegas: Vec<f64> = (0..600)
                    .map(|k| 10f64.powf(-2.0 + 4.398 * k as f64 / 599.0))
                    .collect();
                let series = span_study::bode_series(span, order, elements, &omegas)?;
                let path = out.join("bode.svg");
                let title = format!(
                    "H_U2->U5: EI = {}, mu = {}, c_d = {}, L = {}",
                    span.flexural_rigidity,
                    span.mass_per_length,
                    span.damping_per_length,
                    span.length
                );
                slender_app::plot::bode(&path, &title, &omegas, &series)?;
                Ok(vec![path])
            }
            SpanAction::Study {
                duration,
                step,
                reference_elements,
                reference_substeps,
                fe_substeps,
            } => {
                let plan = span_study::StudyPlan {
                    orders: vec![2, 4, 6, 8, 10, 12, 14, 16],
                    elements: vec![4, 8, 16, 32, 64],
                    fe_substeps,
                    reference_elements,
                    reference_substeps,
                    duration,
                    step,
                };
                let report = span_study::study(span, &plan)?;
                let (pmd, pjson, psvg) = write_study_report(
                    out,
                    "span_study",
                    "accuracy_cost",
                    &span_study::to_markdown(&report),
                    &report,
                )?;
                let points: Vec<(String, f64, f64)> = report
                    .rows
                    .iter()
                    .map(|r| (r.label(), r.cost_per_simulated_second, r.error_sines))
                    .collect();
                slender_app::plot::accuracy_cost(
                    &psvg,
                    "Span: error against cost per simulated second",
                    "error vs the continuum (sum of sines)",
                    &points,
                )?;
                Ok(vec![pmd, pjson, psvg])
            }
            SpanAction::Coupling {
                duration,
                step,
                reference_elements,
                reference_substeps,
                fe_substeps,
            } => {
                use slender_app::coupling_study;
                let plan = coupling_study::CouplingPlan {
                    orders: vec![16, 24, 32],
                    elements: vec![8, 16, 32, 64, 128],
                    fe_substeps,
                    reference_elements,
                    reference_substeps,
                    duration,
                    step,
                };
                let report = coupling_study::coupling_study(span, &plan)?;
                let (pmd, pjson, psvg) = write_study_report(
                    out,
                    "coupling_study",
                    "coupling_accuracy_cost",
                    &coupling_study::to_markdown(&report),
                    &report,
                )?;
                let points: Vec<(String, f64, f64)> = report
                    .rows
                    .iter()
                    .map(|r| {
                        let label = match (r.model.as_str(), r.substeps) {
                            ("fe", 1) => "fe".to_string(),
                            ("fe", n) => format!("fe ({n} substeps)"),
                            (m, _) => format!("span_coupling {m}"),
                        };
                        let worst = r.errors.iter().fold(0.0f64, |a, &e| a.max(e));
                        (label, r.cost_per_simulated_second, worst)
                    })
                    .collect();
                slender_app::plot::accuracy_cost(
                    &psvg,
                    "Span between two sections: error against cost per simulated second",
                    "largest error of the four outputs vs the continuum",
                    &points,
                )?;
                Ok(vec![pmd, pjson, psvg])
            }
        }
    })();
    report_written(written)
}

/// Prints a study's Markdown and writes it as `<stem>.md` with the report as
/// `<stem>.json` into `out`; returns those paths and the path for its plot,
/// `<plot>.svg`.
fn write_study_report(
    out: &Path,
    stem: &str,
    plot: &str,
    markdown: &str,
    report: &impl serde::Serialize,
) -> Result<(PathBuf, PathBuf, PathBuf), String> {
    print!("{markdown}");
    let (md, json, svg) = (
        out.join(format!("{stem}.md")),
        out.join(format!("{stem}.json")),
        out.join(format!("{plot}.svg")),
    );
    std::fs::write(&md, markdown).map_err(|e| format!("{}: {e}", md.display()))?;
    let text = serde_json::to_string_pretty(report).map_err(|e| e.to_string())?;
    std::fs::write(&json, text).map_err(|e| format!("{}: {e}", json.display()))?;
    Ok((md, json, svg))
}

fn fmu_command(action: FmuAction) -> ExitCode {
    use slender_fmi::export::{ExportConfig, default_binary};
    use slender_fmi::import::{FmuParams, FmuUnit};
    use slender_scene::export::{SceneExport, package, wrap_scene};
    let result = match action {
        FmuAction::Export {
            scene,
            unit,
            output,
            binary,
        } => load(&scene).and_then(|scene| {
            let binary = binary.or_else(default_binary).ok_or_else(|| {
                eprintln!(
                    "error: libslender_fmu.so not found next to this executable; build it with `cargo build --release -p slender-fmu` or pass --binary"
                );
                ExitCode::from(2)
            })?;
            let output = output.unwrap_or_else(|| PathBuf::from(format!("{unit}.fmu")));
            let written = ExportConfig::from_scene(&scene, &unit)
                .and_then(|config| package(&config, &binary, &output));
            match written {
                Ok(layout) => {
                    let model = &layout.model;
                    let count = |c| model.variables.iter().filter(|v| v.causality == c).count();
                    use slender_fmi::model_description::VariableCausality as C;
                    println!(
                        "wrote {} ({} inputs, {} outputs, {} parameters, guid {})",
                        output.display(),
                        count(C::Input),
                        count(C::Output),
                        count(C::Parameter),
                        model.guid
                    );
                    Ok(())
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    Err(ExitCode::from(2))
                }
            }
        }),
        FmuAction::Wrap { scene, out, binary } => load(&scene).and_then(|scene| {
            let binary = binary.or_else(default_binary).ok_or_else(|| {
                eprintln!(
                    "error: libslender_fmu.so not found next to this executable; build it with `cargo build --release -p slender-fmu` or pass --binary"
                );
                ExitCode::from(2)
            })?;
            match wrap_scene(&scene, &binary, &out) {
                Ok(path) => {
                    println!("wrote {}", path.display());
                    Ok(())
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    Err(ExitCode::from(2))
                }
            }
        }),
        FmuAction::Info { fmu, preload } => {
            let params = FmuParams {
                file: fmu,
                start: Default::default(),
                preload,
                logging: false,
            };
            match FmuUnit::load(&params, Path::new(".")) {
                Ok(unit) => {
                    use slender_units::Unit;
                    let model = unit.model_description();
                    let d = unit.description();
                    println!("{} ({}), generated by {}", model.model_name, model.guid, model.generation_tool);
                    println!(
                        "rollback: {}, variable step: {}",
                        d.capabilities.rollback, d.capabilities.variable_step
                    );
                    for p in &d.inputs {
                        println!("  input  {:<24} {:<12} {:<5} hold {:?}", p.name, p.kind.name(), p.unit, p.hold);
                    }
                    for p in &d.outputs {
                        let deps: Vec<&str> = p.depends_on.iter().map(|i| d.inputs[*i].name.as_str()).collect();
                        println!("  output {:<24} {:<12} {:<5} depends on [{}]", p.name, p.kind.name(), p.unit, deps.join(", "));
                    }
                    Ok(())
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    Err(ExitCode::from(2))
                }
            }
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(code) => code,
    }
}
