//! The scene file format (TOML), as serde types. Every table rejects unknown keys.
//! `docs/scene-reference.md` documents these types field by field.

pub use crate::analysis::{
    EnvelopesSpec, ExtremesSpec, FatigueCurve, FatigueSpec, MeanStress, SpectraSpec, StatisticsSpec,
};
use serde::Deserialize;
use slender_coupling::settings::MasterSettings;
use slender_units::Hold;
use std::collections::BTreeMap;
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// One line saying what the scene is (printed in summaries and plots).
    #[serde(default)]
    pub title: String,
    /// The time window and step (`[simulation]`).
    pub simulation: SimulationSpec,
    /// The coupling scheme and its tolerances (`[master]`).
    pub master: MasterSettings,
    /// The units (`[[units]]`).
    #[serde(default)]
    pub units: Vec<UnitSpec>,
    /// The connections between their ports (`[[connections]]`).
    #[serde(default)]
    pub connections: Vec<ConnectionSpec>,
    /// What is recorded, judged and drawn (`[output]`).
    #[serde(default)]
    pub output: OutputSpec,
    /// Uncertain inputs for `slender uq` (a run ignores it).
    #[serde(default)]
    pub uncertainty: Option<UncertaintySpec>,
    /// `[structure]`: written out as units and connections when the scene is
    /// read (`Scene::parse`), which append them to `units` and `connections`.
    #[serde(default)]
    pub structure: Option<toml::Value>,
    /// `[mooring]`: a body and its lines, written out the same way.
    #[serde(default)]
    pub mooring: Option<toml::Value>,
    /// `[cases]`: the load-case matrix `slender cases` runs (a run ignores it).
    #[serde(default)]
    pub cases: Option<CasesSpec>,
}

/// `[cases]`: the scatter of sea states, the headings and the seeds of the
/// load-case matrix `slender cases SCENE` runs when its command line gives
/// no `--sea` (what the command line gives replaces the table's).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CasesSpec {
    /// Sea states: `[HS (m), TP (s), probability]` each.
    pub seas: Vec<[f64; 3]>,
    /// Wave headings (deg), each a number (equal shares) or `[deg,
    /// probability]` (all or none); none: the scene's own heading.
    #[serde(default)]
    pub headings: Vec<CasesHeading>,
    /// Seeds of each sea state and heading (1 to `seeds`; default 1).
    #[serde(default)]
    pub seeds: Option<u64>,
}

/// A heading of `[cases]`: its angle (deg), with its probability or not.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum CasesHeading {
    /// An equal share.
    Shared(f64),
    /// `[deg, probability]`.
    Weighted([f64; 2]),
}

/// `[uncertainty]`: distributions given to scene keys, and the indicators whose
/// fidelity phi `slender uq` expands in polynomial chaos.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UncertaintySpec {
    /// Points of the first design; a larger `--samples` doubles it (keeping its
    /// runs) as many times as it takes.
    pub samples: usize,
    /// How the design's points are placed.
    #[serde(default)]
    pub design: DesignKind,
    /// Seed of the designs.
    #[serde(default = "first_seed")]
    pub seed: u64,
    /// Indicator names (`[[output.indicators]]`) whose phi is expanded.
    pub outputs: Vec<String>,
    /// Optional note on scale, e.g. model to full scale by Froude.
    #[serde(default)]
    pub scale: String,
    /// The uncertain inputs, each a distribution given to a scene key.
    pub inputs: Vec<UncertainInput>,
    /// A run counts as unstable when an output's error grows past this many
    /// times its reference's peak, or a unit stops it after a recorded signal
    /// grew past this many times its median window peak (default 10): the
    /// loop left the physics.
    #[serde(default = "unstable_growth")]
    pub unstable_growth: f64,
    /// The phi an unstable run counts as in the expansions (default 0: an
    /// error as large as the signal, no correct digit).
    #[serde(default)]
    pub unstable_fidelity: f64,
}

fn unstable_growth() -> f64 {
    10.0
}

/// `uncertainty.design`: how the points of a study are placed in [0, 1)^d
/// before the inputs' inverse CDFs.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum DesignKind {
    /// Maximin Latin hypercube, doubled by splitting its strata.
    #[default]
    Lhs,
    /// The first points of a seeded Owen-scrambled Sobol' sequence.
    Sobol,
}

fn first_seed() -> u64 {
    1
}

/// One uncertain input: a scene key by its path (as `slender study` takes it)
/// and its distribution.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UncertainInput {
    /// Short name in reports, e.g. `theta1`.
    pub name: String,
    /// The scene key, e.g. `units.sensor.parameters.scale.0`.
    pub key: String,
    /// Its distribution (SI units of the key).
    pub distribution: slender_uq::marginal::Marginal,
    /// Unit of measure of the input, e.g. `N` or `s`.
    #[serde(default)]
    pub unit: String,
}

