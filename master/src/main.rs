//! `slender`: run, check and benchmark co-simulation scenes.

use clap::{Parser, Subcommand};
use slender_master::run::{RunOptions, benchmark, run_scene};
use slender_master::scene::{Scene, kinds};
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
