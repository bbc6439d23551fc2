//! `slender run`, `check`, `bench` and `kinds`.

use super::{CliError, SceneArg, count_in, load, results_folder};
use slender_app::run::{RunOptions, RunResult, benchmark, run_scene};
use slender_scene::kinds;
use std::path::PathBuf;

/// Runs a scene and prints its summary; a run that stops early is a failure
/// (exit 1) with its results up to then on disk.
pub(super) fn run(
    scene: &SceneArg,
    out: Option<PathBuf>,
    (quiet, realtime): (bool, bool),
    duration: Option<f64>,
) -> Result<(), CliError> {
    let mut scene = load(scene)?;
    if let Some(d) = duration {
        super::positive("--duration", d)?;
        scene
            .set_duration(d)
            .map_err(|e| CliError::input(format!("--duration {d}: {}", e.message)))?;
    }
    let dir = out.unwrap_or_else(|| scene.default_output_dir());
    let _lock = results_folder(&dir)?;
    let options = RunOptions {
        output_dir: Some(dir),
        progress: !quiet,
        realtime,
    };
    let result = run_scene(&scene, &options).map_err(CliError::of_run)?;
    print_summary(&result);
    let s = &result.summary;
    match &s.error {
        None => Ok(()),
        Some(e) => Err(CliError {
            // 130: the shell's code for a command ended by Ctrl-C.
            code: if s.status == "interrupted" { 130 } else { 1 },
            message: format!(
                "the run stopped at t = {} s: {e}\n(results up to that time are in the files above)",
                s.start_s + s.simulated_s
            ),
        }),
    }
}

/// The adaptive step's line: steps per size, rejected and failed ones.
fn print_adaptive(simulated_s: f64, a: &slender_coupling::counters::StepSizes) {
    let sizes: Vec<String> = (a.accepted.iter().zip(&a.sizes_s))
        .filter(|(n, _)| **n > 0)
        .map(|(n, h)| format!("{n} of {h} s"))
        .collect();
    println!(
        "simulated    {simulated_s} s in {} adaptive steps ({}), {} rejected over the tolerance, {} repeated after a failure",
        a.accepted_steps(),
        sizes.join(", "),
        a.rejected,
        a.failed
    );
    if a.over_tolerance > 0 {
        println!(
            "             {} steps accepted at the smallest step over the tolerance (largest estimate {:.3} x, on {})",
            a.over_tolerance, a.largest_estimate, a.largest_at
        );
    }
}

/// The computing times of a paced run: percentiles, histogram, overruns.
fn print_realtime(r: &slender_app::realtime::RealtimeReport) {
    let ms = |x: f64| x * 1e3;
    println!(
        "real time    step {:.3} ms: computing median {:.3} ms, 99 % {:.3} ms, 99.9 % {:.3} ms, worst {:.3} ms (step {})",
        ms(r.step_s),
        ms(r.median_s),
        ms(r.p99_s),
        ms(r.p999_s),
        ms(r.worst_s),
        r.worst_step
    );
    let bins: Vec<String> = r.histogram.iter().map(|c| c.to_string()).collect();
    println!(
        "             steps per tenth of the step: {} (last: a whole step or more)",
        bins.join(" ")
    );
    match r.overruns.first() {
        None => println!(
            "             no overrun in {} steps: the scene keeps up with the clock",
            r.steps
        ),
        Some(first) => println!(
            "             {} overruns in {} steps (overruns.csv lists the first {}), the first at t = {} s, {:.3} ms late",
            r.overrun_count,
            r.steps,
            r.overruns.len(),
            first.time_s,
            ms(first.late_s)
        ),
    }
}

