//! The command line: commands and their arguments (clap). What each command does
//! is in `commands/`.

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

/// Co-simulation of substructured slender marine structures.
///
/// A scene file (TOML) lists the units (substructure models), how their ports are
/// connected, the master scheme that couples them and the time window. Start from
/// a file in examples/ and see docs/scene-reference.md.
#[derive(Parser)]
#[command(name = "slender", version, about, long_about)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Set a scene key over the file, by its path as `study --vary` takes it
    /// (repeatable), on every command that reads a scene: `--set
    /// master.scheme=jacobi --set units.line.parameters.elements=40`; the
    /// value is TOML (a bare word a string). summary.json lists them.
    #[arg(long = "set", value_name = "KEY=VALUE", global = true)]
    pub set: Vec<String>,
}

#[derive(Subcommand)]
pub(crate) enum SpanAction {
    /// Bode plot of H_{U2 -> U5}: analytic, Taylor, term and function Pade of one
    /// order, and the FE span (seed 004 Figs. 5.1-5.2). Writes bode.svg.
    Bode {
        /// Order of the approximations: even, 2 to 24.
        #[arg(long, default_value_t = 8)]
        order: usize,
        /// FE span elements (1 to 1024).
        #[arg(long, default_value_t = 32)]
        elements: usize,
    },
    /// Time-domain error against cost per simulated second of span units (orders
    /// 2-16) and FE spans (4-64 elements, stepping with the master or with substeps)
    /// under a sum of sines and a step, against the continuum's response (a fine FE
    /// span with fine substeps), through the study engine. Writes span_study.md,
    /// span_study.json, accuracy_cost.svg and the scenes it ran (scenes/*.toml,
    /// for `slender study --reference`).
    Study {
        /// Simulated time of each run (s).
        #[arg(long, default_value_t = 100.0, allow_negative_numbers = true)]
        duration: f64,
        /// Synchronisation step (s).
        #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
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
    /// the same four end conditions, all four ends driven, through the study
    /// engine. Writes coupling_study.md, coupling_study.json,
    /// coupling_accuracy_cost.svg and the scenes it ran (scenes/coupling_*.toml).
    Coupling {
        /// Simulated time of each run (s).
        #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
        duration: f64,
        /// Synchronisation step (s).
        #[arg(long, default_value_t = 0.001, allow_negative_numbers = true)]
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
pub(crate) enum FmuAction {
    /// Export one unit of a scene as an FMI 2.0 (or, with `--fmi 3`, FMI 3.0)
    /// co-simulation FMU (its parameters, effects, hold and start inputs; the
    /// scene's time window as default experiment).
    Export {
        scene: PathBuf,
        /// The unit to export (its name in the scene).
        #[arg(long)]
        unit: String,
        /// FMI version of the FMU: 2 (default) or 3.
        #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
        fmi: u8,
        /// The .fmu to write (default: <unit>.fmu); `--out` as elsewhere.
        #[arg(short, long, visible_alias = "out")]
        output: Option<PathBuf>,
        /// The slender-fmu shared library (default: libslender_fmu.so next to this
        /// executable; build it with `cargo build --release -p slender-fmu`).
        #[arg(long)]
        binary: Option<PathBuf>,
    },
    /// Export every unit of a scene and write a copy of the scene that uses the
    /// FMUs (kind `fmu`): the same run through the FMI layer; or, with `--out
    /// X.ssp`, an SSP 1.0 archive of the FMUs and the system's structure (for
    /// libcosim, OMSimulator, ... and `slender run X.ssp`).
    Wrap {
        scene: PathBuf,
        /// Folder for the FMUs and the new scene (<scene>_fmu.toml), or an
        /// `.ssp` file.
        #[arg(long)]
        out: PathBuf,
        /// FMI version of the FMUs: 2 (default) or 3 (not in an `.ssp`: SSP
        /// 1.0 holds FMI 2.0 FMUs).
        #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
        fmi: u8,
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

/// A count on the command line: a whole number >= 0, said in a user's
/// words (clap's own parser said `unexpected argument '-1'` or `invalid
/// digit found in string`); each command checks its own range after.
fn whole_number(text: &str) -> Result<usize, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("`{text}`: expected a whole number >= 0"))
}

/// How a study's runs are made, the same for `study` and `fidelity`.
#[derive(Args, Debug)]
pub(crate) struct StudyRuns {
    /// Runs at once (default 1: each run times its cost alone; more finish
    /// sooner but share the cores, so their costs are not comparable).
    /// Results other than costs do not depend on it.
    #[arg(long, allow_negative_numbers = true, value_parser = whole_number)]
    pub jobs: Option<usize>,
    /// Times each run is timed (default 1): its cost is the median, the
    /// spread (max - min) / median is reported, and a spread above 20 % is
    /// warned about.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = whole_number)]
    pub repeats: usize,
    /// The most runs to start (default 10 000): a larger study is
    /// refused before any run, naming its size.
    #[arg(
        long,
        default_value_t = slender_app::DEFAULT_MAX_RUNS,
        allow_negative_numbers = true,
        value_parser = whole_number
    )]
    pub max_runs: usize,
    /// Simulated time of each run (s); default: the scene's duration.
    #[arg(long, allow_negative_numbers = true)]
    pub duration: Option<f64>,
    /// Run every run anew: the runs an earlier study kept in the results
    /// folder (runs/) are removed first, e.g. to time costs again.
    #[arg(long)]
    pub fresh: bool,
}

#[derive(Subcommand)]
pub(crate) enum Command {
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
        /// Pace each synchronisation step against the wall clock, as when the
        /// scene drives a rig, and report the computing time per step and every
        /// overrun (summary.json, overruns.csv).
        #[arg(long)]
        realtime: bool,
        /// Simulated time (s) instead of the scene's `simulation.duration`; a
        /// whole number of its steps.
        #[arg(long)]
        duration: Option<f64>,
    },
    /// Check a scene without running it: parse, build every unit, resolve connections.
    Check { scene: PathBuf },
    /// Print the scene as it runs: a `[structure]` written out as plain units and
    /// connections (checked first).
    Expand { scene: PathBuf },
    /// Measure a scene's cost per simulated second (median of repeated runs, no output written).
    Bench {
        scene: PathBuf,
        /// Timed runs after one warm-up run (at least 1).
        #[arg(long, default_value_t = 5, allow_negative_numbers = true, value_parser = whole_number)]
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
        /// Number of modes (at least 1).
        #[arg(long, default_value_t = 15)]
        count: usize,
        /// Folder for modes.csv and modes.svg (default: results/<scene name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Modes drawn in modes.svg.
        #[arg(long, default_value_t = 6)]
        plot: usize,
    },
    /// A decay test: runs a scene with one body (let go from its
    /// `initial_offset`) and reads each motion's natural period and damping
    /// ratio from the record, beside the moored statics' undamped periods;
    /// writes decay.json with the run's files.
    Decay {
        scene: PathBuf,
        /// Folder for the run's files and decay.json (default: results/<scene name>).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Statics of a scene's moored body (`[mooring]`): its equilibrium on the
    /// lines' catenaries, each fairlead's tension, the 6x6 mooring stiffness,
    /// the undamped natural periods and the offset-restoring curves (surge,
    /// sway, yaw); writes statics.json, offsets.csv and statics.svg.
    Statics {
        scene: PathBuf,
        /// Folder for the files (default: results/<scene name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Surge and sway offsets from -RANGE to RANGE (m).
        #[arg(long, default_value_t = 30.0)]
        range: f64,
        /// Yaw from -YAW to YAW (degrees).
        #[arg(long, default_value_t = 10.0)]
        yaw: f64,
        /// Points per curve (3 to 1001).
        #[arg(long, default_value_t = 21)]
        points: usize,
    },
    /// Convergence and cost study (seed 000 Appendix B): vary one setting at a time
    /// and report, per run, the relative error of the scene's indicator signals
    /// against the finest value, iterations per step and cost per simulated second;
    /// where the indicators judge against an in-run twin, the twin's own error
    /// (the scene again at half its element length and step).
    /// Writes study.csv, study.md, study.svg, error_cost.svg and report.html;
    /// resumable: runs/ keeps each finished run, and the same command again
    /// reuses them.
    Study {
        scene: PathBuf,
        /// KEY=V1,V2,...; KEY is a scene key by its path (simulation.step,
        /// master.scheme, master.acceleration.kind,
        /// units.<name>.parameters.<key>, an array element by index) or a short
        /// name: elements (every cable unit), step, velocity_tolerance,
        /// force_tolerance. Repeat for several sweeps.
        #[arg(long = "vary", required = true)]
        sweeps: Vec<slender_app::study::Sweep>,
        /// Run every combination of the sweeps' values instead of one sweep at a
        /// time.
        #[arg(long)]
        grid: bool,
        #[command(flatten)]
        runs: StudyRuns,
        /// A scene whose run is every run's reference (its indicators matched by
        /// name), e.g. a fine FE model of what the studied scene approximates;
        /// a sweep may then have one value.
        #[arg(long)]
        reference: Option<PathBuf>,
        /// Units whose own stepping time is the cost (default: the whole run),
        /// e.g. the model under study, not its driver or an in-run reference.
        #[arg(long = "cost", value_delimiter = ',')]
        cost_units: Vec<String>,
        /// Results folder (default: results/<scene name>-study).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Fidelity study of a scene's `[structure]` or of a `[mooring]`'s lines: run
    /// their sections at chosen fidelities (full grid or one section at a time),
    /// each combination against the monolithic reference (the whole structure as
    /// one nonlinear unit; a mooring with every line whole): epsilon
    /// of each quantity of interest, cost, speed-up, iterations, non-converged
    /// steps, the Pareto front and the cheapest combination within --tolerance.
    /// Writes fidelity.csv, fidelity.json, fidelity.md, fidelity.svg and
    /// report.html; resumable: runs/ keeps each finished run, and the same
    /// command again reuses them.
    Fidelity {
        scene: PathBuf,
        /// NAME=CHOICE,CHOICE,...: a section and its fidelities (nonlinear,
        /// linear, cable, static, reduced, beam, span), each optionally with an element
        /// count (for reduced: its modes; for span: the order of its fit),
        /// for reduced a training window in seconds after @ (its forces
        /// sampled after it) and sub-steps per coupling step after a slash,
        /// e.g. lower=nonlinear,cable,nonlinear:16,reduced:4,reduced:4@5,nonlinear:16/4
        /// or middle=beam:10,span:24. Repeat for several sections. A mooring's
        /// section is LINE.SECTION (one line's) or SECTION (in every line).
        #[arg(long = "section", required = true)]
        sections: Vec<slender_app::fidelity::SectionChoices>,
        /// Run every combination of the sections' choices instead of one
        /// section at a time.
        #[arg(long)]
        grid: bool,
        /// Largest epsilon of every judged quantity for a combination to count
        /// as good enough (default 0.01).
        #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
        tolerance: f64,
        /// The quantities that judge a combination (its worst epsilon, the
        /// Pareto front, the tolerance), comma-separated, e.g.
        /// top_force,touchdown,sagbend_moment; default: all of them (a
        /// mooring: the lines' tensions).
        #[arg(long, value_delimiter = ',')]
        quantities: Vec<String>,
        /// Measure the errors from this time on (s), leaving out a build-up
        /// (default: the whole run).
        #[arg(long)]
        from: Option<f64>,
        /// The reference: `estimate` (the monolithic run at the model's mesh,
        /// its own error estimated by a run at half its element length and
        /// half its step, reported beside the combinations' and flagged when
        /// above a fifth of the tolerance), `converged` (halved again until
        /// that estimate is below a fifth of the tolerance, at most
        /// --refinements times, and judged against the finest) or `model` (as
        /// written, no estimate).
        #[arg(long, default_value = "estimate")]
        reference: slender_app::fidelity::ReferenceMode,
        /// The most halvings of the reference's element length and step for
        /// `--reference converged` (each one about four times the cost).
        #[arg(long, default_value_t = slender_app::fidelity::reference::DEFAULT_MAX_REFINEMENTS)]
        refinements: u32,
        #[command(flatten)]
        runs: StudyRuns,
        /// Results folder (default: results/<scene name>-fidelity).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Uncertainty study of a scene's `[uncertainty]` inputs: a nested maximin
    /// Latin hypercube of co-simulations (in parallel, resumable: runs.csv keeps
    /// each finished run), a sparse polynomial chaos per output indicator's phi,
    /// its mean, sd and Sobol' indices with 95 % bootstrap intervals. Writes
    /// runs.csv, uq.json and uq.md.
    Uq {
        scene: PathBuf,
        /// Design size (default: `uncertainty.samples`); that times a power of
        /// two keeps the runs of a smaller study, any other size is a Latin
        /// hypercube of its own.
        #[arg(long)]
        samples: Option<usize>,
        /// Results folder (default: results/<scene name>-uq).
        #[arg(long)]
        out: Option<PathBuf>,
        #[command(flatten)]
        runs: SplitRuns,
    },
    /// A load-case matrix: the scene's sea (every wave spectrum in it) at each
    /// sea state of a scatter, each heading and each seed. Each case's
    /// statistics, extremes and fatigue damage go to cases.csv (resumable),
    /// aggregated into each signal's design value and each fatigue entry's
    /// damage per year over the scatter (cases.json, cases.md, report.html).
    /// The scene needs `[output] statistics`.
    Cases {
        scene: PathBuf,
        /// A sea state: significant height (m), peak period (s) and its
        /// probability, `HS,TP,P`; repeat it for a scatter. Without it, the
        /// scene's `[cases]` table.
        #[arg(long = "sea", value_parser = parse_sea)]
        seas: Vec<(f64, f64, f64)>,
        /// A wave heading (deg), `DEG` or `DEG,P` with its probability
        /// (default: equal shares); repeat it; default: the scene's heading.
        #[arg(long = "heading", value_parser = parse_heading, allow_negative_numbers = true)]
        headings: Vec<(f64, Option<f64>)>,
        /// Seeds of each sea state and heading (1 to N; default the scene's
        /// `[cases] seeds`, else 1).
        #[arg(long)]
        seeds: Option<u64>,
        /// Results folder (default: results/<scene name>-cases).
        #[arg(long)]
        out: Option<PathBuf>,
        #[command(flatten)]
        runs: SplitRuns,
    },
    /// The suspended span (seed 004 ch. 5): Bode plots and accuracy against cost.
    Span {
        #[command(subcommand)]
        action: SpanAction,
        /// EI (N m^2).
        #[arg(
            long,
            default_value_t = 1.0e4,
            global = true,
            allow_negative_numbers = true
        )]
        flexural_rigidity: f64,
        /// mu (kg/m).
        #[arg(
            long,
            default_value_t = 1.0e2,
            global = true,
            allow_negative_numbers = true
        )]
        mass_per_length: f64,
        /// c_d (N s/m^2).
        #[arg(
            long,
            default_value_t = 5.0,
            global = true,
            allow_negative_numbers = true
        )]
        damping: f64,
        /// L (m).
        #[arg(
            long,
            default_value_t = 10.0,
            global = true,
            allow_negative_numbers = true
        )]
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