/// `[simulation]`: the time window.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationSpec {
    /// Simulated time (s), > 0, a whole number of steps.
    pub duration: f64,
    /// Synchronisation step (s), > 0.
    pub step: f64,
    /// Start time (s), default 0.
    #[serde(default)]
    pub start: f64,
    /// The most steps a run may take (default 1e8, `DEFAULT_MAX_STEPS`): a
    /// bound stated and checked before anything runs; give it to go past.
    #[serde(default)]
    pub max_steps: Option<u64>,
    /// A paced run (`slender run --realtime`) stops when more steps than this
    /// overran their deadline (default 100, `DEFAULT_MAX_OVERRUNS`).
    #[serde(default)]
    pub max_overruns: Option<u64>,
}

/// The default bound on a paced run's overruns.
pub const DEFAULT_MAX_OVERRUNS: u64 = 100;

/// The default bound on a run's steps: 1e8 (a day of a 1 ms step).
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

/// `[[units]]`: one unit.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitSpec {
    /// Unique name, used in connections as "name.port".
    pub name: Spanned<String>,
    /// Model kind, e.g. "oscillator" (`slender kinds` lists them).
    pub kind: Spanned<String>,
    /// Parameters of the kind (its own table, see the reference).
    #[serde(default)]
    pub parameters: Option<Spanned<toml::Table>>,
    /// Physical effects to include, among those the kind offers; effects not
    /// named are not computed at all.
    #[serde(default)]
    pub effects: Vec<String>,
    /// Input hold for every input of the unit: "ramp" (default) or "zero_order".
    #[serde(default)]
    pub hold: Option<Hold>,
    /// Multi-rate: the unit steps this many times per synchronisation step,
    /// its inputs interpolated within the step as its hold says (default 1).
    #[serde(default)]
    pub substeps: Option<u32>,
    /// Constant values of inputs, by port name: used where nothing drives the input
    /// and as the first guess of inputs fed through a loop.
    #[serde(default)]
    pub inputs: BTreeMap<String, f64>,
    /// The parameters of a unit a `[structure]` or `[mooring]` writes out,
    /// in its kind's own type (None for a unit the scene file gives: its
    /// parameters are the table above).
    #[serde(skip)]
    pub(crate) written: Option<crate::structure::Parameters>,
}

/// `[[connections]]`: an output driving an input, `to = gain * from + offset`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConnectionSpec {
    /// Source output, "unit.port".
    pub from: Spanned<String>,
    /// Destination input, "unit.port".
    pub to: Spanned<String>,
    /// Factor applied to the value on its way (default 1).
    #[serde(default = "one")]
    pub gain: f64,
    /// Added to the value after the gain (default 0).
    #[serde(default)]
    pub offset: f64,
    /// Absolute convergence tolerance of this connection (destination's unit);
    /// default: the master's tolerance for the destination's port kind.
    #[serde(default)]
    pub tolerance: Option<f64>,
}

fn one() -> f64 {
    1.0
}

/// `[output]`: what is written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Folder for results; default `results/<scene file stem>`; the CLI's `--out`
    /// wins over both.
    #[serde(default)]
    pub directory: Option<String>,
    /// Outputs to record, "unit.port"; default: every output of every unit.
    #[serde(default)]
    pub signals: Vec<String>,
    /// Record every n-th synchronisation step (default 1).
    #[serde(default = "every_step")]
    pub every: u32,
    /// Figures to draw; default: one figure with a panel per recorded signal.
    #[serde(default)]
    pub plots: Vec<PlotSpec>,
    /// Accuracy indicators computed at the end of the run.
    #[serde(default)]
    pub indicators: Vec<IndicatorSpec>,
    /// The largest time series a run may record, estimated before it starts
    /// (B; default `DEFAULT_MAX_OUTPUT_BYTES`): a run of more is refused,
    /// naming its size; give it to go past.
    #[serde(default)]
    pub max_bytes: Option<u64>,
    /// The plausibility watch on the units' loads (see `slender_app::watch`).
    #[serde(default)]
    pub watch: WatchSpec,
    /// Statistics of every recorded signal in `summary.json` (mean, standard
    /// deviation, skewness, kurtosis, extremes, zero-up-crossing period),
    /// over the time from `from` on; none unless asked for.
    #[serde(default)]
    pub statistics: Option<StatisticsSpec>,
    /// Fatigue damage of recorded tensions or stresses (rainflow and Miner).
    #[serde(default)]
    pub fatigue: Vec<FatigueSpec>,
    /// Envelopes of the units' tension, curvature and moment along them.
    #[serde(default)]
    pub envelopes: Option<EnvelopesSpec>,
    /// The quantities of interest a study judges (`slender fidelity`'s
    /// names, e.g. `top_force`, `touchdown`, `sagbend_moment`), so that the
    /// scene says what its fidelity answers are about; the command line's
    /// `--quantities` wins; default: the study's own.
    #[serde(default)]
    pub quantities: Vec<String>,
    /// The time (s) from which a study measures the quantities' errors, the
    /// build-up before it left out (`slender fidelity`'s `--from`, which
    /// wins); the whole run when absent.
    #[serde(default)]
    pub quantities_from: Option<f64>,
}

