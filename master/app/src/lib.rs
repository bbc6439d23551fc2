//! slender-app: the application around the coupling algorithm (the `slender`
//! binary is `main.rs`).
//!
//! - [`run`]: running a scene with recording, summary and plots;
//! - [`record`], [`plot`], [`indicators`]: CSV time series, SVG figures of runs, phi / epsilon;
//! - [`report`]: one self-contained HTML page per run and per study;
//! - [`figures`]: the parts of readable figures (ticks, keys), study and trade-off figures;
//! - [`study`], [`span_study`], [`coupling_study`]: convergence and cost studies;
//! - [`fidelity`]: a structure's sections at chosen fidelities against the monolithic model;
//! - [`parallel`]: independent runs on a few threads; [`resume`]: a stopped study resumed;
//!   [`progress`]: k of N runs and the time left.

pub mod analysis;
pub mod cases;
pub mod costs;
pub mod coupling_study;
pub mod decay;
pub mod envelopes;
pub mod error;
pub mod extremes;
pub mod fatigue;
pub mod fidelity;
pub mod figures;
pub mod indicators;
pub mod interrupt;
pub mod parallel;
pub mod plot;
pub mod progress;
pub mod rainflow;
pub mod realtime;
pub mod record;
pub mod report;
pub mod resume;
pub mod run;
pub mod span_study;
pub mod spectrum;
pub mod statistics;
pub mod study;
pub mod uq;
pub mod watch;
pub mod whole;

pub use error::AppError;

/// The most runs a study (`study`, `fidelity`, `uq`) starts unless its
/// `--max-runs` says otherwise: a bound stated and checked before any run.
pub const DEFAULT_MAX_RUNS: usize = 10_000;

/// The refusal of a study larger than its bound.
pub fn too_many_runs(what: &str, runs: usize, bound: usize) -> String {
    format!(
        "{what}: {runs} runs, more than the bound of {bound}; give --max-runs {runs} to go past it"
    )
}