/// How a study of independent runs (`uq`, `cases`) runs: at once, within a
/// bound, and split over a cluster.
#[derive(Args, Debug)]
pub(crate) struct SplitRuns {
    /// Runs at once (default: the machine's cores); results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    /// The most runs to start (default 10 000): a larger study is refused
    /// before any run, naming its size.
    #[arg(long, default_value_t = slender_app::DEFAULT_MAX_RUNS)]
    pub max_runs: usize,
    /// Simulated time of each run (s); default: the scene's duration.
    #[arg(long, allow_negative_numbers = true)]
    pub duration: Option<f64>,
    /// Run only shard K of N (K/N, 1-based: every N-th run from K), into
    /// <out>/shard-K-of-N/, for a cluster's job array.
    #[arg(long, value_parser = parse_shard)]
    pub shard: Option<(usize, usize)>,
    /// Merge the shards' runs under <out> (running any that are missing):
    /// the same results as one local run.
    #[arg(long, conflicts_with = "shard")]
    pub merge: bool,
    /// Write the Slurm scripts for N shards (a job array, and submit.sh,
    /// which submits it and the merge after it).
    #[arg(long, conflicts_with_all = ["shard", "merge"])]
    pub slurm: Option<usize>,
}

/// `HS,TP,P`: three numbers.
fn parse_sea(text: &str) -> Result<(f64, f64, f64), String> {
    let numbers: Result<Vec<f64>, _> = text.split(',').map(|v| v.trim().parse::<f64>()).collect();
    match numbers.as_deref() {
        Ok([hs, tp, p]) => Ok((*hs, *tp, *p)),
        _ => Err(format!(
            "`{text}`: expected HS,TP,PROBABILITY (m, s, a fraction), e.g. 4,9,0.25"
        )),
    }
}

/// `DEG` or `DEG,P`.
fn parse_heading(text: &str) -> Result<(f64, Option<f64>), String> {
    let numbers: Result<Vec<f64>, _> = text.split(',').map(|v| v.trim().parse::<f64>()).collect();
    match numbers.as_deref() {
        Ok([deg]) => Ok((*deg, None)),
        Ok([deg, p]) => Ok((*deg, Some(*p))),
        _ => Err(format!(
            "`{text}`: expected DEG or DEG,PROBABILITY, e.g. 30,0.5"
        )),
    }
}

/// `K/N` with 1 <= K <= N.
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let (k, n) = text
        .split_once('/')
        .ok_or(format!("`{text}`: expected K/N, e.g. 2/8"))?;
    match (k.parse::<usize>(), n.parse::<usize>()) {
        (Ok(k), Ok(n)) if k >= 1 && k <= n => Ok((k, n)),
        _ => Err(format!("`{text}`: expected K/N with 1 <= K <= N")),
    }
}