/// `[output] watch = { factor, stop, breaking_load, energy_growth }`.
#[derive(Copy, Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WatchSpec {
    /// A section's largest tension beyond this multiple of the structure's
    /// at the start is implausible (default 5).
    #[serde(default = "default_factor")]
    pub factor: f64,
    /// Stop the run at the first implausible load instead of warning.
    #[serde(default)]
    pub stop: bool,
    /// The sections' breaking load (N): a largest tension beyond it is
    /// implausible whatever the start.
    #[serde(default)]
    pub breaking_load: Option<f64>,
    /// A section's energy error (the energy its time stepping made, J)
    /// beyond this fraction of the largest energy any section exchanged so
    /// far is implausible growth (default 0.05).
    #[serde(default = "default_energy_growth")]
    pub energy_growth: f64,
}

impl WatchSpec {
    /// The key and what was expected where a value is out of range.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        if !(self.factor.is_finite() && self.factor > 1.0) {
            return Err((
                "output.watch.factor",
                format!("{}: expected a finite multiple above 1", self.factor),
            ));
        }
        if !(self.energy_growth.is_finite() && self.energy_growth > 0.0) {
            return Err((
                "output.watch.energy_growth",
                format!(
                    "{}: expected a positive fraction of the energy exchanged",
                    self.energy_growth
                ),
            ));
        }
        match self.breaking_load {
            Some(b) if !(b.is_finite() && b > 0.0) => Err((
                "output.watch.breaking_load",
                format!("{b}: expected a positive force in N"),
            )),
            _ => Ok(()),
        }
    }
}

fn default_factor() -> f64 {
    5.0
}

fn default_energy_growth() -> f64 {
    0.05
}

impl Default for WatchSpec {
    fn default() -> Self {
        WatchSpec {
            factor: default_factor(),
            stop: false,
            breaking_load: None,
            energy_growth: default_energy_growth(),
        }
    }
}

/// The default bound on a run's recorded time series: 2 GB of CSV (about
/// 0.7 GB held in memory for the figures and indicators).
pub const DEFAULT_MAX_OUTPUT_BYTES: u64 = 2_000_000_000;

/// `[[output.indicators]]`: phi and epsilon (seed 000 eqs. 7-8, 10-11) of recorded
/// signals against recorded reference signals, component by component. Without
/// `reference`, the signals serve `slender study`, which compares them with the
/// finest run of a sweep.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IndicatorSpec {
    /// Its name in summaries and studies.
    pub name: String,
    /// Recorded signals, "unit.port".
    pub signals: Vec<String>,
    /// Recorded reference signals, one per signal (or none).
    #[serde(default)]
    pub reference: Vec<String>,
    /// How a signal's difference from its reference is measured (default `rms`).
    #[serde(default)]
    pub norm: Norm,
    /// The time (s) the error is measured from: the build-up before it is
    /// left out; default the run's start.
    #[serde(default)]
    pub from: Option<f64>,
    /// How the signals (and the references) make the compared components:
    /// each its own (default), or the largest magnitude over them.
    #[serde(default)]
    pub combine: Combine,
}

/// How an indicator's signals make its components.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// Each signal is a component, judged against its own reference.
    #[default]
    Each,
    /// One component: at each time the largest magnitude over the signals,
    /// against the largest over the references (a partition's sections each
    /// report their own extreme, the twin one over the whole structure).
    Largest,
}

impl Combine {
    /// The components `columns` make: themselves, or one column of the
    /// largest magnitude at each sample.
    pub fn apply<'a>(self, columns: Vec<&'a [f64]>) -> Vec<std::borrow::Cow<'a, [f64]>> {
        match self {
            Combine::Each => columns
                .into_iter()
                .map(std::borrow::Cow::Borrowed)
                .collect(),
            Combine::Largest => {
                let samples = columns.iter().map(|c| c.len()).min().unwrap_or(0);
                let largest = (0..samples)
                    .map(|k| columns.iter().map(|c| c[k].abs()).fold(0.0, f64::max))
                    .collect::<Vec<f64>>();
                vec![std::borrow::Cow::Owned(largest)]
            }
        }
    }
}

/// The measure of an indicator's error.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Norm {
    /// Seed 000's epsilon: sqrt(sum_i int (x_i - r_i)^2 dt / int r_i^2 dt).
    #[default]
    Rms,
    /// The largest |x_i - r_i| relative to the largest |r_i|, the worst component
    /// (seed 004 ch. 5's span studies).
    Peak,
}

fn every_step() -> u32 {
    1
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            directory: None,
            signals: Vec::new(),
            every: every_step(),
            plots: Vec::new(),
            indicators: Vec::new(),
            max_bytes: None,
            watch: WatchSpec::default(),
            statistics: None,
            fatigue: Vec::new(),
            envelopes: None,
            quantities: Vec::new(),
            quantities_from: None,
        }
    }
}

/// `[[output.plots]]`: one SVG figure.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlotSpec {
    /// File name without extension.
    pub name: String,
    /// The figure's title.
    #[serde(default)]
    pub title: String,
    /// Panels, top to bottom; each panel overlays the listed recorded signals.
    pub panels: Vec<Vec<String>>,
}