fn print_summary(result: &RunResult) {
    let s = &result.summary;
    let c = &s.counters;
    if !s.title.is_empty() {
        println!("{}", s.title);
    }
    println!("scene        {}", s.scene);
    for o in &s.overrides {
        println!("set          {o}");
    }
    for w in &s.warnings {
        println!("warning      {w}");
    }
    println!(
        "scheme       {} ({}), order {}",
        s.settings.scheme.name(),
        match s.settings.newton {
            Some(_) => "newton".to_string(),
            None => format!("acceleration {}", s.settings.acceleration.name()),
        },
        s.order.join(" -> ")
    );
    match &c.adaptive {
        None => println!(
            "simulated    {} s in {} steps of {} s",
            s.simulated_s, c.steps, s.step_s
        ),
        Some(a) => print_adaptive(s.simulated_s, a),
    }
    if s.simulated_s > 0.0 {
        println!(
            "cost         {:.3} s wall, {:.3e} s per simulated second ({:.0}x real time)",
            s.wall_time_s,
            s.cost_per_simulated_second,
            1.0 / s.cost_per_simulated_second
        );
    } else {
        println!(
            "cost         {:.3} s wall, no simulated time to divide by",
            s.wall_time_s
        );
    }
    println!(
        "iterations   {:.2} per step (max {}), {} rollbacks, {} non-converged steps, largest residual at exit {:.3} x tolerance",
        c.mean_iterations(),
        c.iteration_histogram.len().saturating_sub(1),
        c.rollbacks,
        c.non_converged_steps,
        c.max_residual
    );
    if let Some(r) = &s.realtime {
        print_realtime(r);
    }
    for i in &s.indicators {
        println!(
            "indicator    {:<12} phi = {:.3}, epsilon = {:.3e}",
            i.name, i.fidelity, i.relative_error
        );
        if !i.floored.is_empty() {
            println!(
                "             {} judged against the indicator's largest component: {} reference is round-off against it",
                i.floored.join(", "),
                if i.floored.len() == 1 { "its" } else { "their" }
            );
        }
    }
    print_analysis(&s.analysis);
    for u in &c.units {
        println!(
            "unit         {:<12} {} do_step calls, {:.3} s",
            u.name, u.do_step_calls, u.step_time_s
        );
    }
    for f in &result.files {
        println!("wrote        {}", f.display());
    }
}

/// Prints each signal's most probable maxima and each fatigue entry's damage
/// and life, when the scene asks for them.
fn print_analysis(a: &slender_app::analysis::Analysis) {
    for (signal, e) in &a.extremes {
        let weibull = e.weibull.as_ref().map_or(String::new(), |w| {
            format!(
                ", {:.4e} (Weibull, shape {:.2}, R2 {:.3})",
                w.mpm, w.shape, w.r_squared
            )
        });
        let gpd = e.gpd.as_ref().map_or(String::new(), |g| {
            format!(
                ", {:.4e} (GPD over {} peaks, shape {:.2}, KS {:.3})",
                g.mpm, g.exceedances, g.shape, g.ks_distance
            )
        });
        println!(
            "extreme      {signal}: most probable maximum in {} s {:.4e} (Rayleigh){weibull}{gpd}; largest seen {:.4e}",
            e.duration_s, e.rayleigh_mpm, e.largest_seen
        );
    }
    for (name, d) in &a.fatigue {
        println!(
            "fatigue      {name}: damage {:.3e} in {} s ({} cycles), {:.3e} per year: life {:.3} years",
            d.damage, d.window_s, d.cycles, d.damage_per_year, d.life_years
        );
    }
}

/// Prints the scene as it runs (a `[structure]` expanded), after checking it.
pub(super) fn expand(scene: &SceneArg) -> Result<(), CliError> {
    let scene = load(scene)?;
    scene.build().map_err(|e| CliError::input(e.to_string()))?;
    print!(
        "{}",
        scene.source().map_err(|e| CliError::input(e.to_string()))?
    );
    Ok(())
}

/// Checks a scene and prints its units, ports, connections and schedule.
pub(super) fn check(arg: &SceneArg) -> Result<(), CliError> {
    let path = &arg.path;
    let scene = load(arg)?;
    let master = scene.build().map_err(|e| CliError::input(e.to_string()))?;
    let signals = scene.signals(&master).len();
    slender_app::run::check_output_size(&scene, signals).map_err(CliError::input)?;
    println!("{}: ok", path.display());
    for advisory in &scene.advisories {
        println!("warning: {advisory}");
    }
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
    if let Some(a) = &master.settings().adaptive {
        println!(
            "adaptive step: each step of {} s halved down to at least {} s where the estimate asks",
            scene.step.as_secs(),
            a.min_step
        );
    }
    Ok(())
}

/// Measures a scene's cost per simulated second.
pub(super) fn bench(arg: &SceneArg, repeats: usize, json: bool) -> Result<(), CliError> {
    let repeats = count_in("--repeats", repeats, 1, 1000)?;
    let path = &arg.path;
    let scene = load(arg)?;
    let b = benchmark(&scene, repeats).map_err(CliError::failure)?;
    if json {
        let text =
            serde_json::to_string_pretty(&b).map_err(|e| CliError::failure(e.to_string()))?;
        println!("{text}");
        return Ok(());
    }
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
    Ok(())
}

/// Lists the unit kinds.
pub(super) fn kinds() {
    for k in kinds::KINDS {
        let effects = if k.effects.is_empty() {
            String::new()
        } else {
            format!(" (effects: {})", k.effects.join(", "))
        };
        println!("{:<18} {}{effects}", k.name, k.summary);
    }
}
